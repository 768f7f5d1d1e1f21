"""Type hints of the extension module ``rocking._rocking`` (re-exported by ``rocking``)."""

from os import PathLike
from typing import Any, Dict, List, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Float64Array = npt.NDArray[np.float64]
Int8Array = npt.NDArray[np.int8]
IntArray = npt.NDArray[np.int64]

class RockingError(ValueError):
    """A call the library refused or could not solve. ``code``: the C ABI's status code
    (negative: a bad call; positive: valid but cannot be solved as asked; None for inputs
    outside the models, such as records and pulses); ``name``: its C name; ``message``: the
    code's static text; ``detail``: what exactly was wrong, naming the argument."""

    code: Optional[int]
    name: Optional[str]
    message: Optional[str]
    detail: str

def error_codes() -> List[Tuple[str, int]]: ...

class Report:
    """What a model call did (the C ABI's ``RockingReport``)."""

    solver: str
    changed: bool
    tie: bool
    impacts_applied: int
    configurations_examined: int
    admissible: int
    kinetic_before: float
    kinetic_after: float
    runner_up: float
    condition_estimate: float
    @property
    def runner_up_gap(self) -> float: ...
    @property
    def energy_loss(self) -> float: ...
    def to_dict(self) -> Dict[str, Any]: ...

def impact_model(
    mass: ArrayLike,
    status: ArrayLike,
    velocity: ArrayLike,
    closing_interface: int,
    n_impacts: int = 1,
    solver: str = "auto",
    tolerance: float = 1e-12,
) -> Tuple[Int8Array, Float64Array, Report]:
    """Impact model (thesis 3.2.3, Eq. 7-8, App. A, B): ``(status, velocity, report)`` after
    interface ``closing_interface`` closes."""

def opening_model(
    mass: ArrayLike,
    load: ArrayLike,
    status: ArrayLike,
    solver: str = "auto",
    tolerance: float = 1e-12,
) -> Tuple[Int8Array, Float64Array, Report]:
    """Opening model (thesis 3.2.2): ``(status, acceleration, report)``."""

def check_configuration(
    mass: ArrayLike,
    load: ArrayLike,
    status: ArrayLike,
    tolerance: float = 1e-12,
) -> Tuple[bool, Float64Array, IntArray]:
    """The eccentricity test as reaction signs: ``(holds, reactions, must_open)``."""

def column_mass_matrix(
    width: ArrayLike,
    height: ArrayLike,
    mass: ArrayLike,
    inertia: Optional[ArrayLike] = None,
    contact_width: Optional[ArrayLike] = None,
    phi: Optional[ArrayLike] = None,
    ground_acceleration: float = 0.0,
    gravity: float = 9.81,
) -> Tuple[Float64Array, Float64Array]:
    """``(M, q)`` of a column of rectangular blocks (SPEC §1, thesis Eq. 4-6, Eq. 10)."""

def reduce(
    transformation: ArrayLike,
    nodal_mass: ArrayLike,
    nodal_load: Optional[ArrayLike] = None,
) -> Tuple[Float64Array, Optional[Float64Array]]:
    """``(BᵀMB, Bᵀp)``, thesis Appendix C."""

class Record:
    """A uniformly sampled ground-acceleration record (m/s²)."""

    def __init__(self, samples: ArrayLike, dt: float, name: str = "record") -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def dt(self) -> float: ...
    @property
    def samples(self) -> Float64Array: ...
    @property
    def t(self) -> Float64Array: ...
    @property
    def pga(self) -> float: ...
    @property
    def duration(self) -> float: ...
    @overload
    def acceleration(self, t: float) -> float: ...
    @overload
    def acceleration(self, t: ArrayLike) -> Float64Array: ...
    def scaled(self, factor: float) -> "Record": ...
    def scaled_to_pga(self, pga: float) -> "Record": ...
    def __len__(self) -> int: ...

def read_record(
    path: Union[str, "PathLike[str]"], dt: Optional[float] = None, units: Optional[str] = None
) -> Record:
    """A record from a PEER ``.AT2`` file (in g, its own step: no ``dt``, ``units`` only "g")
    or plain text (``units``: m/s2 (default), g, cm/s2)."""

class Pulse:
    """A pulse-type ground acceleration (thesis Fig. 6, 8)."""

    @property
    def kind(self) -> str: ...
    @property
    def amplitude(self) -> float: ...
    @property
    def end_time(self) -> float: ...
    @overload
    def acceleration(self, t: float) -> float: ...
    @overload
    def acceleration(self, t: ArrayLike) -> Float64Array: ...
    def scaled(self, factor: float) -> "Pulse": ...
    def to_dict(self) -> Dict[str, Any]: ...

def half_sine(amplitude: float, duration: float) -> Pulse: ...
def full_sine(amplitude: float, duration: float) -> Pulse: ...
def half_sines(amplitude: float, duration: float, count: int) -> Pulse: ...
def rectangular(amplitude: float, duration: float) -> Pulse: ...
def triangular(amplitude: float, duration: float) -> Pulse: ...
def ricker(amplitude: float, frequency: float) -> Pulse: ...
def mavroeidis_papageorgiou(amplitude: float, frequency: float, gamma: float, nu: float) -> Pulse: ...
def _time_impact_model(
    mass: ArrayLike, status: ArrayLike, velocity: ArrayLike, closing_interface: int, n_impacts: int = 1,
    repeats: int = 100000,
) -> float:
    """Benchmark hook: mean seconds per call of the library's impact model alone."""
def _report(*fields: Any) -> Report:
    """A Report from its fields (unpickling)."""

# ---- the driver, the spectra and the design method (wrapped by rocking/_simulate.py,
# _spectra.py, _design.py; use rocking.simulate, rocking.oas, ... rather than these) ----

def _simulate(
    path: Optional[str] = None,
    text: Optional[str] = None,
    base: Optional[str] = None,
    name: Optional[str] = None,
    record: Optional[Record] = None,
) -> Dict[str, Any]: ...
def _oas(record: Union[Record, str, "PathLike[str]"], *args: Any) -> Tuple[Dict[str, Any], float]: ...
def _t1(records: List[Union[Record, str]], *args: Any) -> List[Dict[str, Any]]: ...

STEP_TOLERANCE: float
STEP_HALVINGS: int
MAX_THREADS: int
MAX_COUNT: int

def _oc(shape: str, *args: Any) -> Dict[str, Any]: ...
def _tp(records: List[Union[Record, str]]) -> List[Dict[str, Any]]: ...
def _suite(spectra: List[str], name: str, fractiles: List[float]) -> Tuple[Dict[str, Any], List[float], List[float]]: ...
def _arch_oas(record: Union[Record, str], *args: Any) -> Dict[str, Any]: ...
def _arch_oc(shape: str, *args: Any) -> Dict[str, Any]: ...
def _arch_suite(spectra: List[str], name: str, fractiles: List[float]) -> Dict[str, Any]: ...
def _simplified_oas(
    p: ArrayLike, t1: float, i_cr: float, t1_prime: Optional[float] = None, beta: Optional[float] = None
) -> Tuple[Float64Array, Optional[Float64Array]]: ...
def _design_width(height: List[float], pga: List[float], t1: List[float], mass: str, g: float) -> Dict[str, Any]: ...
def _design_check(
    width: List[float], height: List[float], pga: List[float], t1: List[float], mass: str, g: float, exact_icr: bool
) -> Dict[str, Any]: ...
