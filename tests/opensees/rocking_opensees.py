#!/usr/bin/env python3
"""Real OpenSees (openseespy) integrates rocking columns; the rocking library decides the openings and
impacts, through the package's coupling module rocking.opensees (this script is a thin user of it).

Usage: rocking_opensees.py HARNESS_EXE EXACT_EVENTS_JSONL
Run by tests/opensees/run.sh inside its virtualenv (openseespy and the rocking package installed).
Exits 0 when every check passes.

The OpenSees model and the coupling are described in rocking.opensees (python/rocking/opensees/)
and docs/opensees.md. Two scenes: a single block released at 0.15 rad (harness scene a), checked
against Housner's ratio and the C harness (c_examples/opensees_style_harness.c); the thesis 4.2
two-block column (harness scene c), checked against the C harness (thesis Eq. 6) and the Rust
driver with the exact velocity terms (which OpenSees's corotational blocks integrate too).
"""
import json
import subprocess
import sys
import time
from pathlib import Path

import rocking.opensees

SINGLE_BLOCK = {
    "title": "harness scene a: single block 0.2 x 0.6 m, 100 kg, released at 0.15 rad",
    "blocks": [{"width": 0.2, "height": 0.6, "mass": 100.0, "contact_width": 0.2}],
    "initial_angles": [0.15],
    "excitation": {"type": "none"},
    "impacts": 1, "duration": 1.85, "dt": 1e-4,
}

TWO_BLOCKS = {
    "title": "harness scene c: thesis 4.2, two granite blocks, the upper one released at -0.153 rad",
    "blocks": [{"width": 0.1, "height": 0.3, "mass": 2700.0 * 0.1 * 0.3 * 0.2, "contact_width": 0.096}] * 2,
    "initial_angles": [0.0, -0.153],
    "excitation": {"type": "none"},
    "impacts": 2, "duration": 0.33, "dt": 1e-4,
}


def run_scene(scene, max_events):
    """The module's events in the form of the checks below."""
    result = rocking.opensees.run(scene, max_events=max_events)
    events = [dict(e, before=e["statuses_before"], after=e["statuses_after"], v0=e.get("rate_before"),
                   v1=e.get("rate_after")) for e in result["events"]]
    return events, result["summary"]["peak_block_rotation"]


def harness_results(exe):
    out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
    scenes = {}
    for line in out.splitlines():
        if line.startswith("EVENT ") or line.startswith("RESULT "):
            f = dict(w.split("=", 1) for w in line.split()[1:])
            s = scenes.setdefault(f["scene"], {"events": []})
            if line.startswith("EVENT "):
                s["events"].append(dict(kind=f["kind"], t=float(f["t"]), interface=int(f["interface"]),
                                        after=[int(x) for x in f["after"].split(",")]))
            else:
                s["peak"] = [float(x) for x in f["peak"].split(",")]
    return scenes


