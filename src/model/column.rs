//! Column geometry and the interface mass matrix (SPEC §1, thesis Eq. 4–6 and Appendix C).
//!
//! A column is a stack of rigid blocks, bottom (index 0) to top. Interface `k` is the joint under
//! block `k`. Every interface has two rotational degrees of freedom, ordered
//! `phi = [phĭ_0 … phĭ_{n-1}, phî_0 … phî_{n-1}]`: `phĭ_k` is the rotation of everything above
//! interface `k` about its RIGHT corner (admissible `<= 0`), `phî_k` about its LEFT corner
//! (admissible `>= 0`). Angles are counter-clockwise positive, x to the right, y up.
//!
//! The geometry is recomputed from the angles (large rotations), and the mass matrix and load
//! vector are those of the current, rotated geometry:
//! `M[a][b] = Σ_{j ≥ max(k_a, k_b)} ( m_j (c_j − P_a)·(c_j − P_b) + I_j )` and
//! `q[a] = Σ_{j ≥ k_a} ( −(c_j − P_a)_y F_jx + (c_j − P_a)_x F_jy )` with
//! `F_j = (−m_j a_g, −m_j g)`. This is exactly `BᵀMB` and `Bᵀp` of thesis Appendix C.

use std::fmt;

/// Standard acceleration of gravity used by the thesis (m/s²).
pub const GRAVITY: f64 = 9.81;

/// One rigid block of a column.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Width `w` (m).
    pub width: f64,
    /// Height `h` (m).
    pub height: f64,
    /// Mass `m` (kg).
    pub mass: f64,
    /// Moment of inertia about the centre of mass (kg m²); `None` is the uniform rectangle
    /// `m (w² + h²) / 12`.
    pub inertia: Option<f64>,
    /// Width of the contact under this block (its interface with the block below or the ground);
    /// `None` is `min(w_{k-1}, w_k)` (`w_0` on the ground). Cut corners (thesis Fig. 59, Table 1)
    /// and the experiments of section 4 have narrower contacts than the blocks.
    pub contact_width: Option<f64>,
}

impl Block {
    /// A uniform rectangular block with full contact.
    pub fn rectangle(width: f64, height: f64, mass: f64) -> Block {
        Block {
            width,
            height,
            mass,
            inertia: None,
            contact_width: None,
        }
    }
}

/// Why a column could not be built.
#[derive(Clone, Debug, PartialEq)]
pub enum ColumnError {
    /// A column needs at least one block.
    Empty,
    /// A block's field is not a finite positive number (or, for the contact, wider than a block).
    InvalidBlock {
        /// 0-based block index, bottom = 0.
        block: usize,
        /// Field name (`width`, `height`, `mass`, `inertia`, `contact_width`).
        field: &'static str,
        /// The offending value.
        value: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
}

impl fmt::Display for ColumnError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ColumnError::Empty => write!(f, "a column needs at least one block"),
            ColumnError::InvalidBlock {
                block,
                field,
                value,
                reason,
            } => write!(f, "block {block}: {field} = {value}: {reason}"),
        }
    }
}

impl std::error::Error for ColumnError {}

/// A validated column of rigid blocks with its reference (straight) geometry.
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    blocks: Vec<Block>,
    /// Half contact width `b_k` of each interface.
    half_contact: Vec<f64>,
    /// Height of interface `k` in the straight column, `Σ_{j<k} h_j`.
    base_height: Vec<f64>,
    /// Moment of inertia of each block about its centre.
    inertia: Vec<f64>,
}

