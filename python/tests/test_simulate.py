"""rocking.simulate against the CLI: on every bundled scene the events equal events.jsonl, the
summary equals summary.json (wall time aside) and the history equals history.csv to the bit
(tests/golden/scenes holds the CLI's outputs, which `cargo test --test golden` keeps). Then the
dict form of a scene, Pulse and Record objects as excitations, the output options, and the
errors, which name the field."""
import hashlib
import json
import os
import re
import subprocess

import numpy as np
import pytest

import rocking

SCENES = ["two_block_free_rocking", "single_block_half_sine", "three_block_sine_pulse", "column_synthetic_record"]


def golden_events(root, name):
    return [json.loads(line) for line in (root / "tests/golden/scenes" / f"{name}.events.jsonl").read_text().splitlines()]


def golden_summary(root, name):
    # The capture drops the wall-time line, which leaves a trailing comma.
    text = (root / "tests/golden/scenes" / f"{name}.summary.json").read_text()
    return json.loads(re.sub(r",\s*}\s*$", "}", text))


def rust_display(x):
    """Rust's `{}` of an f64 (what history.csv holds): the shortest digits that read back,
    positional, "0" / "-0" for zeros, no trailing ".0"."""
    if x == 0:
        return "-0" if np.signbit(x) else "0"
    return np.format_float_positional(x, unique=True, trim="-")


def history_csv(r):
    n = r.angles.shape[1]
    head = ["t"] + [f"{c}_{k}" for c in ("angle", "rate", "block_rotation", "status") for k in range(n)]
    lines = [",".join(head)]
    for i in range(len(r.t)):
        row = [rust_display(r.t[i])]
        row += [rust_display(v) for a in (r.angles, r.rates, r.block_rotations) for v in a[i]]
        row += [str(int(s)) for s in r.statuses[i]]
        lines.append(",".join(row))
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("name", SCENES)
def test_bundled_scene_as_the_cli(root, name, monkeypatch):
    monkeypatch.chdir(root)  # the CLI's `scene` field is the path as given
    r = rocking.simulate(f"examples/scenes/{name}.json")
    assert r.events == golden_events(root, name)
    summary = dict(r.summary)
    assert summary.pop("wall_time_s") >= 0.0
    assert summary == golden_summary(root, name)
    digest = hashlib.sha256(history_csv(r).encode()).hexdigest()
    assert digest == (root / "tests/golden/scenes" / f"{name}.history.sha256").read_text().strip()


def test_history_arrays(root):
    r = rocking.simulate(root / "examples/scenes/two_block_free_rocking.json")
    n, samples = 2, len(r.t)
    assert r.t.dtype == np.float64 and r.t.shape == (samples,) and samples > 1000
    for a in (r.angles, r.rates, r.block_rotations):
        assert a.shape == (samples, n) and a.dtype == np.float64
    assert r.statuses.shape == (samples, n) and r.statuses.dtype == np.int8
    assert r.dof_angles.shape == r.dof_rates.shape == (samples, 2 * n)
    # The signed interface angle is the sum of the DOF pair; a closed interface has none.
    np.testing.assert_array_equal(r.angles, r.dof_angles[:, :n] + r.dof_angles[:, n:])
    assert np.all(r.angles[r.statuses == 0] == 0.0)
    assert set(np.unique(r.statuses)) <= {-1, 0, 1}
    assert r.block_rotations[0, 1] == pytest.approx(0.153)
    assert np.all(np.diff(r.t) > 0)
    assert r.t_end == 1.5 and not r.overturned and r.stop_reason == "duration"
    assert len(r.events_of("impact")) == r.summary["impacts"] == 23


