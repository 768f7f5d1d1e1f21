"""Plots of the package's results with matplotlib, an optional dependency (``pip install
'./python[plot]'``): importing :mod:`rocking` never needs it; these functions import it when
called. Each draws into ``ax`` (a new figure's axes by default) and returns the axes.

- :func:`simulation`: block rotations against time with the events marked (as ``rocking
  simulate --plot``);
- :func:`contact_simulation`, :func:`contact_slips`: the drum rotations and the joints' slips
  (mm) of a drum column run by the contact scheme (as ``rocking simulate --plot`` draws them in
  ``FILE`` and ``FILE_slips``);
- :func:`oas`: an overturning acceleration spectrum against ``p`` (Fig. 36), ``f`` (Fig. 37) or
  the size, with the simplified spectra (as ``rocking oas --svg``);
- :func:`oc`: an overturning curve (Fig. 33a, as ``rocking oc --svg``);
- :func:`arch_oas`, :func:`arch_oc`: the spectra of an arch (as ``rocking arch oas|oc --svg``);
- :func:`suite`, :func:`arch_suite`: the characteristic OAS of a record suite.
"""
import numpy as np

from . import _rocking


def _pyplot():
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError("rocking's plots need matplotlib: pip install './python[plot]'") from e
    return plt


def _axes(ax):
    if ax is not None:
        return ax
    _, ax = _pyplot().subplots()
    return ax


#: Event markers: colour and line style by kind.
EVENT_STYLE = {
    "opening": ("tab:green", ":"),
    "impact": ("tab:orange", "--"),
    "settled": ("tab:gray", "-."),
    "overturned": ("black", "-"),
    "sliding": ("black", "-"),
    "tension": ("black", "-"),
    "closing": ("tab:orange", "--"),
    "locked": ("tab:gray", ":"),
    "collapsed": ("black", "-"),
    "slip_start": ("tab:purple", ":"),
    "slip_stop": ("tab:brown", ":"),
    "lift_off": ("tab:red", ":"),
    "landing": ("tab:cyan", "--"),
    "scheme_switch": ("tab:gray", "--"),
}

#: Beyond this many events they are ticks above the axes, one row per kind, rather than lines
#: across the data (the 42 000 events of thirty drums hid every curve and took a minute to draw).
MAX_EVENT_LINES = 100
#: Height of a row of event ticks, a fraction of the axes' height.
TICK_ROW = 0.03

#: Beyond this many members (blocks, drums, joints) each takes a shade of viridis, base to top,
#: and at most :data:`MAX_NAMED` of them are in the legend (the default colours repeat every ten).
MAX_COLOURED = 8
MAX_NAMED = 7


def _members(ax, t, values, what, scale=1.0, group=False):
    """One line per column of ``values`` against ``t``, labelled ``what k``; with ``group``,
    columns equal throughout (blocks rocking as one) are one line, ``whats j, k (as one)``:
    drawn one over the other, all but the last were hidden behind it."""
    n = values.shape[1]
    groups = []
    for k in range(n):
        same = [g for g in groups if group and np.array_equal(values[:, g[0]], values[:, k])]
        if same:
            same[0].append(k)
        else:
            groups.append([k])

    def label(g, named=True):
        if len(g) > 1:
            return f"{what}s {', '.join(map(str, g))} (as one)"
        return f"{what} {g[0]}" if named else None

    if n <= MAX_COLOURED:
        for g in groups:
            ax.plot(t, scale * values[:, g[0]], label=label(g))
        return
    cmap = _pyplot().get_cmap("viridis")
    named = {round(i * (n - 1) / (MAX_NAMED - 1)) for i in range(MAX_NAMED)}
    for g in groups:
        k = g[0]
        ax.plot(t, scale * values[:, k], color=cmap(0.9 * k / (n - 1)),
                label=label(g, k in named))


def simulation(result, ax=None, events=True):
    """Block rotations (rad) of a :class:`rocking.Simulation` against time, one line per block,
    and a vertical line at each event (``events``)."""
    ax = _axes(ax)
    _members(ax, result.t, result.block_rotations, "block", group=True)
    rows = _event_lines(ax, result.events) if events else 0
    ax.set_xlabel("t [s]")
    ax.set_ylabel("block rotation [rad]")
    _title(ax, result.title, rows)
    ax.legend(fontsize="small")
    return ax


