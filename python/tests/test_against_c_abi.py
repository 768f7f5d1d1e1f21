"""Random columns through the Python package and through the C ABI (ctypes on the cdylib): the
same statuses, the same numbers bit for bit, the same reports and the same error codes."""
import ctypes

import numpy as np
import pytest

import rocking

SOLVERS = {"auto": 0, "enumerate": 1, "projection": 2}


def random_column(rng, n):
    width = rng.uniform(0.2, 1.0, n)
    height = width * rng.uniform(2.0, 6.0, n)
    mass = rng.uniform(10.0, 1000.0, n)
    return width, height, mass


def random_pose(rng, n):
    """DOF angles with random statuses and admissible signs, and those statuses."""
    status = rng.integers(-1, 2, n)
    phi = np.zeros(2 * n)
    for k, s in enumerate(status):
        if s < 0:
            phi[k] = -rng.uniform(0.0, 0.2)
        elif s > 0:
            phi[n + k] = rng.uniform(0.0, 0.2)
    return phi, status


def c_column(smoke, lib, width, height, mass, phi, ag):
    n = len(width)
    M, q = smoke.doubles([0.0] * 4 * n * n), smoke.doubles([0.0] * 2 * n)
    code = lib.rocking_column_mass_matrix(n, smoke.doubles(width), smoke.doubles(height), smoke.doubles(mass),
                                          None, None, smoke.doubles(phi), ag, 9.81, M, q)
    assert code == 0, lib.rocking_last_error_message()
    return np.array(M[:]).reshape(2 * n, 2 * n), np.array(q[:])


def report_fields(r):
    names = ["changed", "tie", "impacts_applied", "configurations_examined", "admissible",
             "kinetic_before", "kinetic_after", "runner_up", "condition_estimate"]
    values = [bool(getattr(r, k)) if k in ("changed", "tie") else getattr(r, k) for k in names]
    return [("nan" if isinstance(v, float) and np.isnan(v) else v) for v in values]


@pytest.mark.parametrize("seed", range(40))
def test_random_columns(cabi, seed):
    smoke, lib = cabi
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 6))
    width, height, mass = random_column(rng, n)
    phi, status = random_pose(rng, n)
    ag = rng.uniform(-2.0, 2.0) * 9.81 * 0.3
    M, q = rocking.column_mass_matrix(width, height, mass, phi=phi, ground_acceleration=ag)
    Mc, qc = c_column(smoke, lib, width, height, mass, phi, ag)
    assert np.array_equal(M, Mc) and np.array_equal(q, qc)
    solver = ["auto", "enumerate", "projection"][seed % 3]

    # Opening model and reaction test.
    st, acc, rep = rocking.opening_model(M, q, status, solver=solver)
    cst, cacc, crep = smoke.int8s(status.tolist()), smoke.doubles([0.0] * 2 * n), smoke.RockingReport()
    opts = smoke.RockingOptions(1, SOLVERS[solver], 1e-12)
    code = lib.rocking_opening_model(n, smoke.doubles(M.ravel()), smoke.doubles(q), cst, cacc, ctypes.byref(opts),
                                     ctypes.byref(crep))
    assert code == 0, lib.rocking_last_error_message()
    assert st.tolist() == list(cst) and np.array_equal(acc, np.array(cacc[:]))
    assert report_fields(rep) == report_fields(crep)
    assert rep.solver == ["auto", "enumerate", "projection"][crep.solver]
    holds, reactions, must_open = rocking.check_configuration(M, q, status)
    ch, creac, cmust = ctypes.c_uint8(7), smoke.doubles([0.0] * 2 * n), (ctypes.c_uint8 * n)()
    code = lib.rocking_check_configuration(n, smoke.doubles(M.ravel()), smoke.doubles(q), smoke.int8s(status.tolist()),
                                           1e-12, ctypes.byref(ch), creac, cmust)
    assert code == 0
    assert holds == bool(ch.value) and np.array_equal(reactions, np.array(creac[:]))
    assert must_open.tolist() == [k for k in range(n) if cmust[k]]
    assert holds == (not rep.changed)

    # Impact model: an open interface closes (when there is one); otherwise open one at random.
    if not (status != 0).any():
        status[rng.integers(0, n)] = 1
    closing = int(rng.choice(np.flatnonzero(status)))
    v = np.zeros(2 * n)
    for k, s in enumerate(status):
        if s:
            v[k if s < 0 else n + k] = rng.normal()
    dof = closing if status[closing] < 0 else n + closing
    v[dof] = -status[closing] * abs(rng.normal()) - 0.1 * status[closing]  # towards closure
    n_impacts = int(rng.integers(1, 4))
    py = rocking.impact_model(M, status, v, closing, n_impacts=n_impacts, solver=solver)
    cst, cv, crep = smoke.int8s(status.tolist()), smoke.doubles(v), smoke.RockingReport()
    opts = smoke.RockingOptions(n_impacts, SOLVERS[solver], 1e-12)
    code = lib.rocking_impact_model(n, smoke.doubles(M.ravel()), cst, cv, closing, ctypes.byref(opts), ctypes.byref(crep))
    assert code == 0, lib.rocking_last_error_message()
    assert py[0].tolist() == list(cst) and np.array_equal(py[1], np.array(cv[:]))
    assert report_fields(py[2]) == report_fields(crep)

    # The same error code for a broken input (the mass matrix made asymmetric).
    bad = M.copy()
    bad[0, -1] += 1.0
    with pytest.raises(rocking.RockingError) as info:
        rocking.impact_model(bad, status, v, closing)
    code = lib.rocking_impact_model(n, smoke.doubles(bad.ravel()), smoke.int8s(status.tolist()), smoke.doubles(v),
                                    closing, None, None)
    assert info.value.code == code == rocking.ERROR_CODES["ROCKING_ERR_NOT_SYMMETRIC"]
    assert str(info.value) == lib.rocking_last_error_message().decode()


@pytest.mark.parametrize("seed", range(10))
def test_random_reductions(cabi, seed):
    smoke, lib = cabi
    rng = np.random.default_rng(100 + seed)
    n_nodal, n_reduced = int(rng.integers(2, 30)), int(rng.integers(1, 8))
    A = rng.normal(size=(n_nodal, n_nodal))
    M = A @ A.T + n_nodal * np.eye(n_nodal)
    M = 0.5 * (M + M.T)
    B = rng.normal(size=(n_nodal, n_reduced))
    p = rng.normal(size=n_nodal)
    Mr, pr = rocking.reduce(B, M, p)
    cm, cp = smoke.doubles([0.0] * n_reduced * n_reduced), smoke.doubles([0.0] * n_reduced)
    # The C ABI takes column-major matrices (B.T.ravel() is B column by column).
    code = lib.rocking_reduce(n_nodal, n_reduced, smoke.doubles(M.T.ravel()), smoke.doubles(B.T.ravel()),
                              smoke.doubles(p), cm, cp)
    assert code == 0, lib.rocking_last_error_message()
    assert np.array_equal(Mr, np.array(cm[:]).reshape(n_reduced, n_reduced).T)
    assert np.array_equal(pr, np.array(cp[:]))
    np.testing.assert_allclose(Mr, B.T @ M @ B, rtol=1e-12, atol=1e-12 * np.abs(B.T @ M @ B).max())
