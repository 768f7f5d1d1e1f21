"""The OpenSees model of a column of blocks (docs/opensees.md §4): three mass points per block on
stiff corotational beams, compression-only contact springs at the corners of every joint, and a
no-slip tie at the pivot corner."""
import ctypes
import importlib.util
import math
from pathlib import Path

_OPS = None


def load_openseespy():
    """``openseespy.opensees``, imported once.

    openseespy's wheel bundles BLAS/LAPACK/gfortran libraries that its extension does not find by
    itself: they are preloaded globally first (docs/opensees.md §4). Raises ImportError with the
    install hint when openseespy is missing (``pip install ./python[opensees]``)."""
    global _OPS
    if _OPS is not None:
        return _OPS
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.submodule_search_locations:
        libdir = Path(list(spec.submodule_search_locations)[0]) / "lib"
        for name in ["libquadmath.so.0", "libgfortran.so.4", "libblas.so.3", "liblapack.so.3", "libgomp.so.1"]:
            if (libdir / name).exists():
                ctypes.CDLL(str(libdir / name), mode=ctypes.RTLD_GLOBAL)
    try:
        import openseespy.opensees as ops
    except ImportError as e:
        raise ImportError(
            "rocking.opensees needs openseespy: pip install './python[opensees]' "
            "(openseespy 3.7.1.2 has wheels for Python 3.11)"
        ) from e
    _OPS = ops
    return ops


