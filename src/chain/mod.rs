//! Chains of rigid bodies between supports (SPEC §9): the geometry that a closed loop needs —
//! pose from the joint angles, the mass matrix and load of the cut chain, the closure matrix `G`
//! and `Ġ v`, the exact velocity terms, the position-level closure residual — and two loops built
//! on it: the voussoir arch ([`arch`]) and the capped colonnade ([`colonnade`]).
//!
//! Bodies `0 … N−1` lie in a row between a left support (the ground) and, for a loop, a right
//! support (the ground again). Joint `0` lies between the left support and body 0, joint `k`
//! between bodies `k−1` and `k`, and in a loop joint `N` between body `N−1` and the right support.
//! Joint `k` is a contact face with centre `o_k`, unit normal `n_k` (from the body before it to
//! the body after it in chain order) and half width `b_k`; `t_k = (n_y, −n_x)`, corners
//! `R_k = o_k + b_k t_k` and `L_k = o_k − b_k t_k`. DOFs `[phĭ_0 … phĭ_J, phî_0 … phî_J]`:
//! `phĭ_k` rotates everything after joint `k` about `R_k` (admissible `<= 0`), `phî_k` about
//! `L_k` (admissible `>= 0`). A column is the open chain with `n = +y` at every joint.

pub mod arch;
mod closure;
pub mod colonnade;
pub mod system;
#[cfg(test)]
mod tests;
pub(crate) mod velocity;

use crate::validate::{self, InvalidValue};

/// A rigid body of a chain, in the reference (closed) geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Mass (kg).
    pub mass: f64,
    /// Moment of inertia about the centre of mass (kg m²).
    pub inertia: f64,
    /// Centre of mass (m).
    pub centre: [f64; 2],
}

/// A joint (contact face) of a chain, in the reference geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Joint {
    /// Centre `o_k` of the contact face (m).
    pub centre: [f64; 2],
    /// Unit normal `n_k`, from the body before the joint to the body after it in chain order.
    pub normal: [f64; 2],
    /// Half contact width `b_k` (m).
    pub half_width: f64,
}

impl Joint {
    /// `t_k = (n_y, −n_x)`: the normal turned clockwise by 90°.
    pub fn tangent(&self) -> [f64; 2] {
        [self.normal[1], -self.normal[0]]
    }

    /// Corner `R_k = o_k + b_k t_k`, pivot of `phĭ_k`.
    pub fn right_corner(&self) -> [f64; 2] {
        let t = self.tangent();
        [
            self.centre[0] + self.half_width * t[0],
            self.centre[1] + self.half_width * t[1],
        ]
    }

    /// Corner `L_k = o_k − b_k t_k`, pivot of `phî_k`.
    pub fn left_corner(&self) -> [f64; 2] {
        let t = self.tangent();
        [
            self.centre[0] - self.half_width * t[0],
            self.centre[1] - self.half_width * t[1],
        ]
    }
}

/// A validated chain: an open chain (as many joints as bodies) or a loop (one joint more).
#[derive(Clone, Debug, PartialEq)]
pub struct Chain {
    bodies: Vec<Body>,
    joints: Vec<Joint>,
    /// Each joint's corners `[R_k, L_k]` in the closed geometry ([`Joint::right_corner`],
    /// [`Joint::left_corner`]), computed once for [`Chain::pose_into`].
    corners: Vec<[[f64; 2]; 2]>,
}

/// A planar rigid map `x ↦ R(angle) x + shift` (the default is the identity).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RigidMap {
    /// Rotation angle (rad, counter-clockwise).
    pub angle: f64,
    /// Translation (m).
    pub shift: [f64; 2],
}

impl RigidMap {
    /// The identity.
    pub const IDENTITY: RigidMap = RigidMap {
        angle: 0.0,
        shift: [0.0, 0.0],
    };

    /// Image of a point.
    pub fn apply(&self, x: [f64; 2]) -> [f64; 2] {
        self.apply_with(self.angle.sin_cos(), x)
    }

