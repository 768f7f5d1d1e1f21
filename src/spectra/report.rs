//! The reports of the spectra as data (`serde` feature): what `rocking oas --json` and
//! `rocking t1 --json` print, what `--merge` reads back, and the dicts the Python package returns
//! — one definition for both front ends.

use serde::{Deserialize, Serialize};

use super::suite::{characteristic_oas, violations_in_stated_ranges, Violations};
use super::{Oas, OasLevel, Oc, SizeSearch, SpectraError, TransformedHull};

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
    /// With `rocking oas --band` or `--converge-step`: the band and the steps of `t_1` (the
    /// spectrum is the finest step's).
    #[serde(flatten)]
    pub accuracy: T1Accuracy,
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
            accuracy: T1Accuracy::default(),
        }
    }

    /// The report of the spectrum of `result` ([`super::t1_of`]) with its band and steps, the
    /// steps' dt factors relative to the record's step rule scaled by `first_factor`.
    pub fn of_t1(result: &super::T1Result, seconds: f64, first_factor: f64) -> OasReport {
        OasReport {
            accuracy: T1Accuracy::of(result, first_factor),
            ..OasReport::of(&result.oas, seconds)
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

/// One fractile of a record suite (`rocking suite`): the characteristic OAS, its transformed
/// form's `f_min` and the suite's design `t_1`, and the simplified spectra with these parameters
/// checked against every record.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CharacteristicReport {
    /// `q`.
    pub fractile: f64,
    /// The suite's design `t_1 = i_cr / f_min` of the characteristic transformed OAS [s].
    pub design_t1: Option<f64>,
    /// `f_min` of the characteristic transformed OAS [1/s].
    pub f_min: Option<f64>,
    /// For comparison: the `q`-fractile of the records' own `t_1` (thesis 5.3.4 designs with
    /// the largest of the far-field set) [s].
    pub record_t1_fractile: Option<f64>,
    /// The characteristic OAS (its summary carries `t_1`, `t_1'`, `β` of Eq. 20, 28).
    pub oas: OasReport,
    /// Eq. 21, 29, 30 with the design `t_1` and the characteristic OAS's `t_1'`, `β`: boundary
    /// points of the records predicted safe although they overturn, below 4, 6, 12 and at every
    /// level.
    pub violations: Vec<Violations>,
}

/// One vertex of a normalised convex hull.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct HullVertex {
    pub level: f64,
    /// `f` [1/s].
    pub f: f64,
    /// `f / f_min`.
    pub f_normalised: f64,
}

/// The convex hull of one record's transformed OAS (Fig. 48b, 49).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct HullReport {
    pub record: String,
    pub f_min: f64,
    pub vertices: Vec<HullVertex>,
}

impl HullReport {
    /// The hull of `o` (`None` when nothing overturns).
    pub fn of(o: &Oas) -> Option<HullReport> {
        let h = TransformedHull::of(o)?;
        Some(HullReport {
            record: o.record.clone(),
            f_min: h.f_min,
            vertices: h
                .vertices
                .iter()
                .map(|&(level, f)| HullVertex {
                    level,
                    f,
                    f_normalised: f / h.f_min,
                })
                .collect(),
        })
    }
}

/// The design curves of a record suite (`rocking suite --json`): every record's OAS, the
/// characteristic OAS at each fractile, the normalised convex hulls, and the simplified spectra
/// checked against the records with each record's own parameters (the thesis's claim, 5.3.5).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SuiteReport {
    pub name: String,
    /// Every record's OAS, by record name (what `--merge` reads back).
    pub records: Vec<OasReport>,
    pub characteristic: Vec<CharacteristicReport>,
    pub hulls: Vec<HullReport>,
    /// Eq. 21, 29, 30 with each record's own `t_1`, `t_1'`, `β`, below 4, 6, 12 and at every
    /// level.
    pub own_parameters: Vec<Violations>,
    /// Sum of the records' wall times [s].
    pub seconds: f64,
}

impl SuiteReport {
    /// The report of the suite `name` of the spectra `records` (each with its wall time), at the
    /// fractiles `fractiles`; records are sorted by name.
    pub fn of(
        name: &str,
        records: &[(Oas, f64)],
        fractiles: &[f64],
    ) -> Result<SuiteReport, SpectraError> {
        super::suite::distinct_fractiles(fractiles)?;
        let mut records: Vec<&(Oas, f64)> = records.iter().collect();
        records.sort_by(|a, b| a.0.record.cmp(&b.0.record));
        let spectra: Vec<Oas> = records.iter().map(|r| r.0.clone()).collect();

        let characteristic = fractiles
            .iter()
            .map(|&q| {
                let c = characteristic_oas(&spectra, q, &format!("{name} characteristic {q}"))?;
                let s = c.summary();
                let design = s.t1.map(|t1| (t1, s.fit));
                Ok(CharacteristicReport {
                    fractile: q,
                    design_t1: s.t1,
                    f_min: s.f_min.map(|m| m.f),
                    record_t1_fractile: super::suite::record_t1_fractile(
                        spectra.iter().map(Oas::t1),
                        q,
                    ),
                    oas: OasReport::of(&c, 0.0),
                    violations: violations_in_stated_ranges(&spectra, |_| design),
                })
            })
            .collect::<Result<Vec<_>, SpectraError>>()?;
        Ok(SuiteReport {
            name: name.to_string(),
            records: records.iter().map(|r| OasReport::of(&r.0, r.1)).collect(),
            characteristic,
            hulls: spectra.iter().filter_map(HullReport::of).collect(),
            own_parameters: violations_in_stated_ranges(&spectra, |o| {
                o.t1().map(|t1| (t1, o.fit()))
            }),
            seconds: records.iter().map(|r| r.1).sum(),
        })
    }

