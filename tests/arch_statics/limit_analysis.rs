//! Limit analysis of a circular arch with radial joints under self-weight and a horizontal load
//! `λ × weight` pushing +x (Heyman's rigid no-tension material, no sliding), written from
//! scratch for the tests — nothing here uses the library's chain geometry or models.
//!
//! A hinge is a point of a radial section at the angle `ψ` from the left springing, on the
//! intrados or the extrados. For four hinges the structure is a four-bar linkage:
//! - kinematically, the hinge rotations `θ_i` satisfy `Σ θ_i = 0` and `Σ θ_i P_i = 0`, the four
//!   hinges must open (each rotation separates the faces on the side away from its hinge), and
//!   the collapse multiplier of the mechanism is `λ = −P_gravity / P_horizontal` (virtual work);
//! - statically, the thrust line through the four hinge points is statically determinate (the
//!   abutment force and its moment, and `λ`: four unknowns, four hinge conditions); if it lies
//!   inside the arch at every section (every joint, for voussoirs) with compression, `λ` is the
//!   collapse multiplier (uniqueness theorem).
//!
//! The collapse multiplier is the least `λ` over admissible mechanisms (kinematic theorem); the
//! tests also check that its thrust line lies inside (static theorem), so both bounds meet.

#![allow(clippy::needless_range_loop)]

use std::f64::consts::PI;

/// Geometry of the arch: intrados and extrados radii, half embrace. Loads are per unit
/// `ρ g depth` (areas).
#[derive(Clone, Copy, Debug)]
pub struct Arch {
    pub r1: f64,
    pub r2: f64,
    pub beta: f64,
}

/// Which face a hinge is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    Intrados,
    Extrados,
}

/// A hinge: angle from the left springing, face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hinge {
    pub psi: f64,
    pub face: Face,
}

/// A mechanism and its multiplier.
#[derive(Clone, Copy, Debug)]
pub struct Mechanism {
    pub hinges: [Hinge; 4],
    pub lambda: f64,
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

impl Arch {
    pub fn new(radius: f64, thickness: f64, embrace: f64) -> Arch {
        Arch {
            r1: radius - 0.5 * thickness,
            r2: radius + 0.5 * thickness,
            beta: 0.5 * embrace,
        }
    }

    fn polar(&self, psi: f64) -> f64 {
        PI / 2.0 + self.beta - psi
    }

    /// Area and centroid of the part between `psi_a < psi_b` (an annular sector).
    pub fn segment(&self, psi_a: f64, psi_b: f64) -> (f64, [f64; 2]) {
        if psi_b <= psi_a {
            return (0.0, [0.0, 0.0]);
        }
        let half = 0.5 * (psi_b - psi_a);
        let mid = self.polar(0.5 * (psi_a + psi_b));
        let (r1, r2) = (self.r1, self.r2);
        let area = half * (r2 * r2 - r1 * r1);
        let d = 2.0 * half.sin() * (r2.powi(3) - r1.powi(3)) / (3.0 * half * (r2 * r2 - r1 * r1));
        (area, [d * mid.cos(), d * mid.sin()])
    }

    /// Position of a hinge.
    pub fn point(&self, h: Hinge) -> [f64; 2] {
        let th = self.polar(h.psi);
        let r = match h.face {
            Face::Intrados => self.r1,
            Face::Extrados => self.r2,
        };
        [r * th.cos(), r * th.sin()]
    }

