"""rocking.simulate: a scene through the reference driver (thesis 3.3, SPEC §5), as ``rocking
simulate`` runs it, with its outputs as numpy arrays and Python dicts."""
import json
import math
import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from . import _rocking
from ._errors import error as _error
from ._rocking import Pulse, Record


class _Run:
    """What every result of :func:`simulate` has: the title, the scheme that ran it, the sample
    times, the events and the summary."""

    def __init__(self, raw):
        self.title = raw["title"]
        self.scheme = raw["scheme"]
        self.t = raw["t"]
        self.events = raw["events"]
        self.summary = raw["summary"]

    @property
    def t_end(self):
        """Time reached (s)."""
        return self.summary["t_end"]

    def events_of(self, kind):
        """The events of one kind (``opening``, ``impact``, ``settled``, ``overturned``, …; the
        contact scheme's ``slip_start``, ``slip_stop``, ``lift_off``, ``landing``,
        ``scheme_switch``; a loop's ``closing``, ``locked``, ``collapsed``)."""
        return [e for e in self.events if e["kind"] == kind]


class _ColumnRun(_Run):
    """A column's run (either scheme): block rotations, the verdict and the stop."""

    def __init__(self, raw):
        super().__init__(raw)
        self.block_rotations = raw["block_rotations"]

    @property
    def overturned(self):
        """Whether the column overturned (static tipping; fallen with ``continue_until_fallen``;
        a drum slid off, in the contact scheme)."""
        return self.summary["overturned"]

    @property
    def stop_reason(self):
        """Why the run stopped: ``duration``, ``overturned``, ``fallen``, ``sliding``, ``tension``,
        ``too_many_events``, ``at_rest`` or ``cannot_tip`` (the contact scheme also ``slid_off``)."""
        return self.summary["stop_reason"]

    def plot(self, ax=None, events=True):
        """Block rotations against time with the events marked (matplotlib, ``pip install
        './python[plot]'``). Returns the axes."""
        from . import plot

        return plot.simulation(self, ax=ax, events=events)

    def __repr__(self):
        s = self.summary
        return (f"{type(self).__name__}({self.title!r}: {s['stop_reason']} at t = {s['t_end']:.4f} s, "
                f"{s['impacts']} impacts, {len(self.events)} events, {len(self.t)} samples)")


class Simulation(_ColumnRun):
    """The result of :func:`simulate` for a scene run by the reference driver (``scheme`` is
    ``"event_driven"``): what ``rocking simulate`` writes, in memory.

    History (one row per kept step, ``output.every``; empty arrays when ``output.history`` is
    false), the columns of ``history.csv``:

    - ``t`` (s), shape ``(samples,)``;
    - ``angles``, ``rates``: the signed interface angles ``phĭ_k + phî_k`` (rad) and their rates
      (rad/s), shape ``(samples, n)``;
    - ``block_rotations``: the absolute rotation of each block (rad), ``(samples, n)``;
    - ``statuses``: each interface's status (−1, 0, +1; int8), ``(samples, n)``;
    - ``dof_angles``, ``dof_rates``: the ``2n`` DOFs ``[phĭ_0 … phĭ_{n-1}, phî_0 … phî_{n-1}]``
      (SPEC §1), ``(samples, 2n)``.

    ``events``: a list of dicts, the objects of ``events.jsonl`` (``t``, ``kind``, ``interface``,
    ``kinetic_before``, ``kinetic_after``, ``statuses_before``, ``statuses_after``, ``report``).
    ``summary``: the dict of ``summary.json`` (``scene`` is the file's path, None for a dict).
    """

    def __init__(self, raw):
        super().__init__(raw)
        self.angles = raw["angles"]
        self.rates = raw["rates"]
        self.statuses = raw["statuses"]
        self.dof_angles = raw["dof_angles"]
        self.dof_rates = raw["dof_rates"]


