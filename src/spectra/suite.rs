//! Site design curves from a record suite (thesis 5.3.1–5.3.2, Fig. 44, 47): the characteristic
//! OAS at a fractile, its transformed form and the suite's design `t_1`, and the check of the
//! simplified spectra (Eq. 21, 29, 30) against every record's OAS in the level ranges the thesis
//! states (5.3.5: Eq. 21 for `a_p < 4–6 a_p,min`, Eq. 30 for `a_p / a_p,min < 12`).
//!
//! The characteristic OAS at fractile `q` is, at each level, the `q`-fractile over the records of
//! the largest unsafe size ([`statistics::fractile`]: one of the records' sizes, so a size of the
//! grid); a record with no unsafe size at a level counts as the smallest value. At most a share
//! `1 − q` of the records overturn a larger block at that level (thesis Fig. 44b, "for a given
//! probability of exceedance"). It is an [`Oas`] on the records' grid, so its transformed form,
//! `f_min`, `t_1` (the suite's *design* `t_1`, Eq. 20) and the Eq. 28 fit are those of any OAS.

use super::{invalid, statistics, InclinedFit, Oas, OasLevel, SpectraError};

/// The characteristic OAS of `spectra` at fractile `q` (`0 < q ≤ 1`), named `name`. Every
/// spectrum must be on the first one's grid (levels, sizes, slenderness, blocks, impacts, search,
/// gravity). Its levels count no simulations of their own (`simulations = 0`).
pub fn characteristic_oas(spectra: &[Oas], q: f64, name: &str) -> Result<Oas, SpectraError> {
    valid_fractile(q)?;
    let first = spectra
        .first()
        .ok_or_else(|| invalid("spectra", "a suite needs at least one record"))?;
    same_grid(spectra)?;
    let per_record: Vec<&[OasLevel]> = spectra.iter().map(|o| o.levels.as_slice()).collect();
    let levels = characteristic_levels(&first.sizes, &per_record, q);
    Ok(Oas {
        record: name.to_string(),
        levels,
        ..first.clone()
    })
}

/// The characteristic levels of records that share one grid (`sizes`, descending, and the
/// levels of `records[0]`): at each level the `q`-fractile over the records of the largest
/// unsafe size, a record with none counting as the smallest value (size 0), as an index on
/// `sizes` (`None` when the fractile is "none"); `simulations = 0`. The callers check the grid
/// and `q`: [`characteristic_oas`] for columns, [`super::characteristic_arch_oas`] for arches.
pub fn characteristic_levels(sizes: &[f64], records: &[&[OasLevel]], q: f64) -> Vec<OasLevel> {
    let Some(first) = records.first() else {
        return Vec::new();
    };
    (0..first.len())
        .map(|k| {
            // A level without an unsafe size counts as size 0, below every size of the grid.
            let unsafe_sizes: Vec<f64> = records
                .iter()
                .map(|levels| levels[k].largest_unsafe.map_or(0.0, |i| sizes[i]))
                .collect();
            let x = statistics::fractile(&unsafe_sizes, q).unwrap_or(0.0);
            OasLevel {
                level: first[k].level,
                largest_unsafe: (x > 0.0)
                    .then(|| sizes.iter().position(|&s| s == x))
                    .flatten(),
                simulations: 0,
            }
        })
        .collect()
}

/// `0 < q ≤ 1`.
pub(super) fn valid_fractile(q: f64) -> Result<(), SpectraError> {
    if !(q > 0.0 && q <= 1.0) {
        return Err(invalid("fractile", format!("must be in (0, 1], got {q}")));
    }
    Ok(())
}

