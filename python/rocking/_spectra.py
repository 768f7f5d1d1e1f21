"""Overturning spectra (thesis Chapter 5; SPEC §7): ``oas``, ``t1``, ``oc``, ``tp`` and ``suite``,
with the options and the JSON of ``rocking oas``, ``t1``, ``oc``, ``tp`` and ``suite --merge``,
and numpy arrays out.

The sweeps run in parallel (rayon, every core unless ``threads``) without the GIL, and stop on
Ctrl-C (``KeyboardInterrupt``) between levels (OAS) or pulse durations (OC). The results do not
depend on the number of threads: every level and every duration is the library's own call."""
import copy
import json
import numbers
import os
from collections.abc import Iterator

import numpy as np

from . import _rocking
from ._errors import error as _error

_SIMULATION_DOC = """
    Simulations (as the CLI's options): ``impacts`` consecutive impacts per closing (1: Housner;
    2: the thesis's recommended model), ``dt_factor`` a factor on the time step rule
    (``min(Δt_record/4, t_p/100, 1/(100 p))``), ``tail`` simulated time after the motion in units
    of ``1/p`` (default 2), ``hermite`` Hermite event location, ``rk4`` RK4 with it,
    ``full_runs`` every run to its end (same verdicts, slower). ``threads``: rayon threads,
    1 to 1024 (default every core; results identical). ``progress``: a callable ``progress(done, total)``
    called as levels (durations) finish."""


def _optional(v):
    return float("nan") if v is None else v


def _set_level_arrays(result, raw):
    """The per-level arrays an OAS result (:class:`Oas`, :class:`rocking.ArchOas`) exposes, from
    its JSON: ``sizes``, ``levels``, ``largest_unsafe`` (-1: none), ``size``, ``p``, ``f`` (NaN:
    none), ``simulations``."""
    result.sizes = np.array(raw["sizes"], dtype=float)
    lv = raw["levels"]
    result.levels = np.array([x["level"] for x in lv], dtype=float)
    result.largest_unsafe = np.array([-1 if x["largest_unsafe"] is None else x["largest_unsafe"] for x in lv],
                                     dtype=np.int64)
    result.size = np.array([_optional(x["size"]) for x in lv], dtype=float)
    result.p = np.array([_optional(x["p"]) for x in lv], dtype=float)
    result.f = np.array([_optional(x["f"]) for x in lv], dtype=float)
    result.simulations = np.array([x["simulations"] for x in lv], dtype=np.int64)


class Oas:
    """An overturning acceleration spectrum (thesis Fig. 36, 37, 43): for each level
    ``a_p / a_p,min``, the largest size ``R`` of the grid that the scaled record overturns.

    Arrays, one entry per level: ``levels``, ``largest_unsafe`` (index into ``sizes``, −1 when no
    size overturns), ``size`` (m), ``p`` (1/s) and ``f = p · level`` (Eq. 19; NaN when no size
    overturns), ``simulations``. ``sizes``: the size grid (m, descending). ``summary``: ``t1``
    (Eq. 20), ``t1_prime`` and ``beta`` (the inclined line of Eq. 28), ``f_min``,
    ``level_at_f_min``, ``size_at_f_min``, ``simulations``, ``seconds`` (wall time).
    ``conservative``: how many boundary points Eq. 21, 21 with ``i_cr = 1``, 29 and 30 predict
    safe although they overturn. ``i_cr``: Eq. 18 of the slenderness. With ``band`` or
    ``converge_step`` (:func:`oas`): ``t1_range``, ``t1_conservative``, ``band``, ``t1_steps``,
    ``step_converged`` as in :func:`t1`'s rows (None when not computed). :meth:`to_dict` is the
    JSON of ``rocking oas --json``.
    """

    def __init__(self, raw, i_cr):
        self._raw = raw
        self.record = raw["record"]
        self.slenderness = raw["slenderness"]
        self.blocks = raw["blocks"]
        self.impacts = raw["impacts"]
        self.search = raw["search"]
        self.gravity = raw["gravity"]
        self.i_cr = i_cr
        _set_level_arrays(self, raw)
        self.summary = raw["summary"]
        self.conservative = raw["conservative"]
        for k in ("t1_range", "t1_conservative", "band", "t1_steps", "step_converged"):
            setattr(self, k, raw.get(k))

    @property
    def t1(self):
        """The replacement impulse duration ``t_1 = i_cr / f_min`` (s, Eq. 20); None if nothing
        overturns."""
        return self.summary["t1"]

    @property
    def unsafe(self):
        """Boolean mask of the levels at which some size of the grid overturns."""
        return self.largest_unsafe >= 0

    def to_dict(self):
        """``rocking oas --json`` (a new dict)."""
        return copy.deepcopy(self._raw)

    def plot(self, against="p", ax=None, fits=True):
        """The spectrum against ``p`` (Fig. 36), ``f`` (the transformed OAS, Fig. 37) or the
        ``size``, with the simplified spectra (Eq. 21, 30; the lines of Eq. 20, 28 against
        ``f``) when ``fits``. matplotlib (``pip install './python[plot]'``). Returns the axes."""
        from . import plot

        return plot.oas(self, against=against, ax=ax, fits=fits)

    def __repr__(self):
        t1 = self.t1
        return (f"Oas({self.record!r}: {len(self.levels)} levels x {len(self.sizes)} sizes, "
                f"t1 = {'-' if t1 is None else f'{t1:.4f} s'}, {self.summary['simulations']} simulations)")