impl Column {
    /// Validates the blocks and precomputes the reference geometry.
    pub fn new(blocks: Vec<Block>) -> Result<Column, ColumnError> {
        if blocks.is_empty() {
            return Err(ColumnError::Empty);
        }
        let positive = |block: usize, field: &'static str, value: f64| {
            if value.is_finite() && value > 0.0 {
                Ok(())
            } else {
                Err(ColumnError::InvalidBlock {
                    block,
                    field,
                    value,
                    reason: "must be a finite number greater than zero",
                })
            }
        };
        let mut half_contact = Vec::with_capacity(blocks.len());
        let mut base_height = Vec::with_capacity(blocks.len());
        let mut inertia = Vec::with_capacity(blocks.len());
        let mut y = 0.0;
        for (k, b) in blocks.iter().enumerate() {
            positive(k, "width", b.width)?;
            positive(k, "height", b.height)?;
            positive(k, "mass", b.mass)?;
            let i = b
                .inertia
                .unwrap_or(b.mass * (b.width * b.width + b.height * b.height) / 12.0);
            positive(k, "inertia", i)?;
            let widest = if k == 0 {
                b.width
            } else {
                b.width.min(blocks[k - 1].width)
            };
            let contact = b.contact_width.unwrap_or(widest);
            positive(k, "contact_width", contact)?;
            if contact > widest * (1.0 + 1e-12) {
                return Err(ColumnError::InvalidBlock {
                    block: k,
                    field: "contact_width",
                    value: contact,
                    reason: "is wider than the blocks it joins",
                });
            }
            half_contact.push(0.5 * contact);
            base_height.push(y);
            inertia.push(i);
            y += b.height;
        }
        Ok(Column {
            blocks,
            half_contact,
            base_height,
            inertia,
        })
    }

    /// A column of `n` equal uniform rectangular blocks stacked to the given total height.
    pub fn uniform(
        n: usize,
        width: f64,
        total_height: f64,
        total_mass: f64,
    ) -> Result<Column, ColumnError> {
        let h = total_height / n as f64;
        let m = total_mass / n as f64;
        Column::new((0..n).map(|_| Block::rectangle(width, h, m)).collect())
    }

    /// Number of blocks, equal to the number of interfaces `n`.
    pub fn n_interfaces(&self) -> usize {
        self.blocks.len()
    }

    /// Number of rotational DOFs, `2n`.
    pub fn n_dofs(&self) -> usize {
        2 * self.blocks.len()
    }

    /// The blocks, bottom to top.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// Half contact width `b_k` of interface `k`.
    pub fn half_contact_width(&self, k: usize) -> f64 {
        self.half_contact[k]
    }

    /// Moment of inertia of block `k` about its centre.
    pub fn inertia(&self, k: usize) -> f64 {
        self.inertia[k]
    }

    /// Total height of the straight column.
    pub fn total_height(&self) -> f64 {
        self.blocks.iter().map(|b| b.height).sum()
    }

    /// Total mass.
    pub fn total_mass(&self) -> f64 {
        self.blocks.iter().map(|b| b.mass).sum()
    }

    /// Current geometry for the DOF angles `phi` (length `2n`). Each interface rotates by
    /// `phĭ_k + phî_k` about the pivot of whichever DOF is non-zero (right corner if `phĭ_k ≠ 0`).
    /// Admissible signs are not checked here; see [`crate::model::configuration`].
    pub fn pose(&self, phi: &[f64]) -> Pose {
        let mut pose = Pose::with_capacity(self.n_interfaces());
        self.pose_into(phi, &mut pose);
        pose
    }

    /// [`Column::pose`] into a reused buffer (no allocation once the buffer has grown).
    pub fn pose_into(&self, phi: &[f64], pose: &mut Pose) {
        let n = self.n_interfaces();
        assert_eq!(phi.len(), 2 * n, "phi must have 2n entries");
        pose.clear();
        // Current rigid map of the block below: x ↦ R(alpha) x + t (the ground is the identity).
        let mut alpha = 0.0_f64;
        let (mut ca, mut sa) = (1.0_f64, 0.0_f64);
        let mut t = [0.0_f64, 0.0];
        for k in 0..n {
            let b = self.half_contact[k];
            let y = self.base_height[k];
            let map = |p: [f64; 2], ca: f64, sa: f64, t: [f64; 2]| {
                [ca * p[0] - sa * p[1] + t[0], sa * p[0] + ca * p[1] + t[1]]
            };
            let right = map([b, y], ca, sa, t);
            let left = map([-b, y], ca, sa, t);
            let (theta, pref) = if phi[k] != 0.0 {
                (phi[k], [b, y])
            } else {
                (phi[n + k], [-b, y])
            };
            if theta != 0.0 {
                // T_k(r) = R_{α+θ} r + R_α (p − R_θ p) + t
                let (ct, st) = (theta.cos(), theta.sin());
                let d = [
                    pref[0] - (ct * pref[0] - st * pref[1]),
                    pref[1] - (st * pref[0] + ct * pref[1]),
                ];
                t = [ca * d[0] - sa * d[1] + t[0], sa * d[0] + ca * d[1] + t[1]];
                alpha += theta;
                ca = alpha.cos();
                sa = alpha.sin();
            }
            let centre = map([0.0, y + 0.5 * self.blocks[k].height], ca, sa, t);
            pose.right_pivots.push(right);
            pose.left_pivots.push(left);
            pose.centres.push(centre);
            pose.block_angles.push(alpha);
        }
        pose.update_sums(self);
    }

    /// Full `2n × 2n` mass matrix of the current geometry, row-major (it is symmetric).
    pub fn mass_matrix(&self, pose: &Pose) -> Vec<f64> {
        let m = self.n_dofs();
        let mut out = vec![0.0; m * m];
        self.mass_matrix_into(pose, &mut out);
        out
    }

    /// [`Column::mass_matrix`] into `out` (length `4n²`).
    pub fn mass_matrix_into(&self, pose: &Pose, out: &mut [f64]) {
        let m = self.n_dofs();
        assert_eq!(out.len(), m * m);
        for a in 0..m {
            for b in a..m {
                let v = pose.mass_entry(a, b);
                out[a * m + b] = v;
                out[b * m + a] = v;
            }
        }
    }

    /// Mass matrix restricted to the DOFs `dofs` (indices into `0..2n`), row-major
    /// `dofs.len()²` into `out`. The driver assembles only the open DOFs with this.
    pub fn mass_submatrix_into(&self, pose: &Pose, dofs: &[usize], out: &mut [f64]) {
        let m = dofs.len();
        assert_eq!(out.len(), m * m);
        for (r, &a) in dofs.iter().enumerate() {
            for (c, &b) in dofs.iter().enumerate().skip(r) {
                let v = pose.mass_entry(a, b);
                out[r * m + c] = v;
                out[c * m + r] = v;
            }
        }
    }

    /// Load vector `q` (length `2n`) for horizontal ground acceleration `ground_acc` and gravity
    /// `gravity` (both m/s², gravity positive downwards), in the current geometry.
    pub fn load_vector(&self, pose: &Pose, ground_acc: f64, gravity: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.n_dofs()];
        self.load_vector_into(pose, ground_acc, gravity, &mut out);
        out
    }

    /// [`Column::load_vector`] into `out` (length `2n`).
    pub fn load_vector_into(&self, pose: &Pose, ground_acc: f64, gravity: f64, out: &mut [f64]) {
        assert_eq!(out.len(), self.n_dofs());
        for (a, o) in out.iter_mut().enumerate() {
            *o = pose.load_entry(a, ground_acc, gravity);
        }
    }

    /// Velocity-dependent generalised forces that the thesis's Eq. 6 leaves out (centripetal
    /// terms of the exact Lagrangian equations), for DOF rates `rates` (length `2n`), written to
    /// `out` (length `2n`). The exact equations are `M φ̈ = q + out`.
    ///
    /// With `φ̈ = 0` every block still accelerates centripetally:
    /// `a(r on block j) = a(P_j) − ω_j² (r − P_j)`, where `P_j` is the active pivot of interface
    /// `j` (a material point of both blocks it joins) and `ω_j` the angular velocity of block `j`.
    /// The generalised force is `−Σ_{j ≥ k_a} m_j (c_j − P_a) × a_c(c_j)`.
    pub fn velocity_load_into(&self, pose: &Pose, phi: &[f64], rates: &[f64], out: &mut [f64]) {
        let n = self.n_interfaces();
        assert_eq!(rates.len(), 2 * n);
        assert_eq!(phi.len(), 2 * n);
        assert_eq!(out.len(), 2 * n);
        // Accelerations of the block centres with zero DOF accelerations.
        let mut centre_acc = vec![[0.0_f64; 2]; n];
        let mut omega = 0.0_f64;
        // Hinge point of the previous interface and its acceleration (ground: at rest).
        let mut hinge = [0.0_f64, 0.0];
        let mut hinge_acc = [0.0_f64, 0.0];
        for j in 0..n {
            let use_right = phi[j] != 0.0 || (phi[n + j] == 0.0 && rates[j] != 0.0);
            let p = if use_right {
                pose.right_pivots[j]
            } else {
                pose.left_pivots[j]
            };
            // Acceleration of the new hinge as a point of the block below.
            let acc_p = [
                hinge_acc[0] - omega * omega * (p[0] - hinge[0]),
                hinge_acc[1] - omega * omega * (p[1] - hinge[1]),
            ];
            omega += rates[j] + rates[n + j];
            let c = pose.centres[j];
            centre_acc[j] = [
                acc_p[0] - omega * omega * (c[0] - p[0]),
                acc_p[1] - omega * omega * (c[1] - p[1]),
            ];
            hinge = p;
            hinge_acc = acc_p;
        }
        for (a, o) in out.iter_mut().enumerate() {
            let k = a % n;
            let p = if a < n {
                pose.right_pivots[k]
            } else {
                pose.left_pivots[k]
            };
            let mut s = 0.0;
            for j in k..n {
                let r = [pose.centres[j][0] - p[0], pose.centres[j][1] - p[1]];
                let ac = centre_acc[j];
                s -= self.blocks[j].mass * (r[0] * ac[1] - r[1] * ac[0]);
            }
            *o = s;
        }
    }

    /// Position of the centre of mass of the part of the column above interface `k`.
    pub fn centre_of_mass_above(&self, pose: &Pose, k: usize) -> [f64; 2] {
        let m = pose.suffix_mass[k];
        [pose.suffix_moment[k][0] / m, pose.suffix_moment[k][1] / m]
    }

    /// Horizontal ground acceleration at which a straight column starts to rock (static):
    /// the smallest `a_g` that tips the part above some interface about one of its corners.
    /// For a single uniform block this is `g tan δ` (thesis Eq. 3).
    pub fn static_uplift_acceleration(&self, gravity: f64) -> f64 {
        let pose = self.pose(&vec![0.0; self.n_dofs()]);
        (0..self.n_interfaces())
            .map(|k| {
                let c = self.centre_of_mass_above(&pose, k);
                let lever = c[1] - self.base_height[k];
                gravity * self.half_contact[k] / lever
            })
            .fold(f64::INFINITY, f64::min)
    }
}

