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


def duration(move):
    ss = np.asarray(move["s"], dtype=float)
    qs = np.asarray(move["q"], dtype=float)
    vlim = np.asarray(move["vlim"], dtype=float)
    alim = np.asarray(move["alim"], dtype=float)
    path = ta.SplineInterpolator(ss, qs)
    velocity = constraint.JointVelocityConstraint(np.stack([-vlim, vlim], axis=1))
    acceleration = constraint.JointAccelerationConstraint(np.stack([-alim, alim], axis=1))
    instance = algo.TOPPRA(
        [velocity, acceleration],
        path,
        gridpoints=grid(len(ss)),
        parametrizer="ParametrizeConstAccel",
    )
    trajectory = instance.compute_trajectory(0, 0)
    if trajectory is None:
        return None
    return float(trajectory.duration)


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    total = 0.0
    with open(sys.argv[1], encoding="utf-8") as moves:
        for text in moves:
            if not text.strip():
                continue
            move = json.loads(text)
            seconds = duration(move)
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
