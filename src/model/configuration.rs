//! Interface statuses (crack configurations) and the validation of model inputs.
//!
//! Status of interface `k`: −1 open about the RIGHT corner (only `phĭ_k` non-zero, `<= 0`),
//! 0 closed, +1 open about the LEFT corner (only `phî_k` non-zero, `>= 0`) — SPEC §1.

use crate::error::{ErrorKind, RockingError};

/// Largest number of interfaces the models accept.
pub const MAX_INTERFACES: usize = 4096;

/// Status of one interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(i8)]
pub enum Status {
    /// Open about the right corner: `phĭ_k` is the DOF, admissible `<= 0`.
    OpenRight = -1,
    /// Closed: both DOFs zero.
    Closed = 0,
    /// Open about the left corner: `phî_k` is the DOF, admissible `>= 0`.
    OpenLeft = 1,
}

/// With the `serde` feature a status is its C value: -1, 0 or 1.
#[cfg(feature = "serde")]
impl serde::Serialize for Status {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_i8(self.as_i8())
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Status {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Status, D::Error> {
        let v = i8::deserialize(d)?;
        Status::from_i8(v)
            .ok_or_else(|| serde::de::Error::custom(format!("a status is -1, 0 or 1, got {v}")))
    }
}

impl Status {
    /// Decodes a C status value.
    pub fn from_i8(v: i8) -> Option<Status> {
        match v {
            -1 => Some(Status::OpenRight),
            0 => Some(Status::Closed),
            1 => Some(Status::OpenLeft),
            _ => None,
        }
    }

    /// The C value.
    pub fn as_i8(self) -> i8 {
        self as i8
    }

    /// Whether the interface is open.
    pub fn is_open(self) -> bool {
        self != Status::Closed
    }

    /// Index in `0..2n` of the active DOF of interface `k` (None if closed).
    pub fn dof(self, k: usize, n: usize) -> Option<usize> {
        match self {
            Status::OpenRight => Some(k),
            Status::OpenLeft => Some(n + k),
            Status::Closed => None,
        }
    }

    /// Admissible sign of the DOF's angle (−1 for `phĭ`, +1 for `phî`, 0 when closed).
    pub fn sign(self) -> f64 {
        self.as_i8() as f64
    }

    /// The status whose DOF is `dof` of interface `dof % n`.
    pub fn of_dof(dof: usize, n: usize) -> Status {
        if dof < n {
            Status::OpenRight
        } else {
            Status::OpenLeft
        }
    }
}

/// Decodes and checks a status array.
pub fn decode_statuses(raw: &[i8]) -> Result<Vec<Status>, RockingError> {
    raw.iter()
        .enumerate()
        .map(|(k, &v)| {
            Status::from_i8(v).ok_or_else(|| {
                RockingError::new(
                    ErrorKind::InvalidStatus,
                    format!("status[{k}] = {v}, expected -1, 0 or 1"),
                )
            })
        })
        .collect()
}

/// Encodes statuses into a C array.
pub fn encode_statuses(statuses: &[Status], out: &mut [i8]) {
    for (o, s) in out.iter_mut().zip(statuses) {
        *o = s.as_i8();
    }
}

/// The open DOFs (indices into `0..2n`) of a configuration, in interface order.
pub fn open_dofs(statuses: &[Status]) -> Vec<usize> {
    let n = statuses.len();
    statuses
        .iter()
        .enumerate()
        .filter_map(|(k, s)| s.dof(k, n))
        .collect()
}

/// Checks the interface count.
pub fn check_size(n: usize) -> Result<(), RockingError> {
    check_size_named("n_interfaces", n)
}

/// [`check_size`] of the argument `name` (`rocking_column_mass_matrix`'s `n_blocks`): the
/// messages name it.
pub fn check_size_named(name: &str, n: usize) -> Result<(), RockingError> {
    if n == 0 {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("{name} is 0"),
        ));
    }
    if n > MAX_INTERFACES {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!("{name} = {n} exceeds the supported maximum {MAX_INTERFACES}"),
        ));
    }
    Ok(())
}

