//! An arch design rule (issue 15, item 5): the suite procedure of thesis 5.3.1 on arch OAS and
//! candidate rules for the `t₁` of an arch, scored on a set of records.
//!
//! *The suite procedure.* The characteristic arch OAS at fractile `q` is, at each level
//! `a_p/(λ g)`, the `q`-fractile over the records of the largest radius that collapses
//! ([`suite::characteristic_levels`], the columns' procedure on the same slices); its transformed
//! form uses the onset mechanism's `p` (`docs/arch-spectra.md`, "Which p"), and its `f_min` gives
//! the arch suite's design `t₁ = 1/f_min` (Eq. 20 with `i_cr ≈ 1`, the arch analogue of the
//! suite's design `t₁`).
//!
//! *A rule* gives each record a `t₁`; the rule (Eq. 21/31 with `a_p,min → λ g` and the
//! mechanism's `p`: a level `≥ max(1, 1/(p t₁))` collapses) is conservative on a record iff no
//! boundary point of its arch OAS lies below the line ([`ArchOas::check`]), i.e. iff the rule's
//! `t₁` is at least the arch's own `t₁ = 1/f_min`. [`score_t1`] counts the records and boundary
//! points a rule leaves unsafe and the ratio rule `t₁` / arch `t₁` (≥ 1: conservative).

use super::suite::{characteristic_levels, same_levels, valid_fractile, Tally};
use super::{invalid, statistics, ArchOas, ArchRunCounts, SpectraError};

/// The characteristic arch OAS of `spectra` at fractile `q` (`0 < q ≤ 1`), named `name`. Every
/// spectrum must be on the first one's grid (radii, levels, shape, onset, gravity). It has no
/// runs of its own.
pub fn characteristic_arch_oas(
    spectra: &[ArchOas],
    q: f64,
    name: &str,
) -> Result<ArchOas, SpectraError> {
    valid_fractile(q)?;
    let first = spectra
        .first()
        .ok_or_else(|| invalid("spectra", "an arch suite needs at least one record"))?;
    for o in &spectra[1..] {
        let differs = if o.sizes != first.sizes {
            Some("radii")
        } else if !same_levels(&o.levels, &first.levels) {
            Some("levels")
        } else if o.shape != first.shape {
            Some("shape")
        } else if o.onset.lambda != first.onset.lambda || o.onset.p_unit != first.onset.p_unit {
            Some("onset (λ, p)")
        } else if o.gravity != first.gravity {
            Some("gravity")
        } else {
            None
        };
        if let Some(field) = differs {
            return Err(invalid(
                "spectra",
                format!(
                    "`{}` has other {field} than `{}`: an arch suite needs one grid and one arch",
                    o.record, first.record
                ),
            ));
        }
    }
    let per_record: Vec<&[super::OasLevel]> = spectra.iter().map(|o| o.levels.as_slice()).collect();
    Ok(ArchOas {
        record: name.to_string(),
        levels: characteristic_levels(&first.sizes, &per_record, q),
        runs: ArchRunCounts::default(),
        ..first.clone()
    })
}

/// A rule's `t₁` checked against the arch OAS of a set of records.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RuleScore {
    /// Records of the set.
    pub records: usize,
    /// Records for which the rule gives no `t₁` (a missing single-block `t₁` or `t_p`).
    pub unscored: usize,
    /// Boundary points checked (scored records × levels with a collapsing radius).
    pub checked: usize,
    /// Boundary points (records) the rule predicts safe although they collapse.
    pub unsafe_points: Tally,
    /// Rule `t₁` / arch `t₁` over the scored records that collapse somewhere (≥ 1:
    /// conservative): smallest, median, largest.
    pub ratio_min: Option<f64>,
    pub ratio_median: Option<f64>,
    pub ratio_max: Option<f64>,
}

