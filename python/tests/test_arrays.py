"""Any array-like in, new numpy arrays out, the caller's arrays never written: lists, tuples,
integer and float32 arrays, read-only, strided and Fortran-ordered arrays."""
import numpy as np
import pytest

import rocking


@pytest.fixture
def case(samples):
    c = samples["two_block_impact"]
    M, q = rocking.column_mass_matrix(c["width"], c["height"], c["block_mass"])
    return M, q, c


def variants(a, dtype=np.float64):
    """The same values as a list, a tuple, a read-only array, a strided view, Fortran order."""
    a = np.asarray(a, dtype=dtype)
    ro = a.copy()
    ro.flags.writeable = False
    big = np.zeros((2,) + a.shape, dtype=dtype)
    big[0] = a
    strided = np.repeat(a, 2, axis=-1)[..., ::2]
    assert not strided.flags.c_contiguous or a.ndim == 0 or a.shape[-1] <= 1
    return {
        "list": a.tolist(),
        "tuple": tuple(a.tolist()) if a.ndim == 1 else tuple(map(tuple, a.tolist())),
        "read-only": ro,
        "strided": strided,
        "fortran": np.asfortranarray(a),
        "slice of a bigger array": big[0],
    }


def test_every_kind_of_array_like_gives_the_same_answer(case):
    M, _, c = case
    want = rocking.impact_model(M, c["status"], c["velocity"], c["closing"])
    for (km, m), (ks, s), (kv, v) in zip(variants(M).items(), variants(c["status"], np.int8).items(),
                                           variants(c["velocity"]).items()):
        got = rocking.impact_model(m, s, v, c["closing"])
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1]), (km, ks, kv)
    # Other dtypes: int statuses of any width, float32 rates, a flat (4n²,) mass matrix.
    for status in [np.array(c["status"], dtype=np.int64), np.array(c["status"], dtype=np.float64)]:
        got = rocking.impact_model(M.ravel(), status, np.array(c["velocity"], dtype=np.float32), c["closing"])
        assert np.array_equal(got[0], want[0]) and np.array_equal(got[1], want[1])


def test_inputs_are_never_written_and_outputs_are_new(case):
    M, q, c = case
    status = np.array(c["status"], dtype=np.int8)
    velocity = np.array(c["velocity"])
    copies = [M.copy(), status.copy(), velocity.copy(), q.copy()]
    st, v, report = rocking.impact_model(M, status, velocity, c["closing"], n_impacts=2)
    st2, acc, report2 = rocking.opening_model(M, q, status)
    holds, reactions, must_open = rocking.check_configuration(M, q, np.zeros(2, dtype=np.int8))
    for have, want in zip([M, status, velocity, q], copies):
        assert np.array_equal(have, want) and have.dtype == want.dtype
    assert st.dtype == np.int8 and v.dtype == np.float64 and acc.dtype == np.float64
    for out in [st, v, st2, acc, reactions]:
        assert out.flags.writeable  # memory of its own (a Rust Vec handed to numpy)
        for arg in [M, status, velocity, q]:
            assert not np.shares_memory(out, arg)
    assert v.shape == (4,) and st.shape == (2,)


def test_outputs_are_independent_between_calls(case):
    M, _, c = case
    a = rocking.impact_model(M, c["status"], c["velocity"], c["closing"])
    b = rocking.impact_model(M, c["status"], c["velocity"], c["closing"])
    a[1][:] = 99.0
    assert not np.array_equal(a[1], b[1])


def test_column_and_reduce_outputs_are_new_arrays():
    width = np.array([0.1, 0.1])
    M, q = rocking.column_mass_matrix(width, [0.3, 0.3], [15, 15])
    assert M.shape == (4, 4) and q.shape == (4,) and M.flags.c_contiguous
    assert np.array_equal(width, [0.1, 0.1])
    B = np.asfortranarray(np.arange(12.0).reshape(6, 2))
    nodal = np.eye(6)
    Mr, pr = rocking.reduce(B, nodal, np.ones(6))
    np.testing.assert_allclose(Mr, B.T @ B, rtol=1e-15)
    np.testing.assert_allclose(pr, B.T @ np.ones(6), rtol=1e-15)
    assert np.array_equal(nodal, np.eye(6))


def test_report(case):
    M, _, c = case
    _, _, r = rocking.impact_model(M, c["status"], c["velocity"], c["closing"])
    d = r.to_dict()
    assert set(d) == {"admissible", "changed", "condition_estimate", "configurations_examined", "impacts_applied",
                      "kinetic_after", "kinetic_before", "runner_up", "solver", "tie"}
    assert d["kinetic_before"] == r.kinetic_before and d["solver"] == r.solver == "enumerate"
    assert r.configurations_examined > 0 and r.admissible > 0
    assert (d["runner_up"] is None) == np.isnan(r.runner_up)
    assert np.isnan(r.runner_up_gap) == np.isnan(r.runner_up)
    assert "Report(solver=" in repr(r)
    with pytest.raises(AttributeError):
        r.changed = False  # frozen


def frozen(a, dtype=np.float64):
    a = np.array(a, dtype=dtype)
    a.flags.writeable = False
    return a


def test_simulate_spectra_and_design_leave_their_arguments_alone(root):
    """Read-only arrays are accepted (nothing tries to write them), writable ones and the scene
    dict come back unchanged, and the results are new arrays."""
    import copy
    import json

    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    scene["initial_angles"] = frozen(scene["initial_angles"])
    before = copy.deepcopy(scene)
    r = rocking.simulate(scene)
    assert scene.keys() == before.keys() and all(
        np.array_equal(scene[k], before[k]) if isinstance(scene[k], np.ndarray) else scene[k] == before[k]
        for k in scene)
    assert r.block_rotations.flags.writeable and not np.shares_memory(r.dof_angles, scene["initial_angles"])

    levels, sizes = frozen([2.0, 4.0]), frozen([10.0, 1.0, 0.3])
    o = rocking.oas(root / "examples/records/synthetic.AT2", levels=levels, sizes=sizes)
    np.testing.assert_array_equal(levels, [2.0, 4.0])
    assert not np.shares_memory(o.levels, levels) and not np.shares_memory(o.sizes, sizes)

    heights = np.array([10.0, 20.0])
    pga = frozen([3.0, 3.0])
    w = rocking.design_width(heights, pga, 0.25)
    np.testing.assert_array_equal(heights, [10.0, 20.0])
    assert not np.shares_memory(w["height"], heights)
    w["height"][0] = -1.0  # the result is the caller's to write
    assert heights[0] == 10.0


def test_a_report_pickles(case):
    """A worker process's impact_model result goes back through pickle: `cannot pickle
    'rocking.Report' object`. It comes back with every field, NaN runner_up included."""
    import copy
    import pickle

    M, q, c = case
    _, _, report = rocking.impact_model(M, c["status"], c["velocity"], c["closing"])
    Mt, qt = rocking.column_mass_matrix([0.1, 0.1], [0.3, 0.3], [15, 15], ground_acceleration=-4.0)
    _, _, opening = rocking.opening_model(Mt, qt, [0, 0], solver="projection")
    for r in [report, opening]:
        for back in [pickle.loads(pickle.dumps(r)), copy.deepcopy(r)]:
            assert type(back) is type(r) and repr(back) == repr(r) and back.to_dict() == r.to_dict()
