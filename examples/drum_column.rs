//! One drum column under a recorded ground motion with the Moreau–Jean scheme of
//! `rocking::contact`, printed as one JSON object (the counterpart of
//! `bench/siconos/drums_siconos.py`, same arguments):
//!
//! ```text
//! cargo run --release --example drum_column -- --drums 10 --width 1 --height 1 \
//!     --record RECORD.AT2 --pga 4 --mu 0.5 --dt 0.001 [--duration 30] [--impacts 1] \
//!     [--scheme moreau|auto] [--locate 0|1] [--persistent 0|1] [--projection 0|1] \
//!     [--consistent 0|1] [--energy-tol T] [--clusters 0|1]
//! ```
//!
//! `--consistent 1`: `SchemeOptions::energy_consistent` (docs/energy-control.md); `--energy-tol`:
//! the error control. `--clusters 1`: `SchemeOptions::clusters` (condensed steps, docs/multidrum.md);
//! the JSON then ends with their counters (`"clusters"`).
//!
//! `--locate 0 --persistent 0 --projection 0` (all default 1) is plain Moreau–Jean, the scheme
//! of the Siconos peer: no impact located inside the step, restitution zero at every contact
//! (also at persistent ones), no position projection. For comparisons only.
//!
//! `--scheme auto`: the automatic scheme (`rocking::contact::auto`): the event-driven driver
//! where events are few, Moreau–Jean where they crowd.

use std::path::PathBuf;
use std::time::Instant;

use rocking::contact::auto::{self, AutoOptions};
use rocking::contact::simulation::{simulate, DrumOptions, DrumStop};
use rocking::driver::SimulationOptions;
use rocking::ground::excitation::Excitation;
use rocking::ground::records::read_at2;
use rocking::model::column::{Block, Column};

fn main() {
    let mut args = std::env::args().skip(1);
    let (mut n, mut w, mut h, mut pga, mut mu, mut dt) = (10usize, 1.0, 1.0, 4.0, 0.5, 1e-3);
    let mut record: Option<PathBuf> = None;
    let mut duration: Option<f64> = None;
    let mut impacts = 1u32;
    let mut automatic = false;
    let (mut locate, mut persistent, mut projection) = (true, true, true);
    let mut consistent = false;
    let mut energy_tol: Option<f64> = None;
    let mut clusters = false;
    while let Some(a) = args.next() {
        let v = args.next().unwrap_or_else(|| panic!("{a} needs a value"));
        match a.as_str() {
            "--drums" => n = v.parse().unwrap(),
            "--width" => w = v.parse().unwrap(),
            "--height" => h = v.parse().unwrap(),
            "--record" => record = Some(PathBuf::from(v)),
            "--pga" => pga = v.parse().unwrap(),
            "--mu" => mu = v.parse().unwrap(),
            "--dt" => dt = v.parse().unwrap(),
            "--duration" => duration = Some(v.parse().unwrap()),
            "--impacts" => impacts = v.parse().unwrap(),
            "--scheme" => automatic = v == "auto",
            "--locate" => locate = v != "0",
            "--persistent" => persistent = v != "0",
            "--projection" => projection = v != "0",
            "--consistent" => consistent = v != "0",
            "--energy-tol" => energy_tol = Some(v.parse().unwrap()),
            "--clusters" => clusters = v != "0",
            other => panic!("unknown argument {other}"),
        }
    }
    let rec = read_at2(&record.expect("--record")).unwrap();
    let duration = duration.unwrap_or(rec.duration());
    let motion = Excitation::record(rec.scaled_to_pga(pga).unwrap()).unwrap();
    let col = Column::new(vec![Block::rectangle(w, h, 2500.0 * w * h); n]).unwrap();
    let mut opts = DrumOptions {
        dt,
        ..DrumOptions::quiet(duration, mu, impacts)
    };
    opts.scheme.locate_impacts = locate;
    opts.scheme.persistent_restitution = persistent;
    opts.scheme.project = projection;
    opts.scheme.energy_consistent = consistent;
    opts.scheme.energy_tolerance = energy_tol;
    opts.scheme.clusters = clusters;
    let t0 = Instant::now();
    let out = if automatic {
        let mut driver = SimulationOptions::default();
        driver.physics.friction = mu;
        driver.physics.model.n_impacts = impacts;
        let rules = AutoOptions::for_step(dt);
        auto::simulate(&col, &motion, &driver, &opts, &rules, None).unwrap()
    } else {
        simulate(&col, &motion, &opts, None).unwrap()
    };
    let wall = t0.elapsed().as_secs_f64();
    let max_abs = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.9e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let joint = match out.stop {
        DrumStop::Overturned { joint } | DrumStop::SlidOff { joint } => joint.to_string(),
        _ => "null".to_string(),
    };
    let mut json = format!(
        "{{\"code\": \"rocking\", \"drums\": {n}, \"width\": {w}, \"height\": {h}, \"pga\": {pga}, \"mu\": {mu}, \"dt\": {dt}, \"t_end\": {:.6}, \"stop\": \"{:?}\", \"overturned\": {}, \"overturned_joint\": {joint}, \"peak_rotation\": {:.9e}, \"peak_rotations\": [{}], \"peak_top_displacement\": {:.9e}, \"residual_slip\": {:.9e}, \"residual_slips\": [{}], \"peak_slip\": {:.9e}, \"energy_error\": {:.3e}, \"energy\": {{\"ground_work\": {:.6e}, \"potential_change\": {:.6e}, \"kinetic_change\": {:.6e}, \"impact\": {:.6e}, \"friction\": {:.6e}, \"persistent_contact\": {:.6e}, \"projection\": {:.6e}}}, \"counters\": \"{:?}\", \"switches\": {}, \"switch_log\": \"{}\", \"time_event_driven\": {:.4}, \"wall_s\": {wall:.6}}}",
        out.t_end,
        out.stop,
        out.overturned,
        max_abs(&out.peak_rotation),
        list(&out.peak_rotation),
        out.peak_top_displacement,
        max_abs(&out.residual_slip),
        list(&out.residual_slip),
        max_abs(&out.peak_slip),
        out.energy.residual() / out.energy.scale(),
        out.energy.accounts.ground_work,
        out.energy.potential_change,
        out.energy.kinetic_change,
        out.energy.accounts.impact,
        out.energy.accounts.friction,
        out.energy.accounts.persistent_contact,
        out.energy.accounts.projection,
        out.counters,
        out.switches.len(),
        out.switches
            .iter()
            .map(|s| format!("{:.3} s to {} ({})", s.t, s.to.name(), s.why))
            .collect::<Vec<_>>()
            .join("; "),
        out.time_event_driven,
    );
    if clusters {
        json.pop();
        json += &format!(", \"clusters\": \"{:?}\"}}", out.clusters);
    }
    println!("{json}");
}
