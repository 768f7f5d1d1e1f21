"""rocking.opensees: OpenSees (openseespy) integrates, the library decides. On the single block and
the bundled two-block scene, `python -m rocking.opensees SCENE --compare` against the rigid driver
(the CLI with the exact velocity terms, which OpenSees's corotational blocks integrate too): the
same events and configurations, impacts within 2 ms and openings within 5 ms (the tolerances of
tests/opensees, docs/opensees.md §5). Runs where openseespy is installed (tests/opensees/run.sh);
elsewhere only the import checks run."""
import importlib.util
import json
import math
import os
import subprocess
import sys

import pytest

import rocking
import rocking.opensees

HAVE_OPENSEES = importlib.util.find_spec("openseespy") is not None
needs_opensees = pytest.mark.skipif(not HAVE_OPENSEES, reason="openseespy not installed (tests/opensees/run.sh has it)")

SINGLE_BLOCK = {
    "title": "single block 0.2 x 0.6 m, 100 kg, released at 0.15 rad about its left corner",
    "blocks": [{"width": 0.2, "height": 0.6, "mass": 100.0}],
    "initial_angles": [0.15],
    "excitation": {"type": "none"},
    "impacts": 1, "duration": 1.2, "dt": 1e-4,
}


@pytest.fixture(scope="module")
def cli(root):
    path = os.environ.get("ROCKING_CLI") or str(root / "target" / "release" / "rocking")
    if not os.path.exists(path):
        pytest.skip("no rocking CLI (cargo build --release -p rocking-cli) and ROCKING_CLI unset")
    return path


def run_module(scene, cli, *extra):
    out = subprocess.run([sys.executable, "-m", "rocking.opensees", str(scene), "--compare", "--cli", cli, *extra],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)  # one JSON object on standard output, nothing else


def check_against_driver(result, n_events):
    compare = result["compare"]
    assert len(compare) == n_events, compare
    for c in compare:
        assert c["same"], c
        tol = 5e-3 if c["kind"] == "opening" else 2e-3
        assert abs(c["dt"]) <= tol, c


def test_import_without_openseespy():
    import rocking.opensees  # never needs openseespy to import

    assert callable(rocking.opensees.run)
    if not HAVE_OPENSEES:
        with pytest.raises(ImportError, match=r"pip install"):
            rocking.opensees.load_openseespy()


@needs_opensees
def test_single_block_against_the_rigid_driver(cli, tmp_path):
    scene = tmp_path / "single.json"
    scene.write_text(json.dumps(SINGLE_BLOCK))
    result = run_module(scene, cli)
    impacts = [e for e in result["events"] if e["kind"] == "impact"]
    assert len(impacts) == 4 and result["summary"]["events"]["impact"] == 4
    b, h = 0.1, 0.3
    mu = (2 * h * h - b * b) / (2 * h * h + 2 * b * b)  # Housner, thesis Eq. 1
    for e in impacts:
        assert e["rate_after"] / e["rate_before"] == pytest.approx(mu, abs=1e-4)
        assert e["report"]["impacts_applied"] == 1
    check_against_driver(result, 4)
    assert result["summary"]["peak_block_rotation"][0] == pytest.approx(0.15, rel=1e-3)


@needs_opensees
def test_bundled_two_block_scene_against_the_rigid_driver(cli, root):
    result = run_module(root / "examples" / "scenes" / "two_block_free_rocking.json", cli, "--duration", "0.33")
    kinds = [e["kind"] for e in result["events"]]
    assert kinds == ["opening", "impact", "impact", "impact", "impact"], kinds
    opening = result["events"][0]
    assert opening["agrees"] and opening["library"] == opening["statuses_after"]
    check_against_driver(result, 5)


@needs_opensees
def test_ground_motion_with_stiff_blocks_against_the_rigid_driver(cli, root):
    """The bundled half-sine scene (1 x 4 m, 10 t) with blocks stiff enough for their size
    (first mode 255 Hz; the default section gives 3 Hz and a late opening, docs/opensees.md §5):
    the opening within 5 ms of the driver and static tipping within 2 ms."""
    path = root / "examples" / "scenes" / "single_block_half_sine.json"
    result = run_module(path, cli, "--duration", "1.0", "--block-stiffness", "2e14")
    check_against_driver(result, 1)
    tipped = [e for e in result["events"] if e["kind"] == "overturned"]
    rigid = rocking.simulate(dict(json.loads(path.read_text()), exact_velocity_terms=True))
    assert len(tipped) == 1 and rigid.stop_reason == "overturned"
    assert abs(tipped[0]["t"] - rigid.t_end) <= 2e-3, (tipped[0]["t"], rigid.t_end)


