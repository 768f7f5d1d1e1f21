//! The voussoir arch of SPEC §9: a circular centre line of radius `R`, thickness `t` (radial
//! joints, intrados radius `R − t/2`, extrados `R + t/2`), angle of embrace `2β`, `N` voussoirs of
//! equal angle on rigid abutments, uniform density. Chain order runs from the left springing to
//! the right one; the centre of the circle is the origin. Joint `k` lies at the polar angle
//! `θ_k = π/2 + β − 2βk/N`; its normal is the centre-line tangent in chain order,
//! `n_k = (sin θ_k, −cos θ_k)`, so `t_k` points to the centre: `R_k` is the intrados corner,
//! `L_k` the extrados corner. Each voussoir is an annular sector (area, centroid and moment of
//! inertia in closed form).

use crate::chain::{Body, Chain, Joint};
use crate::validate::{self, InvalidValue};

/// Most voussoirs of an arch a time history or a spectrum takes ([`VoussoirArch::runnable`]).
pub const MAX_RUN_VOUSSOIRS: usize = 1000;

/// A voussoir arch on two rigid abutments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VoussoirArch {
    /// Radius `R` of the centre line (m).
    pub radius: f64,
    /// Thickness `t` (m), `0 < t < 2R`.
    pub thickness: f64,
    /// Angle of embrace `2β` (rad), in `(0, 2π)`; `π` is the semicircular arch.
    pub embrace_angle: f64,
    /// Number of voussoirs `N >= 1`.
    pub voussoirs: usize,
    /// Density (kg/m³).
    pub density: f64,
    /// Depth out of plane (m).
    pub depth: f64,
}

/// Mass properties of the annular sector between radii `r1 < r2` and polar angles
/// `theta_a > theta_b`, per unit density and depth: (area, centroid, polar moment about the
/// centroid).
pub fn annular_sector(r1: f64, r2: f64, theta_a: f64, theta_b: f64) -> (f64, [f64; 2], f64) {
    let alpha = 0.5 * (theta_a - theta_b);
    let mid = 0.5 * (theta_a + theta_b);
    let area = alpha * (r2 * r2 - r1 * r1);
    let d = 2.0 * alpha.sin() * (r2.powi(3) - r1.powi(3)) / (3.0 * alpha * (r2 * r2 - r1 * r1));
    let polar_origin = 0.5 * alpha * (r2.powi(4) - r1.powi(4));
    (
        area,
        [d * mid.cos(), d * mid.sin()],
        polar_origin - area * d * d,
    )
}

impl VoussoirArch {
    /// A semicircular arch of unit depth and density 2000 kg/m³.
    pub fn semicircular(radius: f64, thickness: f64, voussoirs: usize) -> VoussoirArch {
        VoussoirArch {
            radius,
            thickness,
            embrace_angle: std::f64::consts::PI,
            voussoirs,
            density: 2000.0,
            depth: 1.0,
        }
    }

    /// Checks the fields (each error names its field).
    pub fn validate(&self) -> Result<(), InvalidValue> {
        validate::positive("arch.radius", self.radius)?;
        validate::positive("arch.thickness", self.thickness)?;
        if self.thickness >= 2.0 * self.radius {
            return Err(InvalidValue::new(
                "arch.thickness",
                self.thickness,
                "must be less than twice the radius (the intrados radius R − t/2 must be positive)",
            ));
        }
        validate::positive("arch.embrace_angle", self.embrace_angle)?;
        if self.embrace_angle >= 2.0 * std::f64::consts::PI {
            return Err(InvalidValue::new(
                "arch.embrace_angle",
                self.embrace_angle,
                "must be less than 2π (a full ring has no abutments)",
            ));
        }
        if self.voussoirs == 0 {
            return Err(InvalidValue::new(
                "arch.voussoirs",
                self.voussoirs,
                "must be at least 1",
            ));
        }
        // The rule's text names the maximum; keep it in step with the constant.
        const _: () = assert!(crate::model::configuration::MAX_INTERFACES == 4096);
        if self.voussoirs >= crate::model::configuration::MAX_INTERFACES {
            return Err(InvalidValue::new(
                "arch.voussoirs",
                self.voussoirs,
                "must be at most 4095 (its voussoirs + 1 joints are at most the models' \
                 supported maximum of 4096 interfaces)",
            ));
        }
        validate::positive("arch.density", self.density)?;
        validate::positive("arch.depth", self.depth)?;
        Ok(())
    }