/// The `q`-fractile of the records' own `t₁` (`None` for a record that overturns no size at
/// any level of the grid): such a record ranks lowest, as the shortest replacement duration
/// (Eq. 21 with `t₁ → 0` calls every block safe), and a fractile that falls on it is `None`.
/// Leaving such records out gave the median of the others: of two records, one overturning
/// nothing, the "0.5-fractile of the records' t₁" was the other's t₁ while the design t₁ of
/// the 0.5 characteristic OAS was none.
pub fn record_t1_fractile(t1s: impl Iterator<Item = Option<f64>>, q: f64) -> Option<f64> {
    let t1s: Vec<f64> = t1s.map(|t| t.unwrap_or(0.0)).collect();
    super::statistics::fractile(&t1s, q).filter(|&t| t > 0.0)
}

/// The fractiles of a suite's report: at least one, each valid, none twice. "0.5,0.5" drew
/// every curve of that fractile twice, printed its rows twice and wrote its CSV rows twice
/// under one key.
pub fn distinct_fractiles(fractiles: &[f64]) -> Result<(), SpectraError> {
    if fractiles.is_empty() {
        return Err(invalid("fractile", "at least one fractile is needed"));
    }
    for (k, &q) in fractiles.iter().enumerate() {
        valid_fractile(q)?;
        if fractiles[..k].contains(&q) {
            return Err(invalid("fractile", format!("{q} is given twice")));
        }
    }
    Ok(())
}

/// Whether two level lists are the same levels (the same values in the same order).
pub(super) fn same_levels(a: &[OasLevel], b: &[OasLevel]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.level == y.level)
}

/// Errors unless every spectrum is on the first one's grid.
fn same_grid(spectra: &[Oas]) -> Result<(), SpectraError> {
    let Some(first) = spectra.first() else {
        return Ok(());
    };
    for o in &spectra[1..] {
        let differs = if o.sizes != first.sizes {
            Some("sizes")
        } else if !same_levels(&o.levels, &first.levels) {
            Some("levels")
        } else if o.slenderness != first.slenderness {
            Some("slenderness")
        } else if o.n_blocks != first.n_blocks {
            Some("n_blocks")
        } else if o.n_impacts != first.n_impacts {
            Some("n_impacts")
        } else if o.search != first.search {
            Some("search")
        } else if o.gravity != first.gravity {
            Some("gravity")
        } else {
            None
        };
        if let Some(field) = differs {
            return Err(invalid(
                "spectra",
                format!(
                    "`{}` has other {field} than `{}`: a suite needs one grid",
                    o.record, first.record
                ),
            ));
        }
    }
    Ok(())
}

/// The level ranges in which the thesis states the simplified spectra hold (5.3.5): Eq. 21 "if
/// `a_p < 4–6 a_p,min`" (both ends), Eq. 30 "if `a_p / a_p,min < 12`".
pub const STATED_RANGES: [f64; 3] = [4.0, 6.0, 12.0];

/// Boundary points that a simplified spectrum predicts safe although they overturn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Tally {
    /// Boundary points (record, level).
    pub points: usize,
    /// Records with at least one.
    pub records: usize,
}

impl Tally {
    /// Counts a record with `n` such points.
    pub fn add(&mut self, n: usize) {
        self.points += n;
        self.records += usize::from(n > 0);
    }
}

/// The check of the simplified spectra against the OAS of a suite's records, at the levels below
/// a bound.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Violations {
    /// Only levels `a_p / a_p,min` below this (`None`: every level).
    pub level_below: Option<f64>,
    /// Boundary points checked (records × levels with an unsafe size, below the bound).
    pub checked: usize,
    /// Eq. 21 with the exact `i_cr` (Eq. 18).
    pub eq21: Tally,
    /// Eq. 21 with `i_cr ≈ 1` (its right-hand form, Eq. 31).
    pub eq21_approx: Tally,
    /// Eq. 29 (the inclined line, as solved from Eq. 28).
    pub eq29: Tally,
    /// Eq. 30 (vertical and inclined line).
    pub eq30: Tally,
}

/// The simplified spectra's parameters for one record: `t_1` and, for Eq. 29/30, the fit.
pub type Parameters = (f64, Option<InclinedFit>);