def loop_simulation(result, ax=None, events=True):
    """The joint angles (rad) of a :class:`rocking.LoopSimulation` against time, one line per
    joint that moved, and a vertical line at each event (``events``)."""
    ax = _axes(ax)
    for k in range(result.angles.shape[1]):
        if result.angles[:, k].any():
            ax.plot(result.t, result.angles[:, k], label=f"joint {k}")
    rows = _event_lines(ax, result.events) if events else 0
    ax.set_xlabel("t [s]")
    ax.set_ylabel("joint angle [rad]")
    _title(ax, result.title, rows)
    ax.legend(fontsize="small")
    return ax


def contact_simulation(result, ax=None, events=True):
    """Drum rotations (rad) of a :class:`rocking.ContactSimulation` against time, one line per
    drum, and the impacts, lift-offs, landings, scheme switches and the overturning marked
    (``events``)."""
    ax = _axes(ax)
    _members(ax, result.t, result.block_rotations, "drum")
    kinds = ("impact", "lift_off", "landing", "scheme_switch", "overturned")
    rows = _event_lines(ax, [e for e in result.events if e["kind"] in kinds]) if events else 0
    ax.set_xlabel("t [s]")
    ax.set_ylabel("drum rotation [rad]")
    _title(ax, result.title, rows)
    ax.legend(fontsize="small", loc="upper left")
    return ax


def contact_slips(result, ax=None, events=True):
    """The joints' slips (mm) of a :class:`rocking.ContactSimulation` against time, one line per
    joint, and the slip starts and stops and the overturning marked (``events``)."""
    ax = _axes(ax)
    _members(ax, result.t, result.slips, "joint", scale=1e3)
    kinds = ("slip_start", "slip_stop", "overturned")
    rows = _event_lines(ax, [e for e in result.events if e["kind"] in kinds]) if events else 0
    ax.set_xlabel("t [s]")
    ax.set_ylabel("joint slip [mm]")
    _title(ax, result.title, rows)
    ax.legend(fontsize="small", loc="upper left")
    return ax


def _event_lines(ax, events):
    """A vertical line at each event; beyond :data:`MAX_EVENT_LINES`, a tick above the axes at
    each, one row per kind, its legend entry with the count."""
    if len(events) > MAX_EVENT_LINES:
        kinds = {}
        for e in events:
            kinds.setdefault(e["kind"], []).append(e["t"])
        for row, (kind, times) in enumerate(kinds.items()):
            colour, _ = EVENT_STYLE.get(kind, ("black", "-"))
            ax.plot(times, np.full(len(times), 1.0 + TICK_ROW * (row + 0.5)), "|", color=colour,
                    markersize=5, transform=ax.get_xaxis_transform(), clip_on=False,
                    label=f"{kind} ({len(times)}, ticks above)")
        return len(kinds)
    seen = set()
    for e in events:
        colour, style = EVENT_STYLE.get(e["kind"], ("black", "-"))
        label = e["kind"] if e["kind"] not in seen else None
        seen.add(e["kind"])
        ax.axvline(e["t"], color=colour, linestyle=style, linewidth=0.8, label=label)
    return 0


def _title(ax, title, rows):
    """The title, above the ``rows`` rows of event ticks if any."""
    height = ax.bbox.height * 72.0 / ax.figure.dpi  # the axes' height in points
    ax.set_title(title, pad=6.0 + rows * TICK_ROW * height)


