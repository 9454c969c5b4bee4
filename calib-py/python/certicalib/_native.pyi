"""Type stubs of the native extension (JSON text in, JSON text out)."""

from os import PathLike
from typing import Optional, Sequence, Tuple, Union

_Path = Union[str, PathLike]

def certify_files(
    robot: _Path,
    measurements: _Path,
    uncertainty: _Path,
    legs: Optional[Sequence[int]] = None,
    sweep: bool = False,
    max_outliers: int = 0,
    fast: bool = False,
    tolerance: float = 0.05,
    max_boxes: int = 200_000,
    max_seconds: Optional[float] = None,
) -> str: ...
def certify_text(
    robot: str,
    measurements: str,
    uncertainty: str,
    names: Tuple[str, str, str],
    legs: Optional[Sequence[int]] = None,
    sweep: bool = False,
    max_outliers: int = 0,
    fast: bool = False,
    tolerance: float = 0.05,
    max_boxes: int = 200_000,
    max_seconds: Optional[float] = None,
) -> str: ...
def simulate(
    out: _Path,
    configs: int = 21,
    seed: int = 7,
    noise_scale: float = 1.0,
    outliers: Sequence[Tuple[int, int, float]] = ...,
) -> str: ...
def lsq(robot: _Path, measurements: _Path) -> str: ...
def parameter_names() -> list: ...
def version() -> str: ...
