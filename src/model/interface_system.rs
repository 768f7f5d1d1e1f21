//! The interface system of a column: the mass matrix `M` and load vector `q` on the `2n`
//! interface DOFs that the two models take (SPEC §1, thesis Eq. 4–6), assembled from plain
//! arrays of block data as an FE code holds them (the C ABI's `rocking_column_mass_matrix`), with
//! every input checked and every failure a [`RockingError`] that names the argument.

use crate::error::{ErrorKind, RockingError};
use crate::model::column::{Block, Column, ColumnError};
use crate::model::configuration;

/// Block data as parallel arrays, bottom block first (the layout of the C ABI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlockArrays<'a> {
    /// Widths `w_k` (m).
    pub width: &'a [f64],
    /// Heights `h_k` (m).
    pub height: &'a [f64],
    /// Masses `m_k` (kg).
    pub mass: &'a [f64],
    /// Moments of inertia about the block centres (kg m²); `None` for uniform rectangles.
    pub inertia: Option<&'a [f64]>,
    /// Contact widths of the interface under each block (m); `None` for `min(w_{k-1}, w_k)`.
    pub contact_width: Option<&'a [f64]>,
}

/// The mass matrix and load vector on the `2n` interface DOFs.
#[derive(Clone, Debug, PartialEq)]
pub struct InterfaceSystem {
    /// `2n × 2n`, symmetric (row-major = column-major).
    pub mass: Vec<f64>,
    /// `2n` generalised loads.
    pub load: Vec<f64>,
}

/// `M` and `q` of a column of blocks in the geometry of the DOF angles `phi` (`None`: the
/// straight column), under the horizontal ground acceleration `ground_acceleration` (m/s², +x to
/// the right) and gravity `gravity` (m/s², positive).
///
/// Checks, in this order: array lengths (`InvalidSize`), `phi` finite (`NotFinite`),
/// `ground_acceleration` and `gravity` finite (`NotFinite`), `gravity` positive
/// (`InvalidGeometry`), at most one non-zero DOF per interface with the admissible sign
/// (`InvalidAngles`), the blocks (`InvalidGeometry`; `Overflow` when finite blocks are too large
/// for double precision, e.g. a derived inertia), and a finite result (`Overflow`).
pub fn column_system(
    blocks: &BlockArrays<'_>,
    phi: Option<&[f64]>,
    ground_acceleration: f64,
    gravity: f64,
) -> Result<InterfaceSystem, RockingError> {
    let n = blocks.width.len();
    let lengths = [
        ("height", Some(blocks.height.len()), n),
        ("mass", Some(blocks.mass.len()), n),
        ("inertia", blocks.inertia.map(<[f64]>::len), n),
        ("contact_width", blocks.contact_width.map(<[f64]>::len), n),
        ("phi", phi.map(<[f64]>::len), 2 * n),
    ];
    for (name, len, want) in lengths {
        if let Some(len) = len.filter(|&len| len != want) {
            return Err(RockingError::new(
                ErrorKind::InvalidSize,
                format!("{name} has {len} values, expected {want} for {n} blocks"),
            ));
        }
    }
    let straight = vec![0.0; 2 * n];
    let phi = phi.unwrap_or(&straight);
    configuration::check_finite("phi", phi)?;
    configuration::check_accelerations(ground_acceleration, gravity)?;
    configuration::statuses_from_angles(phi)?;
    let column = Column::new(
        (0..n)
            .map(|k| Block {
                width: blocks.width[k],
                height: blocks.height[k],
                mass: blocks.mass[k],
                inertia: blocks.inertia.map(|i| i[k]),
                contact_width: blocks.contact_width.map(|c| c[k]),
            })
            .collect(),
    )
    .map_err(|e| {
        let kind = match e {
            ColumnError::TooLarge { .. } => ErrorKind::Overflow,
            _ => ErrorKind::InvalidGeometry,
        };
        RockingError::new(kind, e.to_string())
    })?;
    let pose = column.pose(phi);
    let system = InterfaceSystem {
        mass: column.mass_matrix(&pose),
        load: column.load_vector(&pose, ground_acceleration, gravity),
    };
    configuration::check_result(&system.mass, &system.load)?;
    Ok(system)
}

/// Largest `n_nodal` and `n_reduced` of the Appendix C reduction (`rocking_reduce`).
pub const MAX_REDUCTION_SIZE: usize = 1 << 16;

