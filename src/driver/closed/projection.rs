//! Keeping a loop closed (SPEC §9): the kinetic-metric projections of the rates onto the closure
//! (`G v = 0`, with some joints locked) and of the positions onto the closure manifold
//! (`G(q) = 0`: the last body back on its support).
//!
//! Both are the equality-constrained least-squares problem in the metric of the mass matrix on
//! the open DOFs `F`: `min ½ (y − y⁻)ᵀ M_FF (y − y⁻)` subject to `A_F y = c`, solved by its KKT
//! system `[M_FF A_Fᵀ; A_F 0][y; μ] = [M_FF y⁻; c]`. `M_FF` alone is singular in a loop (the
//! cut joint moves no mass), but it is positive definite on the null space of `A_F` for any
//! configuration of a consistent loop (SPEC §9), so the KKT matrix is not singular.

use super::equations::solve_in_place;
use crate::chain::{Chain, ChainPose};

/// Buffers of the projections, kept from one call to the next (the driver's projections after
/// every step and at every event allocate nothing once they have grown).
#[derive(Default)]
pub(super) struct ProjectionWork {
    kkt: KktWork,
    /// The closure matrix (rates) or the residual's Jacobian (positions), `3 × m`.
    rows: Vec<f64>,
    /// The moving DOFs' joints, pivots and rates, and `M_F· v` (rates).
    moving: Vec<((usize, [f64; 2]), f64)>,
    b: Vec<f64>,
    /// The Newton step's DOFs, correction, trial angles, held DOFs and the trial's pose.
    free: Vec<usize>,
    dx: Vec<f64>,
    trial: Vec<f64>,
    held: Vec<usize>,
    trial_pose: ChainPose,
}

/// The KKT matrix and right-hand side, the open DOFs' joints and pivots.
#[derive(Default)]
struct KktWork {
    mat: Vec<f64>,
    rhs: Vec<f64>,
    piv: Vec<(usize, [f64; 2])>,
}

/// Solves `[M_FF A_Fᵀ; A_F 0][y; μ] = [b; c]` for `y` (in `b`'s place), `M_FF` the mass
/// entries of the DOFs `open` in the pose (built in place by [`Chain::mass_block_into`]: the
/// same formula as [`Chain::mass_matrix`]'s, the same numbers to the bit), `a` the `3 × m`
/// constraint rows; `work` is scratch. `false` when singular.
#[allow(clippy::too_many_arguments)]
fn kkt(
    chain: &Chain,
    pose: &ChainPose,
    a: &[f64],
    m: usize,
    open: &[usize],
    b: &mut [f64],
    c: [f64; 3],
    work: &mut KktWork,
) -> bool {
    let KktWork { mat, rhs, piv } = work;
    let nf = open.len();
    let k = nf + 3;
    mat.clear();
    mat.resize(k * k, 0.0);
    rhs.clear();
    rhs.resize(k, 0.0);
    piv.clear();
    piv.extend(open.iter().map(|&d| chain.dof_pivot(pose, d)));
    chain.mass_block_into(pose, piv, mat, k);
    for (i, &di) in open.iter().enumerate() {
        for r in 0..3 {
            mat[i * k + nf + r] = a[r * m + di];
            mat[(nf + r) * k + i] = a[r * m + di];
        }
        rhs[i] = b[i];
    }
    rhs[nf..].copy_from_slice(&c);
    if !solve_in_place(mat, rhs) {
        return false;
    }
    b.copy_from_slice(&rhs[..nf]);
    true
}

/// Row `d` of the full mass matrix times `rates`, summed over every DOF in order (a `+0.0` for
/// each still one).
fn mass_row_times_rates(chain: &Chain, pose: &ChainPose, d: usize, rates: &[f64]) -> f64 {
    (0..chain.n_dofs())
        .map(|e| {
            if rates[e] != 0.0 {
                chain.mass_entry(pose, d, e) * rates[e]
            } else {
                0.0
            }
        })
        .sum()
}