def _set_oc_grid(result, raw):
    """The grid an overturning curve result (:class:`Oc`, :class:`rocking.ArchOc`; ``p`` already
    set) exposes, from its JSON: ``p_tp``, ``envelope`` (NaN: none), ``t_p`` per row and
    ``levels`` per column. Returns the first row's points (one per column)."""
    env = raw["envelope"]
    result.p_tp = np.array([e["p_tp"] for e in env], dtype=float)
    result.envelope = np.array([_optional(e["level"]) for e in env], dtype=float)
    rows, points = len(env), raw["points"]
    cols = len(points) // rows if rows else 0
    result.t_p = (np.array([points[i * cols]["t_p"] for i in range(rows)], dtype=float) if cols
                  else result.p_tp / result.p)
    result.levels = np.array([q["level"] for q in points[:cols]], dtype=float)
    return points[:cols]


def _oc_flags(raw, key, cols):
    """The boolean ``(rows, columns)`` array of the points' ``key`` (``unsafe``, ``collapses``)."""
    return np.array([q[key] for q in raw["points"]], dtype=bool).reshape(len(raw["envelope"]), cols)


class Oc:
    """An overturning curve (thesis Fig. 8, 33, 40): safe or unsafe on a grid of ``p t_p``
    (rows) × ``a_p / a_p,min`` (columns).

    ``p_tp``, ``t_p`` (s): the rows; ``levels``, ``a_p`` (m/s²): the columns; ``unsafe``: a
    boolean array ``(rows, columns)``; ``envelope``: per row the lowest unsafe level (NaN: none);
    ``p``, ``a_p_min``: of the equivalent block. :meth:`to_dict` is ``rocking oc --json``.
    """

    def __init__(self, raw):
        self._raw = raw
        self.shape = raw["shape"]
        self.blocks = raw["blocks"]
        self.p = raw["p"]
        self.a_p_min = raw["a_p_min"]
        columns = _set_oc_grid(self, raw)
        self.a_p = np.array([q["a_p"] for q in columns], dtype=float)
        self.unsafe = _oc_flags(raw, "unsafe", len(columns))

    def to_dict(self):
        """``rocking oc --json`` (a new dict)."""
        return copy.deepcopy(self._raw)

    def plot(self, ax=None):
        """The unsafe grid points and the envelope against ``p t_p`` (log axis), as Fig. 33a.
        matplotlib (``pip install './python[plot]'``). Returns the axes."""
        from . import plot

        return plot.oc(self, ax=ax)

    def __repr__(self):
        return (f"Oc({self.shape}, {self.blocks} block(s): {self.unsafe.shape[0]} x {self.unsafe.shape[1]} points, "
                f"{int(self.unsafe.sum())} unsafe)")


