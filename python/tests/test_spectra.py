"""rocking.oas, t1, oc, design_width and design_check against the CLI: each equals the JSON of
the same `rocking` command captured in tests/golden (wall times aside), on small grids of the
bundled record. Then the arrays, determinism across thread counts, Ctrl-C, and the errors."""
import json
import os
import signal

import numpy as np
import pytest

import rocking

RECORD = "examples/records/synthetic.AT2"


def golden(root, name):
    return json.loads((root / "tests/golden" / name).read_text())


def without_seconds(d):
    d = json.loads(json.dumps(d))
    if isinstance(d, list):
        for row in d:
            row.pop("seconds")
    else:
        d["summary"].pop("seconds")
    return d


@pytest.fixture(scope="module")
def small_oas(root):
    """`rocking oas examples/records/synthetic.AT2 --json --levels 16 --sizes 40`."""
    return rocking.oas(root / RECORD, levels=16, sizes=40)


def test_oas_as_the_cli(root, small_oas):
    assert without_seconds(small_oas.to_dict()) == golden(root, "oas-synthetic.json")
    assert small_oas.summary["seconds"] > 0


def test_oas_arrays(small_oas):
    o = small_oas
    raw = o.to_dict()
    assert o.levels.shape == o.size.shape == o.p.shape == o.f.shape == o.largest_unsafe.shape == (16,)
    np.testing.assert_allclose(o.levels, np.linspace(1.0, 10.0, 16), rtol=1e-15)
    assert o.sizes.shape == (40,) and np.all(np.diff(o.sizes) < 0)
    assert o.sizes[0] == pytest.approx(1000.0) and o.sizes[-1] == pytest.approx(0.1)
    # level 1 overturns nothing: -1 and NaN; elsewhere the size of the index
    assert o.largest_unsafe[0] == -1 and np.isnan(o.size[0]) and np.isnan(o.f[0])
    m = o.unsafe
    np.testing.assert_array_equal(o.size[m], o.sizes[o.largest_unsafe[m]])
    np.testing.assert_array_equal(o.f[m], o.p[m] * o.levels[m])
    assert int(o.simulations.sum()) == raw["summary"]["simulations"]
    # t1 = i_cr / f_min (Eq. 20), i_cr of H/B = 12 (Eq. 18)
    delta = np.arctan(1 / 12)
    assert o.i_cr == pytest.approx(np.sqrt(2 / (1 + np.cos(delta))), rel=1e-15)
    assert o.t1 == pytest.approx(o.i_cr / np.nanmin(o.f), rel=1e-15)
    assert o.t1 == raw["summary"]["t1"]


def test_oas_of_a_record_object_and_any_thread_count(root, small_oas):
    record = rocking.read_record(root / RECORD)
    one = rocking.oas(record, levels=16, sizes=40, threads=1)
    assert without_seconds(one.to_dict()) == without_seconds(small_oas.to_dict())
    explicit = rocking.oas(record, levels=small_oas.levels, sizes=small_oas.sizes, threads=2)
    assert without_seconds(explicit.to_dict()) == without_seconds(small_oas.to_dict())


def test_t1_as_the_cli(root, monkeypatch):
    """`rocking t1 examples/records/synthetic.AT2 --json --blocks 3 --impacts 2 --levels 8
    --sizes 24 --single-step` (the golden row: one OAS at the step rule; the default, converged in
    the step, is test_t1.py's)."""
    monkeypatch.chdir(root)
    rows = rocking.t1([RECORD], blocks=3, impacts=2, levels=8, sizes=24, converge_step=None)
    assert without_seconds(rows) == golden(root, "t1-synthetic-3blocks.json")
    one = rocking.t1(rocking.read_record(RECORD), blocks=3, impacts=2, levels=8, sizes=24, converge_step=None)
    assert one["file"] is None and one["t1"] == rows[0]["t1"] and one["beta"] == rows[0]["beta"]


