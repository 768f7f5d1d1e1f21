"""The same scene through the rigid driver, and the event-by-event comparison."""
import copy
import json
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import rocking

from ._analysis import load_scene


def find_cli(cli=None):
    """The ``rocking`` command line: ``cli``, ``$ROCKING_CLI``, or ``rocking`` on the PATH; None
    when there is none (the package's own driver is the same library)."""
    if cli is not None and not Path(cli).exists():
        raise FileNotFoundError(f"cli: {cli} does not exist (build it: cargo build --release -p rocking-cli)")
    for candidate in [cli, os.environ.get("ROCKING_CLI"), shutil.which("rocking")]:
        if candidate and Path(candidate).exists():
            return str(candidate)
    return None


def rigid_driver_events(scene, duration=None, cli=None):
    """The rigid driver's events (the CLI's events.jsonl) on the same scene, with the exact
    Lagrangian velocity terms (``exact_velocity_terms``: OpenSees's corotational blocks integrate
    them; thesis Eq. 6 drops them, docs/opensees.md §5): from the ``rocking`` command line
    (``cli``, ``$ROCKING_CLI`` or the PATH) if there is one, else from :func:`rocking.simulate`
    (the same driver and events)."""
    spec, base = load_scene(scene)
    spec = copy.deepcopy(spec)
    spec["exact_velocity_terms"] = True
    if duration is not None:
        spec["duration"] = duration
    exc = spec.get("excitation", {})
    if isinstance(exc, rocking.Pulse):
        spec["excitation"] = exc.to_dict()
    elif isinstance(exc, dict) and exc.get("type") == "record" and not Path(exc["path"]).is_absolute():
        exc["path"] = str(base / exc["path"])
    spec.setdefault("output", {})["history"] = False
    # A Record object has no file for the command line: the package's driver runs it.
    path = None if isinstance(exc, rocking.Record) else find_cli(cli)
    if path is None:
        return rocking.simulate(spec).events
    with tempfile.TemporaryDirectory() as tmp:
        scene_file = Path(tmp) / "scene.json"
        scene_file.write_text(json.dumps(spec))
        subprocess.run([path, "simulate", str(scene_file), "--out", tmp], check=True, capture_output=True, text=True)
        return [json.loads(line) for line in (Path(tmp) / "events.jsonl").read_text().splitlines() if line.strip()]


def compare_events(opensees, rigid):
    """Pairs the opening and impact events in order: for each, whether kind, interface and the
    configuration after agree, and the time difference (OpenSees − driver, s)."""
    a = [e for e in opensees if e["kind"] in ("opening", "impact")]
    b = [e for e in rigid if e["kind"] in ("opening", "impact")]
    out = []
    for i, e in enumerate(a):
        if i >= len(b):
            out.append({"index": i, "kind": e["kind"], "t": e["t"], "same": False, "driver": None, "dt": None})
            continue
        x = b[i]
        same = (e["kind"], e["interface"], list(e["statuses_after"])) == (x["kind"], x["interface"], list(x["statuses_after"]))
        out.append({"index": i, "kind": e["kind"], "interface": e["interface"], "t": e["t"], "driver_t": x["t"],
                    "dt": e["t"] - x["t"], "same": same,
                    "driver": {"kind": x["kind"], "interface": x["interface"], "statuses_after": x["statuses_after"]}})
    return out