/// Checks that a vector over the DOFs has `2n` entries (`m = 2n`), naming it in the error.
pub(crate) fn check_dof_vector(name: &str, values: &[f64], m: usize) -> Result<(), RockingError> {
    if values.len() == m {
        return Ok(());
    }
    Err(RockingError::new(
        ErrorKind::InvalidSize,
        format!("{name} has {} entries, expected 2n = {m}", values.len()),
    ))
}

/// Checks that every value of `values` is finite.
pub fn check_finite(name: &str, values: &[f64]) -> Result<(), RockingError> {
    // All finite (the usual case) in one branch-free sweep; the first one that is not, if any.
    if values.iter().fold(true, |ok, v| ok & v.is_finite()) {
        return Ok(());
    }
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(RockingError::new(
            ErrorKind::NotFinite,
            format!("{name}[{i}] = {}", values[i]),
        )),
    }
}

/// Checks the ground acceleration and gravity (m/s²) of a system helper: both finite
/// (`NotFinite`), and gravity positive, the magnitude of g pointing down (`InvalidGeometry`: an
/// FE code's `g_y = −9.81`, or a forgotten 0, would turn the load upside down, or off).
pub fn check_accelerations(ground_acceleration: f64, gravity: f64) -> Result<(), RockingError> {
    for (name, v) in [
        ("ground_acceleration", ground_acceleration),
        ("gravity", gravity),
    ] {
        if !v.is_finite() {
            return Err(RockingError::new(
                ErrorKind::NotFinite,
                format!("{name} = {v}"),
            ));
        }
    }
    crate::validate::positive("gravity", gravity)
        .map(|_| ())
        .map_err(|e| {
            RockingError::new(
                ErrorKind::InvalidGeometry,
                format!("{e} (the magnitude of g, pointing down)"),
            )
        })
}

/// Checks that a `m × m` matrix is finite and symmetric: entry by entry,
/// `|M_rc − M_cr| <= 1e-9 max(|M_rc|, |M_cr|) + 1e-14 √(|M_rr M_cc|)` — relative to the entry,
/// with a floor at the natural size of an off-diagonal entry of a positive definite matrix, so
/// that round-off of an FE code's `BᵀMB` passes and a real asymmetry never hides behind a
/// large entry elsewhere in the matrix.
pub fn check_symmetric(mass: &[f64], m: usize) -> Result<(), RockingError> {
    check_symmetric_named("mass", mass, m)
}

/// [`check_symmetric`] of the argument `name` (`rocking_reduce`'s `nodal_mass`): the messages
/// name it.
pub fn check_symmetric_named(name: &str, mass: &[f64], m: usize) -> Result<(), RockingError> {
    check_finite(name, mass)?;
    // Equal entries pass (finite: |a − b| = 0 is below the non-negative bound) without the
    // bound's square root: a matrix symmetric to the bit (the chains' are) in one sweep.
    if symmetric_to_the_bit(mass, m) {
        return Ok(());
    }
    for r in 0..m {
        for c in r + 1..m {
            let (a, b) = (mass[r * m + c], mass[c * m + r]);
            let floor = (mass[r * m + r] * mass[c * m + c]).abs().sqrt();
            if (a - b).abs() > 1e-9 * a.abs().max(b.abs()) + 1e-14 * floor {
                return Err(RockingError::new(
                    ErrorKind::NotSymmetric,
                    format!("{name}[{r}][{c}] = {a} but {name}[{c}][{r}] = {b}"),
                ));
            }
        }
    }
    Ok(())
}

