"""rocking.tp and rocking.suite against the CLI run live (`rocking tp --json`, `rocking suite
--merge ... --json` on the same inputs; wall times aside): the bundled record and the same record
reversed in time, on a small grid. Then the result objects, the errors and the arguments left
untouched."""
import copy
import json

import numpy as np
import pytest

import rocking

RECORD = "examples/records/synthetic.AT2"

GRID = dict(levels=8, sizes=24)
GRID_CLI = ["--levels", 8, "--sizes", 24]


def test_tp_as_the_cli(root, cli, reversed_record, tmp_path, monkeypatch):
    other = reversed_record
    monkeypatch.chdir(root)
    expected = cli("tp", RECORD, other, "--json")
    assert rocking.tp([RECORD, other]) == expected
    one = rocking.tp(RECORD)
    assert one == expected[0] and one["t_p"] == pytest.approx(one["i_max"] / (2 / np.pi * one["a_max"]), rel=1e-15)
    assert one["lobe_start"] < one["lobe_end"]
    samples = np.array(rocking.read_record(RECORD).samples)
    kept = samples.copy()
    row = rocking.tp(rocking.Record(samples, 0.01, name="synthetic"))
    assert row["file"] is None and {k: v for k, v in row.items() if k != "file"} == {
        k: v for k, v in one.items() if k != "file"}
    np.testing.assert_array_equal(samples, kept)


def test_tp_errors(tmp_path):
    with pytest.raises(rocking.RockingError, match=r"records\[1\]: `silent` is zero everywhere") as e:
        rocking.tp([RECORD, rocking.Record([0.0, 0.0, 0.0], 0.01, name="silent")])
    assert e.value.code is None
    with pytest.raises(FileNotFoundError):
        rocking.tp(tmp_path / "nowhere.AT2")
    with pytest.raises(rocking.RockingError, match="record"):
        rocking.tp(42)


@pytest.fixture(scope="module")
def two_oas(root, reversed_record):
    return [rocking.oas(root / RECORD, **GRID), rocking.oas(reversed_record, **GRID)]


def strip_seconds(report):
    r = copy.deepcopy(report)
    r.pop("seconds")
    for o in r["records"]:
        o["summary"].pop("seconds")
    return r


def test_suite_as_the_cli(root, cli, reversed_record, tmp_path, two_oas):
    other = reversed_record
    files = []
    for k, rec in enumerate([root / RECORD, other]):
        f = tmp_path / f"oas-{k}.json"
        f.write_text(json.dumps(cli("oas", rec, "--json", *GRID_CLI)))
        files.append(f)
    expected = cli("suite", "--merge", *files, "--json", "--name", "two", "--fractile", "0.5,0.9")
    # the CLI's own reports: the same report, wall times included
    dicts = [json.loads(f.read_text()) for f in files]
    kept = copy.deepcopy(dicts)
    s = rocking.suite(dicts, name="two", fractiles=(0.5, 0.9))
    assert s.to_dict() == expected and dicts == kept
    # the package's own OAS: the same but for the wall times
    s = rocking.suite(two_oas, name="two", fractiles=[0.5, 0.9])
    assert strip_seconds(s.to_dict()) == strip_seconds(expected)
    assert s.seconds == pytest.approx(sum(o.summary["seconds"] for o in two_oas), rel=1e-12)


def test_suite_result(two_oas):
    before = [o.to_dict() for o in two_oas]
    s = rocking.suite(two_oas)
    assert [o.to_dict() for o in two_oas] == before
    assert s.name == "suite" and [o.record for o in s.records] == ["reversed", "synthetic"]
    assert all(isinstance(o, rocking.Oas) for o in s.records)
    assert [c["fractile"] for c in s.characteristic] == [0.5, 0.84]
    median = s.characteristic[0]
    assert isinstance(median["oas"], rocking.Oas) and median["oas"].i_cr == two_oas[0].i_cr
    assert median["design_t1"] == median["oas"].t1 == s.design_t1[0.5]
    # the median of two records' boundaries: at every level between the two (sizes descending)
    lo = np.fmin(two_oas[0].largest_unsafe, two_oas[1].largest_unsafe)
    hi = np.fmax(two_oas[0].largest_unsafe, two_oas[1].largest_unsafe)
    c = median["oas"].largest_unsafe
    assert np.all((lo <= c) & (c <= hi))
    assert len(s.hulls) == 2 and all(h["vertices"][0]["f_normalised"] >= 1.0 for h in s.hulls)
    assert "2 records" in repr(s)


def test_suite_errors(root, two_oas):
    with pytest.raises(rocking.RockingError, match=r"spectra\[1\]: record `synthetic` is already") as e:
        rocking.suite([two_oas[0], two_oas[0]])
    assert e.value.code is None
    with pytest.raises(rocking.RockingError, match=r"fractiles\[0\] = 0"):
        rocking.suite(two_oas, fractiles=[0.0])
    with pytest.raises(rocking.RockingError, match="fractiles"):
        rocking.suite(two_oas, fractiles=[])
    with pytest.raises(rocking.RockingError, match="spectra"):
        rocking.suite([])
    with pytest.raises(rocking.RockingError, match=r"spectra\[0\]: not an OAS"):
        rocking.suite([{"record": "x"}])
    with pytest.raises(TypeError, match="spectra"):
        rocking.suite(["oas.json"])
    with pytest.raises(TypeError, match=r"fractiles\[0\]"):
        rocking.suite(two_oas, fractiles=["median"])
    coarse = rocking.oas(root / RECORD, levels=4, sizes=24).to_dict()
    coarse["record"] = "coarse"
    with pytest.raises(rocking.RockingError, match="level"):
        rocking.suite([two_oas[0], coarse])


def test_suite_plot(two_oas):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    s = rocking.suite(two_oas)
    ax = s.plot()
    assert len(ax.lines) == 2 + 2  # the two records, the two fractiles
    assert len(s.plot(against="f").lines) == 2 + 2 * 2  # and each fractile's design f_min
    with pytest.raises(ValueError, match="against"):
        s.plot(against="size")
