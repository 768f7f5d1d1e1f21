"""Type hints of the package ``rocking``: the extension's functions (``_rocking.pyi``) and the
Python layer (simulate, spectra, design, plots)."""

from os import PathLike
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import plot as plot
from ._rocking import (
    Pulse as Pulse,
    Record as Record,
    Report as Report,
    RockingError as RockingError,
    __version__ as __version__,
    check_configuration as check_configuration,
    column_mass_matrix as column_mass_matrix,
    error_codes as error_codes,
    full_sine as full_sine,
    half_sine as half_sine,
    half_sines as half_sines,
    impact_model as impact_model,
    mavroeidis_papageorgiou as mavroeidis_papageorgiou,
    opening_model as opening_model,
    read_record as read_record,
    rectangular as rectangular,
    reduce as reduce,
    ricker as ricker,
    triangular as triangular,
)

ERROR_CODES: Dict[str, int]
GRAVITY: float

Float64Array = npt.NDArray[np.float64]
Int8Array = npt.NDArray[np.int8]
Int64Array = npt.NDArray[np.int64]
BoolArray = npt.NDArray[np.bool_]
Path = Union[str, "PathLike[str]"]
Progress = Callable[[int, int], Any]

class Simulation:
    """The result of :func:`simulate` (``rocking simulate``'s history, events and summary)."""

    title: str
    scheme: str
    """``"event_driven"``."""
    t: Float64Array
    """Times (s), ``(samples,)``."""
    angles: Float64Array
    """Signed interface angles ``phĭ_k + phî_k`` (rad), ``(samples, n)``."""
    rates: Float64Array
    """Their rates (rad/s), ``(samples, n)``."""
    block_rotations: Float64Array
    """Absolute block rotations (rad), ``(samples, n)``."""
    statuses: Int8Array
    """Interface statuses (−1, 0, +1), ``(samples, n)``."""
    dof_angles: Float64Array
    """The ``2n`` DOF angles (SPEC §1 order), ``(samples, 2n)``."""
    dof_rates: Float64Array
    """The ``2n`` DOF rates, ``(samples, 2n)``."""
    events: List[Dict[str, Any]]
    """The objects of ``events.jsonl``."""
    summary: Dict[str, Any]
    """``summary.json``."""
    @property
    def overturned(self) -> bool: ...
    @property
    def t_end(self) -> float: ...
    @property
    def stop_reason(self) -> str: ...
    def events_of(self, kind: str) -> List[Dict[str, Any]]: ...
    def plot(self, ax: Any = None, events: bool = True) -> Any: ...

class ContactSimulation:
    """The result of :func:`simulate` for a scene run by the contact scheme (joints that slide
    or fly; ``rocking simulate``'s history, events and summary of such a scene)."""

    title: str
    scheme: str
    """``"moreau"`` or ``"auto"``."""
    t: Float64Array
    """Times (s), ``(samples,)``."""
    x: Float64Array
    """Drum centres' horizontal displacement from its place in the straight column at rest (m), ``(samples, n)``."""
    y: Float64Array
    """Drum centres' vertical displacement from its place in the straight column at rest (m), ``(samples, n)``."""
    block_rotations: Float64Array
    """Drum rotations (rad), ``(samples, n)``."""
    slips: Float64Array
    """Joint slips (m), ``(samples, n)``."""
    events: List[Dict[str, Any]]
    """The objects of ``events.jsonl``."""
    summary: Dict[str, Any]
    """``summary.json``."""
    @property
    def overturned(self) -> bool: ...
    @property
    def t_end(self) -> float: ...
    @property
    def stop_reason(self) -> str: ...
    @property
    def residual_slip(self) -> Float64Array: ...
    @property
    def peak_slip(self) -> Float64Array: ...
    def events_of(self, kind: str) -> List[Dict[str, Any]]: ...
    def plot(self, ax: Any = None, events: bool = True) -> Any: ...
    def plot_slips(self, ax: Any = None, events: bool = True) -> Any: ...

class LoopSimulation:
    """The result of :func:`simulate` for a closed chain (an arch or a capped colonnade)."""

    title: str
    scheme: str
    """``"loop"``."""
    t: Float64Array
    """Times (s), ``(samples,)``."""
    angles: Float64Array
    """Each joint's signed angle (rad), ``(samples, joints)``."""
    events: List[Dict[str, Any]]
    """The objects of ``events.jsonl``."""
    summary: Dict[str, Any]
    """``summary.json``."""
    @property
    def collapsed(self) -> bool: ...
    @property
    def t_end(self) -> float: ...
    @property
    def hinges(self) -> List[Tuple[int, int]]: ...
    def events_of(self, kind: str) -> List[Dict[str, Any]]: ...
    def plot(self, ax: Any = None, events: bool = True) -> Any: ...

