#!/usr/bin/python3
"""A column of drums under a recorded ground motion in Siconos (the peer of `rocking::contact`).

Same model as the library's drum scheme: each drum a rigid body in x, y, θ (mass 2500 w h,
uniform), in the frame of the ground (inertial load −m a_g); at each joint the two ends of the
contact (the upper drum's corners on the lower face), each an interaction with a 2D Newton impact
/ Coulomb friction law (restitution 0, friction μ); Moreau–Jean (θ = ½) time stepping and the
2D frictional contact problem solved by nonsmooth Gauss–Seidel (tolerance 1e-10). The contact geometry (gap and its
Jacobian) is re-linearised at every step (a LagrangianLinearTIR whose C and e are updated), the
loads at the step's midpoint. No projection and no impact location (plain Moreau–Jean).

Run with the system Python (`apt-get install python3-siconos`):

    /usr/bin/python3 bench/siconos/drums_siconos.py --drums 10 --width 1 --height 1 \
        --record RECORD.AT2 --pga 4 --mu 0.5 --dt 0.001 [--duration 30] [--linearise mid]

Prints one JSON object: peaks, top displacement, residual slips, verdict, wall time.
"""

import argparse
import json
import math
import os
import time

# One thread: the problems are tiny, and BLAS threads only contend (10x slower on 2 cores).
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np
import siconos.kernel as sk
import siconos.numerics as sn

G = 9.81
SOLVERS = {"nsgs": sn.SICONOS_FRICTION_2D_NSGS, "lemke": sn.SICONOS_FRICTION_2D_LEMKE,
           "enum": sn.SICONOS_FRICTION_2D_ENUM}


def read_at2(path):
    """PEER .AT2: 4 header lines, NPTS and DT on the fourth, then values in g."""
    with open(path) as f:
        lines = f.readlines()
    import re

    header = lines[3]
    npts = int(re.search(r"NPTS\s*=\s*(\d+)", header, re.I).group(1))
    dt = float(re.search(r"DT\s*=\s*([0-9.eE+-]+)", header, re.I).group(1))
    values = []
    for line in lines[4:]:
        values.extend(float(x) for x in line.split())
    return dt, np.array(values[:npts]) * G


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--drums", type=int, default=10)
    ap.add_argument("--width", type=float, default=1.0)
    ap.add_argument("--height", type=float, default=1.0)
    ap.add_argument("--record", required=True)
    ap.add_argument("--pga", type=float, default=4.0)
    ap.add_argument("--mu", type=float, default=0.5)
    ap.add_argument("--dt", type=float, default=1e-3)
    ap.add_argument("--duration", type=float, default=None)
    ap.add_argument("--linearise", choices=["start", "mid"], default="start",
                    help="where the gaps are linearised each step (mid: as the library)")
    a = ap.parse_args()

    rdt, acc = read_at2(a.record)
    acc = acc * (a.pga / np.abs(acc).max())
    duration = a.duration if a.duration is not None else (len(acc) - 1) * rdt

    def ground(t):
        x = t / rdt
        i = int(math.floor(x))
        if x < 0 or i + 1 >= len(acc):
            return 0.0
        s = x - i
        return acc[i] + s * (acc[i + 1] - acc[i])

    out = simulate(a.drums, a.width, a.height, ground, duration, a.mu, a.dt,
                   linearise=a.linearise)
    out.update({"pga": a.pga, "linearise": a.linearise})
    print(json.dumps(out))


