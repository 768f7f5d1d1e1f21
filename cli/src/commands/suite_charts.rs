//! The charts of `rocking suite`: the records' OAS with the characteristic ones (Fig. 44, 47a),
//! the transformed OAS with `f_min` (Fig. 47b), the normalised convex hulls (Fig. 49) and the
//! design curves against the block size.

use rocking::spectra::report::{OasReport, SuiteReport};
use rocking::spectra::{statistics, TransformedHull};

use super::oas::level_chart;
use crate::plot::{Chart, Scale, Series, Style, COLORS};

/// The grey of the individual records.
const GREY: (u8, u8, u8) = (0xbb, 0xbb, 0xbb);

/// The colour of the `k`-th fractile.
fn color(k: usize) -> (u8, u8, u8) {
    COLORS[k % 6]
}

/// One series per record, `point` mapping a level of its OAS to (x, y); only the first is named
/// (the legend's entry for all of them).
fn records(
    r: &SuiteReport,
    point: impl Fn(&OasReport, usize) -> Option<(f64, f64)>,
) -> Vec<Series> {
    r.records
        .iter()
        .enumerate()
        .map(|(k, o)| Series {
            name: if k == 0 {
                format!("OAS of the {} records", r.records.len())
            } else {
                String::new()
            },
            points: (0..o.levels.len()).filter_map(|i| point(o, i)).collect(),
            style: Style::Points,
            color: GREY,
        })
        .collect()
}

/// The level range of the suite: (1, the highest level).
fn level_max(r: &SuiteReport) -> f64 {
    r.records
        .iter()
        .flat_map(|o| o.levels.iter().map(|l| l.level.level))
        .fold(1.0, f64::max)
}

/// `(p, level)` of level `i` of `o`.
fn by_p(o: &OasReport, i: usize) -> Option<(f64, f64)> {
    let l = &o.levels[i];
    Some((l.p?, l.level.level))
}

/// `(f, level)` of level `i` of `o`.
fn by_f(o: &OasReport, i: usize) -> Option<(f64, f64)> {
    let l = &o.levels[i];
    Some((l.f?, l.level.level))
}

/// `(R, level)` of level `i` of `o`.
fn by_size(o: &OasReport, i: usize) -> Option<(f64, f64)> {
    let l = &o.levels[i];
    Some((l.size?, l.level.level))
}

/// `i_cr` of the suite's slenderness (Eq. 18).
fn i_cr(r: &SuiteReport) -> f64 {
    let slenderness = r.records.first().map_or(12.0, |o| o.slenderness);
    let delta = (1.0 / slenderness).atan();
    (2.0 / (1.0 + delta.cos())).sqrt()
}

