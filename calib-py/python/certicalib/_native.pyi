"""Type stubs of the native extension (JSON text in, JSON text out)."""

from os import PathLike
from typing import List, Optional, Sequence, Tuple, TypedDict, Union

_Path = Union[str, PathLike]

class _Options(TypedDict):
    legs: Optional[List[int]]
    sweep: bool
    max_outliers: str  # a number or "auto"
    fast: bool
    tolerance: float
    max_boxes: int
    max_seconds: Optional[float]

def certify_files(robot: _Path, measurements: _Path, uncertainty: _Path, options: _Options) -> str: ...
def certify_text(
    robot: str, measurements: str, uncertainty: str, names: Tuple[str, str, str], options: _Options
) -> str: ...
def simulate(
    out: _Path,
    configs: int = 21,
    seed: int = 7,
    noise_scale: float = 1.0,
    outliers: Sequence[Tuple[int, int, float]] = ...,
    poses: Optional[_Path] = ...,
) -> str: ...
def lsq(robot: _Path, measurements: _Path) -> str: ...
def accuracy(
    robot: _Path, workspace: _Path, before: Optional[_Path] = ..., uncertainty: Optional[_Path] = ...,
    tolerance: float = ..., max_boxes: int = ..., pose_seconds: float = ...,
) -> str: ...
def design(
    out: _Path, robot: Optional[_Path] = ..., uncertainty: Optional[_Path] = ...,
    workspace: Optional[_Path] = ..., configs: int = ..., candidates: int = ...,
    criterion: str = ..., seed: int = ..., extend: Optional[_Path] = ...,
) -> str: ...
def parameter_names() -> list: ...
def version() -> str: ...

class _ArmOptions(TypedDict):
    hull: bool
    tolerance: float
    max_boxes: int
    max_seconds: Optional[float]
    max_outliers: str  # a number or "auto"
    lsq: bool

def arm_certify_files(robot: _Path, measurements: _Path, uncertainty: _Path, options: _ArmOptions) -> str: ...
def arm_simulate(
    out: _Path, configs: int = ..., seed: int = ..., robot: Optional[_Path] = ...,
    outliers: Sequence[Tuple[int, float]] = ...,
) -> str: ...