/// Checks the sizes of the Appendix C reduction `BᵀMB`: each in `1..=`[`MAX_REDUCTION_SIZE`].
pub fn check_reduction_sizes(n_nodal: usize, n_reduced: usize) -> Result<(), RockingError> {
    let ok = |n: usize| (1..=MAX_REDUCTION_SIZE).contains(&n);
    if ok(n_nodal) && ok(n_reduced) {
        Ok(())
    } else {
        Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!(
                "n_nodal = {n_nodal}, n_reduced = {n_reduced}: each must be in 1..={MAX_REDUCTION_SIZE}"
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::column::GRAVITY;
    use crate::samples;

    /// Two 0.1 × 0.3 m granite blocks of 15 kg (`samples::two_granite_column`), as arrays.
    fn two_granite() -> BlockArrays<'static> {
        static WIDTH: [f64; 2] = [0.1; 2];
        static HEIGHT: [f64; 2] = [0.3; 2];
        static MASS: [f64; 2] = [15.0; 2];
        BlockArrays {
            width: &WIDTH,
            height: &HEIGHT,
            mass: &MASS,
            inertia: None,
            contact_width: None,
        }
    }

    #[test]
    fn equals_the_column_of_samples() {
        let arrays = two_granite();
        let got = column_system(&arrays, None, 0.0, GRAVITY).unwrap();
        let col = samples::two_granite_column();
        let pose = col.pose(&[0.0; 4]);
        assert_eq!(got.mass, col.mass_matrix(&pose));
        assert_eq!(got.load, col.load_vector(&pose, 0.0, GRAVITY));
    }

    #[test]
    fn names_the_bad_argument() {
        let ok = two_granite();
        let kind = |blocks: &BlockArrays, phi: Option<&[f64]>, ag: f64| {
            let e = column_system(blocks, phi, ag, GRAVITY).unwrap_err();
            (e.kind, e.detail)
        };
        let short = [0.3];
        let (k, d) = kind(
            &BlockArrays {
                height: &short,
                ..ok
            },
            None,
            0.0,
        );
        assert_eq!(k, ErrorKind::InvalidSize);
        assert!(d.starts_with("height has 1 values"), "{d}");
        let (k, d) = kind(&ok, Some(&[0.0, 0.0, f64::NAN, 0.0]), 0.0);
        assert_eq!((k, d.as_str()), (ErrorKind::NotFinite, "phi[2] = NaN"));
        let (k, d) = kind(&ok, None, f64::INFINITY);
        assert_eq!(
            (k, d.as_str()),
            (ErrorKind::NotFinite, "ground_acceleration = inf")
        );
        let (k, _) = kind(&ok, Some(&[0.0, 0.0, -0.1, 0.0]), 0.0);
        assert_eq!(k, ErrorKind::InvalidAngles);
        let bad_mass = [15.0, -1.0];
        let (k, d) = kind(
            &BlockArrays {
                mass: &bad_mass,
                ..ok
            },
            None,
            0.0,
        );
        assert_eq!(k, ErrorKind::InvalidGeometry);
        assert!(d.contains("block 1: mass = -1"), "{d}");
    }

    /// Gravity is documented positive (m/s², downwards) but was only checked finite: -9.81
    /// turned the load of the weight upside down and 0 dropped it, silently.
    #[test]
    fn gravity_must_be_positive() {
        let ok = two_granite();
        for g in [-GRAVITY, 0.0, -0.0] {
            let e = column_system(&ok, None, 0.0, g).unwrap_err();
            assert_eq!(e.kind, ErrorKind::InvalidGeometry, "{g}");
            assert!(
                e.detail.starts_with(&format!(
                    "gravity = {g:?}: must be a finite number greater than zero"
                )),
                "{}",
                e.detail
            );
        }
        let e = column_system(&ok, None, 0.0, f64::NAN).unwrap_err();
        assert_eq!(
            (e.kind, e.detail.as_str()),
            (ErrorKind::NotFinite, "gravity = NaN")
        );
        assert!(column_system(&ok, None, 0.0, 1.62).is_ok());
    }

    #[test]
    fn reduction_sizes() {
        assert!(check_reduction_sizes(6, 4).is_ok());
        assert!(check_reduction_sizes(MAX_REDUCTION_SIZE, 1).is_ok());
        for (a, b) in [(0, 4), (6, 0), (MAX_REDUCTION_SIZE + 1, 4)] {
            assert_eq!(
                check_reduction_sizes(a, b).unwrap_err().kind,
                ErrorKind::InvalidSize
            );
        }
    }
}