/// The score of the `t₁` given for each arch OAS (`None`: the rule gives none).
pub fn score_t1<'a>(pairs: impl IntoIterator<Item = (&'a ArchOas, Option<f64>)>) -> RuleScore {
    let mut s = RuleScore::default();
    let mut ratios = Vec::new();
    for (oas, t1) in pairs {
        s.records += 1;
        let Some(t1) = t1 else {
            s.unscored += 1;
            continue;
        };
        let c = oas.check(t1);
        s.checked += oas.boundary().len();
        s.unsafe_points.add(c.violations.len());
        if let Some(own) = c.arch_t1 {
            ratios.push(t1 / own);
        }
    }
    s.ratio_min = ratios.iter().copied().reduce(f64::min);
    s.ratio_median = statistics::median(&ratios);
    s.ratio_max = ratios.iter().copied().reduce(f64::max);
    s
}

/// One fractile of an arch suite: the characteristic arch OAS, its design `t₁` and that `t₁`
/// checked against every record.
#[derive(Clone, Debug, PartialEq)]
pub struct ArchCharacteristic {
    pub fractile: f64,
    pub oas: ArchOas,
    /// `1/f_min` of the characteristic transformed OAS (s).
    pub design_t1: Option<f64>,
    /// For comparison: the `q`-fractile of the records' own arch `t₁` (s).
    pub record_t1_fractile: Option<f64>,
    /// The design `t₁` for every record.
    pub check: RuleScore,
}

/// The suite procedure on the arch OAS `spectra` at each of `fractiles`.
pub fn arch_suite(
    spectra: &[ArchOas],
    fractiles: &[f64],
    name: &str,
) -> Result<Vec<ArchCharacteristic>, SpectraError> {
    super::suite::distinct_fractiles(fractiles)?;
    fractiles
        .iter()
        .map(|&q| {
            let oas = characteristic_arch_oas(spectra, q, &format!("{name} characteristic {q}"))?;
            let design_t1 = oas.t1();
            Ok(ArchCharacteristic {
                fractile: q,
                design_t1,
                record_t1_fractile: super::suite::record_t1_fractile(
                    spectra.iter().map(ArchOas::t1),
                    q,
                ),
                check: score_t1(spectra.iter().map(|o| (o, design_t1))),
                oas,
            })
        })
        .collect()
}

/// A record of a rule's set: its arch OAS and what a rule may read of the record.
#[derive(Clone, Debug, PartialEq)]
pub struct ArchRecord {
    pub oas: ArchOas,
    /// The record's single-block `t₁` (s), e.g. the one the arch OAS was checked against.
    pub block_t1: Option<f64>,
    /// The record's replacement sine duration `t_p` (s, Eq. 25).
    pub t_p: Option<f64>,
}

/// A rule for the `t₁` of an arch under a record.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ArchRule {
    /// One `t₁` (s) for every record (a suite's design `t₁`).
    Fixed(f64),
    /// `c` × the record's single-block `t₁`.
    BlockT1(f64),
    /// `c` × the record's replacement sine duration `t_p`.
    SineDuration(f64),
    /// The single-block rule with `p = √(g/R)` in place of the onset mechanism's `p`: the same
    /// verdicts as `t₁ = √g / p₁ ×` the record's single-block `t₁` with the mechanism's `p`
    /// (`p₁` its value at `R = 1 m`); no fitted number.
    BlockT1RootGOverR,
}

impl ArchRule {
    /// Whether the rule may be scored on an arch other than the one it was fitted on. A factor
    /// on the record's own single-block `t₁` or `t_p` may (the arch enters through the arch
    /// OAS, its `λ` and its `p`), and so may rule (d), which has no fitted number and is applied
    /// with the `p₁` of the arch it is scored on. A fixed `t₁` may not: it is the design `t₁` of
    /// one arch's suite, not a `t₁` of another arch.
    pub fn transfers_to_other_arches(&self) -> bool {
        !matches!(self, ArchRule::Fixed(_))
    }

    /// The rule's `t₁` for `r` (s).
    pub fn t1(&self, r: &ArchRecord) -> Option<f64> {
        match *self {
            ArchRule::Fixed(t) => Some(t),
            ArchRule::BlockT1(c) => r.block_t1.map(|t| c * t),
            ArchRule::SineDuration(c) => r.t_p.map(|t| c * t),
            ArchRule::BlockT1RootGOverR => r
                .block_t1
                .map(|t| t * r.oas.gravity.sqrt() / r.oas.onset.p_unit),
        }
    }

