#!/usr/bin/env python3
"""The README's comparison of LinuxCNC's planner with this project's time-optimal trajectory.

For each robot file and data program: LinuxCNC's own planner with the robot file's Cartesian
limits as they are (`--limits cartesian`), with the axis limits derived from the joint limits
over the workspace rectangle (`--limits derived`, the default), with them derived over the
program's own region (`linuxcnc config --for PROGRAM`, then `run --config`), and `biscara
joints` (time-optimal profile) played through the stream path (`--stream`). Prints a Markdown table: each run's duration and its largest
joint velocity and acceleration as a share of the joint's limit (the joint named), over theta1,
theta2, theta3 and d4.

Usage: scripts/linuxcnc-comparison.py [BISCARA [ONLY [MODE]]] > table.md (ONLY: rows whose robot
or program contains it, "" for all; MODE: only the columns whose name contains it)   (needs LinuxCNC; runs serially,
in real time: about 20 minutes for the full table)
"""

import re
import subprocess
import sys
import tempfile

BISCARA = sys.argv[1] if len(sys.argv) > 1 else "target/release/biscara"
# (robot file, program, extra arguments: the placement each program's header asks for)
PLACED = {
    "arcs_and_offsets.ngc": [],
    "pick_place_inch.ngc": [],
    "pen_plot.ngc": ["--origin", "-30,280,10,0", "--tool", "pen"],
    "laser_engraving.ngc": ["--origin", "-30,250,0,0", "--tool", "laser"],
    "engraving_arcs.ngc": ["--origin", "-75,300,20,0", "--tool", "spindle"],
}
CASES = [("default.json", program) for program in PLACED] + [
    ("weak-motors.json", "arcs_and_offsets.ngc"),
    ("weak-motors.json", "pick_place_inch.ngc"),
    ("asymmetric.json", "arcs_and_offsets.ngc"),
    ("asymmetric.json", "pick_place_inch.ngc"),
]
MODES = [
    ("LinuxCNC, Cartesian limits", ["--limits", "cartesian"]),
    ("LinuxCNC, derived limits", ["--limits", "derived"]),
    ("LinuxCNC, job limits (`--for`)", ["--for"]),
    ("optimal profile, streamed", ["--stream"]),
]
PEAK = re.compile(r"(\w+): peak ([\d.]+) \S+ of ([\d.]+) \(\d+ %\), ([\d.]+) \S+ of ([\d.]+)")
NAMES = {"theta1": "θ1", "theta2": "θ2", "theta3": "θ3", "d4": "d4"}
DURATION = re.compile(r"LinuxCNC \w+ \S+: ([\d.]+) s")


def run(robot, program, extra):
    with tempfile.TemporaryDirectory() as folder:
        robot_args = ["--robot", f"data/robots/{robot}"]
        if extra == ["--for"]:
            # A configuration for the program's region, with the placement the program runs with.
            origin = PLACED[program][:2] if PLACED[program][:1] == ["--origin"] else []
            tool = PLACED[program][2:] if origin else PLACED[program]
            config = [BISCARA, *robot_args, "linuxcnc", "config", "--for",
                      f"data/programs/{program}", *origin, *tool, "-o", f"{folder}/cfg"]
            done = subprocess.run(config, capture_output=True, text=True)
            if done.returncode != 0:
                return "failed: " + done.stderr.strip().splitlines()[-1]
            extra = ["--config", f"{folder}/cfg", *origin]
            placed = []
        else:
            placed = PLACED[program]
        command = [BISCARA, *robot_args, "linuxcnc", "run", f"data/programs/{program}",
                   "-o", f"{folder}/run.csv", *placed, *extra]
        done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        return "failed: " + done.stderr.strip().splitlines()[-1]
    duration = float(DURATION.search(done.stderr).group(1))
    peaks = [(NAMES[joint], 100 * float(v) / float(vl), 100 * float(a) / float(al))
             for joint, v, vl, a, al in PEAK.findall(done.stderr)]
    velocity = max(peaks, key=lambda peak: peak[1])
    acceleration = max(peaks, key=lambda peak: peak[2])
    return (f"{duration:.2f} s, {velocity[0]} {velocity[1]:.1f} % / "
            f"{acceleration[0]} {acceleration[2]:.1f} %")


def main():
    modes = [mode for mode in MODES if len(sys.argv) < 4 or sys.argv[3] in mode[0]]
    print("| robot | program | " + " | ".join(name for name, _ in modes) + " |")
    print("| --- | --- | " + " | ".join("---" for _ in modes) + " |")
    only = sys.argv[2] if len(sys.argv) > 2 else None
    for robot, program in CASES:
        if only and only not in f"{robot} {program}":
            continue
        cells = [run(robot, program, extra) for _, extra in modes]
        print(f"| {robot} | {program} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