def test_a_dict_is_the_same_scene(root):
    path = root / "examples/scenes/column_synthetic_record.json"
    from_file = rocking.simulate(path)
    scene = json.loads(path.read_text())
    from_dict = rocking.simulate(scene, base=path.parent)  # the record path is relative to it
    assert from_dict.events == from_file.events
    np.testing.assert_array_equal(from_dict.block_rotations, from_file.block_rotations)
    assert from_dict.summary["scene"] is None and from_file.summary["scene"] == str(path)
    # numpy values in a dict are numbers
    scene["initial_angles"] = np.zeros(3)
    scene["dt"] = np.float64(scene["dt"])
    assert rocking.simulate(scene, base=path.parent).events == from_file.events


def test_record_paths_of_a_dict_start_at_the_cwd(root, monkeypatch):
    scene = json.loads((root / "examples/scenes/column_synthetic_record.json").read_text())
    scene["excitation"]["path"] = "examples/records/synthetic.AT2"
    monkeypatch.chdir(root)
    assert rocking.simulate(scene).events == golden_events(root, "column_synthetic_record")
    monkeypatch.chdir(root / "python")
    with pytest.raises(rocking.RockingError, match="excitation.path"):
        rocking.simulate(scene)


def test_pulse_and_record_objects_as_excitations(root):
    scene = json.loads((root / "examples/scenes/three_block_sine_pulse.json").read_text())
    as_pulse = dict(scene, excitation=rocking.full_sine(-2.467, 0.6))
    assert rocking.simulate(as_pulse).events == golden_events(root, "three_block_sine_pulse")
    path = root / "examples/scenes/column_synthetic_record.json"
    scene = json.loads(path.read_text())
    record = rocking.read_record(root / "examples/records/synthetic.AT2").scaled_to_pga(4.0)
    r = rocking.simulate(dict(scene, excitation=record))
    assert r.events == golden_events(root, "column_synthetic_record")
    assert r.summary["excitation"] == golden_summary(root, "column_synthetic_record")["excitation"]


def test_output_options(root):
    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    full = rocking.simulate(scene)
    every = rocking.simulate(dict(scene, output={"every": 10}))
    assert every.events == full.events
    # every tenth step kept (and the last one)
    assert np.isin(every.t, full.t).all() and len(every.t) == len(full.t[::10]) + 1
    assert every.t[-1] == full.t[-1] == 1.5
    none = rocking.simulate(dict(scene, output={"history": False}))
    assert none.events == full.events
    assert none.t.shape == (0,) and none.angles.shape == (0, 2) and none.statuses.shape == (0, 2)
    # Without events the CLI writes no events.jsonl, and the contact and loop runs return none:
    # the column's run returned them all the same. The summary still counts them.
    quiet = rocking.simulate(dict(scene, output={"events": False}))
    assert quiet.events == [] and quiet.summary["events"] == full.summary["events"]
    assert np.array_equal(quiet.t, full.t)


def test_against_the_cli_binary_on_other_settings(root, tmp_path):
    """A scene with non-default settings (DOP853, Hermite location, the exact velocity terms):
    the same events as the CLI binary, run now."""
    cli = os.environ.get("ROCKING_CLI") or str(root / "target" / "release" / "rocking")
    if not os.path.exists(cli):
        pytest.skip("no rocking CLI (cargo build --release -p rocking-cli) and ROCKING_CLI unset")
    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    scene.update(integrator="dop853", locator="hermite", exact_velocity_terms=True, dt=0.0005, duration=0.6)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    subprocess.run([cli, "simulate", str(path), "--out", str(tmp_path)], check=True, capture_output=True)
    cli_events = [json.loads(line) for line in (tmp_path / "events.jsonl").read_text().splitlines()]
    assert len(cli_events) > 5
    assert rocking.simulate(scene).events == cli_events


@pytest.mark.parametrize(
    "change, field",
    [
        ({"dt": -1}, "dt"),
        ({"colour": 1}, "unknown field `colour`"),
        ({"blocks": [{"width": 0.1, "height": 0.3, "mass": 0}]}, r"blocks\[0\].mass"),
        ({"excitation": {"type": "square"}}, "unknown variant `square`"),
        ({"excitation": {"type": "half_sine", "amplitude": 3, "duration": 0}}, "excitation.duration"),
        ({"impacts": 0}, "impacts"),
        ({"integrator": "euler"}, "integrator"),
        ({"initial_angles": [0.1]}, "initial_angles"),
        ({"duration": float("nan")}, "duration = nan"),
        ({"initial_angles": [0.0, float("inf")]}, r"initial_angles\[1\] = inf"),
    ],
)
def test_errors_name_the_field(root, change, field):
    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    scene.update(change)
    with pytest.raises(rocking.RockingError, match=field):
        rocking.simulate(scene)


