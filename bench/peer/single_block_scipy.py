#!/usr/bin/env python3
"""The tool a researcher would write: a single rocking block (Housner 1963) with scipy's
solve_ivp and event location, on the scenes (a) and (b) of `rocking bench accuracy`
(cli/src/bench_cmd.rs; the parameters are echoed in the output and checked there).

Equation (uniform rectangular block, half width b, half height h, R = sqrt(b^2 + h^2),
p^2 = 3 g / (4 R), delta = atan(b / h); theta > 0 about the left corner, pushed by a_g > 0):
    theta'' = -p^2 [s sin(delta - s theta) - (a_g / g) cos(delta - s theta)],  s = sgn(theta)
(s is held fixed over each arc between impacts, so the right-hand side is smooth on the arc).
Impacts (theta crossing 0): Housner, omega -> mu omega. Uplift from rest when |a_g| > g tan(delta).
Overturning: |theta| >= delta (static tipping, as the Rust driver stops).

Output (JSON, stdout or --out): per scene, per (method, rtol, atol): best-of-N wall time, all
impact times, the kinetic energy lost at each impact (J), the peak |theta| over the run and after
the first impact (from the rate = 0 events), overturned yes/no. The Rust bench computes the
errors against its reference, with the same definitions as for its own runs.
"""
import argparse
import json
import math
import sys
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.integrate import quad
from scipy.optimize import brentq

G = 9.81  # rocking::column::GRAVITY (checked by the Rust side)


def housner_mu(h, b):
    return (2 * h * h - b * b) / (2 * h * h + 2 * b * b)  # thesis Eq. 1


class Block:
    def __init__(self, b, h, mass):
        self.b, self.h, self.mass = b, h, mass
        self.R = math.hypot(b, h)
        self.delta = math.atan(b / h)
        self.p2 = G * self.R / (4.0 / 3.0 * self.R * self.R)
        self.inertia = 4.0 / 3.0 * mass * self.R * self.R
        self.mu = housner_mu(h, b)


def simulate(block, ag, ag_end, theta0, duration, method, rtol, atol):
    """Returns impact times, energy losses, peaks, overturned."""
    d, p2 = block.delta, block.p2
    tan_d = math.tan(d)

    side = [1.0]

    def rhs(t, y):
        # The equation of the current arc's pivot (side fixed per arc), so that it continues
        # smoothly past theta = 0 inside the step that contains the impact (with sgn(theta) the
        # right-hand side jumps there and the event is located on a polluted interpolant).
        th, w = y
        s = side[0]
        u = d - s * th
        return [w, -p2 * (s * math.sin(u) - ag(t) / G * math.cos(u))]

    def impact(t, y):
        return y[0]

    def overturn(t, y):
        return side[0] * y[0] - d

    def peak(t, y):
        return y[1]

    overturn.terminal = True
    peak.terminal = False
    impact.terminal = True

    t = 0.0
    impacts, losses, peaks = [], [], []
    overturned = False
    if theta0 != 0.0:
        y = [theta0, 0.0]
    else:
        # At rest until |a_g| first exceeds g tan(delta): bracket on a fine grid, then brentq.
        grid = np.linspace(0.0, ag_end, 20001)
        vals = [abs(ag(x)) - G * tan_d for x in grid]
        i = next((k for k, v in enumerate(vals) if v > 0), None)
        if i is None:
            return impacts, losses, peaks, False
        t = brentq(lambda x: abs(ag(x)) - G * tan_d, grid[i - 1], grid[i], xtol=1e-15)
        # Start on the side the ground pushes to (theta = +-0 with zero rate).
        y = [math.copysign(1e-300, ag(t + 1e-9)), 0.0]
    # Break points of the excitation (kinks) to integrate across.
    breaks = [x for x in [ag_end] if x > t]
    e_tip = block.mass * G * block.R * (1.0 - math.cos(d))
    while t < duration:
        t_stop = min([b for b in breaks if b > t] + [duration])
        # The impact event must ignore the start at theta = 0: direction towards zero.
        side[0] = 1.0 if y[0] > 0 else -1.0
        impact.direction = -side[0]
        sol = solve_ivp(rhs, (t, t_stop), y, method=method, rtol=rtol, atol=atol,
                        events=(impact, overturn, peak))
        for te, ye in zip(sol.t_events[2], sol.y_events[2]):
            peaks.append((te, abs(ye[0])))
        if sol.status == 1 and len(sol.t_events[1]) > 0:
            overturned = True
            break
        if sol.status == 1 and len(sol.t_events[0]) > 0:
            te = sol.t_events[0][0]
            w = sol.y_events[0][0][1]
            if te <= t:  # spurious event at the start
                raise RuntimeError("impact at the start of an arc")
            ke = 0.5 * block.inertia * w * w
            impacts.append(te)
            losses.append(ke * (1.0 - block.mu ** 2))
            w *= block.mu
            t = te
            if 0.5 * block.inertia * w * w < 1e-6 * e_tip and t > ag_end:
                break  # settled (as the Rust driver's settling rule)
            y = [math.copysign(1e-300, w), w]
            continue
        t = sol.t[-1]
        y = list(sol.y[:, -1])
    return impacts, losses, peaks, overturned


