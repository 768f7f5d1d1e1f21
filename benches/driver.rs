//! Driver timings: a single block and a three-block column under 30 s of a synthetic excitation
//! at dt = 1 ms, with the default options (Wilson θ, linear location, thesis Eq. 6). Two
//! excitations: a sum of three sines (three `sin` calls per evaluation, which the driver's own
//! cost is measured with) and a seeded random record sampled at 100 Hz with linear interpolation
//! (what a real accelerogram costs). Prints the wall time per step; targets: single block
//! ≤ 2 ms per record (≈ 60 ns per step), three blocks ≤ 20 ms.

use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rocking::column::Column;
use rocking::driver::{overturns, simulate, FnMotion, GroundMotion, Recording, SimulationOptions};

fn synthetic(t: f64) -> f64 {
    use std::f64::consts::TAU;
    2.0 * (TAU * 1.3 * t).sin()
        + 1.5 * (TAU * 2.9 * t + 1.0).sin()
        + 0.8 * (TAU * 0.7 * t + 2.0).sin()
}

/// A seeded random record: 100 Hz white noise smoothed by a two-pole filter, peak ≈ 3 m/s².
struct RandomRecord {
    samples: Vec<f64>,
}

impl RandomRecord {
    fn new(seed: u64) -> RandomRecord {
        let mut s = seed;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let (mut y1, mut y2) = (0.0, 0.0);
        let mut samples: Vec<f64> = (0..3001)
            .map(|_| {
                y1 = 0.9 * y1 + next();
                y2 = 0.9 * y2 + y1;
                y2
            })
            .collect();
        let peak = samples.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        samples.iter_mut().for_each(|v| *v *= 3.0 / peak);
        RandomRecord { samples }
    }

    fn at(&self, t: f64) -> f64 {
        let x = t * 100.0;
        let i = x as usize;
        if i + 1 >= self.samples.len() {
            return 0.0;
        }
        let f = x - i as f64;
        self.samples[i] + f * (self.samples[i + 1] - self.samples[i])
    }
}

fn options() -> SimulationOptions {
    SimulationOptions {
        dt: 1e-3,
        duration: 30.0,
        record: Recording::NONE,
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
    let steps = out.t_end / opts.dt;
    eprintln!(
        "{name}: {:.3} ms per 30 s record, {:.1} ns per step ({} impacts, stop {:?} at {:.2} s)",
        1e3 * per_run,
        1e9 * per_run / steps,
        out.impacts,
        out.stop_reason,
        out.t_end
    );
}

fn bench(c: &mut Criterion) {
    let single = Column::uniform(1, 1.0, 4.0, 10_000.0).unwrap();
    let three = Column::uniform(3, 1.0, 6.0, 15_000.0).unwrap();
    let motion = FnMotion(synthetic, 30.0);
    let record = RandomRecord::new(7);
    let recorded = FnMotion(|t: f64| record.at(t), 30.0);
    report("single block 1 x 4 m, sum of sines", &single, &motion);
    report("three blocks 1 x 2 m, sum of sines", &three, &motion);
    report("single block 1 x 4 m, random record", &single, &recorded);
    report("three blocks 1 x 2 m, random record", &three, &recorded);
    let opts = options();
    c.bench_function("driver single block 30 s", |b| {
        b.iter(|| simulate(&single, &motion, &opts, None).unwrap())
    });
    c.bench_function("driver three blocks 30 s", |b| {
        b.iter(|| simulate(&three, &motion, &opts, None).unwrap())
    });
    c.bench_function("overturns single block 30 s", |b| {
        b.iter(|| overturns(&single, &motion, &opts).unwrap())
    });
    c.bench_function("driver single block 30 s record", |b| {
        b.iter(|| simulate(&single, &recorded, &opts, None).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