    /// The records' spectra with their wall times, as read back from the report.
    pub fn spectra(&self) -> Vec<(Oas, f64)> {
        self.records
            .iter()
            .filter_map(|r| Some((OasReport::merge(vec![r.clone()])?, r.summary.seconds)))
            .collect()
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
    /// The band and the steps of `t_1`, when computed.
    #[serde(flatten)]
    pub accuracy: T1Accuracy,
}

impl T1Row {
    /// The row of `result` ([`super::t1_of`]) computed under `options` for a record whose step
    /// rule is scaled by `dt_factor` (the row's `dt_factor` is the finest step's), with the
    /// steps and the band when the method gave them.
    pub fn of(
        result: &super::T1Result,
        seconds: f64,
        file: Option<String>,
        options: &super::OasOptions,
        dt_factor: f64,
        t_p: Option<f64>,
        procedure: Option<String>,
    ) -> T1Row {
        T1Row {
            summary: SummaryReport::of(&result.oas, seconds),
            file,
            slenderness: options.slenderness,
            blocks: options.n_blocks,
            dt_factor: dt_factor * result.factor(),
            search: options.search,
            t_p,
            procedure,
            accuracy: T1Accuracy::of(result, dt_factor),
        }
    }

    /// The dt factor of the row's first step: its own without convergence in the step.
    pub fn first_dt_factor(&self) -> f64 {
        self.accuracy
            .t1_steps
            .as_ref()
            .and_then(|s| s.first())
            .map_or(self.dt_factor, |s| s.0)
    }
}

/// How far a `t_1` can be trusted (issue 14): its band and the steps of its convergence in the
/// time step, each when computed (`rocking t1` and `rocking oas` with `--band`, `--converge-step`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct T1Accuracy {
    /// With a band (`--band`): `[min, max]` of t₁ over the perturbations.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t1_range: Option<[f64; 2]>,
    /// With a band: `i_cr / f_min` of the envelope of the perturbed spectra.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t1_conservative: Option<f64>,
    /// With a band: t₁ of each perturbation, by name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub band: Option<std::collections::BTreeMap<String, Option<f64>>>,
    /// Converged in the step (`--converge-step`): `[dt factor, t₁]` of each step
    /// tried, in order (the row's spectrum, and its `dt_factor`, are the last step's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t1_steps: Option<Vec<(f64, Option<f64>)>>,
    /// Converged in the step: whether the last two steps' t₁ agree within the tolerance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step_converged: Option<bool>,
}

impl T1Accuracy {
    /// The band and the steps of `result` ([`super::t1_of`]), the steps' dt factors relative to
    /// the record's step rule scaled by `first_factor`.
    pub fn of(result: &super::T1Result, first_factor: f64) -> T1Accuracy {
        let band = result.band.as_ref();
        T1Accuracy {
            t1_range: band.and_then(|b| b.t1_range),
            t1_conservative: band.and_then(|b| b.t1_conservative),
            band: band.map(|b| {
                b.members
                    .iter()
                    .map(|(p, t)| (p.name().to_string(), *t))
                    .collect()
            }),
            t1_steps: result.steps.as_ref().map(|c| {
                c.steps
                    .iter()
                    .map(|(f, t)| (first_factor * f, *t))
                    .collect()
            }),
            step_converged: result.steps.as_ref().map(|c| c.converged),
        }
    }
}

/// One record's row of `rocking tp --json` (and the Python package's `tp`): the replacement sine
/// of Eq. 25 (`file` is `None` for a record given as data).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TpRow {
    pub record: String,
    pub file: Option<String>,
    /// Peak absolute ground acceleration [m/s²].
    pub a_max: f64,
    /// Largest single-lobe impulse ∫|a| dt between two zero crossings [m/s].
    pub i_max: f64,
    /// Start and end of that lobe [s].
    pub lobe_start: f64,
    pub lobe_end: f64,
    /// The fullness used, 2/π ([`super::SINE_FULLNESS`]).
    pub fullness: f64,
    /// `t_p = I_max / (F a_max)` [s].
    pub t_p: f64,
}

impl TpRow {
    /// The row of `record` (named `name`, read from `file`) with replacement sine `s`.
    pub fn of(name: &str, file: Option<String>, s: &super::ReplacementSine) -> TpRow {
        TpRow {
            record: name.to_string(),
            file,
            a_max: s.a_max,
            i_max: s.i_max,
            lobe_start: s.lobe_start,
            lobe_end: s.lobe_end,
            fullness: super::SINE_FULLNESS,
            t_p: s.t_p,
        }
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
