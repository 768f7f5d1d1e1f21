"""Spectra of voussoir arches (issue 15, item 5; ``docs/arch-spectra.md``): ``arch_oas``,
``arch_oc`` and ``arch_suite``, with the options and the JSON of ``rocking arch oas``, ``rocking
arch oc`` and ``rocking arch suite``, and numpy arrays out.

An arch family is its ``thickness_ratio`` t/R, ``embrace`` angle (degrees) and ``voussoirs``;
its size is the centre-line radius R. The level is ``a_p / (λ g)``, ``λ`` the static collapse
multiplier; ``p`` is that of the onset mechanism (``p = p_at_1m / √R``); unsafe is the loop
driver's collapse. The sweeps run as :func:`rocking.oas`'s: parallel, without the GIL,
interruptible with Ctrl-C between levels (OAS) or pulse durations (OC), the same results with
any number of threads."""
import copy
import numbers
import os

import numpy as np

from . import _rocking
from ._spectra import (_SuiteResult, _numbers, _oc_flags, _report_json, _set_level_arrays,
                       _set_oc_grid)

_FAMILY_DOC = """
    The arch family (as the CLI's options): ``thickness_ratio`` t/R, ``embrace`` the angle of
    embrace in degrees (180: semicircular), ``voussoirs``; ``dt_factor`` a factor on the time
    step rule (``min(Δt_record/4, t_p/100, 1/(100 p))``, ``p`` of the onset mechanism).
    ``threads``: rayon threads, 1 to 1024 (default every core; results identical). ``progress``: a callable
    ``progress(done, total)``."""


def _family(thickness_ratio, embrace, voussoirs, dt_factor):
    return dict(thickness_ratio=thickness_ratio, embrace=embrace, voussoirs=voussoirs, dt_factor=dt_factor)


class _ArchResult:
    """The arch family and onset of a result (``shape``, ``onset`` of the JSON)."""

    def _family(self, raw):
        self._raw = raw
        self.shape = raw["shape"]
        self.onset = raw["onset"]
        self.thickness_ratio = self.shape["thickness_ratio"]
        self.embrace_angle = self.shape["embrace_angle"]
        self.voussoirs = self.shape["voussoirs"]
        self.lambda_ = self.onset["lambda"]
        self.p_at_1m = self.onset["p_at_1m"]
        self.runs = raw["runs"]
        self.seconds = raw["seconds"]

    def to_dict(self):
        """The CLI's JSON (a new dict)."""
        return copy.deepcopy(self._raw)


class ArchOas(_ArchResult):
    """The overturning acceleration spectrum of an arch family for a record: for each level
    ``a_p / (λ g)`` the largest radius ``R`` of the grid that the scaled record collapses.

    Arrays, one entry per level: ``levels``, ``largest_unsafe`` (index into ``sizes``, −1 when no
    radius collapses), ``size`` (m), ``p`` (1/s, onset mechanism) and ``f = p · level`` (NaN when
    nothing collapses), ``simulations``. ``sizes``: the radii (m, descending). ``t1``: the arch's
    own ``t_1 = 1/f_min`` (s, Eq. 20/31 with ``i_cr ≈ 1``), with ``f_min``, ``level_at_f_min``,
    ``size_at_f_min``; ``check``: the single-block rule with the ``t1`` given (``t1``,
    ``violations``, ``conservative``) or None. ``shape``, ``onset`` (``lambda``, ``hinges``,
    ``p_at_1m``; also ``lambda_``, ``p_at_1m``), ``runs`` (collapsed / survived / never moved,
    every collapse, every failed run), ``seconds`` (wall time). :meth:`to_dict` is ``rocking
    arch oas --json``."""

    def __init__(self, raw):
        self._family(raw)
        self.record = raw["record"]
        self.gravity = raw["gravity"]
        _set_level_arrays(self, raw)
        self.t1 = raw["t1"]
        self.f_min = raw["f_min"]
        self.level_at_f_min = raw["level_at_f_min"]
        self.size_at_f_min = raw["size_at_f_min"]
        self.check = raw["check"]

    @property
    def unsafe(self):
        """Boolean mask of the levels at which some radius of the grid collapses."""
        return self.largest_unsafe >= 0

    def plot(self, against="p", ax=None, fits=True):
        """The spectrum against ``p`` of the onset mechanism or against ``f`` (the transformed
        OAS), with Eq. 21 (``i_cr = 1``) of the arch's own ``t1`` and of the checked one when
        ``fits`` (as ``rocking arch oas --svg``). matplotlib (``pip install './python[plot]'``).
        Returns the axes."""
        from . import plot

        return plot.arch_oas(self, against=against, ax=ax, fits=fits)

    def __repr__(self):
        t1 = self.t1
        return (f"ArchOas({self.record!r}: t/R = {self.thickness_ratio}, {self.voussoirs} voussoirs, "
                f"{len(self.levels)} levels x {len(self.sizes)} radii, "
                f"t1 = {'-' if t1 is None else f'{t1:.4f} s'})")