    /// The rule's score on `records`.
    pub fn score(&self, records: &[ArchRecord]) -> RuleScore {
        score_t1(records.iter().map(|r| (&r.oas, self.t1(r))))
    }
}

/// Whether `a` and `b` are OAS of the same arch: shape, onset mechanism (`λ`, `p₁`) and
/// gravity (the grid may differ).
pub fn same_arch(a: &ArchOas, b: &ArchOas) -> bool {
    a.shape == b.shape
        && a.onset.lambda == b.onset.lambda
        && a.onset.p_unit == b.onset.p_unit
        && a.gravity == b.gravity
}

/// The `q`-fractile (`q = 1`: the largest) over `records` of arch `t₁` / `x(record)`: the factor
/// `c` of a rule `t₁ = c · x` fitted on them (`None` when no record has both).
pub fn fit_factor(
    records: &[ArchRecord],
    x: impl Fn(&ArchRecord) -> Option<f64>,
    q: f64,
) -> Option<f64> {
    let ratios: Vec<f64> = records
        .iter()
        .filter_map(|r| Some(r.oas.t1()? / x(r)?))
        .collect();
    statistics::fractile(&ratios, q)
}

/// A candidate rule with its key and its statement in one sentence.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct NamedRule {
    pub key: String,
    pub statement: String,
    pub rule: ArchRule,
}

/// What a rule `t₁ = c · x` reads of a record: its key, the name of `x`, `x`.
type Factor = (&'static str, &'static str, fn(&ArchRecord) -> Option<f64>);
/// The rule of a factor `c`.
type RuleOf = fn(f64) -> ArchRule;