/// Counts, over the records of `spectra`, the boundary points below `level_below` that the
/// simplified spectra with `parameters(record)` predict safe although they overturn
/// ([`Oas::check`]). Records for which `parameters` gives `None` (nothing overturns) are skipped;
/// without a fit, Eq. 29 and 30 count nothing for that record.
pub fn violations(
    spectra: &[Oas],
    parameters: impl Fn(&Oas) -> Option<Parameters>,
    level_below: Option<f64>,
) -> Violations {
    let inside = |l: f64| level_below.map_or(true, |b| l < b);
    let mut v = Violations {
        level_below,
        checked: 0,
        eq21: Tally::default(),
        eq21_approx: Tally::default(),
        eq29: Tally::default(),
        eq30: Tally::default(),
    };
    for o in spectra {
        let Some((t1, fit)) = parameters(o) else {
            continue;
        };
        v.checked += o.boundary().iter().filter(|q| inside(q.level)).count();
        let c = o.check(t1, fit);
        let count = |pts: &[super::OasPoint]| pts.iter().filter(|q| inside(q.level)).count();
        v.eq21.add(count(&c.eq21));
        v.eq21_approx.add(count(&c.eq21_approx));
        v.eq29.add(count(&c.eq29));
        v.eq30.add(count(&c.eq30));
    }
    v
}

