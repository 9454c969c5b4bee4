"""certicalib: certified calibration of parallel robots, from Python.

For measurements known only within error bounds, certicalib returns per leg of a Gough (Stewart)
platform an ``outer`` box that provably contains every parameter vector consistent with the data,
an ``inner`` box spanned by parameter vectors proved consistent (the true range of each parameter
lies between the two), or a proof that the data are inconsistent, with the configurations to blame.
It runs the same Rust code as the ``gough`` command-line tool and gives the same results.

>>> import certicalib, tempfile, os
>>> d = tempfile.mkdtemp()
>>> truth = certicalib.simulate(d, configs=21, seed=7)
>>> report = certicalib.certify(os.path.join(d, "robot.toml"),
...                             os.path.join(d, "measurements.csv"),
...                             os.path.join(d, "uncertainty.toml"), legs=[1])
>>> leg = report.legs[0]
>>> leg.status, leg.outer.shape
('consistent', (7, 2))

Units are cm and degrees; parameters per leg are ``a_x a_y a_z b_x b_y b_z l``
(``PARAMETER_NAMES``).

Serial arms tracked by a laser tracker go through :func:`certify_arm` (what ``arm certify``
computes; mm and degrees) and :func:`simulate_arm`:

>>> arm_dir = tempfile.mkdtemp()
>>> truth = certicalib.simulate_arm(arm_dir, configs=20, seed=3)
>>> arm = certicalib.certify_arm(os.path.join(arm_dir, "robot.toml"),
...                              os.path.join(arm_dir, "measurements.csv"),
...                              os.path.join(arm_dir, "uncertainty.toml"))
>>> arm.status, arm.outer.shape
('consistent', (39, 2))
"""

from __future__ import annotations

import copy
import json
import os
import warnings
from dataclasses import dataclass
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native

__all__ = ["certify", "simulate", "lsq", "Report", "LegResult", "LeastSquaresFit",
           "certify_arm", "simulate_arm", "ArmReport", "design", "DesignPlan", "accuracy",
           "import_arm", "export_arm", "register_arm", "error_scale", "error_scale_arm", "predict",
           "predict_arm", "accuracy_arm",
           "PARAMETER_NAMES", "__version__"]

__version__: str = _native.version()

#: The parameter names of a leg, in order.
PARAMETER_NAMES: Tuple[str, ...] = tuple(_native.parameter_names())

PathLike = Union[str, "os.PathLike[str]"]
RobotData = Mapping[str, Any]
MeasurementData = Union[np.ndarray, Mapping[str, Any]]
UncertaintyData = Mapping[str, float]


def _box(value: Optional[List[List[float]]]) -> Optional[np.ndarray]:
    """``[[lo, hi], ...]`` as a float64 array of shape (7, 2), or ``None``."""
    return None if value is None else np.asarray(value, dtype=np.float64).reshape(-1, 2)


@dataclass(frozen=True)
class LegResult:
    """One leg's certified result. Boxes are float64 arrays of shape (7, 2): (lower, upper) per
    parameter, in the order of ``names``; ``None`` where the leg was proved empty."""

    #: 1-based leg number.
    leg: int
    #: ``"consistent"`` (a certified witness exists), ``"empty"`` (proved: no parameter vector in
    #: x0 fits the data) or ``"undecided"``.
    status: str
    #: Parameter names, in order.
    names: Tuple[str, ...]
    #: The initial box (nominal ± radius).
    x0: np.ndarray
    #: The tightest certified box: contains every consistent parameter vector.
    outer: Optional[np.ndarray]
    #: Spanned by parameter vectors proved consistent (``None`` without a witness).
    inner: Optional[np.ndarray]
    #: The paper's fixed point x1, for comparison.
    x1: Optional[np.ndarray]
    #: The paper's sweep hull x2 (with ``sweep=True``).
    x2: Optional[np.ndarray]
    #: A certified consistent parameter vector (shape (7,)), or ``None``.
    witness: Optional[np.ndarray]
    #: For an empty leg: a minimal set of conflicting configurations (1-based), else ``None``.
    conflict: Optional[List[int]]
    #: With ``max_outliers``: the configurations (1-based) proved to be outliers.
    outliers: List[int]
    #: How many outliers this leg's result tolerates (with ``max_outliers="auto"``, the smallest
    #: number not proved empty).
    outliers_tolerated: int
    #: Whether the tight hull met its tolerance (``None`` with ``fast=True``).
    converged: Optional[bool]
    #: Wall-clock seconds for this leg.
    seconds: float
    #: How many configurations of a calibrated robot file's stored set were certified with the
    #: new ones (``robot`` a file written with ``write_calibrated``); they are configurations
    #: ``len(new rows) + 1`` onwards. 0 when none were carried over.
    carried_over: int = 0

    @property
    def ratio(self) -> Optional[np.ndarray]:
        """``wid(outer) / wid(inner)`` per parameter: the outer box overstates the true range by
        at most this factor (``None`` without both boxes)."""
        if self.outer is None or self.inner is None:
            return None
        with np.errstate(divide="ignore", invalid="ignore"):
            return (self.outer[:, 1] - self.outer[:, 0]) / (self.inner[:, 1] - self.inner[:, 0])


