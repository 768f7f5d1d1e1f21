#!/usr/bin/python3
"""Side by side: the library's drum scheme (`examples/drum_column.rs`) and Siconos
(`drums_siconos.py`) on the same columns and records, in one run (so the wall-time ratio is
measured under the same load). Prints a Markdown table and writes `results.json` here.

    cargo build --release --example drum_column
    /usr/bin/python3 bench/siconos/compare.py [--quick]

`--quick` runs the first 10 s of each record (the full cases take tens of minutes in Siconos);
`--cases 0,2` runs only those rows of CASES.
"""

import json
import os
import subprocess
import sys

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


def run(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main():
    quick = "--quick" in sys.argv
    cases = CASES
    if "--cases" in sys.argv:
        cases = [CASES[int(i)] for i in sys.argv[sys.argv.index("--cases") + 1].split(",")]
    dt = 1e-3
    rows = []
    for n, w, h, rec, pga, mu in cases:
        path = os.path.join(FAR, rec + ".AT2")
        args = ["--drums", str(n), "--width", str(w), "--height", str(h), "--record", path,
                "--pga", str(pga), "--mu", str(mu), "--dt", str(dt)]
        if quick:
            args += ["--duration", "10"]
        ours = run([OURS] + args)
        peer = run([sys.executable, os.path.join(HERE, "drums_siconos.py")] + args)
        rows.append({"case": [n, w, h, rec, pga, mu], "rocking": ours, "siconos": peer})
        print(f"{n} x {w}x{h} {rec} {pga} m/s² mu {mu}: rocking {ours['wall_s']:.3f} s, "
              f"siconos {peer['wall_s']:.1f} s", file=sys.stderr)
    with open(os.path.join(HERE, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print("| column | record, PGA, μ | code | verdict | peak rotation (rad) | top displacement (m) "
          "| residual slip (m) | peak slip (m) | wall time (s) | ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        n, w, h, rec, pga, mu = r["case"]
        for code in ("rocking", "siconos"):
            d = r[code]
            verdict = "overturned" if d["overturned"] else "stands"
            ratio = r["siconos"]["wall_s"] / max(r["rocking"]["wall_s"], 1e-9)
            print(f"| {n} × {w} × {h} | {rec} {pga} m/s², μ {mu} | {code} | {verdict} "
                  f"(t = {d['t_end']:.2f} s) | {d['peak_rotation']:.4f} | "
                  f"{d['peak_top_displacement']:.4f} | {d['residual_slip']:.2e} | "
                  f"{d['peak_slip']:.2e} | {d['wall_s']:.3f} | "
                  f"{'' if code == 'rocking' else f'{ratio:.0f}×'} |")


if __name__ == "__main__":
    main()
