//! Drum-column timings (issue 11): a column of ten 1 × 1 m drums (2500 kg each, μ = 0.5, sliding
//! and flight allowed) through 30 s of ground motion with the Moreau–Jean scheme of
//! `rocking::contact` (the target: under 50 ms); the same at dt = 1, 2 and 5 ms; and one contact
//! problem of a 20-drum column closed and at rest (the block-tridiagonal solve alone). The record
//! is Northridge MUL009 scaled to 4 m/s² when `../shared` is there, else 30 s of the synthetic
//! record (the bundled one's seed) at 4 m/s². The report lines print the time per run and per
//! step, and the work counters.

use std::path::Path;
use std::time::Instant;

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use rocking::contact::drums::Drums;
use rocking::contact::friction::{ContactProblem, JointContacts, JointStatus};
use rocking::contact::simulation::{simulate, DrumOptions};
use rocking::ground::excitation::Excitation;
use rocking::ground::records::{read_at2, synthetic_record, Record, SYNTHETIC_SEED};
use rocking::model::column::{Block, Column};

fn record() -> (String, Record) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/records/fema-p695/farfield/RSN953_NORTHR_MUL009.AT2");
    match read_at2(&path) {
        Ok(r) => ("MUL009 at 4 m/s²".into(), r.scaled_to_pga(4.0).unwrap()),
        Err(_) => (
            "synthetic at 4 m/s²".into(),
            synthetic_record(SYNTHETIC_SEED, 30.0, 0.01, 4.0).unwrap(),
        ),
    }
}

fn options(dt: f64) -> DrumOptions {
    DrumOptions {
        dt,
        ..DrumOptions::quiet(30.0, 0.5, 1)
    }
}

fn report(name: &str, column: &Column, motion: &Excitation, dt: f64) {
    let opts = options(dt);
    let out = simulate(column, motion, &opts, None).unwrap();
    let runs = 5;
    let start = Instant::now();
    for _ in 0..runs {
        black_box(simulate(column, motion, &opts, None).unwrap());
    }
    let per_run = start.elapsed().as_secs_f64() / runs as f64;
    eprintln!(
        "{name}, dt = {dt}: {:.1} ms per 30 s, {:.2} µs per step; stop {:?} at {:.2} s, peak rotation {:.4}, {} impacts; {:?}",
        1e3 * per_run,
        1e6 * per_run / (out.t_end / dt),
        out.stop,
        out.t_end,
        out.peak_rotation.iter().fold(0.0_f64, |m, x| m.max(*x)),
        out.event_counts[1],
        out.counters
    );
}

fn bench(c: &mut Criterion) {
    let (name, rec) = record();
    let motion = Excitation::record(rec).unwrap();
    let ten = Column::new(vec![Block::rectangle(1.0, 1.0, 2500.0); 10]).unwrap();
    for dt in [1e-3, 2e-3, 5e-3] {
        report(&format!("10 drums 1 × 1 m, {name}"), &ten, &motion, dt);
    }
    let mut g = c.benchmark_group("drums");
    g.sample_size(10);
    g.bench_function("ten drums, 30 s record, dt = 1 ms", |b| {
        b.iter(|| simulate(&ten, &motion, &options(1e-3), None).unwrap())
    });
    g.bench_function("ten drums, 30 s record, dt = 2 ms", |b| {
        b.iter(|| simulate(&ten, &motion, &options(2e-3), None).unwrap())
    });
    g.finish();
    // One contact problem: twenty drums closed, at rest, under gravity and a ground push.
    let twenty = Column::new(vec![Block::rectangle(1.0, 1.0, 2500.0); 20]).unwrap();
    let d = Drums::new(&twenty);
    let q = d.rest_positions();
    let masses: Vec<f64> = (0..20).map(|j| d.mass(j)).collect();
    let inertias: Vec<f64> = (0..20).map(|j| d.inertia(j)).collect();
    let joints: Vec<JointContacts> = (0..20)
        .map(|k| {
            let g = d.joint(&q, k);
            JointContacts {
                active: [true, true],
                bilateral: [false; 2],
                rows: [g.ends[0].rows, g.ends[1].rows],
                mu: 0.5,
            }
        })
        .collect();
    let mut v_free = vec![0.0; 60];
    for j in 0..20 {
        v_free[3 * j] = -1e-3 * 0.5;
        v_free[3 * j + 1] = -1e-3 * 9.81;
    }
    let mut problem = ContactProblem::new(&masses, &inertias);
    c.bench_function("contact problem, 20 joints closed", |b| {
        b.iter(|| {
            problem.set(&joints, &v_free);
            let mut st = vec![
                JointStatus {
                    closed: [true, true],
                    ..JointStatus::default()
                };
                20
            ];
            black_box(problem.solve(&mut st).unwrap())
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
