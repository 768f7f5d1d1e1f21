//! The few statistics a record suite needs: the empirical fractile (the characteristic OAS,
//! thesis 5.3.1), the median, Pearson's correlation and the least-squares lines of t₁ against
//! t_p (Fig. 53).

/// The empirical `q`-fractile of `values` (`0 < q ≤ 1`): the smallest value `x` of the sample
/// with `F_n(x) ≥ q`, `F_n` the sample's distribution function (Hyndman–Fan type 1, no
/// interpolation, so the fractile is one of the values: on an OAS, a size of the grid). At most a
/// share `1 − q` of the sample exceeds it. `None` for an empty sample or `q` outside `(0, 1]`.
pub fn fractile(values: &[f64], q: f64) -> Option<f64> {
    if values.is_empty() || !(q > 0.0 && q <= 1.0) {
        return None;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    // Smallest k (1-based) with k / n >= q; a relative 1e-12 keeps q = k/n exact.
    let k = ((q * n as f64) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
    Some(v[k.min(n) - 1])
}

/// The sample median: the middle value, or the mean of the two middle values of an even sample
/// (Python's `statistics.median`); `None` for an empty sample.
pub fn median(values: &[f64]) -> Option<f64> {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some(0.5 * (v[n / 2 - 1] + v[n / 2])),
    }
}

/// Pearson's correlation coefficient of the pairs `(x, y)`; `None` for fewer than two pairs or a
/// constant coordinate.
pub fn pearson(pairs: &[(f64, f64)]) -> Option<f64> {
    let n = pairs.len() as f64;
    if pairs.len() < 2 {
        return None;
    }
    let mx = pairs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for &(x, y) in pairs {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

/// The least-squares line `y = a + b x` of the pairs: `(a, b)`; `None` as for [`pearson`].
pub fn least_squares(pairs: &[(f64, f64)]) -> Option<(f64, f64)> {
    let n = pairs.len() as f64;
    if pairs.len() < 2 {
        return None;
    }
    let mx = pairs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pairs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pairs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    (sxx > 0.0).then(|| (my - sxy / sxx * mx, sxy / sxx))
}

/// The least-squares slope of `y = b x` (a line through the origin, the thesis's
/// "t₁ ≈ (0.8 ÷ 1) t_p"); `None` when every `x` is zero or there are no pairs.
pub fn slope_through_origin(pairs: &[(f64, f64)]) -> Option<f64> {
    let sxx: f64 = pairs.iter().map(|p| p.0 * p.0).sum();
    let sxy: f64 = pairs.iter().map(|p| p.0 * p.1).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractiles_are_values_of_the_sample() {
        let v = [5.0, 1.0, 4.0, 2.0, 3.0];
        assert_eq!(fractile(&v, 0.5), Some(3.0));
        assert_eq!(fractile(&v, 0.2), Some(1.0));
        assert_eq!(fractile(&v, 0.21), Some(2.0));
        assert_eq!(fractile(&v, 0.84), Some(5.0));
        assert_eq!(fractile(&v, 0.8), Some(4.0));
        assert_eq!(fractile(&v, 1.0), Some(5.0));
        assert_eq!(fractile(&v, 0.0), None);
        assert_eq!(fractile(&[], 0.5), None);
        assert_eq!(median(&v), Some(3.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.5));
        assert_eq!(median(&[]), None);
        // At most a share 1 - q exceeds the fractile.
        let w: Vec<f64> = (0..44).map(|k| ((k * 17) % 44) as f64).collect();
        for q in [0.1, 0.5, 0.84, 0.9] {
            let x = fractile(&w, q).unwrap();
            let above = w.iter().filter(|&&v| v > x).count() as f64 / 44.0;
            let at_most = w.iter().filter(|&&v| v <= x).count() as f64 / 44.0;
            assert!(above <= 1.0 - q + 1e-12 && at_most >= q, "{q}: {x}");
        }
    }

    #[test]
    fn correlation_and_lines() {
        let p = [(1.0, 2.0), (2.0, 4.1), (3.0, 5.9), (4.0, 8.0)];
        let r = pearson(&p).unwrap();
        assert!(r > 0.99 && r <= 1.0);
        let (a, b) = least_squares(&p).unwrap();
        assert!(
            (b - 1.98).abs() < 1e-12 && (a - 0.05).abs() < 1e-12,
            "{a} {b}"
        );
        let neg: Vec<(f64, f64)> = p.iter().map(|&(x, y)| (x, -y)).collect();
        assert!((pearson(&neg).unwrap() + r).abs() < 1e-15);
        assert_eq!(pearson(&[(1.0, 2.0), (1.0, 3.0)]), None);
        assert!((slope_through_origin(&[(1.0, 1.0), (2.0, 2.0)]).unwrap() - 1.0).abs() < 1e-15);
    }
}
