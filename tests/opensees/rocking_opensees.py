#!/usr/bin/env python3
"""Real OpenSees (openseespy) integrates rocking columns; the rocking library decides the impacts.

Usage: rocking_opensees.py LIBROCKING_SO HARNESS_EXE
Run by tests/opensees/run.sh inside its virtualenv. Exits 0 when every check passes.

The OpenSees model (2D, 3 DOF per node), per block:
  - axis nodes at the bottom, centre and top of the block carrying the three lumped mass points of
    thesis Appendix C (mass, centre and moment of inertia reproduced; no rotational mass), and
    corner nodes at the contact width; all joined by very stiff elasticBeamColumn elements with a
    Corotational transformation (rigid bodies, exact for large rotations: OpenSees's rigidLink is
    linear in the rotation, which moves a corner by r θ²/2 = 3.5 mm at 0.15 rad);
  - at every interface, a zeroLength element per corner with an ENT material in the vertical
    direction (compression only: the corner lifts freely), and no sliding: the pivot corner is
    held horizontally (a fix on the ground, an equalDOF between blocks; the Transformation
    constraint handler), and that tie is moved to the new pivot at every opening and impact.
    (A flatSliderBearing with Coulomb friction would be the natural contact; Newton does not
    converge with it here, at the first step after release.)
Openings are left to OpenSees (a corner's bearing goes slack); at each one the script asks the
library's opening model on OpenSees's own matrices and checks that it picks the configuration
OpenSees took. Impacts: when the lifted corner of an open interface comes down onto the part below
(the step is cut to land on the contact), the script
  1. takes OpenSees's mass matrix (GimmeMCK + FullGeneral + printA('-ret'), once: it is lumped
     and constant; only B changes with the geometry),
  2. builds B (equations <- interface DOFs) from the current node positions (coordinates plus
     displacements) and reduces it with rocking_reduce: M~ = B^T M B,
  3. reads the interface rates from OpenSees, calls rocking_impact_model,
  4. writes v = B v+ (and consistent accelerations) into every node of every block with
     setNodeVel / setNodeAccel, then ops.domainChange() (else the integrator keeps its own copy
     of the velocities and overwrites them), and moves the no-slip tie to the new pivot.
The blocks start tilted and at rest with gravity applied statically (the tilt held by an imposed
rotation), so that the contact springs do not ring from a suddenly applied weight.
"""
import ctypes
import json
import math
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "python"))
import smoke  # noqa: E402  (argtypes of the C ABI)