/// The candidate rules, fitted on the set `fit` (named `fit_name`), fixed before any score is
/// looked at: (0) the single-block rule; (a) the arch suite's design `t₁` at 0.84 and 0.5;
/// (b) `c ×` the single-block `t₁`, `c` the largest ratio (conservative on every record it is
/// fitted on, as the single-block `t₁` is on its own record) and its 0.84-fractile (the suite's
/// fractile); (c) the same with `t_p`; (d) `p = √(g/R)`. A rule whose fit has no data is left
/// out.
pub fn candidate_rules(fit: &[ArchRecord], fit_name: &str) -> Vec<NamedRule> {
    let mut out = vec![NamedRule {
        key: "0".into(),
        statement: "t1,arch = the record's single-block t1 (the thesis's rule transferred)".into(),
        rule: ArchRule::BlockT1(1.0),
    }];
    let spectra: Vec<ArchOas> = fit.iter().map(|r| r.oas.clone()).collect();
    for (key, q) in [("a84", 0.84), ("a50", 0.5)] {
        if let Some(t) = characteristic_arch_oas(&spectra, q, fit_name)
            .ok()
            .and_then(|c| c.t1())
        {
            out.push(NamedRule {
                key: key.into(),
                statement: format!(
                    "t1,arch = {t:.4} s for every record: the design t1 of the {fit_name} arch \
                     suite at fractile {q}"
                ),
                rule: ArchRule::Fixed(t),
            });
        }
    }
    let factors: [(Factor, RuleOf); 2] = [
        (("b", "single-block t1", |r| r.block_t1), ArchRule::BlockT1),
        (
            ("c", "replacement sine duration t_p", |r| r.t_p),
            ArchRule::SineDuration,
        ),
    ];
    for ((key, what, x), rule) in factors {
        for (suffix, q, which) in [
            ("max", 1.0, "the largest of"),
            ("84", 0.84, "the 0.84-fractile of"),
        ] {
            if let Some(c) = fit_factor(fit, x, q) {
                out.push(NamedRule {
                    key: format!("{key}{suffix}"),
                    statement: format!(
                        "t1,arch = {c:.4} × the record's {what} ({which} the ratios arch t1 / \
                         {what} over the {fit_name})"
                    ),
                    rule: rule(c),
                });
            }
        }
    }
    out.push(NamedRule {
        key: "d".into(),
        statement: "the single-block rule with p = √(g/R) for the arch (t1,arch = √g/p₁ × the \
                    record's single-block t1)"
            .into(),
        rule: ArchRule::BlockT1RootGOverR,
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::configuration::Status;
    use crate::spectra::suite::characteristic_oas;
    use crate::spectra::{linear_levels, log_sizes, ArchOnset, ArchShape, Oas, OasLevel};

    const LEVELS: usize = 4;

    /// An arch OAS on 4 levels 1.5..=3 and 10 radii 100..1 m with the given largest collapsing
    /// indices; λ = 0.16, p₁ = 2.37 (the 8-voussoir arch's, rounded).
    fn arch(name: &str, unsafe_at: [Option<usize>; LEVELS]) -> ArchOas {
        ArchOas {
            record: name.into(),
            shape: ArchShape {
                voussoirs: 8,
                ..ArchShape::default()
            },
            onset: ArchOnset {
                lambda: 0.16,
                hinges: vec![Status::Closed; 9],
                p_unit: 2.37,
            },
            sizes: log_sizes(100.0, 1.0, 10),
            levels: linear_levels(1.5, 3.0, LEVELS)
                .into_iter()
                .zip(unsafe_at)
                .map(|(level, largest_unsafe)| OasLevel {
                    level,
                    largest_unsafe,
                    simulations: 1,
                })
                .collect(),
            gravity: 9.81,
            runs: ArchRunCounts::default(),
        }
    }

    fn suite() -> Vec<ArchOas> {
        vec![
            arch("a", [None, Some(6), Some(5), Some(4)]),
            arch("b", [Some(9), Some(7), Some(6), Some(5)]),
            arch("c", [None, Some(5), Some(4), Some(3)]),
            arch("d", [Some(8), Some(8), Some(7), Some(2)]),
            arch("e", [None, None, None, None]),
        ]
    }

    #[test]
    fn the_characteristic_arch_oas_is_the_columns_procedure() {
        let spectra = suite();
        // The same indices as columns' OAS: the same characteristic levels.
        let columns: Vec<Oas> = spectra
            .iter()
            .map(|a| Oas {
                record: a.record.clone(),
                slenderness: 12.0,
                n_blocks: 1,
                n_impacts: 1,
                search: crate::spectra::SizeSearch::Scan,
                sizes: a.sizes.clone(),
                levels: a.levels.clone(),
                gravity: a.gravity,
            })
            .collect();
        for q in [0.2, 0.5, 0.84, 1.0] {
            let c = characteristic_arch_oas(&spectra, q, "x").unwrap();
            let b = characteristic_oas(&columns, q, "x").unwrap();
            assert_eq!(c.levels, b.levels, "{q}");
            assert_eq!(c.runs, ArchRunCounts::default());
            assert_eq!(c.onset, spectra[0].onset);
        }
        // Median (3rd of 5, "none" smallest): level 1.5: 0 0 0 s9 s8 -> none; level 2: 0 s8 s7
        // s6 s5 -> s7; level 2.5: 0 s7 s6 s5 s4 -> s6; level 3: 0 s5 s4 s3 s2 -> s4.
        let m = characteristic_arch_oas(&spectra, 0.5, "m").unwrap();
        let idx: Vec<Option<usize>> = m.levels.iter().map(|l| l.largest_unsafe).collect();
        assert_eq!(idx, vec![None, Some(7), Some(6), Some(4)]);
        // Its design t1 is 1/f_min of its own boundary, f = p₁/√R · level.
        let t1 = m.t1().unwrap();
        let f_min = m
            .boundary()
            .iter()
            .map(|q| 2.37 / q.size.sqrt() * q.level)
            .fold(f64::INFINITY, f64::min);
        assert!((t1 * f_min - 1.0).abs() < 1e-15);
    }

    #[test]
    fn an_arch_suite_needs_one_grid_and_one_arch() {
        let a = arch("a", [None, Some(6), Some(5), Some(4)]);
        let mut b = arch("b", [None, Some(6), Some(5), Some(4)]);
        b.onset.p_unit = 2.88;
        let e = characteristic_arch_oas(&[a.clone(), b], 0.5, "x").unwrap_err();
        assert!(e.to_string().contains("`b` has other onset"), "{e}");
        let mut c = arch("c", [None, Some(6), Some(5), Some(4)]);
        c.shape.voussoirs = 20;
        let e = characteristic_arch_oas(&[a.clone(), c], 0.5, "x").unwrap_err();
        assert!(e.to_string().contains("`c` has other shape"), "{e}");
        let mut d = arch("d", [None, Some(6), Some(5), Some(4)]);
        d.sizes[2] *= 1.001;
        let e = characteristic_arch_oas(&[a.clone(), d], 0.5, "x").unwrap_err();
        assert!(e.to_string().contains("radii"), "{e}");
        for q in [0.0, 1.5, f64::NAN] {
            let e = characteristic_arch_oas(std::slice::from_ref(&a), q, "x").unwrap_err();
            assert!(e.to_string().starts_with("fractile"), "{e}");
        }
        assert!(characteristic_arch_oas(&[], 0.5, "x").is_err());
    }

    #[test]
    fn the_suites_design_t1_and_its_check() {
        let spectra = suite();
        let s = arch_suite(&spectra, &[0.5, 1.0], "s").unwrap();
        // Fractile 1: the largest collapsing radius of every level, so its design t1 is at least
        // every record's own and leaves nothing unsafe.
        let all = &s[1];
        assert!(spectra
            .iter()
            .filter_map(ArchOas::t1)
            .all(|t| t <= all.design_t1.unwrap()));
        assert_eq!(all.check.unsafe_points, Tally::default());
        assert_eq!(all.check.records, 5);
        assert_eq!(all.check.checked, 3 + 4 + 3 + 4);
        assert!(all.check.ratio_min.unwrap() >= 1.0);
        // The median's t1 leaves some records unsafe; the count is the records' own checks.
        let m = &s[0];
        let t1 = m.design_t1.unwrap();
        let points: usize = spectra.iter().map(|o| o.check(t1).violations.len()).sum();
        assert!(points > 0);
        assert_eq!(m.check.unsafe_points.points, points);
        // Ratios: the rule's t1 over each collapsing record's own (the 4 that collapse).
        let mut r: Vec<f64> = spectra.iter().filter_map(|o| Some(t1 / o.t1()?)).collect();
        r.sort_by(f64::total_cmp);
        assert_eq!(m.check.ratio_median, Some(0.5 * (r[1] + r[2])));
        assert_eq!(
            m.check.unsafe_points.records,
            r.iter().filter(|&&x| x < 1.0).count()
        );
    }

    #[test]
    fn rules_fitted_on_a_set_and_their_scores() {
        let records: Vec<ArchRecord> = suite()
            .into_iter()
            .zip([0.2, 0.3, 0.25, 0.4, 0.5])
            .map(|(oas, t)| ArchRecord {
                oas,
                block_t1: Some(t),
                t_p: Some(1.1 * t),
            })
            .collect();
        let rules = candidate_rules(&records, "test set");
        let keys: Vec<&str> = rules.iter().map(|r| r.key.as_str()).collect();
        assert_eq!(keys, ["0", "a84", "a50", "bmax", "b84", "cmax", "c84", "d"]);
        for r in &rules {
            let s = r.rule.score(&records);
            assert_eq!(s.records, 5);
            assert_eq!(s.unscored, 0);
            if r.key.ends_with("max") {
                // The largest ratio: conservative on every record it is fitted on, and exactly
                // on the line of the most vulnerable one.
                assert_eq!(s.unsafe_points, Tally::default(), "{}", r.key);
                assert!((s.ratio_min.unwrap() - 1.0).abs() < 1e-12, "{}", r.key);
            }
        }
        // t1 = c t_p with c fitted on ratios to t_p = 1.1 t1,block: the same t1 as rule b.
        let (b, c) = (&rules[3].rule, &rules[5].rule);
        for r in &records {
            assert!((b.t1(r).unwrap() - c.t1(r).unwrap()).abs() < 1e-15);
        }
        // A record without t_p is not scored by rule c.
        let mut no_tp = records.clone();
        no_tp[0].t_p = None;
        assert_eq!(c.score(&no_tp).unscored, 1);
    }

    #[cfg(feature = "serde")]
    #[test]
    fn a_fixed_t1_is_not_scored_on_another_arch() {
        use crate::spectra::arch_report::ArchRulesReport;
        let records = |spectra: Vec<ArchOas>| -> Vec<ArchRecord> {
            spectra
                .into_iter()
                .zip([0.2, 0.3, 0.25, 0.4, 0.5])
                .map(|(oas, t)| ArchRecord {
                    oas,
                    block_t1: Some(t),
                    t_p: Some(1.1 * t),
                })
                .collect()
        };
        let fit = records(suite());
        // The same arch on other records (renamed), and a thicker arch (other λ, p₁, t/R).
        let same = records(
            suite()
                .into_iter()
                .map(|mut o| {
                    o.record += "'";
                    o
                })
                .collect(),
        );
        let thicker = records(
            suite()
                .into_iter()
                .map(|mut o| {
                    o.shape.thickness_ratio = 0.2;
                    o.onset.lambda = 0.21;
                    o.onset.p_unit = 2.6;
                    o
                })
                .collect(),
        );
        assert!(same_arch(&fit[0].oas, &same[0].oas));
        assert!(!same_arch(&fit[0].oas, &thicker[0].oas));
        let tests = vec![("same".to_string(), same), ("thicker".to_string(), thicker)];
        let r = ArchRulesReport::of("fit", &fit, &tests);
        let arches: Vec<bool> = r
            .arches
            .iter()
            .map(|a| a.as_ref().unwrap().fit_arch)
            .collect();
        assert_eq!(arches, [true, true, false]);
        assert_eq!(r.arches[2].as_ref().unwrap().onset.p_at_1m, 2.6);
        for row in &r.rules {
            let fixed = matches!(row.rule.rule, ArchRule::Fixed(_));
            assert_eq!(fixed, !row.rule.rule.transfers_to_other_arches());
            // Every rule on the fit set's arch; a fixed t1 not on the thicker one.
            assert!(row.scores[0].is_some() && row.scores[1].is_some());
            assert_eq!(row.scores[2].is_none(), fixed, "{}", row.rule.key);
            // The same arch and numbers: the same score as in sample.
            assert_eq!(row.scores[0], row.scores[1], "{}", row.rule.key);
        }
        // Rule d is applied with the scored arch's own p₁: its t1 is √g/2.6 × t1,block there.
        let d = &r
            .rules
            .iter()
            .find(|x| x.rule.key == "d")
            .unwrap()
            .rule
            .rule;
        let t1 = d.t1(&tests[1].1[0]).unwrap();
        assert!((t1 - 0.2 * 9.81_f64.sqrt() / 2.6).abs() < 1e-15);
    }

    #[test]
    fn p_root_g_over_r_is_the_block_rule_with_that_p() {
        // Rule d leaves unsafe exactly the boundary points whose f' = √(g/R) · level is below
        // 1/t1 of the record.
        let oas = arch("a", [Some(9), Some(6), Some(5), Some(4)]);
        for t in [0.05, 0.1, 0.2, 0.4] {
            let r = ArchRecord {
                oas: oas.clone(),
                block_t1: Some(t),
                t_p: None,
            };
            let t1 = ArchRule::BlockT1RootGOverR.t1(&r).unwrap();
            let expect = oas
                .boundary()
                .iter()
                .filter(|q| (9.81 / q.size).sqrt() * q.level < (1.0 / t) * (1.0 - 1e-9))
                .count();
            assert_eq!(oas.check(t1).violations.len(), expect, "{t}");
        }
    }
}