class ColumnModel:
    """A column of blocks in OpenSees (2D, 3 DOF per node), and what the coupling needs to know
    about it.

    Build one with :meth:`build`, or describe a model you built yourself with the same
    attributes: ``n`` (blocks), ``nodes`` (``(tag, block)`` of every node of every block: ``B``
    moves them with their block), ``mass_nodes`` (``(tag, mass)`` of the lumped translational
    masses), ``corners`` (per interface ``((lower left, lower right), (upper left, upper
    right))`` node tags; the ground's are fixed nodes), ``bearings`` (per interface the contact
    elements of the left and right corner, with a ``basicForce`` response, compression < 0) and
    ``centres`` (one node per block whose rotation is the block's).

    Node tags of :meth:`build`: ground corners 1 (left), 2 (right); block j:
    ``100(j+1) + {1 bottom-left, 2 bottom-right, 3 bottom axis, 4 centre, 5 top axis,
    6 top-left, 7 top-right}``.
    """

    def __init__(self, ops, n, nodes, mass_nodes, corners, bearings, centres):
        self.ops = ops
        self.n = n
        self.nodes = nodes
        self.mass_nodes = mass_nodes
        self.corners = corners
        self.bearings = bearings
        self.centres = centres
        self.ties = {}  # interface -> corner index (0 left, 1 right) tied horizontally

    @classmethod
    def build(cls, width, height, mass, contact_width=None, inertia=None, k_contact=None, block_stiffness=2e10):
        """Builds the model (``ops.wipe()`` first). Per block: axis nodes at the bottom, centre
        and top carrying the three lumped mass points of thesis Appendix C (mass, centre and
        moment of inertia reproduced; no rotational mass), corner nodes at the contact widths,
        all joined by ``elasticBeamColumn`` elements of modulus ``block_stiffness`` (Pa; area
        0.01 m², I = 1e-3 m⁴) with a Corotational transformation (exact for large rotations;
        ``rigidLink`` is linear in the rotation). At every joint, a ``zeroLength`` element per
        corner with an ``ENT`` (compression-only) material of stiffness ``k_contact`` (N/m;
        default ``1e8 · mass[0]`` per kg, i.e. 1e10 for 100 kg) vertically."""
        ops = load_openseespy()
        n = len(width)
        contact = [min(width[k - 1], width[k]) if k else width[0] for k in range(n)] if contact_width is None else list(contact_width)
        inertia = [m * (w * w + h * h) / 12.0 for w, h, m in zip(width, height, mass)] if inertia is None else list(inertia)
        if k_contact is None:
            k_contact = 1e10 * mass[0] / 100.0
        b = [0.5 * c for c in contact]
        y0 = [sum(height[:j]) for j in range(n)]
        ops.wipe()
        ops.model("basic", "-ndm", 2, "-ndf", 3)
        ops.node(1, -b[0], 0.0)
        ops.node(2, b[0], 0.0)
        ops.fix(1, 1, 1, 1)
        ops.fix(2, 1, 1, 1)
        ops.geomTransf("Corotational", 1)
        ops.uniaxialMaterial("ENT", 1, k_contact)
        nodes, mass_nodes, corners, bearings, centres = [], [], {}, {}, []
        ele = 1000
        for j in range(n):
            y, hh = y0[j], height[j]
            base = 100 * (j + 1)
            coords = {1: (-b[j], y), 2: (b[j], y), 3: (0.0, y), 4: (0.0, y + 0.5 * hh), 5: (0.0, y + hh)}
            if j + 1 < n:
                coords[6] = (-b[j + 1], y + hh)
                coords[7] = (b[j + 1], y + hh)
            for i, (x, yy) in coords.items():
                ops.node(base + i, x, yy)
                nodes.append((base + i, j))
            end = inertia[j] / (2.0 * (0.5 * hh) ** 2)
            for i, mm in [(3, end), (4, mass[j] - 2 * end), (5, end)]:
                ops.mass(base + i, mm, mm, 0.0)
                mass_nodes.append((base + i, mm))
            links = [(1, 3), (3, 2), (3, 4), (4, 5)] + ([(6, 5), (5, 7)] if j + 1 < n else [])
            for i, k in links:
                ele += 1
                ops.element("elasticBeamColumn", ele, base + i, base + k, 0.01, block_stiffness, 1e-3, 1)
            below = (1, 2) if j == 0 else (100 * j + 6, 100 * j + 7)
            pair = []
            for lower, upper in zip(below, (base + 1, base + 2)):
                ele += 1
                ops.element("zeroLength", ele, lower, upper, "-mat", 1, "-dir", 2)
                pair.append(ele)
            bearings[j] = tuple(pair)
            corners[j] = (below, (base + 1, base + 2))
            centres.append(base + 4)
        model = cls(ops, n, nodes, mass_nodes, corners, bearings, centres)
        model.k_contact = k_contact
        return model

    # ---- state read from OpenSees ----

    def block_angles(self):
        return [self.ops.nodeDisp(c, 3) for c in self.centres]

    def block_rates(self):
        return [self.ops.nodeVel(c, 3) for c in self.centres]

    def interface_rates(self):
        """Rates of the interfaces (block rotation rate minus the one below), rad/s."""
        w = self.block_rates()
        return [w[k] - (w[k - 1] if k else 0.0) for k in range(self.n)]

    def position(self, tag):
        c, d = self.ops.nodeCoord(tag), self.ops.nodeDisp(tag)
        return (c[0] + d[0], c[1] + d[1])

    def pivots(self):
        """Current pivot of each interface DOF: the right corners, then the left corners, of the
        part below (SPEC §1 order)."""
        right, left = [], []
        for k in range(self.n):
            lo = self.corners[k][0]
            left.append(self.position(lo[0]))
            right.append(self.position(lo[1]))
        return right + left

    def centre_of_mass_above(self, k):
        """Current centre of mass of the blocks above interface k (from the lumped masses)."""
        total, sx, sy = 0.0, 0.0, 0.0
        owner = dict(self.nodes)
        for tag, m in self.mass_nodes:
            if owner[tag] >= k:
                x, y = self.position(tag)
                total, sx, sy = total + m, sx + m * x, sy + m * y
        return sx / total, sy / total

    def overturned(self, k, status):
        """Static tipping at open interface k: the centre of mass of the part above has passed
        beyond its pivot (SPEC §5), left of the left corner or right of the right one."""
        if status == 0:
            return False
        piv = self.pivots()[k if status < 0 else self.n + k]
        x = self.centre_of_mass_above(k)[0]
        return x > piv[0] if status < 0 else x < piv[0]

    def bearing_forces(self, k):
        """Forces of the left and right corner springs of interface k (compression < 0)."""
        return [self.ops.eleResponse(e, "basicForce")[0] for e in self.bearings[k]]

    def gap(self, k, status):
        """Vertical gap (and its rate) at the lifted corner of open interface k: the right corner
        when rotating about the left one (status +1), the left one otherwise."""
        lower, upper = self.corners[k]
        c = 1 if status > 0 else 0
        ops = self.ops
        g = ops.nodeDisp(upper[c], 2) - (ops.nodeDisp(lower[c], 2) if k else 0.0)
        gd = ops.nodeVel(upper[c], 2) - (ops.nodeVel(lower[c], 2) if k else 0.0)
        return g, gd

    # ---- changes ----

    def tilt(self, k, angle):
        """Rotates everything above interface k by ``angle`` about its right (angle < 0) or left
        corner in the current geometry (an exact rigid rotation, set as committed
        displacements). Tilts compose: apply them bottom-up."""
        ops = self.ops
        piv = self.pivots()[k if angle < 0 else self.n + k]
        c, s = math.cos(angle), math.sin(angle)
        for tag, j in self.nodes:
            if j < k:
                continue
            x0, y0 = ops.nodeCoord(tag)
            x, y = self.position(tag)
            rx, ry = x - piv[0], y - piv[1]
            ops.setNodeDisp(tag, 1, piv[0] + c * rx - s * ry - x0, "-commit")
            ops.setNodeDisp(tag, 2, piv[1] + s * rx + c * ry - y0, "-commit")
            ops.setNodeDisp(tag, 3, ops.nodeDisp(tag, 3) + angle, "-commit")

    def tie(self, k, corner):
        """No sliding: the pivot corner of interface k is held horizontally (a fix on the
        ground, an equalDOF between blocks). Moved when the pivot changes — the constraint
        change an FE code makes at an opening or an impact (docs/opensees.md §3)."""
        if self.ties.get(k) == corner:
            return
        ops = self.ops
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

    def retie(self, status):
        """Ties every interface at its pivot: the right corner when open about it (−1), else the
        left one."""
        for k in range(self.n):
            self.tie(k, 1 if status[k] < 0 else 0)
