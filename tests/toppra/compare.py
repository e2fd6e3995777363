#!/usr/bin/env python3
"""Time-optimal durations from toppra (PyPI), an independent reference for `--profile optimal`.

Reads JSON Lines, one move per line, as tests/it/toppra.rs writes them:
  {"line": 12, "s": [0, ..., 1], "q": [[q_1 .. q_n], ...], "vlim": [n], "alim": [n]}
where q holds the joints sampled along the move by IK (theta1..theta3 in rad, d4 in mm) and the
extra "joints" the path coordinate (mm, carrying the feed and the path acceleration) and C
(degrees, carrying rapid_rotation and rotation_acceleration), and vlim/alim the symmetric limits
of each column. Each move is timed from rest to rest by toppra's TOPPRA over a cubic spline of
the samples, on a grid of at least 1000 points refined geometrically towards both ends (so that
short ramps are resolved). Prints one line per move, `move LINE DURATION` (or `skipped LINE`
where toppra finds no parameterisation, counted as 0 s), then `total SECONDS`.

Usage: compare.py MOVES.jsonl

Torque limits (issue 36) take two runs, so that toppra's JointTorqueConstraint is given the
torques of biscara's own inverse dynamics at exactly the points where it asks for them, without a
re-implementation of the model here:
  compare.py --points MOVES.jsonl
      prints, per move, toppra's grid and the path's q, q', q'' there (the cubic spline's), as
      {"line", "p": [[..]], "ps": [[..]], "pss": [[..]]}, one move a line;
  compare.py --torques MOVES.jsonl TABLE.jsonl
      times the moves as above plus JointTorqueConstraint, whose inverse dynamics looks up the
      table (one line per move: {"c", "a", "b"}, the torques of the first four columns at
      (p, 0, 0), (p, 0, ps) and (p, ps, pss), from `biscara`'s model); MOVES.jsonl then also
      holds "tau_lim" (the four motors' symmetric bounds) and "coulomb" (their Coulomb friction).
"""

import json
import sys

import numpy as np
import toppra as ta
import toppra.algorithm as algo
import toppra.constraint as constraint


def grid(samples):
    """Uniform points, at least 1000 and 4 per sample, plus points at 0.7, 0.7², … 0.7¹⁹ (1e-3)
    of the first interval from each end (finer ones make toppra's solver fail)."""
    count = max(1000, 4 * samples)
    uniform = np.linspace(0.0, 1.0, count + 1)
    step = 1.0 / count
    near = step * 0.7 ** np.arange(1, 20)
    points = np.concatenate([uniform, near, 1.0 - near])
    return np.unique(np.clip(points, 0.0, 1.0))


def path_and_grid(move):
    ss = np.asarray(move["s"], dtype=float)
    qs = np.asarray(move["q"], dtype=float)
    return ta.SplineInterpolator(ss, qs), grid(len(ss))


def points(move):
    """The path's q, q', q'' at toppra's grid points (what JointTorqueConstraint evaluates)."""
    path, gridpoints = path_and_grid(move)
    return {
        "line": move["line"],
        "p": path.eval(gridpoints).tolist(),
        "ps": path.evald(gridpoints).tolist(),
        "pss": path.evaldd(gridpoints).tolist(),
    }


def torque_constraint(move, table):
    """JointTorqueConstraint with the inverse dynamics looked up in `table` (the torques of the
    first four columns at the grid's (p, 0, 0), (p, 0, ps), (p, ps, pss)); the other columns
    (path length, C) carry no torque."""
    path, gridpoints = path_and_grid(move)
    dof = path.dof
    p, ps, pss = path.eval(gridpoints), path.evald(gridpoints), path.evaldd(gridpoints)
    zero = np.zeros(dof)
    known = {}
    for i in range(len(gridpoints)):
        for (v, a), key in [((zero, zero), "c"), ((zero, ps[i]), "a"), ((ps[i], pss[i]), "b")]:
            tau = np.zeros(dof)
            tau[:4] = table[key][i]
            known[(p[i].tobytes(), v.tobytes(), a.tobytes())] = tau

    def inv_dyn(q, qd, qdd):
        key = (np.asarray(q, dtype=float).tobytes(), np.asarray(qd, dtype=float).tobytes(),
               np.asarray(qdd, dtype=float).tobytes())
        return known[key]

    tau_lim = np.full((dof, 2), [-1e12, 1e12])
    tau_lim[:4, 0] = -np.asarray(move["tau_lim"], dtype=float)
    tau_lim[:4, 1] = np.asarray(move["tau_lim"], dtype=float)
    friction = np.zeros(dof)
    friction[:4] = move["coulomb"]
    return constraint.JointTorqueConstraint(inv_dyn, tau_lim, friction)


def duration(move, table=None):
    vlim = np.asarray(move["vlim"], dtype=float)
    alim = np.asarray(move["alim"], dtype=float)
    path, gridpoints = path_and_grid(move)
    velocity = constraint.JointVelocityConstraint(np.stack([-vlim, vlim], axis=1))
    acceleration = constraint.JointAccelerationConstraint(np.stack([-alim, alim], axis=1))
    constraints = [velocity, acceleration]
    if table is not None:
        constraints.append(torque_constraint(move, table))
    instance = algo.TOPPRA(
        constraints,
        path,
        gridpoints=gridpoints,
        parametrizer="ParametrizeConstAccel",
    )
    trajectory = instance.compute_trajectory(0, 0)
    if trajectory is None:
        return None
    return float(trajectory.duration)


def read_lines(name):
    with open(name, encoding="utf-8") as lines:
        return [json.loads(text) for text in lines if text.strip()]


def main():
    args = sys.argv[1:]
    if len(args) == 2 and args[0] == "--points":
        for move in read_lines(args[1]):
            print(json.dumps(points(move)))
        return 0
    tables = None
    if len(args) == 3 and args[0] == "--torques":
        tables = read_lines(args[2])
        args = args[1:2]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    total = 0.0
    moves = read_lines(args[0])
    if tables is not None and len(tables) != len(moves):
        print(f"{len(moves)} moves but {len(tables)} torque tables", file=sys.stderr)
        return 2
    for index, move in enumerate(moves):
        seconds = duration(move, None if tables is None else tables[index])
        if seconds is None:
            # toppra's solver fails on some moves of a few micrometres: counted as 0 s, which
            # only makes the comparison stricter for the caller.
            print(f"skipped {move['line']}")
            continue
        total += seconds
        print(f"move {move['line']} {seconds:.6f}")
    print(f"total {total:.6f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