def load_opensees():
    # openseespy's wheel bundles BLAS/LAPACK/gfortran that the extension does not find by itself:
    # preload them globally first.
    import importlib.util

    # the platform package that carries opensees.so and lib/ (importing it would load the .so)
    spec = importlib.util.find_spec("openseespylinux")
    libdir = Path(list(spec.submodule_search_locations)[0]) / "lib"
    for name in ["libquadmath.so.0", "libgfortran.so.4", "libblas.so.3", "liblapack.so.3", "libgomp.so.1"]:
        path = libdir / name
        if path.exists():
            ctypes.CDLL(str(path), mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


ops = load_opensees()
G = 9.81
# HHT with alpha = 0.9: one-step (so velocities written at an impact are all it needs; the
# multistep TRBDF2 keeps the pre-impact displacement history and gains energy), and dissipative
# at the contact springs' frequency (omega dt ~ 1) while the rocking (omega dt ~ 5e-4) is
# untouched. Average-acceleration Newmark keeps the contact ringing, whose energy exchange with
# the rocking shows as +-1 % jumps of the rocking rate. Override: ROCKING_INTEGRATOR=Newmark,0.5,0.25
INTEGRATOR = os.environ.get("ROCKING_INTEGRATOR", "HHT,0.9").split(",")
INTEGRATOR = [INTEGRATOR[0]] + [float(x) for x in INTEGRATOR[1:]]


class Column:
    """A column of rigid blocks in OpenSees. Node tags: ground corners 1 (left), 2 (right);
    block j: 100j + {1 bottom-left, 2 bottom-right, 3 bottom axis, 4 centre, 5 top axis,
    6 top-left, 7 top-right}."""

    def __init__(self, width, height, mass, contact, k_contact):
        self.n = len(width)
        self.w, self.h, self.m = width, height, mass
        self.b = [0.5 * c for c in contact]
        self.y0 = [sum(height[:j]) for j in range(self.n)]
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(1, -self.b[0], 0.0)
        ops.node(2, self.b[0], 0.0)
        ops.fix(1, 1, 1, 1)
        ops.fix(2, 1, 1, 1)
        ops.geomTransf("Corotational", 1)
        ops.uniaxialMaterial("ENT", 1, k_contact)
        self.nodes = []  # (tag, block)
        self.bearings = {}
        self.corners = {}  # interface -> ((lower left, lower right), (upper left, upper right))
        self.ties = {}  # interface -> corner index (0 left, 1 right) tied horizontally
        self.mass_nodes = []
        ele = 1000
        for j in range(self.n):
            y, hh, bj = self.y0[j], height[j], self.b[j]
            base = 100 * (j + 1)
            coords = {1: (-bj, y), 2: (bj, y), 3: (0.0, y), 4: (0.0, y + 0.5 * hh), 5: (0.0, y + hh)}
            if j + 1 < self.n:
                coords[6] = (-self.b[j + 1], y + hh)
                coords[7] = (self.b[j + 1], y + hh)
            for i, (x, yy) in coords.items():
                ops.node(base + i, x, yy)
                self.nodes.append((base + i, j))
            inertia = mass[j] * (width[j] ** 2 + hh**2) / 12.0
            end = inertia / (2.0 * (0.5 * hh) ** 2)
            for i, mm in [(3, end), (4, mass[j] - 2 * end), (5, end)]:
                ops.mass(base + i, mm, mm, 0.0)
                self.mass_nodes.append((base + i, mm))
            links = [(1, 3), (3, 2), (3, 4), (4, 5)] + ([(6, 5), (5, 7)] if j + 1 < self.n else [])
            for i, k in links:
                ele += 1
                ops.element("elasticBeamColumn", ele, base + i, base + k, 0.01, 2e10, 1e-3, 1)
            below = (1, 2) if j == 0 else (100 * j + 6, 100 * j + 7)
            pair = []
            for lower, upper in zip(below, (base + 1, base + 2)):
                ele += 1
                ops.element("zeroLength", ele, lower, upper, "-mat", 1, "-dir", 2)
                pair.append(ele)
            self.bearings[j] = tuple(pair)  # interface j: (left corner, right corner)
            self.corners[j] = (below, (base + 1, base + 2))

    def centre(self, j):
        return 100 * (j + 1) + 4

    def block_angles(self):
        return [ops.nodeDisp(self.centre(j), 3) for j in range(self.n)]

    def block_rates(self):
        return [ops.nodeVel(self.centre(j), 3) for j in range(self.n)]

    def interface_angles(self):
        a = self.block_angles()
        return [a[k] - (a[k - 1] if k else 0.0) for k in range(self.n)]

    def interface_rates(self):
        w = self.block_rates()
        return [w[k] - (w[k - 1] if k else 0.0) for k in range(self.n)]

    def position(self, tag):
        c, d = ops.nodeCoord(tag), ops.nodeDisp(tag)
        return (c[0] + d[0], c[1] + d[1])

    def pivots(self):
        """Current pivot of each interface DOF: right corners, then left corners (of the part below)."""
        right, left = [], []
        for k in range(self.n):
            lo = (1, 2) if k == 0 else (100 * k + 6, 100 * k + 7)
            left.append(self.position(lo[0]))
            right.append(self.position(lo[1]))
        return right + left

    def tilt(self, k, angle):
        """Rotates everything above interface k by `angle` about its right (angle < 0) or left
        corner (exact rigid rotation, set as committed displacements)."""
        piv = self.pivots()[k if angle < 0 else self.n + k]
        c, s = math.cos(angle), math.sin(angle)
        for tag, j in self.nodes:
            if j < k:
                continue
            x, y = ops.nodeCoord(tag)
            rx, ry = x - piv[0], y - piv[1]
            ops.setNodeDisp(tag, 1, piv[0] + c * rx - s * ry - x, "-commit")
            ops.setNodeDisp(tag, 2, piv[1] + s * rx + c * ry - y, "-commit")
            ops.setNodeDisp(tag, 3, angle, "-commit")

    def bearing_forces(self, k):
        """Forces of the left and right corner springs of interface k (compression < 0)."""
        return [ops.eleResponse(e, "basicForce")[0] for e in self.bearings[k]]

    def gap(self, k, status):
        """Vertical gap (and its rate) at the lifted corner of open interface k: the right corner
        when rotating about the left one (status +1), the left one otherwise."""
        lower, upper = self.corners[k]
        c = 1 if status > 0 else 0
        g = ops.nodeDisp(upper[c], 2) - (ops.nodeDisp(lower[c], 2) if k else 0.0)
        gd = ops.nodeVel(upper[c], 2) - (ops.nodeVel(lower[c], 2) if k else 0.0)
        return g, gd

    def tie(self, k, corner):
        """No sliding: the pivot corner of interface k is held horizontally (a fix on the ground,
        an equalDOF between the blocks). Moved when the pivot changes: the constraint change an
        FE code makes at an opening or an impact."""
        if self.ties.get(k) == corner:
            return
        lower, upper = self.corners[k]
        if k in self.ties:
            old = upper[self.ties[k]]
            if k == 0:
                ops.remove("sp", old, 1)
            else:
                ops.remove("mp", old)
        if k == 0:
            ops.fix(upper[corner], 1, 0, 0)
        else:
            ops.equalDOF(lower[corner], upper[corner], 1)
        self.ties[k] = corner


def opensees_mass_matrix():
    """OpenSees's own mass matrix over its equations: GimmeMCK(1, 0, 0) assembles 1·M + 0·C + 0·K
    into a FullGeneral system, printA('-ret') returns it (BandGeneral returns nothing). The
    solve that the analyze() call attempts fails on the singular M (massless rotations): harmless,
    nothing is updated."""
    ops.wipeAnalysis()
    ops.system("FullGeneral")
    ops.numberer("Plain")
    ops.constraints("Plain")
    ops.algorithm("Linear")
    ops.integrator("GimmeMCK", 1.0, 0.0, 0.0)
    ops.analysis("Transient")
    ops.analyze(1, 0.0)
    flat = ops.printA("-ret")
    neq = int(round(math.sqrt(len(flat))))
    numbering = {tag: ops.nodeDOFs(tag) for tag in ops.getNodeTags()}
    ops.wipeAnalysis()
    return neq, list(flat), numbering


def solve(A, b):
    """Gaussian elimination with partial pivoting (a few unknowns)."""
    n = len(b)
    A = [row[:] + [b[i]] for i, row in enumerate(A)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(A[r][c]))
        A[c], A[p] = A[p], A[c]
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            for k in range(c, n + 1):
                A[r][k] -= f * A[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (A[r][n] - sum(A[r][k] * x[k] for k in range(r + 1, n))) / A[r][r]
    return x


class Coupling:
    """The Python side of the coupling: B, rocking_reduce, the two models."""

    def __init__(self, lib, col, n_impacts):
        self.lib, self.col = lib, col
        self.neq, self.M, self.eqs = opensees_mass_matrix()
        self.opts = smoke.RockingOptions(n_impacts, 0, 1e-12)

    def transformation(self):
        """B (neq x 2n, column-major): a rate about the pivot P of DOF a moves every node r above
        interface a mod n at z x (r - P) and turns it at the same rate."""
        n, col = self.col.n, self.col
        piv = col.pivots()
        B = [0.0] * (self.neq * 2 * n)
        for tag, j in col.nodes:
            dofs = self.eqs[tag]
            r = col.position(tag)
            for a in range(2 * n):
                if j >= a % n:
                    p = piv[a]
                    for eq, v in zip(dofs, (-(r[1] - p[1]), r[0] - p[0], 1.0)):
                        if eq >= 0:
                            B[a * self.neq + eq] = v
        return B

    def reduced(self, ag=0.0):
        """M~ = B^T M B and q~ = B^T p with OpenSees's M and p = -M (a_g e_x + g e_y)."""
        n = self.col.n
        B = self.transformation()
        p = [0.0] * self.neq
        for tag, _ in self.col.nodes:
            dofs = self.eqs[tag]
            for eq, acc in zip(dofs[:2], (ag, G)):
                if eq >= 0:
                    for c in range(self.neq):
                        p[c] -= self.M[eq * self.neq + c] * acc
        Mr, qr = smoke.doubles([0.0] * (4 * n * n)), smoke.doubles([0.0] * (2 * n))
        code = self.lib.rocking_reduce(self.neq, 2 * n, smoke.doubles(self.M), smoke.doubles(B), smoke.doubles(p), Mr, qr)
        assert code == 0, self.lib.rocking_last_error_message()
        return list(Mr), list(qr), B

    def impact(self, status, k):
        """rocking_impact_model on OpenSees's state; writes the velocities back. Returns
        (status after, rate of k's DOF before, rate of k's new DOF after)."""
        n = self.col.n
        Mr, _, B = self.reduced()
        rates = self.col.interface_rates()
        v = [0.0] * (2 * n)
        for j in range(n):
            if status[j] != 0:
                v[j if status[j] < 0 else n + j] = rates[j]
        v_before = rates[k]
        st, vv, rep = smoke.int8s(status), smoke.doubles(v), smoke.RockingReport()
        code = self.lib.rocking_impact_model(n, smoke.doubles(Mr), st, vv, k, ctypes.byref(self.opts), ctypes.byref(rep))
        assert code == 0, self.lib.rocking_last_error_message()
        status, v = list(st), list(vv)
        self.write_back(status, v, Mr, B)
        v_after = v[k if status[k] < 0 else n + k] if status[k] else 0.0
        return status, v_before, v_after

    def write_back(self, status, v, Mr, B):
        """Velocities v_node = B v and accelerations consistent with the new configuration
        (a_node = B a + the centripetal terms of the rigid rotations, with M~_FF a_F = q~_F) into
        every node, then domainChange(): Newmark/HHT keep their own copies of U, U', U'' and
        take them from the domain only then (else they overwrite the new velocities, and a stale
        acceleration makes the first step after the impact wrong)."""
        n = self.col.n
        _, qr, _ = self.reduced()
        free = [k if status[k] < 0 else n + k for k in range(n) if status[k] != 0]
        a = [0.0] * (2 * n)
        if free:
            Mff = [[Mr[i * 2 * n + j] for j in free] for i in free]
            for i, x in zip(free, solve(Mff, [qr[i] for i in free])):
                a[i] = x
        piv = self.col.pivots()
        for tag, j in self.col.nodes:
            r = self.col.position(tag)
            # centripetal acceleration of a point of block j: sum over the open interfaces below,
            # each turning the part above about its pivot (exact for one open interface, and
            # the leading term otherwise)
            cx = cy = 0.0
            omega = 0.0
            for k in range(j + 1):
                if status[k] != 0:
                    d = k if status[k] < 0 else n + k
                    omega_k = v[d]
                    p = piv[d]
                    cx -= omega_k * omega_k * (r[0] - p[0])
                    cy -= omega_k * omega_k * (r[1] - p[1])
                    omega += omega_k
            for d, eq in enumerate(self.eqs[tag]):
                if eq >= 0:
                    vel = sum(B[i * self.neq + eq] * v[i] for i in range(2 * n))
                    acc = sum(B[i * self.neq + eq] * a[i] for i in range(2 * n)) + (cx, cy, 0.0)[d]
                    ops.setNodeVel(tag, d + 1, vel, "-commit")
                    ops.setNodeAccel(tag, d + 1, acc, "-commit")
        ops.domainChange()

    def opening(self, status):
        """The library's opening decision on OpenSees's current state."""
        n = self.col.n
        Mr, qr, _ = self.reduced()
        st, acc, rep = smoke.int8s(status), smoke.doubles([0.0] * (2 * n)), smoke.RockingReport()
        code = self.lib.rocking_opening_model(n, smoke.doubles(Mr), smoke.doubles(qr), st, acc, ctypes.byref(self.opts), ctypes.byref(rep))
        assert code == 0, self.lib.rocking_last_error_message()
        return list(st)


def transient(dt):
    ops.wipeAnalysis()
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-11, 100)
    ops.algorithm("Newton")
    ops.integrator(*INTEGRATOR)
    ops.analysis("Transient")


def gravity(col):
    ops.timeSeries("Constant", 1)
    ops.pattern("Plain", 1, 1)
    for tag, mm in col.mass_nodes:
        ops.load(tag, 0.0, -mm * G, 0.0)


def run_scene(lib, name, width, height, mass, contact, tilt, n_impacts, duration, dt, max_events):
    """Free rocking of a column released at rest with interface `tilt[0]` tilted by `tilt[1]`."""
    n = len(width)
    col = Column(width, height, mass, contact, k_contact=1e10 * mass[0] / 100.0)
    coupling = Coupling(lib, col, n_impacts)
    col.tilt(*tilt)
    status = [0] * n
    status[tilt[0]] = -1 if tilt[1] < 0 else 1

    def retie():
        for k in range(n):
            col.tie(k, 1 if status[k] < 0 else 0)

    retie()
    gravity(col)
    # Gravity first, statically, with the rotation of the tilted block held (a temporary fix
    # of its centre's rotation): the contact springs start pre-compressed, instead of ringing
    # from a suddenly applied weight (which lifts corners that should stay down).
    ops.pattern("Plain", 2, 1)
    ops.sp(col.centre(tilt[0]), 3, tilt[1])  # an imposed value (a fix would impose zero)
    ops.constraints("Transformation")
    ops.numberer("RCM")
    ops.system("BandGeneral")
    ops.test("NormDispIncr", 1e-12, 50)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    assert ops.analyze(1) == 0, "static gravity step"
    ops.loadConst("-time", 0.0)
    ops.remove("loadPattern", 2)
    transient(dt)
    t, events, peak = 0.0, [], [0.0] * n
    land_tol = 1e-12  # m
    last_compressed = {}
    while t < duration and len(events) < max_events:
        # Land on the next impact: the lifted corner of an open interface coming down onto the
        # part below (its contact spring about to engage; the interface rotation is then
        # delta/(2b) ~ 1e-6 rad). Landing on "rotation = 0" instead lets the spring of the
        # arriving corner compress first: an elastic impact has begun, the new pivot rings, and
        # its energy exchange with the rocking shows as a few % of random energy change.
        h = dt
        closing = None
        for k in range(n):
            if status[k] != 0:
                g, gdot = col.gap(k, status[k])
                if gdot < 0 and g < -gdot * h:
                    h, closing = g / -gdot, k
        if closing is not None and col.gap(closing, status[closing])[0] < land_tol:
            before = list(status)
            status, v0, v1 = coupling.impact(status, closing)
            retie()
            events.append(dict(kind="impact", t=t, interface=closing, before=before, after=list(status), v0=v0, v1=v1))
            continue
        assert ops.analyze(1, max(h, 1e-9)) == 0, f"OpenSees failed at t = {t}"
        t += max(h, 1e-9)
        # went through contact within the cut step (the rate changed): the impact, now
        for k in range(n):
            if status[k] != 0 and col.gap(k, status[k])[0] < -land_tol:
                before = list(status)
                status, v0, v1 = coupling.impact(status, k)
                retie()
                events.append(dict(kind="impact", t=t, interface=k, before=before, after=list(status), v0=v0, v1=v1))
        # Openings happen in OpenSees: a corner of a closed interface lifts. Detected when its
        # gap exceeds 1e-6 m (ten times the static compression of the contact springs, above
        # their ringing); the event time is the last instant that corner was still in
        # compression (the onset). The library's opening model is asked on OpenSees's own
        # matrices there and must choose what OpenSees did.
        for k in range(n):
            if status[k] == 0:
                forces = col.bearing_forces(k)
                for c in (0, 1):
                    if forces[c] < 0.0:
                        last_compressed[(k, c)] = t
                lifted = [c for c in (0, 1) if col.gap(k, 1 if c == 1 else -1)[0] > 1e-6]
                if lifted:
                    lib_choice = coupling.opening(status)
                    before = list(status)
                    status[k] = -1 if lifted[0] == 0 else 1  # left corner up: about the right one
                    retie()
                    t_on = last_compressed.get((k, lifted[0]), t)
                    events.append(dict(kind="opening", t=t_on, interface=k, before=before, after=list(status), library=lib_choice))
        peak = [max(p, abs(a)) for p, a in zip(peak, col.block_angles())]
    return events, peak


def harness_results(exe):
    out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
    scenes = {}
    for line in out.splitlines():
        if line.startswith("EVENT ") or line.startswith("RESULT "):
            f = dict(w.split("=", 1) for w in line.split()[1:])
            s = scenes.setdefault(f["scene"], {"events": []})
            if line.startswith("EVENT "):
                s["events"].append(dict(kind=f["kind"], t=float(f["t"]), interface=int(f["interface"]),
                                        after=[int(x) for x in f["after"].split(",")]))
            else:
                s["peak"] = [float(x) for x in f["peak"].split(",")]
    return scenes


def main():
    lib = smoke.load(sys.argv[1])
    harness = harness_results(Path(sys.argv[2]))
    failures = 0

    def check(name, ok, detail):
        nonlocal failures
        print(f"  {'ok ' if ok else 'FAIL'} {name}: {detail}")
        failures += 0 if ok else 1

    # ---- single block 0.2 x 0.6 m, 100 kg, released at 0.15 rad (harness scene a) ----
    t0 = time.time()
    b, hh = 0.1, 0.3
    mu = (2 * hh * hh - b * b) / (2 * hh * hh + 2 * b * b)
    events, peak = run_scene(lib, "a", [0.2], [0.6], [100.0], [0.2], (0, 0.15), 1, 1.85, 1e-4, 8)
    print(f"single block: {len(events)} impacts in {time.time() - t0:.1f} s")
    ref = [e for e in harness["a"]["events"] if e["kind"] == "impact"]
    for i, e in enumerate(events):
        print(f"  impact {i + 1}: t = {e['t']:.5f} s (harness {ref[i]['t']:.5f}), {e['before']} -> {e['after']}, "
              f"rate {e['v0']:+.5f} -> {e['v1']:+.5f} rad/s, ratio {e['v1'] / e['v0']:.6f}")
    for i, e in enumerate(events):
        check(f"impact {i + 1} velocity ratio = Housner mu {mu:.4f}", abs(e["v1"] / e["v0"] - mu) < 1e-4,
              f"{e['v1'] / e['v0']:.6f}")
        # OpenSees's own dynamics between impacts: the rate arriving at impact i+1 over the rate
        # arriving at impact i is Housner's ratio again (energy conserved between impacts)
        if i + 1 < len(events):
            r = events[i + 1]["v0"] / e["v0"]
            check(f"impact {i + 1}->{i + 2} OpenSees arrival-rate ratio = -mu", abs(r + mu) < 2e-3 * mu, f"{r:.6f}")
        check(f"impact {i + 1} time vs C harness", abs(e["t"] - ref[i]["t"]) < 2e-3, f"{e['t']:.5f} vs {ref[i]['t']:.5f}")
        check(f"impact {i + 1} configuration vs C harness", e["after"] == ref[i]["after"], f"{e['after']}")
    check("8 impacts", len(events) == 8, f"{len(events)}")
    check("peak rotation = release angle", abs(peak[0] - 0.15) < 1e-3 * 0.15, f"{peak[0]:.6f}")

    # ---- thesis 4.2 two-block column (harness scene c), first events ----
    t0 = time.time()
    m = 2700.0 * 0.1 * 0.3 * 0.2
    events, peak = run_scene(lib, "c", [0.1, 0.1], [0.3, 0.3], [m, m], [0.096, 0.096], (1, -0.153), 2, 0.33, 1e-4, 5)
    print(f"two blocks: {len(events)} events in {time.time() - t0:.1f} s")
    ref = harness["c"]["events"]
    for i, e in enumerate(events):
        extra = f", library opening choice {e['library']}" if e["kind"] == "opening" else ""
        print(f"  {e['kind']:8s} t = {e['t']:.5f} s (harness {ref[i]['kind']} {ref[i]['t']:.5f}), interface {e['interface']}, "
              f"{e['before']} -> {e['after']}{extra}")
    for i, e in enumerate(events):
        same = (e["kind"], e["interface"], e["after"]) == (ref[i]["kind"], ref[i]["interface"], ref[i]["after"])
        check(f"event {i + 1} as the C harness", same, f"{e['kind']} {e['interface']} {e['after']}")
        if e["kind"] == "opening":
            check(f"event {i + 1}: the library opens what OpenSees opened", e["library"] == e["after"], f"{e['library']}")
    # Times against the C harness (thesis Eq. 6). The opening's onset in the penalty model is found
    # late: the corner must lift by 1e-6 m to be told from the springs' ringing, and is back-dated
    # to its last compression, which the ringing itself delays (measured: 3.1 ms late). The next
    # two impacts follow within 2 ms. Events 4, 5 (the upper block rocking on the rocking lower
    # one) are 12-14 ms later in OpenSees than in Eq. 6, which drops the velocity terms: they are
    # compared with the exact Lagrangian equations below instead.
    for i, tol in [(0, 5e-3), (1, 2e-3), (2, 2e-3)]:
        e = events[i] if i < len(events) else {"t": float("nan")}
        check(f"event {i + 1} time vs C harness (within {tol * 1e3:.0f} ms)", abs(e["t"] - ref[i]["t"]) <= tol,
              f"{e['t']:.5f} vs {ref[i]['t']:.5f}")
    # Against the Rust driver with the exact velocity terms (OpenSees's corotational blocks have
    # them): every event, impacts within 2 ms (measured 0.03-0.7 ms), the opening within 5 ms
    # (measured 3.1 ms early: the onset of a lift in the penalty model is not sharp).
    exact = [json.loads(line) for line in Path(sys.argv[3]).read_text().splitlines() if line.strip()]
    exact = [e for e in exact if e["kind"] in ("opening", "impact")]
    for i, e in enumerate(events):
        x = exact[i] if i < len(exact) else {"kind": "?", "t": float("nan"), "interface": -1, "statuses_after": []}
        after = x["statuses_after"]  # -1 / 0 / 1 as here
        tol = 5e-3 if e["kind"] == "opening" else 2e-3
        same = (e["kind"], e["interface"], e["after"]) == (x["kind"], x["interface"], after)
        check(f"event {i + 1} as the exact-terms driver", same, f"{x['kind']} {x['interface']} {after}")
        check(f"event {i + 1} time vs exact-terms driver (within {tol * 1e3:.0f} ms)", abs(e["t"] - x["t"]) <= tol,
              f"{e['t']:.5f} vs {x['t']:.5f} ({(e['t'] - x['t']) * 1e3:+.2f} ms)")
    check("5 events", len(events) == 5, f"{len(events)}")
    print(f"{'FAILED' if failures else 'OpenSees agrees'} ({failures} failures)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
