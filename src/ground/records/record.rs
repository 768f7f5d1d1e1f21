//! The record itself: samples at a uniform time step, linear interpolation, tail impulses,
//! peak ground acceleration and scaling.

use super::{invalid, RecordError};
use crate::validate::{all_finite, positive};

/// A uniformly sampled ground-acceleration record. Sample `i` is the acceleration at `t = i·dt`.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Name for messages and plots (file stem for files read from disk).
    pub name: String,
    /// Time step \[s\], finite and positive.
    pub dt: f64,
    /// Ground accelerations \[m/s²\], positive = ground accelerates to +x.
    pub samples: Vec<f64>,
}

impl Record {
    /// A record with validated fields: `dt` finite and positive, every sample finite.
    pub fn new(name: &str, dt: f64, samples: Vec<f64>) -> Result<Record, RecordError> {
        let record = Record {
            name: name.to_string(),
            dt,
            samples,
        };
        record.validate()?;
        Ok(record)
    }

    /// Checks the fields: `dt` finite and positive, every sample finite.
    pub fn validate(&self) -> Result<(), RecordError> {
        positive("dt", self.dt)?;
        all_finite("samples", &self.samples)?;
        Ok(())
    }

    /// Ground acceleration at time `t` \[m/s²\]: linear interpolation between samples, zero before
    /// `t = 0`, after the last sample and for NaN `t`. O(1) and allocation-free
    /// (`i = floor(t / dt)`).
    #[inline]
    pub fn acceleration(&self, t: f64) -> f64 {
        let n = self.samples.len();
        let x = t / self.dt;
        // `contains` is false for NaN too.
        if n == 0 || !(0.0..=(n - 1) as f64).contains(&x) {
            return 0.0;
        }
        let i = x as usize; // floor, x >= 0
        if i + 1 >= n {
            return self.samples[n - 1];
        }
        let s = x - i as f64;
        let a0 = self.samples[i];
        a0 + s * (self.samples[i + 1] - a0)
    }

    /// Time of the last sample, `(n − 1)·dt` \[s\] (0 for fewer than two samples); the acceleration
    /// is zero after it.
    pub fn duration(&self) -> f64 {
        self.samples.len().saturating_sub(1) as f64 * self.dt
    }

    /// `S[i] = ∫_{t_i}^{end} |a(t)| dt` of the linearly interpolated record (m/s), one entry per
    /// sample (the last is 0): the tail impulses that [`Record::impulse_after`] reads.
    pub(crate) fn impulse_table(&self) -> Vec<f64> {
        let n = self.samples.len();
        let mut table = vec![0.0; n];
        for i in (0..n.saturating_sub(1)).rev() {
            table[i] = table[i + 1] + abs_integral(self.samples[i], self.samples[i + 1], self.dt);
        }
        table
    }

    /// `∫_t^end |a(s)| ds` (m/s) of the linearly interpolated record, from the `table` of
    /// [`Record::impulse_table`] (0 after the end, the whole record's before the start).
    pub(crate) fn impulse_after(&self, table: &[f64], t: f64) -> f64 {
        let n = self.samples.len().min(table.len());
        if n == 0 {
            return 0.0;
        }
        let x = t / self.dt;
        if x.is_nan() || x <= 0.0 {
            return table[0];
        }
        if x >= (n - 1) as f64 {
            return 0.0;
        }
        let i = x as usize;
        let rest = (i + 1) as f64 - x;
        let b = self.samples[i + 1];
        let a = b + rest * (self.samples[i] - b);
        table[i + 1] + abs_integral(a, b, rest * self.dt)
    }

    /// Peak ground acceleration `max |a|` \[m/s²\] (0 for an empty record). With linear
    /// interpolation this is also the peak of [`Record::acceleration`] over time.
    pub fn pga(&self) -> f64 {
        self.samples.iter().fold(0.0, |m, a| m.max(a.abs()))
    }

    /// The record with every sample multiplied by `factor` (same name, same `dt`).
    pub fn scaled(&self, factor: f64) -> Record {
        Record {
            name: self.name.clone(),
            dt: self.dt,
            samples: self.samples.iter().map(|a| a * factor).collect(),
        }
    }

    /// The record scaled so that its peak ground acceleration is `target` \[m/s²\] (frequency
    /// content unchanged, as the overturning acceleration spectra of SPEC §7 scale records).
    /// Errors: `target` not finite and positive, or a record whose PGA is zero.
    pub fn scaled_to_pga(&self, target: f64) -> Result<Record, RecordError> {
        positive("target", target)?;
        let pga = self.pga();
        if !(pga > 0.0 && pga.is_finite()) {
            return Err(invalid(
                "samples",
                format!("record `{}` has PGA {pga}, it cannot be scaled", self.name),
            ));
        }
        Ok(self.scaled(target / pga))
    }
}

/// `∫_0^h |a + (b − a) s/h| ds`: a trapezoid, or two triangles when the segment crosses zero.
fn abs_integral(a: f64, b: f64, h: f64) -> f64 {
    if a * b >= 0.0 {
        0.5 * h * (a.abs() + b.abs())
    } else {
        0.5 * h * (a * a + b * b) / (a.abs() + b.abs())
    }
}
