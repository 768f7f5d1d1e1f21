//! Driver timings: a single block and a three-block column under 30 s of ground motion at
//! dt = 1 ms, with the default options (Wilson θ, linear location, thesis Eq. 6). Two
//! excitations: a sampled 30 s record — `records::synthetic_record` with the bundled record's
//! seed, 100 Hz, linear interpolation, what a real accelerogram costs (the targets: single block
//! ≤ 2 ms per record, three blocks ≤ 20 ms) — and a sum of three sines (three `sin` calls per
//! evaluation). The report lines check that each run covers the whole 30 s (no overturning) and
//! print the wall time per step.

use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rocking::driver::{
    overturns, simulate, Recording, SimulationOptions, SteppingOptions, StoppingOptions,
};
use rocking::ground::records::{synthetic_record, Record, SYNTHETIC_SEED};
use rocking::ground::{FnMotion, GroundMotion};
use rocking::model::column::Column;

fn synthetic(t: f64) -> f64 {
    use std::f64::consts::TAU;
    2.0 * (TAU * 1.3 * t).sin()
        + 1.5 * (TAU * 2.9 * t + 1.0).sin()
        + 0.8 * (TAU * 0.7 * t + 2.0).sin()
}

fn options() -> SimulationOptions {
    SimulationOptions {
        stepping: SteppingOptions {
            dt: 1e-3,
            ..SteppingOptions::default()
        },
        stopping: StoppingOptions {
            duration: 30.0,
            ..StoppingOptions::default()
        },
        recording: Recording::NONE,
        ..SimulationOptions::default()
    }
}

fn report(name: &str, column: &Column, motion: &dyn GroundMotion) {
    let opts = options();
    let out = simulate(column, motion, &opts, None).unwrap();
    let runs = 20;
    let start = Instant::now();
    for _ in 0..runs {
        black_box(simulate(column, motion, &opts, None).unwrap());
    }
    let per_run = start.elapsed().as_secs_f64() / runs as f64;
    let steps = out.t_end / opts.stepping.dt;
    eprintln!(
        "{name}: {:.3} ms per 30 s record, {:.1} ns per step ({} impacts, stop {:?} at {:.2} s)",
        1e3 * per_run,
        1e9 * per_run / steps,
        out.impacts,
        out.stop_reason,
        out.t_end
    );
}

/// 30 s of the synthetic record (the bundled record's seed), 100 Hz, scaled to `pga` (m/s²).
fn record(pga: f64) -> Record {
    synthetic_record(SYNTHETIC_SEED, 30.0, 0.01, pga).unwrap()
}

fn bench(c: &mut Criterion) {
    let single = Column::uniform(1, 1.0, 4.0, 10_000.0).unwrap();
    let three = Column::uniform(3, 1.0, 6.0, 15_000.0).unwrap();
    let motion = FnMotion(synthetic, 30.0);
    // Peak levels at which both columns rock through the whole record without overturning
    // (checked by the report lines): 1.2 × and 1.1 × their static uplift acceleration.
    let rec1 = record(1.2 * single.static_uplift_acceleration(9.81));
    let rec3 = record(1.1 * three.static_uplift_acceleration(9.81));
    let recorded1 = FnMotion(|t: f64| rec1.acceleration(t), 30.0);
    let recorded3 = FnMotion(|t: f64| rec3.acceleration(t), 30.0);
    report("single block 1 x 4 m, 30 s record", &single, &recorded1);
    report("three blocks 1 x 2 m, 30 s record", &three, &recorded3);
    report("single block 1 x 4 m, sum of sines", &single, &motion);
    report("three blocks 1 x 2 m, sum of sines", &three, &motion);
    let opts = options();
    c.bench_function("driver single block 30 s record", |b| {
        b.iter(|| simulate(&single, &recorded1, &opts, None).unwrap())
    });
    c.bench_function("driver three blocks 30 s record", |b| {
        b.iter(|| simulate(&three, &recorded3, &opts, None).unwrap())
    });
    c.bench_function("overturns single block 30 s record", |b| {
        b.iter(|| overturns(&single, &recorded1, &opts).unwrap())
    });
    c.bench_function("driver single block 30 s sines", |b| {
        b.iter(|| simulate(&single, &motion, &opts, None).unwrap())
    });
    c.bench_function("driver three blocks 30 s sines", |b| {
        b.iter(|| simulate(&three, &motion, &opts, None).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