/// [`violations`] at each bound of [`STATED_RANGES`] and at every level.
pub fn violations_in_stated_ranges(
    spectra: &[Oas],
    parameters: impl Fn(&Oas) -> Option<Parameters>,
) -> Vec<Violations> {
    STATED_RANGES
        .iter()
        .map(|&b| Some(b))
        .chain([None])
        .map(|b| violations(spectra, &parameters, b))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectra::{linear_levels, log_sizes, SizeSearch};

    /// An OAS on 4 levels 1..=4 and 10 sizes 100..0.01 m, with the given largest unsafe indices.
    fn oas(name: &str, unsafe_at: [Option<usize>; 4]) -> Oas {
        let levels = linear_levels(1.0, 4.0, 4);
        Oas {
            record: name.into(),
            slenderness: 12.0,
            n_blocks: 1,
            n_impacts: 1,
            search: SizeSearch::Scan,
            sizes: log_sizes(100.0, 0.01, 10),
            levels: levels
                .iter()
                .zip(unsafe_at)
                .map(|(&level, largest_unsafe)| OasLevel {
                    level,
                    largest_unsafe,
                    simulations: 1,
                })
                .collect(),
            gravity: 9.81,
        }
    }

    #[test]
    fn the_characteristic_oas_is_the_fractile_per_level() {
        // Five records; at level 1 two have no unsafe size. Larger index = smaller size.
        let suite = [
            oas("a", [None, Some(6), Some(5), Some(4)]),
            oas("b", [Some(9), Some(7), Some(6), Some(5)]),
            oas("c", [None, Some(5), Some(4), Some(3)]),
            oas("d", [Some(8), Some(8), Some(7), Some(2)]),
            oas("e", [Some(7), Some(9), Some(3), Some(1)]),
        ];
        let median = characteristic_oas(&suite, 0.5, "median").unwrap();
        let idx: Vec<Option<usize>> = median.levels.iter().map(|l| l.largest_unsafe).collect();
        // Sorted sizes (ascending = descending index), 3rd of 5: level 1: 0, 0, s9, s8, s7 → s9;
        // level 2: s9 s8 s7 s6 s5 → s7; level 3: s7 s6 s5 s4 s3 → s5; level 4: s5..s1 → s3.
        assert_eq!(idx, vec![Some(9), Some(7), Some(5), Some(3)]);
        let high = characteristic_oas(&suite, 0.84, "84").unwrap();
        let idx: Vec<Option<usize>> = high.levels.iter().map(|l| l.largest_unsafe).collect();
        // 5th of 5 (k = ceil(0.84 · 5) = 5): the largest size of each level.
        assert_eq!(idx, vec![Some(7), Some(5), Some(3), Some(1)]);
        let low = characteristic_oas(&suite, 0.2, "20").unwrap();
        // 1st of 5: level 1 has two records without an unsafe size: none.
        assert_eq!(low.levels[0].largest_unsafe, None);
        assert_eq!(low.levels[1].largest_unsafe, Some(9));
        assert!(low.levels.iter().all(|l| l.simulations == 0));
        assert_eq!(high.record, "84");
        // A larger fractile is a larger (more vulnerable) size at every level.
        for (m, h) in median.levels.iter().zip(&high.levels) {
            assert!(h.largest_unsafe <= m.largest_unsafe);
        }
        // Its design t1 is that of its own transformed OAS.
        let t1 = high.t1().unwrap();
        assert!((t1 - high.i_cr() / high.f_min().unwrap().f).abs() < 1e-15);
    }

    #[test]
    fn a_suite_needs_one_grid_and_a_valid_fractile() {
        let a = oas("a", [None, Some(6), Some(5), Some(4)]);
        let mut b = oas("b", [None, Some(6), Some(5), Some(4)]);
        b.slenderness = 8.0;
        let e = characteristic_oas(&[a.clone(), b], 0.5, "x").unwrap_err();
        assert!(e.to_string().contains("`b` has other slenderness"), "{e}");
        let mut c = oas("c", [None, Some(6), Some(5), Some(4)]);
        c.sizes[3] *= 1.001;
        let e = characteristic_oas(&[a.clone(), c], 0.5, "x").unwrap_err();
        assert!(e.to_string().contains("sizes"), "{e}");
        for q in [0.0, 1.5, f64::NAN] {
            let e = characteristic_oas(std::slice::from_ref(&a), q, "x").unwrap_err();
            assert!(e.to_string().starts_with("fractile"), "{e}");
        }
        assert!(characteristic_oas(&[], 0.5, "x").is_err());
        // One record: every fractile is the record itself.
        let one = characteristic_oas(std::slice::from_ref(&a), 0.84, "x").unwrap();
        assert_eq!(
            one.levels,
            a.levels
                .iter()
                .map(|l| OasLevel {
                    simulations: 0,
                    ..*l
                })
                .collect::<Vec<_>>()
        );
    }

    /// "0.5,0.5" made a report with every curve, row and CSV line of 0.5 twice; an empty list a
    /// report without any design t₁ (Python's `fractiles=[]`).
    #[test]
    fn a_suite_report_needs_distinct_fractiles() {
        for (fractiles, says) in [
            (vec![0.5, 0.5], "0.5 is given twice"),
            (vec![0.84, 0.5, 0.84], "0.84 is given twice"),
            (Vec::<f64>::new(), "at least one"),
            (vec![0.5, 1.5], "(0, 1]"),
        ] {
            let e = distinct_fractiles(&fractiles)
                .err()
                .unwrap_or_else(|| panic!("{fractiles:?} accepted"));
            assert!(e.to_string().starts_with("fractile"), "{e}");
            assert!(e.to_string().contains(says), "{e}");
        }
        assert!(distinct_fractiles(&[0.84, 0.5]).is_ok());
        // The suite report (CLI and Python) and the arch suite refuse them.
        let a = oas("a", [None, Some(6), Some(5), Some(4)]);
        #[cfg(feature = "serde")]
        {
            let spectra = [(a.clone(), 0.0)];
            let report = |q: &[f64]| crate::spectra::report::SuiteReport::of("s", &spectra, q);
            assert!(report(&[0.5, 0.5]).is_err());
            assert_eq!(report(&[0.84, 0.5]).unwrap().characteristic.len(), 2);
        }
        let _ = a;
    }

    #[test]
    fn a_record_that_overturns_nothing_ranks_lowest_among_the_records_t1() {
        let t = |v: &[Option<f64>], q| record_t1_fractile(v.iter().copied(), q);
        assert_eq!(t(&[None, Some(0.2)], 0.5), None);
        assert_eq!(t(&[None, Some(0.2)], 1.0), Some(0.2));
        assert_eq!(t(&[Some(0.3), None, Some(0.2)], 0.5), Some(0.2));
        assert_eq!(t(&[Some(0.3), Some(0.2)], 0.5), Some(0.2));
        assert_eq!(t(&[None], 0.84), None);
        // In the suite report: the 0.5 characteristic OAS of these two has no unsafe level,
        // and the records' t1 fractile agrees.
        #[cfg(feature = "serde")]
        {
            let safe = oas("safe", [None, None, None, None]);
            let b = oas("b", [None, Some(6), Some(5), Some(4)]);
            let r = crate::spectra::report::SuiteReport::of(
                "s",
                &[(safe, 0.0), (b.clone(), 0.0)],
                &[0.5, 1.0],
            )
            .unwrap();
            assert_eq!(r.characteristic[0].design_t1, None);
            assert_eq!(r.characteristic[0].record_t1_fractile, None);
            assert_eq!(r.characteristic[1].record_t1_fractile, b.t1());
            assert!(b.t1().is_some());
        }
    }

    #[test]
    fn violations_are_counted_per_level_range() {
        let a = oas("a", [Some(9), Some(6), Some(5), Some(4)]);
        let b = oas("b", [None, Some(8), Some(3), Some(2)]);
        let suite = [a.clone(), b.clone()];
        // Each record with its own t1: Eq. 21 (exact i_cr) holds by the definition of t1.
        let own = violations(&suite, |o| o.t1().map(|t| (t, o.fit())), None);
        assert_eq!(own.eq21, Tally::default());
        assert_eq!(own.eq29, Tally::default(), "the fit is left of every point");
        assert_eq!(own.checked, 7);
        // A t1 half of a's: f_min doubles, and every point of a left of 2 f_min(a) and every
        // point of b left of it is predicted safe although it overturns.
        let t1 = a.t1().unwrap() / 2.0;
        let expect = |o: &Oas, below: f64| {
            o.boundary()
                .iter()
                .filter(|q| q.level < below && q.f < 2.0 * a.f_min().unwrap().f * (1.0 - 1e-9))
                .count()
        };
        for below in [2.5, 10.0] {
            let v = violations(&suite, |_| Some((t1, None)), Some(below));
            let (na, nb) = (expect(&a, below), expect(&b, below));
            assert!(na > 0, "the test must see a violation");
            assert_eq!(v.eq21.points, na + nb);
            assert_eq!(v.eq21.records, usize::from(na > 0) + usize::from(nb > 0));
            // No fit: Eq. 29 and 30 are not checked.
            assert_eq!(v.eq29, Tally::default());
            assert_eq!(v.eq30, Tally::default());
            let checked = suite
                .iter()
                .map(|o| o.boundary().iter().filter(|q| q.level < below).count())
                .sum::<usize>();
            assert_eq!(v.checked, checked);
        }
        // The fractile 1 is the largest unsafe size of every level: Eq. 21 with its t1 is
        // conservative for every record.
        let all = characteristic_oas(&suite, 1.0, "max").unwrap();
        let design = (all.t1().unwrap(), all.fit());
        assert!(design.0 >= a.t1().unwrap() && design.0 >= b.t1().unwrap());
        let v = violations(&suite, |_| Some(design), None);
        assert_eq!(v.eq21, Tally::default());
        let ranges = violations_in_stated_ranges(&suite, |_| Some((t1, None)));
        let bounds: Vec<Option<f64>> = ranges.iter().map(|v| v.level_below).collect();
        assert_eq!(bounds, vec![Some(4.0), Some(6.0), Some(12.0), None]);
        // Levels 1..=4: "below 4" leaves out level 4 only.
        assert_eq!(ranges[1].checked, 7);
        assert_eq!(ranges[0].checked, 5);
    }
}
