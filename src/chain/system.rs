//! The system of a loop that the constrained models take (SPEC §9): the mass matrix `M` and load
//! `q` of the cut chain, the closure matrix `G` and `Ġ v`, at given joint angles and rates — from
//! plain inputs as an FE code or a test holds them (the C ABI's `rocking_arch_system` and
//! `rocking_colonnade_system`), every input checked and every failure a [`RockingError`] that
//! names the argument.

use crate::chain::arch::VoussoirArch;
use crate::chain::colonnade::CappedColonnade;
use crate::chain::Chain;
use crate::error::{ErrorKind, RockingError};
use crate::model::column::Block;
use crate::model::configuration;

/// `M`, `q`, `G` and `Ġ v` of a chain of `J` joints (`2J` DOFs).
#[derive(Clone, Debug, PartialEq)]
pub struct LoopSystem {
    /// `2J × 2J`, symmetric; the rows and columns of the cut (last) joint of a loop are zero.
    pub mass: Vec<f64>,
    /// `2J` generalised loads of gravity and the ground acceleration (without the velocity terms).
    pub load: Vec<f64>,
    /// `G`, row-major `3 × 2J` (empty for an open chain).
    pub constraints: Vec<f64>,
    /// `Ġ v` (3; empty for an open chain): the accelerations obey `G a = −Ġ v`.
    pub constraint_rate: Vec<f64>,
}

fn geometry(e: crate::validate::InvalidValue) -> RockingError {
    // Finite dimensions too large for double precision: the overflow code, as for a column.
    let kind = if e.rule == super::TOO_LARGE {
        ErrorKind::Overflow
    } else {
        ErrorKind::InvalidGeometry
    };
    RockingError::new(kind, e.to_string())
}

/// The system of `chain` at the DOF angles `phi` (`None`: the reference geometry) and rates
/// `rates` (`None`: at rest), under the horizontal ground acceleration `ground_acceleration`
/// (m/s², +x) and gravity `gravity` (m/s², positive).
///
/// Checks, in this order: lengths (`InvalidSize`), `phi`, `rates`, `ground_acceleration` and
/// `gravity` finite (`NotFinite`), `gravity` positive (`InvalidGeometry`), at most one non-zero
/// angle per joint with the admissible sign (`InvalidAngles`), rates on the open DOF of an open
/// joint only, and on a closed joint at most one DOF moving the admissible way (a joint opening
/// at this instant) (`VelocityOnClosedDof`), and a finite result (`Overflow`).
pub fn loop_system(
    chain: &Chain,
    phi: Option<&[f64]>,
    rates: Option<&[f64]>,
    ground_acceleration: f64,
    gravity: f64,
) -> Result<LoopSystem, RockingError> {
    let m = chain.n_dofs();
    for (name, len) in [
        ("phi", phi.map(<[f64]>::len)),
        ("rates", rates.map(<[f64]>::len)),
    ] {
        if let Some(len) = len.filter(|&len| len != m) {
            return Err(RockingError::new(
                ErrorKind::InvalidSize,
                format!("{name} has {len} values, expected 2n = {m}"),
            ));
        }
    }
    let zeros = vec![0.0; m];
    let (phi, rates) = (phi.unwrap_or(&zeros), rates.unwrap_or(&zeros));
    configuration::check_finite("phi", phi)?;
    configuration::check_finite("rates", rates)?;
    configuration::check_accelerations(ground_acceleration, gravity)?;
    let statuses = configuration::statuses_from_angles(phi)?;
    let n = statuses.len();
    for k in 0..n {
        let (r, l) = (rates[k], rates[n + k]);
        let ok = match statuses[k].dof(k, n) {
            Some(d) => rates[if d == k { n + k } else { k }] == 0.0,
            // A closed joint: at most one DOF moving, the admissible way (it opens now).
            None => (r == 0.0 || l == 0.0) && r <= 0.0 && l >= 0.0,
        };
        if !ok {
            return Err(RockingError::new(
                ErrorKind::VelocityOnClosedDof,
                format!(
                    "joint {k} (status {}): rates[{k}] = {r} (phĭ_{k}), rates[{}] = {l} (phî_{k}) \
                     (only the open DOF may move; a closed joint only on one DOF, the \
                     admissible way)",
                    statuses[k].as_i8(),
                    n + k
                ),
            ));
        }
    }
    let pose = chain.pose(phi);
    let system = LoopSystem {
        mass: chain.mass_matrix(&pose),
        load: chain.load_vector(&pose, ground_acceleration, gravity),
        constraints: chain.closure_matrix(&pose),
        constraint_rate: chain.closure_rate(&pose, rates),
    };
    configuration::check_result(&system.mass, &system.load)?;
    configuration::check_result(&system.constraints, &system.constraint_rate)?;
    Ok(system)
}