/// The rates closest to `rates` in kinetic energy that move only the DOFs `open` and keep the
/// loop closed (`G v = 0`): the rates of every other DOF are removed (a locked joint, SPEC §5's
/// settling with the closure). Returns `false` (rates untouched) when the KKT system is singular.
pub fn project_rates(chain: &Chain, pose: &ChainPose, open: &[usize], rates: &mut [f64]) -> bool {
    project_rates_with(chain, pose, open, rates, &mut ProjectionWork::default())
}

/// [`project_rates`] with the buffers of `work`.
pub(super) fn project_rates_with(
    chain: &Chain,
    pose: &ChainPose,
    open: &[usize],
    rates: &mut [f64],
    work: &mut ProjectionWork,
) -> bool {
    let m = chain.n_dofs();
    let ProjectionWork {
        kkt: kkt_work,
        rows: g,
        moving,
        b,
        ..
    } = work;
    chain.closure_matrix_into(pose, g);
    // `M_F· v` over the moving DOFs only, each DOF's joint and pivot found once. The sum over
    // all `m` DOFs in order (a `+0.0` for each still one) is the same sum: adding `+0.0` leaves
    // every partial sum but a zero as it is, and once a non-zero term arrives the partial sums
    // agree; only a sum that ends at zero may differ (in its sign), and that one is taken again
    // over all `m` as before.
    moving.clear();
    moving.extend(
        (0..m)
            .filter(|&e| rates[e] != 0.0)
            .map(|e| (chain.dof_pivot(pose, e), rates[e])),
    );
    let still = moving.len() < m;
    b.clear();
    b.extend(open.iter().map(|&d| {
        let pd = chain.dof_pivot(pose, d);
        let sum: f64 = moving
            .iter()
            .map(|&(pe, r)| chain.mass_entry_of(pose, pd, pe) * r)
            .sum();
        if sum == 0.0 && still {
            mass_row_times_rates(chain, pose, d, rates)
        } else {
            sum
        }
    }));
    if !kkt(chain, pose, g, m, open, b, [0.0; 3], kkt_work) {
        return false;
    }
    rates.iter_mut().for_each(|r| *r = 0.0);
    for (i, &d) in open.iter().enumerate() {
        rates[d] = b[i];
    }
    true
}

/// Moves the open DOFs' angles `phi` onto the closure manifold by Newton steps in the kinetic
/// metric: the residual `r = (angle, dx, dy)` of [`Chain::closure_residual`] has the Jacobian
/// `∂r/∂φ_a = (1, P_y − o′_y, o′_x − P_x)` (a rotation about the pivot `P` of DOF `a` moves the
/// last joint's centre `o′`), and each step is the smallest correction in `M_FF` that zeroes its
/// linearisation. An angle is never moved across zero (a hinge does not close by projection): a
/// DOF the correction would carry across is held where it is and the step solved again without
/// it.
/// Up to `iterations` steps, stopping when the residual stops shrinking; returns the final
/// residual as a length (`max(|(dx, dy)|, |angle| × reach)`).
pub fn project_positions(
    chain: &Chain,
    open: &[usize],
    phi: &mut [f64],
    reach: f64,
    iterations: usize,
) -> f64 {
    let mut pose = chain.pose(phi);
    let mut work = ProjectionWork::default();
    project_positions_posed(chain, open, phi, reach, iterations, &mut pose, &mut work)
}

