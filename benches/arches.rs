//! Constrained impact and opening on a semicircular arch of 20 voussoirs (21 joints, 42 DOFs,
//! t/R = 0.15), projection solver, through the Rust API:
//! - opening from rest at 1.2 × the collapse multiplier (21 closed joints);
//! - opening with the four-hinge collapse mechanism moving (17 closed joints, `G a = −Ġ v`);
//! - impact of that mechanism swinging back, its four hinges closing together.
//!
//! The opening from rest and the impact also through the C ABI
//! (`rocking_opening_model_constrained`, `rocking_impact_model_constrained`: copies, checks and
//! all).
//!
//! Time histories (`rocking::driver::simulate_loop`, dt = 1 ms, 30 s: the bundled 20 s record
//! `examples/records/synthetic.AT2` and 10 s after it) of the same arch: the record scaled to a
//! PGA of 0.1 g (below the arch's λ = 0.149: it stays closed) and as recorded (0.3 g: it opens;
//! the run ends where the arch collapses, printed before the measurement).
//!
//! `cargo bench --bench arches` (issue 15: under 1 ms through the C ABI; a 30 s record under
//! 100 ms).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rocking::chain::arch::VoussoirArch;
use rocking::model::column::GRAVITY;
use rocking::{impact_model_constrained, opening_model_constrained, ModelOptions, Solver, Status};
use std::time::Duration;

struct Case {
    nj: usize,
    mass: Vec<f64>,
    g: Vec<f64>,
    load: Vec<f64>,
    mechanism: Vec<Status>,
    rates: Vec<f64>,
    rhs: Vec<f64>,
}

/// The arch, its four-hinge collapse mechanism of t/R = 0.15 (intrados at joints 3 and 15,
/// extrados at 9 and 20: limit analysis, `tests/arch_statics.rs`) opening at unit rate.
fn case() -> Case {
    let chain = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
    let nj = chain.n_joints();
    let m = 2 * nj;
    let pose = chain.pose(&vec![0.0; m]);
    let mass = chain.mass_matrix(&pose);
    let g = chain.closure_matrix(&pose);
    let load = chain.load_vector(&pose, -0.18 * GRAVITY, GRAVITY);
    let mut mechanism = vec![Status::Closed; nj];
    for (k, s) in [
        (3, Status::OpenRight),
        (9, Status::OpenLeft),
        (15, Status::OpenRight),
        (20, Status::OpenLeft),
    ] {
        mechanism[k] = s;
    }
    // Null vector of the 3 × 4 closure of the hinge DOFs (cofactors), opening direction.
    let dofs: Vec<usize> = (0..nj).filter_map(|k| mechanism[k].dof(k, nj)).collect();
    let col = |i: usize| [g[dofs[i]], g[m + dofs[i]], g[2 * m + dofs[i]]];
    let det3 = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0])
    };
    let mut v: Vec<f64> = (0..4)
        .map(|i| {
            let o: Vec<[f64; 3]> = (0..4).filter(|&j| j != i).map(col).collect();
            (if i % 2 == 0 { 1.0 } else { -1.0 }) * det3(o[0], o[1], o[2])
        })
        .collect();
    let first = mechanism[3].sign();
    let scale = v.iter().fold(0.0_f64, |a, x| a.max(x.abs())) * (v[0] * first).signum();
    v.iter_mut().for_each(|x| *x /= scale);
    let mut rates = vec![0.0; m];
    for (i, &d) in dofs.iter().enumerate() {
        rates[d] = v[i];
    }
    let rhs = chain
        .closure_rate(&pose, &rates)
        .iter()
        .map(|x| -x)
        .collect();
    Case {
        nj,
        mass,
        g,
        load,
        mechanism,
        rates,
        rhs,
    }
}

fn open_joints(st: &[Status]) -> Vec<(usize, i8)> {
    st.iter()
        .enumerate()
        .filter(|(_, s)| s.is_open())
        .map(|(k, s)| (k, s.as_i8()))
        .collect()
}

