//! The C ABI called from Rust: every error class returns its code, leaves the caller's arrays
//! untouched, and sets a detailed message.

use super::*;
use crate::samples;
use std::ffi::CStr;

pub(super) fn last_error() -> String {
    unsafe { CStr::from_ptr(rocking_last_error_message()) }
        .to_string_lossy()
        .into_owned()
}

struct ImpactCall {
    n: usize,
    mass: Vec<f64>,
    status: Vec<i8>,
    velocity: Vec<f64>,
    closing: usize,
    options: Option<RockingOptions>,
}

impl ImpactCall {
    fn thesis() -> ImpactCall {
        let case = samples::two_block_impact();
        ImpactCall {
            n: 2,
            mass: case.mass,
            status: case.statuses.iter().map(|s| s.as_i8()).collect(),
            velocity: case.velocity,
            closing: case.closing,
            options: None,
        }
    }

    /// Calls the C entry point; asserts that on failure nothing was written.
    fn call(&mut self) -> (i32, RockingReport) {
        let before = (self.status.clone(), self.velocity.clone());
        let sentinel = RockingReport {
            solver: 77,
            changed: 77,
            tie: 77,
            impacts_applied: 77,
            configurations_examined: 77,
            admissible: 77,
            kinetic_before: 77.0,
            kinetic_after: 77.0,
            runner_up: 77.0,
            condition_estimate: 77.0,
        };
        let mut report = sentinel;
        let opts = self
            .options
            .as_ref()
            .map_or(std::ptr::null(), |o| o as *const RockingOptions);
        let code = unsafe {
            rocking_impact_model(
                self.n,
                self.mass.as_ptr(),
                self.status.as_mut_ptr(),
                self.velocity.as_mut_ptr(),
                self.closing,
                opts,
                &mut report,
            )
        };
        if code != 0 {
            assert_eq!(
                (self.status.clone(), self.velocity.clone()),
                before,
                "arrays touched on error {code}"
            );
            assert_eq!(report, sentinel, "report written on error {code}");
            assert!(!last_error().is_empty());
        }
        (code, report)
    }
}

#[test]
fn thesis_impact_through_the_c_abi() {
    let mut c = ImpactCall::thesis();
    let (code, report) = c.call();
    assert_eq!(code, ROCKING_OK);
    assert_eq!(c.status, vec![-1, -1]);
    let thesis = samples::TWO_BLOCK_IMPACT_ANSWERS[0];
    assert_eq!(thesis.n_impacts, 1);
    assert!((c.velocity[0] - thesis.rates[0]).abs() < 5e-5);
    assert!((c.velocity[1] - thesis.rates[1]).abs() < 5e-5);
    let loss = 100.0 * (1.0 - report.kinetic_after / report.kinetic_before);
    assert!((loss - thesis.loss_percent).abs() < 0.05);
    assert_eq!(report.changed, 1);
    assert_eq!(last_error(), "");
}