class ArchOc(_ArchResult):
    """The overturning curve of an arch under a pulse: collapse on a grid of ``p t_p`` (rows) ×
    ``a_p / (λ g)`` (columns), ``p`` of the onset mechanism of the arch of ``radius``.

    ``p_tp``, ``t_p`` (s): the rows; ``levels``: the columns; ``collapses``: a boolean array
    ``(rows, columns)`` (False also where a run failed: ``runs["failures"]``); ``envelope``: per
    row the lowest level that collapses (NaN: none); ``pulse``, ``radius``, ``p``; ``shape``,
    ``onset``, ``runs``, ``seconds`` as :class:`ArchOas`. :meth:`to_dict` is ``rocking arch oc
    --json``."""

    def __init__(self, raw):
        self._family(raw)
        self.pulse = raw["pulse"]
        self.radius = raw["radius"]
        self.p = raw["p"]
        columns = _set_oc_grid(self, raw)
        self.collapses = _oc_flags(raw, "collapses", len(columns))

    def plot(self, ax=None):
        """The points that collapse and the envelope against ``p t_p`` (log axis), as ``rocking
        arch oc --svg``. matplotlib (``pip install './python[plot]'``). Returns the axes."""
        from . import plot

        return plot.arch_oc(self, ax=ax)

    def __repr__(self):
        return (f"ArchOc({self.pulse}, R = {self.radius} m, t/R = {self.thickness_ratio}, {self.voussoirs} voussoirs: "
                f"{self.collapses.shape[0]} x {self.collapses.shape[1]} points, {int(self.collapses.sum())} collapse)")


def arch_oas(record, *, thickness_ratio=0.15, embrace=180.0, voussoirs=20, dt_factor=1.0, radius_max=100.0,
             radius_min=1.0, radius_n=12, level_min=1.5, level_max=6.0, level_n=10, t1=None, threads=None,
             progress=None):
    """The overturning acceleration spectrum of an arch family for a record, as ``rocking arch
    oas RECORD --json``: for each of ``level_n`` levels ``a_p / (λ g)`` linear from ``level_min``
    to ``level_max``, the largest of ``radius_n`` radii (log-spaced from ``radius_max`` down to
    ``radius_min``, m) that the record scaled to ``level · λ g`` collapses, scanned from the
    largest. ``t1`` (s): check the single-block design rule (Eq. 21, ``i_cr ≈ 1``) with this
    ``t_1`` (e.g. the record's, from :func:`rocking.t1`) against the arch OAS.

    ``record``: a :class:`rocking.Record` or the path of a record file (``.AT2`` in g, plain text
    in m/s²).
    {family}

    Returns an :class:`ArchOas`."""
    _numbers(thickness_ratio=thickness_ratio, embrace=embrace, voussoirs=voussoirs, dt_factor=dt_factor,
             radius_max=radius_max, radius_min=radius_min, radius_n=radius_n, level_min=level_min,
             level_max=level_max, level_n=level_n, threads=threads, progress=progress)
    if t1 is not None:
        _numbers(t1=t1)
    record = os.fspath(record) if isinstance(record, os.PathLike) else record
    return ArchOas(_rocking._arch_oas(record, _family(thickness_ratio, embrace, int(voussoirs), dt_factor),
                                      radius_max, radius_min, int(radius_n), level_min, level_max, int(level_n), t1,
                                      threads, progress))


arch_oas.__doc__ = arch_oas.__doc__.replace("{family}", _FAMILY_DOC.strip())


