"""biscara for Python: the BiSCARA toolchain's library on NumPy arrays.

Everything runs the Rust library the ``biscara`` command line runs, in this process, with the
GIL released; results come back as NumPy arrays built in Rust. Units are the command line's:
millimetres, and degrees for ``ik``/``fk`` unless ``angle_unit="rad"``; ``joints`` gives radians
unless ``angle_unit="deg"``, as ``biscara joints`` does. Errors raise :class:`biscara.Error`
with the command line's message and ``path``, ``line`` and ``column`` (None where they do not
apply); bad arguments raise ``ValueError`` or ``TypeError`` naming the argument. The pipeline's
notes (the dialect chosen, slowed motions, a placement) go to the ``logging`` logger
``"biscara"`` at level INFO.
"""

from __future__ import annotations

import json
import logging
import math
import os
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _biscara
from ._biscara import Error, __version__

__all__ = [
    "Error",
    "Robot",
    "__version__",
    "check",
    "design",
    "gen",
    "interpolate",
    "interpret",
    "joints",
    "post",
]

PathLike = Union[str, "os.PathLike[str]"]

_log = logging.getLogger("biscara")


def _error(message: str) -> Error:
    error = Error(message)
    error.path = None
    error.line = None
    error.column = None
    return error


def _log_notes(notes: Sequence[str]) -> None:
    for note in notes:
        _log.info("%s", note)


def _rows(value: Any, name: str, finite: bool = True) -> np.ndarray:
    """``value`` as a C-contiguous (N, 4) float64 array (of finite numbers, with ``finite``)."""
    array = value if isinstance(value, np.ndarray) else np.asarray(value)
    if array.dtype.kind not in "fiu":
        raise TypeError(f"{name} must hold real numbers (float64), not dtype {array.dtype}")
    if array.ndim != 2 or array.shape[1] != 4:
        raise ValueError(f"{name} must have shape (N, 4), got {array.shape}")
    array = np.ascontiguousarray(array, dtype=np.float64)
    if finite:
        _finite(array, name)
    return array


def _finite(array: np.ndarray, name: str, row: Optional[int] = None) -> None:
    if row is None:
        rows = np.isfinite(array).all(axis=1)
        if rows.all():
            return
        row = int(np.argmin(rows))
    raise ValueError(f"{name}: row {row} is not finite: {array[row].tolist()}")


def _radians(angle_unit: str) -> bool:
    if angle_unit not in ("deg", "rad"):
        raise ValueError(f'angle_unit must be "deg" or "rad", got {angle_unit!r}')
    return angle_unit == "rad"