    /// [`RigidMap::apply`] with `(sin, cos)` of the map's angle given (the same arithmetic).
    #[inline]
    fn apply_with(&self, (s, c): (f64, f64), x: [f64; 2]) -> [f64; 2] {
        [
            c * x[0] - s * x[1] + self.shift[0],
            s * x[0] + c * x[1] + self.shift[1],
        ]
    }

    /// This map followed by a rotation by `theta` about the (current) point `p`.
    pub fn then_rotate(&self, p: [f64; 2], theta: f64) -> RigidMap {
        let (s, c) = theta.sin_cos();
        let d = [self.shift[0] - p[0], self.shift[1] - p[1]];
        RigidMap {
            angle: self.angle + theta,
            shift: [c * d[0] - s * d[1] + p[0], s * d[0] + c * d[1] + p[1]],
        }
    }
}

/// The current geometry of a chain for given joint angles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChainPose {
    /// Current `R_k` of each joint (a material point of the body before it).
    pub right_pivots: Vec<[f64; 2]>,
    /// Current `L_k` of each joint.
    pub left_pivots: Vec<[f64; 2]>,
    /// Current centre of mass of each body.
    pub centres: Vec<[f64; 2]>,
    /// Current map of each body from the reference geometry.
    pub maps: Vec<RigidMap>,
    /// For a loop, the map of the right support implied by the angles (the identity when the
    /// loop is closed at position level).
    pub support: RigidMap,
    /// Suffix sums over the bodies after each joint: mass, centre of mass, polar moment about
    /// that centre (parallel-axis accumulation, no cancellation).
    suffix_mass: Vec<f64>,
    suffix_centre: Vec<[f64; 2]>,
    suffix_polar: Vec<f64>,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// 2D cross product `a × b = a_x b_y − a_y b_x`.
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// A DOF's share of the mass entries: its joint `k` (clamped to the bodies), pivot `p`, and the
/// suffix sums after `k` with `e = c_k − p`. The entry of a pair takes the sums of the larger
/// joint, and `c_k − P` of the other DOF's pivot is formed as before, so that every entry is
/// `s0 · dot(c_k − P_row, c_k − P_col) + I_k` with the same operations as
/// [`Chain::mass_entry_of`]'s.
#[derive(Clone, Copy)]
pub(crate) struct MassDof {
    k: usize,
    p: [f64; 2],
    s0: f64,
    g: [f64; 2],
    polar: f64,
    e: [f64; 2],
}

impl MassDof {
    #[inline]
    fn new(pose: &ChainPose, k: usize, p: [f64; 2]) -> MassDof {
        let g = pose.suffix_centre[k];
        MassDof {
            k,
            p,
            s0: pose.suffix_mass[k],
            g,
            polar: pose.suffix_polar[k],
            e: sub(g, p),
        }
    }

    /// The entry of the pair (`self` the row, `col` the column): the sums of `max(k_row, k_col)`.
    #[inline]
    fn entry(&self, col: &MassDof) -> f64 {
        let (s0, polar, d_row, d_col) = if col.k >= self.k {
            (col.s0, col.polar, sub(col.g, self.p), col.e)
        } else {
            (self.s0, self.polar, self.e, sub(self.g, col.p))
        };
        if s0 == 0.0 {
            0.0
        } else {
            s0 * dot(d_row, d_col) + polar
        }
    }
}

/// The rule of a chain built from finite dimensions whose derived geometry (a body's mass,
/// inertia or centre, a joint's centre) is not finite: the C helpers answer it with the overflow
/// code.
pub const TOO_LARGE: &str = "gives bodies or joints whose mass, inertia or position is not finite \
                             in double precision: too large (use other units)";

/// [`TOO_LARGE`] naming the shape's own fields (`field`, their values in `value`) when a body or
/// joint derived from them is not finite, before [`Chain::new`] would name a derived `bodies[j]`
/// the caller never gave.
pub(crate) fn check_derived(
    bodies: &[Body],
    joints: &[Joint],
    field: &str,
    value: impl FnOnce() -> String,
) -> Result<(), InvalidValue> {
    let finite = bodies.iter().all(|b| {
        b.mass.is_finite() && b.inertia.is_finite() && b.centre.iter().all(|c| c.is_finite())
    }) && joints.iter().all(|j| {
        j.centre
            .iter()
            .chain([&j.half_width])
            .all(|c| c.is_finite())
    });
    if finite {
        Ok(())
    } else {
        Err(InvalidValue {
            field: field.to_string(),
            value: value(),
            rule: TOO_LARGE,
        })
    }
}

