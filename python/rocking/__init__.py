"""rocking: opening and impact models for columns of rigid rocking blocks (Ther, "Analysis and
Design of Rocking Mechanisms"), numpy in and out.

The models (thesis 3.2.2 and 3.2.3) work on the ``2n`` interface DOFs of a column of ``n``
blocks, ordered ``[phĭ_0 … phĭ_{n-1}, phî_0 … phî_{n-1}]``: ``phĭ_k`` is the rotation of everything
above interface ``k`` about its right corner (admissible ``<= 0``, status −1), ``phî_k`` about its
left corner (``>= 0``, status +1); status 0 is closed (SPEC §1).

- :func:`impact_model`, :func:`opening_model`, :func:`check_configuration`: the decisions;
- :func:`column_mass_matrix` (``M`` and ``q`` of a column of rectangular blocks),
  :func:`reduce` (``BᵀMB``, ``Bᵀp`` of an FE model, thesis Appendix C);
- :func:`read_record`, :class:`Record` and the pulses (:func:`half_sine`, :func:`full_sine`, …);
- :func:`simulate`: a scene (the CLI's schema) through the reference driver (thesis 3.3) or,
  for joints that slide or fly, the contact scheme, or an arch / colonnade through the loop
  driver, with the history as arrays, the events and
  the summary of ``rocking simulate``;
- :func:`oas`, :func:`t1`, :func:`oc`: overturning spectra (thesis Chapter 5), parallel,
  interruptible with Ctrl-C; :func:`tp` (Eq. 25), :func:`suite` (the suite procedure, 5.3.1);
  :func:`design_width`, :func:`design_check`: the design method (Eq. 31);
- :func:`arch_oas`, :func:`arch_oc`, :func:`arch_suite`: the same spectra of voussoir arches;
- :mod:`rocking.plot`: matplotlib plots of the results (needs ``matplotlib``);
- :class:`RockingError`, the one exception (a ``ValueError`` with the C ABI's status code);
- :mod:`rocking.opensees`: the coupling with an openseespy model (needs ``openseespy``).

Every function takes any array-like (lists, tuples, numpy arrays of any numeric dtype), returns
new numpy arrays, and never modifies its arguments.
"""

from . import _rocking
from ._rocking import (
    Pulse,
    Record,
    Report,
    RockingError,
    __version__,
    check_configuration,
    column_mass_matrix,
    error_codes,
    full_sine,
    half_sine,
    half_sines,
    impact_model,
    mavroeidis_papageorgiou,
    opening_model,
    read_record,
    rectangular,
    reduce,
    ricker,
    triangular,
)

from . import plot
from ._design import design_check, design_width
from ._errors import error as _error
from ._simulate import ContactSimulation, LoopSimulation, Simulation, simulate
from ._spectra import Oas, Oc, Suite, oas, oc, suite, t1, tp
from ._arch import ArchOas, ArchOc, ArchSuite, arch_oas, arch_oc, arch_suite

# Defaults, so that a RockingError raised from Python code has every attribute too.
RockingError.code = None
RockingError.name = None
RockingError.message = None
RockingError.detail = ""


#: ``{C name: status code}`` of the C ABI (``ROCKING_OK`` = 0, ``ROCKING_ERR_*``): the values of
#: :attr:`RockingError.code`.
ERROR_CODES = dict(error_codes())

#: The most threads a sweep (``threads=``) starts.
_MAX_THREADS = _rocking.MAX_THREADS

#: The most points of a grid given as a count (``levels=``, ``sizes=``, ``radius_n=``, …).
_MAX_COUNT = _rocking.MAX_COUNT

#: Standard gravity of the thesis (m/s²).
GRAVITY = 9.81

__all__ = [
    "ERROR_CODES",
    "GRAVITY",
    "ArchOas",
    "ArchOc",
    "ArchSuite",
    "Oas",
    "Oc",
    "Pulse",
    "Record",
    "Report",
    "RockingError",
    "Suite",
    "ContactSimulation",
    "LoopSimulation",
    "Simulation",
    "__version__",
    "check_configuration",
    "arch_oas",
    "arch_oc",
    "arch_suite",
    "column_mass_matrix",
    "design_check",
    "design_width",
    "full_sine",
    "half_sine",
    "half_sines",
    "impact_model",
    "mavroeidis_papageorgiou",
    "oas",
    "oc",
    "opening_model",
    "plot",
    "read_record",
    "rectangular",
    "reduce",
    "ricker",
    "simulate",
    "suite",
    "t1",
    "tp",
    "triangular",
]
