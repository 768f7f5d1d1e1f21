//! The reports of the arch spectra as data (`serde` feature): what `rocking arch oas` and
//! `rocking arch oc` print.

use serde::{Deserialize, Serialize};

use super::report::{EnvelopePointReport, LevelReport};
use super::{
    arch_suite, candidate_rules, invalid, same_arch, score_t1, ArchOas, ArchOc, ArchOnset,
    ArchRecord, ArchRunCounts, ArchShape, NamedRule, RuleScore, SpectraError,
};
use crate::model::configuration::Status;

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

impl ArchOasReport {
    /// The arch OAS of the report (what `rocking arch suite` reads back): the onset's hinges are
    /// rebuilt from their list, every index and status is checked.
    pub fn to_oas(&self) -> Result<ArchOas, SpectraError> {
        let n_joints = self.shape.voussoirs + 1;
        let mut hinges = vec![Status::Closed; n_joints];
        for &(joint, status) in &self.onset.hinges {
            let s = Status::from_i8(status).filter(|s| s.is_open());
            match (hinges.get_mut(joint), s) {
                (Some(h), Some(s)) => *h = s,
                _ => {
                    return Err(invalid(
                        "onset.hinges",
                        format!(
                            "`{}`: hinge ({joint}, {status}) is not an open joint of an arch of \
                             {} voussoirs",
                            self.record, self.shape.voussoirs
                        ),
                    ))
                }
            }
        }
        if let Some(l) = self.levels.iter().find(|l| {
            l.level
                .largest_unsafe
                .is_some_and(|i| i >= self.sizes.len())
        }) {
            return Err(invalid(
                "levels",
                format!(
                    "`{}`: level {} has a radius index outside the {} radii",
                    self.record,
                    l.level.level,
                    self.sizes.len()
                ),
            ));
        }
        Ok(ArchOas {
            record: self.record.clone(),
            shape: self.shape,
            onset: ArchOnset {
                lambda: self.onset.lambda,
                hinges,
                p_unit: self.onset.p_at_1m,
            },
            sizes: self.sizes.clone(),
            levels: self.levels.iter().map(|l| l.level).collect(),
            gravity: self.gravity,
            runs: self.runs.clone(),
        })
    }
}

/// One record of an arch suite: its arch `t₁` and the single-block `t₁` it was checked against.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchSuiteRecordRow {
    pub record: String,
    /// The arch's own `t₁ = 1/f_min` (s).
    pub t1: Option<f64>,
    pub f_min: Option<f64>,
    pub level_at_f_min: Option<f64>,
    pub size_at_f_min: Option<f64>,
    /// The record's single-block `t₁` (s), when known.
    pub block_t1: Option<f64>,
}

/// One fractile of an arch suite (`rocking arch suite`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchCharacteristicReport {
    pub fractile: f64,
    /// The arch suite's design `t₁ = 1/f_min` of the characteristic transformed OAS (s).
    pub design_t1: Option<f64>,
    pub f_min: Option<f64>,
    pub level_at_f_min: Option<f64>,
    pub size_at_f_min: Option<f64>,
    /// The `q`-fractile of the records' own arch `t₁` (s).
    pub record_t1_fractile: Option<f64>,
    /// The characteristic arch OAS.
    pub oas: ArchOasReport,
    /// The design `t₁` checked against every record's arch OAS.
    pub check: RuleScore,
}

/// The suite procedure on arch OAS (`rocking arch suite --json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchSuiteReport {
    pub name: String,
    pub shape: ArchShape,
    pub onset: ArchOnsetReport,
    pub records: Vec<ArchSuiteRecordRow>,
    pub characteristic: Vec<ArchCharacteristicReport>,
    /// Each record's single-block `t₁` checked against its arch OAS (records without one are
    /// unscored).
    pub block_rule: RuleScore,
}

impl ArchSuiteReport {
    /// The report of the suite `name` of `records` at `fractiles`; records sorted by name.
    pub fn of(
        name: &str,
        records: &[ArchRecord],
        fractiles: &[f64],
    ) -> Result<ArchSuiteReport, SpectraError> {
        if records.is_empty() {
            return Err(invalid(
                "records",
                "an arch suite needs at least one record",
            ));
        }
        let mut records: Vec<&ArchRecord> = records.iter().collect();
        records.sort_by(|a, b| a.oas.record.cmp(&b.oas.record));
        let spectra: Vec<ArchOas> = records.iter().map(|r| r.oas.clone()).collect();
        let characteristic = arch_suite(&spectra, fractiles, name)?
            .into_iter()
            .map(|c| {
                let m = c.oas.f_min();
                ArchCharacteristicReport {
                    fractile: c.fractile,
                    design_t1: c.design_t1,
                    f_min: m.map(|m| m.f),
                    level_at_f_min: m.map(|m| m.level),
                    size_at_f_min: m.map(|m| m.size),
                    record_t1_fractile: c.record_t1_fractile,
                    oas: ArchOasReport::of(&c.oas, None, 0.0),
                    check: c.check,
                }
            })
            .collect();
        let first = &records[0].oas;
        Ok(ArchSuiteReport {
            name: name.to_string(),
            shape: first.shape,
            onset: ArchOnsetReport::of(&first.onset),
            records: records
                .iter()
                .map(|r| {
                    let m = r.oas.f_min();
                    ArchSuiteRecordRow {
                        record: r.oas.record.clone(),
                        t1: r.oas.t1(),
                        f_min: m.map(|m| m.f),
                        level_at_f_min: m.map(|m| m.level),
                        size_at_f_min: m.map(|m| m.size),
                        block_t1: r.block_t1,
                    }
                })
                .collect(),
            characteristic,
            block_rule: score_t1(records.iter().map(|r| (&r.oas, r.block_t1))),
        })
    }
}

