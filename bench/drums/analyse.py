#!/usr/bin/env python3
"""Figures of the drum suite from the CSVs of `rocking bench drums --csv` (stdlib only).

    analyse.py full_*.csv                  the suite: how runs end, energy, peaks, slips, CPU
    analyse.py --halve halve_*.csv         dt-halving: the runs at dt against dt / 2
    analyse.py --merge all.csv full_*.csv  also write the merged CSV (rows sorted by case)

A CSV's run times (`cpu_s`) are each run's wall clock; where `X.time` lies beside `X.csv`
(the output of `/usr/bin/time -v -o X.time rocking bench drums ... --csv X.csv`), the user
CPU time of the processes is summed too.

Quantiles are taken as `rocking bench drums` takes them: sorted[round((n - 1) p)].
"""

import argparse
import csv
import os
import sys
from collections import defaultdict

G = 9.81
ROCKING = 0.01  # rad: a run "rocks" when its peak rotation reaches this


def quantile(values, p):
    v = sorted(values)
    if not v:
        return float("nan")
    return v[round((len(v) - 1) * p)]


def read(paths):
    rows = []
    header = None
    for p in paths:
        with open(p, newline="") as f:
            r = csv.DictReader(f)
            if header is None:
                header = r.fieldnames
            elif r.fieldnames != header:
                sys.exit(f"{p}: columns differ from the first file's")
            for row in r:
                for k in ("drums", "impacts", "slip_starts", "lift_offs", "fallbacks"):
                    row[k] = int(row[k])
                for k in ("w", "h", "pga", "mu", "dt", "t_end", "duration", "peak_rotation",
                          "peak_top", "residual_slip", "peak_slip", "energy_error", "closure",
                          "cpu_s"):
                    row[k] = float(row[k])
                row["overturned"] = row["overturned"] == "true"
                rows.append(row)
    return header, rows


def key(r):
    return (r["record"], r["drums"], r["w"], r["h"], r["pga"], r["mu"])


def shape(r):
    return f"{r['w']:g} × {r['h']:g}"


def case(r):
    return (f"{r['drums']} drums {shape(r)}, {r['record']}, {r['pga']:g} m/s², μ {r['mu']:g}")


def ends(rows):
    c = defaultdict(int)
    for r in rows:
        c[r["stop"]] += 1
    return c


def other(rows):
    return sum(1 for r in rows if r["stop"] not in ("end of record", "overturned"))


def stats(values):
    return (f"median {quantile(values, 0.5):.1e}, 90 % {quantile(values, 0.9):.1e}, "
            f"max {quantile(values, 1.0):.1e}")