/// Current positions of the pivots and block centres, with the suffix sums that make each mass
/// matrix entry an O(1) computation.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Pose {
    /// Current right corner of each interface (pivot of `phĭ_k`).
    pub right_pivots: Vec<[f64; 2]>,
    /// Current left corner of each interface (pivot of `phî_k`).
    pub left_pivots: Vec<[f64; 2]>,
    /// Current centre of mass of each block.
    pub centres: Vec<[f64; 2]>,
    /// Absolute rotation of each block (sum of the interface angles below and at it).
    pub block_angles: Vec<f64>,
    suffix_mass: Vec<f64>,
    suffix_moment: Vec<[f64; 2]>,
    suffix_second: Vec<f64>,
    suffix_inertia: Vec<f64>,
}

impl Pose {
    fn with_capacity(n: usize) -> Pose {
        Pose {
            right_pivots: Vec::with_capacity(n),
            left_pivots: Vec::with_capacity(n),
            centres: Vec::with_capacity(n),
            block_angles: Vec::with_capacity(n),
            suffix_mass: Vec::with_capacity(n),
            suffix_moment: Vec::with_capacity(n),
            suffix_second: Vec::with_capacity(n),
            suffix_inertia: Vec::with_capacity(n),
        }
    }

    fn clear(&mut self) {
        self.right_pivots.clear();
        self.left_pivots.clear();
        self.centres.clear();
        self.block_angles.clear();
        self.suffix_mass.clear();
        self.suffix_moment.clear();
        self.suffix_second.clear();
        self.suffix_inertia.clear();
    }