/// Whether `M_rc == M_cr` for every pair (finite entries): four rows at a time, each against
/// four consecutive entries of the rows below (the same pairs as one loop over the upper
/// triangle, whose verdict does not depend on the order).
fn symmetric_to_the_bit(mass: &[f64], m: usize) -> bool {
    let mut equal = true;
    let mut r = 0;
    while r + 4 <= m {
        // The pairs inside the block, then the columns after it.
        for i in r..r + 4 {
            for c in i + 1..r + 4 {
                equal &= mass[i * m + c] == mass[c * m + i];
            }
        }
        let rows = &mass[r * m..(r + 4) * m];
        let (r0, rest) = rows.split_at(m);
        let (r1, rest) = rest.split_at(m);
        let (r2, r3) = rest.split_at(m);
        for c in r + 4..m {
            let col = &mass[c * m + r..c * m + r + 4];
            equal &= (r0[c] == col[0]) & (r1[c] == col[1]) & (r2[c] == col[2]) & (r3[c] == col[3]);
        }
        r += 4;
    }
    for i in r..m {
        for c in i + 1..m {
            equal &= mass[i * m + c] == mass[c * m + i];
        }
    }
    equal
}

/// Checks that a DOF vector (velocities or angles) is zero on every DOF that is not open.
pub fn check_zero_off_configuration(
    name: &str,
    statuses: &[Status],
    values: &[f64],
    kind: ErrorKind,
) -> Result<(), RockingError> {
    let n = statuses.len();
    for (i, &v) in values.iter().enumerate() {
        let k = i % n;
        if v != 0.0 && statuses[k].dof(k, n) != Some(i) {
            let which = if i < n { "phĭ" } else { "phî" };
            return Err(RockingError::new(
                kind,
                format!(
                    "{name}[{i}] ({which}_{k}) = {v} but interface {k} has status {}",
                    statuses[k].as_i8()
                ),
            ));
        }
    }
    Ok(())
}

/// Statuses implied by a DOF angle vector `phi` (length `2n`), checking that at most one DOF of
/// each interface is non-zero and that it has the admissible sign.
pub fn statuses_from_angles(phi: &[f64]) -> Result<Vec<Status>, RockingError> {
    let n = phi.len() / 2;
    (0..n)
        .map(|k| match (phi[k], phi[n + k]) {
            (r, l) if r == 0.0 && l == 0.0 => Ok(Status::Closed),
            (r, l) if l == 0.0 && r < 0.0 => Ok(Status::OpenRight),
            (r, l) if r == 0.0 && l > 0.0 => Ok(Status::OpenLeft),
            (r, l) => Err(RockingError::new(
                ErrorKind::InvalidAngles,
                format!(
                    "interface {k}: phi[{k}] = {r} (phĭ_{k}), phi[{}] = {l} (phî_{k}) (need \
                     phĭ <= 0, phî >= 0, at most one non-zero)",
                    n + k
                ),
            )),
        })
        .collect()
}

/// Checks that a model's outputs are finite (finite but huge inputs can overflow).
pub fn check_result(values: &[f64], energies: &[f64]) -> Result<(), RockingError> {
    if values.iter().chain(energies).all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(RockingError::new(
            ErrorKind::Overflow,
            "a velocity, acceleration or kinetic energy of the result is not finite",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blocked sweep gives the verdict of the plain loop over the upper triangle, for every
    /// size up to 13 and every single asymmetric pair (and none).
    #[test]
    fn symmetric_sweep_finds_every_asymmetric_pair() {
        let plain = |mass: &[f64], m: usize| {
            (0..m).all(|r| (r + 1..m).all(|c| mass[r * m + c] == mass[c * m + r]))
        };
        for m in 0..14 {
            let sym: Vec<f64> = (0..m * m)
                .map(|x| {
                    let (i, j) = (x / m, x % m);
                    (i.min(j) * 31 + i.max(j) * 7) as f64 * 0.25
                })
                .collect();
            assert!(symmetric_to_the_bit(&sym, m) && plain(&sym, m), "m = {m}");
            for r in 0..m {
                for c in 0..m {
                    if r == c {
                        continue;
                    }
                    let mut a = sym.clone();
                    a[r * m + c] += 1.0;
                    assert!(
                        !symmetric_to_the_bit(&a, m) && !plain(&a, m),
                        "m = {m}: ({r}, {c})"
                    );
                }
            }
        }
    }
}
