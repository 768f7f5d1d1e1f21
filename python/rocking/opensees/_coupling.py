"""The library's side of the coupling (docs/opensees.md §1–3 and §6): ``B`` from the current node
positions, ``M̃ = BᵀMB`` and ``p̃ = Bᵀp`` from OpenSees's own mass matrix, the two models on them,
and the velocities written back."""
import math

import numpy as np

import rocking

GRAVITY = rocking.GRAVITY


def opensees_mass_matrix(ops):
    """OpenSees's own mass matrix over its equations: ``GimmeMCK(1, 0, 0)`` assembles
    ``1·M + 0·C + 0·K`` into a FullGeneral system and ``printA('-ret')`` returns it (BandGeneral
    returns nothing). The solve that ``analyze`` attempts fails on the singular ``M`` (massless
    rotations) and prints a warning: harmless, nothing is updated. The equation numbers are
    those of this analysis (``nodeDOFs``), recorded here. Returns ``(M, {node: equations})``."""
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
    return np.array(flat, dtype=float).reshape(neq, neq), numbering


def dof(k, status, n):
    """Index of the open DOF of interface k (SPEC §1 order), or None when closed."""
    return None if status[k] == 0 else (k if status[k] < 0 else n + k)


class Coupling:
    """Every opening and impact decision of an OpenSees column, delegated to the library.

    ``model``: a :class:`ColumnModel`; ``n_impacts``: consecutive impacts per closing (1 =
    Housner, 2 = the thesis's recommended model); ``solver``: as for :func:`rocking.impact_model`.
    The lumped mass matrix is read from OpenSees once (it is constant; only ``B`` changes with
    the geometry)."""

    def __init__(self, model, n_impacts=1, solver="auto"):
        self.model = model
        self.n_impacts = n_impacts
        self.solver = solver
        self.M, self.eqs = opensees_mass_matrix(model.ops)
        self.neq = self.M.shape[0]

    def transformation(self):
        """``B`` (equations × 2n) in the current geometry (docs/opensees.md §1): a rate about the
        pivot ``P`` of DOF ``a`` moves every node ``r`` above interface ``a mod n`` at
        ``ẑ × (r − P)`` and turns it at the same rate."""
        model, n = self.model, self.model.n
        piv = model.pivots()
        B = np.zeros((self.neq, 2 * n))
        for tag, j in model.nodes:
            r = model.position(tag)
            for a in range(2 * n):
                if j >= a % n:
                    p = piv[a]
                    for eq, v in zip(self.eqs[tag], (-(r[1] - p[1]), r[0] - p[0], 1.0)):
                        if eq >= 0:
                            B[eq, a] = v
        return B

    def nodal_load(self, ground_acceleration=0.0):
        """``p = −M (a_g e_x + g e_y)``: gravity and the inertia of the ground motion."""
        acc = np.zeros(self.neq)
        for tag, _ in self.model.nodes:
            for eq, a in zip(self.eqs[tag][:2], (ground_acceleration, GRAVITY)):
                if eq >= 0:
                    acc[eq] = a
        return -self.M @ acc

    def reduced(self, ground_acceleration=0.0):
        """``(M̃, q̃, B)``: ``BᵀMB`` and ``Bᵀp`` on the 2n interface DOFs (thesis Appendix C)."""
        B = self.transformation()
        Mr, qr = rocking.reduce(B, self.M, self.nodal_load(ground_acceleration))
        return Mr, qr, B

    def interface_velocity(self, status):
        """The 2n DOF rates of OpenSees's state: each open interface's rate on its open DOF."""
        n = self.model.n
        rates = self.model.interface_rates()
        v = np.zeros(2 * n)
        for k in range(n):
            d = dof(k, status, n)
            if d is not None:
                v[d] = rates[k]
        return v

    def impact(self, status, k, ground_acceleration=0.0, at_rest=False):
        """:func:`rocking.impact_model` on OpenSees's state when interface ``k`` closes; writes
        the velocities back. ``at_rest``: the interface arrives with no rate (its corner went
        through the contact within a step and the springs already turned it back: the model
        takes its rate as zero). Returns ``(status after, rate before, rate after, report)``."""
        n = self.model.n
        Mr, _, B = self.reduced(ground_acceleration)
        v = self.interface_velocity(status)
        before = v[dof(k, status, n)]
        if at_rest:
            v[dof(k, status, n)] = 0.0
        st, vv, report = rocking.impact_model(Mr, status, v, k, n_impacts=self.n_impacts, solver=self.solver)
        status = [int(s) for s in st]
        self.write_back(status, vv, ground_acceleration)
        d = dof(k, status, n)
        return status, before, (vv[d] if d is not None else 0.0), report

    def opening(self, status, ground_acceleration=0.0):
        """:func:`rocking.opening_model` on OpenSees's current state: ``(status, report)``."""
        Mr, qr, _ = self.reduced(ground_acceleration)
        st, _, report = rocking.opening_model(Mr, qr, status, solver=self.solver)
        return [int(s) for s in st], report

    def write_back(self, status, v, ground_acceleration=0.0):
        """Velocities ``B v`` and consistent accelerations (``B a`` + the centripetal terms of
        the rigid rotations, ``M̃_FF a_F = q̃_F``) into every node, then ``domainChange()``:
        Newmark/HHT keep their own copies of U, U', U'' and take them from the domain only then
        (else they overwrite the new velocities, and a stale acceleration spoils the first step
        after the impact)."""
        model, n, ops = self.model, self.model.n, self.model.ops
        Mr, qr, B = self.reduced(ground_acceleration)
        free = [dof(k, status, n) for k in range(n) if status[k] != 0]
        a = np.zeros(2 * n)
        if free:
            a[free] = np.linalg.solve(Mr[np.ix_(free, free)], qr[free])
        piv = model.pivots()
        node_v, node_a = B @ v, B @ a
        for tag, j in model.nodes:
            r = model.position(tag)
            # Centripetal acceleration of a point of block j: each open interface below turns the
            # part above about its pivot (exact for one open interface, the leading term else).
            cx = cy = 0.0
            for k in range(j + 1):
                d = dof(k, status, n)
                if d is not None:
                    w2, p = v[d] * v[d], piv[d]
                    cx -= w2 * (r[0] - p[0])
                    cy -= w2 * (r[1] - p[1])
            for i, eq in enumerate(self.eqs[tag]):
                if eq >= 0:
                    ops.setNodeVel(tag, i + 1, float(node_v[eq]), "-commit")
                    ops.setNodeAccel(tag, i + 1, float(node_a[eq] + (cx, cy, 0.0)[i]), "-commit")
        ops.domainChange()