class Report:
    """The result of :func:`certify`: ``legs`` (one :class:`LegResult` per certified leg) and
    ``seconds``; :meth:`to_dict` gives the JSON report of ``gough certify --json`` (schema
    version 1), so ``json.dump(report.to_dict(), f)`` writes the same file."""

    def __init__(self, text: str) -> None:
        self._dict: Dict[str, Any] = json.loads(text)
        self.seconds: float = self._dict["seconds"]
        self.legs: List[LegResult] = [
            LegResult(
                leg=leg["leg"],
                status=leg["status"],
                names=tuple(leg["names"]),
                x0=_box(leg["x0"]),
                outer=_box(leg.get("outer")),
                inner=_box(leg.get("inner")),
                x1=_box(leg.get("x1")),
                x2=_box(leg.get("x2")),
                witness=None if leg.get("witness") is None
                else np.asarray(leg["witness"], dtype=np.float64),
                conflict=leg.get("conflict"),
                outliers=list(leg.get("outliers", [])),
                outliers_tolerated=int(leg.get("outliers_tolerated", 0)),
                converged=leg.get("converged"),
                seconds=leg["seconds"],
                carried_over=len((leg.get("carried_over") or {}).get("rows", [])),
            )
            for leg in self._dict["legs"]
        ]

    def to_dict(self) -> Dict[str, Any]:
        """The JSON report (schema version 1) as plain Python data."""
        return copy.deepcopy(self._dict)

    def __repr__(self) -> str:
        verdicts = ", ".join(f"leg {leg.leg}: {leg.status}" for leg in self.legs)
        return f"<certicalib.Report {verdicts}>"


def _options(legs: Optional[Sequence[int]], sweep: bool, max_outliers: Union[int, str],
             fast: bool, tolerance: float, max_boxes: int,
             max_seconds: Optional[float],
             write_calibrated: Optional[PathLike] = None,
             task: Optional[PathLike] = None) -> Dict[str, Any]:
    return dict(legs=None if legs is None else [int(v) for v in legs], sweep=bool(sweep),
                max_outliers=str(max_outliers) if isinstance(max_outliers, str)
                else str(int(max_outliers)), fast=bool(fast), tolerance=float(tolerance),
                max_boxes=int(max_boxes), max_seconds=max_seconds,
                write_calibrated=None if write_calibrated is None
                else os.fspath(write_calibrated),
                task=None if task is None else os.fspath(task))


def _is_path(value: Any) -> bool:
    return isinstance(value, (str, os.PathLike))


def _num(v: Any) -> str:
    """A float in shortest round-trip form (the Rust parser reads it back exactly)."""
    return repr(float(v))


def _vec(values: Any) -> str:
    return "[" + ", ".join(_num(v) for v in values) + "]"


def _robot_text(robot: RobotData) -> str:
    """``{"a": (n, 3), "b": (n, 3), "l": (n,), "radius": float | (n,) | (n, 7)}`` as robot.toml."""
    try:
        a = np.asarray(robot["a"], dtype=np.float64).reshape(-1, 3)
        b = np.asarray(robot["b"], dtype=np.float64).reshape(-1, 3)
        l = np.asarray(robot["l"], dtype=np.float64).reshape(-1)
        radius = np.asarray(robot["radius"], dtype=np.float64)
    except KeyError as e:
        raise ValueError(f"robot (in memory): missing key {e}; expected a, b, l, radius") from None
    except (TypeError, ValueError) as e:
        raise ValueError(f"robot (in memory): {e}") from None
    n = len(l)
    if len(a) != n or len(b) != n:
        raise ValueError(f"robot (in memory): a, b and l must describe the same number of legs "
                         f"(found {len(a)}, {len(b)}, {n})")
    out = []
    for i in range(n):
        r = radius if radius.ndim == 0 else radius[i]
        r_text = _num(r) if np.ndim(r) == 0 else _vec(r)
        out.append(f"[[leg]]\na = {_vec(a[i])}\nb = {_vec(b[i])}\nl = {_num(l[i])}\n"
                   f"radius = {r_text}\n")
    return "\n".join(out)


def _measurements_text(measurements: MeasurementData) -> str:
    """An array (p, 7 + n) with columns px,py,pz,ax,ay,az,angle_deg,L1..Ln, or a dict with "p"
    (p, 3), "axis" (p, 3) and "angle_deg" (p,) or "q" (p, 3), and "lengths" (p, n), as CSV."""
    if isinstance(measurements, Mapping):
        try:
            p = np.asarray(measurements["p"], dtype=np.float64).reshape(-1, 3)
            lengths = np.asarray(measurements["lengths"], dtype=np.float64)
            lengths = lengths.reshape(len(p), -1)
            if "q" in measurements:
                orient = np.asarray(measurements["q"], dtype=np.float64).reshape(-1, 3)
                head = ["px", "py", "pz", "q1", "q2", "q3"]
            else:
                axis = np.asarray(measurements["axis"], dtype=np.float64).reshape(-1, 3)
                angle = np.asarray(measurements["angle_deg"], dtype=np.float64).reshape(-1, 1)
                orient = np.hstack([axis, angle])
                head = ["px", "py", "pz", "ax", "ay", "az", "angle_deg"]
            rows = np.hstack([p, orient, lengths])
        except KeyError as e:
            raise ValueError(f"measurements (in memory): missing key {e}") from None
        except ValueError as e:
            raise ValueError(f"measurements (in memory): {e}") from None
    else:
        rows = np.asarray(measurements, dtype=np.float64)
        if rows.ndim != 2 or rows.shape[1] < 8:
            raise ValueError("measurements (in memory): expected an array of shape (p, 7 + legs) "
                             f"with columns px,py,pz,ax,ay,az,angle_deg,L1..; found {rows.shape}")
        head = ["px", "py", "pz", "ax", "ay", "az", "angle_deg"]
    legs = rows.shape[1] - len(head)
    head = head + [f"L{i + 1}" for i in range(legs)]
    lines = [",".join(head)] + [",".join(_num(v) for v in row) for row in rows]
    return "\n".join(lines) + "\n"


