#!/usr/bin/env python3
"""Convergence of t1 in the time step over a record suite, from `rocking t1 --json --dt-factor F`.

usage: tools/t1_dt_convergence.py [--band 0.10] FACTOR=FILE.json [FACTOR=FILE.json ...]

Each FILE is a list of rows (one per record, as `rocking t1 --json` writes them, several sets may be
joined by giving several files with the same FACTOR). FACTOR is the dt factor relative to the rule
the rows were computed with (e.g. 1, 0.5, 0.25). For every pair of consecutive factors (a, a/2) it
prints the spread max/min - 1 of t1 per record, the records beyond the band, and the largest
spread; the coarsest factor whose spread to its half is within the band on every record is the
converged one. Markdown on stdout.
"""
import json, os, sys
from collections import defaultdict

band = 0.10
args = sys.argv[1:]
if args[:1] == ["--band"]:
    band, args = float(args[1]), args[2:]
rows = defaultdict(dict)  # record -> factor -> row
for a in args:
    f, path = a.split("=", 1)
    for r in json.load(open(path)):
        rows[r["record"]][float(f)] = r
factors = sorted({f for r in rows.values() for f in r}, reverse=True)
recs = sorted(rows)
out = []
w = out.append
w(f"t1 [s] of {len(recs)} records at dt factors {', '.join(f'{f:g}' for f in factors)}; "
  f"spread = max/min - 1 between a factor and its half; band {band:.0%}.\n")
w("| pair | records compared | max spread | record | median spread | beyond the band | records beyond |")
w("|---|---:|---:|---|---:|---:|---|")
for a, b in zip(factors, factors[1:]):
    sp = {}
    for k in recs:
        if a in rows[k] and b in rows[k]:
            x, y = rows[k][a]["t1"], rows[k][b]["t1"]
            sp[k] = max(x, y) / min(x, y) - 1
    if not sp:
        continue
    worst = max(sp, key=sp.get)
    s = sorted(sp.values())
    beyond = sorted((k for k in sp if sp[k] > band), key=lambda k: -sp[k])
    w(f"| {a:g} vs {b:g} | {len(sp)} | {sp[worst]*100:.1f} % | {worst} | {s[len(s)//2]*100:.1f} % | "
      f"{len(beyond)} | {', '.join(f'{k} ({sp[k]*100:.1f} %)' for k in beyond) or '–'} |")
w("")
w("| record | " + " | ".join(f"t1 at x{f:g}" for f in factors) + " | level at f_min | R at f_min [m] |")
w("|---|" + "---:|" * len(factors) + "---:|---:|")
for k in recs:
    r = rows[k]
    finest = r[min(r)]
    w(f"| {k} | " + " | ".join(f"{r[f]['t1']:.4f}" if f in r else "" for f in factors)
      + f" | {finest['level_at_f_min']:.2f} | {finest['size_at_f_min']:.3f} |")
secs = {f: sum(r[f]["seconds"] for r in rows.values() if f in r and "seconds" in r[f]) for f in factors}
w("")
w("Sum of the per-record wall times (the rows' `seconds`, machine shared): "
  + ", ".join(f"x{f:g}: {secs[f]:.0f} s" for f in factors) + ".")
print("\n".join(out))