def simulate(
    scene: Union[Path, Mapping[str, Any]], base: Optional[Path] = None
) -> Union[Simulation, ContactSimulation, LoopSimulation]:
    """A scene (a file, or a dict with the CLI's schema) through the reference driver (thesis
    3.3, SPEC §5) or, for joints that slide or fly, the contact scheme, as ``rocking
    simulate``."""

class Oas:
    """An overturning acceleration spectrum (thesis Fig. 36, 37, 43)."""

    record: str
    slenderness: float
    blocks: int
    impacts: int
    search: str
    gravity: float
    i_cr: float
    sizes: Float64Array
    levels: Float64Array
    largest_unsafe: Int64Array
    size: Float64Array
    p: Float64Array
    f: Float64Array
    simulations: Int64Array
    summary: Dict[str, Any]
    conservative: Optional[Dict[str, int]]
    t1_range: Optional[List[float]]
    t1_conservative: Optional[float]
    band: Optional[Dict[str, Optional[float]]]
    t1_steps: Optional[List[List[Optional[float]]]]
    step_converged: Optional[bool]
    @property
    def t1(self) -> Optional[float]: ...
    @property
    def unsafe(self) -> BoolArray: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def plot(self, against: Literal["p", "f", "size"] = "p", ax: Any = None, fits: bool = True) -> Any: ...

class Oc:
    """An overturning curve (thesis Fig. 8, 33, 40)."""

    shape: str
    blocks: int
    p: float
    a_p_min: float
    p_tp: Float64Array
    t_p: Float64Array
    levels: Float64Array
    a_p: Float64Array
    unsafe: BoolArray
    envelope: Float64Array
    def to_dict(self) -> Dict[str, Any]: ...
    def plot(self, ax: Any = None) -> Any: ...