impl Chain {
    /// Validates bodies and joints: masses and inertias finite and positive, centres finite,
    /// normals finite and non-zero (they are normalised), half widths finite and positive, and
    /// `joints.len()` equal to `bodies.len()` (open chain) or `bodies.len() + 1` (loop).
    pub fn new(bodies: Vec<Body>, mut joints: Vec<Joint>) -> Result<Chain, InvalidValue> {
        if bodies.is_empty() {
            return Err(InvalidValue::new(
                "bodies",
                0,
                "a chain needs at least one body",
            ));
        }
        if joints.len() != bodies.len() && joints.len() != bodies.len() + 1 {
            return Err(InvalidValue::new(
                "joints",
                joints.len(),
                "must be as many as the bodies (open chain) or one more (loop)",
            ));
        }
        for (j, b) in bodies.iter().enumerate() {
            validate::positive(format!("bodies[{j}].mass"), b.mass)?;
            validate::positive(format!("bodies[{j}].inertia"), b.inertia)?;
            validate::finite(format!("bodies[{j}].centre.x"), b.centre[0])?;
            validate::finite(format!("bodies[{j}].centre.y"), b.centre[1])?;
        }
        for (k, jt) in joints.iter_mut().enumerate() {
            validate::finite(format!("joints[{k}].centre.x"), jt.centre[0])?;
            validate::finite(format!("joints[{k}].centre.y"), jt.centre[1])?;
            validate::positive(format!("joints[{k}].half_width"), jt.half_width)?;
            let norm = jt.normal[0].hypot(jt.normal[1]);
            if !(norm.is_finite() && norm > 0.0) {
                return Err(InvalidValue::new(
                    format!("joints[{k}].normal"),
                    jt.normal,
                    "must be a finite non-zero vector",
                ));
            }
            jt.normal = [jt.normal[0] / norm, jt.normal[1] / norm];
        }
        let corners = joints
            .iter()
            .map(|j| [j.right_corner(), j.left_corner()])
            .collect();
        Ok(Chain {
            bodies,
            joints,
            corners,
        })
    }

    /// Number of bodies `N`.
    pub fn n_bodies(&self) -> usize {
        self.bodies.len()
    }

    /// Number of joints (`N` for an open chain, `N + 1` for a loop).
    pub fn n_joints(&self) -> usize {
        self.joints.len()
    }

    /// Number of DOFs, twice the number of joints.
    pub fn n_dofs(&self) -> usize {
        2 * self.joints.len()
    }

    /// Whether the chain ends on a right support.
    pub fn is_loop(&self) -> bool {
        self.joints.len() == self.bodies.len() + 1
    }

    /// The bodies in chain order.
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The joints in chain order (reference geometry).
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Total mass.
    pub fn total_mass(&self) -> f64 {
        self.bodies.iter().map(|b| b.mass).sum()
    }

    /// Current geometry for the DOF angles `phi` (length `2J`). Joint `k` rotates everything
    /// after it by `phĭ_k + phî_k` about the pivot of whichever DOF is non-zero (`R_k` if
    /// `phĭ_k ≠ 0`). Admissible signs are not checked here.
    pub fn pose(&self, phi: &[f64]) -> ChainPose {
        let mut pose = ChainPose::default();
        self.pose_into(phi, &mut pose);
        pose
    }

