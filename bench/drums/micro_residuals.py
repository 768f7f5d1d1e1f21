#!/usr/bin/env python3
"""The runs of a drum-suite CSV that barely rock (peak below 1e-3 rad) and whose relative energy
residual exceeds 1e-3: each is rerun as a `rocking simulate` scene (the bench's case: 2500 kg/m³
drums, `impacts: 2`, dt 1 ms, to the end of the record, sliding and flight allowed) and its
absolute residual is split into its terms and expressed as a height, residual / weight.

    micro_residuals.py SUITE.csv ROCKING_BINARY RECORDS_DIR WORK_DIR [--consistent] [--energy-tol TOL]

e.g. `bench/drums/micro_residuals.py bench/drums/consistent_sweeps_suite.csv
target/release/rocking ../shared/records/fema-p695/farfield /tmp/micro --consistent`
(docs/energy-control.md, "The micro-rocking runs"). Stdlib only.
"""

import argparse
import csv
import json
import os
import statistics
import subprocess

G = 9.81


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("suite")
    ap.add_argument("rocking")
    ap.add_argument("records")
    ap.add_argument("work")
    ap.add_argument("--consistent", action="store_true", help="energy_consistent scenes")
    ap.add_argument("--energy-tol", type=float, default=None,
                    help="the scheme's error control (energy_tolerance) in the scenes")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    rows = [r for r in csv.DictReader(open(a.suite))
            if float(r["peak_rotation"]) < 1e-3 and abs(float(r["energy_error"])) > 1e-3]
    out = []
    for i, r in enumerate(rows):
        n, w, h = int(r["drums"]), float(r["w"]), float(r["h"])
        m = 2500 * w * h
        scene = {
            "title": f"{n} drums {w} x {h} m, {r['record']} at {r['pga']} m/s², mu {r['mu']}",
            "blocks": [{"width": w, "height": h, "mass": m}] * n,
            "excitation": {"type": "record", "path": os.path.abspath(
                os.path.join(a.records, r["record"] + ".AT2")),
                "scale_to_pga": float(r["pga"])},
            "impacts": 2, "dt": float(r["dt"]), "duration": float(r["duration"]),
            "friction": float(r["mu"]), "on_sliding": "slide", "on_tension": "fly",
            "scheme": "moreau", "energy_consistent": a.consistent,
        }
        if a.energy_tol is not None:
            scene["energy_tolerance"] = a.energy_tol
        path = os.path.join(a.work, f"scene{i}.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        outdir = os.path.join(a.work, f"out{i}")
        before = os.times()
        subprocess.run([a.rocking, "simulate", path, "--out", outdir], check=True,
                       capture_output=True)
        after = os.times()
        with open(os.path.join(outdir, "summary.json")) as f:
            e = json.load(f)["energy"]
        out.append({
            "row": r, "residual": abs(e["residual"]), "height": abs(e["residual"]) / (n * m * G),
            "projection_share": abs(e["projection"]) / abs(e["residual"]) if e["residual"] else 1.0,
            "same": f"{e['relative_residual']:.3e}" == f"{float(r['energy_error']):.3e}",
            "scale": abs(e["residual"] / e["relative_residual"]) if e["relative_residual"] else 0.0,
            "relative": abs(e["relative_residual"]),
            "cpu": after.children_user - before.children_user,
        })
    if not out:
        print("no run of the CSV barely rocks with a relative residual above 1e-3")
        return
    med = lambda k: statistics.median(x[k] for x in out)
    big = lambda k: max(x[k] for x in out)
    print(f"{len(out)} runs (peak < 1e-3 rad, |relative residual| > 1e-3); the scene's relative "
          f"residual equals the CSV's in {sum(x['same'] for x in out)}")
    print(f"largest peak rotation among them: {max(float(x['row']['peak_rotation']) for x in out)} rad")
    print(f"energy scale (J):          median {med('scale'):.2e}, largest {big('scale'):.2e}")
    print(f"|residual| (J):            median {med('residual'):.2e}, largest {big('residual'):.2e}")
    print(f"|residual| / weight (m):   median {med('height'):.2e}, largest {big('height'):.2e}")
    print(f"projection work / residual: smallest {min(x['projection_share'] for x in out):.6f}")
    print(f"relative residual of these scenes: median {med('relative'):.2e}, largest "
          f"{big('relative'):.2e}, above 1e-3: {sum(x['relative'] > 1e-3 for x in out)}")
    print(f"user CPU of the {len(out)} simulations: {sum(x['cpu'] for x in out):.2f} s")


if __name__ == "__main__":
    main()