def oas(
    record: Union[Record, Path],
    *,
    slenderness: float = 12.0,
    levels: Union[int, npt.ArrayLike] = 80,
    level_max: float = 10.0,
    sizes: Union[int, npt.ArrayLike] = 120,
    size_min: float = 0.1,
    size_max: float = 1000.0,
    blocks: int = 1,
    bisection: bool = False,
    impacts: int = 1,
    dt_factor: float = 1.0,
    tail: Optional[float] = None,
    hermite: bool = False,
    rk4: bool = False,
    full_runs: bool = False,
    band: bool = False,
    converge_step: Optional[float] = None,
    converge_halvings: int = 4,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> Oas:
    """The OAS of a record (thesis 5.2), as ``rocking oas --json`` (``band``, ``converge_step``,
    ``converge_halvings``: ``--band``, ``--converge-step``, ``--converge-halvings``); parallel,
    Ctrl-C stops it."""

@overload
def t1(
    records: Union[Record, Path],
    *,
    band: bool = False,
    converge_step: Optional[float] = 0.1,
    converge_halvings: int = 4,
    **options: Any,
) -> Dict[str, Any]:
    """t1 (Eq. 20) of a record, as ``rocking t1 --json``: converged in the time step by default
    (``converge_step``, ``converge_halvings``: ``--converge-step``, ``--converge-halvings``;
    ``converge_step=None``: ``--single-step``); ``band``: ``--band``, at the row's step; the
    other options are :func:`oas`'s."""

@overload
def t1(
    records: Sequence[Union[Record, Path]],
    *,
    band: bool = False,
    converge_step: Optional[float] = 0.1,
    converge_halvings: int = 4,
    **options: Any,
) -> List[Dict[str, Any]]: ...
def oc(
    shape: str = "half-sine",
    *,
    blocks: int = 1,
    slenderness: float = 12.0,
    size: float = 1.0,
    ptp: Union[int, npt.ArrayLike] = 40,
    ptp_min: float = 0.1,
    ptp_max: float = 10.0,
    levels: Union[int, npt.ArrayLike] = 40,
    level_max: float = 10.0,
    impacts: int = 1,
    dt_factor: float = 1.0,
    tail: Optional[float] = None,
    hermite: bool = False,
    rk4: bool = False,
    full_runs: bool = False,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> Oc:
    """The overturning curve of a pulse shape (thesis Fig. 8, 33, 40), as ``rocking oc --json``."""

@overload
def tp(records: Union[Record, Path]) -> Dict[str, Any]: ...
@overload
def tp(records: Union[List[Union[Record, Path]], Tuple[Union[Record, Path], ...]]) -> List[Dict[str, Any]]: ...

class _SuiteResult:
    """What :class:`Suite` and :class:`ArchSuite` share."""
    @property
    def design_t1(self) -> Dict[float, Optional[float]]: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def plot(self, against: Literal["p", "f"] = "p", ax: Any = None) -> Any: ...

class Suite(_SuiteResult):
    """The design curves of a record suite (thesis 5.3.1-5.3.2), as ``rocking suite --json``."""

    name: str
    records: List[Oas]
    characteristic: List[Dict[str, Any]]
    """Per fractile: ``fractile``, ``design_t1``, ``f_min``, ``record_t1_fractile``, ``oas`` (an
    :class:`Oas`), ``violations``."""
    hulls: List[Dict[str, Any]]
    own_parameters: List[Dict[str, Any]]
    seconds: float

def suite(
    spectra: Sequence[Union[Oas, Mapping[str, Any]]],
    *,
    name: str = "suite",
    fractiles: Union[float, Sequence[float]] = (0.5, 0.84),
) -> Suite:
    """The suite procedure on the records' OAS, as ``rocking suite --merge ... --json``."""

class ArchOas:
    """The OAS of an arch family for a record, as ``rocking arch oas --json``."""

    record: str
    shape: Dict[str, Any]
    onset: Dict[str, Any]
    thickness_ratio: float
    embrace_angle: float
    """Radians (the argument ``embrace`` is in degrees)."""
    voussoirs: int
    lambda_: float
    p_at_1m: float
    gravity: float
    sizes: Float64Array
    levels: Float64Array
    largest_unsafe: Int64Array
    size: Float64Array
    p: Float64Array
    f: Float64Array
    simulations: Int64Array
    t1: Optional[float]
    f_min: Optional[float]
    level_at_f_min: Optional[float]
    size_at_f_min: Optional[float]
    check: Optional[Dict[str, Any]]
    runs: Dict[str, Any]
    seconds: float
    @property
    def unsafe(self) -> BoolArray: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def plot(self, against: Literal["p", "f"] = "p", ax: Any = None, fits: bool = True) -> Any: ...

class ArchOc:
    """The overturning curve of an arch under a pulse, as ``rocking arch oc --json``."""

    pulse: str
    radius: float
    p: float
    shape: Dict[str, Any]
    onset: Dict[str, Any]
    thickness_ratio: float
    embrace_angle: float
    voussoirs: int
    lambda_: float
    p_at_1m: float
    p_tp: Float64Array
    t_p: Float64Array
    levels: Float64Array
    collapses: BoolArray
    envelope: Float64Array
    runs: Dict[str, Any]
    seconds: float
    def to_dict(self) -> Dict[str, Any]: ...
    def plot(self, ax: Any = None) -> Any: ...

def arch_oas(
    record: Union[Record, Path],
    *,
    thickness_ratio: float = 0.15,
    embrace: float = 180.0,
    voussoirs: int = 20,
    dt_factor: float = 1.0,
    radius_max: float = 100.0,
    radius_min: float = 1.0,
    radius_n: int = 12,
    level_min: float = 1.5,
    level_max: float = 6.0,
    level_n: int = 10,
    t1: Optional[float] = None,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> ArchOas:
    """The OAS of an arch family for a record, as ``rocking arch oas --json``; parallel, Ctrl-C
    stops it."""

def arch_oc(
    shape: str = "half-sine",
    *,
    thickness_ratio: float = 0.15,
    embrace: float = 180.0,
    voussoirs: int = 20,
    dt_factor: float = 1.0,
    radius: float = 5.0,
    ptp_min: float = 0.5,
    ptp_max: float = 10.0,
    ptp_n: int = 8,
    level_max: float = 6.0,
    level_n: int = 11,
    threads: Optional[int] = None,
    progress: Optional[Progress] = None,
) -> ArchOc:
    """The overturning curve of an arch under a pulse, as ``rocking arch oc --json``."""

class ArchSuite(_SuiteResult):
    """The suite procedure on arch OAS, as ``rocking arch suite --json``."""

    name: str
    shape: Dict[str, Any]
    onset: Dict[str, Any]
    records: List[Dict[str, Any]]
    characteristic: List[Dict[str, Any]]
    """Per fractile: ``fractile``, ``design_t1``, ``f_min``, ``level_at_f_min``,
    ``size_at_f_min``, ``record_t1_fractile``, ``oas`` (an :class:`ArchOas`), ``check``."""
    block_rule: Dict[str, Any]

def arch_suite(
    spectra: Sequence[Union[ArchOas, Mapping[str, Any]]],
    *,
    name: str = "arch suite",
    fractiles: Union[float, Sequence[float]] = (0.5, 0.84),
) -> ArchSuite:
    """The suite procedure on arch OAS, as ``rocking arch suite --json``."""

def design_width(
    height: npt.ArrayLike,
    pga: npt.ArrayLike,
    t1: npt.ArrayLike,
    mass: Literal["uniform", "top"] = "uniform",
    g: float = 9.81,
) -> Dict[str, Any]:
    """The required pier width (thesis Eq. 31, 23, 24), as ``rocking design width --json``."""

def design_check(
    width: npt.ArrayLike,
    height: npt.ArrayLike,
    pga: npt.ArrayLike,
    t1: npt.ArrayLike,
    mass: Literal["uniform", "top"] = "uniform",
    g: float = 9.81,
    exact_icr: bool = False,
) -> Dict[str, Any]:
    """The Eq. 31 verdict for a pier, as ``rocking design check --json``."""