def _uncertainty_text(u: UncertaintyData) -> str:
    """``{"pos", "len", "axis", "angle_deg"}`` or ``{"pos", "len", "q"}`` as uncertainty.toml."""
    if not isinstance(u, Mapping):
        raise ValueError("uncertainty (in memory): expected a dict of half-widths")
    return "".join(f"{k} = {_num(v)}\n" for k, v in u.items())


def certify(robot: Union[PathLike, RobotData],
            measurements: Union[PathLike, MeasurementData],
            uncertainty: Union[PathLike, UncertaintyData], *,
            legs: Optional[Sequence[int]] = None, sweep: bool = False,
            max_outliers: Union[int, str] = 0,
            fast: bool = False, tolerance: float = 0.05, max_boxes: int = 200_000,
            max_seconds: Optional[float] = None,
            write_calibrated: Optional[PathLike] = None,
            task: Optional[PathLike] = None) -> Report:
    """Certify every leg (or ``legs``, 1-based) of a Gough platform, as ``gough certify`` does.

    Each input is either a path (``str`` or ``os.PathLike``) to the file ``gough certify`` reads,
    or in-memory data:

    - ``robot``: ``{"a": (n, 3), "b": (n, 3), "l": (n,), "radius": r}``, with ``r`` a float, one
      per leg ``(n,)`` or one per parameter ``(n, 7)``: the initial box is nominal ± radius.
    - ``measurements``: an array ``(p, 7 + n)`` with columns ``px,py,pz,ax,ay,az,angle_deg,L1..Ln``
      (one row per configuration), or a dict with ``"p"`` (p, 3), ``"axis"`` (p, 3) and
      ``"angle_deg"`` (p,) — or ``"q"`` (p, 3), the Rodrigues vector — and ``"lengths"`` (p, n).
    - ``uncertainty``: ``{"pos": .., "len": .., "axis": .., "angle_deg": ..}`` (or ``"q"``):
      half-widths of the measurement errors.

    ``sweep`` adds the paper's 128-box sweep (``x2``); ``max_outliers`` tolerates that many bad
    configurations per leg (``"auto"``: per leg, the smallest number not proved empty, in
    ``LegResult.outliers_tolerated``); ``fast`` computes only the paper's fixed point x1 (reported as
    ``outer``); ``tolerance``, ``max_boxes`` and ``max_seconds`` are the tight hull's stop rule.
    ``write_calibrated``: write the calibrated robot file there, as ``--write-calibrated`` does
    (per leg a geometry proved consistent with every measurement, and the certified set that
    :func:`accuracy` works over); with ``task`` (a ``workspace.toml`` or a poses CSV, as
    ``--task``), each geometry is chosen towards the centre of its predictions there. A
    ``robot`` file written so carries its certified sets over: each leg is certified against the
    new measurements and the rows its set was certified against, as ``gough certify`` does
    (``LegResult.carried_over`` counts them). The interpreter is released while the work runs. Malformed input raises ``ValueError`` naming
    the file (or in-memory input), the line and the field.
    """
    opts = _options(legs, sweep, max_outliers, fast, tolerance, max_boxes, max_seconds,
                    write_calibrated, task)
    if _is_path(robot) and _is_path(measurements) and _is_path(uncertainty):
        return Report(_native.certify_files(os.fspath(robot), os.fspath(measurements),
                                            os.fspath(uncertainty), opts))
    texts, names = [], []
    for value, render, name in [(robot, _robot_text, "robot"),
                                (measurements, _measurements_text, "measurements"),
                                (uncertainty, _uncertainty_text, "uncertainty")]:
        if _is_path(value):
            with open(value, encoding="utf-8") as f:
                texts.append(f.read())
            names.append(os.fspath(value))
        else:
            texts.append(render(value))
            names.append(f"{name} (in memory)")
    return Report(_native.certify_text(texts[0], texts[1], texts[2], tuple(names), opts))


def simulate(out: PathLike, *, configs: int = 21, seed: int = 7, noise_scale: float = 1.0,
             outliers: Sequence[Tuple[int, int, float]] = (),
             poses: Optional[PathLike] = None) -> Dict[str, Any]:
    """Write a simulated data set of the built-in hexapod into the folder ``out``, as
    ``gough simulate`` does: ``robot.toml``, ``measurements.csv``, ``uncertainty.toml`` and
    ``truth.json``. ``outliers`` are ``(configuration, leg, delta_cm)`` with 1-based numbers.
    ``poses``: a CSV with header ``px,py,pz,ax,ay,az,angle_deg`` to measure at instead of
    ``configs`` random poses (``gough simulate --poses``). Returns the truth (the contents of
    ``truth.json``) as a dict."""
    text = _native.simulate(os.fspath(out), int(configs), int(seed), float(noise_scale),
                            [(int(c), int(l), float(d)) for c, l, d in outliers],
                            None if poses is None else os.fspath(poses))
    return json.loads(text)


@dataclass(frozen=True)
class LeastSquaresFit:
    """A Levenberg–Marquardt fit of one leg from its nominal geometry."""

    #: 1-based leg number.
    leg: int
    #: Whether the solver reported convergence.
    converged: bool
    #: The fitted parameters, shape (7,).
    x: np.ndarray
    #: Root-mean-square residual.
    rms: float
    #: Largest leg-length error of the fit, in cm.
    max_length_error: float


