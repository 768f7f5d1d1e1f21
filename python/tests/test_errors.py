"""Every error class: RockingError (a ValueError) with the C ABI's code and a detail that names the
argument; the caller's arrays untouched, whatever the error."""
import math

import numpy as np
import pytest

import rocking

CODES = rocking.ERROR_CODES


@pytest.fixture
def two_blocks(samples):
    case = samples["two_block_impact"]
    M, q = rocking.column_mass_matrix(case["width"], case["height"], case["block_mass"])
    return M, q


def impact_args(M, **change):
    args = dict(mass=M.copy(), status=np.array([0, 1], dtype=np.int8), velocity=np.array([0, 0, 0, -1.0]),
                closing_interface=1)
    args.update(change)
    return args


def mutated(M, index, value):
    out = M.copy()
    out.flat[index] = value
    return out


def indefinite(M):
    out = M.copy()
    np.fill_diagonal(out, -np.abs(np.diag(out)))
    return out


IMPACT_CASES = [
    # (name, change, C name, text the detail must contain)
    ("no interface", lambda M: dict(status=np.array([], dtype=np.int8), mass=np.zeros((0, 0)), velocity=np.zeros(0)),
     "ROCKING_ERR_INVALID_SIZE", "n_interfaces is 0"),
    ("mass of the wrong shape", lambda M: dict(mass=M[:3, :3].copy()), "ROCKING_ERR_INVALID_SIZE", "mass has shape (3, 3)"),
    ("velocity of the wrong length", lambda M: dict(velocity=np.zeros(3)), "ROCKING_ERR_INVALID_SIZE", "velocity has shape (3,)"),
    ("velocity 2-D", lambda M: dict(velocity=np.zeros((2, 2))), "ROCKING_ERR_INVALID_SIZE", "velocity has shape (2, 2)"),
    ("status 2-D", lambda M: dict(status=np.zeros((1, 2))), "ROCKING_ERR_INVALID_SIZE", "status has shape (1, 2)"),
    ("NaN in mass", lambda M: dict(mass=mutated(M, 5, math.nan)), "ROCKING_ERR_NOT_FINITE", "mass[5] = NaN"),
    ("inf in velocity", lambda M: dict(velocity=np.array([0, 0, 0, -math.inf])), "ROCKING_ERR_NOT_FINITE", "velocity[3] = -inf"),
    ("non-symmetric mass", lambda M: dict(mass=mutated(M, 1, 9.0)), "ROCKING_ERR_NOT_SYMMETRIC", "mass[0][1] = 9"),
    ("status 3", lambda M: dict(status=[0, 3]), "ROCKING_ERR_INVALID_STATUS", "status[1] = 3"),
    ("status 3 (int8)", lambda M: dict(status=np.array([0, 3], dtype=np.int8)), "ROCKING_ERR_INVALID_STATUS", "status[1] = 3"),
    ("status -1 of 2-D int8", lambda M: dict(status=np.array([[0, 1]], dtype=np.int8)), "ROCKING_ERR_INVALID_SIZE", "status has shape (1, 2)"),
    ("status 0.5", lambda M: dict(status=[0.5, 1]), "ROCKING_ERR_INVALID_STATUS", "status[0] = 0.5"),
    ("closing interface out of range", lambda M: dict(closing_interface=5), "ROCKING_ERR_INVALID_CLOSING_INTERFACE", "closing_interface = 5"),
    ("closing interface negative", lambda M: dict(closing_interface=-1), "ROCKING_ERR_INVALID_CLOSING_INTERFACE", "closing_interface = -1"),
    ("closing interface beyond 64 bits", lambda M: dict(closing_interface=2**70), "ROCKING_ERR_INVALID_CLOSING_INTERFACE",
     f"closing_interface = {2**70}"),
    ("closing interface numpy", lambda M: dict(closing_interface=np.int64(7)), "ROCKING_ERR_INVALID_CLOSING_INTERFACE",
     "closing_interface = 7"),
    ("closing interface closed", lambda M: dict(closing_interface=0), "ROCKING_ERR_INVALID_CLOSING_INTERFACE", "interface 0 is closed"),
    ("velocity on a closed DOF", lambda M: dict(velocity=np.array([0.2, 0, 0, -1.0])), "ROCKING_ERR_VELOCITY_ON_CLOSED_DOF", "velocity[0]"),
    ("n_impacts = 0", lambda M: dict(n_impacts=0), "ROCKING_ERR_INVALID_OPTIONS", "n_impacts = 0"),
    ("n_impacts = -1", lambda M: dict(n_impacts=-1), "ROCKING_ERR_INVALID_OPTIONS", "n_impacts = -1"),
    ("n_impacts = 10001", lambda M: dict(n_impacts=10001), "ROCKING_ERR_INVALID_OPTIONS", "n_impacts = 10001"),
    ("unknown solver", lambda M: dict(solver="fast"), "ROCKING_ERR_INVALID_OPTIONS", 'solver = "fast"'),
    ("tolerance 0.5", lambda M: dict(tolerance=0.5), "ROCKING_ERR_INVALID_OPTIONS", "tolerance = 0.5"),
    ("closing interface moving away", lambda M: dict(velocity=np.array([0, 0, 0, 1.0])), "ROCKING_ERR_INCONSISTENT_STATE", "moving away"),
    ("indefinite mass", lambda M: dict(mass=indefinite(M)), "ROCKING_ERR_NOT_POSITIVE_DEFINITE", "Cholesky"),
    ("huge velocities overflow", lambda M: dict(velocity=np.array([0, 0, 0, -1e300])), "ROCKING_ERR_OVERFLOW", "not finite"),
]


