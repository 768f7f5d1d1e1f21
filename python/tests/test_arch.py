"""rocking.arch_oas, arch_oc and arch_suite against the CLI run live (`rocking arch oas|oc|suite
--json` on the same inputs; wall times aside), on small grids of an 8-voussoir arch and the
bundled record; then determinism across thread counts, Ctrl-C, the errors and the arguments left
untouched."""
import copy
import json
import os
import signal

import numpy as np
import pytest

import rocking

RECORD = "examples/records/synthetic.AT2"


def without_seconds(d):
    d = copy.deepcopy(d)
    assert d.pop("seconds") >= 0.0
    return d


SMALL = dict(voussoirs=8, radius_n=4, level_n=3)
SMALL_CLI = ["--voussoirs", 8, "--radius-n", 4, "--level-n", 3]


@pytest.fixture(scope="module")
def small_arch_oas(root):
    return rocking.arch_oas(root / RECORD, t1=0.3, **SMALL)


def test_arch_oas_as_the_cli(root, cli, small_arch_oas):
    expected = cli("arch", "oas", root / RECORD, *SMALL_CLI, "--t1", 0.3)
    assert without_seconds(small_arch_oas.to_dict()) == without_seconds(expected)
    assert small_arch_oas.check == {"t1": 0.3, "violations": 0, "conservative": True}
    # another family and grid, without a check
    args = dict(thickness_ratio=0.2, embrace=160, voussoirs=10, dt_factor=2, radius_max=50, radius_min=2,
                radius_n=3, level_min=2, level_max=5, level_n=2)
    flags = [x for k, v in args.items() for x in ("--" + k.replace("_", "-"), v)]
    expected = cli("arch", "oas", root / RECORD, *flags)
    got = rocking.arch_oas(root / RECORD, **args)
    assert without_seconds(got.to_dict()) == without_seconds(expected) and got.check is None


def test_arch_oas_arrays_threads_and_record_objects(root, small_arch_oas):
    o = small_arch_oas
    raw = o.to_dict()
    assert o.levels.shape == o.size.shape == o.p.shape == o.f.shape == o.largest_unsafe.shape == (3,)
    np.testing.assert_allclose(o.levels, np.linspace(1.5, 6.0, 3), rtol=1e-15)
    assert o.sizes.shape == (4,) and np.all(np.diff(o.sizes) < 0)
    m = o.unsafe
    assert m.any() and not m.all()
    np.testing.assert_array_equal(o.size[m], o.sizes[o.largest_unsafe[m]])
    np.testing.assert_allclose(o.p[m], o.p_at_1m / np.sqrt(o.size[m]), rtol=1e-15)
    np.testing.assert_array_equal(o.f[m], o.p[m] * o.levels[m])
    assert np.isnan(o.f[~m]).all() and (o.largest_unsafe[~m] == -1).all()
    assert o.t1 == pytest.approx(1.0 / np.nanmin(o.f), rel=1e-15) and o.f_min == np.nanmin(o.f)
    assert int(o.simulations.sum()) == o.runs["collapsed"] + o.runs["survived"] + len(o.runs["failures"])
    assert o.lambda_ == raw["onset"]["lambda"] and o.voussoirs == 8 and o.embrace_angle == pytest.approx(np.pi)
    samples = np.array(rocking.read_record(root / RECORD).samples)
    kept = samples.copy()
    record = rocking.Record(samples, 0.01, name="synthetic")
    one = rocking.arch_oas(record, t1=0.3, threads=1, **SMALL)
    two = rocking.arch_oas(record, t1=0.3, threads=2, **SMALL)
    assert without_seconds(one.to_dict()) == without_seconds(raw) == without_seconds(two.to_dict())
    np.testing.assert_array_equal(samples, kept)


