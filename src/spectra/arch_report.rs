//! The reports of the arch spectra as data (`serde` feature): what `rocking arch oas` and
//! `rocking arch oc` print.

use serde::{Deserialize, Serialize};

use super::report::{EnvelopePointReport, LevelReport};
use super::{ArchOas, ArchOc, ArchRunCounts, ArchShape};

/// The onset of the arch family: `λ`, its mechanism and `p` at `R = 1 m`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchOnsetReport {
    pub lambda: f64,
    /// `(joint, status)` of the onset mechanism's hinges (`-1` intrados, `+1` extrados).
    pub hinges: Vec<(usize, i8)>,
    pub p_at_1m: f64,
}

impl ArchOnsetReport {
    fn of(o: &super::ArchOnset) -> ArchOnsetReport {
        ArchOnsetReport {
            lambda: o.lambda,
            hinges: o
                .hinges
                .iter()
                .enumerate()
                .filter(|(_, s)| s.is_open())
                .map(|(k, s)| (k, s.as_i8()))
                .collect(),
            p_at_1m: o.p_unit,
        }
    }
}

/// The single-block rule checked against an arch OAS.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchCheckReport {
    /// The `t₁` checked (s).
    pub t1: f64,
    /// Boundary points predicted safe (Eq. 21, `i_cr ≈ 1`) although they collapse.
    pub violations: usize,
    /// Whether the rule is conservative on this OAS.
    pub conservative: bool,
}

/// An arch OAS (`rocking arch oas`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchOasReport {
    pub record: String,
    pub shape: ArchShape,
    pub onset: ArchOnsetReport,
    pub gravity: f64,
    pub sizes: Vec<f64>,
    pub levels: Vec<LevelReport>,
    /// The arch's `t₁ = 1/f_min` (s), `f = p · a_p/(λ g)`.
    pub t1: Option<f64>,
    pub f_min: Option<f64>,
    pub level_at_f_min: Option<f64>,
    pub size_at_f_min: Option<f64>,
    pub check: Option<ArchCheckReport>,
    pub runs: ArchRunCounts,
    /// Wall time (s).
    pub seconds: f64,
}

impl ArchOasReport {
    /// The report of `o`, which took `seconds`, with the single-block rule of `t1` checked.
    pub fn of(o: &ArchOas, t1: Option<f64>, seconds: f64) -> ArchOasReport {
        let m = o.f_min();
        ArchOasReport {
            record: o.record.clone(),
            shape: o.shape,
            onset: ArchOnsetReport::of(&o.onset),
            gravity: o.gravity,
            sizes: o.sizes.clone(),
            levels: o
                .levels
                .iter()
                .map(|l| {
                    let size = l.largest_unsafe.map(|i| o.sizes[i]);
                    let p = size.map(|r| o.onset.p(r));
                    LevelReport {
                        level: *l,
                        size,
                        p,
                        f: p.map(|p| p * l.level),
                    }
                })
                .collect(),
            t1: o.t1(),
            f_min: m.map(|m| m.f),
            level_at_f_min: m.map(|m| m.level),
            size_at_f_min: m.map(|m| m.size),
            check: t1.map(|t1| {
                let c = o.check(t1);
                ArchCheckReport {
                    t1,
                    violations: c.violations.len(),
                    conservative: c.violations.is_empty(),
                }
            }),
            runs: o.runs.clone(),
            seconds,
        }
    }
}

/// One grid point of an arch OC.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchOcPointReport {
    pub t_p: f64,
    pub p_tp: f64,
    pub level: f64,
    pub collapses: bool,
}

/// An arch OC (`rocking arch oc`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchOcReport {
    pub pulse: String,
    pub shape: ArchShape,
    pub radius: f64,
    pub onset: ArchOnsetReport,
    pub p: f64,
    pub points: Vec<ArchOcPointReport>,
    pub envelope: Vec<EnvelopePointReport>,
    pub runs: ArchRunCounts,
    pub seconds: f64,
}

impl ArchOcReport {
    /// The report of `oc`, which took `seconds`.
    pub fn of(oc: &ArchOc, seconds: f64) -> ArchOcReport {
        let p = oc.p();
        let n = oc.levels.len();
        let points = oc
            .t_p
            .iter()
            .enumerate()
            .flat_map(|(i, &t_p)| {
                oc.levels
                    .iter()
                    .enumerate()
                    .map(move |(j, &level)| (i, j, t_p, level))
            })
            .map(|(i, j, t_p, level)| ArchOcPointReport {
                t_p,
                p_tp: p * t_p,
                level,
                collapses: oc.collapsed[i * n + j],
            })
            .collect();
        let envelope = oc
            .t_p
            .iter()
            .zip(oc.envelope())
            .map(|(&t, level)| EnvelopePointReport { p_tp: p * t, level })
            .collect();
        ArchOcReport {
            pulse: oc.pulse.name(),
            shape: oc.shape,
            radius: oc.radius,
            onset: ArchOnsetReport::of(&oc.onset),
            p,
            points,
            envelope,
            runs: oc.runs.clone(),
            seconds,
        }
    }
}
