//! `rocking oas --overlay A.json B.json ...`: several stored OAS (each the JSON of a whole
//! `rocking oas` run) on one chart, and how they compare — thesis Fig. 43 (columns of 1, 2, 3
//! blocks × 1, 2, 10 impacts) and Fig. 45 (slenderness H/B = 3, 5, 8, 12).
//!
//! The slenderness check (thesis 5.3.1: "the curve corresponding to higher slenderness is a safe
//! approximation of the one which belongs to a lower slenderness"): spectra of the same record,
//! column, impacts and levels that differ in H/B are compared pairwise, level by level, on the
//! normalised axes (`a_p / a_p,min` of each block, its size `R`, hence its `p`). The higher
//! slenderness is on the safe side at a level when its largest unsafe size is at least the lower
//! slenderness's (everything the lower one calls unsafe, the higher one calls unsafe too); a level
//! where the lower slenderness has a larger unsafe size (or the higher none) is a violation.
//! The same check compares columns of different numbers of blocks (the monolith expected the most
//! vulnerable) and different numbers of consecutive impacts (less dissipation expected the more
//! vulnerable), thesis 5.2.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rocking::spectra::report::OasReport;
use serde::Serialize;

use crate::output::{print_json, read_report};
use crate::plot::{Chart, Scale, Series, Style, COLORS};

/// One spectrum of the overlay.
#[derive(Serialize)]
struct SpectrumRow {
    file: String,
    record: String,
    slenderness: f64,
    blocks: usize,
    impacts: u32,
    /// Cells of the grid at or below the boundary: Σ over levels of the sizes from the largest
    /// unsafe one down (a measure of the unsafe area; larger = more vulnerable).
    unsafe_cells: usize,
    levels_with_unsafe: usize,
    t1: Option<f64>,
    /// `p` of the largest unsafe size at the highest level.
    p_at_top_level: Option<f64>,
}

/// One pair of spectra of a record that differ in one setting: `lower` is expected to be the
/// less vulnerable (its largest unsafe size at most `higher`'s at every level).
#[derive(Serialize)]
struct PairRow {
    record: String,
    blocks: usize,
    impacts: u32,
    slenderness: f64,
    lower: f64,
    higher: f64,
    levels_compared: usize,
    /// Levels where `lower` has a larger unsafe size than `higher`.
    violations: usize,
    /// Of those, levels where it is larger by more than one cell of the size grid.
    violations_beyond_one_cell: usize,
    violating_levels: Vec<f64>,
}

/// The pairwise check of spectra that differ in one setting.
#[derive(Serialize)]
struct Check {
    pairs: Vec<PairRow>,
    /// Records with at least one pair compared.
    records: usize,
    /// Records with a violation in some pair / with a violation against the highest value
    /// (H/B: the highest; blocks: the monolith; impacts: the most).
    records_violating: usize,
    records_violating_highest: usize,
    /// Violating (record, pair, level) triples / beyond one cell / against the highest value.
    violations: usize,
    violations_beyond_one_cell: usize,
    violations_highest: usize,
    levels_compared: usize,
}

#[derive(Serialize)]
struct Overlay {
    spectra: Vec<SpectrumRow>,
    /// Higher H/B expected the more vulnerable (thesis 5.3.1, Fig. 45).
    slenderness_check: Check,
    /// Fewer blocks expected the more vulnerable: the monolith most (thesis 5.2, Fig. 40, 43);
    /// `lower`/`higher` are minus the number of blocks.
    blocks_check: Check,
    /// More consecutive impacts (less dissipation) expected the more vulnerable (Fig. 43).
    impacts_check: Check,
}

/// Index in the size grid of the largest unsafe size at each level (`None`: none unsafe).
fn boundary_index(r: &OasReport) -> Vec<(f64, Option<usize>)> {
    r.levels
        .iter()
        .map(|l| (l.level.level, l.level.largest_unsafe))
        .collect()
}

