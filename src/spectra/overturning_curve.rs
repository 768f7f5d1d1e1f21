//! Overturning curves (OC) of pulses: safe / unsafe on a grid of pulse durations and peak
//! accelerations (thesis Fig. 8, 33, 40, 41).

use super::sweep::map_indexed;
use super::{Progress, SpectraError, SweepOptions};
use crate::driver::overturns_with;
use crate::ground::excitation::{Excitation, Pulse};
use crate::model::column::Column;
use crate::model::single_block::EquivalentBlock;
use crate::validate::all_positive;

/// The shape of a pulse family for an overturning curve; `t_p` is its duration parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PulseShape {
    /// `lobes` half sines of alternating sign; `t_p` = duration of one half sine (thesis Fig. 8:
    /// 1 = half sine, 2 = full sine, 3 = three half sines).
    HalfSines {
        /// Number of half sines.
        lobes: u32,
    },
    /// Rectangular pulse of duration `t_p`.
    Rectangular,
    /// Symmetric triangular pulse of duration `t_p`.
    Triangular,
    /// Ricker wavelet of peak frequency `1/t_p`.
    Ricker,
    /// Mavroeidis–Papageorgiou pulse of period `t_p` (frequency `1/t_p`).
    MavroeidisPapageorgiou {
        /// Oscillatory character `γ`.
        gamma: f64,
        /// Phase `ν` \[rad\].
        nu: f64,
    },
}

impl PulseShape {
    /// Half sine (thesis Fig. 8a, 33).
    pub const fn half_sine() -> PulseShape {
        PulseShape::HalfSines { lobes: 1 }
    }
    /// Full sine (thesis Fig. 8b, 39, 40).
    pub const fn full_sine() -> PulseShape {
        PulseShape::HalfSines { lobes: 2 }
    }
    /// Three half sines (thesis Fig. 8c).
    pub const fn three_half_sines() -> PulseShape {
        PulseShape::HalfSines { lobes: 3 }
    }

    /// The pulse of peak `a_p` \[m/s²\] and duration parameter `t_p` \[s\].
    pub fn pulse(&self, a_p: f64, t_p: f64) -> Result<Pulse, SpectraError> {
        Ok(match *self {
            PulseShape::HalfSines { lobes } => Pulse::half_sines(a_p, t_p, lobes)?,
            PulseShape::Rectangular => Pulse::rectangular(a_p, t_p)?,
            PulseShape::Triangular => Pulse::triangular(a_p, t_p)?,
            PulseShape::Ricker => Pulse::ricker(a_p, 1.0 / t_p)?,
            PulseShape::MavroeidisPapageorgiou { gamma, nu } => {
                Pulse::mavroeidis_papageorgiou(a_p, 1.0 / t_p, gamma, nu)?
            }
        })
    }

    /// A short name (`half-sine`, `full-sine`, `3-half-sines`, `rectangular`, …).
    pub fn name(&self) -> String {
        match *self {
            PulseShape::HalfSines { lobes: 1 } => "half-sine".into(),
            PulseShape::HalfSines { lobes: 2 } => "full-sine".into(),
            PulseShape::HalfSines { lobes } => format!("{lobes}-half-sines"),
            PulseShape::Rectangular => "rectangular".into(),
            PulseShape::Triangular => "triangular".into(),
            PulseShape::Ricker => "ricker".into(),
            PulseShape::MavroeidisPapageorgiou { gamma, nu } => format!("mp-g{gamma}-nu{nu}"),
        }
    }
}

/// Whether `column` overturns under the pulse `shape(a_p, t_p)` (one point of an OC).
pub fn pulse_overturns(
    column: &Column,
    shape: PulseShape,
    a_p: f64,
    t_p: f64,
    options: &SweepOptions,
) -> Result<bool, SpectraError> {
    options.validate()?;
    let g = options.simulation.physics.gravity;
    let p = EquivalentBlock::of_column(column).frequency_parameter(g);
    let pulse = shape.pulse(a_p, t_p)?;
    // Never lifts off: no simulation needed (the peak of every shape is |a_p|).
    if a_p.abs() < column.static_uplift_acceleration(g) * (1.0 - 1e-9) {
        return Ok(false);
    }
    let dt = options.time_step.dt(None, Some(t_p), p);
    let sim = options.simulation(dt, pulse.end_time() + options.tail / p);
    Ok(overturns_with(column, &Excitation::Pulse(pulse), sim)?)
}

