//! A column of drums in natural coordinates: `x, y, θ` of every drum, in the frame that moves
//! with the ground (so the ground is fixed and every drum carries the inertial load `−m a_g`).
//!
//! The mass matrix is `diag(m_j, m_j, I_j)`: constant, and the equations of motion between
//! contact impulses are linear (no velocity terms). All geometry sits in the contact Jacobian.
//!
//! Joint `k` is the contact under drum `k` (joint 0 on the ground). Its contacts are the two ends
//! of the overlap of the faces it joins: each end is a corner of one face against the other face
//! (the upper drum's corner on the lower face, or, once a drum has slid past the edge of the one
//! below, the lower drum's corner against the upper face). A corner that belongs to neither face's
//! edge is never a contact of a flat joint. For every end the Jacobian rows are those of the
//! relative velocity of the two drums' material points at the end, normal (gap rate) and tangent
//! (slip rate) to the face it touches; the normal points from the lower body into the upper one
//! and the tangent is the normal turned clockwise, `t = (n_y, −n_x)` (SPEC §9).
//!
//! The slip of a joint is the tangential offset between the two faces' material points at its
//! contact end (the end with the smaller gap): zero for rocking without sliding, the same at both
//! ends when the joint is closed.

use crate::model::column::Column;

/// Number of coordinates per drum (`x`, `y`, `θ`).
pub(crate) const DOF_PER_DRUM: usize = 3;

/// The drums of a column and their joints, in natural coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Drums {
    mass: Vec<f64>,
    inertia: Vec<f64>,
    half_height: Vec<f64>,
    /// Half extent of the contact on drum `k`'s bottom face (joint `k`'s upper face).
    upper_extent: Vec<f64>,
    /// Half extent of the contact on joint `k`'s lower face (`f64::INFINITY` on the ground).
    lower_extent: Vec<f64>,
    /// Heights of the drum centres in the straight column.
    rest_height: Vec<f64>,
}

/// Jacobian rows of one contact for the two bodies it joins: `[n_x, n_y, (r − c) × n]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactRows {
    /// Normal row for the upper drum.
    pub n_up: [f64; 3],
    /// Normal row for the lower drum (already with the minus sign of the relative velocity).
    pub n_low: [f64; 3],
    /// Tangent row for the upper drum.
    pub t_up: [f64; 3],
    /// Tangent row for the lower drum (with the minus sign).
    pub t_low: [f64; 3],
}

/// One end of a joint's overlap segment.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContactEnd {
    /// Location (m).
    pub point: [f64; 2],
    /// Unit normal of the face it touches, from the lower body into the upper one.
    pub normal: [f64; 2],
    /// Gap along the normal (m), negative for penetration.
    pub gap: f64,
    /// Whether the end is the upper drum's corner (else the lower drum's corner).
    pub upper_corner: bool,
    /// Jacobian rows.
    pub rows: ContactRows,
}

/// The contact geometry of one joint.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct JointGeometry {
    /// Right end (index 0) and left end (index 1), as the thesis's `phĭ` (right corner) and `phî`
    /// (left corner) pivots.
    pub ends: [ContactEnd; 2],
    /// Slip (m): tangential offset of the upper face relative to the lower one at the contact end.
    pub slip: f64,
    /// Length of the overlap of the two faces (m); zero or negative once a drum has slid off.
    pub overlap: f64,
}

#[inline]
fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The frame of one body: centre, axis `e1` (along the faces), `e2` (up the drum).
#[derive(Clone, Copy, Debug)]
struct Frame {
    c: [f64; 2],
    e1: [f64; 2],
    e2: [f64; 2],
}

impl Frame {
    #[inline(always)]
    fn of(q: &[f64], j: usize) -> Frame {
        let (s, co) = q[3 * j + 2].sin_cos();
        Frame::with(q, j, s, co)
    }

    #[inline(always)]
    fn with(q: &[f64], j: usize, s: f64, co: f64) -> Frame {
        Frame {
            c: [q[3 * j], q[3 * j + 1]],
            e1: [co, s],
            e2: [-s, co],
        }
    }