def lsq(robot: PathLike, measurements: PathLike) -> List[LeastSquaresFit]:
    """Least squares per leg from the nominal geometry, as ``gough lsq`` does (the classical
    calibration the paper compares against: its solutions need not be consistent with the data)."""
    fits = json.loads(_native.lsq(os.fspath(robot), os.fspath(measurements)))
    return [LeastSquaresFit(leg=f["leg"], converged=f["converged"],
                            x=np.asarray(f["x"], dtype=np.float64), rms=f["rms"],
                            max_length_error=f["max_length_error"]) for f in fits]


class DesignPlan:
    """The result of :func:`design`: the poses chosen and the certified widths they are predicted
    to give, next to a random design of the same size and to the other criterion's design.
    :meth:`to_dict` gives the JSON of ``gough design --json``."""

    def __init__(self, text: str) -> None:
        self._dict: Dict[str, Any] = json.loads(text)
        d = self._dict
        #: The criterion the poses were chosen by (``"certified"`` or ``"d-optimal"``).
        self.criterion: str = d["criterion"]
        #: The poses, shape (K, 7): px, py, pz, ax, ay, az, angle_deg (cm, unit axis, degrees).
        self.poses: np.ndarray = np.asarray(d["poses"], dtype=np.float64).reshape(-1, 7)
        #: The random design compared with, shape (K, 7).
        self.random_poses: np.ndarray = np.asarray(d["random_poses"],
                                                   dtype=np.float64).reshape(-1, 7)
        #: Per design (``"designed"``, ``"random"`` and the other criterion's name), the
        #: predicted certified widths in cm, shape (legs, 7).
        self.widths: Dict[str, np.ndarray] = {
            name: np.asarray(p["widths"], dtype=np.float64) for name, p in d["predicted"].items()}
        #: Per design, the geometric mean of its predicted certified widths (cm).
        self.geometric_mean: Dict[str, float] = {
            name: p["geometric_mean"] for name, p in d["predicted"].items()}
        #: First-order widths (cm), shape (legs, 7): ``"designed"``, ``"random"`` and
        #: ``"every_candidate"`` (no design from these candidates does better).
        self.first_order: Dict[str, np.ndarray] = {
            name: np.asarray(w, dtype=np.float64) for name, w in d["first_order"].items()}
        #: How many greedily chosen poses already match the random design (first order).
        self.matching_prefix: Optional[int] = d["matching_prefix"]

    def to_dict(self) -> Dict[str, Any]:
        """The JSON of ``gough design --json`` as a dict."""
        return json.loads(json.dumps(self._dict))

    def __repr__(self) -> str:
        gm = self.geometric_mean
        return (f"DesignPlan({len(self.poses)} poses, {self.criterion}: geometric mean "
                f"{gm['designed']:.4f} cm vs random {gm['random']:.4f} cm)")


def design(out: PathLike, *, robot: Optional[PathLike] = None,
           uncertainty: Optional[PathLike] = None, workspace: Optional[PathLike] = None,
           configs: int = 21, candidates: int = 2000, criterion: str = "certified",
           seed: int = 1, extend: Optional[PathLike] = None) -> DesignPlan:
    """Choose the poses to measure, as ``gough design`` does, and write them to ``out`` (a CSV
    with header ``px,py,pz,ax,ay,az,angle_deg``, for :func:`simulate` ``(poses=...)``).

    Without ``robot`` the built-in hexapod (± 0.1 cm), without ``uncertainty`` the paper's error
    bounds, without ``workspace`` the simulator's workspace. ``criterion``: ``"certified"``
    (the smallest predicted certified box) or ``"d-optimal"``. ``extend``: a measurements CSV
    whose configurations are kept; the new poses extend them.

    >>> import tempfile, os
    >>> plan = design(os.path.join(tempfile.mkdtemp(), "poses.csv"), configs=8, candidates=200)
    >>> plan.poses.shape
    (8, 7)
    >>> plan.geometric_mean["designed"] < plan.geometric_mean["random"]
    True
    """
    def opt(p: Optional[PathLike]) -> Optional[str]:
        return None if p is None else os.fspath(p)
    return DesignPlan(_native.design(os.fspath(out), opt(robot), opt(uncertainty), opt(workspace),
                                     int(configs), int(candidates), str(criterion), int(seed),
                                     opt(extend)))


