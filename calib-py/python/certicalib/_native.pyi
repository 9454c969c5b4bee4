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
    write_calibrated: Optional[str]

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
    max_set_boxes: int = ..., report: Optional[_Path] = ..., refine_set: bool = ...,
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
    write_calibrated: Optional[str]

def arm_certify_files(robot: _Path, measurements: _Path, uncertainty: _Path, options: _ArmOptions) -> str: ...
def arm_simulate(
    out: _Path, configs: int = ..., seed: int = ..., robot: Optional[_Path] = ...,
    outliers: Sequence[Tuple[int, float]] = ...,
) -> str: ...
def arm_accuracy(
    robot: _Path, joints: Optional[_Path] = ..., before: Optional[_Path] = ...,
    uncertainty: Optional[_Path] = ..., tolerance: float = ..., max_boxes: int = ...,
    max_set_boxes: int = ..., report: Optional[_Path] = ...,
) -> str: ...

class _Columns(TypedDict):
    joint_columns: Optional[List[str]]
    point_columns: Optional[List[str]]
    joint_unit: str  # "deg" or "rad"
    length_unit: str  # "mm" or "m"
    rows: Optional[str]  # "A-B", "A-" or "A"

def arm_import(
    source: _Path, kind: str, out: _Path, base_link: Optional[str] = ...,
    tip_link: Optional[str] = ..., angle_radius: float = ..., length_radius: float = ...,
) -> str: ...
def arm_export(
    robot: _Path, ur_yaml: Optional[_Path] = ..., urdf: Optional[_Path] = ...,
    hash: Optional[str] = ...,
) -> None: ...
def arm_register(
    robot: _Path, measurements: _Path, out: _Path, columns: _Columns,
    priors: Tuple[float, float, float], orientation_columns: Optional[List[str]] = ...,
    orientation_convention: str = ..., tool_rotation_radius: float = ...,
) -> str: ...
def arm_error_scale(
    robot: _Path, measurements: _Path, uncertainty: _Path, columns: _Columns, scale_bounds: str,
) -> str: ...
def error_scale_files(
    robot: _Path, measurements: _Path, uncertainty: _Path, scale_bounds: str,
    legs: Optional[Sequence[int]] = ...,
) -> str: ...
def predict(
    robot: _Path, uncertainty: _Path, poses: Optional[_Path] = ...,
    measurements: Optional[_Path] = ...,
) -> str: ...
def arm_predict(robot: _Path, uncertainty: _Path, measurements: _Path, columns: _Columns) -> str: ...