    /// The frame of drum `j` after `below`, the frame of drum `j − 1`: the sine and cosine are
    /// taken over when the two angles have the same bits (drums turning together, the common
    /// case: the same function of the same number), else computed.
    #[inline(always)]
    fn next(q: &[f64], j: usize, below: &Frame) -> Frame {
        if j > 0 && q[3 * j + 2].to_bits() == q[3 * j - 1].to_bits() {
            Frame::with(q, j, below.e1[1], below.e1[0])
        } else {
            Frame::of(q, j)
        }
    }

    fn ground() -> Frame {
        Frame {
            c: [0.0, 0.0],
            e1: [1.0, 0.0],
            e2: [0.0, 1.0],
        }
    }

    fn at(&self, along: f64, up: f64) -> [f64; 2] {
        [
            self.c[0] + along * self.e1[0] + up * self.e2[0],
            self.c[1] + along * self.e1[1] + up * self.e2[1],
        ]
    }
}

/// Jacobian rows at location `r` with normal `n` for the upper body centred at `cu` and the lower
/// body centred at `cl` (`None`: the ground, zero rows).
#[inline(always)]
fn rows_at(r: [f64; 2], n: [f64; 2], cu: [f64; 2], cl: Option<[f64; 2]>) -> ContactRows {
    let t = [n[1], -n[0]];
    let du = [r[0] - cu[0], r[1] - cu[1]];
    let mut rows = ContactRows {
        n_up: [n[0], n[1], cross(du, n)],
        t_up: [t[0], t[1], cross(du, t)],
        ..ContactRows::default()
    };
    if let Some(cl) = cl {
        let dl = [r[0] - cl[0], r[1] - cl[1]];
        rows.n_low = [-n[0], -n[1], -cross(dl, n)];
        rows.t_low = [-t[0], -t[1], -cross(dl, t)];
    }
    rows
}

impl Drums {
    /// The drums of a validated column (its blocks' widths, heights, masses, inertias and contact
    /// widths: a block's `contact_width` narrows both faces of the joint under it, as cut corners
    /// do; without it each face spans its drum's width).
    pub fn new(column: &Column) -> Drums {
        let blocks = column.blocks();
        let n = blocks.len();
        let mut d = Drums {
            mass: Vec::with_capacity(n),
            inertia: Vec::with_capacity(n),
            half_height: Vec::with_capacity(n),
            upper_extent: Vec::with_capacity(n),
            lower_extent: Vec::with_capacity(n),
            rest_height: Vec::with_capacity(n),
        };
        let mut y = 0.0;
        for (k, b) in blocks.iter().enumerate() {
            d.mass.push(b.mass);
            d.inertia.push(column.inertia(k));
            d.half_height.push(0.5 * b.height);
            d.rest_height.push(y + 0.5 * b.height);
            y += b.height;
            match b.contact_width {
                Some(c) => {
                    d.upper_extent.push(0.5 * c);
                    d.lower_extent
                        .push(if k == 0 { f64::INFINITY } else { 0.5 * c });
                }
                None => {
                    d.upper_extent.push(0.5 * b.width);
                    d.lower_extent.push(if k == 0 {
                        f64::INFINITY
                    } else {
                        0.5 * blocks[k - 1].width
                    });
                }
            }
        }
        d
    }

    /// Number of drums (and joints).
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    /// Whether there is no drum (never, for a validated column).
    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// Mass of drum `j`.
    pub fn mass(&self, j: usize) -> f64 {
        self.mass[j]
    }

    /// Moment of inertia of drum `j` about its centre.
    pub fn inertia(&self, j: usize) -> f64 {
        self.inertia[j]
    }

    /// Half height of drum `j`.
    pub fn half_height(&self, j: usize) -> f64 {
        self.half_height[j]
    }

    /// Half extent of joint `k`'s contact on the upper face.
    pub fn upper_extent(&self, k: usize) -> f64 {
        self.upper_extent[k]
    }

    /// The straight column at rest: `x = 0`, `y` = centre heights, `θ = 0`.
    pub fn rest_positions(&self) -> Vec<f64> {
        let mut q = vec![0.0; DOF_PER_DRUM * self.len()];
        for (j, y) in self.rest_height.iter().enumerate() {
            q[3 * j + 1] = *y;
        }
        q
    }