@pytest.mark.parametrize(
    "name, args",
    [
        ("oc-half-sine.json", dict(shape="half-sine", blocks=2, impacts=2, ptp=12, levels=12)),
        ("oc-ricker.json", dict(shape="ricker", ptp=12, levels=12)),
    ],
)
def test_oc_as_the_cli(root, name, args):
    o = rocking.oc(**args)
    assert o.to_dict() == golden(root, name)
    assert o.unsafe.shape == (12, 12) and o.unsafe.dtype == bool
    np.testing.assert_allclose(o.p_tp, o.p * o.t_p, rtol=1e-15)
    np.testing.assert_allclose(o.levels, o.a_p / o.a_p_min, rtol=1e-15)
    for i in range(12):
        lowest = o.levels[o.unsafe[i]].min() if o.unsafe[i].any() else np.nan
        np.testing.assert_equal(o.envelope[i], lowest)
    assert rocking.oc(**args, threads=1).to_dict() == o.to_dict()


def test_design_as_the_cli(root):
    """`rocking design width --height 10 --pga 3 --t1 0.25 --mass uniform --json` and `design
    check --width 1.5 ...`."""
    assert rocking.design_width(10, 3, 0.25, mass="uniform") == golden(root, "design-width.json")
    assert rocking.design_check(1.5, 10, 3, 0.25) == golden(root, "design-check.json")


def test_design_over_arrays():
    heights, t1s = np.array([10.0, 20.0, 30.0]), np.array([[0.25], [0.5]])
    w = rocking.design_width(heights, 3.0, t1s, mass="top")
    assert w["width"].shape == (2, 3) and w["governing"].shape == (2, 3) and w["mass"] == "top"
    for i in range(2):
        for j in range(3):
            one = rocking.design_width(heights[j], 3.0, t1s[i, 0], mass="top")
            assert w["width"][i, j] == one["width"] and w["governing"][i, j] == one["governing"]
    # the required width passes its own check (Eq. 31 with i_cr = 1), up to the bisection
    c = rocking.design_check(w["width"] * (1 + 1e-9), heights, 3.0, t1s, mass="top")
    assert c["safe"].all() and c["safe"].dtype == bool
    np.testing.assert_allclose(c["utilisation"], 1.0, rtol=1e-6)


def test_design_errors_name_the_argument():
    with pytest.raises(rocking.RockingError, match="pga"):
        rocking.design_width(10, -3, 0.25)
    with pytest.raises(rocking.RockingError, match=r"t1\[1\]"):
        rocking.design_width(10, 3, [0.25, 0.0])
    with pytest.raises(rocking.RockingError, match="width"):
        rocking.design_check(0.0, 10, 3, 0.25)
    with pytest.raises(rocking.RockingError, match="mass"):
        rocking.design_width(10, 3, 0.25, mass="heavy")
    with pytest.raises(rocking.RockingError, match="broadcast"):
        rocking.design_width([10, 20], [3, 4, 5], 0.25)


@pytest.mark.parametrize(
    "args, field",
    [
        (dict(levels=0), "levels"),
        (dict(sizes=[1.0, 2.0]), "sizes"),
        (dict(impacts=0), "impacts"),
        (dict(dt_factor=-1.0), "dt_factor"),
        (dict(tail=-1.0), "tail"),
        (dict(slenderness=0.0), "slenderness"),
        (dict(blocks=0), "blocks"),
        (dict(threads=0), "threads"),
        (dict(levels=[[1.0, 2.0]]), "levels"),
        (dict(level_max=float("nan")), "level_max = NaN"),
        (dict(size_min=0.0), "size_min = 0.0"),
        (dict(size_max=float("inf")), "size_max = inf"),
        (dict(blocks=2**70), f"blocks = {2**70}: out of range"),
        (dict(levels=2**64), f"levels = {2**64}: out of range"),
    ],
)
def test_oas_errors_name_the_argument(root, args, field):
    with pytest.raises(rocking.RockingError, match=field):
        rocking.oas(root / RECORD, **{"levels": 2, "sizes": 3, **args})


@pytest.mark.parametrize("call, field", [
    (lambda r: rocking.oas(r, levels=[], sizes=3), "levels: no value"),
    (lambda r: rocking.oas(r, levels=2, sizes=np.zeros(0)), "sizes: no value"),
    (lambda r: rocking.t1(r, levels=(), sizes=3, converge_step=None), "levels: no value"),
    (lambda r: rocking.oc(ptp=[], levels=2), "ptp: no value"),
    (lambda r: rocking.oc(ptp=2, levels=[]), "levels: no value"),
])
def test_an_empty_grid_is_refused(root, call, field):
    """levels=[] ran a spectrum of no level (t1 None, 0 simulations), silently."""
    with pytest.raises(rocking.RockingError, match=field):
        call(root / RECORD)