@pytest.mark.parametrize(
    "args, flags",
    [
        (dict(voussoirs=8, ptp_n=3, level_n=4), ["--voussoirs", 8, "--ptp-n", 3, "--level-n", 4]),
        (dict(shape="ricker", voussoirs=12, radius=3, ptp_min=1, ptp_max=8, ptp_n=5, level_max=5, level_n=6),
         ["--shape", "ricker", "--voussoirs", 12, "--radius", 3, "--ptp-min", 1, "--ptp-max", 8, "--ptp-n", 5,
          "--level-max", 5, "--level-n", 6]),
    ],
)
def test_arch_oc_as_the_cli(cli, args, flags):
    o = rocking.arch_oc(**args)
    assert without_seconds(o.to_dict()) == without_seconds(cli("arch", "oc", *flags))
    rows, cols = args["ptp_n"], args["level_n"]
    assert o.collapses.shape == (rows, cols) and o.collapses.dtype == bool
    np.testing.assert_allclose(o.p_tp, o.p * o.t_p, rtol=1e-15)
    np.testing.assert_allclose(o.levels, np.linspace(1.0, args.get("level_max", 6.0), cols), rtol=1e-15)
    for i in range(rows):
        lowest = o.levels[o.collapses[i]].min() if o.collapses[i].any() else np.nan
        np.testing.assert_equal(o.envelope[i], lowest)
    assert o.runs["collapsed"] == int(o.collapses.sum())
    assert without_seconds(rocking.arch_oc(**args, threads=1).to_dict()) == without_seconds(o.to_dict())


def test_arch_suite_as_the_cli(root, cli, reversed_record, tmp_path, small_arch_oas):
    other = reversed_record
    files = []
    for k, rec in enumerate([root / RECORD, other]):
        f = tmp_path / f"arch-{k}.json"
        f.write_text(json.dumps(cli("arch", "oas", rec, *SMALL_CLI, "--t1", 0.3)))
        files.append(f)
    expected = cli("arch", "suite", *files, "--json", "--name", "two", "--fractile", "0.5,0.9")
    dicts = [json.loads(f.read_text()) for f in files]
    kept = copy.deepcopy(dicts)
    assert rocking.arch_suite(dicts, name="two", fractiles=[0.5, 0.9]).to_dict() == expected
    assert dicts == kept
    # from the package's own results: the same report (the characteristic OAS has no wall time)
    results = [small_arch_oas, rocking.arch_oas(other, t1=0.3, **SMALL)]
    before = [r.to_dict() for r in results]
    got = rocking.arch_suite(results, name="two", fractiles=[0.5, 0.9])
    assert got.to_dict() == expected and [r.to_dict() for r in results] == before
    assert got.name == "two" and [r["record"] for r in got.records] == ["reversed", "synthetic"]
    assert got.block_rule["records"] == 2 and got.records[1]["block_t1"] == 0.3
    median = got.characteristic[0]
    assert isinstance(median["oas"], rocking.ArchOas) and median["design_t1"] == median["oas"].t1
    assert got.design_t1 == {0.5: median["design_t1"], 0.9: got.characteristic[1]["design_t1"]}
    # the characteristic arch OAS of two records lies between them, level by level
    lo = np.fmin(results[0].largest_unsafe, results[1].largest_unsafe)
    hi = np.fmax(results[0].largest_unsafe, results[1].largest_unsafe)
    assert np.all((lo <= median["oas"].largest_unsafe) & (median["oas"].largest_unsafe <= hi))
    assert "2 records" in repr(got)


def test_ctrl_c_stops_an_arch_sweep(root):
    seen = []

    def progress(done, total):
        seen.append((done, total))
        if done >= 1 and not any(d >= 1 for d, _ in seen[:-1]):
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        rocking.arch_oas(root / RECORD, voussoirs=8, level_n=40, threads=1, progress=progress)
    done, total = seen[-1]
    assert total == 40 and 1 <= done < total
    with pytest.raises(RuntimeError, match="stop"):
        rocking.arch_oc(voussoirs=8, progress=lambda d, n: (_ for _ in ()).throw(RuntimeError("stop")))