#[test]
fn impact_error_classes() {
    type Mutation = Box<dyn Fn(&mut ImpactCall)>;
    // (case, mutation, code, what the message must say: the argument, and the value)
    let cases: Vec<(&str, Mutation, i32, &str)> = vec![
        (
            "n = 0",
            Box::new(|c| c.n = 0),
            ROCKING_ERR_INVALID_SIZE,
            "n_interfaces is 0",
        ),
        (
            "n overflows",
            Box::new(|c| c.n = usize::MAX / 2 + 7),
            ROCKING_ERR_INVALID_SIZE,
            "n_interfaces = ",
        ),
        (
            "NaN mass",
            Box::new(|c| c.mass[5] = f64::NAN),
            ROCKING_ERR_NOT_FINITE,
            "mass[5] = NaN",
        ),
        (
            "inf velocity",
            Box::new(|c| c.velocity[3] = f64::NEG_INFINITY),
            ROCKING_ERR_NOT_FINITE,
            "velocity[3] = -inf",
        ),
        (
            "non-symmetric",
            Box::new(|c| c.mass[1] += 0.01),
            ROCKING_ERR_NOT_SYMMETRIC,
            "mass[0][1]",
        ),
        (
            "status 2",
            Box::new(|c| c.status[0] = 2),
            ROCKING_ERR_INVALID_STATUS,
            "status[0] = 2",
        ),
        (
            "closing out of range",
            Box::new(|c| c.closing = 2),
            ROCKING_ERR_INVALID_CLOSING_INTERFACE,
            "closing_interface = 2",
        ),
        (
            "closing closed",
            Box::new(|c| c.closing = 0),
            ROCKING_ERR_INVALID_CLOSING_INTERFACE,
            "closing_interface = 0",
        ),
        (
            "velocity on closed DOF",
            Box::new(|c| c.velocity[0] = 0.1),
            ROCKING_ERR_VELOCITY_ON_CLOSED_DOF,
            "velocity[0]",
        ),
        (
            "velocity on inactive DOF",
            Box::new(|c| c.velocity[1] = 0.1),
            ROCKING_ERR_VELOCITY_ON_CLOSED_DOF,
            "velocity[1]",
        ),
        (
            "moving away",
            Box::new(|c| c.velocity[3] = 1.0),
            ROCKING_ERR_INCONSISTENT_STATE,
            "velocity[3] = 1",
        ),
        (
            "n_impacts 0",
            Box::new(|c| {
                c.options = Some(RockingOptions {
                    n_impacts: 0,
                    solver: 0,
                    tolerance: 1e-12,
                })
            }),
            ROCKING_ERR_INVALID_OPTIONS,
            "n_impacts = 0",
        ),
        (
            "solver 7",
            Box::new(|c| {
                c.options = Some(RockingOptions {
                    n_impacts: 1,
                    solver: 7,
                    tolerance: 1e-12,
                })
            }),
            ROCKING_ERR_INVALID_OPTIONS,
            "solver = 7",
        ),
        (
            "tolerance NaN",
            Box::new(|c| {
                c.options = Some(RockingOptions {
                    n_impacts: 1,
                    solver: 0,
                    tolerance: f64::NAN,
                })
            }),
            ROCKING_ERR_INVALID_OPTIONS,
            "tolerance = NaN",
        ),
        (
            "indefinite",
            Box::new(|c| {
                for i in 0..4 {
                    c.mass[i * 4 + i] = -1.0;
                }
            }),
            ROCKING_ERR_NOT_POSITIVE_DEFINITE,
            "mass matrix",
        ),
    ];
    for (name, mutate, expected, says) in cases {
        let mut c = ImpactCall::thesis();
        mutate(&mut c);
        if c.n > 2 {
            // Sizes that overflow are refused before any pointer is read.
            let code = unsafe {
                rocking_impact_model(
                    c.n,
                    c.mass.as_ptr(),
                    c.status.as_mut_ptr(),
                    c.velocity.as_mut_ptr(),
                    0,
                    std::ptr::null(),
                    std::ptr::null_mut(),
                )
            };
            assert_eq!(code, expected, "{name}");
            assert!(last_error().contains(says), "{name}: {}", last_error());
            continue;
        }
        let (code, _) = c.call();
        assert_eq!(code, expected, "{name}: {}", last_error());
        assert!(last_error().contains(says), "{name}: {}", last_error());
    }
}