@pytest.mark.parametrize("name,change,c_name,detail", IMPACT_CASES, ids=[c[0] for c in IMPACT_CASES])
def test_impact_model_errors(two_blocks, name, change, c_name, detail):
    M, _ = two_blocks
    args = impact_args(M, **change(M))
    before = {k: (np.array(v, copy=True) if not isinstance(v, (int, str, float)) else v) for k, v in args.items()}
    with pytest.raises(rocking.RockingError) as info:
        rocking.impact_model(**args)
    e = info.value
    assert isinstance(e, ValueError)
    assert e.code == CODES[c_name] and e.name == c_name, (e.code, e.name, str(e))
    assert detail in e.detail, e.detail
    assert str(e) == f"{e.message}: {e.detail}"
    for k, v in args.items():  # the caller's arrays are untouched
        if isinstance(v, np.ndarray):
            np.testing.assert_array_equal(v, before[k])


def test_enumeration_too_large():
    """13 closed interfaces: the enumeration refuses (code 2), the projection solves it."""
    n = 14
    M, _ = rocking.column_mass_matrix([0.5] * n, [1.0] * n, [100.0] * n)
    status = [0] * (n - 1) + [1]
    v = np.zeros(2 * n)
    v[2 * n - 1] = -1.0
    with pytest.raises(rocking.RockingError) as info:
        rocking.impact_model(M, status, v, n - 1, solver="enumerate")
    assert info.value.code == CODES["ROCKING_ERR_ENUMERATION_TOO_LARGE"] == 2
    assert "13 closed" in info.value.detail
    st, v2, report = rocking.impact_model(M, status, v, n - 1, solver="projection")
    assert report.solver == "projection"


@pytest.mark.parametrize("change,c_name,detail", [
    (dict(load=[0.0, 0.0, math.nan, 0.0]), "ROCKING_ERR_NOT_FINITE", "load[2] = NaN"),
    (dict(load=[0.0] * 5), "ROCKING_ERR_INVALID_SIZE", "load has shape (5,)"),
    (dict(status=[0, -2]), "ROCKING_ERR_INVALID_STATUS", "status[1] = -2"),
    (dict(solver="exhaustive"), "ROCKING_ERR_INVALID_OPTIONS", "solver"),
    (dict(mass="indefinite"), "ROCKING_ERR_NOT_POSITIVE_DEFINITE", "Cholesky"),
    (dict(mass="asymmetric"), "ROCKING_ERR_NOT_SYMMETRIC", "mass[1][3]"),
])
def test_opening_model_errors(two_blocks, change, c_name, detail):
    M, q = two_blocks
    args = dict(mass=M.copy(), load=q.copy(), status=np.zeros(2, dtype=np.int8))
    args.update(change)
    if isinstance(args["mass"], str):  # a marker: the matrix is made from M here
        args["mass"] = indefinite(M) if args["mass"] == "indefinite" else mutated(M, 7, 2.0)
    before = {k: np.array(v, copy=True) for k, v in args.items() if k != "solver"}
    with pytest.raises(rocking.RockingError) as info:
        rocking.opening_model(**args)
    assert info.value.name == c_name and detail in info.value.detail, str(info.value)
    for k, v in before.items():
        np.testing.assert_array_equal(args[k], v)
    if "solver" not in change:
        with pytest.raises(rocking.RockingError) as info:
            rocking.check_configuration(**args)
        assert info.value.name == c_name


