//! The potential-energy barrier behind the column stop
//! ([`StoppingOptions::stop_when_safe_column`]), certified by `driver::barrier` for 2 and 3
//! equal blocks (docs/column-early-stop.md): here its two lemmas checked on many
//! paths through the driver's own code, and the certificate's closed forms checked against the
//! driver's potential energy and tipping check. From the straight column, along a
//! ray of interface rotations (one signed angle per interface: negative about the right corner,
//! positive about the left), up to the first static tipping of some part (the driver's own
//! check): (L1) the potential energy stays `≥ 0` before it, (L2) at the tipping it is at least
//! the smallest rigid mechanism's `E_tip`. Rays reach the part of the tipping boundary visible
//! from the straight column: a check, not a proof.

use super::*;

/// A small deterministic generator (no dependency): uniform in [-1, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// `(tipped, V)` of the column turned by `angles` (one per interface), at rest.
fn probe(dy: &mut ColumnDynamics, angles: &[f64]) -> (bool, f64) {
    let n = angles.len();
    let mut phi = vec![0.0; 2 * n];
    let mut statuses = vec![Status::Closed; n];
    let mut open = Vec::new();
    for (k, &a) in angles.iter().enumerate() {
        if a < 0.0 {
            phi[k] = a;
            statuses[k] = Status::OpenRight;
            open.push(k);
        } else if a > 0.0 {
            phi[n + k] = a;
            statuses[k] = Status::OpenLeft;
            open.push(n + k);
        }
    }
    open.sort_unstable();
    let rates = vec![0.0; 2 * n];
    let tipped = dy
        .check(&open, &statuses, 0.0, &phi, &rates, false)
        .tipped
        .is_some();
    let (_, v) = dy.energy(&open, &phi, &rates);
    (tipped, v)
}

/// The smallest `V / E_tip` at the first tipping along `rays` rays (and the smallest `V / E_tip`
/// before it), for a column of `n` equal blocks of slenderness `h_over_b`.
fn barrier_ratios(n: usize, h_over_b: f64, rays: usize) -> (f64, f64) {
    let column = crate::spectra::column_of_size(10.0, h_over_b, n).unwrap();
    let mut dy = ColumnDynamics::new(&column, G, true, 1e-9, f64::INFINITY);
    let e_tip = dy.tipping_energy();
    let mut rng = Lcg(12345 + n as u64);
    let (mut at_tip, mut before) = (f64::INFINITY, f64::INFINITY);
    for r in 0..rays {
        // The first 2n rays are the rigid mechanisms (one interface turned).
        let dir: Vec<f64> = if r < 2 * n {
            (0..n)
                .map(|k| {
                    if k == r % n {
                        if r < n {
                            1.0
                        } else {
                            -1.0
                        }
                    } else {
                        0.0
                    }
                })
                .collect()
        } else {
            (0..n).map(|_| rng.next()).collect()
        };
        let norm = dir.iter().fold(0.0f64, |m, d| m.max(d.abs()));
        let at = |s: f64| dir.iter().map(|d| s * d / norm).collect::<Vec<f64>>();
        // Up to 1 rad on the largest interface rotation, in 400 steps.
        let steps = 400;
        let mut prev = 0.0;
        for i in 1..=steps {
            let s = i as f64 / steps as f64;
            let (tipped, v) = probe(&mut dy, &at(s));
            if !tipped {
                before = before.min(v / e_tip);
                prev = s;
                continue;
            }
            let (mut lo, mut hi) = (prev, s);
            for _ in 0..50 {
                let mid = 0.5 * (lo + hi);
                if probe(&mut dy, &at(mid)).0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            at_tip = at_tip.min(probe(&mut dy, &at(hi)).1 / e_tip);
            break;
        }
    }
    (at_tip, before)
}

#[test]
fn no_ray_to_tipping_is_cheaper_than_the_rigid_mechanisms() {
    for n in [2, 3] {
        for h_over_b in [3.0, 5.0, 8.0, 12.0] {
            let (at_tip, before) = barrier_ratios(n, h_over_b, 3000);
            println!("{n} blocks, H/B = {h_over_b}: min V/E_tip at tipping {at_tip:.6}, before {before:.3e}");
            // The rigid rays reach E_tip itself (to the bisection's precision).
            assert!(
                (0.999_999..=1.000_001).contains(&at_tip),
                "{n}, {h_over_b}: {at_tip}"
            );
            assert!(before >= -1e-12, "{n}, {h_over_b}: {before}");
        }
    }
}

/// The closed forms that the certificate bounds (`driver::barrier`) are the driver's own
/// potential energy and tipping check, on random configurations of 2 and 3 blocks.
#[test]
fn the_certified_formulas_are_the_drivers_potential_and_tipping() {
    let mut rng = Lcg(777);
    let mut tipped_seen = [0usize; 2];
    for n in [2, 3] {
        for h_over_b in [3.0, 5.0, 12.0] {
            let column = crate::spectra::column_of_size(10.0, h_over_b, n).unwrap();
            let b = 0.5 * column.blocks()[0].width;
            let mass = column.blocks()[0].mass;
            let lambda = h_over_b / n as f64;
            let mut dy = ColumnDynamics::new(&column, G, true, 1e-9, f64::INFINITY);
            for _ in 0..2000 {
                let psi: Vec<f64> = (0..n).map(|_| 0.8 * rng.next()).collect();
                let (tipped, v) = probe(&mut dy, &psi);
                let (v_unit, margins) = crate::driver::barrier::configuration(&psi, lambda);
                let scale = mass * G * b;
                assert!(
                    (v - v_unit * scale).abs() <= 1e-9 * scale,
                    "{psi:?}: {v} vs {}",
                    v_unit * scale
                );
                let tipped_here = margins.iter().any(|&m| m < 0.0);
                // Away from the boundary (margins of a rounding size are left out).
                if margins.iter().all(|m| m.abs() > 1e-9) {
                    assert_eq!(tipped, tipped_here, "{n}, {h_over_b}, {psi:?}: {margins:?}");
                    tipped_seen[usize::from(tipped)] += 1;
                }
            }
        }
    }
    assert!(
        tipped_seen[0] > 100 && tipped_seen[1] > 100,
        "{tipped_seen:?}"
    );
    // Where nothing has tipped, every |ψ_k| ≤ atan(2/λ): the box the certificate covers.
    for n in [2, 3] {
        for lambda in [1.0, 1.5, 4.0, 6.0] {
            for _ in 0..200_000 {
                let psi: Vec<f64> = (0..n).map(|_| 1.5 * rng.next()).collect();
                let (_, margins) = crate::driver::barrier::configuration(&psi, lambda);
                if margins.iter().all(|&m| m >= 0.0) {
                    let bound = (2.0 / lambda).atan();
                    assert!(psi.iter().all(|p| p.abs() <= bound), "{psi:?}, {lambda}");
                }
            }
        }
    }
}