fn arches(c: &mut Criterion) {
    let case = case();
    let nj = case.nj;
    let opts = ModelOptions {
        solver: Solver::Projection,
        ..ModelOptions::default()
    };
    // What each case decides (printed once).
    {
        let mut st = vec![Status::Closed; nj];
        let mut a = vec![0.0; 2 * nj];
        let r = opening_model_constrained(
            &case.mass, &case.load, &case.g, None, &mut st, &mut a, &opts,
        )
        .unwrap();
        println!(
            "opening from rest: {} relaxed problems, opens {:?}",
            r.configurations_examined,
            open_joints(&st)
        );
        let mut st = case.mechanism.clone();
        let r = opening_model_constrained(
            &case.mass,
            &case.load,
            &case.g,
            Some(&case.rhs),
            &mut st,
            &mut a,
            &opts,
        )
        .unwrap();
        println!(
            "opening, mechanism moving: {} relaxed problems, open {:?}",
            r.configurations_examined,
            open_joints(&st)
        );
        let mut st = case.mechanism.clone();
        let mut v: Vec<f64> = case.rates.iter().map(|x| -x).collect();
        let closing: Vec<bool> = case.mechanism.iter().map(|s| s.is_open()).collect();
        let r = impact_model_constrained(&case.mass, &case.g, &mut st, &mut v, &closing, &opts)
            .unwrap();
        println!(
            "impact: {} relaxed problems, open after {:?}, kinetic energy kept {:.4}",
            r.configurations_examined,
            open_joints(&st),
            r.kinetic_after / r.kinetic_before
        );
    }
    let mut group = c.benchmark_group("arch 21 joints");
    group
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    group.bench_function("opening from rest", |b| {
        b.iter(|| {
            let mut st = vec![Status::Closed; nj];
            let mut a = vec![0.0; 2 * nj];
            opening_model_constrained(
                black_box(&case.mass),
                &case.load,
                &case.g,
                None,
                &mut st,
                &mut a,
                &opts,
            )
            .unwrap()
        })
    });
    group.bench_function("opening, mechanism moving", |b| {
        b.iter(|| {
            let mut st = case.mechanism.clone();
            let mut a = vec![0.0; 2 * nj];
            opening_model_constrained(
                black_box(&case.mass),
                &case.load,
                &case.g,
                Some(&case.rhs),
                &mut st,
                &mut a,
                &opts,
            )
            .unwrap()
        })
    });
    let back: Vec<f64> = case.rates.iter().map(|x| -x).collect();
    let closing: Vec<bool> = case.mechanism.iter().map(|s| s.is_open()).collect();
    group.bench_function("impact, four hinges closing", |b| {
        b.iter(|| {
            let mut st = case.mechanism.clone();
            let mut v = back.clone();
            impact_model_constrained(
                black_box(&case.mass),
                &case.g,
                &mut st,
                &mut v,
                &closing,
                &opts,
            )
            .unwrap()
        })
    });
    let m = 2 * nj;
    let c_opts = rocking::ffi::RockingOptions {
        n_impacts: 1,
        solver: rocking::ffi::ROCKING_SOLVER_PROJECTION,
        tolerance: 1e-12,
    };
    group.bench_function("C ABI: opening from rest", |b| {
        b.iter(|| {
            let mut st = vec![0i8; nj];
            let mut a = vec![0.0; m];
            let code = unsafe {
                rocking::ffi::rocking_opening_model_constrained(
                    nj,
                    black_box(case.mass.as_ptr()),
                    case.load.as_ptr(),
                    3,
                    case.g.as_ptr(),
                    std::ptr::null(),
                    st.as_mut_ptr(),
                    a.as_mut_ptr(),
                    &c_opts,
                    std::ptr::null_mut(),
                )
            };
            assert_eq!(code, 0);
            a
        })
    });
    let c_mechanism: Vec<i8> = case.mechanism.iter().map(|s| s.as_i8()).collect();
    let c_closing: Vec<u8> = closing.iter().map(|&f| u8::from(f)).collect();
    group.bench_function("C ABI: impact, four hinges closing", |b| {
        b.iter(|| {
            let mut st = c_mechanism.clone();
            let mut v = back.clone();
            let code = unsafe {
                rocking::ffi::rocking_impact_model_constrained(
                    nj,
                    black_box(case.mass.as_ptr()),
                    3,
                    case.g.as_ptr(),
                    st.as_mut_ptr(),
                    v.as_mut_ptr(),
                    c_closing.as_ptr(),
                    &c_opts,
                    std::ptr::null_mut(),
                )
            };
            assert_eq!(code, 0);
            v
        })
    });
    group.finish();
}

fn time_history(c: &mut Criterion) {
    use rocking::driver::closed::Screen;
    use rocking::driver::{simulate_loop, LoopOptions, LoopState};
    use rocking::ground::records::parse_at2;
    use rocking::ground::FnMotion;
    let chain = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
    let record = parse_at2(
        include_str!("../examples/records/synthetic.AT2"),
        "synthetic.AT2",
    )
    .unwrap();
    let options = LoopOptions {
        dt: 1e-3,
        duration: 30.0,
        ..LoopOptions::default()
    };
    let mut group = c.benchmark_group("arch time history, 30 s at dt = 1 ms");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    // The opening model's screen (docs/arch-performance.md) on, as by default, and off.
    for (name, pga, screen) in [
        ("PGA 0.1 g", Some(0.1 * GRAVITY), Screen::On),
        ("as recorded (0.3 g)", None, Screen::On),
        ("as recorded (0.3 g), screen off", None, Screen::Off),
    ] {
        let rec = match pga {
            Some(p) => record.scaled_to_pga(p).unwrap(),
            None => record.clone(),
        };
        let motion = FnMotion(|t| rec.acceleration(t), rec.duration());
        let options = LoopOptions {
            screen,
            ..options.clone()
        };
        let run = || simulate_loop(&chain, &motion, LoopState::at_rest(&chain), &options).unwrap();
        let out = run();
        println!(
            "{name}: collapsed {} at t = {:.4} s, {} events, peak joint angle {:.6} rad, \
             closure residual {:.1e} m, opening model after a moving step {} times, {} answered \
             by the screen",
            out.collapsed,
            out.state.time,
            out.events.len(),
            out.peak_angle,
            out.max_closure_residual,
            out.moving_checks,
            out.screened
        );
        group.bench_function(name, |b| b.iter(|| black_box(run())));
    }
    group.finish();
}

criterion_group!(benches, arches, time_history);
criterion_main!(benches);
