#!/usr/bin/env python3
"""One row of the README's G64 P table (issue 17): a program run with exact stops and under
G64 P0.01, P0.05 and P0.1.

Usage: BISCARA=target/release/biscara scripts/blend-table.py NAME PROGRAM [ARGS...]

The program's own G61/G61.1/G64 lines are replaced by G61 or `G64 P…` (and `--blend P` is passed,
for programs that never say); ARGS (e.g. --origin or --fit) go to every run. Each cell: the
duration (last row of `interpolate`), the peak central-difference joint acceleration of `joints
--precision 9` over its limit (the largest joint), and — blended — the worst distance of a path
sample from the exact-stop run's sampled path (which lies on the programmed path). Needs numpy and
scipy.
"""
import json, math, os, re, subprocess, sys, tempfile

import numpy as np
from scipy.spatial import cKDTree

BIN = os.environ.get("BISCARA", "target/release/biscara")
NAMES = ["theta1", "theta2", "theta3", "d4"]


def run(args):
    done = subprocess.run([BIN] + args, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{args}: {done.stderr[-500:]}")
    return done.stdout


def rows(text):
    return np.array([[float(v) for v in line.split(",")] for line in text.splitlines()[1:]])


def peak(joints, limits):
    dt = joints[1, 0] - joints[0, 0]
    acceleration = np.abs(joints[2:, 1:5] - 2 * joints[1:-1, 1:5] + joints[:-2, 1:5]) / dt / dt
    ratios = (acceleration / limits).max(0)
    return ratios.max(), NAMES[int(ratios.argmax())]


def deviation(path, reference):
    points, ref = path[:, 1:4], reference[:, 1:4]
    _, nearest = cKDTree(ref).query(points, k=40)
    best = np.full(len(points), np.inf)
    for column in range(nearest.shape[1]):
        for offset in (-1, 0):
            i = np.clip(nearest[:, column] + offset, 0, len(ref) - 2)
            a, ab = ref[i], ref[i + 1] - ref[i]
            length2 = (ab * ab).sum(1)
            along = ((points - a) * ab).sum(1) / np.where(length2 > 0, length2, 1)
            t = np.where(length2 > 0, along, 0).clip(0, 1)
            best = np.minimum(best, np.sqrt(((points - a - t[:, None] * ab) ** 2).sum(1)))
    return best.max()


def main():
    name, source, extra = sys.argv[1], sys.argv[2], sys.argv[3:]
    robot = json.loads(run(["robot"]))
    limits = np.array(
        [math.radians(robot["joint_max_acceleration"][k]) for k in NAMES[:3]]
        + [robot["joint_max_acceleration"]["d4"]]
    )
    text = open(source, encoding="utf-8", errors="replace").read()
    folder = tempfile.mkdtemp()

    def sampled(mode, blend):
        program = os.path.join(folder, f"{mode.replace(' ', '')}.ngc")
        with open(program, "w") as out:
            out.write(re.sub(r"(?im)^\s*G6(1\.1|1|4)\b[^\n(;]*", mode, text))
        args = ["--precision", "9"] + (["--blend", blend] if blend else []) + extra
        return rows(run(["interpolate", program] + args)), rows(run(["joints", program] + args))

    reference, joints = sampled("G61", None)
    ratio, joint = peak(joints, limits)
    cells = [f"{reference[-1, 0]:.3f} s ({ratio:.2f} {joint})"]
    for blend in ["0.01", "0.05", "0.1"]:
        path, joints = sampled(f"G64 P{blend}", blend)
        ratio, joint = peak(joints, limits)
        cells.append(f"{path[-1, 0]:.3f} s ({ratio:.2f} {joint}, {deviation(path, reference):.4f} mm)")
    print(f"| {name} | " + " | ".join(cells) + " |")


main()