    /// Checks that a time history or a spectrum of the arch makes sense and ends: at least 3
    /// voussoirs (with fewer than 4 joints no mechanism can open, a loop moves only with four or
    /// more open joints, SPEC §9, so the arch would stay at rest under any ground motion) and at
    /// most [`MAX_RUN_VOUSSOIRS`]. [`VoussoirArch::validate`] accepts both (the arch's system is
    /// well defined for the C helper up to 4095 voussoirs).
    pub fn runnable(&self) -> Result<(), InvalidValue> {
        if self.voussoirs < 3 {
            return Err(InvalidValue::new(
                "arch.voussoirs",
                self.voussoirs,
                "must be at least 3 to move: with fewer than 4 joints no mechanism can open \
                 (a loop needs four open joints, SPEC §9), so the arch never moves",
            ));
        }
        // The text names the limit; keep it in step.
        const _: () = assert!(MAX_RUN_VOUSSOIRS == 1000);
        if self.voussoirs > MAX_RUN_VOUSSOIRS {
            return Err(InvalidValue::new(
                "arch.voussoirs",
                self.voussoirs,
                "must be at most 1000 for a time history or a spectrum: at rest the driver \
                 bisects what the closed arch resists with the dense opening model, whose cost \
                 grows as the cube of the joints (500 voussoirs: 6 s, 1000: 45 s, 2000: over \
                 200 s, 4095: hours and 2 GB)",
            ));
        }
        Ok(())
    }

    /// Half the angle of embrace, `β`.
    pub fn half_embrace(&self) -> f64 {
        0.5 * self.embrace_angle
    }

    /// Polar angle `θ_k` of joint `k` (0 at the left springing, `N` at the right one).
    pub fn joint_polar_angle(&self, k: usize) -> f64 {
        let beta = self.half_embrace();
        std::f64::consts::FRAC_PI_2 + beta - 2.0 * beta * k as f64 / self.voussoirs as f64
    }

    /// Angle of joint `k` from the left springing, `2βk/N`.
    pub fn joint_position(&self, k: usize) -> f64 {
        self.embrace_angle * k as f64 / self.voussoirs as f64
    }

    /// The loop: `N` voussoirs, `N + 1` joints.
    pub fn chain(&self) -> Result<Chain, InvalidValue> {
        self.validate()?;
        let (r1, r2) = (
            self.radius - 0.5 * self.thickness,
            self.radius + 0.5 * self.thickness,
        );
        let rho = self.density * self.depth;
        let n = self.voussoirs;
        let bodies: Vec<Body> = (0..n)
            .map(|k| {
                let (area, centre, polar) = annular_sector(
                    r1,
                    r2,
                    self.joint_polar_angle(k),
                    self.joint_polar_angle(k + 1),
                );
                Body {
                    mass: rho * area,
                    inertia: rho * polar,
                    centre,
                }
            })
            .collect();
        let joints: Vec<Joint> = (0..=n)
            .map(|k| {
                let th = self.joint_polar_angle(k);
                Joint {
                    centre: [self.radius * th.cos(), self.radius * th.sin()],
                    normal: [th.sin(), -th.cos()],
                    half_width: 0.5 * self.thickness,
                }
            })
            .collect();
        super::check_derived(&bodies, &joints, "arch", || {
            format!(
                "{{radius: {:?}, thickness: {:?}, density: {:?}, depth: {:?}}}",
                self.radius, self.thickness, self.density, self.depth
            )
        })?;
        Chain::new(bodies, joints)
    }
}
