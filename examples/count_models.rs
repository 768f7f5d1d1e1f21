//! One call of a models-bench case (`impact`/`opening`, `enum`/`proj`, closed interfaces), for
//! callgrind's instruction count (docs/performance.md, "Redesign (issue 10): models and spectra").
use rocking::model::column::{Column, GRAVITY};
use rocking::{impact_model, opening_model, ModelOptions, Solver, Status};
use std::hint::black_box;

#[inline(never)]
fn run_impact(mass: &[f64], st: &[Status], v: &[f64], opts: &ModelOptions) -> f64 {
    let n = st.len();
    let mut s = st.to_vec();
    let mut vv = v.to_vec();
    impact_model(black_box(mass), &mut s, &mut vv, n - 1, opts).unwrap();
    vv[0]
}

#[inline(never)]
fn run_opening(mass: &[f64], load: &[f64], n: usize, opts: &ModelOptions) -> f64 {
    let mut s = vec![Status::Closed; n];
    let mut a = vec![0.0; 2 * n];
    opening_model(black_box(mass), load, &mut s, &mut a, opts).unwrap();
    a[0]
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (kind, solver, n) = (&args[1], &args[2], args[3].parse::<usize>().unwrap());
    let solver = if solver == "enum" {
        Solver::Enumerate
    } else {
        Solver::Projection
    };
    let opts = ModelOptions {
        solver,
        ..ModelOptions::default()
    };
    let column = Column::uniform(n, 0.4, 1.2 * n as f64, 100.0 * n as f64).unwrap();
    let pose = column.pose(&vec![0.0; 2 * n]);
    let mass = column.mass_matrix(&pose);
    let r = if kind == "impact" {
        let mut st = vec![Status::Closed; n];
        st[n - 1] = Status::OpenLeft;
        let mut v = vec![0.0; 2 * n];
        v[2 * n - 1] = -1.0;
        run_impact(&mass, &st, &v, &opts)
    } else {
        let amin = column.static_uplift_acceleration(GRAVITY);
        let load = column.load_vector(&pose, 2.0 * amin, GRAVITY);
        run_opening(&mass, &load, n, &opts)
    };
    println!("{r:e}");
}
