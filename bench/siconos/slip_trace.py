#!/usr/bin/python3
"""The top joint's slip of the bundled sliding column, step by step, in the library and in
Siconos: is the back-and-forth of a few millimetres that `docs/multidrum.md` ("Slip measure")
reports physics of the model or an artefact of the library's scheme or of its slip measure?

Both codes are measured the same way, from the drums' centres and rotations: the offset of drum
k's centre from drum k − 1's along drum k − 1's face direction, `s_k = (c_k − c_{k−1})·e1_{k−1}`
(minus its value at rest, 0), which equals the joint's slip whenever the joint is closed and does
not depend on which contact end the library measures at.

    /usr/bin/python3 bench/siconos/slip_trace.py [--duration 10] [--dt 0.001] [--joint 4]
        [--rocking target/release/rocking] [--csv OUT.csv]

Runs `rocking simulate` on `examples/scenes/drums_sliding_column.json` (its own `impacts: 2`,
and a copy with `impacts: 1`, Siconos' law) and the Siconos peer (`drums_siconos.py`: plain
Moreau–Jean, Newton impact e = 0, 2D Coulomb) on the same column, record and scale, and prints
the offset of the joint every 0.01 s where either code moves it, and its plateaus between the
column's side changes.
"""

import csv
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)


def opt(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


def offsets_library(history, n, h):
    """Per row: t, rotation of the top drum, and the centre offsets s_k of every joint k ≥ 1."""
    rows = []
    with open(history) as f:
        for r in csv.DictReader(f):
            x = [float(r[f"x_{k}"]) for k in range(n)]
            y = [float(r[f"y_{k}"]) + (k + 0.5) * h for k in range(n)]
            th = [float(r[f"block_rotation_{k}"]) for k in range(n)]
            s = [0.0]
            for k in range(1, n):
                c, si = math.cos(th[k - 1]), math.sin(th[k - 1])
                s.append((x[k] - x[k - 1]) * c + (y[k] - y[k - 1]) * si)
            rows.append((float(r["t"]), th[-1], s))
    return rows


def run_library(binary, scene, impacts, duration, dt, tmp):
    s = dict(scene)
    s.update({"impacts": impacts, "duration": duration, "dt": dt})
    s["excitation"] = dict(scene["excitation"])
    s["excitation"]["path"] = os.path.join(ROOT, "examples", "records", "synthetic.AT2")
    path = os.path.join(tmp, f"scene_{impacts}.json")
    with open(path, "w") as f:
        json.dump(s, f)
    out = os.path.join(tmp, f"out_{impacts}")
    subprocess.run([binary, "simulate", path, "--out", out], check=True, capture_output=True)
    return os.path.join(out, "history.csv")


def run_siconos(n, w, h, pga, mu, duration, dt):
    import numpy as np

    import drums_siconos as ds

    rdt, acc = ds.read_at2(os.path.join(ROOT, "examples", "records", "synthetic.AT2"))
    acc = acc * (pga / np.abs(acc).max())

    def ground(t):
        x = t / rdt
        i = int(math.floor(x))
        if x < 0 or i + 1 >= len(acc):
            return 0.0
        return acc[i] + (x - i) * (acc[i + 1] - acc[i])

    rows = []
    every = max(1, round(1e-3 / dt))

    def trace(t, drums):
        if round(t / dt) % every:
            return
        q = [d.q() for d in drums]
        s = [0.0]
        for k in range(1, n):
            c, si = math.cos(q[k - 1][2]), math.sin(q[k - 1][2])
            s.append((q[k][0] - q[k - 1][0]) * c + (q[k][1] - q[k - 1][1]) * si)
        rows.append((t, q[-1][2], s))

    summary = ds.simulate(n, w, h, ground, duration, mu, dt, trace=trace)
    return rows, summary


def plateaus(rows, joint, threshold=1e-4):
    """The offset's values where it stays within 1e-5 m for at least 0.05 s."""
    out = []
    start = 0
    for i in range(1, len(rows) + 1):
        if i == len(rows) or abs(rows[i][2][joint] - rows[start][2][joint]) > 1e-5:
            if rows[i - 1][0] - rows[start][0] >= 0.05:
                out.append((rows[start][0], rows[i - 1][0], rows[start][2][joint]))
            start = i
    return out


def main():
    duration = float(opt("--duration", 10.0))
    dt = float(opt("--dt", 0.001))
    binary = opt("--rocking", os.path.join(ROOT, "target", "release", "rocking"))
    with open(os.path.join(ROOT, "examples", "scenes", "drums_sliding_column.json")) as f:
        scene = json.load(f)
    n = len(scene["blocks"])
    w, h = scene["blocks"][0]["width"], scene["blocks"][0]["height"]
    joint = int(opt("--joint", n - 1))
    pga, mu = scene["excitation"]["scale_to_pga"], scene["friction"]
    with tempfile.TemporaryDirectory() as tmp:
        lib = {k: offsets_library(run_library(binary, scene, k, duration, dt, tmp), n, h)
               for k in (2, 1)}
    sic, summary = run_siconos(n, w, h, pga, mu, duration, dt)
    print(f"{n} drums {w} x {h} m, synthetic record at {pga} m/s², mu {mu}, dt {dt}, "
          f"{duration} s; offset s_{joint} of drum {joint} on drum {joint - 1} (mm)")
    print(f"Siconos: peak rotation {summary['peak_rotation']:.5f} rad, residual slips (mm) "
          + ", ".join(f"{1e3 * s:.3f}" for s in summary["residual_slips"]))
    for name, rows in [("rocking, impacts 2", lib[2]), ("rocking, impacts 1", lib[1]),
                       ("Siconos", sic)]:
        print(f"\n{name}: plateaus of s_{joint} (from, to, mm), and the top drum's rotation "
              "at their start")
        by_t = {round(r[0], 6): r for r in rows}
        for a, b, v in plateaus(rows, joint):
            print(f"  {a:7.3f} – {b:7.3f} s  {1e3 * v:8.3f}  (rotation "
                  f"{by_t[round(a, 6)][1]:+.4f})")
    if "--csv" in sys.argv:
        with open(opt("--csv", ""), "w", newline="") as f:
            wr = csv.writer(f)
            wr.writerow(["code", "t", "top_rotation", f"offset_{joint}"])
            for name, rows in [("rocking2", lib[2]), ("rocking1", lib[1]), ("siconos", sic)]:
                for t, th, s in rows:
                    wr.writerow([name, f"{t:.6f}", f"{th:.6e}", f"{s[joint]:.6e}"])


if __name__ == "__main__":
    main()
