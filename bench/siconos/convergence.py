#!/usr/bin/python3
"""dt-halving of both codes and their CPU-time ratio at equal accuracy, from the files that
`compare.py --dt …` writes (no simulation here):

    /usr/bin/python3 bench/siconos/convergence.py [--tol 0.05,0.02,0.005] FILE.json [FILE.json …]

For every case and code (the library's default scheme, its plain Moreau–Jean variant
`--plain`, Siconos) it prints, at each dt, the peak rotation and top displacement, their
relative errors against the reference — the library's (default scheme's) value at its finest
dt — and the CPU time of the run. Then, for each tolerance of `--tol` and each code, the
coarsest dt from which on (that dt and every finer one run) the peak rotation and the top
displacement are within the tolerance of that reference, with its CPU time: the ratio of the
two CPU times (whole processes, as `/usr/bin/time` counts them) is the speed-up at equal
accuracy. When Siconos is within it at no dt run, the ratio printed is a lower bound
(Siconos' finest run, which still misses, against the library's run that meets it).
A first-order Richardson value `2 f(dt/2) − f(dt)` from each code's two finest steps is printed
beside, to show where each is heading.
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
                if code == "rocking" and row.get("rocking_scheme") == "plain":
                    name = "rocking (plain)"
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
        for name in ("rocking", "rocking (plain)", "siconos"):
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
            if len(dts) >= 2:
                f1, f2 = r[dts[1]]["peak_rotation"], r[dts[0]]["peak_rotation"]
                print(f"| {name}: Richardson (dt {dts[1] * 1e3:g}, {dts[0] * 1e3:g} ms) | | "
                      f"{2 * f2 - f1:.5g} | {(2 * f2 - f1) / ref_p - 1:+.2%} | | | | | | |")
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