@pytest.mark.parametrize("args, field", [(dict(levels=4.0), "levels = 4.0"), (dict(sizes=6.0), "sizes = 6.0"),
                                         (dict(sizes=np.float64(6)), "sizes = 6.0")])
def test_a_count_that_is_a_float_is_named_as_a_count(root, args, field):
    """sizes=6.0 said `sizes has shape (), expected 1-D`: a count must be an integer."""
    with pytest.raises(TypeError, match=rf"{field}: a count must be an integer"):
        rocking.oas(root / RECORD, **{"levels": 2, "sizes": 3, **args})


def test_other_errors(root, tmp_path):
    with pytest.raises(FileNotFoundError):
        rocking.oas(tmp_path / "nowhere.AT2")
    with pytest.raises(rocking.RockingError, match="record"):
        rocking.oas(42)
    with pytest.raises(rocking.RockingError, match="zero PGA"):
        rocking.oas(rocking.Record([0.0, 0.0, 0.0], 0.01), levels=2, sizes=2)
    with pytest.raises(TypeError, match="slenderness"):
        rocking.oas(root / RECORD, slenderness="tall")
    with pytest.raises(rocking.RockingError, match="shape"):
        rocking.oc("square")
    with pytest.raises(rocking.RockingError, match="size"):
        rocking.oc(size=-1.0)
    # A reversed grid range (it ran on the reversed grid), as `rocking oc`.
    with pytest.raises(rocking.RockingError, match="ptp_min = 5: must be below ptp_max"):
        rocking.oc(ptp_min=5.0, ptp_max=1.0, ptp=2, levels=2)
    with pytest.raises(rocking.RockingError, match="level_max = 0.5: must be above 1"):
        rocking.oc(level_max=0.5, ptp=2, levels=2)
    with pytest.raises(rocking.RockingError, match="size_min = 10: must be below size_max"):
        rocking.oas(root / RECORD, size_min=10.0, size_max=1.0, levels=2, sizes=2)
    with pytest.raises(rocking.RockingError, match="level_max = 0.5: must be above 1"):
        rocking.oas(root / RECORD, level_max=0.5, levels=2, sizes=2)


def test_ctrl_c_stops_a_sweep(root):
    """SIGINT (what Ctrl-C sends) once the first level is done: KeyboardInterrupt instead of a
    result, and the next sweep runs normally."""
    seen = []

    def progress(done, total):
        seen.append((done, total))
        if done >= 1 and not any(d >= 1 for d, _ in seen[:-1]):
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        rocking.oas(root / RECORD, levels=80, sizes=120, threads=1, progress=progress)
    done, total = seen[-1]
    assert total == 80 and 1 <= done < total
    assert rocking.oas(root / RECORD, levels=2, sizes=4).levels.shape == (2,)


def test_a_failing_progress_callback_stops_the_sweep(root):
    def progress(done, total):
        raise RuntimeError(f"stop at {done}")

    with pytest.raises(RuntimeError, match="stop at"):
        rocking.oas(root / RECORD, levels=8, sizes=40, progress=progress)


def test_progress_reaches_the_total(root):
    seen = []
    rocking.oc(ptp=6, levels=4, progress=lambda d, n: seen.append((d, n)))
    assert seen[-1] == (6, 6) and all(n == 6 for _, n in seen)
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda r: rocking.oas(r, levels=2, sizes=2, level_max="10"), "level_max"),
        (lambda r: rocking.oas(r, levels=2, sizes=2, blocks=1.5), "blocks"),
        (lambda r: rocking.t1(r, levels=2, sizes=2, tail="long"), "tail"),
        (lambda r: rocking.oc(ptp=2, levels=2, size=None), "size"),
        (lambda r: rocking.oc(ptp=2, levels=2, threads=True), "threads"),
    ],
)
def test_type_errors_name_the_argument(root, call, field):
    with pytest.raises(TypeError, match=field):
        call(root / RECORD)


def test_design_type_errors_name_the_argument():
    with pytest.raises(TypeError, match="^height"):
        rocking.design_width("tall", 3.0, 0.25)
    with pytest.raises(TypeError, match="^t1"):
        rocking.design_check(1.5, 10.0, 3.0, [0.25, None, "x"])
