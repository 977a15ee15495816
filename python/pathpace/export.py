"""Trajectory export for controllers: a ROS ``trajectory_msgs/JointTrajectory``-shaped dict.

The numerics (sampling, the C² time spline, inverse dynamics) are in C++; this module only arranges
arrays. The C++ module binds ``Trajectory.to_joint_trajectory`` to the function here.
"""

from __future__ import annotations

import math
from typing import Any, Sequence


from ._core import InvalidInputError, RobotModel, Trajectory


def _duration(t: float) -> dict[str, int]:
    """builtin_interfaces/Duration (ROS 2): whole seconds and nanoseconds."""
    ns = int(round(t * 1e9))
    return {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000}


def to_joint_trajectory(
    traj: Trajectory,
    dt: float | None = None,
    joint_names: Sequence[str] | None = None,
    robot: RobotModel | None = None,
    spline: bool = False,
) -> dict[str, Any]:
    """Trajectory.to_joint_trajectory (its docstring: cpp/bindings/docstrings.txt)."""
    smp = traj.resample(dt, spline)
    n = smp["q"].shape[1]
    robot = robot if robot is not None else traj.robot
    if joint_names is None:
        joint_names = list(robot.joint_names) if robot is not None and robot.nq == n else [f"joint_{j}" for j in range(n)]
    joint_names = list(joint_names)
    if len(joint_names) != n:
        raise InvalidInputError(f"joint_names has {len(joint_names)} entries, the trajectory has {n} coordinates")
    if robot is not None:
        if robot.nq != n:
            raise InvalidInputError(f"robot '{robot.name}' has {robot.nq} joints, the trajectory has {n} coordinates")
        # τ = a ṡ² + b s̈ + c (eq. 12) of the path q(t) itself (ṡ = 1, s̈ = 0) is M q̈ + C q̇ + g: batch RNEA.
        a, _, c = robot.path_torque_coefficients(smp["q"], smp["qd"], smp["qdd"])
        effort = (a + c).tolist()
    else:
        effort = [[] for _ in range(len(smp["t"]))]
    points = [
        {
            "positions": p,
            "velocities": v,
            "accelerations": acc,
            "effort": e,
            "time_from_start": _duration(float(t)),
        }
        for t, p, v, acc, e in zip(smp["t"], smp["q"].tolist(), smp["qd"].tolist(), smp["qdd"].tolist(), effort)
    ]
    if any(not math.isfinite(x) for pt in points for x in pt["positions"]):
        raise InvalidInputError("the trajectory has non-finite positions: nothing to export")
    return {"joint_names": joint_names, "points": points}