def oas(result, against="p", ax=None, fits=True):
    """The boundary of a :class:`rocking.Oas` (the largest unsafe size at each level) against
    ``p`` (1/s, Fig. 36), ``f = p a_p / a_p,min`` (1/s, the transformed OAS, Fig. 37) or the
    ``size`` R (m, log axis); with ``fits``, the simplified spectrum of Eq. 21 (``t_1``, exact
    ``i_cr``) and Eq. 30 (``t_1'``, ``β``) — against ``f``, the lines of Eq. 20 and 28."""
    if against not in ("p", "f", "size"):
        raise ValueError(f"against = {against!r}: expected 'p', 'f' or 'size'")
    ax = _axes(ax)
    m = result.unsafe
    x = {"p": result.p, "f": result.f, "size": result.size}[against][m]
    ax.plot(x, result.levels[m], "o", markersize=3, label="largest unsafe size")
    s = result.summary
    lmax = max(float(result.levels.max(initial=1.0)), 1.0)
    if fits and s["t1"] is not None:
        t1, tp, beta = s["t1"], s["t1_prime"], s["beta"]
        if against == "f":
            f_min = result.i_cr / t1
            ax.plot([f_min, f_min], [1.0, lmax], "--", label=f"f_min = i_cr / t1 (Eq. 20), t1 = {t1:.3f} s")
            if tp is not None and beta is not None:
                lv = np.array([1.0, lmax])
                ax.plot(lv / beta + 1.0 / tp, lv, "--", label=f"Eq. 28, t1' = {tp:.3f} s, beta = {beta:.2f} s")
        else:
            if against == "p":
                p = np.linspace(0.0, np.nanmax(x, initial=1.0) * 1.1, 401)[1:]
                xs = p
            else:
                xs = np.geomspace(result.sizes.min(), result.sizes.max(), 401)
                # p of the equivalent block of each size: p = sqrt(g / (4/3 R)) (Eq. 13)
                p = np.sqrt(result.gravity / (4.0 / 3.0 * xs))
            eq21, eq30 = _rocking._simplified_oas(p, t1, result.i_cr, tp, beta)
            ax.plot(xs, eq21, "--", label=f"Eq. 21, t1 = {t1:.3f} s")
            if eq30 is not None:
                ax.plot(xs, eq30, "--", label=f"Eq. 30, t1' = {tp:.3f} s, beta = {beta:.2f} s")
    ax.set_xlabel({"p": "p [1/s]", "f": "f = p a_p / a_p,min [1/s]", "size": "size R [m] (half diagonal)"}[against])
    if against == "size":
        ax.set_xscale("log")
    ax.set_ylabel("a_p / a_p,min")
    ax.set_ylim(0.0, lmax)
    ax.set_title(f"OAS, {result.record}")
    ax.legend(fontsize="small")
    return ax


def _oc_points(ax, result, flags, label):
    """An overturning curve's flagged points (``flags``: rows × levels) and its envelope against
    ``p t_p`` on a log axis (:func:`oc`, :func:`arch_oc`). Returns the axes."""
    ax = _axes(ax)
    rows, cols = np.nonzero(flags)
    ax.plot(result.p_tp[rows], result.levels[cols], "o", markersize=3, label=label)
    ax.plot(result.p_tp, result.envelope, "-", label="envelope")
    ax.set_xscale("log")
    # The whole computed grid, not only the points that overturn (a grid from p t_p = 0.1 whose
    # shortest pulses overturned nothing was drawn from 0.2, as if it started there).
    lo, hi = float(np.min(result.p_tp)), float(np.max(result.p_tp))
    ax.set_xlim(lo / 1.1, hi * 1.1)
    ax.set_ylim(0.0, float(np.max(result.levels)) * 1.03)
    return ax


def oc(result, ax=None):
    """The unsafe points of a :class:`rocking.Oc` and its envelope (the lowest unsafe level at
    each ``p t_p``), against ``p t_p`` on a log axis (Fig. 33a)."""
    ax = _oc_points(ax, result, result.unsafe, "overturns")
    ax.set_xlabel("p t_p")
    ax.set_ylabel("a_p / a_p,min")
    ax.set_title(f"Overturning curve, {result.shape}, {result.blocks} block{'s' if result.blocks != 1 else ''}")
    ax.legend(fontsize="small")
    return ax


