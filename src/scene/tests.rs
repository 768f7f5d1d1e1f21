//! Tests of the scene schema: fields, errors that name them, sizes.

use super::*;

#[test]
fn a_history_is_refused_only_beyond_its_sample_limit() {
    let output = |history, every| OutputSpec {
        history,
        every,
        events: true,
    };
    // 1e9 steps: refused with every step kept, kept at the limit with every 10th, and
    // without a history.
    assert!(output(true, 1).check_samples(1e6, 1e-3).is_err());
    assert!(output(true, 9).check_samples(1e6, 1e-3).is_err());
    assert!(output(true, 10).check_samples(1e6, 1e-3).is_ok());
    assert!(output(false, 1).check_samples(1e6, 1e-3).is_ok());
    assert!(output(true, 1).check_samples(30.0, 1e-3).is_ok());
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    let spec: SceneSpec = serde_json::from_str(text).map_err(|e| SceneError(e.to_string()))?;
    build(spec, Path::new("."), "test")
}

const GOOD: &str = r#"{"blocks": [{"width": 0.2, "height": 1.0, "mass": 10}],
    "excitation": {"type": "half_sine", "amplitude": 5.0, "duration": 0.3},
    "duration": 1.0, "dt": 0.001}"#;

#[test]
fn a_good_scene_builds() {
    let s = parse(GOOD).unwrap();
    assert_eq!(s.column.n_interfaces(), 1);
    assert_eq!(s.options.physics.model.n_impacts, 1);
    assert!((s.excitation.peak() - 5.0).abs() < 1e-12);
    for (name, integrator) in [
        ("wilson", Integrator::default()),
        ("newmark", Integrator::Newmark),
        ("rk4", Integrator::Rk4),
        ("dop853", Integrator::Dop853),
    ] {
        let text = GOOD.replace(
            "\"duration\": 1.0,",
            &format!("\"duration\": 1.0, \"integrator\": \"{name}\", \"locator\": \"hermite\","),
        );
        let s = parse(&text).unwrap();
        assert_eq!(s.options.stepping.integrator, integrator);
        assert_eq!(s.options.stepping.locator, EventLocator::Hermite);
    }
}

#[test]
fn a_blank_title_is_the_name() {
    for blank in ["", "   "] {
        let text = GOOD.replace(
            "\"dt\": 0.001",
            &format!("\"dt\": 0.001, \"title\": {blank:?}"),
        );
        assert_eq!(parse(&text).unwrap().title, "test");
    }
    let text = GOOD.replace("\"dt\": 0.001", "\"dt\": 0.001, \"title\": \"Drums\"");
    assert_eq!(parse(&text).unwrap().title, "Drums");
}

#[test]
fn errors_name_the_field() {
    let cases = [
        (GOOD.replace("\"dt\": 0.001", "\"dt\": -1"), "dt"),
        (
            GOOD.replace("\"dt\": 0.001", "\"dt\": 0.001, \"colour\": 1"),
            "unknown field `colour`",
        ),
        (
            GOOD.replace("\"mass\": 10", "\"mass\": 0"),
            "blocks[0].mass",
        ),
        (
            GOOD.replace(
                "\"width\": 0.2, \"height\": 1.0",
                "\"width\": 1e-8, \"height\": 1e-8",
            ),
            "dt: 0.001: more than a tenth of the column's own time √(H/g) = 3.193e-5 s",
        ),
        (
            GOOD.replace("\"width\": 0.2", "\"width\": 1e200"),
            "blocks[0]: the inertia m (w² + h²) / 12 from mass = 10.0, width = 1e200",
        ),
        (
            GOOD.replace("\"half_sine\"", "\"square\""),
            "unknown variant `square`",
        ),
        (
            GOOD.replace("\"duration\": 0.3", "\"duration\": 0.0"),
            "excitation.duration",
        ),
        (
            GOOD.replace("\"duration\": 1.0,", "\"duration\": 1.0, \"impacts\": 0,"),
            "impacts",
        ),
        (
            GOOD.replace(
                "\"duration\": 1.0,",
                "\"duration\": 1.0, \"integrator\": \"euler\",",
            ),
            "integrator",
        ),
        (
            GOOD.replace(
                "\"duration\": 1.0,",
                "\"duration\": 1.0, \"initial_angles\": [0.1, 0.2],",
            ),
            "initial_angles",
        ),
        (
            GOOD.replace("\"duration\": 1.0,", ""),
            "missing field `duration`",
        ),
        ("{\"blocks\": [".to_string(), "EOF"),
        (
            GOOD.replace("\"dt\": 0.001", "\"dt\": 0.001, \"min_flight\": 1"),
            "min_flight",
        ),
    ];
    for (text, field) in cases {
        let e = parse(&text)
            .err()
            .unwrap_or_else(|| panic!("accepted: {text}"));
        assert!(e.0.contains(field), "{field}: {}", e.0);
    }
}