fn spectrum_row(file: &Path, r: &OasReport) -> SpectrumRow {
    let n = r.sizes.len();
    let b = boundary_index(r);
    SpectrumRow {
        file: file.display().to_string(),
        record: r.record.clone(),
        slenderness: r.slenderness,
        blocks: r.blocks,
        impacts: r.impacts,
        unsafe_cells: b.iter().filter_map(|(_, i)| i.map(|i| n - i)).sum(),
        levels_with_unsafe: b.iter().filter(|(_, i)| i.is_some()).count(),
        t1: r.summary.t1,
        p_at_top_level: r
            .levels
            .iter()
            .max_by(|a, b| a.level.level.total_cmp(&b.level.level))
            .and_then(|l| l.p),
    }
}

/// The pair check of `lower` against `higher` (same grid), whose compared setting is `value`.
fn pair(lower: &OasReport, higher: &OasReport, value: fn(&OasReport) -> f64) -> Option<PairRow> {
    if lower.sizes != higher.sizes || lower.levels.len() != higher.levels.len() {
        return None;
    }
    let (mut violations, mut beyond, mut levels) = (0, 0, Vec::new());
    for ((level, lo), (level_h, hi)) in boundary_index(lower)
        .into_iter()
        .zip(boundary_index(higher))
    {
        if level != level_h {
            return None;
        }
        // A smaller index is a larger size. No unsafe size = an index past the grid.
        let past = lower.sizes.len();
        let (lo, hi) = (lo.unwrap_or(past), hi.unwrap_or(past));
        if lo < hi {
            violations += 1;
            beyond += usize::from(hi - lo > 1);
            levels.push(level);
        }
    }
    Some(PairRow {
        record: lower.record.clone(),
        blocks: lower.blocks,
        impacts: lower.impacts,
        slenderness: lower.slenderness,
        lower: value(lower),
        higher: value(higher),
        levels_compared: lower.levels.len(),
        violations,
        violations_beyond_one_cell: beyond,
        violating_levels: levels,
    })
}

/// The setting a check compares, and the key of the spectra it compares (all else).
struct Vary {
    value: fn(&OasReport) -> f64,
    key: fn(&OasReport) -> (String, u64, u64),
}

const SLENDERNESS: Vary = Vary {
    value: |r| r.slenderness,
    key: |r| (r.record.clone(), r.blocks as u64, u64::from(r.impacts)),
};
const BLOCKS: Vary = Vary {
    value: |r| -(r.blocks as f64),
    key: |r| {
        (
            r.record.clone(),
            r.slenderness.to_bits(),
            u64::from(r.impacts),
        )
    },
};
const IMPACTS: Vary = Vary {
    value: |r| f64::from(r.impacts),
    key: |r| (r.record.clone(), r.slenderness.to_bits(), r.blocks as u64),
};

fn check(reports: &[OasReport], vary: &Vary) -> Check {
    let mut groups: BTreeMap<(String, u64, u64), Vec<&OasReport>> = BTreeMap::new();
    for r in reports {
        groups.entry((vary.key)(r)).or_default().push(r);
    }
    let mut pairs = Vec::new();
    let (mut records, mut violating, mut violating_highest) = (0, 0, 0);
    let (mut violations, mut beyond, mut highest_count, mut compared) = (0, 0, 0, 0);
    for group in groups.values_mut() {
        group.sort_by(|a, b| (vary.value)(a).total_cmp(&(vary.value)(b)));
        let top = group.last().map_or(0.0, |r| (vary.value)(r));
        let before = pairs.len();
        for (i, lo) in group.iter().enumerate() {
            for hi in &group[i + 1..] {
                if (vary.value)(hi) > (vary.value)(lo) {
                    pairs.extend(pair(lo, hi, vary.value));
                }
            }
        }
        let new = &pairs[before..];
        if new.is_empty() {
            continue;
        }
        records += 1;
        violating += usize::from(new.iter().any(|p: &PairRow| p.violations > 0));
        let against_top = new.iter().filter(|p| p.higher == top);
        let top_violations: usize = against_top.map(|p| p.violations).sum();
        violating_highest += usize::from(top_violations > 0);
        highest_count += top_violations;
        violations += new.iter().map(|p| p.violations).sum::<usize>();
        beyond += new
            .iter()
            .map(|p| p.violations_beyond_one_cell)
            .sum::<usize>();
        compared += new.iter().map(|p| p.levels_compared).sum::<usize>();
    }
    Check {
        pairs,
        records,
        records_violating: violating,
        records_violating_highest: violating_highest,
        violations,
        violations_beyond_one_cell: beyond,
        violations_highest: highest_count,
        levels_compared: compared,
    }
}