#[test]
fn enumeration_limit_is_a_positive_code() {
    let col = crate::model::column::Column::uniform(14, 1.0, 14.0, 14.0).unwrap();
    let mut phi = vec![0.0; 28];
    phi[13] = -0.01;
    let mass = col.mass_matrix(&col.pose(&phi));
    let mut status = vec![0i8; 14];
    status[13] = -1;
    let mut v = vec![0.0; 28];
    v[13] = 0.5;
    let opts = RockingOptions {
        n_impacts: 1,
        solver: 1,
        tolerance: 1e-12,
    };
    let code = unsafe {
        rocking_impact_model(
            14,
            mass.as_ptr(),
            status.as_mut_ptr(),
            v.as_mut_ptr(),
            13,
            &opts,
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, ROCKING_ERR_ENUMERATION_TOO_LARGE);
    assert!(last_error().contains("13 closed"));
    // The projection solves it.
    let opts = RockingOptions { solver: 2, ..opts };
    let code = unsafe {
        rocking_impact_model(
            14,
            mass.as_ptr(),
            status.as_mut_ptr(),
            v.as_mut_ptr(),
            13,
            &opts,
            std::ptr::null_mut(),
        )
    };
    assert_eq!(code, ROCKING_OK, "{}", last_error());
}

#[test]
fn null_pointers() {
    let c = ImpactCall::thesis();
    let mut status = c.status.clone();
    let mut v = c.velocity.clone();
    unsafe {
        assert_eq!(
            rocking_impact_model(
                2,
                std::ptr::null(),
                status.as_mut_ptr(),
                v.as_mut_ptr(),
                1,
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        assert!(last_error().contains("mass"));
        assert_eq!(
            rocking_impact_model(
                2,
                c.mass.as_ptr(),
                std::ptr::null_mut(),
                v.as_mut_ptr(),
                1,
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        assert_eq!(
            rocking_impact_model(
                2,
                c.mass.as_ptr(),
                status.as_mut_ptr(),
                std::ptr::null_mut(),
                1,
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        let mut a = [0.0; 4];
        let load = [0.0; 4];
        assert_eq!(
            rocking_opening_model(
                2,
                c.mass.as_ptr(),
                std::ptr::null(),
                status.as_mut_ptr(),
                a.as_mut_ptr(),
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        assert_eq!(
            rocking_opening_model(
                2,
                c.mass.as_ptr(),
                load.as_ptr(),
                status.as_mut_ptr(),
                std::ptr::null_mut(),
                std::ptr::null(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        assert_eq!(
            rocking_reduce(
                3,
                1,
                std::ptr::null(),
                std::ptr::null(),
                std::ptr::null(),
                a.as_mut_ptr(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
        let mut holds = 0u8;
        assert_eq!(
            rocking_check_configuration(
                2,
                c.mass.as_ptr(),
                load.as_ptr(),
                std::ptr::null(),
                0.0,
                &mut holds,
                std::ptr::null_mut(),
                std::ptr::null_mut()
            ),
            ROCKING_ERR_NULL_POINTER
        );
    }
    assert_eq!((status, v), (c.status, c.velocity));
}

#[test]
fn opening_through_the_c_abi() {
    let case = samples::two_block_top_push();
    let mut status = [0i8; 2];
    let mut a = [9.0; 4];
    let mut report = std::mem::MaybeUninit::<RockingReport>::uninit();
    let code = unsafe {
        rocking_opening_model(
            2,
            case.mass.as_ptr(),
            case.load.as_ptr(),
            status.as_mut_ptr(),
            a.as_mut_ptr(),
            std::ptr::null(),
            report.as_mut_ptr(),
        )
    };
    assert_eq!(code, ROCKING_OK);
    let report = unsafe { report.assume_init() };
    assert_eq!(status, [1, -1]);
    assert_eq!(report.changed, 1);
    // Accelerations only on the chosen DOFs, with the admissible signs.
    assert!(a[2] > 0.0 && a[1] < 0.0 && a[0] == 0.0 && a[3] == 0.0);
    // The reaction test agrees: the closed column does not hold.
    let mut holds = 7u8;
    let mut flags = [9u8; 2];
    let mut reactions = [0.0; 4];
    let code = unsafe {
        rocking_check_configuration(
            2,
            case.mass.as_ptr(),
            case.load.as_ptr(),
            [0i8, 0].as_ptr(),
            0.0,
            &mut holds,
            reactions.as_mut_ptr(),
            flags.as_mut_ptr(),
        )
    };
    assert_eq!(code, 0);
    assert_eq!(holds, 0);
    assert!(flags.contains(&1));
}

#[test]
fn codes_and_messages() {
    let pairs = [
        (ROCKING_ERR_NULL_POINTER, ErrorKind::NullPointer),
        (ROCKING_ERR_INVALID_SIZE, ErrorKind::InvalidSize),
        (ROCKING_ERR_NOT_FINITE, ErrorKind::NotFinite),
        (ROCKING_ERR_NOT_SYMMETRIC, ErrorKind::NotSymmetric),
        (ROCKING_ERR_INVALID_STATUS, ErrorKind::InvalidStatus),
        (
            ROCKING_ERR_INVALID_CLOSING_INTERFACE,
            ErrorKind::InvalidClosingInterface,
        ),
        (
            ROCKING_ERR_VELOCITY_ON_CLOSED_DOF,
            ErrorKind::VelocityOnClosedDof,
        ),
        (ROCKING_ERR_INVALID_OPTIONS, ErrorKind::InvalidOptions),
        (ROCKING_ERR_INCONSISTENT_STATE, ErrorKind::InconsistentState),
        (ROCKING_ERR_INVALID_GEOMETRY, ErrorKind::InvalidGeometry),
        (ROCKING_ERR_INVALID_ANGLES, ErrorKind::InvalidAngles),
        (
            ROCKING_ERR_NOT_POSITIVE_DEFINITE,
            ErrorKind::NotPositiveDefinite,
        ),
        (
            ROCKING_ERR_ENUMERATION_TOO_LARGE,
            ErrorKind::EnumerationTooLarge,
        ),
        (
            ROCKING_ERR_SOLVER_DID_NOT_CONVERGE,
            ErrorKind::SolverDidNotConverge,
        ),
        (ROCKING_ERR_OVERFLOW, ErrorKind::Overflow),
        (ROCKING_ERR_INTERNAL, ErrorKind::Internal),
    ];
    assert_eq!(pairs.len(), ErrorKind::ALL.len());
    for (code, kind) in pairs {
        assert_eq!(code, kind.code());
        let text = unsafe { CStr::from_ptr(rocking_error_message(code)) }
            .to_str()
            .unwrap();
        assert_eq!(text, kind.message());
    }
    let unknown = unsafe { CStr::from_ptr(rocking_error_message(12345)) }
        .to_str()
        .unwrap();
    assert_eq!(unknown, "unknown status code");
    assert_eq!(
        ROCKING_MAX_INTERFACES,
        crate::model::configuration::MAX_INTERFACES
    );
    assert_eq!(rocking_abi_version(), ROCKING_ABI_VERSION);
    let v = unsafe { CStr::from_ptr(rocking_version()) }
        .to_str()
        .unwrap();
    assert_eq!(v, env!("CARGO_PKG_VERSION"));
}

#[test]
fn concurrent_calls_agree_with_serial_ones() {
    let serial = {
        let mut c = ImpactCall::thesis();
        c.call();
        c.velocity
    };
    let handles: Vec<_> = (0..8)
        .map(|_| {
            std::thread::spawn(|| {
                let mut out = Vec::new();
                for _ in 0..200 {
                    let mut c = ImpactCall::thesis();
                    assert_eq!(c.call().0, 0);
                    out = c.velocity;
                }
                out
            })
        })
        .collect();
    for h in handles {
        assert_eq!(h.join().unwrap(), serial);
    }
}
