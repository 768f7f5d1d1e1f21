"""rocking.t1 against the CLI: the rows equal `rocking t1 --json` (wall times aside) on small grids
of the bundled record, for any number of threads, by default (converged in the step), with
`converge_step=None` (`--single-step`), `band` (`--band`, with either) and the other
`--converge-step TOL --converge-halvings N`; Ctrl-C stops them; bad values name the argument."""
import json
import os
import signal

import numpy as np
import pytest

import rocking

RECORD = "examples/records/synthetic.AT2"
GRID = dict(levels=8, sizes=24)
GRID_CLI = ("--levels", 8, "--sizes", 24)


def without_seconds(rows):
    rows = json.loads(json.dumps(rows))
    for row in rows:
        row.pop("seconds")
    return rows


def test_default_converges_in_the_step_as_the_cli(root, cli, monkeypatch, reversed_record):
    monkeypatch.chdir(root)
    records = [RECORD, str(reversed_record)]
    rows = rocking.t1(records, **GRID)
    assert without_seconds(rows) == without_seconds(cli("t1", *records, "--json", *GRID_CLI))
    explicit = rocking.t1(records, converge_step=0.1, converge_halvings=4, **GRID)
    assert without_seconds(explicit) == without_seconds(rows)
    for row in rows:
        steps = row["t1_steps"]
        assert steps[0][0] == 1.0 and row["dt_factor"] == steps[-1][0] and row["t1"] == steps[-1][1]
        assert 2 <= len(steps) <= 5 and isinstance(row["step_converged"], bool) and "band" not in row


def test_single_step_as_the_cli(root, cli, monkeypatch, reversed_record):
    monkeypatch.chdir(root)
    records = [RECORD, str(reversed_record)]
    rows = rocking.t1(records, converge_step=None, **GRID)
    assert without_seconds(rows) == without_seconds(cli("t1", *records, "--json", *GRID_CLI, "--single-step"))
    for row in rows:
        assert row["dt_factor"] == 1.0 and "t1_steps" not in row and "step_converged" not in row
    # converge_halvings is unused without converge_step.
    other = rocking.t1(records, converge_step=None, converge_halvings=7, **GRID)
    assert without_seconds(other) == without_seconds(rows)


@pytest.mark.parametrize(
    "options, cli_options",
    [
        # Converged in the step (the default), the band at the row's step.
        (dict(), ()),
        (dict(converge_step=None), ("--single-step",)),
        (dict(dt_factor=4.0, converge_halvings=3), ("--dt-factor", 4, "--converge-halvings", 3)),
    ],
)
def test_band_as_the_cli(root, cli, monkeypatch, options, cli_options):
    monkeypatch.chdir(root)
    rows = rocking.t1([RECORD], band=True, **options, **GRID)
    assert without_seconds(rows) == without_seconds(cli("t1", RECORD, "--json", *GRID_CLI, "--band", *cli_options))
    row = rows[0]
    assert set(row["band"]) == {"nominal", "half-step", "levels-shifted", "sizes-shifted", "other-locator"}
    assert row["band"]["nominal"] == row["t1"]
    lo, hi = row["t1_range"]
    assert lo <= row["t1"] <= hi == max(row["band"].values()) and row["t1_conservative"] >= hi
    if options.get("converge_step", 0.1) is None:
        assert "t1_steps" not in row and "step_converged" not in row
        assert row["dt_factor"] == options.get("dt_factor", 1.0)
    else:
        # The row is the converged spectrum's, the same as without the band.
        alone = rocking.t1(RECORD, **options, **GRID)
        assert (row["t1_steps"], row["step_converged"], row["dt_factor"], row["t1"]) == (
            alone["t1_steps"], alone["step_converged"], alone["dt_factor"], alone["t1"])
    # The same band from a Record, on one thread.
    one = rocking.t1(rocking.read_record(RECORD), band=True, threads=1, **options, **GRID)
    assert one["file"] is None
    assert {k: one[k] for k in ("band", "t1_range", "t1_conservative", "simulations")} == {
        k: row[k] for k in ("band", "t1_range", "t1_conservative", "simulations")
    }


