#!/usr/bin/python3
"""dt-halving of both codes and their CPU-time ratio at equal accuracy, from the files that
`compare.py --dt …` writes (no simulation here):

    /usr/bin/python3 bench/siconos/convergence.py [--tol 0.05,0.02,0.005] FILE.json [FILE.json …]

A run of a code at a dt in a later file replaces the one in an earlier file (put the file whose
two codes ran in one process last, so that the ratios are of runs under the same load).

For every case and code (the library's default scheme, its variants — `--plain` Moreau–Jean,
`--rocking-args …` —, Siconos) it prints, at each dt, the peak rotation and top displacement, their
relative errors against the reference — the library's (default scheme's) value at its finest
dt — and the CPU time of the run. Then, for each tolerance of `--tol` and each code, the
coarsest dt from which on (that dt and every finer one run) the peak rotation and the top
displacement are within the tolerance of that reference, with its CPU time: the ratio of the
two CPU times (whole processes, as `/usr/bin/time` counts them) is the speed-up at equal
accuracy. When Siconos is within it at no dt run, the ratio printed is a lower bound
(Siconos' finest run, which still misses, against the library's run that meets it).
Each code's three finest steps: the spread of their peak rotations (relative to the reference)
and, when they are monotone, the first-order Richardson value `2 f(dt/2) − f(dt)` of the two
finest, to show whether and where each is heading.
"""

import json
import sys


def load(paths):
    runs = {}  # (case, code) -> {dt: result}
    for p in paths:
        for row in json.load(open(p)):
            case = tuple(row["case"])
            for code in ("rocking", "siconos"):
                if code not in row:
                    continue
                name = code
                scheme = row.get("rocking_scheme", "default")
                if code == "rocking" and scheme != "default":
                    name = f"rocking ({scheme})"
                runs.setdefault((case, name), {})[row["dt"]] = row[code]
    return runs


def main():
    args = sys.argv[1:]
    tols = [0.05, 0.02, 0.005]
    if "--tol" in args:
        i = args.index("--tol")
        tols = [float(x) for x in args[i + 1].split(",")]
        del args[i:i + 2]
    runs = load(args)
    for case in sorted({c for c, _ in runs}, key=lambda c: c[0]):
        ours = runs.get((case, "rocking"))
        if not ours:
            continue
        fine = min(ours)
        ref_p = ours[fine]["peak_rotation"]
        ref_d = ours[fine]["peak_top_displacement"]
        n, w, h, rec, pga, mu = case
        print(f"\n{n} drums {w} x {h} m, {rec} at {pga} m/s², μ {mu}: reference (the library "
              f"at dt = {fine * 1e3:g} ms) peak rotation {ref_p:.5f} rad, top {ref_d:.4f} m")
        print("| code | dt (ms) | peak rotation (rad) | error | top displacement (m) | error "
              "| residual slip (m) | verdict | solver residual | CPU (s) |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        ok_from = {}  # (code, tol) -> coarsest (dt, CPU) from which every finer dt is within
        finest = {}
        names = ["rocking"] + sorted(k for c, k in runs if c == case and k.startswith("rocking ("))
        for name in names + ["siconos"]:
            r = runs.get((case, name))
            if not r:
                continue
            within = {}  # tol -> every dt so far (finest first) within it
            for dt in sorted(r):  # finest first
                d = r[dt]
                ep = d["peak_rotation"] / ref_p - 1.0
                ed = d["peak_top_displacement"] / ref_d - 1.0
                res = d.get("solver_residual_max")
                print(f"| {name} | {dt * 1e3:g} | {d['peak_rotation']:.5g} | {ep:+.2%} | "
                      f"{d['peak_top_displacement']:.5g} | {ed:+.2%} | "
                      f"{d['residual_slip']:.2e} | "
                      f"{'overturned' if d['overturned'] else 'stands'} | "
                      f"{'' if res is None else f'{res:.0e}'} | {d['cpu_s']:.3f} |")
                for t in tols:
                    if within.get(t, True) and abs(ep) <= t and abs(ed) <= t:
                        ok_from[name, t] = (dt, d["cpu_s"])
                    else:
                        within[t] = False
            dts = sorted(r)
            if len(dts) >= 3:
                f = [r[x]["peak_rotation"] for x in dts[:3]]  # finest first
                spread = (max(f) - min(f)) / ref_p
                trend = "not monotone"
                if (f[0] - f[1]) * (f[1] - f[2]) > 0:
                    x = 2 * f[0] - f[1]
                    trend = f"Richardson {x:.5g} ({x / ref_p - 1:+.2%})"
                print(f"| {name}: three finest steps | | spread {spread:.2%} | {trend} "
                      f"| | | | | | |")
            finest[name] = r[dts[0]]
        if "rocking" not in finest or "siconos" not in finest:
            continue
        for t in tols:
            o, s = ok_from.get(("rocking", t)), ok_from.get(("siconos", t))
            if o is None:
                print(f"within {t:.1%}: the library at no dt run")
            elif s is not None:
                print(f"within {t:.1%}: the library from dt = {o[0] * 1e3:g} ms ({o[1]:.3f} s "
                      f"CPU), Siconos from dt = {s[0] * 1e3:g} ms ({s[1]:.1f} s): "
                      f"{s[1] / max(o[1], 1e-3):.0f}× (CPU times below 1 ms counted as 1 ms)")
            else:
                fin = finest["siconos"]
                print(f"within {t:.1%}: the library from dt = {o[0] * 1e3:g} ms ({o[1]:.3f} s "
                      f"CPU); Siconos at no dt run (finest {fin['dt'] * 1e3:g} ms, "
                      f"{fin['cpu_s']:.1f} s, error {fin['peak_rotation'] / ref_p - 1:+.1%}): "
                      f"ratio at least {fin['cpu_s'] / max(o[1], 1e-3):.0f}×")

if __name__ == "__main__":
    main()
