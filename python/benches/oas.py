#!/usr/bin/env python3
"""rocking.oas from Python against `rocking oas` (the CLI) on the bundled record.

Usage (in a virtualenv with the package installed, the CLI built with cargo build --release):

    python python/benches/oas.py [--rounds 3] [--threads 1] [--levels 80] [--sizes 120] [--cli PATH]

Each round runs the CLI (`rocking oas RECORD --json --threads T`, a subprocess) and then the same
OAS from Python (`rocking.oas(RECORD, threads=T)`), so that a busy machine slows both alike.
Prints per round and as the best and the median of the rounds: the wall time of the whole call
(the CLI's process: start, read, sweep, JSON out; Python: the call) and the sweep's own time
(`summary.seconds`, which both measure around the sweep), and the ratio Python / CLI. Checks
first that both give the same JSON (wall times aside).
"""
import argparse
import json
import os
import statistics
import subprocess
import time
from pathlib import Path

import rocking

ROOT = Path(__file__).resolve().parents[2]
RECORD = ROOT / "examples" / "records" / "synthetic.AT2"


def without_seconds(d):
    d = json.loads(json.dumps(d))
    d["summary"].pop("seconds")
    return d


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--levels", type=int, default=80)
    ap.add_argument("--sizes", type=int, default=120)
    ap.add_argument("--cli", default=os.environ.get("ROCKING_CLI") or str(ROOT / "target" / "release" / "rocking"))
    a = ap.parse_args()
    cmd = [a.cli, "oas", str(RECORD), "--json", "--threads", str(a.threads), "--levels", str(a.levels),
           "--sizes", str(a.sizes)]
    print(f"record {RECORD.name}, {a.levels} levels x {a.sizes} sizes, {a.threads} thread(s), "
          f"{a.rounds} rounds, load average {os.getloadavg()[0]:.1f}")
    rows = []
    for i in range(a.rounds):
        t0 = time.perf_counter()
        out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
        cli_wall = time.perf_counter() - t0
        cli = json.loads(out)
        t0 = time.perf_counter()
        py = rocking.oas(RECORD, threads=a.threads, levels=a.levels, sizes=a.sizes)
        py_wall = time.perf_counter() - t0
        if i == 0 and without_seconds(py.to_dict()) != without_seconds(cli):
            raise SystemExit("the Python OAS differs from the CLI's")
        rows.append((cli_wall, cli["summary"]["seconds"], py_wall, py.summary["seconds"]))
        print(f"round {i + 1}: CLI {cli_wall:.2f} s (sweep {rows[-1][1]:.2f} s), "
              f"Python {py_wall:.2f} s (sweep {rows[-1][3]:.2f} s), ratio {py_wall / cli_wall:.3f}")
    for name, f in (("best", min), ("median", statistics.median)):
        cw, cs, pw, ps = (f(r[j] for r in rows) for j in range(4))
        print(f"{name}: CLI {cw:.2f} s (sweep {cs:.2f} s), Python {pw:.2f} s (sweep {ps:.2f} s); "
              f"Python / CLI: call {pw / cw:.3f}, sweep {ps / cs:.3f}")
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
