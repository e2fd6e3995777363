#!/usr/bin/env python3
"""Benchmarks of the Python package against the Rust figures (docs/performance.md, "Python").

    python scripts/python-bench.py ik [RUNS]                  # Robot.ik on 1 M reachable poses
    python scripts/python-bench.py joints PROGRAM BINARY [RUNS]
        # biscara.joints(PROGRAM) against `BINARY joints PROGRAM -o /dev/null`, interleaved

Prints the median wall time and CPU time of each. Run it with the package installed
(pip install ./python) and, for `joints`, a release build of the command line.
"""

import resource
import statistics
import subprocess
import sys
import time

import numpy as np

import biscara


def timed(function):
    wall, cpu = time.perf_counter(), time.process_time()
    function()
    return time.perf_counter() - wall, time.process_time() - cpu


def report(name, samples):
    wall = statistics.median(s[0] for s in samples)
    cpu = statistics.median(s[1] for s in samples)
    print(f"{name}: median wall {wall * 1e3:.1f} ms, CPU {cpu * 1e3:.1f} ms ({len(samples)} runs)")
    return wall, cpu


def ik(runs):
    robot = biscara.Robot()
    rng = np.random.default_rng(1)
    # 1 M poses in the workspace rectangle of the built-in robot, all reachable.
    x0, x1, y0, y1 = robot.workspace(step=2.0)["rect"]
    n = 1_000_000
    poses = np.column_stack([
        rng.uniform(x0, x1, n), rng.uniform(y0, y1, n),
        rng.uniform(0.0, 100.0, n), rng.uniform(-170.0, 170.0, n),
    ])
    joints, mask = robot.ik(poses, errors="nan")
    print(f"{mask.sum()} of {n} poses reachable")
    report("Robot.ik, 1 M poses", [timed(lambda: robot.ik(poses, errors="nan")) for _ in range(runs)])


def cli_run(binary, program):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.perf_counter()
    subprocess.run([binary, "joints", program, "-o", "/dev/null"], check=True)
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def joints(program, binary, runs):
    rows = len(biscara.joints(program)["t_s"])
    print(f"{program}: {rows} samples")
    python, cli = [], []
    for _ in range(runs):
        python.append(timed(lambda: biscara.joints(program)))
        cli.append(cli_run(binary, program))
    py_wall, py_cpu = report("biscara.joints", python)
    cli_wall, cli_cpu = report("biscara joints -o /dev/null", cli)
    print(f"ratio Python/CLI: wall {py_wall / cli_wall:.3f}, CPU {py_cpu / cli_cpu:.3f}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["ik"]:
        ik(int(sys.argv[2]) if len(sys.argv) > 2 else 7)
    elif sys.argv[1:2] == ["joints"] and len(sys.argv) >= 4:
        joints(sys.argv[2], sys.argv[3], int(sys.argv[4]) if len(sys.argv) > 4 else 5)
    else:
        sys.exit(__doc__)
