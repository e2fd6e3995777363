#!/usr/bin/env python3
"""MuJoCo's inverse dynamics against `biscara joints --torques` (docs/dynamics.md).

Usage: inverse_dynamics.py MODEL.xml COMPANION.traj.csv TORQUES.csv [--json]

MODEL.xml and COMPANION.traj.csv are what `biscara mjcf -o MODEL.xml --traj TORQUES.csv` writes;
TORQUES.csv is the joint CSV of `biscara joints --torques` (radians, with the torque columns).

At every row: the model's six joints from the companion file (the elbows from our forward
kinematics); the actuated joints' velocities and accelerations from the CSV's own columns; the
elbows' from the loop closure with MuJoCo's Jacobians (J_c·q̇ = 0, J_c·q̈ = −J̇_c·q̇, J̇_c by
central differences of J_c along q̇), where J_c is the `connect` constraint's Jacobian (the
difference of the two distal links' point Jacobians at the platform point). Then `mj_inverse`
with the constraint solver off gives the open tree's generalised forces τ_tree = M·q̈ + bias −
passive (armature, gravity, joint damping included); the loop's force λ is the one that leaves
the passive elbows unloaded (J_c[:, elbows]ᵀ·λ = τ_tree[elbows]), and the motors' torques are
τ = τ_tree[actuated] − J_c[:, actuated]ᵀ·λ. The payload column is added to the gripper body's
mass at each row; the Coulomb friction (the joints' `frictionloss`, a constraint MuJoCo's inverse
does not apply) is taken off our torques with the sign of the CSV's velocity.

The check: for every motor, the largest difference over the rows is at most 0.5 % of the
motor's peak (the actuator's force range), or of the largest torque MuJoCo gives for that joint
when the model has no force ranges. Prints the figures; exits 1 when a check fails.
"""

import sys

import mujoco
import numpy as np

from common import JOINTS, arguments, load, read_csv, report

TOLERANCE = 0.005
ACTUATED = ["theta1", "theta2", "theta3", "d4"]
ELBOWS = ["elbow1", "elbow2"]
TORQUE_COLUMNS = ["tau_theta1_Nm", "tau_theta2_Nm", "tau_theta3_Nm", "f_d4_N", "payload_kg"]


def loop_jacobian(model, data, platform):
    """J_c (3 × nv): the platform point's Jacobian on distal2 minus that on distal1."""
    point = data.xpos[platform[0]] + data.xmat[platform[0]].reshape(3, 3) @ platform[1]
    jac1 = np.zeros((3, model.nv))
    jac2 = np.zeros((3, model.nv))
    mujoco.mj_jac(model, data, jac1, None, point, platform[0])
    mujoco.mj_jac(model, data, jac2, None, point, platform[2])
    return (jac1 - jac2)[:2]  # the loop is planar: its z row is zero


