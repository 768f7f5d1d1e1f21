//! Axes of the charts: range, round ticks and their labels, and the coordinate plotters maps
//! with (log10 of the value on a log axis).

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::prelude::Ranged;

use super::Scale;

/// An axis: its scale, range and ticks, in data units.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Axis {
    pub(super) scale: Scale,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// Ticks with a grid line; those with a label have `Some`.
    pub(super) ticks: Vec<(f64, Option<String>)>,
    /// Fine grid lines (2…9 × 10ᵏ on a log axis).
    pub(super) minor: Vec<f64>,
}

/// A step of 1, 2 or 5 × 10ᵏ giving about five to eight ticks over `span`.
fn nice_step(span: f64) -> f64 {
    let raw = span / 6.0;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    mag * if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    }
}

/// `v` with `decimals` decimals, or in powers of ten outside [1e-3, 1e5).
fn fmt_tick(v: f64, decimals: usize) -> String {
    if v == 0.0 || (1e-3..1e5).contains(&v.abs()) {
        if v == 0.0 {
            return "0".into();
        }
        return format!("{v:.decimals$}");
    }
    fmt_power(v)
}

/// `v` as `m×10ᵉ` (`10ᵉ` when `m` = 1), `m` rounded to a whole number.
fn fmt_power(v: f64) -> String {
    let e = v.abs().log10().floor() as i32;
    let m = (v / 10f64.powi(e)).round();
    let pow = format!("10{}", superscript(e));
    match m {
        1.0 => pow,
        -1.0 => format!("−{pow}"),
        _ => format!("{m}×{pow}"),
    }
}

