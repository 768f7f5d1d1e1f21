#!/usr/bin/python3
"""The Siconos peer (`drums_siconos.py`) on the cases whose answer is known in closed form,
before any drum column is compared:

1. one 1 × 1 m block on the ground, μ = 5, no excitation, 1 s: it stays at rest;
2. free rocking of a 0.25 × 1 m block released from half its slenderness angle, μ = 5: the
   ratio of angular velocities across the first impact is Housner's (the thesis's impact model
   for one block), `1 − 1.5 sin²α`, and the first peak after it follows from energy;
3. a squat 1 × 0.5 m block (b/h = 2 > μ, it cannot rock) under a rectangular pulse: its
   permanent slip is Newmark's `(A − μg) A t_p² / (2 μ g)` (the formulas of tests/drums.rs).

    /usr/bin/python3 bench/siconos/checks.py [--solver nsgs|lemke|enum]

Prints each figure next to its closed form and exits non-zero if one is off.
"""

import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import drums_siconos as peer  # noqa: E402

G = peer.G


def main():
    solver = sys.argv[sys.argv.index("--solver") + 1] if "--solver" in sys.argv else "nsgs"
    ok = True

    # 1. At rest.
    out = peer.simulate(1, 1.0, 1.0, lambda t: 0.0, 1.0, 5.0, 1e-3, solver=solver)
    good = out["peak_rotation"] < 1e-4 and out["residual_slip"] < 1e-8
    ok &= good
    print(f"rest: peak rotation {out['peak_rotation']:.2e} rad, slip "
          f"{out['residual_slip']:.2e} m (stays at rest: {good})")

    # 2. Free rocking, Housner's restitution.
    w, h, dt = 0.25, 1.0, 1e-4
    alpha = math.atan(w / h)
    th0 = -0.5 * alpha  # clockwise about the right base corner: the left corner lifts
    e_h = 1.0 - 1.5 * math.sin(alpha) ** 2
    r = 0.5 * math.hypot(w, h)
    i0 = 4.0 / 3.0 * r * r  # per unit mass, about a corner
    trace = []
    peer.simulate(1, w, h, lambda t: 0.0, 0.8, 5.0, dt, tilt=th0, solver=solver,
                  trace=lambda t, ds: trace.append((t, ds[0].q()[2], ds[0].velocity()[2])))
    k = next(i for i in range(1, len(trace)) if trace[i][1] * th0 <= 0 < trace[i - 1][1] * th0)
    w_pre, w_post = trace[k - 2][2], trace[k + 1][2]
    w_imp = math.sqrt(2 * G * r * (math.cos(alpha - abs(th0)) - math.cos(alpha)) / i0)
    w_aft = e_h * w_imp
    th_peak = alpha - math.acos(math.cos(alpha) + 0.5 * i0 * w_aft * w_aft / (G * r))
    peak = max(abs(x[1]) for x in trace[k:])
    ratio = w_post / w_pre
    good = abs(ratio - e_h) < 1e-3 and abs(peak - th_peak) < 1e-3 * th_peak
    ok &= good
    print(f"free rocking 0.25 x 1 m from {abs(th0):.4f} rad, dt {dt}: impact at "
          f"{trace[k][0]:.4f} s, ω before {w_pre:.5f} (exact {w_imp:.5f}) rad/s, ratio "
          f"{ratio:.5f} (Housner {e_h:.5f}), next peak {peak:.5f} (exact {th_peak:.5f}) rad: "
          f"{good}")

    # 3. Newmark's sliding block.
    for a, tp, mu in [(5.0, 0.5, 0.3), (3.0, 0.25, 0.2), (8.0, 0.3, 0.5)]:
        exact = (a - mu * G) * a * tp * tp / (2.0 * mu * G)
        out = peer.simulate(1, 1.0, 0.5, lambda t, a=a, tp=tp: a if 0.0 <= t < tp else 0.0,
                            tp * a / (mu * G) + 0.5, mu, 1e-3, solver=solver)
        d = -out["residual_slips"][0]
        good = abs(d - exact) < 1e-3 * exact and out["peak_rotation"] < 1e-4
        ok &= good
        print(f"Newmark A={a} tp={tp} μ={mu}: slip {d:.6f} m, closed form {exact:.6f} m "
              f"(rel. {abs(d - exact) / exact:.1e}), peak rotation "
              f"{out['peak_rotation']:.1e}: {good}")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