@pytest.mark.parametrize("change,c_name,detail", [
    (dict(width=[]), "ROCKING_ERR_INVALID_SIZE", "n_interfaces is 0"),
    (dict(height=[0.3]), "ROCKING_ERR_INVALID_SIZE", "height has 1 values, expected 2"),
    (dict(mass=[15.0, -1.0]), "ROCKING_ERR_INVALID_GEOMETRY", "block 1: mass = -1"),
    (dict(contact_width=[0.1, 0.5]), "ROCKING_ERR_INVALID_GEOMETRY", "contact_width"),
    (dict(phi=[0.0, 0.0, -0.1, 0.0]), "ROCKING_ERR_INVALID_ANGLES", "interface 0"),
    (dict(phi=[0.0, 0.0, math.nan, 0.0]), "ROCKING_ERR_NOT_FINITE", "phi[2] = NaN"),
    (dict(phi=[0.0, 0.0, 0.0]), "ROCKING_ERR_INVALID_SIZE", "phi has 3 values, expected 4"),
    (dict(ground_acceleration=math.inf), "ROCKING_ERR_NOT_FINITE", "ground_acceleration = inf"),
    (dict(width=[[0.1, 0.1]]), "ROCKING_ERR_INVALID_SIZE", "width has shape (1, 2), expected 1-D"),
    # documented positive; -9.81 turned the weight's load upside down, silently
    (dict(gravity=-9.81), "ROCKING_ERR_INVALID_GEOMETRY", "gravity = -9.81: must be a finite number greater than zero"),
    (dict(gravity=0.0), "ROCKING_ERR_INVALID_GEOMETRY", "gravity = 0.0: must be a finite number greater than zero"),
    # finite blocks whose derived inertia overflows: named with their inputs, not "inertia = inf"
    (dict(width=[1e200, 1e200]), "ROCKING_ERR_OVERFLOW", "block 0: the inertia m (w² + h²) / 12 from mass = 15.0, width = 1e200"),
])
def test_column_mass_matrix_errors(change, c_name, detail):
    args = dict(width=[0.1, 0.1], height=[0.3, 0.3], mass=[15.0, 15.0])
    args.update(change)
    with pytest.raises(rocking.RockingError) as info:
        rocking.column_mass_matrix(**args)
    assert info.value.name == c_name and detail in info.value.detail, str(info.value)


def test_reduce_errors():
    B = np.ones((6, 2))
    M = np.eye(6)
    cases = [
        (dict(transformation=np.ones(6)), "ROCKING_ERR_INVALID_SIZE", "transformation has shape (6,), expected 2-D"),
        (dict(transformation=np.ones((0, 2))), "ROCKING_ERR_INVALID_SIZE", "n_nodal = 0"),
        (dict(nodal_mass=np.eye(5)), "ROCKING_ERR_INVALID_SIZE", "nodal_mass has shape (5, 5), expected (6, 6)"),
        (dict(nodal_mass=mutated(M, 1, 0.5)), "ROCKING_ERR_NOT_SYMMETRIC", "mass[0][1] = 0.5"),
        (dict(transformation=mutated(B, 3, math.nan)), "ROCKING_ERR_NOT_FINITE", "transformation[3] = NaN"),
        (dict(nodal_load=[0.0] * 5 + [math.inf]), "ROCKING_ERR_NOT_FINITE", "nodal_load[5] = inf"),
        (dict(nodal_load=[0.0] * 4), "ROCKING_ERR_INVALID_SIZE", "nodal_load has shape (4,), expected (6,)"),
        (dict(nodal_mass=M * 1e300, transformation=B * 1e10), "ROCKING_ERR_OVERFLOW", "not finite"),
    ]
    for change, c_name, detail in cases:
        args = dict(transformation=B.copy(), nodal_mass=M.copy(), nodal_load=np.zeros(6))
        args.update(change)
        before = {k: np.array(v, copy=True) for k, v in args.items()}
        with pytest.raises(rocking.RockingError) as info:
            rocking.reduce(**args)
        assert info.value.name == c_name and detail in info.value.detail, (change, str(info.value))
        for k, v in before.items():
            np.testing.assert_array_equal(args[k], v)


def test_not_an_array_is_a_type_error(two_blocks):
    M, _ = two_blocks
    for bad in [dict(velocity=["a", "b", "c", "d"]), dict(mass=[[1, 2], [3]]), dict(status=None),
                dict(closing_interface=1.0), dict(closing_interface="1"),
                # numpy would drop the imaginary parts with a warning
                dict(mass=M.astype(complex)), dict(velocity=np.array([0, 0, 0, -1.0 + 0j]))]:
        with pytest.raises(TypeError) as info:
            rocking.impact_model(**impact_args(M, **bad))
        assert next(iter(bad)) in str(info.value)


