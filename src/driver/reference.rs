//! Exact reference of a single block in free rocking, by quadrature of the single-block equation
//! `I_P θ̈ = −m g R sin(δ − θ)` (`0 < θ < δ`, θ = |φ|, uniform rectangular block, `I_P = 4/3 m R²`):
//! impact times, amplitudes and energies with a constant velocity ratio μ at every impact.
//!
//! Used by the driver's acceptance tests and by `rocking bench accuracy`.

/// Exact free rocking of one uniform rectangular block about its corners.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SingleBlockExact {
    /// Slenderness angle δ (rad), `tan δ = b / h`.
    pub delta: f64,
    /// `m g R / I_P` (= p²) (1/s²).
    pub p2: f64,
}

impl SingleBlockExact {
    /// A uniform block `2b × 2h` (half dimensions `b`, `h` (m), as Housner and Appendix A)
    /// under gravity `g` (m/s²).
    pub fn new(b: f64, h: f64, g: f64) -> SingleBlockExact {
        let r = (b * b + h * h).sqrt();
        // I_P = m R² + m ((2b)² + (2h)²) / 12 = 4/3 m R².
        SingleBlockExact {
            delta: (b / h).atan(),
            p2: g * r / (4.0 / 3.0 * r * r),
        }
    }

    /// Time to fall from rest at `theta0` (rad) to `θ = 0` (a quarter of the rocking period) (s):
    /// `∫ dθ / ω`, `ω² = 2 p² (cos(δ − θ0) − cos(δ − θ))`, by the midpoint rule after
    /// `θ = θ0 (1 − s²)` (which removes the square-root singularity at θ0), Richardson-extrapolated.
    pub fn quarter(&self, theta0: f64) -> f64 {
        // Midpoint rule (error ∝ 1/N² for this smooth integrand), Richardson-extrapolated.
        (4.0 * self.midpoint(theta0, 40_000) - self.midpoint(theta0, 20_000)) / 3.0
    }

    fn midpoint(&self, theta0: f64, n: usize) -> f64 {
        let mut sum = 0.0;
        for i in 0..n {
            let s = (i as f64 + 0.5) / n as f64;
            let theta = theta0 * (1.0 - s * s);
            // cos(δ − θ0) − cos(δ − θ) = 2 sin(δ − (θ0 + θ)/2) sin((θ0 − θ)/2): the product
            // form has no cancellation near θ0 (the difference of cosines lost ~1e-10 s per
            // quarter period there).
            let w2 = 4.0
                * self.p2
                * (self.delta - 0.5 * (theta0 + theta)).sin()
                * (0.5 * theta0 * s * s).sin();
            sum += 2.0 * theta0 * s / w2.sqrt();
        }
        sum / n as f64
    }

    /// Amplitude (rad) reached from `θ = 0` with rate `omega` (rad/s).
    pub fn amplitude(&self, omega: f64) -> f64 {
        let c = self.delta.cos() + 0.5 * omega * omega / self.p2;
        self.delta - c.acos()
    }

    /// Rate (rad/s) at `θ = 0` after falling from rest at `theta0` (rad).
    pub fn rate_at_zero(&self, theta0: f64) -> f64 {
        (2.0 * self.p2 * ((self.delta - theta0).cos() - self.delta.cos())).sqrt()
    }

    /// Potential energy above the closed position per unit `m g R` at angle `theta` (rad):
    /// `cos(δ − θ) − cos δ` (dimensionless).
    pub fn potential(&self, theta: f64) -> f64 {
        (self.delta - theta).cos() - self.delta.cos()
    }

    /// Times (s) of the first `count` impacts after release from rest at `theta0` (rad), with
    /// a constant velocity ratio `mu` at every impact.
    pub fn impact_times(&self, theta0: f64, mu: f64, count: usize) -> Vec<f64> {
        let mut t = self.quarter(theta0);
        let mut out = vec![t];
        let mut omega = self.rate_at_zero(theta0);
        for _ in 1..count {
            omega *= mu;
            let a = self.amplitude(omega);
            t += 2.0 * self.quarter(a);
            out.push(t);
        }
        out.truncate(count);
        out
    }

    /// Amplitudes (rad) of the swings after each of the first `count` impacts.
    pub fn amplitudes_after_impacts(&self, theta0: f64, mu: f64, count: usize) -> Vec<f64> {
        let mut omega = self.rate_at_zero(theta0);
        (0..count)
            .map(|_| {
                omega *= mu;
                self.amplitude(omega)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_angle_limit_is_the_pendulum_quarter_period() {
        // For θ0 → 0 and δ → 0 the motion is θ̈ = p² (θ − δ): fall from θ0 to 0 in
        // acosh(δ / (δ − θ0)) / p.
        let e = SingleBlockExact::new(0.001, 1.0, 9.81);
        let theta0 = 0.5 * e.delta;
        let t = (e.delta / (e.delta - theta0)).acosh() / e.p2.sqrt();
        assert!((e.quarter(theta0) - t).abs() < 1e-6 * t);
        // Energy: the rate at zero carries the potential energy.
        let w = e.rate_at_zero(theta0);
        assert!((0.5 * w * w / e.p2 - e.potential(theta0)).abs() < 1e-15);
        assert!((e.amplitude(w) - theta0).abs() < 1e-9);
    }
}