    /// Kinematics of four hinges: the powers of gravity and of the horizontal load (per unit
    /// `ρ g depth` and unit largest hinge rotation) in the direction of the linkage that opens all
    /// four hinges, or `None` when neither direction does.
    pub fn powers(&self, hinges: [Hinge; 4]) -> Option<(f64, f64)> {
        let p: Vec<[f64; 2]> = hinges.iter().map(|&h| self.point(h)).collect();
        // Null vector of the 3 × 4 closure [1; P_y; −P_x] by cofactors.
        let col = |i: usize| [1.0, p[i][1], -p[i][0]];
        let det3 = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| {
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        };
        let mut theta = [0.0; 4];
        for i in 0..4 {
            let others: Vec<[f64; 3]> = (0..4).filter(|&j| j != i).map(col).collect();
            let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
            theta[i] = sign * det3(others[0], others[1], others[2]);
        }
        let norm = theta.iter().map(|x| x.abs()).fold(0.0, f64::max);
        if norm < 1e-12 * (self.r2 * self.r2) {
            return None;
        }
        theta.iter_mut().for_each(|x| *x /= norm);
        // A hinge opens when the other corner of its section moves away from the part before,
        // i.e. along the direction of travel (left springing to right).
        let opens = |i: usize, th: f64| -> bool {
            let h = hinges[i];
            let other_r = match h.face {
                Face::Intrados => self.r2,
                Face::Extrados => self.r1,
            };
            let polar = self.polar(h.psi);
            let o = [other_r * polar.cos(), other_r * polar.sin()];
            let d = [o[0] - p[i][0], o[1] - p[i][1]];
            let vel = [-th * d[1], th * d[0]];
            vel[0] * polar.sin() - vel[1] * polar.cos() > 0.0
        };
        let direction = if (0..4).all(|i| opens(i, theta[i])) {
            1.0
        } else if (0..4).all(|i| opens(i, -theta[i])) {
            -1.0
        } else {
            return None;
        };
        theta.iter_mut().for_each(|x| *x *= direction);
        let (mut pg, mut ph) = (0.0, 0.0);
        for s in 0..3 {
            let (area, c) = self.segment(hinges[s].psi, hinges[s + 1].psi);
            let mut v = [0.0, 0.0];
            for h in 0..=s {
                v[0] += -theta[h] * (c[1] - p[h][1]);
                v[1] += theta[h] * (c[0] - p[h][0]);
            }
            pg -= area * v[1];
            ph += area * v[0];
        }
        Some((pg, ph))
    }

    /// The admissible mechanism of four hinges and its multiplier `λ = −P_g / P_h`, or `None`
    /// when none opens all four hinges or the horizontal load does no work on it.
    pub fn mechanism(&self, hinges: [Hinge; 4]) -> Option<Mechanism> {
        let (pg, ph) = self.powers(hinges)?;
        (ph > 0.0).then(|| Mechanism {
            hinges,
            lambda: -pg / ph,
        })
    }

    /// The thrust line of a load multiplier `lambda` through the hinges' equilibrium, returned as
    /// the abutment force and moment `(H, V, M0)` solving the four hinge conditions with `λ` as
    /// the fourth unknown.
    pub fn thrust(&self, hinges: [Hinge; 4]) -> Option<[f64; 4]> {
        // Unknowns x = (H, V, M0, λ). At a section ψ: F = (H + λ Wx(ψ), V − W(ψ)), Mo = M0 +
        // Σ c × w. Hinge condition: Mo + ρ N = 0 with N = F · n.
        let mut a = [[0.0; 4]; 4];
        let mut b = [0.0; 4];
        for (row, h) in hinges.iter().enumerate() {
            let (coef, rhs) = self.section_equation(
                h.psi,
                match h.face {
                    Face::Intrados => self.r1,
                    Face::Extrados => self.r2,
                },
            );
            a[row] = coef;
            b[row] = rhs;
        }
        solve4(a, b)
    }

    /// `Mo + ρ N` at the section `psi` as `coef · (H, V, M0, λ) − rhs`.
    fn section_equation(&self, psi: f64, rho: f64) -> ([f64; 4], f64) {
        let (area, c) = self.segment(0.0, psi);
        let th = self.polar(psi);
        let n = [th.sin(), -th.cos()];
        // F = (H + λ area, V − area); Mo = M0 + c × (λ area, −area) = M0 − c_x area − λ c_y area;
        // N = n · F. The hinge condition Mo + ρ N = 0 is linear in (H, V, M0, λ).
        let mo_lambda = -c[1] * area;
        let mo_const = -c[0] * area;
        let coef = [rho * n[0], rho * n[1], 1.0, mo_lambda + rho * n[0] * area];
        let rhs = -(mo_const - rho * n[1] * area);
        (coef, rhs)
    }