/// One candidate rule and its score on each set.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchRuleRow {
    #[serde(flatten)]
    pub rule: NamedRule,
    /// In the order of [`ArchRulesReport::sets`]; `None`: not scored, the rule does not transfer
    /// to the set's arch ([`super::ArchRule::transfers_to_other_arches`]: a fixed `t₁` on a set of another
    /// arch than the fit set's).
    pub scores: Vec<Option<RuleScore>>,
}

/// The arch of a set of [`ArchRulesReport`] (its first record's).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchSetArch {
    pub shape: ArchShape,
    pub onset: ArchOnsetReport,
    /// Whether it is the fit set's arch.
    pub fit_arch: bool,
}

/// Candidate arch design rules fitted on one set and scored on it and on others
/// (`rocking arch rules --json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ArchRulesReport {
    /// The set the rules are fitted on (the first of `sets`).
    pub fit: String,
    /// The sets scored: the fit set (in sample), then the test sets (out of sample).
    pub sets: Vec<String>,
    /// The arch of each set (`None`: an empty set), in the order of `sets`.
    pub arches: Vec<Option<ArchSetArch>>,
    pub rules: Vec<ArchRuleRow>,
}

impl ArchRulesReport {
    /// The rules fitted on `fit` (named `fit_name`), scored on `fit` and on each of `tests`
    /// (each set of one arch, its first record's). A rule that does not transfer to another
    /// arch is not scored on a set whose arch differs from the fit set's.
    pub fn of(fit_name: &str, fit: &[ArchRecord], tests: &[(String, Vec<ArchRecord>)]) -> Self {
        let sets: Vec<(&str, &[ArchRecord])> = std::iter::once((fit_name, fit))
            .chain(tests.iter().map(|(n, r)| (n.as_str(), r.as_slice())))
            .collect();
        let fit_arch = |set: &[ArchRecord]| match (fit.first(), set.first()) {
            (Some(a), Some(b)) => same_arch(&a.oas, &b.oas),
            _ => true,
        };
        ArchRulesReport {
            fit: fit_name.to_string(),
            sets: sets.iter().map(|s| s.0.to_string()).collect(),
            arches: sets
                .iter()
                .map(|s| {
                    s.1.first().map(|r| ArchSetArch {
                        shape: r.oas.shape,
                        onset: ArchOnsetReport::of(&r.oas.onset),
                        fit_arch: fit_arch(s.1),
                    })
                })
                .collect(),
            rules: candidate_rules(fit, fit_name)
                .into_iter()
                .map(|rule| ArchRuleRow {
                    scores: sets
                        .iter()
                        .map(|s| {
                            (fit_arch(s.1) || rule.rule.transfers_to_other_arches())
                                .then(|| rule.rule.score(s.1))
                        })
                        .collect(),
                    rule,
                })
                .collect(),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectra::{linear_levels, log_sizes, OasLevel};

    #[test]
    fn an_arch_oas_reads_back_from_its_report() {
        let n = 8;
        let mut hinges = vec![Status::Closed; n + 1];
        hinges[1] = Status::from_i8(-1).unwrap();
        hinges[4] = Status::from_i8(1).unwrap();
        let o = ArchOas {
            record: "r".into(),
            shape: ArchShape {
                voussoirs: n,
                ..ArchShape::default()
            },
            onset: ArchOnset {
                lambda: 0.159,
                hinges,
                p_unit: 2.37,
            },
            sizes: log_sizes(100.0, 1.0, 5),
            levels: linear_levels(1.5, 3.0, 3)
                .into_iter()
                .zip([None, Some(4), Some(2)])
                .map(|(level, largest_unsafe)| OasLevel {
                    level,
                    largest_unsafe,
                    simulations: 3,
                })
                .collect(),
            gravity: 9.81,
            runs: ArchRunCounts::default(),
        };
        let report = ArchOasReport::of(&o, Some(0.2), 1.0);
        let text = serde_json::to_string(&report).unwrap();
        let back: ArchOasReport = serde_json::from_str(&text).unwrap();
        assert_eq!(back.to_oas().unwrap(), o);
        let mut bad = back.clone();
        bad.levels[1].level.largest_unsafe = Some(5);
        let e = bad.to_oas().unwrap_err().to_string();
        assert!(e.contains("radius index outside the 5 radii"), "{e}");
        let mut bad = back;
        bad.onset.hinges.push((9, 0));
        let e = bad.to_oas().unwrap_err().to_string();
        assert!(e.starts_with("onset.hinges: `r`: hinge (9, 0)"), "{e}");
    }
}
