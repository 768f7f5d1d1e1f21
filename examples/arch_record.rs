//! The 20-voussoir arch (R = 5 m, t = 0.75 m) under the bundled record through the loop driver
//! (`rocking::driver::simulate_loop`, dt = 1 ms): events by kind, wall time, closure residual,
//! peak angle — the figures of docs/arch-performance.md in one run.
//!
//! `cargo run --release --example arch_record -- [duration_s] [pga_g|recorded] [dt_s]`
//! (defaults: 30, recorded, 0.001). Environment: `FLIGHT=k` sets `LoopOptions::min_flight`,
//! `LOCK_LOSS`, `LOCK_RATE` the lock's options, `EVENTS=1` prints every event;
//! `ROCKING_LOOP_SCREEN=off|on|verify` the opening model's screen (docs/arch-performance.md).
use rocking::chain::arch::VoussoirArch;
use rocking::driver::closed::{LoopEventKind, Screen};
use rocking::driver::{simulate_loop, LoopOptions, LoopState};
use rocking::ground::records::parse_at2;
use rocking::ground::FnMotion;
use rocking::model::column::GRAVITY;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let duration: f64 = args.get(1).map_or(30.0, |s| s.parse().unwrap());
    let pga: Option<f64> = args
        .get(2)
        .filter(|s| *s != "recorded")
        .map(|s| s.parse::<f64>().unwrap() * GRAVITY);
    let dt: f64 = args.get(3).map_or(1e-3, |s| s.parse().unwrap());
    let chain = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
    let record = parse_at2(include_str!("records/synthetic.AT2"), "synthetic.AT2").unwrap();
    let rec = match pga {
        Some(p) => record.scaled_to_pga(p).unwrap(),
        None => record,
    };
    let motion = FnMotion(|t| rec.acceleration(t), rec.duration());
    let options = LoopOptions {
        dt,
        duration,
        lock_loss: std::env::var("LOCK_LOSS").map_or(1e-6, |s| s.parse().unwrap()),
        lock_rate: std::env::var("LOCK_RATE").ok().map(|s| s.parse().unwrap()),
        min_flight: std::env::var("FLIGHT").map_or(0.0, |s| s.parse().unwrap()),
        screen: Screen::from_env(),
        ..LoopOptions::default()
    };
    let clock = std::time::Instant::now();
    let out = simulate_loop(&chain, &motion, LoopState::at_rest(&chain), &options);
    let wall = clock.elapsed();
    let out = match out {
        Ok(out) => out,
        Err(e) => {
            println!("error after {wall:?}: {e}");
            return;
        }
    };
    let mut kinds = [0usize; 5];
    let mut multi = 0usize;
    for e in &out.events {
        let i = match &e.kind {
            LoopEventKind::Opening => 0,
            LoopEventKind::Closing { joints, .. } => {
                multi += usize::from(joints.len() > 1);
                1
            }
            LoopEventKind::Locked { .. } => 2,
            LoopEventKind::Settled => 3,
            LoopEventKind::Collapsed => 4,
        };
        kinds[i] += 1;
    }
    println!(
        "collapsed {} at t = {:.6} s, {} events (opening {}, closing {} of which {} multi-joint, \
         locked {}, settled {}), peak joint angle {:.6} rad, closure residual {:.1e} m, step \
         drift {:.1e} m, wall {:.3} s",
        out.collapsed,
        out.state.time,
        out.events.len(),
        kinds[0],
        kinds[1],
        multi,
        kinds[2],
        kinds[3],
        out.peak_angle,
        out.max_closure_residual,
        out.max_step_drift,
        wall.as_secs_f64()
    );
    println!(
        "opening model after a moving step: {} questions, {} answered by the screen ({:.1} %, \
         ROCKING_LOOP_SCREEN = {:?})",
        out.moving_checks,
        out.screened,
        100.0 * out.screened as f64 / out.moving_checks.max(1) as f64,
        options.screen
    );
    if std::env::var("EVENTS").is_ok() {
        for e in &out.events {
            let open: Vec<(usize, i8)> = e
                .statuses
                .iter()
                .enumerate()
                .filter(|(_, s)| **s != 0)
                .map(|(k, s)| (k, *s))
                .collect();
            println!("  {:.6} {:?} {:?}", e.time, e.kind, open);
        }
    }
}