def _number(value: Any, name: str, low: float, high: float, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, not {type(value).__name__}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite number, got {value}")
    if not low <= value <= high:
        raise ValueError(f"{name} must lie in [{low:g}, {high:g}] {unit}, got {value}")
    return value


def _numbers(value: Any, name: str, count: int) -> Tuple[float, ...]:
    if isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be {count} numbers, not a string")
    try:
        values = tuple(value)
    except TypeError:
        raise TypeError(f"{name} must be {count} numbers, not {type(value).__name__}") from None
    if len(values) != count:
        raise ValueError(f"{name} must be {count} numbers, got {len(values)}")
    return tuple(_number(v, name, -math.inf, math.inf, "") for v in values)


def _program(path: Optional[PathLike], source: Optional[str], what: str = "path"):
    if (path is None) == (source is None):
        raise TypeError(f"give either {what} or source=, exactly one")
    if source is not None:
        if not isinstance(source, str):
            raise TypeError(f"source must be a str, not {type(source).__name__}")
        return None, source
    return os.fspath(path), None


def _robot(robot: Optional["Robot"]) -> "_biscara.Robot":
    if robot is None:
        return _DEFAULT._inner
    if not isinstance(robot, Robot):
        raise TypeError(f"robot must be a biscara.Robot, not {type(robot).__name__}")
    return robot._inner


def _options(
    kind: Optional[str] = None,
    dialect: str = "auto",
    tool: Optional[str] = None,
    origin: Optional[Sequence[float]] = None,
    fit: bool = False,
    profile: str = "optimal",
    dt: float = 0.001,
    grip_time: float = 0.0,
    blend: Optional[float] = None,
    subroutine_path: Sequence[PathLike] = (),
    tool_table: Optional[PathLike] = None,
    ini: Optional[PathLike] = None,
    max_idle_jumps: int = 100_000,
    max_motions: int = 10_000_000,
    time_limit: float = 14_400.0,
) -> Dict[str, Any]:
    if kind not in (None, "gcode", "jsonl", "path"):
        raise ValueError(f'kind must be "gcode", "jsonl", "path" or None, got {kind!r}')
    if profile not in ("constant", "trapezoid", "optimal"):
        raise ValueError(f'profile must be "constant", "trapezoid" or "optimal", got {profile!r}')
    if isinstance(max_idle_jumps, bool) or not isinstance(max_idle_jumps, (int, np.integer)):
        raise TypeError("max_idle_jumps must be an int")
    if max_idle_jumps < 0:
        raise ValueError(f"max_idle_jumps must be at least 0, got {max_idle_jumps}")
    if isinstance(max_motions, bool) or not isinstance(max_motions, (int, np.integer)):
        raise TypeError("max_motions must be an int")
    if max_motions < 0:
        raise ValueError(f"max_motions must be at least 0, got {max_motions}")
    return {
        "kind": kind,
        "dialect": str(dialect),
        "tool": None if tool is None else str(tool),
        "origin": None if origin is None else _numbers(origin, "origin", 4),
        "fit": bool(fit),
        "profile": profile,
        "dt": _number(dt, "dt", 1e-6, 10.0, "s"),
        "grip_time": _number(grip_time, "grip_time", 0.0, 3600.0, "s"),
        "blend": None if blend is None else _number(blend, "blend", 0.0, 100.0, "mm"),
        "subroutine_path": [os.fspath(p) for p in subroutine_path],
        "tool_table": None if tool_table is None else os.fspath(tool_table),
        "ini": None if ini is None else os.fspath(ini),
        "max_idle_jumps": int(max_idle_jumps),
        "max_motions": int(max_motions),
        "time_limit": _number(time_limit, "time_limit", 0.0, 1e9, "s"),
    }


class Robot:
    """A robot: the built-in one, or a robot file (robot.json) validated and modelled once."""

    __slots__ = ("_inner",)

    def __init__(self) -> None:
        self._inner = _biscara.Robot()

    @classmethod
    def _wrap(cls, inner: "_biscara.Robot") -> "Robot":
        robot = cls.__new__(cls)
        robot._inner = inner
        return robot

    @classmethod
    def from_file(cls, path: PathLike) -> "Robot":
        """The robot of the file ``path`` (robot.json)."""
        return cls._wrap(_biscara.Robot.from_file(os.fspath(path)))

    @classmethod
    def from_json(cls, text: str) -> "Robot":
        """The robot described by the JSON ``text``."""
        if not isinstance(text, str):
            raise TypeError(f"text must be a str, not {type(text).__name__}")
        return cls._wrap(_biscara.Robot.from_json(text))

    def to_json(self) -> str:
        """The robot as JSON, as ``biscara robot`` prints it: a complete robot file."""
        return self._inner.to_json()

    @property
    def name(self) -> str:
        """The robot's name."""
        return self._inner.name

    def __repr__(self) -> str:
        return f"biscara.Robot({self.name!r})"

    def with_design(self, l1: float, l2: float, base: float) -> "Robot":
        """This robot with proximal links ``l1``, distal links ``l2`` and the base joints
        ``base`` apart (mm), as :func:`design` sweeps it."""
        values = [_number(v, n, 0.0, math.inf, "mm") for v, n in ((l1, "l1"), (l2, "l2"), (base, "base"))]
        return Robot._wrap(self._inner.with_design(*values))

    def ik(self, poses: Any, *, angle_unit: str = "deg", errors: str = "raise"):
        """Inverse kinematics of every row of the (N, 4) array ``poses`` (x, y, z in mm, c),
        by the library's batch (SIMD) path: the (N, 4) joints θ1, θ2, θ3, d4.

        A pose the robot cannot take (unreachable, outside a joint limit, near a singularity)
        raises :class:`Error` naming its row; with ``errors="nan"`` its row is NaN and the call
        returns ``(joints, mask)``, ``mask`` True where the pose was solved.
        """
        if errors not in ("raise", "nan"):
            raise ValueError(f'errors must be "raise" or "nan", got {errors!r}')
        radians = _radians(angle_unit)
        # The batch solver finds the poses that are not finite (one pass less over the array).
        poses = _rows(poses, "poses", finite=False)
        joints, mask, first, not_finite = self._inner.ik(poses, radians)
        if not_finite is not None:
            _finite(poses, "poses", not_finite)
        if errors == "nan":
            return joints, mask
        if first is not None:
            raise _error(first[1])
        return joints

    def fk(self, joints: Any, *, angle_unit: str = "deg", errors: str = "raise"):
        """Forward kinematics of every row of the (N, 4) array ``joints`` (θ1, θ2, θ3, d4 in
        mm): the (N, 4) poses x, y, z, c in the robot's assembly mode. Joints outside their
        limits are solved too. A row with no pose raises :class:`Error` naming it; with
        ``errors="nan"`` it is NaN and the call returns ``(poses, mask)``."""
        if errors not in ("raise", "nan"):
            raise ValueError(f'errors must be "raise" or "nan", got {errors!r}')
        radians = _radians(angle_unit)
        poses, mask, first, _ = self._inner.fk(_rows(joints, "joints"), radians)
        if errors == "nan":
            return poses, mask
        if first is not None:
            raise _error(first[1])
        return poses

    def workspace(self, step: float = 2.0) -> Dict[str, Any]:
        """The reachable XY region on a grid of ``step`` mm, as ``biscara workspace``: a dict
        with ``area_mm2``, ``step_mm``, ``rect`` (x0, x1, y0, y1 of the largest rectangle, or
        None), ``grid`` (bool, shape (len(y_mm), len(x_mm))), ``x_mm`` and ``y_mm``."""
        return self._inner.workspace(_number(step, "step", 0.0, math.inf, "mm"))


_DEFAULT = Robot()


def interpret(
    path: Optional[PathLike] = None,
    *,
    source: Optional[str] = None,
    robot: Optional[Robot] = None,
    dialect: str = "auto",
    origin: Optional[Sequence[float]] = None,
    fit: bool = False,
    tool: Optional[str] = None,
    subroutine_path: Sequence[PathLike] = (),
    tool_table: Optional[PathLike] = None,
    ini: Optional[PathLike] = None,
    max_idle_jumps: int = 100_000,
) -> List[Dict[str, Any]]:
    """A G-code program's motions, as ``biscara interpret``: the inter-file's records (one
    dict per motion or event, absolute positions in mm and degrees)."""
    path, source = _program(path, source)
    options = _options(
        dialect=dialect, origin=origin, fit=fit, tool=tool, subroutine_path=subroutine_path,
        tool_table=tool_table, ini=ini, max_idle_jumps=max_idle_jumps,
    )
    text, notes = _biscara.interpret(_robot(robot), path, source, options)
    _log_notes(notes)
    return json.loads(text)


def joints(
    path: Optional[PathLike] = None,
    *,
    source: Optional[str] = None,
    robot: Optional[Robot] = None,
    profile: str = "optimal",
    dt: float = 0.001,
    derivatives: bool = False,
    angle_unit: str = "rad",
    events: bool = False,
    torques: bool = False,
    **options: Any,
) -> Dict[str, np.ndarray]:
    """A program's joint trajectory, as ``biscara joints``: a dict of 1-D arrays named as the
    joint CSV's columns (``t_s``, ``theta1_rad``, …, ``d4_mm``; velocities and accelerations
    with ``derivatives``; with ``torques`` (which implies ``derivatives``) the motors' torques
    ``tau_theta1_Nm``, ``tau_theta2_Nm``, ``tau_theta3_Nm``, ``f_d4_N`` and the payload held,
    ``payload_kg``, each row's inverse dynamics as ``joints --torques`` writes them; the tool's
    column with ``events``).

    ``options``: ``kind``, ``dialect``, ``tool``, ``origin``, ``fit``, ``grip_time``, ``blend``,
    ``subroutine_path``, ``tool_table``, ``ini``, ``max_idle_jumps``, ``max_motions``,
    ``time_limit`` (s of robot time, 4 h by default), as the command line's flags."""
    path, source = _program(path, source)
    radians = _radians(angle_unit)
    options = _options(profile=profile, dt=dt, **options)
    columns, notes = _biscara.joints(
        _robot(robot),
        path,
        source,
        options,
        bool(derivatives),
        radians,
        bool(events),
        bool(torques),
    )
    _log_notes(notes)
    return dict(columns)


def interpolate(
    path: Optional[PathLike] = None,
    *,
    source: Optional[str] = None,
    robot: Optional[Robot] = None,
    profile: str = "optimal",
    dt: float = 0.001,
    events: bool = False,
    **options: Any,
) -> Dict[str, np.ndarray]:
    """A program's Cartesian path, as ``biscara interpolate``: a dict of 1-D arrays named as
    the path CSV's columns (``t_s``, ``x_mm``, ``y_mm``, ``z_mm``, ``c_deg``; the tool's
    column with ``events``). ``options`` as for :func:`joints`."""
    path, source = _program(path, source)
    options = _options(profile=profile, dt=dt, **options)
    columns, notes = _biscara.interpolate(_robot(robot), path, source, options, bool(events))
    _log_notes(notes)
    return dict(columns)


def check(
    path: Optional[PathLike] = None,
    *,
    source: Optional[str] = None,
    robot: Optional[Robot] = None,
    scene: Union[None, PathLike, Mapping[str, Any]] = None,
    profile: str = "optimal",
    dt: float = 0.001,
    time_limit: float = 14_400.0,
    **options: Any,
) -> Dict[str, Any]:
    """Runs a program on the virtual robot, as ``biscara check --json``: the report as a dict
    (``ok``, ``problems``, ``summary``). ``scene`` is a scene file or the scene as a dict
    (``{"boxes": [{"name": …, "min": [x, y, z], "max": [x, y, z]}]}``). A program with
    problems is not an error here: look at ``report["ok"]``. A program still moving after
    ``time_limit`` seconds of robot time (4 h by default) is an error (an endless loop)."""
    time_limit = _number(time_limit, "time_limit", 0.0, 1e9, "s")
    path, source = _program(path, source)
    options = _options(profile=profile, dt=dt, time_limit=time_limit, **options)
    scene_path = scene_text = None
    if isinstance(scene, Mapping):
        scene_text = json.dumps(scene)
    elif scene is not None:
        scene_path = os.fspath(scene)
    text, notes = _biscara.check(_robot(robot), path, source, options, scene_path, scene_text)
    _log_notes(notes)
    return json.loads(text)


def _range(value: Any, name: str) -> str:
    low, high, count = _numbers(value, name, 3)
    if count != int(count) or count < 1:
        raise ValueError(f"{name}: the count (third number) must be a whole number ≥ 1, got {count}")
    return f"{low!r}:{high!r}:{int(count)}"


def design(
    l1: Sequence[float],
    l2: Sequence[float],
    base: Sequence[float],
    *,
    robot: Optional[Robot] = None,
    step: float = 2.0,
    task: Optional[Sequence[float]] = None,
    objective: str = "rect",
    threads: int = 0,
    programs: Sequence[PathLike] = (),
    fit: bool = False,
) -> Dict[str, Any]:
    """Sweeps link lengths and base distance, as ``biscara design``: each range is
    ``(min, max, n)`` (mm, n values). A dict of 1-D arrays named as the design CSV's columns
    (``index``, ``l1``, ``l2``, ``base``, ``area_mm2``, ``rect_w_mm``, ``rect_h_mm``,
    ``rect_x0_mm``, ``rect_y0_mm``, ``gci``, ``lci_min``, ``status``; ``task_ok`` with a
    ``task`` (x0, y0, x1, y1)), and ``best``: the row of the best design by ``objective``
    (``"rect"``, ``"gci"``, ``"area"``, ``"lci_min"``, ``"time"`` or ``"cycle"``), None when
    none has a rectangle. With ``programs`` (files), each design's total time of them as
    ``joints`` runs them (``time_s``, NaN where one cannot run; centred in each design's
    rectangle first with ``fit``). With ``objective="cycle"``, each design's Adept cycle time
    (``cycle_s``, as ``biscara cycle`` times it; NaN where it cannot run), the fastest best."""
    objectives = ("rect", "gci", "area", "lci_min", "time", "cycle")
    if objective not in objectives:
        raise ValueError(f"objective must be one of {objectives}, got {objective!r}")
    if isinstance(programs, (str, bytes, os.PathLike)):
        raise TypeError("programs must be a list of paths")
    programs = [os.fspath(p) for p in programs]
    if objective == "time" and not programs:
        raise ValueError('objective="time" needs programs')
    task_text = None if task is None else ",".join(repr(v) for v in _numbers(task, "task", 4))
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 0:
        raise ValueError(f"threads must be a whole number ≥ 0, got {threads!r}")
    columns, best = _biscara.design(
        _robot(robot), _range(l1, "l1"), _range(l2, "l2"), _range(base, "base"),
        _number(step, "step", 0.0, math.inf, "mm"), task_text, objective, int(threads),
        programs, bool(fit),
    )
    columns["status"] = np.asarray(columns["status"])
    columns["best"] = best
    return columns


def gen(
    path: Optional[PathLike] = None,
    *,
    source: Optional[str] = None,
    robot: Optional[Robot] = None,
    line_numbers: bool = False,
) -> str:
    """A pick-and-place points file (or its text) turned into G-code, as ``biscara gen``."""
    path, source = _program(path, source)
    return _biscara.gen(_robot(robot), path, source, bool(line_numbers))


def post(
    source: Optional[str] = None,
    *,
    path: Optional[PathLike] = None,
    line_numbers: bool = False,
) -> str:
    """A CL file's text (or the file ``path=``) turned into G-code for LinuxCNC, as
    ``biscara post``."""
    path, source = _program(path, source, what="the CL text or path=")
    text, note = _biscara.post(path, source, bool(line_numbers))
    if note is not None:
        _log.info("%s", note)
    return text