def main(argv):
    parsed = arguments(argv, 3, __doc__)
    if parsed is None:
        return 2
    (model_path, companion_path, torques_path), as_json = parsed
    model, companion = load(model_path, companion_path)
    header, rows = read_csv(torques_path)
    if len(rows) != len(companion):
        raise SystemExit(f"{len(rows)} rows of torques but {len(companion)} in the companion")
    missing = [c for c in TORQUE_COLUMNS if c not in header]
    if missing or "theta1_rad" not in header:
        raise SystemExit(f"{torques_path}: needs radians and the columns {missing}")
    column = {name: header.index(name) for name in header}
    si = np.array([1.0, 1.0, 1.0, 1e-3])  # d4 in mm → m
    q_cols = [column[c] for c in ["theta1_rad", "theta2_rad", "theta3_rad", "d4_mm"]]
    qd_cols = [column[c] for c in ["dtheta1_rad_s", "dtheta2_rad_s", "dtheta3_rad_s", "dd4_mm_s"]]
    qdd_cols = [
        column[c] for c in ["ddtheta1_rad_s2", "ddtheta2_rad_s2", "ddtheta3_rad_s2", "ddd4_mm_s2"]
    ]
    ours = rows[:, [column[c] for c in TORQUE_COLUMNS[:4]]]
    payloads = rows[:, column["payload_kg"]]

    model.opt.disableflags |= int(mujoco.mjtDisableBit.mjDSBL_CONSTRAINT)
    data = mujoco.MjData(model)
    qpos_adr = {name: model.joint(name).qposadr[0] for name in JOINTS}
    dof = {name: model.joint(name).dofadr[0] for name in JOINTS}
    act = [dof[name] for name in ACTUATED]
    passive = [dof[name] for name in ELBOWS]
    eq = model.equality("platform")
    platform = (int(eq.obj1id[0]), np.array(eq.data[0:3]), int(eq.obj2id[0]))
    gripper = model.body("gripper").id
    slide_mass = float(model.body_mass[gripper])
    coulomb = np.array([model.dof_frictionloss[d] for d in act])
    if np.all(model.actuator_forcelimited == 0):
        peaks = None
    else:
        peaks = np.array([model.actuator(name).forcerange[1] for name in ACTUATED])

    def set_qpos(values):
        for name, value in zip(JOINTS, values):
            data.qpos[qpos_adr[name]] = value

    theirs = np.empty_like(ours)
    h = 1e-6
    for k in range(len(rows)):
        qpos = companion[k, 1:7]
        qd_a = rows[k, qd_cols] * si
        qdd_a = rows[k, qdd_cols] * si
        set_qpos(qpos)
        mujoco.mj_kinematics(model, data)
        mujoco.mj_comPos(model, data)
        jc = loop_jacobian(model, data, platform)
        qvel = np.zeros(model.nv)
        qvel[act] = qd_a
        qvel[passive] = np.linalg.solve(jc[:, passive], -jc[:, act] @ qd_a)
        # J̇_c·q̇ by central differences of J_c along q̇.
        jdot = []
        for sign in (1.0, -1.0):
            moved = qpos.copy()
            for i, name in enumerate(JOINTS):
                moved[i] += sign * h * qvel[dof[name]]
            set_qpos(moved)
            mujoco.mj_kinematics(model, data)
            mujoco.mj_comPos(model, data)
            jdot.append(loop_jacobian(model, data, platform))
        jdot_qd = (jdot[0] - jdot[1]) @ qvel / (2.0 * h)
        qacc = np.zeros(model.nv)
        qacc[act] = qdd_a
        qacc[passive] = np.linalg.solve(jc[:, passive], -jc[:, act] @ qdd_a - jdot_qd)
        set_qpos(qpos)
        data.qvel[:] = qvel
        data.qacc[:] = qacc
        model.body_mass[gripper] = slide_mass + payloads[k]
        mujoco.mj_inverse(model, data)
        tree = data.qfrc_inverse.copy()
        loop = np.linalg.solve(jc[:, passive].T, tree[passive])
        theirs[k] = tree[act] - jc[:, act].T @ loop
    model.body_mass[gripper] = slide_mass

    rates = rows[:, qd_cols]
    ours_without_coulomb = ours - coulomb * np.sign(rates)
    difference = np.abs(ours_without_coulomb - theirs).max(axis=0)
    largest = np.abs(theirs).max(axis=0)
    scale = peaks if peaks is not None else np.maximum(largest, 1e-9)
    relative = difference / scale
    figures = {
        "mujoco_version": mujoco.__version__,
        "rows": int(len(rows)),
        "scale": "peak" if peaks is not None else "largest torque",
        "largest_torque": dict(zip(ACTUATED, largest.tolist())),
        "max_difference": dict(zip(ACTUATED, difference.tolist())),
        "max_difference_relative": dict(zip(ACTUATED, relative.tolist())),
    }
    problems = [
        f"{name}: differs from MuJoCo by {d:.6g} ({r * 100:.4f} % of {s:.6g}, limit 0.5 %)"
        for name, d, r, s in zip(ACTUATED, difference, relative, scale)
        if not r <= TOLERANCE
    ]
    return report(figures, problems, as_json)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