    fn update_sums(&mut self, column: &Column) {
        let n = self.centres.len();
        self.suffix_mass.resize(n, 0.0);
        self.suffix_moment.resize(n, [0.0; 2]);
        self.suffix_second.resize(n, 0.0);
        self.suffix_inertia.resize(n, 0.0);
        let (mut s0, mut s1, mut s2, mut si) = (0.0, [0.0, 0.0], 0.0, 0.0);
        for j in (0..n).rev() {
            let m = column.blocks[j].mass;
            let c = self.centres[j];
            s0 += m;
            s1 = [s1[0] + m * c[0], s1[1] + m * c[1]];
            s2 += m * (c[0] * c[0] + c[1] * c[1]);
            si += column.inertia[j];
            self.suffix_mass[j] = s0;
            self.suffix_moment[j] = s1;
            self.suffix_second[j] = s2;
            self.suffix_inertia[j] = si;
        }
    }

    fn pivot(&self, a: usize) -> [f64; 2] {
        let n = self.centres.len();
        if a < n {
            self.right_pivots[a]
        } else {
            self.left_pivots[a - n]
        }
    }

    /// Entry `M[a][b]` of the mass matrix:
    /// `Σ_{j≥K} m_j |c_j|² − (P_a + P_b)·Σ m_j c_j + P_a·P_b Σ m_j + Σ I_j`, `K = max(k_a, k_b)`.
    ///
    /// The expanded form loses digits when the column is far from the pivots compared with its
    /// size, so the entry is evaluated as `Σ m_j (c_j − P_a)·(c_j − P_b)` about the centre of mass
    /// of the part above: `S0 (g − P_a)·(g − P_b) + (S2 − S0 |g|²) + ΣI`.
    pub fn mass_entry(&self, a: usize, b: usize) -> f64 {
        let n = self.centres.len();
        let k = (a % n).max(b % n);
        let pa = self.pivot(a);
        let pb = self.pivot(b);
        let s0 = self.suffix_mass[k];
        let s1 = self.suffix_moment[k];
        let g = [s1[0] / s0, s1[1] / s0];
        let spread = self.suffix_second[k] - s0 * (g[0] * g[0] + g[1] * g[1]);
        s0 * ((g[0] - pa[0]) * (g[0] - pb[0]) + (g[1] - pa[1]) * (g[1] - pb[1]))
            + spread.max(0.0)
            + self.suffix_inertia[k]
    }