def arch_oc(shape="half-sine", *, thickness_ratio=0.15, embrace=180.0, voussoirs=20, dt_factor=1.0, radius=5.0,
            ptp_min=0.5, ptp_max=10.0, ptp_n=8, level_max=6.0, level_n=11, threads=None, progress=None):
    """The overturning curve of the arch of ``radius`` (m) under a pulse, as ``rocking arch oc
    --json``: collapse on a grid of ``ptp_n`` values of ``p t_p`` (log-spaced from ``ptp_min`` to
    ``ptp_max``, ``p`` of the onset mechanism) × ``level_n`` levels ``a_p / (λ g)`` (linear from
    1 to ``level_max``).

    ``shape``: ``half-sine``, ``full-sine``, ``three-half-sines``, ``rectangular``,
    ``triangular`` or ``ricker``.
    {family}

    Returns an :class:`ArchOc`."""
    _numbers(thickness_ratio=thickness_ratio, embrace=embrace, voussoirs=voussoirs, dt_factor=dt_factor,
             radius=radius, ptp_min=ptp_min, ptp_max=ptp_max, ptp_n=ptp_n, level_max=level_max, level_n=level_n,
             threads=threads, progress=progress)
    return ArchOc(_rocking._arch_oc(shape, _family(thickness_ratio, embrace, int(voussoirs), dt_factor), radius,
                                    ptp_min, ptp_max, int(ptp_n), level_max, int(level_n), threads, progress))


arch_oc.__doc__ = arch_oc.__doc__.replace("{family}", _FAMILY_DOC.strip())


class ArchSuite(_SuiteResult):
    """The suite procedure on arch OAS, as ``rocking arch suite --json``: ``records`` one dict per
    record (``record``, its arch ``t1``, ``f_min``, ``level_at_f_min``, ``size_at_f_min``,
    ``block_t1`` — the single-block ``t_1`` its OAS was checked with, or None), by name;
    ``characteristic`` one dict per fractile (``fractile``, ``design_t1`` — ``1/f_min`` of the
    characteristic arch OAS, ``f_min``, ``level_at_f_min``, ``size_at_f_min``,
    ``record_t1_fractile``, ``oas`` — the characteristic arch OAS as an :class:`ArchOas`,
    ``check`` — the design ``t_1`` scored against every record: points and records predicted safe
    that collapse, ratios); ``block_rule``: each record's single-block ``t_1`` scored against its
    own arch OAS; ``name``, ``shape``, ``onset``. :meth:`to_dict` is the CLI's JSON."""

    _plot = "arch_suite"

    def __init__(self, raw):
        self._raw = raw
        self.name = raw["name"]
        self.shape = raw["shape"]
        self.onset = raw["onset"]
        self.records = raw["records"]
        self.characteristic = [dict(c, oas=ArchOas(c["oas"])) for c in raw["characteristic"]]
        self.block_rule = raw["block_rule"]


def arch_suite(spectra, *, name="arch suite", fractiles=(0.5, 0.84)):
    """The suite procedure on arch OAS (thesis 5.3.1 on arches), as ``rocking arch suite
    --json``: the characteristic arch OAS at each fractile, its design ``t_1 = 1/f_min``, that
    ``t_1`` checked against every record, and each record's single-block ``t_1`` (the ``t1`` its
    :func:`arch_oas` was checked with) checked against its own arch OAS.

    ``spectra``: the records' :class:`ArchOas` (one record each, one arch and grid) or their
    :meth:`ArchOas.to_dict` (e.g. ``json.load`` of ``rocking arch oas`` files); the spectra are
    computed once and the suite takes milliseconds. ``fractiles``: each in (0, 1]. Returns an
    :class:`ArchSuite`."""
    texts = [_report_json(s, ArchOas, "an ArchOas") for s in spectra]
    qs = [fractiles] if isinstance(fractiles, numbers.Real) else list(fractiles)
    for k, q in enumerate(qs):
        if isinstance(q, bool) or not isinstance(q, numbers.Real):
            raise TypeError(f"fractiles[{k}]: expected a number, got {type(q).__name__}")
    return ArchSuite(_rocking._arch_suite(texts, str(name), [float(q) for q in qs]))