/// An overturning curve: safe / unsafe on a grid of `(t_p, a_p)` (thesis Fig. 8, 33, 40, 41).
#[derive(Clone, Debug, PartialEq)]
pub struct Oc {
    /// Pulse shape.
    pub shape: PulseShape,
    /// Equivalent block of the column (normalisation).
    pub block: EquivalentBlock,
    /// Acceleration of gravity used \[m/s²\].
    pub gravity: f64,
    /// Number of blocks.
    pub n_blocks: usize,
    /// Pulse durations `t_p` \[s\] (rows).
    pub t_p: Vec<f64>,
    /// Peak accelerations `a_p` \[m/s²\] (columns).
    pub a_p: Vec<f64>,
    /// `overturned[i * a_p.len() + j]`: the column overturns under `(t_p[i], a_p[j])`.
    pub overturned: Vec<bool>,
}

impl Oc {
    /// Whether `(t_p[i], a_p[j])` overturns the column.
    pub fn is_unsafe(&self, i: usize, j: usize) -> bool {
        self.overturned[i * self.a_p.len() + j]
    }

    /// Number of unsafe grid points.
    pub fn unsafe_count(&self) -> usize {
        self.overturned.iter().filter(|&&u| u).count()
    }

    /// The envelope: for each `t_p`, the smallest unsafe `a_p` of the grid (`None`: none
    /// overturns). Safe bays above it are ignored (thesis 1: "a single envelope can be used for
    /// design purposes").
    pub fn envelope(&self) -> Vec<Option<f64>> {
        (0..self.t_p.len())
            .map(|i| {
                (0..self.a_p.len())
                    .filter(|&j| self.is_unsafe(i, j))
                    .map(|j| self.a_p[j])
                    .reduce(f64::min)
            })
            .collect()
    }

    /// Normalised coordinates of every grid point: `(p t_p, a_p / a_p,min, unsafe)` (Fig. 33a).
    pub fn normalised(&self) -> Vec<(f64, f64, bool)> {
        let (p, a_p_min) = self.axes();
        let mut out = Vec::with_capacity(self.overturned.len());
        for (i, &t) in self.t_p.iter().enumerate() {
            for (j, &a) in self.a_p.iter().enumerate() {
                out.push((p * t, a / a_p_min, self.is_unsafe(i, j)));
            }
        }
        out
    }

    /// The envelope in normalised coordinates `(p t_p, a_p / a_p,min)`.
    pub fn normalised_envelope(&self) -> Vec<(f64, Option<f64>)> {
        let (p, a_p_min) = self.axes();
        self.t_p
            .iter()
            .zip(self.envelope())
            .map(|(&t, e)| (p * t, e.map(|a| a / a_p_min)))
            .collect()
    }

    /// `p` and `a_p,min` of the equivalent block.
    fn axes(&self) -> (f64, f64) {
        (
            self.block.frequency_parameter(self.gravity),
            self.block.a_p_min(self.gravity),
        )
    }
}

/// The overturning curve of `column` for `shape` on the grid `t_p × a_p`, parallel over `t_p`.
pub fn overturning_curve(
    column: &Column,
    shape: PulseShape,
    t_p: &[f64],
    a_p: &[f64],
    options: &SweepOptions,
    progress: Option<Progress<'_>>,
) -> Result<Oc, SpectraError> {
    options.validate()?;
    all_positive("t_p", t_p)?;
    all_positive("a_p", a_p)?;
    let rows = map_indexed(t_p.len(), |i| {
        let row: Result<Vec<bool>, SpectraError> = a_p
            .iter()
            .map(|&a| pulse_overturns(column, shape, a, t_p[i], options))
            .collect();
        if let Some(p) = progress {
            p();
        }
        row
    });
    let mut overturned = Vec::with_capacity(t_p.len() * a_p.len());
    for row in rows {
        overturned.extend(row?);
    }
    Ok(Oc {
        shape,
        block: EquivalentBlock::of_column(column),
        gravity: options.simulation.physics.gravity,
        n_blocks: column.n_interfaces(),
        t_p: t_p.to_vec(),
        a_p: a_p.to_vec(),
        overturned,
    })
}