def test_a_scene_with_an_at2_record_gives_its_excitation(root):
    """The bundled record scene (an .AT2, in g, no units given): the excitation is the record
    scaled to the scene's PGA (it was read with units "m/s2", which an .AT2 refuses)."""
    scenes = root / "examples" / "scenes"
    spec, base = rocking.opensees.load_scene(scenes / "column_synthetic_record.json")
    record = rocking.opensees.excitation_of(spec["excitation"], base)
    expected = rocking.read_record(root / "examples" / "records" / "synthetic.AT2")
    assert record.dt == expected.dt and len(record) == len(expected)
    assert record.pga == pytest.approx(spec["excitation"]["scale_to_pga"], rel=1e-12)


def no_cli(monkeypatch, tmp_path):
    """An environment without the rocking command line: ROCKING_CLI unset, nothing on the PATH."""
    monkeypatch.delenv("ROCKING_CLI", raising=False)
    monkeypatch.setenv("PATH", str(tmp_path))


def test_the_rigid_driver_without_a_command_line_is_the_package_own(monkeypatch, tmp_path):
    """README's `python -m rocking.opensees ... --compare` needed the CLI on the PATH (a
    FileNotFoundError after the OpenSees run): without one the rigid driver is rocking.simulate,
    the same driver, with the exact velocity terms."""
    no_cli(monkeypatch, tmp_path)
    events = rocking.opensees.rigid_driver_events(SINGLE_BLOCK, duration=0.5)
    rigid = rocking.simulate(dict(SINGLE_BLOCK, duration=0.5, exact_velocity_terms=True))
    assert [e["kind"] for e in events] == [e["kind"] for e in rigid.events] and len(events) >= 1
    assert [e["t"] for e in events] == [e["t"] for e in rigid.events]


def test_the_rigid_driver_from_the_command_line_gives_the_same_events(cli):
    from_cli = rocking.opensees.rigid_driver_events(SINGLE_BLOCK, duration=0.5, cli=cli)
    own = rocking.opensees.rigid_driver_events(SINGLE_BLOCK, duration=0.5, cli=None)
    assert [(e["kind"], e["interface"], e["t"]) for e in from_cli] == [(e["kind"], e["interface"], e["t"]) for e in own]


def test_a_cli_that_does_not_exist_is_refused_before_the_run(tmp_path):
    out = subprocess.run([sys.executable, "-m", "rocking.opensees", str(tmp_path / "missing.json"), "--compare",
                          "--cli", str(tmp_path / "no-such-rocking")], capture_output=True, text=True)
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert "cli: " in out.stderr and "no-such-rocking" in out.stderr


def test_a_missing_scene_is_an_error_message_not_a_traceback(tmp_path):
    out = subprocess.run([sys.executable, "-m", "rocking.opensees", str(tmp_path / "missing.json")],
                         capture_output=True, text=True)
    assert out.returncode == 2 and "Traceback" not in out.stderr and "missing.json" in out.stderr


@needs_opensees
def test_the_readme_command_runs_without_a_command_line(root, monkeypatch, tmp_path):
    no_cli(monkeypatch, tmp_path)
    out = subprocess.run([sys.executable, "-m", "rocking.opensees", "examples/scenes/two_block_free_rocking.json",
                          "--duration", "0.33", "--compare"], capture_output=True, text=True, cwd=root, check=True)
    check_against_driver(json.loads(out.stdout), 5)


def scene_file(root, name):
    return root / "examples" / "scenes" / name


@pytest.mark.parametrize("name, says", [("arch_half_sine.json", "closed chain"),
                                        ("drums_sliding_column.json", "contact scheme")])
def test_scenes_it_does_not_model_are_refused(root, name, says):
    """An arch failed with KeyError: 'blocks'; drums that slide and fly ran as rocking blocks
    (friction and sliding ignored)."""
    with pytest.raises(rocking.RockingError, match=says):
        rocking.opensees.run(scene_file(root, name))


@pytest.mark.parametrize("change, says", [
    (dict(gravity=3.71), "gravity = 3.71"),
    (dict(durations=1.0), "unknown field `durations`"),
    (dict(blocks=[{"width": 1.0, "height": 0.3, "mass": 100.0}]), r"blocks\[0\]: inertia"),
    (dict(blocks=[{"width": -0.2, "height": 0.6, "mass": 100.0}]), r"blocks\[0\].width"),
])
def test_a_scene_is_checked_by_the_library_before_the_model_is_built(change, says):
    with pytest.raises(rocking.RockingError, match=says):
        rocking.opensees.run(dict(SINGLE_BLOCK, **change))


@pytest.mark.parametrize("option, value", [("dt", 0.0), ("dt", -1e-4), ("dt", math.nan), ("duration", -1.0),
                                           ("block_stiffness", -2e10), ("k_contact", 0.0), ("max_events", -1),
                                           ("settle", -1e-6), ("solver", "fastest")])
def test_run_options_out_of_range_are_refused(option, value):
    """dt = 0 fell back to the default silently; a negative dt stepped 1e-9 s at a time for ever."""
    with pytest.raises(rocking.RockingError, match=f"{option} = "):
        rocking.opensees.run(SINGLE_BLOCK, **{option: value})