/// A round value (one significant digit) without trailing zeros: 0.001, 0.2, 50.
fn fmt_round(v: f64) -> String {
    let s = format!("{v:.6}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

fn superscript(e: i32) -> String {
    e.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

impl Axis {
    /// The axis over `range`, or fitted to `values` (finite, and > 0 on a log axis); either is
    /// rounded out to a tick (a multiple of the step, or a decade).
    pub(super) fn new(
        scale: Scale,
        range: Option<(f64, f64)>,
        values: impl Iterator<Item = f64>,
    ) -> Axis {
        let (lo, hi) = match range {
            Some(r) => r,
            None => {
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for v in values.filter(|v| v.is_finite() && (scale == Scale::Linear || *v > 0.0)) {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
                (lo, hi)
            }
        };
        let (lo, hi, step) = fit(scale, lo, hi);
        match scale {
            Scale::Linear => {
                let decimals = (-step.log10().floor()).max(0.0) as usize;
                let mut ticks = Vec::new();
                let mut k = (lo / step).ceil();
                while k * step <= hi + 1e-9 * step {
                    let t = if (k * step).abs() < 1e-12 * step {
                        0.0
                    } else {
                        k * step
                    };
                    ticks.push((t, Some(fmt_tick(t, decimals))));
                    k += 1.0;
                }
                Axis {
                    scale,
                    lo,
                    hi,
                    ticks,
                    minor: Vec::new(),
                }
            }
            Scale::Log => {
                let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
                let decades = b - a;
                // Label every decade up to 8 of them, else every 2nd or 3rd.
                let every = 1 + (decades - 1).max(0) / 8;
                let mut ticks = Vec::new();
                let mut minor = Vec::new();
                for e in a..=b {
                    let d = 10f64.powi(e);
                    let labelled = (e - a) % every == 0;
                    ticks.push((d, labelled.then_some(d)));
                    for m in 2..=9 {
                        let v = f64::from(m) * d;
                        if decades <= 2 && (m == 2 || m == 5) {
                            ticks.push((v, Some(v)));
                        } else if decades <= 8 {
                            minor.push(v);
                        }
                    }
                }
                let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
                ticks.retain(|(v, _)| inside(*v));
                minor.retain(|v| inside(*v));
                // One notation on the axis: powers of ten if any label needs them.
                let powers = ticks
                    .iter()
                    .any(|(v, l)| l.is_some() && !(1e-3..1e5).contains(v));
                let ticks = ticks
                    .into_iter()
                    .map(|(v, l)| {
                        let text = |v: f64| if powers { fmt_power(v) } else { fmt_round(v) };
                        (v, l.map(text))
                    })
                    .collect();
                Axis {
                    scale,
                    lo,
                    hi,
                    ticks,
                    minor,
                }
            }
        }
    }

    /// Data → drawing coordinate (log10 on a log axis).
    pub(super) fn to(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => v,
            Scale::Log => v.log10(),
        }
    }

    pub(super) fn coord(&self) -> Coord {
        Coord {
            range: self.to(self.lo)..self.to(self.hi),
            bold: self.ticks.iter().map(|t| self.to(t.0)).collect(),
            light: self.minor.iter().map(|&v| self.to(v)).collect(),
        }
    }

    /// The label of the tick at drawing coordinate `u`.
    pub(super) fn label(&self, u: f64) -> String {
        self.ticks
            .iter()
            .find(|t| (self.to(t.0) - u).abs() <= 1e-9 * (1.0 + u.abs()))
            .and_then(|t| t.1.clone())
            .unwrap_or_default()
    }

    /// Whether data value `v` can be drawn on this axis at all.
    pub(super) fn drawable(&self, v: f64) -> bool {
        v.is_finite() && (self.scale == Scale::Linear || v > 0.0)
    }
}

/// An axis as plotters sees it: drawing coordinates (log10 on a log axis) mapped linearly, with
/// our ticks (bold grid lines, labelled by [`Axis::label`]) and fine grid lines.
pub(super) struct Coord {
    range: Range<f64>,
    bold: Vec<f64>,
    light: Vec<f64>,
}

impl Ranged for Coord {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let f = (v - self.range.start) / (self.range.end - self.range.start);
        limit.0 + (f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.light.clone()
        } else {
            self.bold.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.range.clone()
    }
}

/// The range `[lo, hi]` rounded out to a tick: a multiple of the step on a linear axis (also
/// returned), a decade on a log axis.
fn fit(scale: Scale, lo: f64, hi: f64) -> (f64, f64, f64) {
    if !lo.is_finite() {
        return match scale {
            Scale::Linear => (0.0, 1.0, 0.2),
            Scale::Log => (1.0, 10.0, 0.0),
        };
    }
    match scale {
        Scale::Log if hi / lo <= 100.0 => {
            // Two decades or less: round out to 1, 2 or 5 × 10ᵏ (those are then ticks).
            let down = |v: f64| {
                let d = 10f64.powf(v.log10().floor());
                let m = [5.0, 2.0, 1.0]
                    .into_iter()
                    .find(|m| m * d <= v * (1.0 + 1e-12));
                m.unwrap_or(1.0) * d
            };
            let up = |v: f64| {
                let d = 10f64.powf(v.log10().floor());
                let m = [1.0, 2.0, 5.0, 10.0]
                    .into_iter()
                    .find(|m| m * d >= v * (1.0 - 1e-12));
                m.unwrap_or(10.0) * d
            };
            let (a, b) = (down(lo), up(hi));
            (a, if b > a { b } else { 10.0 * a }, 0.0)
        }
        Scale::Log => {
            let a = lo.log10().floor();
            let b = hi.log10().ceil().max(a + 1.0);
            (10f64.powf(a), 10f64.powf(b), 0.0)
        }
        Scale::Linear => {
            let (lo, hi) = if hi - lo < 1e-300 {
                (lo - 1.0, hi + 1.0)
            } else {
                (lo, hi)
            };
            let mut step = nice_step(hi - lo);
            loop {
                let (a, b) = ((lo / step).floor() * step, (hi / step).ceil() * step);
                // Rounding out can widen the span past the next step size: round again.
                let wider = nice_step(b - a);
                if wider <= step {
                    return (a, b, step);
                }
                step = wider;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round() {
        // Today's OAS axis ran 0 … 4.9 with ticks 0.98, 1.95, 2.93, …
        let a = Axis::new(Scale::Linear, Some((0.0, 4.9)), std::iter::empty());
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!((a.lo, a.hi), (0.0, 5.0));
        assert_eq!(labels, ["0", "1", "2", "3", "4", "5"]);
        let a = Axis::new(Scale::Linear, None, [-0.093, 0.153].into_iter());
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!(
            labels,
            ["-0.10", "-0.05", "0", "0.05", "0.10", "0.15", "0.20"]
        );
        let a = Axis::new(Scale::Linear, None, [1.0, 9.7].into_iter());
        assert_eq!((a.lo, a.hi), (0.0, 10.0));
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!(labels, ["0", "2", "4", "6", "8", "10"]);
    }

    #[test]
    fn log_ticks_are_decades() {
        let a = Axis::new(Scale::Log, None, [2e-6, 0.3].into_iter());
        assert_eq!((a.lo, a.hi), (1e-6, 1.0));
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!(
            labels,
            ["10⁻⁶", "10⁻⁵", "10⁻⁴", "10⁻³", "10⁻²", "10⁻¹", "10⁰"]
        );
        let a = Axis::new(Scale::Log, Some((0.1, 10.0)), std::iter::empty());
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!(labels, ["0.1", "0.2", "0.5", "1", "2", "5", "10"]);
        // Within two decades the ends are 1, 2 or 5 × 10ᵏ, not whole decades.
        let a = Axis::new(Scale::Log, None, [0.3, 4.0].into_iter());
        assert_eq!((a.lo, a.hi), (0.2, 5.0));
        let labels: Vec<&str> = a.ticks.iter().filter_map(|t| t.1.as_deref()).collect();
        assert_eq!(labels, ["0.2", "0.5", "1", "2", "5"]);
    }
}
