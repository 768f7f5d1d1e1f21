use super::*;

/// The columns the stop is the default for (with `--lagrangian`): certified, with the smallest
/// `V / E_tip` at a first tipping at least `1 − ε`.
#[test]
fn the_barrier_is_certified_for_the_columns_the_stop_is_the_default_for() {
    for (n, lo, hi) in CERTIFIED_COLUMNS {
        let cert = certify_column_barrier(n, (lo, hi), CERTIFIED_EPSILON, 50_000_000)
            .unwrap_or_else(|f| panic!("{n} blocks, H/B {lo}–{hi}: {f:?}"));
        println!(
            "{n} blocks, H/B {lo}–{hi}: V/E_tip ≥ {:.6} at every first tipping, V ≥ 0 before \
             ({} boxes, {} on the boundary)",
            cert.min_ratio, cert.boxes, cert.boundary_boxes
        );
        assert!(cert.min_ratio >= 1.0 - CERTIFIED_EPSILON);
    }
    assert!(column_stop_is_certified(3, 12.0) && column_stop_is_certified(2, 3.0));
    assert!(!column_stop_is_certified(3, 13.0) && !column_stop_is_certified(4, 12.0));
}

/// The certificate can fail: the rigid mechanisms tip at exactly `E_tip`, so `V ≥ 1.001 E_tip`
/// is false and must not be certified; it fails near the lowest mechanism.
#[test]
fn a_false_barrier_is_not_certified() {
    for n in [2, 3] {
        let f = certify(n, (3.0, 12.0), 1.001, 10_000_000, 1e-5).unwrap_err();
        println!("{f:?}");
        assert_eq!(f.reason, "a box too small to bound");
        assert!((0.99..1.01).contains(&f.ratio_at_centre), "{f:?}");
    }
}