@pytest.mark.parametrize(
    "options, cli_options",
    [
        # dt x4: t1 moves by 16 % from x4 to x2 and from x2 to x1, and settles at x0.5.
        (dict(dt_factor=4.0, converge_step=0.1, converge_halvings=3),
         ("--dt-factor", 4, "--converge-step", 0.1, "--converge-halvings", 3)),
        # Two halvings are not enough: the finest step's row, not converged.
        (dict(dt_factor=4.0, converge_step=0.1, converge_halvings=2),
         ("--dt-factor", 4, "--converge-step", 0.1, "--converge-halvings", 2)),
        # The default step and halvings, two blocks, two impacts per closing.
        (dict(converge_step=0.0, blocks=2, impacts=2), ("--converge-step", 0, "--blocks", 2, "--impacts", 2)),
    ],
)
def test_converge_step_as_the_cli(root, cli, monkeypatch, reversed_record, options, cli_options):
    monkeypatch.chdir(root)
    records = [RECORD, str(reversed_record)]
    rows = rocking.t1(records, **options, **GRID)
    assert without_seconds(rows) == without_seconds(cli("t1", *records, "--json", *GRID_CLI, *cli_options))
    for row in rows:
        steps = row["t1_steps"]
        assert steps[0][0] == options.get("dt_factor", 1.0) and row["dt_factor"] == steps[-1][0]
        assert row["t1"] == steps[-1][1] and isinstance(row["step_converged"], bool)
        assert 2 <= len(steps) <= options.get("converge_halvings", 4) + 1
        assert "band" not in row
    first = rows[0]
    if options.get("converge_halvings") == 3:
        assert [f for f, _ in first["t1_steps"]] == [4.0, 2.0, 1.0, 0.5] and first["step_converged"]
    if options.get("converge_halvings") == 2:
        assert len(first["t1_steps"]) == 3 and not first["step_converged"]
    # A Record on two threads: the same history.
    two = rocking.t1(rocking.read_record(RECORD), threads=2, **options, **GRID)
    assert (two["t1_steps"], two["step_converged"], two["dt_factor"]) == (
        first["t1_steps"], first["step_converged"], first["dt_factor"])


@pytest.mark.parametrize(
    "options, ends",
    [
        # Two steps that agree, then the band's four other OAS at the row's step.
        (dict(), [8, 8, 8, 7, 8, 8]),
        (dict(converge_step=None), [8, 8, 7, 8, 8]),
    ],
)
def test_progress_counts_the_levels_of_each_spectrum(root, options, ends):
    seen = []
    rocking.t1(root / RECORD, band=True, progress=lambda d, n: seen.append((d, n)), **options, **GRID)
    # One (total, total) per OAS: the grid's 8 levels, one fewer with the levels shifted.
    assert [n for d, n in seen if d == n] == ends


def test_ctrl_c_stops_the_band(root):
    """SIGINT once the first OAS (the step rule's) is done: KeyboardInterrupt (from the callback,
    or from the next spectrum's sweep, which then stops), and no other spectrum finishes."""
    seen = []

    def progress(done, total):
        seen.append((done, total))
        if done == total:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        rocking.t1(root / RECORD, band=True, levels=16, sizes=40, threads=1, progress=progress)
    assert [n for d, n in seen if d == n] == [16]
    assert rocking.t1(root / RECORD, levels=2, sizes=4)["record"] == "synthetic"


