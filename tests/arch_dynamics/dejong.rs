//! DeJong's one-DOF four-hinge arch, the reference of `arch_dynamics` (see its header).

use super::*;

// ---------------------------------------------------------------------------------------------
// DeJong's four-hinge mechanism, from the arch's dimensions alone.
// ---------------------------------------------------------------------------------------------

pub(crate) struct FourHinge {
    /// Hinge points A, B, C, D in the reference geometry.
    h: [[f64; 2]; 4],
    /// Segments 1 … 3 (A–B, B–C, C–D): mass, centroid, moment of inertia about the centroid.
    seg: [(f64, [f64; 2], f64); 3],
}

/// Configuration of the linkage at `θ`: rotations of the three segments.
#[derive(Clone, Copy)]
pub(crate) struct Linkage {
    psi: [f64; 3],
}

impl FourHinge {
    /// The four hinge rates (A … D) at the closed pose when the first segment turns at `rate0`
    /// (the linkage's velocity analysis).
    pub(crate) fn closed_hinge_rates(&self, rate0: f64) -> [f64; 4] {
        let (w, _) = self.jacobian(&self.position(0.0, 0.0));
        [
            rate0 * w[0],
            rate0 * (w[1] - w[0]),
            rate0 * (w[2] - w[1]),
            -rate0 * w[2],
        ]
    }

    pub(crate) fn new() -> FourHinge {
        let beta = PI / 2.0;
        let polar = |k: usize| PI / 2.0 + beta - 2.0 * beta * k as f64 / N as f64;
        let point = |(k, s): (usize, i8)| {
            let r = RADIUS + 0.5 * THICKNESS * f64::from(s);
            let th = polar(k);
            [r * th.cos(), r * th.sin()]
        };
        let rho = 2000.0;
        let (r1, r2) = (RADIUS - 0.5 * THICKNESS, RADIUS + 0.5 * THICKNESS);
        let sector = |a: usize, b: usize| {
            let (area, c, polar_moment) = annular_sector(r1, r2, polar(a), polar(b));
            (rho * area, c, rho * polar_moment)
        };
        FourHinge {
            h: HINGES.map(point),
            seg: [
                sector(HINGES[0].0, HINGES[1].0),
                sector(HINGES[1].0, HINGES[2].0),
                sector(HINGES[2].0, HINGES[3].0),
            ],
        }
    }

    /// The linkage at `θ` (segment 1's rotation about A): C on the circle about D at distance
    /// |BC| from B, on the branch of the reference configuration (Newton from `guess` for ψ₃).
    pub(crate) fn position(&self, theta: f64, guess: f64) -> Linkage {
        let [a, b0, c0, d] = self.h;
        let b = rot(b0, a, theta);
        let l2 = (c0[0] - b0[0]).powi(2) + (c0[1] - b0[1]).powi(2);
        let mut psi3 = guess;
        for _ in 0..50 {
            let c = rot(c0, d, psi3);
            let f = (c[0] - b[0]).powi(2) + (c[1] - b[1]).powi(2) - l2;
            // dc/dψ3 = ẑ × (c − d)
            let dc = [-(c[1] - d[1]), c[0] - d[0]];
            let df = 2.0 * ((c[0] - b[0]) * dc[0] + (c[1] - b[1]) * dc[1]);
            let step = f / df;
            psi3 -= step;
            if step.abs() < 1e-15 {
                break;
            }
        }
        let c = rot(c0, d, psi3);
        let psi2 = (c[1] - b[1]).atan2(c[0] - b[0]) - (c0[1] - b0[1]).atan2(c0[0] - b0[0]);
        Linkage {
            psi: [theta, psi2, psi3],
        }
    }

    /// Centroid of segment `i` and the point it turns with.
    pub(crate) fn centroid(&self, l: &Linkage, i: usize) -> [f64; 2] {
        let [a, b0, _, d] = self.h;
        match i {
            0 => rot(self.seg[0].1, a, l.psi[0]),
            1 => {
                let b = rot(b0, a, l.psi[0]);
                let c = rot(self.seg[1].1, b0, l.psi[1]);
                [c[0] + b[0] - b0[0], c[1] + b[1] - b0[1]]
            }
            _ => rot(self.seg[2].1, d, l.psi[2]),
        }
    }

    /// Velocity analysis at `l` for θ̇ = 1: the segments' rates ∂ψ_i/∂θ and the centroids'
    /// velocities ∂c_i/∂θ.
    pub(crate) fn jacobian(&self, l: &Linkage) -> ([f64; 3], [[f64; 2]; 3]) {
        let [a, b0, c0, d] = self.h;
        let b = rot(b0, a, l.psi[0]);
        let c = rot(c0, d, l.psi[2]);
        // v_B = ẑ × (B − A); v_C = ω3 ẑ × (C − D) = v_B + ω2 ẑ × (C − B).
        let perp = |p: [f64; 2], o: [f64; 2]| [-(p[1] - o[1]), p[0] - o[0]];
        let vb = perp(b, a);
        let (u2, u3) = (perp(c, b), perp(c, d));
        // ω3 u3 − ω2 u2 = vb
        let det = cross(u3, [-u2[0], -u2[1]]);
        let w3 = cross(vb, [-u2[0], -u2[1]]) / det;
        let w2 = cross(u3, vb) / det;
        let w = [1.0, w2, w3];
        let cs: Vec<[f64; 2]> = (0..3).map(|i| self.centroid(l, i)).collect();
        let v = [
            perp(cs[0], a),
            [
                vb[0] + w2 * perp(cs[1], b)[0],
                vb[1] + w2 * perp(cs[1], b)[1],
            ],
            [w3 * perp(cs[2], d)[0], w3 * perp(cs[2], d)[1]],
        ];
        (w, v)
    }

    /// `m*(θ)` and `Q(θ, a_g)`.
    pub(crate) fn mass_and_load(&self, l: &Linkage, ag: f64) -> (f64, f64) {
        let (w, v) = self.jacobian(l);
        let mut m = 0.0;
        let mut q = 0.0;
        for i in 0..3 {
            let (mi, _, ii) = self.seg[i];
            m += mi * (v[i][0] * v[i][0] + v[i][1] * v[i][1]) + ii * w[i] * w[i];
            q += mi * (-ag * v[i][0] - GRAVITY * v[i][1]);
        }
        (m, q)
    }

    /// θ̈ of Lagrange's equation, `m*'` by a central difference.
    pub(crate) fn accel(&self, theta: f64, rate: f64, ag: f64, guess: &mut f64) -> f64 {
        let l = self.position(theta, *guess);
        *guess = l.psi[2];
        let h = 1e-6;
        let mp = self
            .mass_and_load(&self.position(theta + h, l.psi[2]), 0.0)
            .0;
        let mm = self
            .mass_and_load(&self.position(theta - h, l.psi[2]), 0.0)
            .0;
        let (m, q) = self.mass_and_load(&l, ag);
        (q - 0.5 * (mp - mm) / (2.0 * h) * rate * rate) / m
    }

    /// The four hinge angles (chain DOF values) of `l`: relative rotations across A … D.
    pub(crate) fn hinge_angles(l: &Linkage) -> [f64; 4] {
        [
            l.psi[0],
            l.psi[1] - l.psi[0],
            l.psi[2] - l.psi[1],
            -l.psi[2],
        ]
    }
}