    /// [`Chain::pose`] into an existing pose, reusing its memory (the driver's hot path).
    pub fn pose_into(&self, phi: &[f64], pose: &mut ChainPose) {
        let nj = self.n_joints();
        assert_eq!(phi.len(), 2 * nj, "phi must have 2 entries per joint");
        let nb = self.n_bodies();
        pose.right_pivots.clear();
        pose.left_pivots.clear();
        pose.centres.clear();
        pose.maps.clear();
        // One allocation each for a new pose (not one growth per push).
        pose.right_pivots.reserve(nj);
        pose.left_pivots.reserve(nj);
        pose.centres.reserve(nb);
        pose.maps.reserve(nb);
        pose.support = RigidMap::IDENTITY;
        let mut map = RigidMap::IDENTITY;
        // `sin_cos` of the map's angle, taken again only when the map turns.
        let mut sc = map.angle.sin_cos();
        for (k, &[r, l]) in self.corners.iter().enumerate() {
            let right = map.apply_with(sc, r);
            let left = map.apply_with(sc, l);
            let (theta, pivot) = if phi[k] != 0.0 {
                (phi[k], right)
            } else {
                (phi[nj + k], left)
            };
            if theta != 0.0 {
                map = map.then_rotate(pivot, theta);
                sc = map.angle.sin_cos();
            }
            pose.right_pivots.push(right);
            pose.left_pivots.push(left);
            if k < nb {
                pose.centres.push(map.apply_with(sc, self.bodies[k].centre));
                pose.maps.push(map);
            } else {
                pose.support = map;
            }
        }
        // Suffix sums over bodies j >= k (parallel-axis accumulation).
        pose.suffix_mass.clear();
        pose.suffix_mass.resize(nb + 1, 0.0);
        pose.suffix_centre.clear();
        pose.suffix_centre.resize(nb + 1, [0.0; 2]);
        pose.suffix_polar.clear();
        pose.suffix_polar.resize(nb + 1, 0.0);
        for j in (0..nb).rev() {
            let (m, c, i) = (self.bodies[j].mass, pose.centres[j], self.bodies[j].inertia);
            let (m1, c1, j1) = (
                pose.suffix_mass[j + 1],
                pose.suffix_centre[j + 1],
                pose.suffix_polar[j + 1],
            );
            let s0 = m + m1;
            let g = [(m * c[0] + m1 * c1[0]) / s0, (m * c[1] + m1 * c1[1]) / s0];
            let d = sub(c, g);
            let d1 = sub(c1, g);
            pose.suffix_mass[j] = s0;
            pose.suffix_centre[j] = g;
            pose.suffix_polar[j] = j1 + m1 * dot(d1, d1) + i + m * dot(d, d);
        }
    }

    /// The joint and the pivot of DOF `a` in the pose, for [`Chain::mass_entry_of`].
    #[inline]
    pub fn dof_pivot(&self, pose: &ChainPose, a: usize) -> (usize, [f64; 2]) {
        let nj = self.n_joints();
        (if a < nj { a } else { a - nj }, self.pivot(pose, a))
    }

    /// [`Chain::mass_entry`] of two DOFs given by [`Chain::dof_pivot`] (the same arithmetic,
    /// without finding the joints and pivots again in a loop over pairs).
    #[inline]
    pub fn mass_entry_of(
        &self,
        pose: &ChainPose,
        (ka, pa): (usize, [f64; 2]),
        (kb, pb): (usize, [f64; 2]),
    ) -> f64 {
        let k = ka.max(kb).min(self.n_bodies());
        let s0 = pose.suffix_mass[k];
        if s0 == 0.0 {
            return 0.0;
        }
        let g = pose.suffix_centre[k];
        s0 * dot(sub(g, pa), sub(g, pb)) + pose.suffix_polar[k]
    }

    /// The entries [`Chain::mass_entry_of`] of every pair of the DOFs `dofs` (given by
    /// [`Chain::dof_pivot`]) into the leading `dofs.len()` square of the row-major matrix `out` of
    /// row length `stride`, both triangles (the same arithmetic: `max(j_a, j_b).min(N)` is the
    /// larger of the clamped joints).
    pub fn mass_block_into(
        &self,
        pose: &ChainPose,
        dofs: &[(usize, [f64; 2])],
        out: &mut [f64],
        stride: usize,
    ) {
        let nb = self.n_bodies();
        let (mass, centre, polar) = (
            &pose.suffix_mass[..=nb],
            &pose.suffix_centre[..=nb],
            &pose.suffix_polar[..=nb],
        );
        for (i, &(ka, pa)) in dofs.iter().enumerate() {
            let ka = ka.min(nb);
            for (j, &(kb, pb)) in dofs.iter().enumerate().skip(i) {
                let k = ka.max(kb.min(nb));
                let s0 = mass[k];
                let v = if s0 == 0.0 {
                    0.0
                } else {
                    let g = centre[k];
                    s0 * dot(sub(g, pa), sub(g, pb)) + polar[k]
                };
                out[i * stride + j] = v;
                out[j * stride + i] = v;
            }
        }
    }

