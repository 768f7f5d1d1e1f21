//! `t_1` with its uncertainty (issue 14, item 3): the same OAS under small changes that a careful
//! analyst would call equivalent, and the spread of `t_1` over them.
//!
//! `t_1` is set by one grid point of the OAS boundary, usually a column that survives the strong
//! motion and tips seconds later, where overturning is chaotic: one step more or less, one cell of
//! the grid further, and the verdict of that point changes. The band makes that visible: the
//! spectrum is recomputed with the time step halved, with the level grid and the size grid each
//! shifted by half a cell, and with the other event locator (Hermite for linear, linear for
//! Hermite). `t1_range` is the smallest and largest `t_1` of the nominal spectrum and these four;
//! `t1_conservative` is `i_cr / f_min` of their envelope (at every level, the union of the unsafe
//! points), which is the largest `t_1` of the five since they share `i_cr`.

use super::{oas, Oas, OasOptions, Progress, SpectraError};
use crate::driver::EventLocator;
use crate::ground::records::Record;

/// One perturbation of the nominal OAS options.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Perturbation {
    /// The nominal options.
    Nominal,
    /// The time step rule halved.
    HalfStep,
    /// Levels at the midpoints of consecutive nominal levels (one fewer).
    LevelsShifted,
    /// Sizes at the geometric midpoints of consecutive nominal sizes (one fewer; the sizes are
    /// log-spaced, so this is half a cell).
    SizesShifted,
    /// The other event locator.
    OtherLocator,
}

impl Perturbation {
    /// Every perturbation, the nominal first.
    pub const ALL: [Perturbation; 5] = [
        Perturbation::Nominal,
        Perturbation::HalfStep,
        Perturbation::LevelsShifted,
        Perturbation::SizesShifted,
        Perturbation::OtherLocator,
    ];

    /// A short name (reports).
    pub fn name(self) -> &'static str {
        match self {
            Perturbation::Nominal => "nominal",
            Perturbation::HalfStep => "half-step",
            Perturbation::LevelsShifted => "levels-shifted",
            Perturbation::SizesShifted => "sizes-shifted",
            Perturbation::OtherLocator => "other-locator",
        }
    }

    /// The options of this perturbation of `nominal`.
    pub fn apply(self, nominal: &OasOptions) -> OasOptions {
        let mut o = nominal.clone();
        match self {
            Perturbation::Nominal => {}
            Perturbation::HalfStep => o.sweep.time_step = o.sweep.time_step.scaled(0.5),
            Perturbation::LevelsShifted => {
                let shifted: Vec<f64> = o.levels.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
                if !shifted.is_empty() {
                    o.levels = shifted;
                }
            }
            Perturbation::SizesShifted => {
                let shifted: Vec<f64> = o.sizes.windows(2).map(|w| (w[0] * w[1]).sqrt()).collect();
                if !shifted.is_empty() {
                    o.sizes = shifted;
                }
            }
            Perturbation::OtherLocator => {
                let l = &mut o.sweep.simulation.stepping.locator;
                *l = match *l {
                    EventLocator::Linear => EventLocator::Hermite,
                    _ => EventLocator::Linear,
                };
            }
        }
        o
    }
}

/// `t_1` of a record with its band.
#[derive(Clone, Debug, PartialEq)]
pub struct T1Band {
    /// `t_1` of each perturbation, in the order of [`Perturbation::ALL`] (`None`: nothing
    /// overturned on that grid).
    pub members: Vec<(Perturbation, Option<f64>)>,
    /// `[min, max]` of the members' `t_1` (`None` when no member has one).
    pub t1_range: Option<[f64; 2]>,
    /// `i_cr / f_min` of the envelope of the members' spectra.
    pub t1_conservative: Option<f64>,
    /// Simulations of all members.
    pub simulations: usize,
}

impl T1Band {
    /// The band of spectra computed for the perturbations `members` (same record, slenderness
    /// and column, so the same `i_cr`).
    pub fn of(members: &[(Perturbation, Oas)]) -> T1Band {
        let t1s: Vec<(Perturbation, Option<f64>)> =
            members.iter().map(|(p, o)| (*p, o.t1())).collect();
        let known = t1s.iter().filter_map(|(_, t)| *t);
        let t1_range = known.fold(None, |r: Option<[f64; 2]>, t| {
            Some(r.map_or([t, t], |[lo, hi]| [lo.min(t), hi.max(t)]))
        });
        // The envelope's f_min: the lowest f of any member's boundary.
        let envelope = members
            .iter()
            .filter_map(|(_, o)| o.f_min().map(|m| (m.f, o.i_cr())))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        T1Band {
            members: t1s,
            t1_range,
            t1_conservative: envelope.map(|(f, i_cr)| i_cr / f),
            simulations: members.iter().map(|(_, o)| o.simulations()).sum(),
        }
    }
}

/// The nominal OAS of `record` and the band of `t_1` over [`Perturbation::ALL`].
pub fn t1_band(
    record: &Record,
    options: &OasOptions,
    progress: Option<Progress<'_>>,
) -> Result<(Oas, T1Band), SpectraError> {
    t1_band_with(options, |o| oas(record, o, progress))
}

/// [`t1_band`] with each spectrum computed by `spectrum` (the OAS of the record under the
/// options given, as [`oas`] computes it): for a caller that runs the OAS its own way (the
/// Python package, on its interruptible runner), with the same spectra and the same band.
pub fn t1_band_with<E>(
    options: &OasOptions,
    mut spectrum: impl FnMut(&OasOptions) -> Result<Oas, E>,
) -> Result<(Oas, T1Band), E> {
    let nominal = spectrum(options)?;
    t1_band_around(nominal, options, spectrum)
}

/// The band of `t_1` around a nominal spectrum already computed under `options` (the step
/// converged by [`super::t1_step_converged`], say): the other perturbations of `options`
/// computed by `spectrum`, in the order of [`Perturbation::ALL`]; the nominal is given back.
pub fn t1_band_around<E>(
    nominal: Oas,
    options: &OasOptions,
    mut spectrum: impl FnMut(&OasOptions) -> Result<Oas, E>,
) -> Result<(Oas, T1Band), E> {
    let mut members = Vec::with_capacity(Perturbation::ALL.len());
    members.push((Perturbation::Nominal, nominal));
    for p in &Perturbation::ALL[1..] {
        members.push((*p, spectrum(&p.apply(options))?));
    }
    let band = T1Band::of(&members);
    let nominal = members.swap_remove(0).1;
    Ok((nominal, band))
}