def test_strings_and_dates_are_not_numbers(two_blocks):
    """numpy reads the strings "0" and "-1" and a date (days since 1970) as float64: they were
    taken as numbers. Refused, naming the argument (the statuses, masses, rates, records, times
    and design arguments alike)."""
    M, _ = two_blocks
    for bad in [dict(velocity=["0", "0", "0", "-1"]), dict(velocity=np.array(["0", "0", "0", "-1"])),
                dict(velocity=np.array([b"0", b"0", b"0", b"-1"])), dict(status=np.array(["0", "1"])),
                dict(mass=M.astype(str)), dict(velocity=np.array(["2020-01-01"] * 4, dtype="datetime64[D]")),
                dict(velocity=np.array([0, 0, 0, -1], dtype="timedelta64[s]"))]:
        with pytest.raises(TypeError, match=f"{next(iter(bad))}: ") as info:
            rocking.impact_model(**impact_args(M, **bad))
        assert "not numbers" in str(info.value), info.value
    with pytest.raises(TypeError, match="width: "):
        rocking.column_mass_matrix(["0.1"], [0.3], [15])
    with pytest.raises(TypeError, match="samples: "):
        rocking.Record(np.array(["1", "2"]), 0.01)
    with pytest.raises(TypeError, match="t: "):
        rocking.half_sine(1.0, 1.0).acceleration("0.5")
    for name in ["height", "pga", "t1"]:
        args = dict(height=10.0, pga=3.0, t1=0.25)
        for bad in [None, "3", ["3"], [3.0, None]]:
            with pytest.raises(TypeError, match=f"{name}: "):
                rocking.design_width(**dict(args, **{name: bad}))
    with pytest.raises(TypeError, match="width: "):
        rocking.design_check(width=None, height=10.0, pga=3.0, t1=0.25)


def test_codes_and_messages_are_the_c_abis(cabi):
    """ERROR_CODES is the C header's table, and each RockingError.message is the text of
    rocking_error_message for its code."""
    smoke, lib = cabi
    for name, code in rocking.ERROR_CODES.items():
        assert lib.rocking_error_message(code).decode() != "unknown status code", name
    assert rocking.ERROR_CODES["ROCKING_OK"] == 0
    header = (pytest.importorskip("pathlib").Path(__file__).resolve().parents[2] / "include" / "rocking.h").read_text()
    for name, code in rocking.ERROR_CODES.items():
        assert f"#define {name} {code}" in header or f"#define {name} ({code})" in header, name
    M, _ = rocking.column_mass_matrix([0.1, 0.1], [0.3, 0.3], [15, 15])
    for name, change, c_name, _ in IMPACT_CASES:
        with pytest.raises(rocking.RockingError) as info:
            rocking.impact_model(**impact_args(M, **change(M)))
        assert info.value.message == lib.rocking_error_message(info.value.code).decode(), name


def test_record_and_pulse_errors_have_no_code(tmp_path):
    bad = tmp_path / "bad.txt"
    bad.write_text("0.1\nabc\n")
    with pytest.raises(rocking.RockingError) as info:
        rocking.read_record(bad, dt=0.01)
    assert info.value.code is None and info.value.name is None
    assert "line 2" in info.value.detail
    with pytest.raises(FileNotFoundError):
        rocking.read_record(tmp_path / "missing.AT2")
    with pytest.raises(rocking.RockingError) as info:
        rocking.read_record(bad, units="furlongs")
    assert "units" in info.value.detail
    for make, field in [(lambda: rocking.half_sine(1.0, 0.0), "duration"),
                        (lambda: rocking.full_sine(math.nan, 1.0), "amplitude"),
                        (lambda: rocking.half_sines(1.0, 0.5, 0), "count"),
                        (lambda: rocking.ricker(1.0, -2.0), "frequency"),
                        (lambda: rocking.mavroeidis_papageorgiou(1.0, 1.0, 0.5, 0.0), "gamma"),
                        (lambda: rocking.Record([0.0, math.nan], 0.01), "samples"),
                        (lambda: rocking.Record([0.0, 1.0], -0.01), "dt"),
                        (lambda: rocking.Record([0.0, 1.0], 0.01).scaled_to_pga(-1.0), "target")]:
        with pytest.raises(rocking.RockingError) as info:
            make()
        assert info.value.code is None and field in info.value.detail, (field, str(info.value))