    /// Kinetic energy `½ vᵀ M v` (J).
    pub fn kinetic_energy(&self, v: &[f64]) -> f64 {
        let mut e = 0.0;
        for j in 0..self.len() {
            let m = self.mass[j];
            e += 0.5
                * (m * (v[3 * j] * v[3 * j] + v[3 * j + 1] * v[3 * j + 1])
                    + self.inertia[j] * v[3 * j + 2] * v[3 * j + 2]);
        }
        e
    }

    /// Potential energy of gravity above the straight column at rest (J).
    pub fn potential_energy(&self, q: &[f64], gravity: f64) -> f64 {
        let mut e = 0.0;
        for j in 0..self.len() {
            e += self.mass[j] * gravity * (q[3 * j + 1] - self.rest_height[j]);
        }
        e
    }

    /// Total mass and centre of mass of the drums `k..n`.
    pub fn centre_of_mass_above(&self, q: &[f64], k: usize) -> (f64, [f64; 2]) {
        let (mut m, mut sx, mut sy) = (0.0, 0.0, 0.0);
        for j in k..self.len() {
            m += self.mass[j];
            sx += self.mass[j] * q[3 * j];
            sy += self.mass[j] * q[3 * j + 1];
        }
        (m, [sx / m, sy / m])
    }

    fn frames(&self, q: &[f64], k: usize) -> (Frame, Frame) {
        let low = if k == 0 {
            Frame::ground()
        } else {
            Frame::of(q, k - 1)
        };
        (Frame::of(q, k), low)
    }

    /// Contact geometry of every joint at positions `q` into `out` (at most one `sin_cos` per
    /// drum).
    pub fn joints_into(&self, q: &[f64], out: &mut [JointGeometry]) {
        let mut low = Frame::ground();
        for (k, g) in out.iter_mut().enumerate().take(self.len()) {
            let up = Frame::next(q, k, &low);
            self.joint_into::<true>(k, &up, &low, g);
            low = up;
        }
    }

    /// Only the Jacobian rows (and the points and normals) of every joint's ends at `q` into
    /// `out`, the same numbers as [`Drums::joints_into`]'s; the gaps, the slip and the overlap
    /// are left as they were (a step's midpoint geometry needs only its rows).
    pub fn joints_rows_into(&self, q: &[f64], out: &mut [JointGeometry]) {
        let mut low = Frame::ground();
        for (k, g) in out.iter_mut().enumerate().take(self.len()) {
            let up = Frame::next(q, k, &low);
            self.joint_into::<false>(k, &up, &low, g);
            low = up;
        }
    }

    /// Contact geometry of joint `k` at positions `q`.
    pub fn joint(&self, q: &[f64], k: usize) -> JointGeometry {
        let (up, low) = self.frames(q, k);
        let mut g = JointGeometry::default();
        self.joint_into::<true>(k, &up, &low, &mut g);
        g
    }

    /// Contact geometry of joint `k` between the frames `up` and `low`, written into `g` (in
    /// place: a geometry is a few hundred bytes, and two columns' worth are made every step).
    /// Without `FULL`, only the ends' points, normals, corners and rows.
    fn joint_into<const FULL: bool>(
        &self,
        k: usize,
        up: &Frame,
        low: &Frame,
        g: &mut JointGeometry,
    ) {
        let (up, low) = (*up, *low);
        let hl = if k == 0 { 0.0 } else { self.half_height[k - 1] };
        let hu = self.half_height[k];
        let (eu, el) = (self.upper_extent[k], self.lower_extent[k]);
        let cl = if k == 0 { None } else { Some(low.c) };
        // Face centres.
        let o_low = low.at(0.0, hl);
        let o_up = up.at(0.0, -hu);
        for (i, s) in [1.0_f64, -1.0].into_iter().enumerate() {
            let corner_up = up.at(s * eu, -hu);
            // The upper corner's position along the lower face.
            let along = dot([corner_up[0] - o_low[0], corner_up[1] - o_low[1]], low.e1);
            // Written field by field in place (no temporary end to copy).
            let end = &mut g.ends[i];
            if s * along <= el {
                // The upper drum's corner on the lower face.
                let n = low.e2;
                if FULL {
                    end.gap = dot([corner_up[0] - o_low[0], corner_up[1] - o_low[1]], n);
                }
                end.point = corner_up;
                end.normal = n;
                end.upper_corner = true;
                end.rows = rows_at(corner_up, n, up.c, cl);
            } else {
                // The lower drum's corner against the upper face.
                let corner_low = low.at(s * el, hl);
                let n = up.e2;
                if FULL {
                    end.gap = dot([o_up[0] - corner_low[0], o_up[1] - corner_low[1]], n);
                }
                end.point = corner_low;
                end.normal = n;
                end.upper_corner = false;
                end.rows = rows_at(corner_low, n, up.c, cl);
            }
        }
        if !FULL {
            return;
        }
        // Overlap of the faces along the lower face.
        let centre_along = dot([o_up[0] - o_low[0], o_up[1] - o_low[1]], low.e1);
        let hi = (centre_along + eu * dot(up.e1, low.e1)).min(el);
        let lo = (centre_along - eu * dot(up.e1, low.e1)).max(-el);
        g.overlap = hi - lo;
        // Slip at the end with the smaller gap.
        let r = if g.ends[0].gap <= g.ends[1].gap {
            g.ends[0].point
        } else {
            g.ends[1].point
        };
        let x_low = dot([r[0] - o_low[0], r[1] - o_low[1]], low.e1);
        let x_up = dot([r[0] - o_up[0], r[1] - o_up[1]], up.e1);
        g.slip = x_low - x_up;
    }

