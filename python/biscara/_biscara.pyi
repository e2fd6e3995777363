"""Type stubs of the extension module `biscara._biscara` (the Rust part; use `biscara`)."""

from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class Error(Exception):
    path: Optional[str]
    line: Optional[int]
    column: Optional[int]

_Solved = Tuple[
    npt.NDArray[np.float64], npt.NDArray[np.bool_], Optional[Tuple[int, str]], Optional[int]
]
_Table = Tuple[List[Tuple[str, npt.NDArray[np.float64]]], List[str]]

class Robot:
    def __init__(self) -> None: ...
    @staticmethod
    def from_file(path: str) -> Robot: ...
    @staticmethod
    def from_json(text: str) -> Robot: ...
    def to_json(self) -> str: ...
    @property
    def name(self) -> str: ...
    def with_design(self, l1: float, l2: float, base: float) -> Robot: ...
    def ik(self, poses: npt.NDArray[np.float64], radians: bool) -> _Solved: ...
    def fk(self, joints: npt.NDArray[np.float64], radians: bool) -> _Solved: ...
    def workspace(self, step: float) -> Dict[str, Any]: ...

def interpret(
    robot: Robot, path: Optional[str], source: Optional[str], options: Dict[str, Any]
) -> Tuple[str, List[str]]: ...
def joints(
    robot: Robot,
    path: Optional[str],
    source: Optional[str],
    options: Dict[str, Any],
    derivatives: bool,
    radians: bool,
    events: bool,
    torques: bool,
) -> _Table: ...
def interpolate(
    robot: Robot, path: Optional[str], source: Optional[str], options: Dict[str, Any], events: bool
) -> _Table: ...
def check(
    robot: Robot,
    path: Optional[str],
    source: Optional[str],
    options: Dict[str, Any],
    scene_path: Optional[str],
    scene_text: Optional[str],
) -> Tuple[str, List[str]]: ...
def design(
    robot: Robot,
    l1: str,
    l2: str,
    base: str,
    step: float,
    task: Optional[str],
    objective: str,
    threads: int,
    programs: List[str],
    fit: bool,
) -> Tuple[Dict[str, Any], Optional[int]]: ...
def gen(robot: Robot, path: Optional[str], source: Optional[str], line_numbers: bool) -> str: ...
def post(
    path: Optional[str], source: Optional[str], line_numbers: bool
) -> Tuple[str, Optional[str]]: ...
