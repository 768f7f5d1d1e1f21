"""rocking.opensees: an openseespy model of a column of blocks, with every opening and impact
decision delegated to the library (the recipe of docs/opensees.md).

OpenSees integrates the column — blocks as stiff corotational beams carrying the three mass
points of thesis Appendix C, compression-only contact springs at the corners of every joint, a
no-slip tie at the pivot — and the library decides:

- **openings** happen in OpenSees (a corner's spring goes slack); at each one the library's
  opening model (thesis 3.2.2) is asked on OpenSees's own matrices, and its choice is recorded
  next to what OpenSees did;
- **impacts**: the step is cut to land on the contact of the arriving corner; the library's
  impact model (thesis 3.2.3, Eq. 7) takes ``M̃ = BᵀMB`` (OpenSees's mass matrix, ``B`` rebuilt
  from the current node positions, thesis Appendix C) and the interface rates, and its answer is
  written back into every node (``setNodeVel`` / ``setNodeAccel`` + ``domainChange``, the no-slip
  tie moved to the new pivot).

Needs openseespy (``pip install './python[opensees]'``; openseespy 3.7.1.2 has wheels for
Python 3.11); ``import rocking`` works without it, and so does importing this module: openseespy
is loaded when a model is built.

Use it on a CLI scene::

    result = rocking.opensees.run("examples/scenes/two_block_free_rocking.json", duration=0.33)
    for e in result["events"]:
        print(e["t"], e["kind"], e["interface"], e["statuses_after"])

or from the command line (one JSON object on standard output)::

    python -m rocking.opensees SCENE.json [--compare] [--duration T] [--max-events N]

or on a model of your own: build it (or describe it with the attributes of
:class:`ColumnModel`) and call :class:`Coupling`'s ``impact`` / ``opening`` from your analysis
loop.
"""

from ._analysis import excitation_of, load_scene, run
from ._compare import compare_events, rigid_driver_events
from ._coupling import Coupling, opensees_mass_matrix
from ._model import ColumnModel, load_openseespy

__all__ = [
    "ColumnModel",
    "Coupling",
    "compare_events",
    "excitation_of",
    "load_openseespy",
    "load_scene",
    "opensees_mass_matrix",
    "rigid_driver_events",
    "run",
]