    /// Rows of a contact of joint `k` at location `r` with normal `n` (a bump between the ends).
    pub fn rows_at(&self, q: &[f64], k: usize, r: [f64; 2], n: [f64; 2]) -> ContactRows {
        let cu = [q[3 * k], q[3 * k + 1]];
        let cl = if k == 0 {
            None
        } else {
            Some([q[3 * k - 3], q[3 * k - 2]])
        };
        rows_at(r, n, cu, cl)
    }

    /// Relative velocity of a contact along its normal and tangent rows.
    pub fn rates(&self, rows: &ContactRows, v: &[f64], k: usize) -> (f64, f64) {
        let u = &v[3 * k..3 * k + 3];
        let mut un = rows.n_up[0] * u[0] + rows.n_up[1] * u[1] + rows.n_up[2] * u[2];
        let mut ut = rows.t_up[0] * u[0] + rows.t_up[1] * u[1] + rows.t_up[2] * u[2];
        if k > 0 {
            let l = &v[3 * k - 3..3 * k];
            un += rows.n_low[0] * l[0] + rows.n_low[1] * l[1] + rows.n_low[2] * l[2];
            ut += rows.t_low[0] * l[0] + rows.t_low[1] * l[1] + rows.t_low[2] * l[2];
        }
        (un, ut)
    }