def _count(x):
    """A count given as any integer (numpy's too) is a Python int; anything else is values."""
    return int(x) if isinstance(x, numbers.Integral) else x


#: The arguments that are counts.
_INTEGRAL = ("blocks", "impacts", "threads", "voussoirs", "radius_n", "level_n", "ptp_n", "converge_halvings")

#: The arguments that may be None.
_OPTIONAL = ("tail", "threads", "converge_step")


def _numbers(**args):
    """A TypeError naming the argument that is not a number (``None`` allowed for ``tail``,
    ``threads`` and ``converge_step``): the extension's own message names it on some Python
    versions only."""
    progress = args.pop("progress", None)
    if progress is not None and not callable(progress):
        # It was called only once the sweep ran (TypeError: 'int' object is not callable).
        raise TypeError(f"progress: expected a callable progress(done, total) or None, got {type(progress).__name__}")
    for name, v in args.items():
        if v is None and name in _OPTIONAL:
            continue
        integral = name in _INTEGRAL
        kind = numbers.Integral if integral else numbers.Real
        if isinstance(v, bool) or not isinstance(v, kind):
            raise TypeError(f"{name}: expected {'an integer' if integral else 'a number'}, got {type(v).__name__}")
        if integral and not -2**63 <= v < 2**63:
            # The extension would raise Python's OverflowError: the package's one exception instead.
            raise _error(f"{name} = {v}: out of range")
        if name == "threads" and not 1 <= v <= _rocking.MAX_THREADS:
            # A negative count was Python's OverflowError (unnamed), a huge one started that many
            # threads (the extension checks it too).
            raise _error(f"threads = {v}: must be in 1..={_rocking.MAX_THREADS}")


def _simulation(impacts, dt_factor, tail, hermite, rk4, full_runs):
    """The settings of every simulation (the extension's ``Simulation``)."""
    return dict(impacts=impacts, dt_factor=dt_factor, tail=tail, hermite=bool(hermite), rk4=bool(rk4),
                full_runs=bool(full_runs))


def _grid_args(slenderness, levels, level_max, sizes, size_min, size_max, blocks, bisection, impacts, dt_factor,
               tail, hermite, rk4, full_runs, threads, progress):
    """``grid, simulation, threads, progress`` of the extension's ``_oas`` and ``_t1``."""
    _numbers(slenderness=slenderness, level_max=level_max, size_min=size_min, size_max=size_max, blocks=blocks,
             impacts=impacts, dt_factor=dt_factor, tail=tail, threads=threads, progress=progress)
    grid = dict(slenderness=slenderness, levels=_count(levels), level_max=level_max, sizes=_count(sizes),
                size_min=size_min, size_max=size_max, blocks=blocks, bisection=bool(bisection))
    return grid, _simulation(impacts, dt_factor, tail, hermite, rk4, full_runs), threads, progress


