#!/usr/bin/env python3
"""MuJoCo checks of the model `biscara mjcf` writes (docs/virtual-robot.md).

Usage: check_model.py MODEL.xml TRAJ.traj.csv [--json]

TRAJ.traj.csv is the companion file `biscara mjcf --traj` writes: per row the model's joints in
MuJoCo's units (theta1..3 and the elbows in radians, d4 in metres; the elbows from our forward
kinematics) and the tool pose our FK gives.

(a) kinematic: every joint set from each row, mj_forward; the `tool` site must lie within
    0.001 mm of FK (and its rotation within 1e-9 rad of FK's C), the `connect` constraint's
    residual must be below 0.001 mm;
(b) dynamic: the position actuators driven along the trajectory with gravity on; the run must be
    stable (no MuJoCo warning, no NaN) and the tool site must follow FK's path within 1 mm at the
    95th percentile.

Prints the figures; exits 1 when a check fails, 2 on usage errors.
"""

import math
import sys

import mujoco
import numpy as np

from common import JOINTS, arguments, load, report

KINEMATIC_TOLERANCE_M = 1e-6  # 0.001 mm
ROTATION_TOLERANCE_RAD = 1e-9
RESIDUAL_TOLERANCE_M = 1e-6
DYNAMIC_P95_TOLERANCE_M = 1e-3  # 1 mm
ACTUATED = ["theta1", "theta2", "theta3", "d4"]


def wrap(angle):
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


def kinematic(model, rows):
    data = mujoco.MjData(model)
    qpos_adr = [model.joint(name).qposadr[0] for name in JOINTS]
    tool = model.site("tool").id
    equality_rows = None
    worst_tool = worst_rotation = worst_residual = 0.0
    for row in rows:
        data.qpos[:] = model.qpos0
        data.qvel[:] = 0.0
        for adr, value in zip(qpos_adr, row[1:7]):
            data.qpos[adr] = value
        mujoco.mj_forward(model, data)
        worst_tool = max(worst_tool, float(np.linalg.norm(data.site_xpos[tool] - row[7:10])))
        xmat = data.site_xmat[tool].reshape(3, 3)
        rotation = math.atan2(xmat[1, 0], xmat[0, 0])
        worst_rotation = max(worst_rotation, abs(wrap(rotation - row[10])))
        if equality_rows is None:
            equality_rows = data.efc_type[: data.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY
            if equality_rows.sum() != 3:
                raise SystemExit(f"expected 3 equality rows (one connect), found {equality_rows.sum()}")
        residual = float(np.linalg.norm(data.efc_pos[: data.nefc][equality_rows]))
        worst_residual = max(worst_residual, residual)
    return worst_tool, worst_rotation, worst_residual


def dynamic(model, rows):
    data = mujoco.MjData(model)
    mujoco.mj_resetData(model, data)
    mujoco.mj_forward(model, data)
    tool = model.site("tool").id
    columns = {name: 1 + JOINTS.index(name) for name in ACTUATED}
    actuator_ids = [model.actuator(name).id for name in ACTUATED]
    times = rows[:, 0]
    targets = rows[:, [columns[name] for name in ACTUATED]]
    # Velocity feed-forward: a position servo with damping kv lags a moving set point by
    # (kv / kp) * velocity, so the set point leads the trajectory by that much (what an industrial
    # drive's velocity feed-forward does). Velocities by central differences of the positions.
    velocities = np.gradient(targets, times, axis=0)
    lead = np.array(
        [model.actuator_biasprm[a, 2] / model.actuator_biasprm[a, 1] for a in actuator_ids]
    )
    setpoints = targets + lead * velocities
    errors = np.empty(len(rows))
    dt = model.opt.timestep
    index = 0
    while index < len(rows):
        t = data.time
        # The servo set points: the trajectory at the current time (linear between rows).
        for k, actuator in enumerate(actuator_ids):
            data.ctrl[actuator] = np.interp(t + dt, times, setpoints[:, k])
        mujoco.mj_step(model, data)
        while index < len(rows) and times[index] <= data.time + 0.5 * dt:
            errors[index] = np.linalg.norm(data.site_xpos[tool] - rows[index, 7:10])
            index += 1
        if not np.all(np.isfinite(data.qpos)):
            return None, errors, f"NaN in qpos at t = {data.time:.4f} s"
    warnings = {
        mujoco.mjtWarning(i).name: int(data.warning[i].number)
        for i in range(len(data.warning))
        if data.warning[i].number > 0
    }
    return warnings, errors, None


def main(argv):
    parsed = arguments(argv, 2, __doc__)
    if parsed is None:
        return 2
    (model_path, companion_path), as_json = parsed
    model, rows = load(model_path, companion_path)

    tool, rotation, residual = kinematic(model, rows)
    warnings, errors, failure = dynamic(model, rows)
    p95 = float(np.percentile(errors, 95)) if failure is None else float("nan")
    peak = float(np.max(errors)) if failure is None else float("nan")
    figures = {
        "mujoco_version": mujoco.__version__,
        "rows": int(len(rows)),
        "duration_s": float(rows[-1, 0]),
        "kinematic_tool_max_mm": tool * 1000.0,
        "kinematic_rotation_max_rad": rotation,
        "kinematic_residual_max_mm": residual * 1000.0,
        "dynamic_timestep_s": float(model.opt.timestep),
        "dynamic_p95_mm": p95 * 1000.0,
        "dynamic_max_mm": peak * 1000.0,
        "dynamic_warnings": warnings,
    }
    problems = []
    if tool > KINEMATIC_TOLERANCE_M:
        problems.append(f"kinematic: tool site {tool * 1000:.6f} mm from FK (limit 0.001 mm)")
    if rotation > ROTATION_TOLERANCE_RAD:
        problems.append(f"kinematic: tool rotation {rotation:.3e} rad from FK's C")
    if residual > RESIDUAL_TOLERANCE_M:
        problems.append(f"kinematic: connect residual {residual * 1000:.6f} mm (limit 0.001 mm)")
    if failure is not None:
        problems.append(f"dynamic: unstable: {failure}")
    else:
        if warnings:
            problems.append(f"dynamic: MuJoCo warnings {warnings}")
        if not p95 <= DYNAMIC_P95_TOLERANCE_M:
            problems.append(f"dynamic: tool 95th-percentile error {p95 * 1000:.4f} mm (limit 1 mm)")
    return report(figures, problems, as_json)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
