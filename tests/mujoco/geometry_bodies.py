#!/usr/bin/env python3
"""The bodies `biscara mjcf` writes for a robot without `dynamics` against MuJoCo's own masses and
inertias of the geoms, solid aluminium (docs/dynamics.md).

Usage: geometry_bodies.py MODEL.xml

MODEL.xml carries explicit inertials (from `biscara-dynamics`). The same model with the inertials
removed and MuJoCo computing them from the geoms at 2,700 kg/m³ must give the same mass, centre
and vertical inertia for each link, the same mass for the gripper body (the slide), and without
the column the same inertia about the tool axis (the tool). Exits 1
when they differ by more than 1e-9 relative.
"""

import re
import sys

import mujoco
import numpy as np


def vertical_inertia(model, body):
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.body_iquat[body])
    rotation = rotation.reshape(3, 3)
    return float((rotation @ np.diag(model.body_inertia[body]) @ rotation.T)[2, 2])


def main(argv):
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    text = open(argv[0], encoding="utf-8").read()
    ours = mujoco.MjModel.from_xml_string(text)
    geoms = re.sub(r"\s*<inertial [^>]*/>", "", text)
    geoms = geoms.replace('inertiafromgeom="false"', 'inertiafromgeom="true"')
    geoms = geoms.replace('<geom contype="0" conaffinity="0"/>', '<geom contype="0" conaffinity="0" density="2700"/>')
    theirs = mujoco.MjModel.from_xml_string(geoms)
    problems = []

    def compare(what, a, b):
        print(f"{what}: ours {a:.12g}, from the geoms {b:.12g}")
        if abs(a - b) > 1e-9 * max(abs(b), 1e-12):
            problems.append(what)

    for name in ["proximal1", "distal1", "proximal2", "distal2"]:
        a, b = ours.body(name).id, theirs.body(name).id
        compare(f"{name} mass", ours.body_mass[a], theirs.body_mass[b])
        for axis in range(2):
            compare(f"{name} centre[{axis}]", ours.body_ipos[a][axis], theirs.body_ipos[b][axis])
        compare(f"{name} inertia zz", vertical_inertia(ours, a), vertical_inertia(theirs, b))
    compare("gripper (slide) mass", ours.body_mass[ours.body("gripper").id],
            theirs.body_mass[theirs.body("gripper").id])
    # The tool: the gripper and its finger (the column turns with the distal link, not with θ3)
    # about the tool axis.
    tool_only = mujoco.MjModel.from_xml_string(re.sub(r"\s*<geom name=\"column\"[^>]*/>", "", geoms))
    g = tool_only.body("gripper").id
    about_axis = vertical_inertia(tool_only, g) + tool_only.body_mass[g] * float(
        tool_only.body_ipos[g][0] ** 2 + tool_only.body_ipos[g][1] ** 2
    )
    compare("tool inertia about its axis", ours.body_inertia[ours.body("gripper").id][2], about_axis)
    if problems:
        print(f"differ: {problems}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
