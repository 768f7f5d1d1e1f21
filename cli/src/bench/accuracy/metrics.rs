//! What a run is judged by (impact times, peak rotation, energy lost) and the error measures
//! built on them: errors against a reference, observed order, time at equal error.

use rocking::driver;

use super::scenes::K_IMPACTS;

/// What a run is judged by.
#[derive(Clone, Debug, Default)]
pub(super) struct Metrics {
    /// Times and interfaces of the impacts (all of them).
    pub(super) impacts: Vec<(f64, usize)>,
    /// Kinetic energy lost at each impact (J).
    pub(super) losses: Vec<f64>,
    /// Peak rotation per block (as the scene defines it) (rad).
    pub(super) peak: Vec<f64>,
    pub(super) overturned: bool,
}

#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Errors {
    pub(super) impact: f64,
    pub(super) peak: f64,
    pub(super) energy: f64,
}

/// Largest |block angle| per block after `from`, refined between consecutive samples with no
/// event in between by the cubic Hermite interpolant of (angle, rate).
pub(super) fn refined_peaks(h: &driver::History, from: f64, events: &[f64]) -> Vec<f64> {
    let n = h.n_interfaces;
    let mut peaks = vec![0.0_f64; n];
    let block_rate = |i: usize, j: usize| -> f64 {
        let r = &h.rates[i * 2 * n..(i + 1) * 2 * n];
        (0..=j).map(|k| r[k] + r[n + k]).sum()
    };
    for i in 0..h.len() {
        if h.t[i] < from {
            continue;
        }
        for (j, p) in peaks.iter_mut().enumerate() {
            *p = p.max(h.block_angles_at(i)[j].abs());
        }
        if i + 1 == h.len()
            || h.statuses[i * n..(i + 1) * n] != h.statuses[(i + 1) * n..(i + 2) * n]
        {
            continue;
        }
        let (t0, t1) = (h.t[i], h.t[i + 1]);
        if events.iter().any(|&te| te > t0 && te <= t1) {
            continue;
        }
        let dt = t1 - t0;
        for (j, p) in peaks.iter_mut().enumerate() {
            let (y0, y1) = (h.block_angles_at(i)[j], h.block_angles_at(i + 1)[j]);
            let (d0, d1) = (block_rate(i, j) * dt, block_rate(i + 1, j) * dt);
            if d0 * d1 >= 0.0 {
                continue;
            }
            // y(s) = h00 y0 + h10 d0 + h01 y1 + h11 d1; y'(s) = a s² + b s + c.
            let a = 6.0 * y0 + 3.0 * d0 - 6.0 * y1 + 3.0 * d1;
            let b = -6.0 * y0 - 4.0 * d0 + 6.0 * y1 - 2.0 * d1;
            let c = d0;
            let roots = if a.abs() < 1e-300 {
                vec![-c / b]
            } else {
                let disc = (b * b - 4.0 * a * c).max(0.0).sqrt();
                vec![(-b + disc) / (2.0 * a), (-b - disc) / (2.0 * a)]
            };
            for s in roots {
                if (0.0..=1.0).contains(&s) {
                    let s2 = s * s;
                    let s3 = s2 * s;
                    let y = (2.0 * s3 - 3.0 * s2 + 1.0) * y0
                        + (s3 - 2.0 * s2 + s) * d0
                        + (-2.0 * s3 + 3.0 * s2) * y1
                        + (s3 - s2) * d1;
                    *p = p.max(y.abs());
                }
            }
        }
    }
    peaks
}

pub(super) fn errors(m: &Metrics, r: &Metrics) -> Errors {
    let k = K_IMPACTS.min(r.impacts.len());
    let same = m.impacts.len() >= k
        && m.impacts[..k]
            .iter()
            .zip(&r.impacts[..k])
            .all(|(a, b)| a.1 == b.1);
    let impact = if same {
        m.impacts[..k]
            .iter()
            .zip(&r.impacts[..k])
            .map(|(a, b)| (a.0 - b.0).abs())
            .fold(0.0, f64::max)
    } else {
        f64::NAN
    };
    let energy = if same && k > 0 {
        let d: f64 = m.losses[..k].iter().sum();
        let dr: f64 = r.losses[..k].iter().sum();
        (d - dr).abs() / dr
    } else {
        f64::NAN
    };
    let peak = if m.peak.len() == r.peak.len() && m.overturned == r.overturned {
        m.peak
            .iter()
            .zip(&r.peak)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    } else {
        f64::NAN
    };
    Errors {
        impact,
        peak,
        energy,
    }
}

/// Observed order: least-squares slope of log(error) against log(dt), `points` in decreasing dt,
/// over the leading run of finite errors above `floor` that keep decreasing (past it the error
/// has reached round-off or the reference's own error).
pub(super) fn observed_order(points: &[(f64, f64)], floor: f64) -> Option<f64> {
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for p in points {
        let ok = p.1.is_finite() && p.1 > floor && pts.last().is_none_or(|l| p.1.ln() < l.1);
        if !ok {
            break;
        }
        pts.push((p.0.ln(), p.1.ln()));
    }
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

/// Time a curve needs to reach `err`, on the Pareto front of `(time, error)` points, by
/// interpolation in log-log. `None` if `err` is below every point.
pub(super) fn time_at_error(points: &[(f64, f64)], err: f64) -> Option<(f64, bool)> {
    let mut pts: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.1.is_finite() && p.1 > 0.0)
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Pareto front: time ascending, error strictly descending.
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in pts {
        if front.last().is_none_or(|l| p.1 < l.1) {
            front.push(p);
        }
    }
    let first = *front.first()?;
    if err >= first.1 {
        // Reached already by the cheapest run: its time is an upper bound.
        return Some((first.0, true));
    }
    for w in front.windows(2) {
        let (a, b) = (w[0], w[1]);
        if err <= a.1 && err >= b.1 {
            let f = (err.ln() - a.1.ln()) / (b.1.ln() - a.1.ln());
            return Some(((a.0.ln() + f * (b.0.ln() - a.0.ln())).exp(), false));
        }
    }
    None
}
