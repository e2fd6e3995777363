"""What the MuJoCo scripts here share: their command line, the model `biscara mjcf` writes with
its companion trajectory file (`mjcf --traj`), and how a check reports.

The scripts import it as a sibling (`python3 tests/mujoco/SCRIPT.py` puts this folder first on
the module path).
"""

import json
import sys

import mujoco
import numpy as np

# The model's joints, in the companion file's column order after t_s.
JOINTS = ["theta1", "theta2", "theta3", "d4", "elbow1", "elbow2"]
COMPANION_HEADER = ["t_s"] + JOINTS + ["tool_x_m", "tool_y_m", "tool_z_m", "tool_phi_rad"]


def arguments(argv, count, usage):
    """The `count` positional arguments and whether `--json` was given; `None` after printing
    `usage` on standard error when there are not `count` of them."""
    args = [a for a in argv if a != "--json"]
    if len(args) != count:
        print(usage, file=sys.stderr)
        return None
    return args, "--json" in argv


def read_csv(path):
    """A CSV's header (a list of names) and its rows (a 2-D array)."""
    with open(path, encoding="utf-8") as f:
        header = f.readline().strip().split(",")
    return header, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def load(model_path, companion_path):
    """The model and its companion file's rows: per row t_s, the model's joints in MuJoCo's units
    (radians, d4 in metres) and the tool pose of our forward kinematics. Exits when the companion
    is not one (its header) or has fewer than two rows."""
    model = mujoco.MjModel.from_xml_path(model_path)
    header, rows = read_csv(companion_path)
    if header != COMPANION_HEADER:
        raise SystemExit(
            f"{companion_path}: unexpected header {header}, expected {COMPANION_HEADER}"
        )
    if len(rows) < 2:
        raise SystemExit(f"{companion_path}: fewer than two rows")
    return model, rows


def set_joints(model, data, row):
    """Sets the model's joints in `data` from a companion row."""
    for name, value in zip(JOINTS, row[1:7]):
        data.qpos[model.joint(name).qposadr[0]] = value


def report(figures, problems, as_json):
    """Prints the figures and the problems (JSON on one line, or `key: value` lines); the exit
    code: 1 when there are problems, else 0."""
    figures["problems"] = problems
    if as_json:
        print(json.dumps(figures))
    else:
        for key, value in figures.items():
            print(f"{key}: {value}")
    return 1 if problems else 0