def accuracy(robot: PathLike, workspace: PathLike, *, before: Optional[PathLike] = None,
             uncertainty: Optional[PathLike] = None, tolerance: float = 0.04,
             max_boxes: int = 300_000, pose_seconds: float = 30.0,
             max_set_boxes: int = 1000, report: Optional[PathLike] = None,
             refine_set: bool = False) -> Dict[str, Any]:
    r"""Bracket, per leg, how far the leg length the controller commands (from ``robot``'s values)
    can be from the length the real leg needs, over every pose of ``workspace`` (a
    ``workspace.toml``) and every geometry in ``robot``'s boxes — as ``gough accuracy`` does.
    ``before``: the uncalibrated robot file (the improvement is then a proved factor);
    ``uncertainty``: adds the actuators' error. Returns the JSON of ``gough accuracy --json`` as a
    dict: ``leg_length`` (per leg ``upper``, ``lower``, ``ratio``, ``worst``), ``position`` and
    ``orientation`` of the platform (``lower``: attained by ``worst``, an instance whose reached
    pose is proved; ``upper``: proved over the whole workspace, or ``None`` where the reached pose
    could not be enclosed, ``upper_unproved_at`` then naming the box of poses and
    ``upper_unproved`` saying why: ``finest`` — even the finest box of poses — or the budget
    ended first, with ``settled_share`` of the workspace settled), ``before``,
    ``improvement`` (per leg) and ``pose_improvement`` (``position``, ``orientation``: proved
    factors, ``None`` where not proved). ``tolerance`` stops every bracket at ``upper <= (1 + tolerance) lower``;
    ``max_boxes`` bounds each leg-length bracket's boxes of poses, ``pose_seconds`` the time spent
    per robot on the pose errors' upper bounds (they stay proved, only less tight),
    ``max_set_boxes`` each leg's boxes of poses over a certified set. ``report``: also write the
    accuracy certificate there (what ``gough accuracy --report`` writes: one HTML page).
    ``refine_set``: refine each leg's certified set where the workspace's errors are largest
    first (``gough accuracy --refine-set``): tighter bounds at more time per box, worth it on a
    small workspace.

    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> _ = simulate(d, seed=2)
    >>> ws = os.path.join(d, "workspace.toml")
    >>> _ = open(ws, "w").write("x = [-2, 2]\ny = [-2, 2]\nz = [58, 62]\ntilt_deg = 5\n")
    >>> result = accuracy(os.path.join(d, "robot.toml"), ws)
    >>> all(0 < leg["lower"] <= leg["upper"] <= 1.05 * leg["lower"] for leg in result["leg_length"])
    True
    >>> p = result["position"]
    >>> p["lower"] > 0 and (p["upper"] is None or p["upper"] >= p["lower"])
    True
    """
    def opt(p: Optional[PathLike]) -> Optional[str]:
        return None if p is None else os.fspath(p)
    return json.loads(_native.accuracy(os.fspath(robot), os.fspath(workspace), opt(before),
                                       opt(uncertainty), float(tolerance), int(max_boxes),
                                       float(pose_seconds), int(max_set_boxes), opt(report),
                                       bool(refine_set)))


def accuracy_arm(robot: PathLike, *, joints: Optional[PathLike] = None,
                 before: Optional[PathLike] = None, uncertainty: Optional[PathLike] = None,
                 tolerance: float = 0.04, max_boxes: int = 20_000,
                 max_set_boxes: int = 300, report: Optional[PathLike] = None,
                 task: Optional[PathLike] = None) -> Dict[str, Any]:
    r"""Bracket how far an arm's tool point can be from where the controller computes it (from
    ``robot``'s values), over every configuration of ``joints`` (a ``joints.toml``: ``q1 = [lo,
    hi]``, … degrees; default ±170° per joint), every geometry of ``robot``'s certified set (its
    boxes for a file without one) and every joint error within ``uncertainty``'s ``joint_deg`` —
    as ``arm accuracy`` does. ``before``: the uncalibrated robot file, bracketed over its boxes,
    and the improvement as a proved factor. Returns the JSON of ``arm accuracy --json`` as a
    dict: ``position`` and ``before`` (each ``upper``, ``lower``, ``ratio``, ``over``, ``worst``
    with ``joints_deg`` and ``theta``), ``improvement``. ``tolerance`` stops a bracket at
    ``upper <= (1 + tolerance) lower``; ``max_boxes`` and ``max_set_boxes`` bound the joint boxes
    over a box and over a certified set. ``report``: also write the accuracy certificate there
    (what ``arm accuracy --report`` writes: one HTML page). ``task``: instead of ``joints``, the
    configurations a task uses (a CSV with columns ``q1..qN``, degrees), each bounded as given
    (``arm accuracy --task``); ``boxes`` then counts configurations.

    >>> import os, tempfile
    >>> d = tempfile.mkdtemp()
    >>> _ = simulate_arm(d, configs=12, seed=3)
    >>> cell = os.path.join(d, "cell.toml")
    >>> _ = open(cell, "w").write("".join(f"q{k} = [-2, 2]\n" for k in range(1, 7)))
    >>> r = accuracy_arm(os.path.join(d, "robot.toml"), joints=cell, max_boxes=300)
    >>> 0 < r["position"]["lower"] <= r["position"]["upper"]
    True
    """
    def opt(p: Optional[PathLike]) -> Optional[str]:
        return None if p is None else os.fspath(p)
    return json.loads(_native.arm_accuracy(os.fspath(robot), opt(joints), opt(before),
                                           opt(uncertainty), float(tolerance), int(max_boxes),
                                           int(max_set_boxes), opt(report), opt(task)))