    /// Positions and velocities of the drums for a thesis state: interface DOF angles `phi` and
    /// rates (length `2n` each, SPEC §1), with the column's pivots at `±b_k`.
    pub fn from_interface_state(
        &self,
        column: &Column,
        phi: &[f64],
        rates: &[f64],
        q: &mut [f64],
        v: &mut [f64],
    ) {
        let n = self.len();
        let pose = column.pose(phi);
        for j in 0..n {
            q[3 * j] = pose.centres[j][0];
            q[3 * j + 1] = pose.centres[j][1];
            q[3 * j + 2] = pose.block_angles[j];
        }
        v.iter_mut().for_each(|x| *x = 0.0);
        for a in 0..2 * n {
            let w = rates[a];
            if w == 0.0 {
                continue;
            }
            let k = a % n;
            let p = if a < n {
                pose.right_pivots[k]
            } else {
                pose.left_pivots[k]
            };
            for j in k..n {
                let c = pose.centres[j];
                v[3 * j] += -w * (c[1] - p[1]);
                v[3 * j + 1] += w * (c[0] - p[0]);
                v[3 * j + 2] += w;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::column::Block;

    fn column(widths: &[f64]) -> Column {
        Column::new(
            widths
                .iter()
                .map(|&w| Block::rectangle(w, 1.0, 100.0))
                .collect(),
        )
        .unwrap()
    }

    /// At rest every end of every joint touches with zero gap and zero slip.
    #[test]
    fn straight_column_is_closed() {
        let c = column(&[1.0, 0.8, 1.2]);
        let d = Drums::new(&c);
        let q = d.rest_positions();
        for k in 0..3 {
            let g = d.joint(&q, k);
            for e in g.ends {
                assert!(e.gap.abs() < 1e-15, "joint {k}: {e:?}");
            }
            assert!(g.slip.abs() < 1e-15);
            assert!((g.overlap - 2.0 * c.half_contact_width(k)).abs() < 1e-15);
            // The ends are the thesis's pivots ±b_k.
            assert!((g.ends[0].point[0] - c.half_contact_width(k)).abs() < 1e-15);
            assert!((g.ends[1].point[0] + c.half_contact_width(k)).abs() < 1e-15);
        }
        // Joint 2: drum 2 (1.2) wider than drum 1 (0.8): the lower drum's corners.
        let g = d.joint(&q, 2);
        assert!(!g.ends[0].upper_corner && !g.ends[1].upper_corner);
        assert!(d.joint(&q, 1).ends[0].upper_corner);
    }

    /// A rotation about a thesis pivot keeps that end closed and unslipped and opens the other by
    /// `2 b sin φ`; the velocities from the interface rates give zero rates at the pivot.
    #[test]
    fn rocking_about_a_pivot() {
        let c = column(&[1.0, 1.0]);
        let d = Drums::new(&c);
        let phi = [0.0, -0.1, 0.0, 0.0]; // upper joint about its right corner
        let rates = [0.0, -0.7, 0.3, 0.0]; // and the lower one rotating about its left corner
        let mut q = vec![0.0; 6];
        let mut v = vec![0.0; 6];
        d.from_interface_state(&c, &phi, &rates, &mut q, &mut v);
        let g = d.joint(&q, 1);
        assert!(g.ends[0].gap.abs() < 1e-15);
        assert!((g.ends[1].gap - 2.0 * 0.5 * (0.1f64).sin()).abs() < 1e-14);
        assert!(g.slip.abs() < 1e-15);
        let (un, ut) = d.rates(&g.ends[0].rows, &v, 1);
        assert!(un.abs() < 1e-15 && ut.abs() < 1e-15, "{un} {ut}");
        // The lower joint's left end is its pivot.
        let g0 = d.joint(&q, 0);
        let (un, ut) = d.rates(&g0.ends[1].rows, &v, 0);
        assert!(un.abs() < 1e-15 && ut.abs() < 1e-15);
        let (un, _) = d.rates(&g0.ends[0].rows, &v, 0);
        assert!((un - 0.3).abs() < 1e-15, "right end lifts at 2b·ω: {un}");
    }

    /// The rows are the derivatives of the gap and of the slip: finite differences.
    #[test]
    fn rows_are_gap_and_slip_rates() {
        let c = column(&[1.0, 0.9]);
        let d = Drums::new(&c);
        let mut q = d.rest_positions();
        // Upper drum tilted, shifted and lifted a little, lower one tilted the other way.
        q[2] = -0.02;
        q[3] += 0.03;
        q[4] += 0.01;
        q[5] = 0.05;
        let v = [0.1, -0.2, 0.3, -0.4, 0.5, -0.6];
        let h = 1e-7;
        let qp: Vec<f64> = q.iter().zip(&v).map(|(a, b)| a + h * b).collect();
        let qm: Vec<f64> = q.iter().zip(&v).map(|(a, b)| a - h * b).collect();
        for k in 0..2 {
            let g = d.joint(&q, k);
            let (gp, gm) = (d.joint(&qp, k), d.joint(&qm, k));
            for i in 0..2 {
                let fd = (gp.ends[i].gap - gm.ends[i].gap) / (2.0 * h);
                let (un, _) = d.rates(&g.ends[i].rows, &v, k);
                assert!((fd - un).abs() < 1e-7, "joint {k} end {i}: {fd} vs {un}");
            }
            // The slip's rate is the tangent row at the contact end, exactly.
            let e = if g.ends[0].gap <= g.ends[1].gap { 0 } else { 1 };
            let fd = (gp.slip - gm.slip) / (2.0 * h);
            let (_, ut) = d.rates(&g.ends[e].rows, &v, k);
            assert!((fd - ut).abs() < 1e-7, "joint {k}: {fd} vs {ut}");
        }
    }
}
