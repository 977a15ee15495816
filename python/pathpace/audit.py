"""Audit any trajectory (e.g. a CSV from another planner or a controller log) against a problem file:
the worst margin of each constraint. Dynamics and contact forces come from the C++ core."""

from __future__ import annotations

import csv
import os
from pathlib import Path
from typing import Any

import numpy as np

from ._core import InvalidInputError
from .progress import ProgressBar


def load_trajectory_csv(file: str | os.PathLike, joint_names: list[str]) -> dict[str, np.ndarray]:
    """t, q and (when present) qd, qdd from a CSV with a header: ``t`` and ``q_<joint>`` or ``<joint>``
    columns (``qd_<joint>``, ``qdd_<joint>`` optional), or ``q_<index>``. Missing qd/qdd are taken by
    second-order finite differences in t (``numpy.gradient``)."""
    path = Path(file)
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise InvalidInputError(f"{path}: cannot be read ({e.strerror or e})") from None
    if len(rows) < 3:
        raise InvalidInputError(f"{path}: expected a header row and at least 2 samples, got {len(rows)} rows")
    header = [h.strip() for h in rows[0]]
    try:
        data = np.array([[float(x) for x in r] for r in rows[1:] if r], dtype=float)
    except ValueError:
        raise InvalidInputError(f"{path}: a row after the header is not numeric") from None
    col = {h: i for i, h in enumerate(header)}
    if "t" not in col:
        raise InvalidInputError(f"{path}: no column 't' (header: {', '.join(header)})")

    def block(prefix: str, required: bool) -> np.ndarray | None:
        idx = []
        for j, name in enumerate(joint_names):
            for key in (f"{prefix}{name}", f"{prefix}{j}") + ((name,) if prefix == "q_" else ()):
                if key in col:
                    idx.append(col[key])
                    break
            else:
                if required:
                    raise InvalidInputError(f"{path}: no column '{prefix}{name}' (or '{name}') for joint {j} '{name}'")
                return None
        return data[:, idx]

    t = data[:, col["t"]]
    if np.any(np.diff(t) <= 0):
        raise InvalidInputError(f"{path}: column 't' must be strictly increasing")
    q = block("q_", True)
    qd = block("qd_", False)
    qdd = block("qdd_", False)
    if qd is None:
        qd = np.gradient(q, t, axis=0, edge_order=2)
    if qdd is None:
        qdd = np.gradient(qd, t, axis=0, edge_order=2)
    return {"t": t, "q": q, "qd": qd, "qdd": qdd}


def _row(name: str, margins: np.ndarray, scale: np.ndarray, t: np.ndarray, where: list[str], unit) -> dict[str, Any]:
    """The worst (smallest) margin over samples (rows) and joints (columns); `unit` is one string, or one per
    joint (the worst joint's is reported)."""
    k, j = np.unravel_index(int(np.argmin(margins)), margins.shape)
    return {"constraint": name, "margin": float(margins[k, j]), "scale": float(scale[j]),
            "unit": unit if isinstance(unit, str) else unit[j], "t": float(t[k]), "where": where[j] if where else ""}


def _units(spec, n: int, suffix: str, torque: bool = False) -> list[str]:
    """Per joint: rad or m (from the robot's joint kinds), then `suffix`; "rad or m" without a robot."""
    kinds = list(spec.robot.joint_units) if spec.robot is not None and spec.robot.nq == n else None
    if torque:
        return ["N" if k == "m" else "N·m" for k in kinds] if kinds else ["N·m or N"] * n
    return [k + suffix for k in kinds] if kinds else [f"rad{suffix} or m{suffix}"] * n


