//! Impact and opening time against the number of closed interfaces: enumeration 1–12,
//! projection 1–200, a 40- and 100-block impact through the C ABI, and the thesis's two-block
//! cases of `rocking::samples` (SPEC §8), checked against their printed answers before timing.
//!
//! `cargo bench --bench models` (numbers go into docs/performance.md).

use criterion::measurement::WallTime;
use criterion::{
    black_box, criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion,
};
use rocking::ffi::{rocking_impact_model, RockingOptions};
use rocking::model::column::{Column, GRAVITY};
use rocking::{impact_model, opening_model, samples, ModelOptions, Solver, Status};
use std::time::Duration;

/// A column of `n` slender blocks (0.4 × 1.2 m) whose top interface closes at 1 rad/s about
/// its left corner: `n − 1` closed interfaces choose.
fn impact_case(n: usize) -> (Vec<f64>, Vec<Status>, Vec<f64>) {
    let column = Column::uniform(n, 0.4, 1.2 * n as f64, 100.0 * n as f64).unwrap();
    let mass = column.mass_matrix(&column.pose(&vec![0.0; 2 * n]));
    let mut st = vec![Status::Closed; n];
    st[n - 1] = Status::OpenLeft;
    let mut v = vec![0.0; 2 * n];
    v[2 * n - 1] = -1.0;
    (mass, st, v)
}

/// The same column, closed, under a ground acceleration of 2 a_min: `n` closed interfaces.
fn opening_case(n: usize) -> (Vec<f64>, Vec<f64>) {
    let column = Column::uniform(n, 0.4, 1.2 * n as f64, 100.0 * n as f64).unwrap();
    let pose = column.pose(&vec![0.0; 2 * n]);
    let amin = column.static_uplift_acceleration(GRAVITY);
    (
        column.mass_matrix(&pose),
        column.load_vector(&pose, 2.0 * amin, GRAVITY),
    )
}

/// Closed interfaces timed per solver: enumeration up to its limit (12), projection to 200.
fn closed_interfaces() -> [(Solver, Vec<usize>); 2] {
    [
        (Solver::Enumerate, vec![1, 2, 3, 5, 7, 9, 11, 12]),
        (
            Solver::Projection,
            vec![1, 2, 3, 5, 7, 9, 11, 12, 20, 40, 100, 200],
        ),
    ]
}

/// A benchmark group with short warm-up and measurement (each call is microseconds).
fn group<'a>(c: &'a mut Criterion, name: &str) -> BenchmarkGroup<'a, WallTime> {
    let mut g = c.benchmark_group(name);
    g.warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
        .sample_size(10);
    g
}

fn impacts(c: &mut Criterion) {
    let mut g = group(c, "impact");
    for (solver, sizes) in closed_interfaces() {
        for closed in sizes {
            let (mass, st, v) = impact_case(closed + 1);
            let opts = ModelOptions {
                solver,
                ..ModelOptions::default()
            };
            g.bench_with_input(
                BenchmarkId::new(format!("{solver:?}"), closed),
                &closed,
                |b, _| {
                    b.iter(|| {
                        let mut s = st.clone();
                        let mut vv = v.clone();
                        impact_model(black_box(&mass), &mut s, &mut vv, closed, &opts).unwrap()
                    })
                },
            );
        }
    }
    g.finish();
}

fn openings(c: &mut Criterion) {
    let mut g = group(c, "opening");
    for (solver, sizes) in closed_interfaces() {
        for closed in sizes {
            let (mass, load) = opening_case(closed);
            let opts = ModelOptions {
                solver,
                ..ModelOptions::default()
            };
            g.bench_with_input(
                BenchmarkId::new(format!("{solver:?}"), closed),
                &closed,
                |b, _| {
                    b.iter(|| {
                        let mut s = vec![Status::Closed; closed];
                        let mut a = vec![0.0; 2 * closed];
                        opening_model(black_box(&mass), &load, &mut s, &mut a, &opts).unwrap()
                    })
                },
            );
        }
    }
    g.finish();
}

fn c_abi(c: &mut Criterion) {
    let mut g = group(c, "c_abi_impact");
    for blocks in [40usize, 100] {
        let (mass, st, v) = impact_case(blocks);
        let st: Vec<i8> = st.iter().map(|s| s.as_i8()).collect();
        let opts = RockingOptions {
            n_impacts: 1,
            solver: 0,
            tolerance: 1e-12,
        };
        g.bench_with_input(BenchmarkId::from_parameter(blocks), &blocks, |b, _| {
            b.iter(|| {
                let mut s = st.clone();
                let mut vv = v.clone();
                let code = unsafe {
                    rocking_impact_model(
                        blocks,
                        mass.as_ptr(),
                        s.as_mut_ptr(),
                        vv.as_mut_ptr(),
                        blocks - 1,
                        &opts,
                        std::ptr::null_mut(),
                    )
                };
                assert_eq!(code, 0);
            })
        });
    }
    g.finish();
}

/// The impact of thesis Fig. 22 (one and two consecutive impacts) and the opening of
/// Fig. 18–19, each solver.
fn thesis_cases(c: &mut Criterion) {
    let mut g = group(c, "thesis");
    let impact = samples::two_block_impact();
    let opening = samples::two_block_top_push();
    for solver in [Solver::Enumerate, Solver::Projection] {
        for answer in samples::TWO_BLOCK_IMPACT_ANSWERS {
            let opts = ModelOptions {
                solver,
                n_impacts: answer.n_impacts,
                ..ModelOptions::default()
            };
            let run = || {
                let mut s = impact.statuses.clone();
                let mut v = impact.velocity.clone();
                impact_model(
                    black_box(&impact.mass),
                    &mut s,
                    &mut v,
                    impact.closing,
                    &opts,
                )
                .unwrap();
                (s, v)
            };
            let (s, v) = run();
            let rates = answer.printed_rates();
            assert!(s == answer.statuses && rates[0].matches(v[0]) && rates[1].matches(v[1]));
            let id = format!("impact {solver:?}, {} impact(s)", answer.n_impacts);
            g.bench_function(id, |b| b.iter(run));
        }
        let opts = ModelOptions {
            solver,
            ..ModelOptions::default()
        };
        let run = || {
            let mut s = vec![Status::Closed; 2];
            let mut a = vec![0.0; 4];
            opening_model(
                black_box(&opening.mass),
                &opening.load,
                &mut s,
                &mut a,
                &opts,
            )
            .unwrap();
            s
        };
        assert_eq!(run(), opening.expected);
        g.bench_function(format!("opening {solver:?}"), |b| b.iter(run));
    }
    g.finish();
}

criterion_group!(benches, impacts, openings, c_abi, thesis_cases);
criterion_main!(benches);