def exact_impact_times(block, theta0, count):
    """Free rocking: quarter periods by quadrature (theta = theta0 (1 - s^2))."""
    d, p2 = block.delta, block.p2

    def quarter(a):
        # cos(d - a) - cos(d - a + a s^2) = 2 sin(d - a + a s^2 / 2) sin(a s^2 / 2), no cancellation.
        def f(s):
            return 2 * a * s / math.sqrt(4 * p2 * math.sin(d - a + 0.5 * a * s * s) * math.sin(0.5 * a * s * s))

        return quad(f, 0.0, 1.0, epsabs=1e-14, epsrel=1e-13, limit=200)[0]

    def amplitude(w):
        return d - math.acos(math.cos(d) + 0.5 * w * w / p2)

    t = quarter(theta0)
    out = [t]
    w = math.sqrt(2 * p2 * (math.cos(d - theta0) - math.cos(d)))
    while len(out) < count:
        w *= block.mu
        t += 2 * quarter(amplitude(w))
        out.append(t)
    return out


def scenes():
    ba, ha, ma = 0.25, 1.0, 100.0
    a = Block(ba, ha, ma)
    theta0 = -0.6 * a.delta
    # Duration: between impacts 5 and 6 of the exact solution, as the Rust bench.
    t5, t6 = exact_impact_times(a, abs(theta0), 6)[4:6]
    bb, hb, mb = 0.5, 2.0, 10_000.0
    amp, tp = 4.0, 0.8

    def half_sine(t):
        return amp * math.sin(math.pi * t / tp) if 0.0 <= t <= tp else 0.0

    return {
        "a": dict(block=a, ag=lambda t: 0.0, ag_end=0.0, theta0=theta0,
                  params=dict(width=2 * ba, height=2 * ha, mass=ma, theta0=theta0,
                              duration=0.5 * (t5 + t6),
                              mu=a.mu, gravity=G)),
        "b": dict(block=Block(bb, hb, mb), ag=half_sine, ag_end=tp, theta0=0.0,
                  params=dict(width=2 * bb, height=2 * hb, mass=mb, amplitude=amp,
                              half_period=tp, duration=6.0, mu=housner_mu(hb, bb), gravity=G)),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default="-")
    ap.add_argument("--methods", default="RK45,DOP853,LSODA")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    tols = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
    if args.quick:
        tols = [1e-4, 1e-7]
    out = {"tool": "scipy.integrate.solve_ivp", "scipy": __import__("scipy").__version__,
           "numpy": np.__version__, "python": sys.version.split()[0], "scenes": {}}
    for key, sc in scenes().items():
        duration = sc["params"]["duration"]
        runs = []
        for method in args.methods.split(","):
            for rtol in tols:
                atol = rtol * 1e-3  # angles ~ 1e-2..1e-1 rad
                best, total, reps, res = math.inf, 0.0, 0, None
                while reps < 3 or (total < 1.0 and reps < 20):
                    s = time.perf_counter()
                    try:
                        res = simulate(sc["block"], sc["ag"], sc["ag_end"], sc["theta0"],
                                       duration, method, rtol, atol)
                    except (ValueError, RuntimeError) as exc:
                        res = exc
                        break
                    e = time.perf_counter() - s
                    best, total, reps = min(best, e), total + e, reps + 1
                if isinstance(res, Exception):
                    print(f"scene ({key}) {method} rtol={rtol:.0e}: failed: {res}", file=sys.stderr)
                    out.setdefault("failures", []).append(
                        dict(scene=key, method=method, rtol=rtol, error=str(res)))
                    continue
                impacts, losses, peaks, overturned = res
                first = impacts[0] if impacts else math.inf
                runs.append(dict(
                    method=method, rtol=rtol, atol=atol, wall_s=best, repetitions=reps,
                    impact_times=impacts, impact_losses=losses,
                    peak=max([p for _, p in peaks] + [0.0]),
                    peak_after_first_impact=max([p for t, p in peaks if t > first] + [0.0]),
                    overturned=overturned))
                print(f"scene ({key}) {method} rtol={rtol:.0e}: {best * 1e3:.2f} ms, "
                      f"{len(impacts)} impacts, first {impacts[:3]}", file=sys.stderr)
        out["scenes"][key] = {"parameters": sc["params"], "runs": runs}
    text = json.dumps(out, indent=1)
    if args.out == "-":
        print(text)
    else:
        with open(args.out, "w") as f:
            f.write(text + "\n")


if __name__ == "__main__":
    main()