class ArmReport:
    """The result of :func:`certify_arm` (one parameter vector for the whole arm). Boxes are
    float64 arrays of shape (n, 2): (lower, upper) per parameter in the order of ``names``, in the
    units of ``units`` (mm or degrees); ``None`` where the data were proved inconsistent.
    :meth:`to_dict` gives the JSON report of ``arm certify --json``."""

    def __init__(self, text: str) -> None:
        self._dict: Dict[str, Any] = json.loads(text)
        params = self._dict["parameters"]

        def column(key: str) -> Optional[np.ndarray]:
            values = [p[key] for p in params]
            if any(v is None for v in values):
                return None
            return np.asarray(values, dtype=np.float64)

        #: ``"consistent"``, ``"empty"`` or ``"undecided"``.
        self.status: str = self._dict["status"]
        #: Parameter names (``theta1, d1, a1, alpha1, beta1, ..., tool_z``).
        self.names: Tuple[str, ...] = tuple(p["name"] for p in params)
        #: Units per parameter (``"mm"`` or ``"°"``).
        self.units: Tuple[str, ...] = tuple(p["unit"] for p in params)
        #: Whether each parameter is fixed (radius 0 in the robot file).
        self.fixed: np.ndarray = np.asarray([p["fixed"] for p in params], dtype=bool)
        #: The prior box (nominal ± radius).
        self.x0: np.ndarray = column("x0").reshape(-1, 2)
        #: The certified outer box: contains every consistent parameter vector.
        self.outer: Optional[np.ndarray] = _box(None if column("outer") is None
                                                else [p["outer"] for p in params])
        #: Bounds attained by parameter vectors proved consistent.
        self.inner: Optional[np.ndarray] = _box(None if column("inner") is None
                                                else [p["inner"] for p in params])
        #: A certified consistent parameter vector, or ``None``.
        self.witness: Optional[np.ndarray] = column("witness")
        #: The least-squares solution (with ``lsq=True``), or ``None``.
        self.lsq: Optional[np.ndarray] = column("lsq")
        #: For an empty verdict: a minimal set of conflicting configurations (1-based).
        self.conflict: Optional[List[int]] = self._dict.get("conflict")
        #: The configurations (1-based) proved to be outliers.
        self.outliers: List[int] = list(self._dict.get("outliers", []))
        #: How many outliers the result tolerates.
        self.outliers_tolerated: int = int(self._dict.get("outliers_tolerated", 0))
        #: The verdict and its evidence, in words.
        self.verdict: List[str] = list(self._dict["verdict"])
        #: The identifiability findings, in words.
        self.identifiability: List[str] = list(self._dict["identifiability"])
        #: Whether the tight hull met its tolerance (``None`` without ``hull=True``).
        self.converged: Optional[bool] = self._dict.get("converged")
        #: Wall-clock seconds.
        self.seconds: float = self._dict["seconds"]
        #: With a robot file that carries a certified set: ``file`` and ``configurations`` (the
        #: earlier rows, numbered after the new ones in ``conflict`` and ``outliers``), else
        #: ``None``.
        self.carried_over: Optional[Dict[str, Any]] = self._dict.get("carried_over")

    @property
    def ratio(self) -> Optional[np.ndarray]:
        """``wid(outer) / wid(inner)`` per parameter (NaN for fixed ones), or ``None``."""
        if self.outer is None or self.inner is None:
            return None
        with np.errstate(divide="ignore", invalid="ignore"):
            r = (self.outer[:, 1] - self.outer[:, 0]) / (self.inner[:, 1] - self.inner[:, 0])
        r[self.fixed] = np.nan
        return r

    def to_dict(self) -> Dict[str, Any]:
        """The JSON report as plain Python data."""
        return copy.deepcopy(self._dict)

    def __repr__(self) -> str:
        return f"<certicalib.ArmReport {self.status}, {int((~self.fixed).sum())} free parameters>"


def certify_arm(robot: PathLike, measurements: PathLike, uncertainty: PathLike, *,
                hull: bool = False, tolerance: float = 0.10, max_boxes: int = 10_000,
                max_seconds: Optional[float] = None, max_outliers: Union[int, str] = 0,
                lsq: bool = False,
                write_calibrated: Optional[PathLike] = None,
                task: Optional[PathLike] = None,
                joint_columns: Optional[Sequence[str]] = None,
                point_columns: Optional[Sequence[str]] = None, joint_unit: str = "deg",
                length_unit: str = "mm", rows: Optional[str] = None,
                orientation_columns: Optional[Sequence[str]] = None,
                orientation_convention: str = "euler-xyz-deg") -> ArmReport:
    """Certify a serial arm from the files ``arm certify`` reads (``robot.toml``,
    ``measurements.csv``, ``uncertainty.toml``; mm and degrees), with the same options: ``hull``
    refines to the tight hull (``tolerance``, ``max_boxes``, ``max_seconds``), ``max_outliers``
    tolerates bad configurations (``"auto"``: the smallest number not proved empty), ``lsq`` adds
    the least-squares fit. ``write_calibrated``: write the calibrated robot file there, as
    ``--write-calibrated`` does (a parameter vector proved consistent with every measurement,
    towards the least-squares fit within the set, and the certified set); with ``task`` (a
    ``joints.toml`` box or a CSV of configurations, as ``--task``), towards the centre of the tool
    points it predicts there instead. A tracker's file as it
    comes: ``joint_columns``, ``point_columns``, ``joint_unit`` (``"deg"``/``"rad"``),
    ``length_unit`` (``"mm"``/``"m"``), ``rows`` (``"1-60"``), as ``arm certify`` takes them.
    With ``orientation_columns`` (a 6-DoF probe's Euler angles, ``orientation_convention``
    ``"euler-xyz-deg"`` or ``"euler-xyz-rad"``) six equations per configuration: the robot file
    needs the tool frame's rotation (:func:`register_arm` with ``orientation_columns``) and the
    uncertainty file ``orient_deg``; the calibrated file then holds the tool frame's rotation too.
    A robot file that carries a certified set (a calibrated file, or the file :func:`register_arm`
    writes from one in a new cell) joins that set's configurations to the new ones, each series
    in its own tracker frame, as ``arm certify`` does (the report's ``carried_over``).
    The interpreter is released while the work runs. Malformed input raises ``ValueError``
    naming the file, the line and the field."""
    opts = dict(hull=bool(hull), tolerance=float(tolerance), max_boxes=int(max_boxes),
                max_seconds=max_seconds,
                max_outliers=str(max_outliers) if isinstance(max_outliers, str)
                else str(int(max_outliers)), lsq=bool(lsq),
                write_calibrated=None if write_calibrated is None
                else os.fspath(write_calibrated),
                task=None if task is None else os.fspath(task),
                orientation_columns=None if orientation_columns is None
                else [str(c) for c in orientation_columns],
                orientation_convention=str(orientation_convention))
    cols = _columns(joint_columns, point_columns, joint_unit, length_unit, rows)
    return ArmReport(_native.arm_certify_files(os.fspath(robot), os.fspath(measurements),
                                               os.fspath(uncertainty), opts, cols))


