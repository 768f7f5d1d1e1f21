#!/usr/bin/python3
"""Side by side: the library's drum scheme (`examples/drum_column.rs`) and Siconos
(`drums_siconos.py`) on the same columns and records, in one run (so the wall-time ratio is
measured under the same load). Prints a Markdown table and writes `results.json` here.

    cargo build --release --example drum_column
    /usr/bin/python3 bench/siconos/compare.py [--quick] [--cases 0,2] [--dt 0.001,0.0005]
        [--out FILE] [--impacts 1] [--only rocking|siconos] [--plain] [--rocking-args '…']
        [--siconos-args '--linearise mid']

`--quick` runs the first 10 s of each record (the full cases take tens of minutes in Siconos);
`--cases 0,2` runs only those rows of CASES;
`--dt 0.001,0.0005,0.00025` runs every case at each of these steps (default 0.001), both codes at
  the same step, one process at a time (the dt-halving study: `convergence.py` reads the output);
`--out FILE` writes the results there instead of `results.json` (rewritten after every run, so
  an interrupted sweep keeps what it measured);
`--impacts N` is passed to the library (`n_impacts`; 1, the default, is Siconos' law: one
  Newton impact with e = 0 at every closed corner at once);
`--only CODE` runs one code (e.g. to re-run the library alone at the steps of a stored sweep);
`--plain` runs the library as plain Moreau–Jean, the peer's scheme (`drum_column --locate 0
  --persistent 0 --projection 0`: no impact location, restitution zero also at persistent
  contacts, no position projection), to separate the scheme's differences from the codes';
`--rocking-args '--locate 0'` passes any other of these switches to the library (recorded with
  the run as `rocking_scheme`);
`--siconos-args '--linearise mid'` passes options to the peer (`drums_siconos.py`; `--linearise
  mid`: gaps linearised at the step's predicted midpoint, as the library does, instead of at its
  start), recorded as `siconos_scheme`.

Each run records its wall time (`wall_s`, printed by the program itself, the time loop only) and
the CPU time of the whole process (`cpu_s`, user + system, as `/usr/bin/time` reports it).
"""

import json
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
FAR = os.path.join(ROOT, "..", "shared", "records", "fema-p695", "farfield")
OURS = os.path.join(ROOT, "target", "release", "examples", "drum_column")

# (drums, width, height, record, pga, mu)
CASES = [
    (3, 1.0, 1.0, "RSN953_NORTHR_MUL009", 4.0, 0.5),
    (5, 1.0, 2.0, "RSN953_NORTHR_MUL009", 4.0, 0.5),
    (10, 1.0, 1.0, "RSN953_NORTHR_MUL009", 4.0, 0.5),
    (10, 1.5, 1.0, "RSN1111_KOBE_NIS000", 4.0, 0.7),
    (5, 1.0, 0.5, "RSN1111_KOBE_NIS000", 6.0, 0.5),
    (20, 1.5, 1.0, "RSN953_NORTHR_MUL009", 4.0, 0.5),
]


def opt(name, default):
    return sys.argv[sys.argv.index(name) + 1] if name in sys.argv else default


def run(cmd):
    """Runs one program; its JSON line plus the process's CPU time and wall time."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.time()
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    wall = time.time() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    d = json.loads(out.stdout.strip().splitlines()[-1])
    d["cpu_s"] = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    d["process_wall_s"] = wall
    d["load_avg"] = os.getloadavg()[0]
    return d


def main():
    quick = "--quick" in sys.argv
    cases = CASES
    if "--cases" in sys.argv:
        cases = [CASES[int(i)] for i in opt("--cases", "").split(",")]
    dts = [float(x) for x in opt("--dt", "0.001").split(",")]
    out_path = opt("--out", os.path.join(HERE, "results.json"))
    impacts = opt("--impacts", "1")
    only = opt("--only", None)
    plain = opt("--rocking-args", "").split()
    if "--plain" in sys.argv:
        plain = ["--locate", "0", "--persistent", "0", "--projection", "0"]
    peer = opt("--siconos-args", "").split()
    scheme = "default"
    if plain:
        scheme = "plain" if "--plain" in sys.argv else " ".join(plain)
    rows = []
    for n, w, h, rec, pga, mu in cases:
        for dt in dts:
            path = os.path.join(FAR, rec + ".AT2")
            args = ["--drums", str(n), "--width", str(w), "--height", str(h), "--record", path,
                    "--pga", str(pga), "--mu", str(mu), "--dt", repr(dt)]
            if quick:
                args += ["--duration", "10"]
            row = {"case": [n, w, h, rec, pga, mu], "dt": dt, "duration": 10 if quick else None,
                   "rocking_scheme": scheme, "impacts": int(impacts),
                   "siconos_scheme": " ".join(peer) or "default"}
            if only in (None, "rocking"):
                row["rocking"] = run([OURS] + args + ["--impacts", impacts] + plain)
            if only in (None, "siconos"):
                row["siconos"] = run([sys.executable, os.path.join(HERE, "drums_siconos.py")]
                                     + args + peer)
            rows.append(row)
            with open(out_path, "w") as f:
                json.dump(rows, f, indent=1)
            print(f"{n} x {w}x{h} {rec} {pga} m/s² mu {mu} dt {dt}: "
                  + ", ".join(f"{c} {row[c]['wall_s']:.3f} s (cpu {row[c]['cpu_s']:.2f} s)"
                              for c in ("rocking", "siconos") if c in row), file=sys.stderr)
    print("| column | record, PGA, μ | dt (ms) | code | verdict | peak rotation (rad) "
          "| top displacement (m) | residual slip (m) | peak slip (m) | wall time (s) "
          "| CPU (s) | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        n, w, h, rec, pga, mu = r["case"]
        for code in ("rocking", "siconos"):
            if code not in r:
                continue
            d = r[code]
            verdict = "overturned" if d["overturned"] else "stands"
            ratio = ""
            if code == "siconos" and "rocking" in r:
                ratio = f"{r['siconos']['cpu_s'] / max(r['rocking']['cpu_s'], 1e-9):.0f}×"
            print(f"| {n} × {w} × {h} | {rec} {pga} m/s², μ {mu} | {r['dt'] * 1e3:g} | {code} "
                  f"| {verdict} (t = {d['t_end']:.2f} s) | {d['peak_rotation']:.4f} | "
                  f"{d['peak_top_displacement']:.4f} | {d['residual_slip']:.2e} | "
                  f"{d['peak_slip']:.2e} | {d['wall_s']:.3f} | {d['cpu_s']:.2f} | {ratio} |")


if __name__ == "__main__":
    main()