    /// Entry `q[a]` of the load vector: `a_g (S1y − S0 P_ay) − g (S1x − S0 P_ax)` over `j ≥ k_a`.
    pub fn load_entry(&self, a: usize, ground_acc: f64, gravity: f64) -> f64 {
        let n = self.centres.len();
        let k = a % n;
        let p = self.pivot(a);
        let s0 = self.suffix_mass[k];
        let s1 = self.suffix_moment[k];
        ground_acc * (s1[1] - s0 * p[1]) - gravity * (s1[0] - s0 * p[0])
    }

    /// Total mass of the part above interface `k` and its centre of mass.
    pub fn mass_above(&self, k: usize) -> (f64, [f64; 2]) {
        let s0 = self.suffix_mass[k];
        (
            s0,
            [self.suffix_moment[k][0] / s0, self.suffix_moment[k][1] / s0],
        )
    }
}

/// The FE route of thesis Appendix C: `M̃ = BᵀMB` and `p̃ = Bᵀp` for a nodal mass matrix `M`
/// (`n_nodal × n_nodal`), a transformation `B` (`n_nodal × n_reduced`, nodal displacements from
/// reduced coordinates, Eq. C2) and nodal loads `p`. All matrices are column-major
/// (LAPACK / OpenSees `Matrix` storage). Outputs: `reduced_mass` (`n_reduced²`, column-major)
/// and `reduced_load` (`n_reduced`).
pub fn reduce(
    n_nodal: usize,
    n_reduced: usize,
    nodal_mass: &[f64],
    transformation: &[f64],
    nodal_load: &[f64],
    reduced_mass: &mut [f64],
    reduced_load: &mut [f64],
) {
    assert_eq!(nodal_mass.len(), n_nodal * n_nodal);
    assert_eq!(transformation.len(), n_nodal * n_reduced);
    assert_eq!(nodal_load.len(), n_nodal);
    assert_eq!(reduced_mass.len(), n_reduced * n_reduced);
    assert_eq!(reduced_load.len(), n_reduced);
    let bcol = |c: usize| &transformation[c * n_nodal..(c + 1) * n_nodal];
    // MB, column by column.
    let mut mb = vec![0.0; n_nodal];
    for c in 0..n_reduced {
        let b = bcol(c);
        for (r, v) in mb.iter_mut().enumerate() {
            *v = (0..n_nodal)
                .map(|k| nodal_mass[k * n_nodal + r] * b[k])
                .sum();
        }
        for r in 0..n_reduced {
            reduced_mass[c * n_reduced + r] = bcol(r).iter().zip(&mb).map(|(x, y)| x * y).sum();
        }
        reduced_load[c] = b.iter().zip(nodal_load).map(|(x, y)| x * y).sum();
    }
}