def suite(rows):
    out = []
    p = out.append
    dts = sorted({r["dt"] for r in rows})
    records = {r["record"] for r in rows}
    keys = {key(r) for r in rows}
    p(f"{len(rows)} runs ({len(keys)} distinct cases, {len(records)} records, dt {dts})")
    if len(keys) != len(rows):
        p(f"WARNING: {len(rows) - len(keys)} duplicated cases")
    p("")
    p("## How the runs end")
    p("")
    for k, v in sorted(ends(rows).items()):
        p(f"- {k}: {v}")
    p(f"- anything but end of record / overturned: {other(rows)}")
    p(f"- overturned flag set: {sum(r['overturned'] for r in rows)}")
    p("")
    p("### By drums × shape")
    p("")
    p("| drums | w × h | runs | overturned | end of record | other | max peak rotation "
      "(rad) | max residual slip (m) | median energy residual | run time summed (s) |")
    p("|---|---|---|---|---|---|---|---|---|---|")
    groups = defaultdict(list)
    for r in rows:
        groups[(r["drums"], r["w"], r["h"])].append(r)
    for (n, w, h), rs in sorted(groups.items()):
        e = ends(rs)
        p(f"| {n} | {w:g} × {h:g} | {len(rs)} | {e['overturned']} | {e['end of record']} | "
          f"{other(rs)} | {max(r['peak_rotation'] for r in rs):.3f} | "
          f"{max(r['residual_slip'] for r in rs):.4f} | "
          f"{quantile([abs(r['energy_error']) for r in rs], 0.5):.1e} | "
          f"{sum(r['cpu_s'] for r in rs):.1f} |")
    p("")
    p("### By PGA and μ")
    p("")
    p("| PGA (m/s²) | μ | runs | overturned | end of record | other |")
    p("|---|---|---|---|---|---|")
    groups = defaultdict(list)
    for r in rows:
        groups[(r["pga"], r["mu"])].append(r)
    for (a, mu), rs in sorted(groups.items()):
        e = ends(rs)
        p(f"| {a:g} | {mu:g} | {len(rs)} | {e['overturned']} | {e['end of record']} | "
          f"{other(rs)} |")
    p("")
    p("### Overturned by drums (columns: PGA 2, 4, 6 m/s²; μ 0.5 / 0.7)")
    p("")
    groups = defaultdict(int)
    for r in rows:
        groups[(r["drums"], r["pga"], r["mu"])] += r["stop"] == "overturned"
    pgas = sorted({r["pga"] for r in rows})
    mus = sorted({r["mu"] for r in rows})
    for n in sorted({r["drums"] for r in rows}):
        cells = ", ".join(
            f"{a:g}: " + " / ".join(str(groups[(n, a, mu)]) for mu in mus) for a in pgas)
        p(f"- {n} drums: {cells}")
    p("")
    p("## Energy residual (|residual()| / scale())")
    p("")
    e_all = [abs(r["energy_error"]) for r in rows]
    p(f"- all runs ({len(rows)}): {stats(e_all)}, above 1e-3: "
      f"{sum(x > 1e-3 for x in e_all)}")
    bands = [
        (f"peak ≥ {ROCKING} rad (rocking)", lambda r: r["peak_rotation"] >= ROCKING),
        ("peak 0.001–0.01 rad", lambda r: 1e-3 <= r["peak_rotation"] < ROCKING),
        ("peak < 0.001 rad (micro-rocking)", lambda r: r["peak_rotation"] < 1e-3),
    ]
    for name, f in bands:
        e = [abs(r["energy_error"]) for r in rows if f(r)]
        p(f"- {name} ({len(e)}): {stats(e)}, above 1e-3: {sum(x > 1e-3 for x in e)}")
    for n in sorted({r["drums"] for r in rows}):
        e = [abs(r["energy_error"]) for r in rows
             if r["drums"] == n and r["peak_rotation"] >= ROCKING]
        if e:
            p(f"  - {n} drums, rocking ({len(e)}): {stats(e)}, above 1e-3: "
              f"{sum(x > 1e-3 for x in e)}")
    rock = [r for r in rows if r["peak_rotation"] >= ROCKING]
    if rock:
        w = max(rock, key=lambda r: abs(r["energy_error"]))
        p(f"- largest among rocking runs: {w['energy_error']:.3e} ({case(w)}, {w['stop']}, "
          f"peak {w['peak_rotation']:.4f} rad)")
    w = max(rows, key=lambda r: abs(r["energy_error"]))
    p(f"- largest overall: {w['energy_error']:.3e} ({case(w)}, peak "
      f"{w['peak_rotation']:.2e} rad)")
    p(f"- closure (the identity with the scheme's own terms): largest "
      f"{max(abs(r['closure']) for r in rows):.1e}")
    p("")
    p("## Peaks and slips")
    p("")
    stood = [r for r in rows if not r["overturned"]]
    for label, rs in (("all runs", rows), ("runs that stood", stood)):
        if rs:
            w = max(rs, key=lambda r: r["peak_rotation"])
            p(f"- largest peak rotation, {label}: {w['peak_rotation']:.4f} rad ({case(w)})")
    for col in ("residual_slip", "peak_slip", "peak_top"):
        w = max(rows, key=lambda r: r[col])
        p(f"- largest {col}: {w[col]:.4f} m ({case(w)}, {w['stop']})")
    big = [r for r in stood if r["residual_slip"] > 0.01]
    p(f"- runs that stood with a residual slip above 1 cm: {len(big)}; above 1 mm: "
      f"{sum(r['residual_slip'] > 1e-3 for r in stood)}")
    p("")
    p("## Sliding below μg (PGA < μ g; a run slides if it has a slip_start event)")
    p("")
    groups = defaultdict(list)
    for r in rows:
        if r["pga"] < r["mu"] * G:
            groups[(r["mu"], r["pga"])].append(r)
    for (mu, a), rs in sorted(groups.items()):
        slid = sum(r["slip_starts"] > 0 for r in rs)
        p(f"- μ {mu:g} (μg = {mu * G:.2f} m/s²), PGA {a:g}: {slid} of {len(rs)} slide; "
          f"peak slip > 1 mm: {sum(r['peak_slip'] > 1e-3 for r in rs)}; "
          f"> 1 cm: {sum(r['peak_slip'] > 1e-2 for r in rs)}")
    p("")
    p("## Events and solver")
    p("")
    p(f"- impacts {sum(r['impacts'] for r in rows)}, slip starts "
      f"{sum(r['slip_starts'] for r in rows)}, lift-offs {sum(r['lift_offs'] for r in rows)}")
    w = max(rows, key=lambda r: r["fallbacks"])
    p(f"- contact problems that needed a fallback: {sum(r['fallbacks'] for r in rows)} "
      f"(most in one run: {w['fallbacks']}, {case(w)})")
    p("")
    p("## Run time (each run's own wall clock, summed; under load it exceeds CPU time)")
    p("")
    cpu = sum(r["cpu_s"] for r in rows)
    p(f"- total {cpu:.1f} s over {len(rows)} runs")
    for n in sorted({r["drums"] for r in rows}):
        c = sum(r["cpu_s"] for r in rows if r["drums"] == n)
        p(f"  - {n} drums: {c:.1f} s ({100 * c / cpu:.0f} %)")
    w = max(rows, key=lambda r: r["cpu_s"])
    p(f"- slowest run: {w['cpu_s']:.2f} s ({case(w)})")
    return out