def oas(record, *, slenderness=12.0, levels=80, level_max=10.0, sizes=120, size_min=0.1, size_max=1000.0,
        blocks=1, bisection=False, impacts=1, dt_factor=1.0, tail=None, hermite=False, rk4=False,
        full_runs=False, band=False, converge_step=None, converge_halvings=_rocking.STEP_HALVINGS, threads=None,
        progress=None):
    """The overturning acceleration spectrum of a record (thesis 5.2, Fig. 36, 37, 43), as
    ``rocking oas RECORD --json``: for each level ``a_p / a_p,min`` the largest size ``R`` (half
    diagonal of the equivalent block, H/B = ``slenderness``) that the record scaled to
    ``level · a_p,min`` overturns, scanning the sizes from the largest (the thesis's search;
    ``bisection``: approximate, faster).

    ``record``: a :class:`rocking.Record` or the path of a record file (``.AT2`` in g, plain text
    in m/s², as the CLI reads it). Grid (the thesis's by default): ``levels`` a count (linear
    from 1 to ``level_max``) or the levels themselves; ``sizes`` a count (log-spaced from
    ``size_max`` down to ``size_min``, m) or the sizes, descending; ``blocks`` equal blocks in
    the column.
    {simulation}

    One OAS at the step rule by default (the step ``t1(..., converge_step=None)`` uses). As
    ``rocking oas --converge-step TOL --converge-halvings N --band``: ``converge_step=TOL`` the
    spectrum converged in the time step as :func:`t1` computes it (the finest step's, with
    ``t1_steps`` and ``step_converged``); ``band=True`` adds ``t1``'s band at the spectrum's step
    (``t1_range``, ``t1_conservative``, ``band``).

    Returns an :class:`Oas`."""
    _numbers(converge_step=converge_step, converge_halvings=converge_halvings)
    raw, i_cr = _rocking._oas(record, *_grid_args(slenderness, levels, level_max, sizes, size_min, size_max, blocks,
                                                  bisection, impacts, dt_factor, tail, hermite, rk4, full_runs,
                                                  threads, progress),
                              bool(band), None if converge_step is None else float(converge_step),
                              int(converge_halvings))
    return Oas(raw, i_cr)


oas.__doc__ = oas.__doc__.replace("{simulation}", _SIMULATION_DOC.strip())


def t1(records, *, slenderness=12.0, levels=80, level_max=10.0, sizes=120, size_min=0.1, size_max=1000.0,
       blocks=1, bisection=False, impacts=1, dt_factor=1.0, tail=None, hermite=False, rk4=False,
       full_runs=False, band=False, converge_step=_rocking.STEP_TOLERANCE,
       converge_halvings=_rocking.STEP_HALVINGS, threads=None, progress=None):
    """The replacement impulse duration ``t_1 = i_cr / f_min`` (thesis Eq. 20) of a record, with
    the inclined line of Eq. 28 (``t1_prime``, ``beta``) and ``f_min``, each from the record's OAS
    (same options as :func:`oas`), as ``rocking t1 RECORD --json``: by default converged in the
    time step, as the CLI.

    ``records``: a :class:`rocking.Record` or a path: returns one dict (``record``, ``t1``,
    ``t1_prime``, ``beta``, ``f_min``, ``level_at_f_min``, ``size_at_f_min``, ``simulations``,
    ``seconds``, ``file`` (the path; None for a Record), ``slenderness``, ``blocks``,
    ``dt_factor``, ``search``, ``t_p`` — the replacement sine duration of Eq. 25); a list of them
    (or a tuple, a numpy array, an iterator such as ``Path.glob``'s): a list of dicts, in order.

    The time step (``docs/t1-accuracy.md``), as ``rocking t1``'s ``--converge-step``,
    ``--converge-halvings`` and ``--single-step``:

    - ``converge_step=0.1`` (the default, ``TOL`` ≥ 0): the OAS at the step rule (× ``dt_factor``),
      again at half the step, and again, until two successive steps give ``t1`` within TOL
      (``max/min − 1``) or after ``converge_halvings`` halvings (≥ 1, default 4); the row is the
      finest step's (its ``dt_factor`` too), with ``t1_steps`` (``[dt factor, t1]`` of each step)
      and ``step_converged``. Two OAS per record at least (about 3× one OAS).
    - ``converge_step=None``: one OAS at the step rule (``--single-step``; ``converge_halvings``
      unused), the step :func:`oas` uses: faster, ``t1`` within 10 % of the
      converged one on 95 of the 100 FEMA P695 records.

    How far to trust ``t1``: ``band=True`` (``--band``) also computes the OAS again with half
    the row's time step, with the level and the size grids shifted by half a cell and with the
    other event locator, each at the row's step (the converged one, or the rule's with
    ``converge_step=None``; four OAS more per record); adds ``t1_range`` ``[min, max]``,
    ``t1_conservative`` (``i_cr / f_min`` of the envelope of the five spectra) and ``band``
    (each one's ``t1``, by name, ``nominal`` the row's; None where nothing overturned).

    {simulation}

    ``progress`` counts the levels of the OAS under way: with several records, several steps or
    ``band`` it starts again with each spectrum."""
    _numbers(converge_step=converge_step, converge_halvings=converge_halvings)
    items, single = _paths(records)
    rows = _rocking._t1(items, *_grid_args(slenderness, levels, level_max, sizes, size_min, size_max, blocks,
                                           bisection, impacts, dt_factor, tail, hermite, rk4, full_runs, threads,
                                           progress),
                        bool(band), None if converge_step is None else float(converge_step), int(converge_halvings))
    return rows[0] if single else rows