def simulate(n, w, h, ground, duration, mu, dt, tilt=0.0, restitution=0.0, trace=None,
             solver="nsgs", linearise="start"):
    """Runs the column; `ground(t)` the ground acceleration (m/s²), `tilt` an initial rotation
    of the whole column about its right base corner (free rocking), `trace(t, drums)` called
    after every step; `linearise` where the gaps and their Jacobians are linearised each step:
    `"start"` at the step's start positions (plain Moreau–Jean as Siconos' examples do), `"mid"`
    at the predicted midpoint `q + h v / 2` (as the library's scheme does). Returns the summary
    dict."""
    m = 2500.0 * w * h
    inertia = m * (w * w + h * h) / 12.0
    drums = []
    nsds = sk.NonSmoothDynamicalSystem(0.0, duration)
    for j in range(n):
        # Rigid rotation of the column by `tilt` about the base's right corner (w/2, 0).
        px, py = -0.5 * w, (j + 0.5) * h
        c0, s0 = math.cos(tilt), math.sin(tilt)
        q0 = np.array([0.5 * w + c0 * px - s0 * py, s0 * px + c0 * py, tilt])
        ds = sk.LagrangianLinearTIDS(q0, np.zeros(3), np.diag([m, m, inertia]))
        ds.setFExtPtr(np.array([0.0, -m * G, 0.0]))
        nsds.insertDynamicalSystem(ds)
        drums.append(ds)
    # One interaction per joint end: (joint, side, relation).
    ends = []
    for k in range(n):
        for side in (1.0, -1.0):
            cols = 3 if k == 0 else 6
            rel = sk.LagrangianLinearTIR(np.zeros((2, cols)), np.zeros(2))
            nsl = sk.NewtonImpactFrictionNSL(restitution, 0.0, mu, 2)
            inter = sk.Interaction(nsl, rel)
            if k == 0:
                nsds.link(inter, drums[0])
            else:
                nsds.link(inter, drums[k], drums[k - 1])
            ends.append((k, side, rel))

    def frame(j, ahead=0.0):
        q = drums[j].q() + ahead * drums[j].velocity()
        c, s = math.cos(q[2]), math.sin(q[2])
        return np.array([q[0], q[1]]), np.array([c, s]), np.array([-s, c]), np.array(q)

    def relink(ahead=0.0):
        """Linearise every end's gap (and tangential position) at the positions `ahead` seconds
        on at the current velocities (0: the current positions)."""
        for k, side, rel in ends:
            cu, e1u, e2u, qu = frame(k, ahead)
            corner = cu + side * 0.5 * w * e1u - 0.5 * h * e2u
            if k == 0:
                nrm, tan, o_low = np.array([0.0, 1.0]), np.array([1.0, 0.0]), np.zeros(2)
            else:
                cl, e1l, e2l, ql = frame(k - 1, ahead)
                nrm, tan, o_low = e2l, e1l, cl + 0.5 * h * e2l
            ru = corner - cu
            rows_u = [
                [nrm[0], nrm[1], ru[0] * nrm[1] - ru[1] * nrm[0]],
                [tan[0], tan[1], ru[0] * tan[1] - ru[1] * tan[0]],
            ]
            if k == 0:
                C = np.array(rows_u)
                qq = qu
            else:
                rl = corner - cl
                rows_l = [
                    [-nrm[0], -nrm[1], -(rl[0] * nrm[1] - rl[1] * nrm[0])],
                    [-tan[0], -tan[1], -(rl[0] * tan[1] - rl[1] * tan[0])],
                ]
                C = np.hstack([np.array(rows_u), np.array(rows_l)])
                qq = np.concatenate([qu, ql])
            gap = float((corner - o_low) @ nrm)
            rel.setCPtr(C)
            rel.setEPtr(np.array([gap - C[0] @ qq, -(C[1] @ qq)]))

    def slips():
        """Tangential offset of each joint's upper face relative to the lower at the lower
        corner (both corners agree when the joint is closed)."""
        out = []
        for k in range(n):
            cu, e1u, e2u, _ = frame(k)
            if k == 0:
                o_low, e1l, e2l = np.zeros(2), np.array([1.0, 0.0]), np.array([0.0, 1.0])
            else:
                cl, e1l, e2l, _ = frame(k - 1)
                o_low = cl + 0.5 * h * e2l
            gaps = []
            for side in (1.0, -1.0):
                corner = cu + side * 0.5 * w * e1u - 0.5 * h * e2u
                gaps.append(((corner - o_low) @ e2l, side, corner))
            _, side, corner = min(gaps, key=lambda g: g[0])
            out.append(float((corner - o_low) @ e1l - side * 0.5 * w))
        return out

    relink()
    td = sk.TimeDiscretisation(0.0, dt)
    osi = sk.MoreauJeanOSI(0.5)
    # Nonsmooth Gauss–Seidel on the 2D Coulomb problem, tolerance 1e-10: Lemke's algorithm
    # (the earlier choice) returns a wrong solution without an error on the column's redundant
    # contacts (two corners per closed joint), and one such step threw a 3-drum column at 65 m/s.
    osnspb = sk.FrictionContact(2, SOLVERS[solver])
    so = osnspb.numericsSolverOptions()
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 100000
    so.dparam[sn.SICONOS_DPARAM_TOL] = 1e-10
    sim = sk.TimeStepping(nsds, td, osi, osnspb)
    peak_rot = [0.0] * n
    peak_slip = [0.0] * n
    peak_top = 0.0
    worst = (0.0, 0.0)  # the solver's largest reported residual and its step
    overturned = None
    t0 = time.time()
    t = 0.0
    steps = 0
    while sim.hasNextEvent():
        ag = ground(t + 0.5 * dt)
        for ds in drums:
            ds.setFExtPtr(np.array([-m * ag, -m * G, 0.0]))
        relink(0.5 * dt if linearise == "mid" else 0.0)
        osnspb.setHasBeenUpdated(False)
        so.dparam[sn.SICONOS_DPARAM_RESIDU] = 0.0
        sim.computeOneStep()
        worst = max(worst, (so.dparam[sn.SICONOS_DPARAM_RESIDU], t))
        sim.nextStep()
        t += dt
        steps += 1
        if trace is not None:
            trace(t, drums)
        for j in range(n):
            peak_rot[j] = max(peak_rot[j], abs(drums[j].q()[2]))
        peak_top = max(peak_top, abs(drums[-1].q()[0]))
        if steps % 10 == 0:
            for k, s in enumerate(slips()):
                peak_slip[k] = max(peak_slip[k], abs(s))
        # Static tipping of the part above a joint beyond its corner (as the library checks).
        if overturned is None:
            for k in range(n):
                mtot = sum(1.0 for _ in range(k, n))
                cx = sum(drums[j].q()[0] for j in range(k, n)) / mtot
                cu, e1u, e2u, _ = frame(k)
                right = cu + 0.5 * w * e1u - 0.5 * h * e2u
                left = cu - 0.5 * w * e1u - 0.5 * h * e2u
                if cx > right[0] + 1e-9 and right[1] < left[1]:
                    overturned = (k, t)
                    break
                if cx < left[0] - 1e-9 and left[1] < right[1]:
                    overturned = (k, t)
                    break
            if overturned is not None:
                break
    wall = time.time() - t0
    res = slips()
    return {
        "code": "siconos",
        "drums": n,
        "width": w,
        "height": h,
        "mu": mu,
        "dt": dt,
        "t_end": t,
        "steps": steps,
        "overturned": overturned is not None,
        "overturned_joint": None if overturned is None else overturned[0],
        "peak_rotation": max(peak_rot),
        "peak_rotations": peak_rot,
        "peak_top_displacement": peak_top,
        "residual_slip": max(abs(s) for s in res),
        "residual_slips": res,
        "peak_slip": max(peak_slip),
        "wall_s": wall,
        "solver": solver,
        "solver_residual_max": worst[0],
        "solver_residual_max_t": worst[1],
    }


if __name__ == "__main__":
    main()