@pytest.mark.parametrize(
    "change, message",
    [
        ({"impacts": 2.0}, "impacts: invalid type: floating point `2.0`, expected u32"),
        ({"gravity": "9.81"}, "gravity: invalid type"),
        ({"blocks": [{"width": 0.1, "height": True, "mass": 16}]}, r"blocks\[0\].height: invalid type"),
        ({"integrator": {"type": "wilson", "theta": 1.4, "gamma": 1}}, "integrator: .*no other field"),
        ({"excitation": {"type": "none", "amplitude": 3}}, "excitation: unknown field `amplitude`"),
        ({"excitation": {"type": "record", "path": "examples/records/synthetic.AT2", "units": "m/s2"}},
         "excitation.units: .*in g"),
    ],
)
def test_a_dicts_wrong_value_is_named_by_its_field(root, change, message, monkeypatch):
    """A value of the wrong type in a dict scene names its field, without the line and column of
    the JSON text the package wrote from the dict (which the user never saw)."""
    monkeypatch.chdir(root)
    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    scene.update(change)
    with pytest.raises(rocking.RockingError, match=message) as e:
        rocking.simulate(scene)
    assert "line 1 column" not in str(e.value)


def test_base_with_a_scene_file_is_refused(root):
    """``base`` is where a dict scene's record paths start; with a scene file (whose record paths
    start at the file) it was silently ignored."""
    with pytest.raises(TypeError, match="base"):
        rocking.simulate(root / "examples/scenes/column_synthetic_record.json", base=root)


def test_zero_dimensional_arrays_are_numbers(root):
    """A 0-d numpy array is a number, as a numpy scalar is (it was a TypeError, 'iteration over a
    0-d array', from the NaN check)."""
    scene = json.loads((root / "examples/scenes/two_block_free_rocking.json").read_text())
    scene.update(duration=0.2, friction=0.5, scheme="moreau")
    plain = rocking.simulate(scene)
    scene.update(duration=np.array(0.2), friction=np.array(0.5))
    r = rocking.simulate(scene)
    assert r.summary["stop_reason"] == plain.summary["stop_reason"]
    assert np.array_equal(r.block_rotations, plain.block_rotations) and len(r.t) > 100
    scene.update(friction=np.array(float("nan")))
    with pytest.raises(rocking.RockingError, match="friction = nan"):
        rocking.simulate(scene)


def test_missing_fields_files_and_types(root, tmp_path):
    with pytest.raises(rocking.RockingError, match="missing field `duration`"):
        rocking.simulate({"blocks": [{"width": 0.2, "height": 1, "mass": 1}], "excitation": {"type": "none"},
                          "dt": 0.001})
    with pytest.raises(FileNotFoundError):
        rocking.simulate(tmp_path / "nowhere.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{\"blocks\": [")
    with pytest.raises(rocking.RockingError, match="bad.json"):
        rocking.simulate(bad)
    with pytest.raises(TypeError, match="scene"):
        rocking.simulate(42)
    with pytest.raises(TypeError, match="scene"):
        rocking.simulate({"blocks": object()})


