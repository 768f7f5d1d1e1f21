"""rocking.t1's band and converge_step against the CLI: the rows equal `rocking t1 --json` with
`--band` and `--converge-step TOL --converge-halvings N` (wall times aside) on small grids of the
bundled record, for any number of threads; Ctrl-C stops them; bad values name the argument."""
import json
import os
import signal

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


def test_band_as_the_cli(root, cli, monkeypatch):
    monkeypatch.chdir(root)
    rows = rocking.t1([RECORD], band=True, **GRID)
    assert without_seconds(rows) == without_seconds(cli("t1", RECORD, "--json", *GRID_CLI, "--band"))
    row = rows[0]
    assert set(row["band"]) == {"nominal", "half-step", "levels-shifted", "sizes-shifted", "other-locator"}
    assert row["band"]["nominal"] == row["t1"]
    lo, hi = row["t1_range"]
    assert lo <= row["t1"] <= hi == max(row["band"].values()) and row["t1_conservative"] >= hi
    assert "t1_steps" not in row and "step_converged" not in row
    # The same band from a Record, on one thread.
    one = rocking.t1(rocking.read_record(RECORD), band=True, threads=1, **GRID)
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


def test_progress_counts_the_levels_of_each_spectrum(root):
    seen = []
    rocking.t1(root / RECORD, band=True, progress=lambda d, n: seen.append((d, n)), **GRID)
    # One (total, total) per OAS: the nominal grid's 8 levels, one fewer with the levels shifted.
    ends = [n for d, n in seen if d == n]
    assert ends == [8, 8, 7, 8, 8]


def test_ctrl_c_stops_the_band(root):
    """SIGINT once the nominal OAS is done: KeyboardInterrupt (from the callback, or from the next
    spectrum's sweep, which then stops), and no other spectrum finishes."""
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
        (dict(band=True, converge_step=0.1), "^band and converge_step: "),
        (dict(converge_step=-0.1), r"^converge_step = -0\.1: "),
        (dict(converge_step=float("nan")), "^converge_step = NaN: "),
        (dict(converge_step=float("inf")), "^converge_step = inf: "),
        (dict(converge_step=0.1, converge_halvings=0), "^converge_halvings = 0: "),
        (dict(converge_step=0.1, converge_halvings=-2), "^converge_halvings = -2: "),
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