def main():
    harness = harness_results(Path(sys.argv[1]))
    failures = 0

    def check(name, ok, detail):
        nonlocal failures
        print(f"  {'ok ' if ok else 'FAIL'} {name}: {detail}")
        failures += 0 if ok else 1

    # ---- single block 0.2 x 0.6 m, 100 kg, released at 0.15 rad (harness scene a) ----
    t0 = time.time()
    b, hh = 0.1, 0.3
    mu = (2 * hh * hh - b * b) / (2 * hh * hh + 2 * b * b)
    events, peak = run_scene(SINGLE_BLOCK, 8)
    print(f"single block: {len(events)} impacts in {time.time() - t0:.1f} s")
    ref = [e for e in harness["a"]["events"] if e["kind"] == "impact"]
    for i, e in enumerate(events):
        print(f"  impact {i + 1}: t = {e['t']:.5f} s (harness {ref[i]['t']:.5f}), {e['before']} -> {e['after']}, "
              f"rate {e['v0']:+.5f} -> {e['v1']:+.5f} rad/s, ratio {e['v1'] / e['v0']:.6f}")
    for i, e in enumerate(events):
        check(f"impact {i + 1} velocity ratio = Housner mu {mu:.4f}", abs(e["v1"] / e["v0"] - mu) < 1e-4,
              f"{e['v1'] / e['v0']:.6f}")
        # OpenSees's own dynamics between impacts: the rate arriving at impact i+1 over the rate
        # arriving at impact i is Housner's ratio again (energy conserved between impacts)
        if i + 1 < len(events):
            r = events[i + 1]["v0"] / e["v0"]
            check(f"impact {i + 1}->{i + 2} OpenSees arrival-rate ratio = -mu", abs(r + mu) < 2e-3 * mu, f"{r:.6f}")
        check(f"impact {i + 1} time vs C harness", abs(e["t"] - ref[i]["t"]) < 2e-3, f"{e['t']:.5f} vs {ref[i]['t']:.5f}")
        check(f"impact {i + 1} configuration vs C harness", e["after"] == ref[i]["after"], f"{e['after']}")
    check("8 impacts", len(events) == 8, f"{len(events)}")
    check("peak rotation = release angle", abs(peak[0] - 0.15) < 1e-3 * 0.15, f"{peak[0]:.6f}")

    # ---- thesis 4.2 two-block column (harness scene c), first events ----
    t0 = time.time()
    events, peak = run_scene(TWO_BLOCKS, 5)
    print(f"two blocks: {len(events)} events in {time.time() - t0:.1f} s")
    ref = harness["c"]["events"]
    for i, e in enumerate(events):
        extra = f", library opening choice {e['library']}" if e["kind"] == "opening" else ""
        print(f"  {e['kind']:8s} t = {e['t']:.5f} s (harness {ref[i]['kind']} {ref[i]['t']:.5f}), interface {e['interface']}, "
              f"{e['before']} -> {e['after']}{extra}")
    for i, e in enumerate(events):
        same = (e["kind"], e["interface"], e["after"]) == (ref[i]["kind"], ref[i]["interface"], ref[i]["after"])
        check(f"event {i + 1} as the C harness", same, f"{e['kind']} {e['interface']} {e['after']}")
        if e["kind"] == "opening":
            check(f"event {i + 1}: the library opens what OpenSees opened", e["library"] == e["after"], f"{e['library']}")
    # Times against the C harness (thesis Eq. 6). The opening's onset in the penalty model is found
    # late: the corner must lift by 1e-6 m to be told from the springs' ringing, and is back-dated
    # to its last compression, which the ringing itself delays (measured: 3.1 ms late). The next
    # two impacts follow within 2 ms. Events 4, 5 (the upper block rocking on the rocking lower
    # one) are 12-14 ms later in OpenSees than in Eq. 6, which drops the velocity terms: they are
    # compared with the exact Lagrangian equations below instead.
    for i, tol in [(0, 5e-3), (1, 2e-3), (2, 2e-3)]:
        e = events[i] if i < len(events) else {"t": float("nan")}
        check(f"event {i + 1} time vs C harness (within {tol * 1e3:.0f} ms)", abs(e["t"] - ref[i]["t"]) <= tol,
              f"{e['t']:.5f} vs {ref[i]['t']:.5f}")
    # Against the Rust driver with the exact velocity terms (OpenSees's corotational blocks have
    # them): every event, impacts within 2 ms (measured 0.03-0.7 ms), the opening within 5 ms
    # (measured 3.1 ms early: the onset of a lift in the penalty model is not sharp).
    exact = [json.loads(line) for line in Path(sys.argv[2]).read_text().splitlines() if line.strip()]
    exact = [e for e in exact if e["kind"] in ("opening", "impact")]
    for i, e in enumerate(events):
        x = exact[i] if i < len(exact) else {"kind": "?", "t": float("nan"), "interface": -1, "statuses_after": []}
        after = x["statuses_after"]  # -1 / 0 / 1 as here
        tol = 5e-3 if e["kind"] == "opening" else 2e-3
        same = (e["kind"], e["interface"], e["after"]) == (x["kind"], x["interface"], after)
        check(f"event {i + 1} as the exact-terms driver", same, f"{x['kind']} {x['interface']} {after}")
        check(f"event {i + 1} time vs exact-terms driver (within {tol * 1e3:.0f} ms)", abs(e["t"] - x["t"]) <= tol,
              f"{e['t']:.5f} vs {x['t']:.5f} ({(e['t'] - x['t']) * 1e3:+.2f} ms)")
    check("5 events", len(events) == 5, f"{len(events)}")
    print(f"{'FAILED' if failures else 'OpenSees agrees'} ({failures} failures)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