/// The loop of a voussoir arch, checking that the caller's joint count `n_interfaces` is its
/// `voussoirs + 1` (`InvalidSize`) and its fields (`InvalidGeometry`, naming the field;
/// `Overflow` when finite dimensions give voussoirs too large for double precision).
pub fn arch_chain(arch: &VoussoirArch, n_interfaces: usize) -> Result<Chain, RockingError> {
    configuration::check_size(n_interfaces)?;
    if arch.voussoirs.checked_add(1) != Some(n_interfaces) {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!(
                "n_interfaces = {n_interfaces}, but an arch of {} voussoirs has {} joints",
                arch.voussoirs,
                arch.voussoirs.saturating_add(1)
            ),
        ));
    }
    arch.chain().map_err(geometry)
}

/// The loop of a capped colonnade from rows `(width, height, mass)` of each column (bottom to
/// top, uniform rectangles, full contact), the beam `(length, depth, mass)` and the span; the
/// caller's joint count `n_interfaces` must be `n_left + n_right + 2` (`InvalidSize`).
pub fn colonnade_chain(
    left: &[[f64; 3]],
    right: &[[f64; 3]],
    beam: [f64; 3],
    span: f64,
    n_interfaces: usize,
) -> Result<Chain, RockingError> {
    configuration::check_size(n_interfaces)?;
    let joints = left.len() + right.len() + 2;
    if joints != n_interfaces {
        return Err(RockingError::new(
            ErrorKind::InvalidSize,
            format!(
                "n_interfaces = {n_interfaces}, but a colonnade of {} + {} blocks has {joints} \
                 joints",
                left.len(),
                right.len()
            ),
        ));
    }
    let blocks = |rows: &[[f64; 3]]| -> Vec<Block> {
        rows.iter()
            .map(|&[w, h, m]| Block::rectangle(w, h, m))
            .collect()
    };
    CappedColonnade {
        left: blocks(left),
        right: blocks(right),
        beam: Block::rectangle(beam[0], beam[1], beam[2]),
        span,
    }
    .chain()
    .map_err(geometry)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::column::GRAVITY;

    #[test]
    fn arch_system_is_the_chain_s() {
        let arch = VoussoirArch::semicircular(5.0, 0.75, 8);
        let chain = arch_chain(&arch, 9).unwrap();
        let s = loop_system(&chain, None, None, -2.0, GRAVITY).unwrap();
        let pose = chain.pose(&[0.0; 18]);
        assert_eq!(s.mass, chain.mass_matrix(&pose));
        assert_eq!(s.load, chain.load_vector(&pose, -2.0, GRAVITY));
        assert_eq!(s.constraints, chain.closure_matrix(&pose));
        assert_eq!(s.constraint_rate, vec![0.0; 3]);
    }

    #[test]
    fn errors_name_the_argument() {
        let arch = VoussoirArch::semicircular(5.0, 0.75, 8);
        let e = arch_chain(&arch, 8).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidSize);
        assert!(
            e.detail.contains("8 voussoirs has 9 joints"),
            "{}",
            e.detail
        );
        let bad = VoussoirArch {
            thickness: 11.0,
            ..arch
        };
        let e = arch_chain(&bad, 9).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidGeometry);
        assert!(e.detail.contains("arch.thickness"), "{}", e.detail);
        let chain = arch_chain(&arch, 9).unwrap();
        let mut phi = vec![0.0; 18];
        phi[3] = 0.1;
        let e = loop_system(&chain, Some(&phi), None, 0.0, GRAVITY).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidAngles);
        phi[3] = -0.1;
        let mut rates = vec![0.0; 18];
        rates[9 + 3] = 1.0;
        let e = loop_system(&chain, Some(&phi), Some(&rates), 0.0, GRAVITY).unwrap_err();
        assert_eq!(e.kind, ErrorKind::VelocityOnClosedDof);
        let e = loop_system(&chain, Some(&phi[..4]), None, 0.0, GRAVITY).unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidSize);
        let e = loop_system(&chain, None, None, f64::NAN, GRAVITY).unwrap_err();
        assert_eq!(
            (e.kind, e.detail.as_str()),
            (ErrorKind::NotFinite, "ground_acceleration = NaN")
        );
        let e = colonnade_chain(
            &[[0.5, 3.0, 1.0]],
            &[[0.5, 3.0, 1.0]],
            [4.0, 0.5, 1.0],
            3.0,
            5,
        )
        .unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidSize);
        let e = colonnade_chain(
            &[[0.5, 3.0, 1.0]],
            &[[0.5, 2.0, 1.0]],
            [4.0, 0.5, 1.0],
            3.0,
            4,
        )
        .unwrap_err();
        assert_eq!(e.kind, ErrorKind::InvalidGeometry);
        assert!(e.detail.contains("colonnade.right"), "{}", e.detail);
        // Finite dimensions whose voussoirs or blocks overflow: the overflow code, naming the
        // shape and its inputs (not a derived `bodies[0].mass = NaN` the caller never gave).
        let huge = VoussoirArch {
            radius: 1e200,
            thickness: 1.5e199,
            ..arch
        };
        let e = arch_chain(&huge, 9).unwrap_err();
        assert_eq!(e.kind, ErrorKind::Overflow, "{}", e.detail);
        assert!(
            e.detail
                .starts_with("arch = {radius: 1e200, thickness: 1.5e199"),
            "{}",
            e.detail
        );
        let e = colonnade_chain(
            &[[1e200, 3.0, 1.0]],
            &[[1e200, 3.0, 1.0]],
            [4.0, 0.5, 1.0],
            3.0,
            4,
        )
        .unwrap_err();
        assert_eq!(e.kind, ErrorKind::Overflow, "{}", e.detail);
        assert!(
            e.detail
                .starts_with("colonnade.left[0] = {width: 1e200, height: 3.0, mass: 1.0}"),
            "{}",
            e.detail
        );
    }

    #[test]
    fn colonnade_system_is_the_frame_s() {
        let chain = colonnade_chain(
            &[[0.6, 3.6, 1500.0]],
            &[[0.6, 3.6, 1500.0]],
            [3.6, 0.5, 2400.0],
            3.0,
            4,
        )
        .unwrap();
        let frame = CappedColonnade::frame(0.6, 3.6, 1500.0, 3.0, 0.5, 2400.0)
            .chain()
            .unwrap();
        assert_eq!(chain, frame);
        let mut phi = vec![0.0; 8];
        let mut rates = vec![0.0; 8];
        for (d, s) in [(0, -1.0), (5, 1.0), (2, -1.0), (7, 1.0)] {
            phi[d] = 0.05 * s;
            rates[d] = 0.3 * s;
        }
        let s = loop_system(&chain, Some(&phi), Some(&rates), 1.0, GRAVITY).unwrap();
        let pose = chain.pose(&phi);
        assert_eq!(s.constraint_rate, chain.closure_rate(&pose, &rates));
        assert!(s.constraint_rate.iter().any(|&x| x != 0.0));
    }
}