/// [`project_positions`] with `pose` the pose of `phi` on entry and the buffers of `work`; on
/// return `pose` is the pose of the final `phi` (the driver's next uses of it need not build it
/// again).
pub(super) fn project_positions_posed(
    chain: &Chain,
    open: &[usize],
    phi: &mut [f64],
    reach: f64,
    iterations: usize,
    pose: &mut ChainPose,
    work: &mut ProjectionWork,
) -> f64 {
    let m = chain.n_dofs();
    let size = |r: [f64; 3]| r[1].hypot(r[2]).max(r[0].abs() * reach);
    let depth = |d: usize, x: f64| if d < m / 2 { -x } else { x };
    let ProjectionWork {
        kkt: kkt_work,
        rows: jac,
        free,
        dx,
        trial,
        held,
        trial_pose,
        ..
    } = work;
    let mut r = chain.closure_residual(pose);
    for _ in 0..iterations {
        if size(r) == 0.0 {
            break;
        }
        let o = chain.joints()[chain.n_joints() - 1].centre;
        let moved = pose.support.apply(o);
        // Zero on the DOFs not open (read by nothing but the KKT rows of `free ⊆ open`).
        jac.clear();
        jac.resize(3 * m, 0.0);
        for &a in open {
            let p = chain.pivot(pose, a);
            jac[a] = 1.0;
            jac[m + a] = p[1] - moved[1];
            jac[2 * m + a] = moved[0] - p[0];
        }
        free.clear();
        free.extend_from_slice(open);
        let found = loop {
            dx.clear();
            dx.resize(free.len(), 0.0);
            if free.len() < 3
                || !kkt(
                    chain,
                    pose,
                    jac,
                    m,
                    free,
                    dx,
                    [-r[0], -r[1], -r[2]],
                    kkt_work,
                )
            {
                break false;
            }
            trial.clear();
            trial.extend_from_slice(phi);
            held.clear();
            for (i, &d) in free.iter().enumerate() {
                let x = trial[d] + dx[i];
                if depth(d, x) < 0.0 {
                    held.push(d);
                }
                trial[d] = x;
            }
            if held.is_empty() {
                break true;
            }
            free.retain(|f| !held.contains(f));
        };
        if !found {
            break;
        }
        // The trial's pose in the memory of the last one (a pose is rebuilt whole).
        chain.pose_into(trial, trial_pose);
        let trial_r = chain.closure_residual(trial_pose);
        if size(trial_r) >= size(r) {
            break;
        }
        phi.copy_from_slice(trial);
        std::mem::swap(pose, trial_pose);
        r = trial_r;
    }
    size(r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::arch::VoussoirArch;

    /// The 20-voussoir arch's collapse mechanism (joints 3, 15 intrados; 9, 20 extrados).
    fn mechanism() -> (Chain, Vec<usize>) {
        let chain = VoussoirArch::semicircular(5.0, 0.75, 20).chain().unwrap();
        let n = chain.n_joints();
        (chain, vec![3, 15, n + 9, n + 20])
    }

    /// Angles off the closure by millimetres are brought back to round-off in a few Newton
    /// steps, on the admissible side; rates are projected onto `G v = 0` and a second projection
    /// changes nothing.
    #[test]
    fn positions_and_rates_back_on_the_closure() {
        let (chain, open) = mechanism();
        let m = chain.n_dofs();
        let mut phi = vec![0.0; m];
        for (&d, x) in open.iter().zip([-0.010, -0.015, 0.020, 0.010]) {
            phi[d] = x;
        }
        let before = chain.closure_residual(&chain.pose(&phi));
        assert!(before[1].hypot(before[2]) > 1e-3, "{before:?}");
        let r = project_positions(&chain, &open, &mut phi, 10.0, 8);
        assert!(r < 1e-12, "{r}");
        assert!(phi[3] < 0.0 && phi[15] < 0.0 && phi[m / 2 + 9] > 0.0 && phi[m / 2 + 20] > 0.0);
        let pose = chain.pose(&phi);
        let mut rates = vec![0.0; m];
        for (&d, v) in open.iter().zip([-0.1, -0.1, 0.1, 0.1]) {
            rates[d] = v;
        }
        assert!(project_rates(&chain, &pose, &open, &mut rates));
        let g = chain.closure_matrix(&pose);
        for row in 0..3 {
            let gv: f64 = (0..m).map(|a| g[row * m + a] * rates[a]).sum();
            assert!(gv.abs() < 1e-12, "{gv}");
        }
        let again = {
            let mut r2 = rates.clone();
            assert!(project_rates(&chain, &pose, &open, &mut r2));
            r2
        };
        for (a, b) in rates.iter().zip(&again) {
            assert!((a - b).abs() <= 1e-12 * a.abs().max(1.0));
        }
    }

    /// The projection as it was before `M_F· v` skipped the still DOFs and `M_FF` was built in
    /// the KKT matrix: every DOF in the sum, `M_FF` from `Chain::mass_entry`, copied.
    fn project_rates_reference(
        chain: &Chain,
        pose: &ChainPose,
        open: &[usize],
        rates: &mut [f64],
    ) -> bool {
        let m = chain.n_dofs();
        let g = chain.closure_matrix(pose);
        let mut b: Vec<f64> = open
            .iter()
            .map(|&d| mass_row_times_rates(chain, pose, d, rates))
            .collect();
        let (nf, k) = (open.len(), open.len() + 3);
        let mut mat = vec![0.0; k * k];
        let mut rhs = vec![0.0; k];
        for (i, &di) in open.iter().enumerate() {
            for (j, &dj) in open.iter().enumerate() {
                mat[i * k + j] = chain.mass_entry(pose, di, dj);
            }
            for r in 0..3 {
                mat[i * k + nf + r] = g[r * m + di];
                mat[(nf + r) * k + i] = g[r * m + di];
            }
            rhs[i] = b[i];
        }
        if !solve_in_place(&mut mat, &mut rhs) {
            return false;
        }
        b.copy_from_slice(&rhs[..nf]);
        rates.iter_mut().for_each(|r| *r = 0.0);
        for (i, &d) in open.iter().enumerate() {
            rates[d] = b[i];
        }
        true
    }

    /// `project_rates` gives the reference's rates to the bit: random poses of the mechanism with
    /// more joints open, random rates with some DOFs still (zero) or of zero sum, and all rates
    /// zero (every sum zero: the fallback over all DOFs keeps the reference's `+0.0`).
    #[test]
    fn project_rates_is_the_reference_bit_for_bit() {
        let (chain, _) = mechanism();
        let (m, n) = (chain.n_dofs(), chain.n_joints());
        let mut u = crate::test_support::uniform(0x5eed_a7c4);
        for case in 0..200 {
            // Open joints: the four of the mechanism and a few more, on random faces.
            let mut open: Vec<usize> = vec![3, 15, n + 9, n + 20];
            for k in [1, 2, 6, 12, 16, 18] {
                if u() < 0.5 {
                    open.push(if u() < 0.5 { k } else { n + k });
                }
            }
            open.sort_unstable();
            let mut phi = vec![0.0; m];
            for &d in &open {
                let x = 0.02 * u();
                phi[d] = if d < n { -x } else { x };
            }
            let pose = chain.pose(&phi);
            let mut rates = vec![0.0; m];
            for (i, &d) in open.iter().enumerate() {
                rates[d] = match case % 4 {
                    0 => 0.0,
                    1 if i % 2 == 0 => 0.0,
                    _ => 0.2 * u() - 0.1,
                };
            }
            // A rate on a DOF outside the projection's set (a locked joint's).
            if case % 3 == 0 {
                rates[7] = -0.05 * u();
            }
            let sub: Vec<usize> = open.iter().copied().skip(case % 2).collect();
            let (mut a, mut b) = (rates.clone(), rates.clone());
            let (ok_a, ok_b) = (
                project_rates(&chain, &pose, &sub, &mut a),
                project_rates_reference(&chain, &pose, &sub, &mut b),
            );
            assert_eq!(ok_a, ok_b, "case {case}");
            for (x, y) in a.iter().zip(&b) {
                assert_eq!(x.to_bits(), y.to_bits(), "case {case}: {a:?} against {b:?}");
            }
        }
    }
}