@pytest.mark.parametrize(
    "options, detail",
    [
        (dict(converge_step=-0.1), r"^converge_step = -0\.1: "),
        (dict(converge_step=float("nan")), "^converge_step = NaN: "),
        (dict(converge_step=float("inf")), "^converge_step = inf: "),
        (dict(converge_step=0.1, converge_halvings=0), "^converge_halvings = 0: "),
        (dict(converge_step=0.1, converge_halvings=-2), "^converge_halvings = -2: "),
        # Checked without converge_step too (the default converges; None leaves it unused).
        (dict(converge_halvings=0), "^converge_halvings = 0: "),
        (dict(converge_step=None, band=True, converge_halvings=-1), "^converge_halvings = -1: "),
    ],
)
def test_bad_values_name_the_argument(root, options, detail):
    with pytest.raises(rocking.RockingError, match=detail) as e:
        rocking.t1(root / RECORD, levels=2, sizes=2, **options)
    assert e.value.code is None


@pytest.mark.parametrize(
    "options, name",
    [
        (dict(converge_step="0.1"), "^converge_step"),
        (dict(converge_step=True), "^converge_step"),
        (dict(converge_step=0.1, converge_halvings=2.0), "^converge_halvings"),
        (dict(converge_step=0.1, converge_halvings=None), "^converge_halvings"),
    ],
)
def test_type_errors_name_the_argument(root, options, name):
    with pytest.raises(TypeError, match=name):
        rocking.t1(root / RECORD, levels=2, sizes=2, **options)


@pytest.mark.parametrize(
    "options, cli_options",
    [
        (dict(band=True, converge_step=0.1), ("--band", "--converge-step", 0.1)),
        (dict(converge_step=0.1, converge_halvings=2, dt_factor=4.0),
         ("--converge-step", 0.1, "--converge-halvings", 2, "--dt-factor", 4.0)),
        (dict(band=True), ("--band",)),
    ],
)
def test_oas_band_and_converge_step_as_the_cli(root, cli, monkeypatch, options, cli_options):
    """rocking.oas(band=, converge_step=) is `rocking oas --band --converge-step` (wall time
    aside), its attributes the report's; a plain oas has none of them."""
    monkeypatch.chdir(root)
    o = rocking.oas(RECORD, **options, **GRID)
    want = cli("oas", RECORD, "--json", *GRID_CLI, *cli_options)
    got = o.to_dict()
    got["summary"].pop("seconds")
    want["summary"].pop("seconds")
    assert got == want
    assert o.t1_range == want.get("t1_range") and o.t1_steps == want.get("t1_steps")
    assert (o.t1_steps is not None) == ("converge_step" in options)
    assert (o.band is not None) == options.get("band", False)
    plain = rocking.oas(RECORD, **GRID)
    assert plain.t1_range is None and plain.t1_steps is None and "band" not in plain.to_dict()


def test_oas_bad_converge_step_names_it(root):
    with pytest.raises(rocking.RockingError, match=r"^converge_step = -0\.1: "):
        rocking.oas(root / RECORD, converge_step=-0.1, **GRID)
    with pytest.raises(TypeError, match="^converge_step"):
        rocking.oas(root / RECORD, converge_step="0.1", **GRID)


def test_records_from_a_glob_or_an_array(root, tmp_path):
    """Path.glob gives a generator and numpy an array of paths: each was taken for one record
    ("record: expected a rocking.Record or the path of a record file")."""
    import shutil

    for name in ("a.AT2", "b.AT2"):
        shutil.copy(root / "examples/records/synthetic.AT2", tmp_path / name)
    grid = dict(levels=2, sizes=3, converge_step=None)
    want = [r["t1"] for r in rocking.t1(sorted(tmp_path.glob("*.AT2")), **grid)]
    assert len(want) == 2
    assert [r["t1"] for r in rocking.t1(iter(sorted(tmp_path.glob("*.AT2"))), **grid)] == want
    assert [r["t1"] for r in rocking.t1(np.array([str(p) for p in sorted(tmp_path.glob("*.AT2"))]), **grid)] == want
    assert [r["record"] for r in rocking.tp(p for p in sorted(tmp_path.glob("*.AT2")))] == ["a", "b"]