@pytest.mark.parametrize(
    "args, field",
    [
        (dict(thickness_ratio=-0.1), "thickness_ratio"),
        (dict(embrace=0.0), "embrace"),
        (dict(voussoirs=0), "voussoirs"),
        (dict(dt_factor=-1.0), "dt_factor"),
        (dict(radius_max=-1.0), "radius_max"),
        (dict(radius_min=200.0), "radius_min"),
        (dict(radius_n=0), "radius_n"),
        (dict(level_min=0.0), "level_min"),
        (dict(level_max=float("nan")), "level_max"),
        (dict(level_n=0), "level_n"),
        (dict(t1=0.0), "t1"),
        (dict(threads=0), "threads"),
        (dict(thickness_ratio=0.01), "arch"),
        (dict(level_min=5.0, level_max=2.0), "level_min = 5: must be below level_max"),
    ],
)
def test_arch_oas_errors_name_the_argument(root, args, field):
    with pytest.raises(rocking.RockingError, match=field) as e:
        rocking.arch_oas(root / RECORD, **{**SMALL, **args})
    assert isinstance(e.value, ValueError) and e.value.code is None and field in e.value.detail


@pytest.mark.parametrize(
    "args, field",
    [
        (dict(shape="square"), "shape"),
        (dict(radius=-5.0), "radius"),
        (dict(ptp_min=0.0), "ptp_min"),
        (dict(ptp_n=0), "ptp_n"),
        (dict(level_n=0), "level_n"),
        (dict(voussoirs=0), "voussoirs"),
        # Judged in the degrees and the t/R given (they were `arch.embrace_angle = 6.28…: must
        # be less than 2π` and `arch.thickness = 2.5`).
        (dict(embrace=360.0), "embrace = 360: must be greater than 0"),
        (dict(thickness_ratio=2.5), "thickness_ratio = 2.5"),
        # A reversed grid range (it ran on the reversed grid), as `arch oc`.
        (dict(ptp_min=5.0, ptp_max=1.0), "ptp_min = 5: must be below ptp_max"),
        (dict(level_max=0.5), "level_max = 0.5: must be above 1"),
    ],
)
def test_arch_oc_errors_name_the_argument(args, field):
    with pytest.raises(rocking.RockingError, match=field) as e:
        rocking.arch_oc(**{"voussoirs": 8, "ptp_n": 2, "level_n": 2, **args})
    assert e.value.code is None and field in e.value.detail


def test_arch_type_and_input_errors(root, small_arch_oas):
    with pytest.raises(TypeError, match="voussoirs"):
        rocking.arch_oas(root / RECORD, voussoirs=8.5)
    with pytest.raises(TypeError, match="radius"):
        rocking.arch_oc(radius="big")
    with pytest.raises(rocking.RockingError, match="zero PGA"):
        rocking.arch_oas(rocking.Record([0.0, 0.0, 0.0], 0.01), **SMALL)
    with pytest.raises(TypeError, match="spectra"):
        rocking.arch_suite([42])
    with pytest.raises(rocking.RockingError, match=r"spectra\[0\]: not an arch OAS"):
        rocking.arch_suite([{"record": "x"}])
    with pytest.raises(rocking.RockingError, match=r"spectra\[1\]: record `synthetic` is already"):
        rocking.arch_suite([small_arch_oas, small_arch_oas])
    with pytest.raises(rocking.RockingError, match=r"fractiles\[1\]"):
        rocking.arch_suite([small_arch_oas], fractiles=[0.5, 1.5])
    other = rocking.arch_oas(root / RECORD, voussoirs=8, radius_n=3, level_n=3)
    other_dict = other.to_dict()
    other_dict["record"] = "other"
    with pytest.raises(rocking.RockingError, match=r"spectra\[1\]"):
        rocking.arch_suite([small_arch_oas, other_dict])


def test_arch_plots(small_arch_oas):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    ax = small_arch_oas.plot()
    assert len(ax.lines) == 3  # the boundary, Eq. 21 of the arch's own t1 and of the checked one
    assert len(small_arch_oas.plot(against="f").lines) == 3
    oc = rocking.arch_oc(voussoirs=8, ptp_n=3, level_n=4)
    assert len(oc.plot().lines) == 2
    with pytest.raises(ValueError, match="against"):
        small_arch_oas.plot(against="size")
    suite = rocking.arch_suite([small_arch_oas])
    assert len(suite.plot().lines) == 2 and len(suite.plot(against="f").lines) == 4  # and the f_min lines