class ContactSimulation(_ColumnRun):
    """The result of :func:`simulate` for a scene run by the contact scheme (joints that slide or
    fly: ``scheme`` ``"moreau"`` or ``"auto"``, ``on_sliding: "slide"``, ``on_tension: "fly"``;
    docs/multidrum.md), as ``rocking simulate`` writes it.

    History (empty arrays when ``output.history`` is false), the columns of ``history.csv``, each
    ``(samples, n)`` but ``t``:

    - ``t`` (s), shape ``(samples,)``;
    - ``x``, ``y``: each drum's centre, displacement from its place in the straight column
      at rest (m; ``summary["peak_top_displacement"]`` is the top's largest |x|);
    - ``block_rotations``: each drum's rotation (rad, counter-clockwise positive);
    - ``slips``: each joint's slip (m, + when the upper face moved to +x).

    ``events``: the objects of ``events.jsonl`` (``t``, ``kind``, ``joint``; a ``scheme_switch``
    with ``from``, ``to``, ``why``, ``kinetic_before``, ``kinetic_after``, ``slip_dropped``).
    ``summary``: the dict of ``summary.json`` (``peak_slip``, ``residual_slip``,
    ``peak_top_displacement``, ``modes_end``, the energy accounts, …).
    """

    def __init__(self, raw):
        super().__init__(raw)
        self.x = raw["x"]
        self.y = raw["y"]
        self.slips = raw["slips"]

    @property
    def residual_slip(self):
        """Each joint's slip at the end (m, signed)."""
        return np.asarray(self.summary["residual_slip"])

    @property
    def peak_slip(self):
        """Each joint's largest absolute slip (m)."""
        return np.asarray(self.summary["peak_slip"])

    def plot(self, ax=None, events=True):
        """Drum rotations against time with the impacts, lift-offs, landings and the overturning
        marked (matplotlib; as ``rocking simulate --plot FILE``). Returns the axes."""
        from . import plot

        return plot.contact_simulation(self, ax=ax, events=events)

    def plot_slips(self, ax=None, events=True):
        """The joints' slips (mm) against time with the slip starts and stops marked (as the
        ``FILE_slips`` of ``rocking simulate --plot FILE``). Returns the axes."""
        from . import plot

        return plot.contact_slips(self, ax=ax, events=events)


class LoopSimulation(_Run):
    """The result of :func:`simulate` for a closed chain (an ``"arch"`` or ``"colonnade"`` scene,
    ``scheme`` ``"loop"``; docs/arches.md), as ``rocking simulate`` writes it.

    History (empty arrays when ``output.history`` is false): ``t`` (s), ``(samples,)``, and
    ``angles``, each joint's signed angle ``phĭ_k + phî_k`` (rad), ``(samples, joints)`` (the
    columns of ``history.csv``). ``events``: the objects of ``events.jsonl`` (``t``, ``kind``:
    opening, closing, locked, settled, collapsed; ``statuses`` after; a closing's ``joints``,
    ``kinetic_before``, ``kinetic_after``). ``summary``: ``summary.json`` (``collapsed``,
    ``peak_angle``, ``hinges`` as ``[joint, face]``, ``max_closure_residual``, ``energy``: the
    ground's work, the kinetic energy lost at closings and settlings, the kinetic energy at the
    start and end, the change of potential energy, and the balance's ``residual``, …).
    """

    def __init__(self, raw):
        super().__init__(raw)
        self.angles = raw["angles"]

    @property
    def collapsed(self):
        """Whether the chain collapsed (passed its point of no return, docs/arches.md)."""
        return self.summary["collapsed"]

    @property
    def hinges(self):
        """Every ``(joint, face)`` that opened: face −1 about the joint's R corner (an arch's
        intrados), +1 about L (extrados)."""
        return [tuple(h) for h in self.summary["hinges"]]

    def plot(self, ax=None, events=True):
        """The joint angles that moved against time, events marked (matplotlib). Returns the
        axes."""
        from . import plot

        return plot.loop_simulation(self, ax=ax, events=events)

    def __repr__(self):
        s = self.summary
        verdict = "collapsed" if s["collapsed"] else "end of duration"
        return (f"LoopSimulation({self.title!r}: {verdict} at t = {s['t_end']:.4f} s, "
                f"{len(self.events)} events, peak joint angle {s['peak_angle']:.6f} rad)")