    /// Eccentricity position `ρ` of the thrust line and normal force `N` at the section `psi`.
    pub fn thrust_at(&self, x: [f64; 4], psi: f64) -> (f64, f64) {
        let [h, v, m0, lambda] = x;
        let (area, c) = self.segment(0.0, psi);
        let th = self.polar(psi);
        let n = [th.sin(), -th.cos()];
        let f = [h + lambda * area, v - area];
        let mo = m0 + cross(c, [lambda * area, -area]);
        let normal = f[0] * n[0] + f[1] * n[1];
        (-mo / normal, normal)
    }

    /// Whether the thrust line `x` lies inside the arch with compression at all `sections`.
    pub fn admissible(&self, x: [f64; 4], sections: &[f64], slack: f64) -> bool {
        let t = self.r2 - self.r1;
        sections.iter().all(|&psi| {
            let (rho, normal) = self.thrust_at(x, psi);
            normal > 0.0 && rho >= self.r1 - slack * t && rho <= self.r2 + slack * t
        })
    }

    /// Least multiplier over four-hinge mechanisms with hinges at the given sections (every
    /// choice of four sections and faces).
    pub fn discrete_collapse(&self, sections: &[f64]) -> Option<Mechanism> {
        let n = sections.len();
        let mut best: Option<Mechanism> = None;
        let faces = [Face::Intrados, Face::Extrados];
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    for l in k + 1..n {
                        for pattern in 0..16 {
                            let h = |q: usize, bit: usize| Hinge {
                                psi: sections[q],
                                face: faces[(pattern >> bit) & 1],
                            };
                            let hinges = [h(i, 0), h(j, 1), h(k, 2), h(l, 3)];
                            if let Some(m) = self.mechanism(hinges) {
                                if best.map_or(true, |b| m.lambda < b.lambda) {
                                    best = Some(m);
                                }
                            }
                        }
                    }
                }
            }
        }
        best
    }

    /// Least multiplier with hinges anywhere: the best mechanism on a grid of `grid + 1`
    /// sections, then a pattern search on the four hinge angles (faces kept).
    pub fn continuous_collapse(&self, grid: usize) -> Mechanism {
        let grid: Vec<f64> = (0..=grid)
            .map(|k| 2.0 * self.beta * k as f64 / grid as f64)
            .collect();
        let mut best = self.discrete_collapse(&grid).expect("a mechanism exists");
        let mut step = 2.0 * self.beta / 72.0;
        while step > 1e-12 {
            let mut improved = false;
            for q in 0..4 {
                for delta in [-step, step] {
                    let mut h = best.hinges;
                    h[q].psi = (h[q].psi + delta).clamp(0.0, 2.0 * self.beta);
                    if (0..3).any(|i| h[i].psi >= h[i + 1].psi) {
                        continue;
                    }
                    if let Some(m) = self.mechanism(h) {
                        if m.lambda < best.lambda {
                            best = m;
                            improved = true;
                        }
                    }
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        best
    }

    /// Whether some four-hinge mechanism on the sections collapses under gravity alone
    /// (positive power of gravity).
    pub fn collapses_under_gravity(&self, sections: &[f64]) -> bool {
        let n = sections.len();
        let faces = [Face::Intrados, Face::Extrados];
        for i in 0..n {
            for j in i + 1..n {
                for k in j + 1..n {
                    for l in k + 1..n {
                        for pattern in 0..16 {
                            let h = |q: usize, bit: usize| Hinge {
                                psi: sections[q],
                                face: faces[(pattern >> bit) & 1],
                            };
                            let hinges = [h(i, 0), h(j, 1), h(k, 2), h(l, 3)];
                            if self.powers(hinges).is_some_and(|(pg, _)| pg > 0.0) {
                                return true;
                            }
                        }
                    }
                }
            }
        }
        false
    }
}

/// Gaussian elimination with partial pivoting for a 4 × 4 system.
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for c in 0..4 {
        let p = (c..4).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() < 1e-14 {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        for r in c + 1..4 {
            let f = a[r][c] / a[c][c];
            for k in c..4 {
                a[r][k] -= f * a[c][k];
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let s: f64 = (r + 1..4).map(|k| a[r][k] * x[k]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
}