def user_time(paths):
    """Summed user CPU time of the `X.time` files beside the CSVs, and how many were found."""
    total, found = 0.0, 0
    for p in paths:
        t = os.path.splitext(p)[0] + ".time"
        if os.path.exists(t):
            with open(t) as f:
                for line in f:
                    if line.strip().startswith("User time (seconds):"):
                        total += float(line.split(":")[1])
                        found += 1
    return total, found


def rel(a, b, floor=1e-3):
    return abs(a - b) / max(abs(b), floor)


def halving(rows):
    out = []
    p = out.append
    dts = sorted({r["dt"] for r in rows}, reverse=True)
    if len(dts) != 2:
        sys.exit(f"--halve needs runs at two steps, found {dts}")
    by = defaultdict(dict)
    for r in rows:
        by[key(r)][r["dt"]] = r
    pairs = [(v[dts[0]], v[dts[1]]) for v in by.values() if len(v) == 2]
    pairs.sort(key=lambda ab: key(ab[0]))
    p(f"{len(pairs)} cases at dt = {dts[0]:g} s (a) and {dts[1]:g} s (b)")
    p("")
    same = [ab for ab in pairs if ab[0]["overturned"] == ab[1]["overturned"]]
    p(f"- verdicts (overturned or not) agree in {len(same)} of {len(pairs)}; "
      f"how runs end at b: {dict(sorted(ends([b for _, b in pairs]).items()))}")
    oa = sum(a["overturned"] for a, _ in pairs)
    ob = sum(b["overturned"] for _, b in pairs)
    flips = sum(a["overturned"] and not b["overturned"] for a, b in pairs)
    p(f"  - overturned at a: {oa}, at b: {ob}; a overturned and b stood: {flips}, "
      f"a stood and b overturned: {len(pairs) - len(same) - flips}")
    for a, b in pairs:
        if a["overturned"] != b["overturned"]:
            p(f"  - differs: {case(a)}: a {a['stop']} (peak {a['peak_rotation']:.4f}), "
              f"b {b['stop']} (peak {b['peak_rotation']:.4f})")
    both = [ab for ab in pairs if not ab[0]["overturned"] and not ab[1]["overturned"]]
    pk = [rel(a["peak_rotation"], b["peak_rotation"]) for a, b in both]
    p(f"- stood in both ({len(both)}): peak rotation relative change (floor 1e-3 rad) "
      f"median {quantile(pk, 0.5):.3f}, 90 % {quantile(pk, 0.9):.3f}, max {quantile(pk, 1):.3f}")
    rk = [ab for ab in both if max(ab[0]["peak_rotation"], ab[1]["peak_rotation"]) >= ROCKING]
    pk = [rel(a["peak_rotation"], b["peak_rotation"]) for a, b in rk]
    if rk:
        p(f"  - of them rocking (peak ≥ {ROCKING} rad at a or b, {len(rk)}): median "
          f"{quantile(pk, 0.5):.3f}, 90 % {quantile(pk, 0.9):.3f}, max {quantile(pk, 1):.3f}")
    if both:
        qa = [a["peak_rotation"] for a, _ in both]
        qb = [b["peak_rotation"] for _, b in both]
        p("  - the distribution of the peaks (stood in both) at a / b: " + ", ".join(
            f"{int(100 * q)} % {quantile(qa, q):.4f} / {quantile(qb, q):.4f}"
            for q in (0.5, 0.75, 0.9, 0.99)))
    for n in sorted({a["drums"] for a, _ in both}):
        sub = [(a, b) for a, b in both if a["drums"] == n]
        pk = [rel(a["peak_rotation"], b["peak_rotation"]) for a, b in sub]
        sk = [abs(a["residual_slip"] - b["residual_slip"]) for a, b in sub]
        p(f"  - {n} drums ({len(sub)}): peak change median {quantile(pk, 0.5):.3f}, 90 % "
          f"{quantile(pk, 0.9):.3f}, max {quantile(pk, 1):.3f}; residual slip change (m) "
          f"median {quantile(sk, 0.5):.1e}, 90 % {quantile(sk, 0.9):.1e}, max "
          f"{quantile(sk, 1):.1e}")
    if both:
        a, b = max(both, key=lambda ab: rel(ab[0]["peak_rotation"], ab[1]["peak_rotation"]))
        p(f"  - largest peak change: {case(a)}: {a['peak_rotation']:.4f} → "
          f"{b['peak_rotation']:.4f} rad")
        sk = [abs(a["residual_slip"] - b["residual_slip"]) for a, b in both]
        p(f"- residual slip change (m), stood in both: median {quantile(sk, 0.5):.1e}, 90 % "
          f"{quantile(sk, 0.9):.1e}, max {quantile(sk, 1):.1e}")
        a, b = max(both, key=lambda ab: abs(ab[0]["residual_slip"] - ab[1]["residual_slip"]))
        p(f"  - largest: {case(a)}: {1e3 * a['residual_slip']:.2f} → "
          f"{1e3 * b['residual_slip']:.2f} mm")
    ea = [abs(a["energy_error"]) for a, _ in pairs]
    eb = [abs(b["energy_error"]) for _, b in pairs]
    p(f"- energy residual at a: {stats(ea)}; at b: {stats(eb)}")
    rk = [(a, b) for a, b in pairs if a["peak_rotation"] >= ROCKING]
    if rk:
        fell = sum(abs(b["energy_error"]) < abs(a["energy_error"]) for a, b in rk)
        ra = [abs(a["energy_error"]) for a, _ in rk]
        rb = [abs(b["energy_error"]) for _, b in rk]
        p(f"  - rocking runs ({len(rk)}): at a {stats(ra)}; at b {stats(rb)}; smaller at b "
          f"in {fell}")
    p(f"- run time summed: a {sum(a['cpu_s'] for a, _ in pairs):.1f} s, "
      f"b {sum(b['cpu_s'] for _, b in pairs):.1f} s")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--halve", action="store_true", help="pair the runs at dt and dt / 2")
    ap.add_argument("--merge", metavar="OUT", help="write the merged rows to OUT")
    args = ap.parse_args()
    header, rows = read(args.csv)
    print("\n".join(halving(rows) if args.halve else suite(rows)))
    cpu, found = user_time(args.csv)
    if found:
        print(f"- user CPU time of the {found} processes (/usr/bin/time -v, of "
              f"{len(args.csv)} CSVs): {cpu:.1f} s")
    if args.merge:
        with open(args.csv[0], newline="") as f:
            raw_header = next(csv.reader(f))
        raw = []
        for path in args.csv:
            with open(path, newline="") as f:
                raw.extend(list(csv.reader(f))[1:])
        idx = {k: i for i, k in enumerate(raw_header)}
        raw.sort(key=lambda r: (r[idx["record"]], int(r[idx["drums"]]), float(r[idx["w"]]),
                                float(r[idx["h"]]), float(r[idx["pga"]]), float(r[idx["mu"]]),
                                -float(r[idx["dt"]])))
        with open(args.merge, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(raw_header)
            w.writerows(raw)


if __name__ == "__main__":
    main()