    /// Entry `M[a][b]` of the mass matrix of the cut chain in the pose ([`Chain::mass_matrix`]).
    #[inline]
    pub fn mass_entry(&self, pose: &ChainPose, a: usize, b: usize) -> f64 {
        self.mass_entry_of(pose, self.dof_pivot(pose, a), self.dof_pivot(pose, b))
    }

    /// Entry `q[a]` of the load vector ([`Chain::load_vector`]).
    #[inline]
    pub fn load_entry(&self, pose: &ChainPose, a: usize, ground_acc: f64, gravity: f64) -> f64 {
        let nj = self.n_joints();
        let k = (if a < nj { a } else { a - nj }).min(self.n_bodies());
        let s0 = pose.suffix_mass[k];
        if s0 == 0.0 {
            return 0.0;
        }
        s0 * cross(
            sub(pose.suffix_centre[k], self.pivot(pose, a)),
            [-ground_acc, -gravity],
        )
    }

    /// Pivot of DOF `a` in the pose.
    #[inline]
    pub fn pivot(&self, pose: &ChainPose, a: usize) -> [f64; 2] {
        let nj = self.n_joints();
        if a < nj {
            pose.right_pivots[a]
        } else {
            pose.left_pivots[a - nj]
        }
    }

    /// Full `2J × 2J` mass matrix of the cut chain in the pose, row-major:
    /// `M[a][b] = Σ_{j after both joints} ( m_j (c_j − P_a)·(c_j − P_b) + I_j )`. In a loop the
    /// last joint's rows and columns are zero (it moves no mass).
    pub fn mass_matrix(&self, pose: &ChainPose) -> Vec<f64> {
        let mut out = Vec::new();
        self.mass_matrix_with(pose, &mut out, &mut Vec::new());
        out
    }

    /// [`Chain::mass_matrix`] into `out` (cleared first), with `dofs` as scratch: both reuse
    /// their memory (the loop driver's impacts).
    pub(crate) fn mass_matrix_with(
        &self,
        pose: &ChainPose,
        out: &mut Vec<f64>,
        dofs: &mut Vec<MassDof>,
    ) {
        let (nj, m) = (self.n_joints(), self.n_dofs());
        let nb = self.n_bodies();
        // Each DOF's joint (clamped to the bodies: `max(j_a, j_b).min(N)` is the larger of the
        // clamped joints) and pivot once (the entries' arithmetic as before).
        dofs.clear();
        dofs.extend((0..m).map(|a| MassDof::new(pose, (a % nj).min(nb), self.pivot(pose, a))));
        // Row by row without a zero fill (a zeroed allocation of this size costs more than the
        // rows): the entries left of the diagonal copied from the rows above.
        out.clear();
        out.reserve(m * m);
        for (a, row) in dofs.iter().enumerate() {
            for b in 0..a {
                let v = out[b * m + a];
                out.push(v);
            }
            out.extend(dofs[a..].iter().map(|col| row.entry(col)));
        }
    }

    /// Load vector `q` (length `2J`) for a horizontal ground acceleration `ground_acc` and gravity
    /// `gravity` (positive downwards): the inertial forces `F_j = m_j (−a_g, −g)` about each
    /// DOF's pivot, `q[a] = Σ_{j after joint} (c_j − P_a) × F_j`.
    pub fn load_vector(&self, pose: &ChainPose, ground_acc: f64, gravity: f64) -> Vec<f64> {
        let (nj, nb) = (self.n_joints(), self.n_bodies());
        let f = [-ground_acc, -gravity];
        (0..self.n_dofs())
            .map(|a| {
                let k = (a % nj).min(nb);
                let s0 = pose.suffix_mass[k];
                if s0 == 0.0 {
                    return 0.0;
                }
                s0 * cross(sub(pose.suffix_centre[k], self.pivot(pose, a)), f)
            })
            .collect()
    }
}
