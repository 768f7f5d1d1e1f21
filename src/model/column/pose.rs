//! The current geometry of a column (large rotations): pivots, block centres and angles for the
//! DOF angles, with the suffix sums of mass, first and second moments and inertia above each
//! interface that make every mass matrix and load entry O(1) (SPEC §1).

use super::Column;

impl Column {
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
        pose.set_len(n);
        let (right_pivots, left_pivots) = (&mut pose.right_pivots[..n], &mut pose.left_pivots[..n]);
        let (centres, block_angles) = (&mut pose.centres[..n], &mut pose.block_angles[..n]);
        let block_sin_cos = &mut pose.block_sin_cos[..n];
        let (half_contact, base_height) = (&self.half_contact[..n], &self.base_height[..n]);
        let (blocks, phi) = (&self.blocks[..n], &phi[..2 * n]);
        // Current rigid map of the block below (the ground is the identity).
        let mut map = BlockMap::GROUND;
        for k in 0..n {
            let (b, y) = (half_contact[k], base_height[k]);
            let right = map.apply([b, y]);
            let left = map.apply([-b, y]);
            map.turn(phi[k], phi[n + k], b, y);
            let centre = map.apply([0.0, y + 0.5 * blocks[k].height]);
            right_pivots[k] = right;
            left_pivots[k] = left;
            centres[k] = centre;
            block_angles[k] = map.alpha;
            block_sin_cos[k] = map.sin_cos;
        }
        pose.update_sums(self);
    }
}

/// The rigid map `x ↦ R(α) x + t` of a block, advanced from the ground up interface by
/// interface: the one arithmetic of [`Column::pose_into`] and of the driver's fixed-size poses.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BlockMap {
    /// Absolute rotation `α`.
    pub alpha: f64,
    /// `α.sin_cos()`, bit for bit.
    pub sin_cos: (f64, f64),
    t: [f64; 2],
}

impl BlockMap {
    /// The ground's map, the identity.
    pub const GROUND: BlockMap = BlockMap {
        alpha: 0.0,
        sin_cos: (0.0, 1.0),
        t: [0.0, 0.0],
    };

    /// Image of a point of the block's reference geometry.
    #[inline(always)]
    pub fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        let ((sa, ca), t) = (self.sin_cos, self.t);
        [ca * p[0] - sa * p[1] + t[0], sa * p[0] + ca * p[1] + t[1]]
    }

    /// From this block's map to the map of the block above an interface whose corners are
    /// `(±b, y)` and whose DOF angles are `phi_right` (`phĭ`) and `phi_left` (`phî`): a turn by the
    /// non-zero one about its corner (right if `phĭ ≠ 0`), `T(r) = R_{α+θ} r + R_α (p − R_θ p) + t`.
    #[inline(always)]
    pub fn turn(&mut self, phi_right: f64, phi_left: f64, b: f64, y: f64) {
        let (theta, pref) = if phi_right != 0.0 {
            (phi_right, [b, y])
        } else {
            (phi_left, [-b, y])
        };
        if theta == 0.0 {
            return;
        }
        let (st, ct) = theta.sin_cos();
        let d = [
            pref[0] - (ct * pref[0] - st * pref[1]),
            pref[1] - (st * pref[0] + ct * pref[1]),
        ];
        self.t = self.apply(d);
        if self.alpha == 0.0 {
            // The first turned interface: `0 + θ` is `θ` exactly, and so are its sine and cosine
            // (one `sin_cos` fewer).
            self.alpha = theta;
            self.sin_cos = (st, ct);
        } else {
            self.alpha += theta;
            self.sin_cos = self.alpha.sin_cos();
        }
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
    /// `block_angles[k].sin_cos()`, bit for bit (computed once, with the pose).
    pub block_sin_cos: Vec<(f64, f64)>,
    /// The sums over the part above each interface, in one record per interface (one bounds
    /// check and one cache line per mass matrix entry).
    pub(super) above: Vec<Above>,
}

/// The part above an interface: its mass `S0`, first moment `S1`, the blocks' own moments of
/// inertia `ΣI`, its centre of mass `g = S1 / S0` and `max(0, S2 − S0 |g|²)` (`S2 = Σ m_j |c_j|²`,
/// the spread term of [`Pose::mass_entry`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Above {
    pub mass: f64,
    pub moment: [f64; 2],
    pub inertia: f64,
    pub centre: [f64; 2],
    pub spread: f64,
}

impl Pose {
    fn with_capacity(n: usize) -> Pose {
        Pose {
            right_pivots: Vec::with_capacity(n),
            left_pivots: Vec::with_capacity(n),
            centres: Vec::with_capacity(n),
            block_angles: Vec::with_capacity(n),
            block_sin_cos: Vec::with_capacity(n),
            above: Vec::with_capacity(n),
        }
    }

    /// Every vector of length `n` (their entries are then all overwritten; no allocation once
    /// they have grown).
    #[inline]
    fn set_len(&mut self, n: usize) {
        if self.above.len() == n && self.right_pivots.len() == n {
            return;
        }
        self.right_pivots.resize(n, [0.0; 2]);
        self.left_pivots.resize(n, [0.0; 2]);
        self.centres.resize(n, [0.0; 2]);
        self.block_angles.resize(n, 0.0);
        self.block_sin_cos.resize(n, (0.0, 1.0));
        self.above.resize(n, Above::default());
    }

    fn update_sums(&mut self, column: &Column) {
        let n = self.centres.len();
        let (centres, above) = (&self.centres[..n], &mut self.above[..n]);
        let (blocks, inertia) = (&column.blocks[..n], &column.inertia[..n]);
        let (mut s0, mut s1, mut s2, mut si) = (0.0, [0.0, 0.0], 0.0, 0.0);
        for j in (0..n).rev() {
            let m = blocks[j].mass;
            let c = centres[j];
            s0 += m;
            s1 = [s1[0] + m * c[0], s1[1] + m * c[1]];
            s2 += m * (c[0] * c[0] + c[1] * c[1]);
            si += inertia[j];
            let g = [s1[0] / s0, s1[1] / s0];
            above[j] = Above {
                mass: s0,
                moment: s1,
                inertia: si,
                centre: g,
                spread: (s2 - s0 * (g[0] * g[0] + g[1] * g[1])).max(0.0),
            };
        }
    }

    #[inline]
    pub(super) fn pivot(&self, a: usize) -> [f64; 2] {
        let n = self.centres.len();
        if a < n {
            self.right_pivots[a]
        } else {
            self.left_pivots[a - n]
        }
    }

    /// The interface of DOF `a < 2n` (`a mod n` without an integer division).
    #[inline]
    pub(super) fn interface(&self, a: usize) -> usize {
        let n = self.centres.len();
        if a < n {
            a
        } else {
            a - n
        }
    }

    /// Total mass of the part above interface `k` and its centre of mass.
    #[inline]
    pub(crate) fn mass_above(&self, k: usize) -> (f64, [f64; 2]) {
        let a = &self.above[k];
        (a.mass, a.centre)
    }
}