def simulate_arm(out: PathLike, *, configs: int = 50, seed: int = 1,
                 robot: Optional[PathLike] = None,
                 outliers: Sequence[Tuple[int, float]] = ()) -> Dict[str, Any]:
    """Write a simulated data set into the folder ``out``, as ``arm simulate`` does (the built-in
    6-axis arm, or the arm of ``robot``; tracker ±0.01 mm, encoders ±0.001°): ``robot.toml``,
    ``measurements.csv``, ``uncertainty.toml`` and ``truth.json``. ``outliers`` are
    ``(configuration, delta_mm)`` with 1-based configurations. Returns the truth by name."""
    text = _native.arm_simulate(os.fspath(out), int(configs), int(seed),
                                None if robot is None else os.fspath(robot),
                                [(int(c), float(d)) for c, d in outliers])
    return json.loads(text)



def _columns(joint_columns, point_columns, joint_unit, length_unit, rows) -> Dict[str, Any]:
    """The tracker-file options as the native functions take them."""
    return dict(joint_columns=None if joint_columns is None else [str(c) for c in joint_columns],
                point_columns=None if point_columns is None else [str(c) for c in point_columns],
                joint_unit=str(joint_unit), length_unit=str(length_unit),
                rows=None if rows is None else str(rows))


def import_arm(source: PathLike, out: PathLike, *, kind: str = "ur_yaml",
               base_link: Optional[str] = None, tip_link: Optional[str] = None,
               angle_radius: float = 0.1, length_radius: float = 1.0) -> str:
    """Import a vendor's kinematics into the robot file ``out``, as ``arm import`` does:
    ``kind="ur_yaml"`` (UR's ``kinematics:`` YAML) or ``"urdf"`` (the chain from ``base_link`` to
    ``tip_link``). Exact Denavit–Hartenberg/Hayati parameters, the identifiable ones free with
    priors ``angle_radius`` (°) and ``length_radius`` (mm). Returns the file's text."""
    return _native.arm_import(os.fspath(source), str(kind), os.fspath(out), base_link, tip_link,
                              float(angle_radius), float(length_radius))


def export_arm(robot: PathLike, *, ur_yaml: Optional[PathLike] = None,
               urdf: Optional[PathLike] = None, hash: Optional[str] = None) -> None:
    """Write the arm of ``robot`` as UR's kinematics YAML (``ur_yaml``, for the UR driver; its
    ``hash`` is the file's own unless given) and/or a URDF, as ``arm export`` does. A
    least-squares fit (``arm lsq --out``) not proved consistent with its measurements raises
    ``ValueError``: it is a comparison, not a calibration."""
    if ur_yaml is None and urdf is None:
        raise ValueError("export_arm: give ur_yaml, urdf or both")
    _native.arm_export(os.fspath(robot), None if ur_yaml is None else os.fspath(ur_yaml),
                       None if urdf is None else os.fspath(urdf), hash)


def register_arm(robot: PathLike, measurements: PathLike, out: PathLike, *,
                 joint_columns: Optional[Sequence[str]] = None,
                 point_columns: Optional[Sequence[str]] = None, joint_unit: str = "deg",
                 length_unit: str = "mm", rows: Optional[str] = None,
                 base_radius: Tuple[float, float] = (2.0, 0.1),
                 tool_radius: float = 2.0,
                 orientation_columns: Optional[Sequence[str]] = None,
                 orientation_convention: str = "euler-xyz-deg",
                 tool_rotation_radius: float = 0.5) -> Dict[str, Any]:
    """Find the tracker-to-base transform and the tool point from scratch, as ``arm register``
    does, and write the robot file ``out`` with them and their priors (``base_radius``: mm and
    degrees; ``tool_radius``: mm). The measurement file is read as the command line reads it
    (``joint_columns``, ``point_columns``, ``joint_unit`` ``"deg"|"rad"``, ``length_unit``
    ``"mm"|"m"``, ``rows`` such as ``"1-60"``). Returns ``base`` (x, y, z mm, rx, ry, rz °),
    ``tool`` (mm), ``tool_kept``, ``warning``, ``rms_mm``, ``max_mm``, ``start_rms_mm`` and
    ``converged``. Where the rows cannot tell the tool point from the base (one flange
    orientation), the robot file's tool point is kept, fixed (prior 0 whatever ``tool_radius``),
    the base fitted alone, and ``warning`` says why (also raised as a ``UserWarning``). With
    ``orientation_columns`` (a 6-DoF probe's three Euler angles, ``orientation_convention``
    ``"euler-xyz-deg"`` or ``"euler-xyz-rad"``) the tool frame's rotation is registered too and
    written with the prior ``tool_rotation_radius`` (degrees): ``tool_rotation`` holds its
    ``rpy_deg`` and the orientation residuals ``rms_deg``, ``max_deg`` (else ``None``). From a
    calibrated file (one with a certified set), ``out`` carries that set on as its
    ``[carried_set]``, which :func:`certify_arm` joins to the new cell's rows."""
    cols = _columns(joint_columns, point_columns, joint_unit, length_unit, rows)
    text = _native.arm_register(os.fspath(robot), os.fspath(measurements), os.fspath(out), cols,
                                (float(base_radius[0]), float(base_radius[1]),
                                 float(tool_radius)),
                                None if orientation_columns is None else list(orientation_columns),
                                str(orientation_convention), float(tool_rotation_radius))
    result = json.loads(text)
    if result.get("warning"):
        warnings.warn(result["warning"], stacklevel=2)
    return result


