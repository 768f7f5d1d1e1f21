//! The reports of the spectra as data (`serde` feature): what `rocking oas --json` and
//! `rocking t1 --json` print, what `--merge` reads back, and the dicts the Python package returns
//! — one definition for both front ends.

use serde::{Deserialize, Serialize};

use super::{Oas, OasLevel, Oc, SizeSearch};

/// One level of an OAS: the library's level and, when a size overturns, the largest unsafe one
/// with its `p` and `f = p · level`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct LevelReport {
    #[serde(flatten)]
    pub level: OasLevel,
    pub size: Option<f64>,
    pub p: Option<f64>,
    pub f: Option<f64>,
}

/// The summary of an OAS, also the body of a `t1` row (the `f_min` point flattened).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SummaryReport {
    pub record: String,
    pub t1: Option<f64>,
    pub t1_prime: Option<f64>,
    pub beta: Option<f64>,
    pub f_min: Option<f64>,
    pub level_at_f_min: Option<f64>,
    pub size_at_f_min: Option<f64>,
    pub simulations: usize,
    /// Wall time of the run [s].
    pub seconds: f64,
}

impl SummaryReport {
    /// The summary of `o`, which took `seconds`.
    pub fn of(o: &Oas, seconds: f64) -> SummaryReport {
        let s = o.summary();
        SummaryReport {
            record: o.record.clone(),
            t1: s.t1,
            t1_prime: s.fit.map(|f| f.t1_prime),
            beta: s.fit.map(|f| f.beta),
            f_min: s.f_min.map(|m| m.f),
            level_at_f_min: s.f_min.map(|m| m.level),
            size_at_f_min: s.f_min.map(|m| m.size),
            simulations: s.simulations,
            seconds,
        }
    }
}

/// How many boundary points each simplified spectrum predicts safe although they overturn.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ConservativeCounts {
    pub eq21: usize,
    pub eq21_approx: usize,
    pub eq29: usize,
    pub eq30: usize,
}

/// An OAS with its grid, its levels and its summary.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct OasReport {
    pub record: String,
    pub slenderness: f64,
    pub blocks: usize,
    pub impacts: u32,
    pub search: SizeSearch,
    pub gravity: f64,
    pub sizes: Vec<f64>,
    pub levels: Vec<LevelReport>,
    pub summary: SummaryReport,
    pub conservative: Option<ConservativeCounts>,
}

impl OasReport {
    /// The report of `o`, which took `seconds`.
    pub fn of(o: &Oas, seconds: f64) -> OasReport {
        let levels = o
            .levels
            .iter()
            .map(|l| {
                let size = l.largest_unsafe.map(|i| o.sizes[i]);
                let p = size.map(|r| o.block(r).frequency_parameter(o.gravity));
                LevelReport {
                    level: *l,
                    size,
                    p,
                    f: p.map(|p| p * l.level),
                }
            })
            .collect();
        let s = o.summary();
        OasReport {
            record: o.record.clone(),
            slenderness: o.slenderness,
            blocks: o.n_blocks,
            impacts: o.n_impacts,
            search: o.search,
            gravity: o.gravity,
            sizes: o.sizes.clone(),
            levels,
            summary: SummaryReport::of(o, seconds),
            conservative: s.t1.map(|t1| {
                let c = o.check(t1, s.fit);
                ConservativeCounts {
                    eq21: c.eq21.len(),
                    eq21_approx: c.eq21_approx.len(),
                    eq29: c.eq29.len(),
                    eq30: c.eq30.len(),
                }
            }),
        }
    }

    /// Rebuilds an OAS from reports of level shards: their levels, in level order, on the first
    /// one's grid and settings (`None` when there is nothing to merge).
    pub fn merge(parts: Vec<OasReport>) -> Option<Oas> {
        let mut levels: Vec<OasLevel> = parts
            .iter()
            .flat_map(|p| p.levels.iter().map(|l| l.level))
            .collect();
        levels.sort_by(|a, b| a.level.total_cmp(&b.level));
        let first = parts.into_iter().next()?;
        Some(Oas {
            record: first.record,
            slenderness: first.slenderness,
            n_blocks: first.blocks,
            n_impacts: first.impacts,
            search: first.search,
            sizes: first.sizes,
            levels,
            gravity: first.gravity,
        })
    }
}

/// One record's row of `t1`: the summary of its OAS, the settings, and the replacement sine
/// duration `t_p` of the record (Eq. 25).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct T1Row {
    #[serde(flatten)]
    pub summary: SummaryReport,
    /// The record's file (`None` for a record given as data).
    pub file: Option<String>,
    pub slenderness: f64,
    pub blocks: usize,
    pub dt_factor: f64,
    pub search: SizeSearch,
    /// Replacement sine duration `t_p = I_max / (F a_max)` of the record [s] (Eq. 25).
    #[serde(default)]
    pub t_p: Option<f64>,
    /// The t₁ procedure, when not the default (`converged`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub procedure: Option<String>,
    /// With a band (`rocking t1 --band`): `[min, max]` of t₁ over the perturbations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t1_range: Option<[f64; 2]>,
    /// With a band: `i_cr / f_min` of the envelope of the perturbed spectra.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t1_conservative: Option<f64>,
    /// With a band: t₁ of each perturbation, by name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub band: Option<std::collections::BTreeMap<String, Option<f64>>>,
}

impl T1Row {
    /// Writes the band's figures into the row.
    pub fn set_band(&mut self, b: &super::T1Band) {
        self.t1_range = b.t1_range;
        self.t1_conservative = b.t1_conservative;
        self.band = Some(
            b.members
                .iter()
                .map(|(p, t)| (p.name().to_string(), *t))
                .collect(),
        );
    }
}

/// One grid point of an overturning curve.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct OcPointReport {
    pub t_p: f64,
    pub a_p: f64,
    pub p_tp: f64,
    pub level: f64,
    #[serde(rename = "unsafe")]
    pub overturns: bool,
}

/// One point of the envelope: the lowest unsafe level at `p t_p` (`None`: none).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct EnvelopePointReport {
    pub p_tp: f64,
    pub level: Option<f64>,
}

/// An overturning curve (`rocking oc --json`): every grid point, normalised by the equivalent
/// monolith's `p` and `a_p,min`, and the envelope.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct OcReport {
    pub shape: String,
    pub blocks: usize,
    pub p: f64,
    pub a_p_min: f64,
    pub points: Vec<OcPointReport>,
    pub envelope: Vec<EnvelopePointReport>,
}

impl OcReport {
    /// The report of `oc` computed at the accelerations `a_p` for a column of `blocks` blocks
    /// whose equivalent monolith has `p` and `a_p_min`.
    pub fn of(oc: &Oc, a_p: &[f64], blocks: usize, p: f64, a_p_min: f64) -> OcReport {
        let points = oc
            .normalised()
            .iter()
            .zip(
                oc.t_p
                    .iter()
                    .flat_map(|t| a_p.iter().map(move |ap| (*t, *ap))),
            )
            .map(|(&(p_tp, level, overturns), (t_p, a_p))| OcPointReport {
                t_p,
                a_p,
                p_tp,
                level,
                overturns,
            })
            .collect();
        let envelope = oc
            .normalised_envelope()
            .iter()
            .map(|&(p_tp, level)| EnvelopePointReport { p_tp, level })
            .collect();
        OcReport {
            shape: oc.shape.name(),
            blocks,
            p,
            a_p_min,
            points,
            envelope,
        }
    }
}
