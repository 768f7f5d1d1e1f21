"""The thesis's design method (5.3.4; Eq. 21, 23, 24, 31), as ``rocking design width|check
--json``, elementwise over numpy arrays."""
import numpy as np

from . import _rocking
from ._errors import error


def _broadcast(**arrays):
    """The arguments broadcast together (numpy's rules), flattened, and their common shape."""
    values = []
    for name, v in arrays.items():
        try:
            raw = np.asarray(v)
            # numpy reads None as NaN, "3" as 3.0 and a date as its count of days: not numbers.
            if raw.dtype.kind not in "biufO" or (raw.dtype.kind == "O" and any(x is None for x in raw.flat)):
                raise TypeError(f"got {v!r}")
            values.append(np.asarray(raw, dtype=float))
        except (TypeError, ValueError) as e:
            raise TypeError(f"{name}: expected a number or an array of numbers ({e})") from None
    try:
        b = np.broadcast_arrays(*values)
    except ValueError as e:
        raise error(f"{', '.join(arrays)}: shapes do not broadcast together ({e})") from None
    shape = b[0].shape if b else ()
    return [np.ascontiguousarray(x).ravel().tolist() for x in b], shape


def _shaped(columns, shape):
    """Arrays of ``shape`` (0-d: Python scalars, as the CLI's JSON)."""
    out = {}
    for k, v in columns.items():
        # An empty column of names (``governing``) is still strings, not numpy's float default.
        strings = isinstance(v, list) and not v and k == "governing"
        a = np.asarray(v, dtype=str if strings else None).reshape(shape)
        out[k] = a.item() if shape == () else a
    return out


def design_width(height, pga, t1, mass="uniform", g=9.81):
    """The required width ``B`` of a pier (thesis 5.3.4, Eq. 31) as ``rocking design width
    --json``: the smaller of the width that keeps the pier from rocking, ``at_rest = 2 h_c a_p /
    g``, and the impulse branch, Eq. 23 solved exactly with ``i_cr = 1`` (``eq23``); also Eq. 21
    with ``i_cr`` of Eq. 18 (``eq21_exact_icr``) and the slender approximation Eq. 24 (``eq24``).

    ``height`` H (m), ``pga`` the peak ground acceleration ``a_p`` (m/s²), ``t1`` the site's
    replacement impulse duration (s, :func:`rocking.t1`), ``mass`` ``"uniform"`` (a solid pier)
    or ``"top"`` (the mass at the top), ``g`` (m/s²). Numbers or arrays (broadcast together).

    Returns a dict: ``width``, ``governing`` (``"impulse"`` or ``"no-rocking"``), ``eq23``,
    ``eq21_exact_icr``, ``eq24``, ``at_rest``, ``height``, ``pga``, ``t1``, ``mass``; floats for
    numbers, arrays of the broadcast shape for arrays."""
    (h, a, t), shape = _broadcast(height=height, pga=pga, t1=t1)
    cols = _rocking._design_width(h, a, t, mass, g)
    out = _shaped(cols, shape)
    out.update(_shaped({"height": h, "pga": a, "t1": t}, shape))
    out["mass"] = mass
    return out


def design_check(width, height, pga, t1, mass="uniform", g=9.81, exact_icr=False):
    """The verdict of Eq. 31 on a pier of width ``B`` (thesis 5.3.4) as ``rocking design check
    --json``: safe when ``a_p <= max(a_p,min, a_p,min i_cr / (t_1 p))`` with ``i_cr = 1``, or
    Eq. 21 with ``i_cr`` of Eq. 18 when ``exact_icr``; ``a_p,min = g tan δ`` (Eq. 3), ``p`` of
    Eq. 13 (Eq. 22 for ``mass="top"``).

    Numbers or arrays (broadcast together). Returns a dict: ``safe``, ``a_p``, ``a_p_min``,
    ``p``, ``i_cr``, ``impulse_limit``, ``limit``, ``governing``, ``utilisation``
    (``a_p / limit``)."""
    (w, h, a, t), shape = _broadcast(width=width, height=height, pga=pga, t1=t1)
    return _shaped(_rocking._design_check(w, h, a, t, mass, g, bool(exact_icr)), shape)