def contact_history_csv(r):
    n = r.block_rotations.shape[1]
    head = ["t"] + [f"{c}_{k}" for c in ("x", "y", "block_rotation", "slip") for k in range(n)]
    lines = [",".join(head)]
    for i in range(len(r.t)):
        row = [rust_display(r.t[i])]
        row += [rust_display(v) for a in (r.x, r.y, r.block_rotations, r.slips) for v in a[i]]
        lines.append(",".join(row))
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("scheme", ["moreau", "auto"])
def test_a_contact_scheme_scene_is_run_as_the_cli(root, tmp_path, scheme):
    """A scene whose joints slide or fly runs the contact scheme (Moreau–Jean, or the automatic
    scheme), as `rocking simulate` does: the same events, summary (wall time aside) and history
    to the bit."""
    cli = os.environ.get("ROCKING_CLI") or str(root / "target" / "release" / "rocking")
    if not os.path.exists(cli):
        pytest.skip("no rocking CLI (cargo build --release -p rocking-cli) and ROCKING_CLI unset")
    scene = json.loads((root / "examples/scenes/drums_sliding_column.json").read_text())
    scene["excitation"]["path"] = str(root / "examples/records/synthetic.AT2")
    scene.update(duration=8.0, scheme=scheme)
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    subprocess.run([cli, "simulate", str(path), "--out", str(tmp_path)], check=True, capture_output=True)
    r = rocking.simulate(path)
    assert isinstance(r, rocking.ContactSimulation) and r.scheme == scheme
    cli_events = [json.loads(line) for line in (tmp_path / "events.jsonl").read_text().splitlines()]
    assert r.events == cli_events
    assert {"impact", "slip_start"} <= {e["kind"] for e in r.events}
    cli_summary = json.loads((tmp_path / "summary.json").read_text())
    summary = dict(r.summary)
    assert summary.pop("wall_time_s") >= 0.0 and cli_summary.pop("wall_time_s") >= 0.0
    assert summary == cli_summary
    assert summary["scheme"] == scheme and summary["t_end"] == 8.0
    assert contact_history_csv(r) == (tmp_path / "history.csv").read_text()
    n, samples = 5, len(r.t)
    for a in (r.x, r.y, r.block_rotations, r.slips):
        assert a.shape == (samples, n) and a.dtype == np.float64
    np.testing.assert_array_equal(r.residual_slip, r.slips[-1])
    assert np.all(r.peak_slip >= np.abs(r.slips).max(axis=0))
    assert r.stop_reason == "duration" and not r.overturned
    # The same scene as a dict, its record path relative to `base`.
    scene["excitation"]["path"] = "examples/records/synthetic.AT2"
    d = rocking.simulate(scene, base=root)
    assert d.events == r.events
    np.testing.assert_array_equal(d.slips, r.slips)


def test_an_arch_and_a_colonnade_run_as_the_cli(root, tmp_path):
    """A closed chain (an arch, a capped colonnade) runs the loop driver as `rocking simulate`
    does: the same events, summary (wall time aside) and joint angles to the bit."""
    cli = os.environ.get("ROCKING_CLI") or str(root / "target" / "release" / "rocking")
    if not os.path.exists(cli):
        pytest.skip("no rocking CLI (cargo build --release -p rocking-cli) and ROCKING_CLI unset")
    colonnade = {"colonnade": {"width": 0.5, "height": 3.0, "column_mass": 1000, "span": 3.0,
                               "beam_height": 0.5, "beam_mass": 2000},
                 "excitation": {"type": "half_sine", "amplitude": 4.0, "duration": 0.6},
                 "duration": 3.0, "dt": 0.001}
    (tmp_path / "colonnade.json").write_text(json.dumps(colonnade))
    for i, path in enumerate([root / "examples/scenes/arch_half_sine.json", tmp_path / "colonnade.json"]):
        out = tmp_path / f"out{i}"
        subprocess.run([cli, "simulate", str(path), "--out", str(out)], check=True, capture_output=True)
        r = rocking.simulate(path)
        assert isinstance(r, rocking.LoopSimulation) and r.scheme == "loop"
        assert r.events == [json.loads(line) for line in (out / "events.jsonl").read_text().splitlines()]
        cli_summary = json.loads((out / "summary.json").read_text())
        summary = dict(r.summary)
        assert summary.pop("wall_time_s") >= 0.0 and cli_summary.pop("wall_time_s") >= 0.0
        assert summary == cli_summary
        lines = ["t," + ",".join(f"angle_{k}" for k in range(r.angles.shape[1]))]
        lines += [",".join(rust_display(v) for v in [t, *row]) for t, row in zip(r.t, r.angles)]
        assert "\n".join(lines) + "\n" == (out / "history.csv").read_text()
        assert r.collapsed and r.t_end < 3.0 and len(r.events_of("collapsed")) == 1
        assert r.hinges and all(face in (-1, 1) for _, face in r.hinges)
        # The energy balance closes to the scheme's error (docs/arches.md, "Energy balance").
        e = summary["energy"]
        terms = [e["ground_work"], e["dissipated"], e["kinetic_end"], e["potential_change"]]
        assert e["residual"] == pytest.approx(e["ground_work"] - e["dissipated"] - e["kinetic_end"]
                                              + e["kinetic_start"] - e["potential_change"], abs=1e-9)
        assert abs(e["residual"]) < 1e-4 * max(abs(x) for x in terms)
    # The arch's first mechanism (docs/arches.md 2c): joints 3, 15, 9, 20 open first.
    arch = rocking.simulate(root / "examples/scenes/arch_half_sine.json")
    first = arch.events_of("opening")[0]
    assert {k for k, s in enumerate(first["statuses"]) if s != 0} == {3, 9, 15, 20}
    assert arch.angles.shape[1] == 21