def arch_oas(result, against="p", ax=None, fits=True):
    """The boundary of a :class:`rocking.ArchOas` (the largest radius that collapses at each
    level ``a_p / (λ g)``) against ``p`` of the onset mechanism (1/s) or ``f = p a_p / (λ g)``
    (1/s); with ``fits``, Eq. 21 with ``i_cr = 1`` for the arch's own ``t_1`` and for the checked
    one (against ``f``: the lines ``f = 1/t_1``), as ``rocking arch oas --svg``."""
    if against not in ("p", "f"):
        raise ValueError(f"against = {against!r}: expected 'p' or 'f'")
    ax = _axes(ax)
    m = result.unsafe
    x = {"p": result.p, "f": result.f}[against][m]
    ax.plot(x, result.levels[m], "o", markersize=3, label="largest radius that collapses")
    lmax = max(float(result.levels.max(initial=1.0)), 1.0)
    if fits:
        checked = None if result.check is None else result.check["t1"]
        p = np.linspace(0.0, np.nanmax(x, initial=0.1) * 1.2, 401)[1:]
        for t1, what in ((result.t1, "the arch's own"), (checked, "single-block")):
            if t1 is None:
                continue
            label = f"Eq. 21 (i_cr = 1), {what} t1 = {t1:.3f} s"
            if against == "f":
                ax.plot([1.0 / t1, 1.0 / t1], [1.0, lmax], "--", label=label)
            else:
                eq21, _ = _rocking._simplified_oas(p, t1, 1.0)
                ax.plot(p, eq21, "--", label=label)
    ax.set_xlabel({"p": "p of the onset mechanism [1/s]", "f": "f = p a_p / (λ g) [1/s]"}[against])
    ax.set_ylabel("a_p / (λ g)")
    ax.set_ylim(0.0, lmax)
    ax.set_title(f"Arch OAS, t/R = {result.thickness_ratio}, {result.voussoirs} voussoirs, {result.record}")
    ax.legend(fontsize="small")
    return ax


def arch_oc(result, ax=None):
    """The points of a :class:`rocking.ArchOc` that collapse and its envelope (the lowest level
    that collapses at each ``p t_p``), against ``p t_p`` on a log axis."""
    ax = _oc_points(ax, result, result.collapses, "collapses")
    ax.set_xlabel("p t_p (p of the onset mechanism)")
    ax.set_ylabel("a_p / (λ g)")
    ax.set_title(f"Arch OC, {result.pulse}, R = {result.radius} m, t/R = {result.thickness_ratio}, "
                 f"{result.voussoirs} voussoirs")
    ax.legend(fontsize="small")
    return ax


def suite(result, against="p", ax=None):
    """The records' OAS of a :class:`rocking.Suite` (grey points) and the characteristic OAS at
    each fractile (lines), against ``p`` (1/s, Fig. 44, 47a) or ``f`` (1/s, Fig. 47b, with the
    design ``f_min = i_cr / t_1`` of each fractile as a dashed line), as ``rocking suite --svg``
    draws them."""
    return _suite(result, against, ax, "a_p / a_p,min", "p [1/s]", "f = p a_p / a_p,min [1/s]", "OAS")


def arch_suite(result, against="p", ax=None):
    """The characteristic arch OAS of a :class:`rocking.ArchSuite` at each fractile against ``p``
    of the onset mechanism or ``f`` (with the design ``f_min = 1/t_1`` of each fractile, dashed).
    The suite keeps the records' rows, not their spectra: draw those with
    :meth:`rocking.ArchOas.plot` into the same ``ax``."""
    return _suite(result, against, ax, "a_p / (λ g)", "p of the onset mechanism [1/s]", "f = p a_p / (λ g) [1/s]",
                  "arch OAS")


def _suite(result, against, ax, level_label, p_label, f_label, what):
    if against not in ("p", "f"):
        raise ValueError(f"against = {against!r}: expected 'p' or 'f'")
    ax = _axes(ax)
    lmax = 1.0
    for k, o in enumerate(getattr(result, "records", [])):
        if not hasattr(o, "unsafe"):
            break  # an arch suite's rows are not spectra
        m = o.unsafe
        x = o.p if against == "p" else o.f
        label = f"OAS of the {len(result.records)} records" if k == 0 else None
        ax.plot(x[m], o.levels[m], "o", markersize=2, color="0.73", label=label)
        lmax = max(lmax, float(o.levels.max(initial=1.0)))
    for c in result.characteristic:
        o = c["oas"]
        m = o.unsafe
        x = o.p if against == "p" else o.f
        (line,) = ax.plot(x[m], o.levels[m], "-o", markersize=3, label=f"characteristic, fractile {c['fractile']}")
        lmax = max(lmax, float(o.levels.max(initial=1.0)))
        if against == "f" and c["f_min"] is not None:
            ax.plot([c["f_min"]] * 2, [1.0, lmax], "--", color=line.get_color(),
                    label=f"design t1 = {c['design_t1']:.3f} s")
    ax.set_xlabel(p_label if against == "p" else f_label)
    ax.set_ylabel(level_label)
    ax.set_ylim(0.0, lmax)
    ax.set_title(f"{'Transformed ' if against == 'f' else ''}{what}, {result.name}")
    ax.legend(fontsize="small")
    return ax