/// A loop scene's `min_flight` reaches the driver's options (default 0, the driver's
/// default); a negative one is named (JSON has no NaN or infinity).
#[test]
fn a_loop_scene_takes_min_flight() {
    let text = |extra: &str| {
        format!(
            r#"{{"arch": {{"radius": 5, "thickness": 0.75, "voussoirs": 8}},
                "excitation": {{"type": "none"}}, "duration": 1.0, "dt": 0.001{extra}}}"#
        )
    };
    let options = |extra: &str| -> Result<f64, SceneError> {
        let spec: SceneSpec =
            serde_json::from_str(&text(extra)).map_err(|e| SceneError(e.to_string()))?;
        match build_any(spec, Path::new("."), "test")? {
            AnyScene::Loop(s) => Ok(s.options.min_flight),
            AnyScene::Column(_) => panic!("a column"),
        }
    };
    assert_eq!(options("").unwrap(), 0.0);
    assert_eq!(options(", \"min_flight\": 1.5").unwrap(), 1.5);
    for bad in ["-1", "-0.001"] {
        let e = options(&format!(", \"min_flight\": {bad}")).unwrap_err();
        assert!(e.0.contains("min_flight"), "{bad}: {}", e.0);
    }
}

/// Sizes beyond the models' maximum are refused by name before anything is allocated for
/// them (a column of 10⁵ blocks asked the driver for 80 GB and aborted), and an arch's angle
/// of embrace is judged in the degrees the scene gives it in.
#[test]
fn oversized_and_out_of_range_shapes_are_named() {
    let load = |text: &str| -> Result<AnyScene, SceneError> {
        let spec: SceneSpec = serde_json::from_str(text).map_err(|e| SceneError(e.to_string()))?;
        build_any(spec, Path::new("."), "test")
    };
    let max = crate::model::configuration::MAX_INTERFACES;
    let column = |n: usize| {
        let blocks = vec![r#"{"width": 1, "height": 1, "mass": 2500}"#; n].join(",");
        format!(
            r#"{{"blocks": [{blocks}], "excitation": {{"type": "none"}},
                "duration": 0.01, "dt": 0.001}}"#
        )
    };
    assert!(matches!(load(&column(max)), Ok(AnyScene::Column(_))));
    let e = load(&column(max + 1)).err().expect("accepted");
    assert!(
        e.0.starts_with("blocks: ") && e.0.contains(&format!("{}", max + 1)),
        "{}",
        e.0
    );
    let arch = |fields: &str| {
        format!(
            r#"{{"arch": {{"radius": 5, "thickness": 0.75, {fields}}},
                "excitation": {{"type": "none"}}, "duration": 0.01, "dt": 0.001}}"#
        )
    };
    let e = load(&arch(&format!(r#""voussoirs": {max}"#)))
        .err()
        .expect("accepted");
    assert!(
        e.0.contains("arch.voussoirs") && e.0.contains("4095"),
        "{}",
        e.0
    );
    for bad in ["400", "360", "0", "-90"] {
        let text = arch(&format!(r#""voussoirs": 8, "embrace_angle": {bad}"#));
        let e = load(&text)
            .err()
            .unwrap_or_else(|| panic!("accepted {bad}"));
        assert!(
            e.0.contains("arch.embrace_angle")
                && e.0.contains(&format!("{bad}: "))
                && e.0.contains("360 degrees"),
            "{}",
            e.0
        );
    }
    assert!(load(&arch(r#""voussoirs": 8, "embrace_angle": 359"#)).is_ok());
}

/// The enumeration solver on a column taller than its limit is refused naming `solver`, on the
/// event-driven driver and in the driver's parts of scheme "auto" (both failed at the first
/// opening: "model error: enumeration refused"); at the limit it is taken.
#[test]
fn the_enumeration_on_too_many_joints_is_named() {
    let limit = ModelOptions::default().max_enumerated_closed;
    let column = |n: usize, extra: &str| {
        let blocks = vec![r#"{"width": 1, "height": 1, "mass": 2500}"#; n].join(",");
        format!(
            r#"{{"blocks": [{blocks}], "excitation": {{"type": "none"}},
                "duration": 0.01, "dt": 0.001, "solver": "enumerate"{extra}}}"#
        )
    };
    assert!(parse(&column(limit, "")).is_ok());
    for extra in ["", r#", "scheme": "auto", "on_sliding": "slide""#] {
        let e = parse(&column(limit + 1, extra)).err().expect("accepted");
        assert!(
            e.0.starts_with("solver: ") && e.0.contains(&format!("has {}", limit + 1)),
            "{extra}: {}",
            e.0
        );
    }
}