def error_scale(robot: PathLike, measurements: PathLike, uncertainty: PathLike, *,
                scale_bounds: str = "all", legs: Optional[Sequence[int]] = None) -> Dict[str, Any]:
    """How much error must a Gough platform's data be allowed? The smallest factor of the
    uncertainty file's bounds (``scale_bounds``: ``"all"``, ``"pos"``, ``"len"`` or
    ``"orientation"``) for which every leg (or ``legs``, 1-based) is consistent, as ``gough certify
    --error-scale auto`` finds it: ``s_lo`` proved inconsistent, ``s_hi`` certified consistent,
    ``estimate`` (the first-order minimax fit, not a proof) and every certification tried
    (``trials``)."""
    return json.loads(_native.error_scale_files(os.fspath(robot), os.fspath(measurements),
                                                os.fspath(uncertainty), str(scale_bounds),
                                                None if legs is None else list(legs)))


def error_scale_arm(robot: PathLike, measurements: PathLike, uncertainty: PathLike, *,
                    scale_bounds: str = "all", joint_columns: Optional[Sequence[str]] = None,
                    point_columns: Optional[Sequence[str]] = None, joint_unit: str = "deg",
                    length_unit: str = "mm", rows: Optional[str] = None,
                    orientation_columns: Optional[Sequence[str]] = None,
                    orientation_convention: str = "euler-xyz-deg") -> Dict[str, Any]:
    """How much error must the data be allowed? The smallest factor of the uncertainty file's
    bounds (``scale_bounds``: ``"all"``, ``"pos"``, ``"joint_deg"`` or, with
    ``orientation_columns``, ``"orient_deg"``) for which the data are consistent, as ``arm certify
    --error-scale auto`` finds it: ``s_lo`` proved inconsistent, ``s_hi`` certified consistent,
    with every certification tried (``trials``). With ``orientation_columns`` (a 6-DoF probe's
    Euler angles, ``orientation_convention`` ``"euler-xyz-deg"`` or ``"euler-xyz-rad"``) the data
    are positions and orientations: the robot file needs the tool frame's rotation
    (:func:`register_arm` with ``orientation_columns``) and the uncertainty file ``orient_deg``."""
    cols = _columns(joint_columns, point_columns, joint_unit, length_unit, rows)
    return json.loads(_native.arm_error_scale(
        os.fspath(robot), os.fspath(measurements), os.fspath(uncertainty), cols,
        str(scale_bounds), None if orientation_columns is None else list(orientation_columns),
        str(orientation_convention)))


def predict(robot: PathLike, uncertainty: PathLike, *, poses: Optional[PathLike] = None,
            measurements: Optional[PathLike] = None) -> Dict[str, Any]:
    """Predict a Gough platform's leg readings, as ``gough predict`` does: at the poses of
    ``poses`` (a poses CSV) or of ``measurements`` (then each reading is checked), the certified
    range of every leg's reading over the geometries ``robot``'s certified set allows (its boxes
    for a file without one), and the same widened by the error bounds. Returns the JSON of
    ``gough predict --json``: ``rows`` (per pose and leg ``range``, ``with_errors``, ``inside``)
    and ``refuting`` (the readings outside: the model or the bounds are wrong there)."""
    if (poses is None) == (measurements is None):
        raise ValueError("predict: give poses or measurements (one of them)")
    return json.loads(_native.predict(os.fspath(robot), os.fspath(uncertainty),
                                      None if poses is None else os.fspath(poses),
                                      None if measurements is None
                                      else os.fspath(measurements)))


def predict_arm(robot: PathLike, uncertainty: PathLike, measurements: PathLike, *,
                joint_columns: Optional[Sequence[str]] = None,
                point_columns: Optional[Sequence[str]] = None, joint_unit: str = "deg",
                length_unit: str = "mm", rows: Optional[str] = None,
                orientation_columns: Optional[Sequence[str]] = None,
                orientation_convention: str = "euler-xyz-deg") -> Dict[str, Any]:
    """Check held-out measurements of an arm, as ``arm predict --measurements`` does: per
    configuration the certified range of each tool-point coordinate over ``robot``'s certified
    set, the same widened by the error bounds, whether the measured point lies inside, and the
    robot file's own residuals (``residuals``: ``rms_mm``, ``max_mm``). The file is read with the
    same column and unit options as :func:`register_arm`. With ``orientation_columns`` (a 6-DoF
    calibrated ``robot``, its tool frame's rotation included) also ``orientation_residuals``
    (``rms_deg``, ``max_deg``, ``per_row_deg``: the angle between each measured frame and the one
    the file's values predict)."""
    cols = _columns(joint_columns, point_columns, joint_unit, length_unit, rows)
    return json.loads(_native.arm_predict(
        os.fspath(robot), os.fspath(uncertainty), os.fspath(measurements), cols,
        None if orientation_columns is None else [str(c) for c in orientation_columns],
        str(orientation_convention)))