t1.__doc__ = t1.__doc__.replace("{simulation}", _SIMULATION_DOC.strip())


def oc(shape="half-sine", *, blocks=1, slenderness=12.0, size=1.0, ptp=40, ptp_min=0.1, ptp_max=10.0, levels=40,
       level_max=10.0, impacts=1, dt_factor=1.0, tail=None, hermite=False, rk4=False, full_runs=False, threads=None,
       progress=None):
    """The overturning curve of a pulse shape (thesis Fig. 8, 33, 40), as ``rocking oc --json``:
    safe or unsafe for a column of ``blocks`` equal blocks (size ``R``, m, of the equivalent block
    of H/B = ``slenderness``) on a grid of ``p t_p`` × ``a_p / a_p,min``.

    ``shape``: ``half-sine``, ``full-sine``, ``three-half-sines``, ``rectangular``,
    ``triangular`` or ``ricker`` (``t_p``: the duration of one lobe; the Ricker wavelet's peak
    frequency is ``1/t_p``). ``ptp``: a count (log-spaced from ``ptp_min`` to ``ptp_max``) or the
    values of ``p t_p``; ``levels``: a count (linear from 1 to ``level_max``) or the levels.
    {simulation}

    Returns an :class:`Oc`."""
    _numbers(blocks=blocks, slenderness=slenderness, size=size, ptp_min=ptp_min, ptp_max=ptp_max, level_max=level_max,
             impacts=impacts, dt_factor=dt_factor, tail=tail, threads=threads, progress=progress)
    return Oc(_rocking._oc(shape, blocks, slenderness, size, _count(ptp), ptp_min, ptp_max, _count(levels), level_max,
                           _simulation(impacts, dt_factor, tail, hermite, rk4, full_runs), threads, progress))


oc.__doc__ = oc.__doc__.replace("{simulation}", _SIMULATION_DOC.strip())


def _paths(records):
    """``records`` (one, or a list, tuple, array or iterator of them: ``Path.glob`` gives a
    generator) as the extension's list, and whether it was one."""
    if isinstance(records, np.ndarray):
        records = records.tolist()
    single = not isinstance(records, (list, tuple, Iterator))
    items = [records] if single else list(records)
    return [os.fspath(r) if isinstance(r, os.PathLike) else r for r in items], single


def tp(records):
    """The replacement sine duration ``t_p = I_max / (F a_max)`` (thesis 5.3.5, Eq. 25, Fig. 52,
    ``F = 2/π``) of a record, as ``rocking tp RECORD --json``: no simulation, milliseconds.

    ``records``: a :class:`rocking.Record` or a path: returns one dict (``record``, ``file``
    (None for a Record), ``a_max`` (m/s², the peak), ``i_max`` (m/s, the largest single-lobe
    impulse), ``lobe_start``, ``lobe_end`` (s, that lobe), ``fullness`` (``F``), ``t_p`` (s)); a
    list of them (or any iterator): a list of dicts, in order."""
    items, single = _paths(records)
    rows = _rocking._tp(items)
    return rows[0] if single else rows