/// The charts: (name, chart).
pub fn charts(r: &SuiteReport) -> Vec<(&'static str, Chart)> {
    let lmax = level_max(r);
    let i_cr = i_cr(r);
    let first = r.records.first();
    let gravity = first.map_or(9.81, |o| o.gravity);
    let slenderness = first.map_or(12.0, |o| o.slenderness);
    // p of a block of size R (Eq. 13, α = 4/3).
    let p_of = |size: f64| (gravity / (4.0 / 3.0 * size)).sqrt();
    let pmax = r
        .records
        .iter()
        .flat_map(|o| o.levels.iter().filter_map(|l| l.p))
        .fold(1.0, f64::max)
        * 1.05;
    let fmax = r
        .records
        .iter()
        .flat_map(|o| o.levels.iter().filter_map(|l| l.f))
        .fold(1.0, f64::max)
        * 1.05;
    // The region of interest: up to three times the largest f (p) of the lowest fractile's
    // curve; the records' far-out points (small blocks at high levels) would squeeze it.
    let cap = |of: fn(&rocking::spectra::report::LevelReport) -> Option<f64>| {
        r.characteristic
            .iter()
            .flat_map(|c| c.oas.levels.iter().filter_map(of))
            .fold(0.0, f64::max)
            * 3.0
    };
    let (pcap, fcap) = (cap(|l| l.p), cap(|l| l.f));
    let pmax = if pcap > 0.0 { pmax.min(pcap) } else { pmax };
    let fmax = if fcap > 0.0 { fmax.min(fcap) } else { fmax };
    let sizes: Vec<f64> = first.map_or(Vec::new(), |o| o.sizes.clone());
    let (rmin, rmax) = sizes.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &s| {
        (lo.min(s), hi.max(s))
    });

    let mut oas = records(r, by_p);
    let mut transformed = records(r, by_f);
    let mut size = records(r, by_size);
    for (k, c) in r.characteristic.iter().enumerate() {
        let name = format!("characteristic OAS, fractile {}", c.fractile);
        let curve = |points: Vec<(f64, f64)>| Series {
            name: name.clone(),
            points,
            style: Style::Line,
            color: color(k),
        };
        oas.push(curve(
            (0..c.oas.levels.len())
                .filter_map(|i| by_p(&c.oas, i))
                .collect(),
        ));
        transformed.push(curve(
            (0..c.oas.levels.len())
                .filter_map(|i| by_f(&c.oas, i))
                .collect(),
        ));
        size.push(curve(
            (0..c.oas.levels.len())
                .filter_map(|i| by_size(&c.oas, i))
                .collect(),
        ));
        let Some(t1) = c.design_t1 else { continue };
        let eq21 = |p: f64| rocking::design::simplified_oas(p, t1, i_cr);
        let name = format!("Eq. 21, design t1 = {t1:.3} s");
        let dashed = |points: Vec<(f64, f64)>| Series {
            name: name.clone(),
            points,
            style: Style::Dashed,
            color: color(k),
        };
        oas.push(dashed(
            (1..=400)
                .map(|j| pmax * j as f64 / 400.0)
                .map(|p| (p, eq21(p)))
                .collect(),
        ));
        size.push(dashed(
            (0..=400)
                .map(|j| rmin * (rmax / rmin).powf(j as f64 / 400.0))
                .map(|s| (s, eq21(p_of(s))))
                .collect(),
        ));
        transformed.push(Series {
            name: format!(
                "f_min = {:.2} 1/s (Eq. 20), design t1 = {t1:.3} s",
                i_cr / t1
            ),
            points: vec![(i_cr / t1, 1.0), (i_cr / t1, lmax)],
            style: Style::Dashed,
            color: color(k),
        });
    }

    let mut hulls: Vec<Series> = r
        .hulls
        .iter()
        .enumerate()
        .map(|(k, h)| Series {
            name: if k == 0 {
                format!("convex hulls of the {} records", r.hulls.len())
            } else {
                String::new()
            },
            points: h
                .vertices
                .iter()
                .map(|v| (v.f_normalised, v.level))
                .collect(),
            style: Style::Line,
            color: GREY,
        })
        .collect();
    let levels: Vec<f64> = first.map_or(Vec::new(), |o| {
        o.levels.iter().map(|l| l.level.level).collect()
    });
    let rebuilt: Vec<TransformedHull> = r
        .hulls
        .iter()
        .filter_map(|h| {
            TransformedHull::of_points(
                &h.vertices
                    .iter()
                    .map(|v| (v.level, v.f))
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    for (k, (q, name)) in [(0.5, "median"), (0.16, "16 % fractile")]
        .into_iter()
        .enumerate()
    {
        let points: Vec<(f64, f64)> = levels
            .iter()
            .filter_map(|&l| {
                let v: Vec<f64> = rebuilt
                    .iter()
                    .filter_map(|h| Some(h.at(l)? / h.f_min))
                    .collect();
                Some((statistics::fractile(&v, q)?, l))
            })
            .collect();
        hulls.push(Series {
            name: format!("{name} of the hulls"),
            points,
            style: Style::Line,
            color: color(k),
        });
    }
    hulls.push(Series {
        name: "Eq. 21: f = f_min (vertical line)".into(),
        points: vec![(1.0, 1.0), (1.0, lmax)],
        style: Style::Dashed,
        color: COLORS[7],
    });
    let hull_max = r
        .hulls
        .iter()
        .flat_map(|h| h.vertices.iter().map(|v| v.f_normalised))
        .fold(2.0, f64::max)
        .min(8.0);

    let chart = |title, x_label, x_scale, x_range, series| {
        level_chart(title, x_label, x_scale, Some(x_range), lmax, series)
    };
    let of = format!("{}, H/B = {slenderness}", r.name);
    vec![
        (
            "oas",
            chart(
                format!("OAS of the records and the characteristic OAS (Fig. 44, 47a), {of}"),
                "p [1/s]",
                Scale::Linear,
                (0.0, pmax),
                oas,
            ),
        ),
        (
            "transformed",
            chart(
                format!("Transformed OAS and f_min of the characteristic OAS (Fig. 47b), {of}"),
                "f = p a_p / a_p,min [1/s]",
                Scale::Linear,
                (0.0, fmax),
                transformed,
            ),
        ),
        (
            "hulls",
            chart(
                format!("Convex hulls of the transformed OAS normalised by f_min (Fig. 49), {of}"),
                "f / f_min",
                Scale::Linear,
                (0.0, hull_max),
                hulls,
            ),
        ),
        (
            "size",
            chart(
                format!("Design curves against the block size, {of}"),
                "size R [m] (half diagonal)",
                Scale::Log,
                (rmin, rmax),
                size,
            ),
        ),
    ]
}
