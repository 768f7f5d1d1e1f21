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


class Simulation:
    """The result of :func:`simulate`: what ``rocking simulate`` writes, in memory.

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
        self.title = raw["title"]
        self.t = raw["t"]
        self.angles = raw["angles"]
        self.rates = raw["rates"]
        self.block_rotations = raw["block_rotations"]
        self.statuses = raw["statuses"]
        self.dof_angles = raw["dof_angles"]
        self.dof_rates = raw["dof_rates"]
        self.events = raw["events"]
        self.summary = raw["summary"]

    @property
    def overturned(self):
        """Whether the column overturned (static tipping; fallen with ``continue_until_fallen``)."""
        return self.summary["overturned"]

    @property
    def t_end(self):
        """Time reached (s)."""
        return self.summary["t_end"]

    @property
    def stop_reason(self):
        """Why the run stopped: ``duration``, ``overturned``, ``fallen``, ``sliding``, ``tension``,
        ``too_many_events``, ``at_rest`` or ``cannot_tip``."""
        return self.summary["stop_reason"]

    def events_of(self, kind):
        """The events of one kind (``opening``, ``impact``, ``settled``, ``overturned``, …)."""
        return [e for e in self.events if e["kind"] == kind]

    def plot(self, ax=None, events=True):
        """Block rotations against time with the events marked (matplotlib, ``pip install
        './python[plot]'``). Returns the axes."""
        from . import plot

        return plot.simulation(self, ax=ax, events=events)

    def __repr__(self):
        s = self.summary
        return (f"Simulation({self.title!r}: {s['stop_reason']} at t = {s['t_end']:.4f} s, "
                f"{s['impacts']} impacts, {len(self.events)} events, {len(self.t)} samples)")


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

    The simulation runs without the GIL (other Python threads go on) but cannot be interrupted
    midway. Returns a :class:`Simulation`; an invalid scene raises :class:`rocking.RockingError`
    naming the field.
    """
    if isinstance(scene, (str, os.PathLike)):
        return Simulation(_rocking._simulate(path=os.fspath(scene)))
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
    return Simulation(_rocking._simulate(text=text, base=os.fspath(base), record=record))