class _SuiteResult:
    """What a suite result (:class:`Suite`, :class:`rocking.ArchSuite`) shares: its design ``t_1``
    per fractile, the CLI's JSON, the plot and the repr. A subclass sets ``_raw``, ``name``,
    ``records``, ``characteristic``, ``_command`` (the CLI command) and ``_plot`` (the name of
    its function in :mod:`rocking.plot`)."""

    @property
    def design_t1(self):
        """``{fractile: design t_1 (s) or None}``."""
        return {c["fractile"]: c["design_t1"] for c in self.characteristic}

    def to_dict(self):
        """The JSON of the CLI's ``--json`` (a new dict)."""
        return copy.deepcopy(self._raw)

    def plot(self, against="p", ax=None):
        """The characteristic OAS of each fractile against ``p`` or ``f`` (a column suite also
        draws the records' OAS). matplotlib (``pip install './python[plot]'``). Returns the axes."""
        from . import plot

        return getattr(plot, self._plot)(self, against=against, ax=ax)

    def __repr__(self):
        t1 = ", ".join(f"{q}: {'-' if t is None else f'{t:.4f} s'}" for q, t in self.design_t1.items())
        return f"{type(self).__name__}({self.name!r}: {len(self.records)} records, design t1 {{{t1}}})"


class Suite(_SuiteResult):
    """The design curves of a record suite (thesis 5.3.1–5.3.2, Fig. 44, 47–49), as ``rocking
    suite --json``: ``records`` every record's :class:`Oas` (by name), ``characteristic`` one
    dict per fractile (``fractile``, ``design_t1`` — the suite's ``t_1 = i_cr / f_min`` of the
    characteristic transformed OAS, ``f_min``, ``record_t1_fractile``, ``oas`` — the
    characteristic OAS as an :class:`Oas`, ``violations`` — Eq. 21, 29, 30 with these parameters
    checked against every record below levels 4, 6, 12 and at every level), ``hulls`` (the
    normalised convex hulls of the transformed OAS, Fig. 49), ``own_parameters`` (the same check
    with each record's own ``t_1``, ``t_1'``, ``β``), ``seconds`` (the records' wall times).
    :meth:`to_dict` is the JSON of ``rocking suite --json``."""

    _plot = "suite"

    def __init__(self, raw, records_i_cr, characteristic_i_cr):
        self._raw = raw
        self.name = raw["name"]
        self.records = [Oas(r, i) for r, i in zip(raw["records"], records_i_cr)]
        self.characteristic = []
        for c, i in zip(raw["characteristic"], characteristic_i_cr):
            c = dict(c)
            c["oas"] = Oas(c["oas"], i)
            self.characteristic.append(c)
        self.hulls = raw["hulls"]
        self.own_parameters = raw["own_parameters"]
        self.seconds = raw["seconds"]


def _report_json(spectrum, cls, what):
    """The JSON text of one OAS of a suite: an ``Oas``/``ArchOas`` result or its ``to_dict()``."""
    if isinstance(spectrum, cls):
        raw = spectrum._raw
    elif isinstance(spectrum, dict):
        raw = spectrum
    else:
        raise TypeError(f"spectra: expected {what} or its to_dict(), got {type(spectrum).__name__}")
    return json.dumps(raw, allow_nan=False)


def suite(spectra, *, name="suite", fractiles=(0.5, 0.84)):
    """The suite procedure of thesis 5.3.1 on the OAS of a record suite: the characteristic OAS
    at each fractile with its design ``t_1``, the normalised convex hulls of the transformed OAS,
    and Eq. 21, 29, 30 checked against every record — as ``rocking suite --merge`` on the
    records' ``rocking oas --json`` reports.

    ``spectra``: the records' :class:`Oas` (from :func:`oas`, one record each, on one grid), or
    their :meth:`Oas.to_dict` (e.g. ``json.load`` of ``rocking oas --json`` files); the OAS are
    computed once and the analysis takes milliseconds. ``name``: the suite's name in the report;
    ``fractiles``: each in (0, 1]. Returns a :class:`Suite`."""
    texts = [_report_json(s, Oas, "an Oas") for s in spectra]
    qs = [fractiles] if isinstance(fractiles, numbers.Real) else list(fractiles)
    for k, q in enumerate(qs):
        if isinstance(q, bool) or not isinstance(q, numbers.Real):
            raise TypeError(f"fractiles[{k}]: expected a number, got {type(q).__name__}")
    return Suite(*_rocking._suite(texts, str(name), [float(q) for q in qs]))