_RESULTS = {"event_driven": Simulation, "loop": LoopSimulation}


def _result(raw):
    return _RESULTS.get(raw["scheme"], ContactSimulation)(raw)


def _json_value(x):
    """numpy scalars and arrays as JSON values (json.dumps calls this for what it cannot write)."""
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, os.PathLike):
        return os.fspath(x)
    raise TypeError(f"scene: {type(x).__name__} is not a JSON value")


def _check_finite(value, path):
    """A RockingError naming the field of the first NaN or infinity (JSON has none)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]  # a 0-d array is its number (json.dumps writes it as one)
    if isinstance(value, Mapping):
        for k, v in value.items():
            _check_finite(v, f"{path}.{k}" if path else str(k))
    elif isinstance(value, (list, tuple, np.ndarray)):
        for i, v in enumerate(value):
            _check_finite(v, f"{path}[{i}]")
    elif isinstance(value, (float, np.floating)) and not math.isfinite(value):
        raise _error(f"{path} = {value}: must be a finite number")


def simulate(scene, base=None):
    """Runs a scene through the reference driver (thesis 3.3; SPEC §5) as ``rocking simulate``
    does: the same schema, parser and results (``events`` as ``events.jsonl``, ``summary`` as
    ``summary.json``, the history of ``history.csv`` as arrays).

    ``scene``: the path of a scene file (record paths relative to the file), or a dict with the
    same schema (``blocks``, ``initial_angles``, ``excitation``, ``impacts``, ``duration``,
    ``dt``, ``integrator``, ``locator``, ``solver``, ``friction``, ``gravity``,
    ``exact_velocity_terms``, ``continue_until_fallen``, ``output``, ``title``; see
    ``examples/scenes`` and ``rocking::scene``), whose record paths are relative to ``base``
    (default: the current directory). In a dict, ``excitation`` may also be a
    :class:`rocking.Pulse` or a :class:`rocking.Record`, and numbers may be numpy values.

    A scene that chooses the contact scheme (``scheme`` ``"moreau"`` or ``"auto"``,
    ``on_sliding: "slide"``, ``on_tension: "fly"``, ``friction``; docs/multidrum.md) runs it as
    ``rocking simulate`` does and returns a :class:`ContactSimulation` (drum positions, rotations
    and joint slips); a closed chain (``"arch"`` or ``"colonnade"`` in place of ``blocks``)
    runs the loop driver and returns a :class:`LoopSimulation` (joint angles, hinges).

    The simulation runs without the GIL (other Python threads go on); Ctrl-C interrupts a
    column's run midway (``KeyboardInterrupt``; a loop's runs to its end). Returns a :class:`Simulation` (or :class:`ContactSimulation`, :class:`LoopSimulation`); an invalid scene raises
    :class:`rocking.RockingError` naming the field.
    """
    if isinstance(scene, (str, os.PathLike)):
        if base is not None:
            # It was ignored: a file's record paths start at the file.
            raise TypeError("base: applies to a dict scene; a scene file's record paths are "
                            "relative to the file")
        return _result(_rocking._simulate(path=os.fspath(scene)))
    if not isinstance(scene, Mapping):
        raise TypeError(f"scene: expected a dict or the path of a scene file, got {type(scene).__name__}")
    spec = dict(scene)
    record = None
    excitation = spec.get("excitation")
    if isinstance(excitation, Pulse):
        spec["excitation"] = excitation.to_dict()
    elif isinstance(excitation, Record):
        spec["excitation"], record = {"type": "none"}, excitation
    _check_finite(spec, "")
    text = json.dumps(spec, default=_json_value)
    base = Path.cwd() if base is None else Path(base)
    return _result(_rocking._simulate(text=text, base=os.fspath(base), record=record))
