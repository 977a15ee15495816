"""Trajectory export for controllers: a ROS ``trajectory_msgs/JointTrajectory``-shaped dict.

The numerics (the C² time spline, inverse dynamics) are in C++; this module only arranges arrays.
"""

from __future__ import annotations

import math
from typing import Any, Sequence

import numpy as np

from ._core import InvalidInputError, RobotModel, Trajectory


def _duration(t: float) -> dict[str, int]:
    """builtin_interfaces/Duration (ROS 2): whole seconds and nanoseconds."""
    ns = int(round(t * 1e9))
    return {"sec": ns // 1_000_000_000, "nanosec": ns % 1_000_000_000}


def resample(traj: Trajectory, dt: float | None = None, spline: bool = False) -> dict[str, np.ndarray]:
    """Samples of the trajectory at a controller rate.

    Parameters
    ----------
    traj : Trajectory
    dt : float, optional
        Sample period in s (e.g. 0.001 for a 1 kHz controller); the duration T is appended when it is
        not a multiple of dt. None: the solver's grid times.
    spline : bool
        False (default): the exact timing, sampled (q̈ jumps at grid points, between samples): every sample
        meets the limits the problem was solved under (at every instant with ``guarantee="continuous"``).
        True: from ``traj.time_spline()``, the C² cubic spline in t through the grid (continuous q̈), which
        rings where the exact q̈ jumps: up to 1.26x the acceleration limits (measured, any N); solve with
        acceleration limits x 0.75 if the spline is what the robot executes.

    Returns
    -------
    dict
        ``t`` (m,) in s; ``q`` (m, n) in rad or m; ``qd`` (m, n) per s; ``qdd`` (m, n) per s².
    """
    t = traj.times if dt is None else traj.sample_times(dt)
    if spline:
        q, qd, qdd = traj.time_spline().evaluate(t)
    else:
        q, qd, qdd = traj.evaluate(t)
    return {"t": np.asarray(t), "q": q, "qd": qd, "qdd": qdd}


def to_joint_trajectory(
    traj: Trajectory,
    dt: float | None = None,
    joint_names: Sequence[str] | None = None,
    robot: RobotModel | None = None,
    spline: bool = False,
) -> dict[str, Any]:
    """The trajectory as a ``trajectory_msgs/JointTrajectory``-shaped dict, ready for ``json.dumps``.

    Parameters
    ----------
    traj : Trajectory
    dt : float, optional
        Controller period in s; None: one point per grid time of the solver.
    joint_names : sequence of str, optional
        Default: the robot's joint names, else ``joint_0``, ``joint_1``, ...
    robot : RobotModel, optional
        For ``effort`` (N·m or N, by inverse dynamics of the exported motion). Default: the robot whose
        torque limits or contacts shaped the trajectory; without one, ``effort`` lists are empty (as ROS
        allows).
    spline : bool
        See :func:`resample`.

    Returns
    -------
    dict
        ``{"joint_names": [...], "points": [{"positions", "velocities", "accelerations", "effort",
        "time_from_start": {"sec", "nanosec"}}, ...]}`` (ROS 2 field names; plain Python floats and ints).
    """
    smp = resample(traj, dt, spline)
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


def install() -> None:
    """Adds ``to_joint_trajectory`` and ``resample`` as methods of :class:`Trajectory`."""
    Trajectory.to_joint_trajectory = to_joint_trajectory
    Trajectory.resample = resample