/// Three mass points per block (thesis Appendix C): on the block's axis at its bottom, centre
/// and top, with end masses `I / (2 (h/2)²)` and the rest in the middle, so that mass, centre and
/// moment of inertia are reproduced. Returns `(points, masses)` for the current geometry, block by
/// block (bottom, centre, top).
pub fn three_mass_points(column: &Column, pose: &Pose) -> Vec<([f64; 2], f64)> {
    let mut out = Vec::with_capacity(3 * column.n_interfaces());
    for (j, block) in column.blocks.iter().enumerate() {
        let half = 0.5 * block.height;
        let end = column.inertia[j] / (2.0 * half * half);
        let c = pose.centres[j];
        let a = pose.block_angles[j];
        // The block's axis in the current geometry.
        let axis = [-a.sin() * half, a.cos() * half];
        out.push(([c[0] - axis[0], c[1] - axis[1]], end));
        out.push((c, block.mass - 2.0 * end));
        out.push(([c[0] + axis[0], c[1] + axis[1]], end));
    }
    out
}

/// Transformation `B` of Appendix C (Eq. C2, C11, C14) from the `2n` interface DOFs to the
/// x and y displacements of the given points: `points[i]` belongs to block `owner[i]`. Rows are
/// all x components then all y components (`2·points` rows), column-major storage.
pub fn transformation_matrix(
    column: &Column,
    pose: &Pose,
    points: &[[f64; 2]],
    owner: &[usize],
) -> Vec<f64> {
    assert_eq!(points.len(), owner.len());
    let n = column.n_interfaces();
    let rows = 2 * points.len();
    let mut b = vec![0.0; rows * 2 * n];
    for a in 0..2 * n {
        let k = a % n;
        let p = pose.pivot(a);
        for (i, (r, &j)) in points.iter().zip(owner).enumerate() {
            if j >= k {
                // ẑ × (r − P) = (−(r−P)_y, (r−P)_x)
                b[a * rows + i] = -(r[1] - p[1]);
                b[a * rows + points.len() + i] = r[0] - p[0];
            }
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_granite() -> Column {
        Column::new(vec![
            Block::rectangle(0.1, 0.3, 15.0),
            Block::rectangle(0.1, 0.3, 15.0),
        ])
        .unwrap()
    }

    /// Thesis Eq. 10: the 4×4 mass matrix of two 0.1 × 0.3 m, 15 kg blocks.
    #[test]
    fn thesis_eq10_mass_matrix() {
        let col = two_granite();
        let m = col.mass_matrix(&col.pose(&[0.0; 4]));
        let expected = [
            [3.700, 1.175, 3.550, 1.100],
            [1.175, 0.500, 1.100, 0.425],
            [3.550, 1.100, 3.700, 1.175],
            [1.100, 0.425, 1.175, 0.500],
        ];
        for r in 0..4 {
            for c in 0..4 {
                assert!(
                    (m[r * 4 + c] - expected[r][c]).abs() < 5e-4,
                    "M[{r}][{c}] = {}",
                    m[r * 4 + c]
                );
            }
        }
    }

    fn appendix_c_column() -> Column {
        Column::new(vec![
            Block::rectangle(1.0, 4.0, 1.0),
            Block::rectangle(1.0, 4.0, 1.0),
        ])
        .unwrap()
    }

    /// Round to the printed digits and compare (`printed` has `decimals` decimals).
    fn printed(value: f64, printed: f64, decimals: i32) {
        let scale = 10f64.powi(decimals);
        assert_eq!(
            (value * scale).round() / scale,
            printed,
            "{value} does not print as {printed}"
        );
    }

    /// Appendix C, straight: `M̃` Eq. C13 and `p̃` Eq. C12 (rotations about the right corners).
    #[test]
    fn appendix_c_straight() {
        let col = appendix_c_column();
        let pose = col.pose(&[0.0; 4]);
        let m = col.mass_matrix(&pose);
        let q = col.load_vector(&pose, -1.0, GRAVITY);
        printed(m[0], 43.333, 3);
        printed(m[1], 13.667, 3);
        printed(m[4 + 1], 5.667, 3);
        printed(q[0], 1.810, 3);
        printed(q[1], 2.905, 3);
    }

    /// Appendix C, upper block inclined by 10° about its right corner: Eq. C15 and C16.
    #[test]
    fn appendix_c_inclined() {
        let col = appendix_c_column();
        let phi = [0.0, -10f64.to_radians(), 0.0, 0.0];
        let pose = col.pose(&phi);
        let m = col.mass_matrix(&pose);
        let q = col.load_vector(&pose, -1.0, GRAVITY);
        printed(m[0], 43.785, 3);
        printed(m[1], 13.892, 3);
        printed(m[4 + 1], 5.667, 3);
        printed(q[0], -1.728, 3);
        printed(q[1], -0.633, 3);
    }

    /// The FE route gives the same numbers: three mass points per block, `B` from the geometry,
    /// `BᵀMB`, `Bᵀp` (thesis Eq. C9–C16).
    #[test]
    fn appendix_c_reduction_matches_direct_route() {
        let col = appendix_c_column();
        for phi in [
            [0.0, 0.0, 0.0, 0.0],
            [0.0, -10f64.to_radians(), 0.0, 0.0],
            [-0.05, 0.0, 0.0, 0.2],
        ] {
            let pose = col.pose(&phi);
            let pts = three_mass_points(&col, &pose);
            let np = pts.len();
            let points: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
            let owner: Vec<usize> = (0..np).map(|i| i / 3).collect();
            let b = transformation_matrix(&col, &pose, &points, &owner);
            let nn = 2 * np;
            let mut nodal_mass = vec![0.0; nn * nn];
            let mut nodal_load = vec![0.0; nn];
            for (i, (_, m)) in pts.iter().enumerate() {
                nodal_mass[i * nn + i] = *m;
                nodal_mass[(np + i) * nn + np + i] = *m;
                nodal_load[i] = -m * -1.0;
                nodal_load[np + i] = -m * GRAVITY;
            }
            let mut rm = vec![0.0; 16];
            let mut rl = vec![0.0; 4];
            reduce(nn, 4, &nodal_mass, &b, &nodal_load, &mut rm, &mut rl);
            let m = col.mass_matrix(&pose);
            let q = col.load_vector(&pose, -1.0, GRAVITY);
            for i in 0..16 {
                assert!((rm[i] - m[i]).abs() < 1e-10, "{i}: {} vs {}", rm[i], m[i]);
            }
            for i in 0..4 {
                assert!((rl[i] - q[i]).abs() < 1e-10);
            }
        }
    }

    #[test]
    fn single_block_matches_appendix_b() {
        // Eq. B7: θ0 = 4/3 m (h² + b²), θ1 = 4/3 m (h² − b²/2) with 2h × 2b.
        let (h, b, m) = (1.3, 0.4, 7.0);
        let col = Column::new(vec![Block::rectangle(2.0 * b, 2.0 * h, m)]).unwrap();
        let mm = col.mass_matrix(&col.pose(&[0.0, 0.0]));
        assert!((mm[0] - 4.0 / 3.0 * m * (h * h + b * b)).abs() < 1e-12);
        assert!((mm[1] - 4.0 / 3.0 * m * (h * h - 0.5 * b * b)).abs() < 1e-12);
        assert!((col.static_uplift_acceleration(GRAVITY) - GRAVITY * b / h).abs() < 1e-12);
    }

    /// The velocity terms are the exact Lagrangian ones: compare with a finite-difference
    /// derivative of the centre velocities for a two-block chain.
    #[test]
    fn velocity_load_matches_finite_differences() {
        let col = Column::new(vec![
            Block::rectangle(0.4, 1.2, 3.0),
            Block::rectangle(0.3, 0.9, 2.0),
        ])
        .unwrap();
        let phi = [0.0, -0.1, 0.05, 0.0];
        let rates = [0.0, -0.7, 0.4, 0.0];
        let pose = col.pose(&phi);
        let mut vl = [0.0; 4];
        col.velocity_load_into(&pose, &phi, &rates, &mut vl);
        // Centre positions along the path φ(t) = φ + t·rates (zero DOF acceleration).
        let centres = |t: f64| {
            let p: Vec<f64> = phi.iter().zip(&rates).map(|(a, r)| a + t * r).collect();
            col.pose(&p).centres
        };
        let h = 1e-4;
        let (cm, c0, cp) = (centres(-h), centres(0.0), centres(h));
        for a in 0..4 {
            let k = a % 2;
            let p = pose.pivot(a);
            let mut s = 0.0;
            for j in k..2 {
                let acc = [
                    (cp[j][0] - 2.0 * c0[j][0] + cm[j][0]) / (h * h),
                    (cp[j][1] - 2.0 * c0[j][1] + cm[j][1]) / (h * h),
                ];
                let r = [c0[j][0] - p[0], c0[j][1] - p[1]];
                s -= col.blocks()[j].mass * (r[0] * acc[1] - r[1] * acc[0]);
            }
            assert!((s - vl[a]).abs() < 1e-5, "a={a}: fd {s} vs {}", vl[a]);
        }
    }

    #[test]
    fn rejects_bad_blocks() {
        assert_eq!(Column::new(vec![]), Err(ColumnError::Empty));
        let e = Column::new(vec![Block::rectangle(1.0, f64::NAN, 1.0)]).unwrap_err();
        assert!(e.to_string().contains("height"));
        let mut b = Block::rectangle(1.0, 1.0, 1.0);
        b.contact_width = Some(2.0);
        assert!(Column::new(vec![b])
            .unwrap_err()
            .to_string()
            .contains("contact_width"));
    }
}