@needs_opensees
def test_the_bundled_two_block_scene_runs_to_its_end(root):
    """Its whole 1.5 s: the upper block's rocking dies out in ever smaller impacts, and a corner
    that went through the contact and back within a step (rate away from closure) made the impact
    model refuse the state, killing the run at 0.47 s. It closes at rest now (``settled``, the
    library deciding), as the rigid driver's upper interface settles, and the lower block rocks on
    with the driver's impacts."""
    path = scene_file(root, "two_block_free_rocking.json")
    result = rocking.opensees.run(path)
    assert result["summary"]["t_end"] == pytest.approx(1.5)
    rigid = rocking.opensees.rigid_driver_events(path)
    settled = [e for e in result["events"] if e["kind"] == "settled"]
    driver_settled = [e for e in rigid if e["kind"] == "settled"]
    assert [(e["interface"], e["statuses_after"]) for e in settled] == \
        [(e["interface"], e["statuses_after"]) for e in driver_settled] == [(1, [-1, 0])]
    after = [e for e in result["events"] if e["t"] > settled[0]["t"]]
    driver_after = [e for e in rigid if e["t"] > driver_settled[0]["t"]]
    assert [(e["kind"], e["interface"], e["statuses_after"]) for e in after] == \
        [(e["kind"], e["interface"], e["statuses_after"]) for e in driver_after]
    # The settling comes 6.6 ms before the driver's; the later impacts drift by 0.9, 5.8 and
    # 10.3 ms (measured), within 1 % of their times.
    assert len(after) == 3 and all(a["t"] == pytest.approx(b["t"], rel=1e-2) for a, b in zip(after, driver_after))


def test_a_file_that_is_not_json_is_named(root):
    """It said `Expecting value: line 1 column 1 (char 0)`, naming no file."""
    out = subprocess.run([sys.executable, "-m", "rocking.opensees", "README.md"], capture_output=True, text=True,
                         cwd=root)
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert "README.md: not a JSON scene" in out.stderr, out.stderr


def test_a_dict_scene_may_hold_pulse_and_record_objects(root, cli):
    """rocking.simulate takes them in a dict; rocking.opensees failed with AttributeError:
    'rocking.Pulse' object has no attribute 'get'. Each gives the events of its dict form."""
    record = rocking.read_record(root / "examples/records/synthetic.AT2")
    path = str(root / "examples/records/synthetic.AT2")
    base = {"blocks": [{"width": 0.4, "height": 1.2, "mass": 500.0}], "duration": 10.0, "dt": 0.001}
    for obj, as_dict in [(rocking.half_sine(6.0, 0.8), {"type": "half_sine", "amplitude": 6.0, "duration": 0.8}),
                         (record.scaled_to_pga(6.0), {"type": "record", "path": path, "scale_to_pga": 6.0})]:
        got = rocking.opensees.rigid_driver_events(dict(base, excitation=obj), cli=cli)
        want = rocking.opensees.rigid_driver_events(dict(base, excitation=as_dict), cli=cli)
        assert len(want) >= 1 and [(e["kind"], e["t"]) for e in got] == [(e["kind"], e["t"]) for e in want]
        assert rocking.opensees.excitation_of(obj, root) is obj


@needs_opensees
def test_run_takes_a_pulse_object(root):
    scene = dict(json.loads(scene_file(root, "single_block_half_sine.json").read_text()), duration=0.2)
    as_dict = rocking.opensees.run(scene)
    as_object = rocking.opensees.run(dict(scene, excitation=rocking.half_sine(6.0, 0.8)))
    assert as_object["events"] == as_dict["events"] and as_object["summary"]["t_end"] == as_dict["summary"]["t_end"]


@needs_opensees
def test_settle_zero_turns_the_energy_rule_off():
    result = rocking.opensees.run(SINGLE_BLOCK, settle=0.0, duration=0.05)
    assert result["summary"]["t_end"] == pytest.approx(0.05)


@needs_opensees
@pytest.mark.parametrize("blocks, angles, says", [
    # the driver overturns it at its first step
    ([(0.202, 0.59, 88.6), (0.138, 0.793, 377.3), (0.379, 0.611, 491.5)], [0.117, 0.0, 0.0],
     "past static tipping at interface 0"),
    # the reaction test fails at interfaces 0 and 1; the driver's opening model opens 1 at t = 0
    ([(0.135, 0.892, 398.9), (0.412, 0.694, 232.4), (0.329, 0.448, 495.0)], [0.0, 0.0, -0.105],
     r"closed interface\(s\) \[0, 1\] must open"),
])
def test_a_column_that_does_not_stand_as_tilted_is_named(blocks, angles, says):
    """The analysis starts from static equilibrium, which these do not have: they failed with
    RuntimeError: OpenSees: the static gravity step failed, saying no more (found by random
    columns, 2 of 396; the columns whose static step succeeds run as before)."""
    scene = dict(SINGLE_BLOCK, blocks=[{"width": w, "height": h, "mass": m} for w, h, m in blocks],
                 initial_angles=angles)
    with pytest.raises(rocking.RockingError, match=f"initial_angles: .*{says}"):
        rocking.opensees.run(scene)