def _bound_margins(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    margins = np.minimum(hi - x, x - lo)
    finite = np.isfinite(lo) & np.isfinite(hi)
    scale = np.where(finite, np.maximum(np.abs(hi), np.abs(lo)), np.where(np.isfinite(hi), np.abs(hi), np.abs(lo)))
    scale = np.where(np.isfinite(scale) & (scale > 0), scale, 1.0)
    return np.where(np.isfinite(margins), margins, np.inf), scale


def audit_trajectory(spec, traj: dict[str, np.ndarray], progress: bool = False, chunk: int = 500) -> list[dict[str, Any]]:
    """One row per constraint of the problem: the worst margin (limit minus value; < 0 is a violation),
    the limit's size (``scale``), its unit, and where (time, joint). Contacts: the force-distribution LP's
    margin in N."""
    t, q, qd, qdd = traj["t"], traj["q"], traj["qd"], traj["qdd"]
    names = list(spec.joint_names)
    rows = []
    robot = spec.robot
    if robot is not None:
        lim = robot.position_limits
        if np.isfinite(lim).any():
            m, sc = _bound_margins(q, lim[0], lim[1])
            rows.append(_row("position", m, sc, t, names, _units(spec, q.shape[1], "")))
    if spec.velocity_limits is not None:
        m, sc = _bound_margins(qd, *spec.velocity_limits)
        rows.append(_row("velocity", m, sc, t, names, _units(spec, q.shape[1], "/s")))
    if spec.acceleration_limits is not None:
        m, sc = _bound_margins(qdd, *spec.acceleration_limits)
        rows.append(_row("acceleration", m, sc, t, names, _units(spec, q.shape[1], "/s²")))
    if spec.torque_limits is not None:
        # τ = a ṡ² + b s̈ + c (eq. 12) of the motion itself (ṡ = 1, s̈ = 0): M q̈ + C q̇ + g by batch RNEA.
        a, _, c = robot.path_torque_coefficients(q, qd, qdd)
        m, sc = _bound_margins(a + c, spec.torque_limits.tau_min, spec.torque_limits.tau_max)
        rows.append(_row("torque", m, sc, t, names, _units(spec, q.shape[1], "", torque=True)))
    for c in getattr(spec, "frame_limits", []):
        rows.append(_frame_row(robot, c, t, q, qd, qdd))
    if spec.contacts is not None:
        margins = np.empty(len(t))
        with ProgressBar(len(t), "contact forces", enabled=progress) as bar:
            for i in range(0, len(t), chunk):
                margins[i : i + chunk] = spec.contacts.force_distribution(q[i : i + chunk], qd[i : i + chunk],
                                                                          qdd[i : i + chunk]).margin
                bar.update(min(chunk, len(t) - i))
        rows.append(_row("contact", margins[:, None], np.ones(1), t, [], "N"))
    return rows


_FRAME_UNITS = {"translational_speed": "m/s", "linear_velocity": "m/s", "angular_velocity": "rad/s",
                "linear_acceleration": "m/s²", "angular_acceleration": "rad/s²"}


def _frame_row(robot, c, t: np.ndarray, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray) -> dict[str, Any]:
    """A FrameLimits of the problem (limits.frames) on the motion itself: robot.path_frame_motion with
    p' = q̇ and p'' = q̈ (ṡ = 1, s̈ = 0) is the point's velocity J q̇, the link's angular velocity and their
    classical accelerations, in the world frame; frame "local" takes their components on the link's axes
    (Rᵀ x, R from frame_placement)."""
    v, w, a, alpha = robot.path_frame_motion(q, qd, qdd, c.link, c.point)
    name = f"frame {c.link} {c.quantity}"
    unit = _FRAME_UNITS[c.quantity]
    if c.quantity == "translational_speed":
        speed = np.linalg.norm(v, axis=1)[:, None]
        m, sc = _bound_margins(speed, np.array([-np.inf]), np.asarray(c.hi, dtype=float).reshape(1))
        return _row(name, m, sc, t, [], unit)
    x = {"linear_velocity": v, "angular_velocity": w, "linear_acceleration": a, "angular_acceleration": alpha}[c.quantity]
    if c.frame == "local":
        R = np.stack([np.asarray(robot.frame_placement(qi, c.link))[:3, :3] for qi in q])
        x = np.einsum("kji,kj->ki", R, x)
    m, sc = _bound_margins(x, np.asarray(c.lo, dtype=float), np.asarray(c.hi, dtype=float))
    return _row(name, m, sc, t, ["x", "y", "z"], unit)