/// The label of a spectrum in the legend: what differs between the spectra.
fn label(r: &OasReport, all: &[OasReport]) -> String {
    let mut parts = Vec::new();
    if all.iter().any(|o| o.record != r.record) {
        parts.push(r.record.clone());
    }
    if all.iter().any(|o| o.slenderness != r.slenderness) {
        parts.push(format!("H/B = {}", r.slenderness));
    }
    if all.iter().any(|o| o.blocks != r.blocks) {
        parts.push(format!(
            "{} block{}",
            r.blocks,
            if r.blocks == 1 { "" } else { "s" }
        ));
    }
    if all.iter().any(|o| o.impacts != r.impacts) {
        parts.push(format!(
            "{} impact{}",
            r.impacts,
            if r.impacts == 1 { "" } else { "s" }
        ));
    }
    if parts.is_empty() {
        r.record.clone()
    } else {
        parts.join(", ")
    }
}

/// The overlay charts: the boundaries against `p` (Fig. 43, 45) and against the size `R`.
fn charts(reports: &[OasReport]) -> Vec<(&'static str, Chart)> {
    let lmax = reports
        .iter()
        .flat_map(|r| r.levels.iter().map(|l| l.level.level))
        .fold(1.0, f64::max);
    let series = |x: &dyn Fn(&rocking::spectra::report::LevelReport) -> Option<f64>| {
        reports
            .iter()
            .enumerate()
            .map(|(k, r)| Series {
                name: label(r, reports),
                points: r
                    .levels
                    .iter()
                    .filter_map(|l| Some((x(l)?, l.level.level)))
                    .collect(),
                // Past the palette, the colours repeat dashed.
                style: if k < COLORS.len() {
                    Style::Line
                } else {
                    Style::Dashed
                },
                color: COLORS[k % COLORS.len()],
            })
            .collect::<Vec<_>>()
    };
    let record = reports.first().map_or(String::new(), |r| r.record.clone());
    let chart = |title, x_label, x_scale, series| {
        super::oas::level_chart(title, x_label, x_scale, None, lmax, series)
    };
    vec![
        (
            "overlay",
            chart(
                format!("OAS, {record}"),
                "p [1/s]",
                Scale::Linear,
                series(&|l| l.p),
            ),
        ),
        (
            "overlay-size",
            chart(
                format!("OAS against the block size, {record}"),
                "size R [m] (half diagonal)",
                Scale::Log,
                series(&|l| l.size),
            ),
        ),
    ]
}

/// Reads the reports, prints the comparison (JSON) and writes the charts under `svg`.
pub fn run(files: &[PathBuf], svg: Option<&Path>, png: bool) -> Result<(), String> {
    let reports: Vec<OasReport> = files
        .iter()
        .map(|p| read_report(p, "an OAS report (`rocking oas --json`)"))
        .collect::<Result<_, _>>()?;
    if reports.is_empty() {
        return Err("--overlay: no OAS given".into());
    }
    let overlay = Overlay {
        spectra: files
            .iter()
            .zip(&reports)
            .map(|(f, r)| spectrum_row(f, r))
            .collect(),
        slenderness_check: check(&reports, &SLENDERNESS),
        blocks_check: check(&reports, &BLOCKS),
        impacts_check: check(&reports, &IMPACTS),
    };
    print_json(&overlay)?;
    if let Some(prefix) = svg {
        for (name, chart) in charts(&reports) {
            chart.write_named(prefix, name, png)?;
        }
    }
    Ok(())
}