def test_a_scene_file_saved_with_a_byte_order_mark(root, tmp_path):
    """Windows editors write a UTF-8 byte-order mark first: refused as `expected value at line 1
    column 1`. It runs as the same scene, and rocking.opensees reads it too."""
    text = (root / "examples/scenes/single_block_half_sine.json").read_text()
    (tmp_path / "marked.json").write_bytes(b"\xef\xbb\xbf" + text.encode())
    (tmp_path / "plain.json").write_text(text)
    assert rocking.simulate(tmp_path / "marked.json").events == rocking.simulate(tmp_path / "plain.json").events
    from rocking import opensees

    assert opensees.load_scene(tmp_path / "marked.json")[0] == json.loads(text)


@pytest.mark.parametrize("scheme", ["moreau", "auto", "loop"])
def test_ctrl_c_stops_a_long_run_promptly(root, scheme):
    """Ctrl-C (here ``_thread.interrupt_main`` from another thread) interrupts a run midway with
    KeyboardInterrupt: thirty drums through the synthetic record take tens of seconds, and Ctrl-C
    waited for the end (the GIL released, the signal was seen only when the run returned); so
    did an arch (the loop driver) at a fine step."""
    import _thread
    import threading
    import time

    record = {"type": "record", "path": "examples/records/synthetic.AT2"}
    if scheme == "loop":
        scene = {"arch": {"radius": 5.0, "thickness": 0.75, "embrace_angle": 180,
                          "voussoirs": 20},
                 "excitation": record, "duration": 20.0, "dt": 0.00001,
                 "output": {"history": False, "events": False}}
    else:
        scene = {"blocks": [{"width": 1.0, "height": 1.0, "mass": 2500}] * 30, "impacts": 2,
                 "excitation": dict(record, scale_to_pga=4.0),
                 "duration": 20.0, "dt": 0.001, "scheme": scheme, "friction": 0.6,
                 "on_sliding": "slide", "on_tension": "fly"}
    sent = []

    def interrupter():
        time.sleep(0.5)
        sent.append(time.monotonic())
        _thread.interrupt_main()

    t = threading.Thread(target=interrupter)
    t.start()
    started = time.monotonic()
    try:
        with pytest.raises(KeyboardInterrupt):
            rocking.simulate(scene, base=root)
            for _ in range(600):  # a run that ended before the signal: wait for it here
                time.sleep(0.1)
        returned = time.monotonic()
    finally:
        t.join()
    assert sent and returned - sent[0] < 5.0, f"{returned - sent[0]:.1f} s after the signal"
    assert returned - started < 10.0
