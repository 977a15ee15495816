"""Export of results and trajectories: dicts (JSON-ready), CSV, and waypoint CSV input."""

from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from ._core import Result, Trajectory


def _require(value: Any, kind: type | tuple[type, ...], name: str, expected: str) -> None:
    """A TypeError naming the argument and the expected type (not an AttributeError from deep inside)."""
    if not isinstance(value, kind):
        got = "None" if value is None else type(value).__name__
        raise TypeError(f"{name} must be {expected}, got {got}")


def result_to_dict(res: Result) -> dict[str, Any]:
    """Everything a result holds, as plain Python types (JSON-serialisable)."""
    _require(res, Result, "res", "a pathpace.Result")
    finite = lambda v: None if v is None or (isinstance(v, float) and not math.isfinite(v)) else v  # noqa: E731
    return {
        "status": res.status.name.lower(),
        "ok": res.ok,
        "message": res.message,
        "duration": finite(float(res.duration)),
        "s": res.s.tolist(),
        "sdot": res.sdot.tolist(),
        "times": res.times.tolist(),
        "sddot": res.sddot.tolist(),
        "infeasible_index": int(res.infeasible_index),
        "infeasible_s": finite(float(res.infeasible_s)),
        "binding_constraints": list(res.binding_constraints),
        "stats": dict(res.stats),
        "contact_drift": [dict(d) for d in res.contact_drift],
    }


def save_result_json(res: Result, path: str | Path) -> None:
    _require(path, (str, os.PathLike), "path", "a str or os.PathLike")
    Path(path).write_text(json.dumps(result_to_dict(res), indent=1))


def trajectory_to_dict(traj: Trajectory, dt: float) -> dict[str, Any]:
    """Uniform resampling at dt: t (m,), q, qd, qdd (m, n) as nested lists."""
    _require(traj, Trajectory, "traj", "a pathpace.Trajectory")
    smp = traj.sample(dt)
    return {key: np.asarray(val).tolist() for key, val in smp.items()} | {"duration": traj.duration}


def save_trajectory_csv(traj: Trajectory, path: str | Path, dt: float, joint_names: list[str] | None = None) -> None:
    """CSV with columns t, q_<j>..., qd_<j>..., qdd_<j>... sampled every dt (and at T)."""
    _require(traj, Trajectory, "traj", "a pathpace.Trajectory")
    _require(path, (str, os.PathLike), "path", "a str or os.PathLike")
    if joint_names is not None:
        _require(joint_names, (list, tuple), "joint_names", "a list of str")
    smp = traj.sample(dt)
    n = smp["q"].shape[1]
    names = joint_names if joint_names is not None else [str(j) for j in range(n)]
    if len(names) != n:
        from ._core import InvalidInputError

        raise InvalidInputError(f"joint_names has {len(names)} entries, the trajectory has {n} coordinates")
    header = ["t"] + [f"q_{a}" for a in names] + [f"qd_{a}" for a in names] + [f"qdd_{a}" for a in names]
    data = np.column_stack([smp["t"], smp["q"], smp["qd"], smp["qdd"]])
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(data.tolist())


def load_waypoints_csv(path: str | Path) -> np.ndarray:
    """A (K, n) array from a CSV of waypoints, one per row; a header row of names is skipped."""
    _require(path, (str, os.PathLike), "path", "a str or os.PathLike")
    from ._core import InvalidInputError

    rows = []
    with open(path, newline="") as f:
        for i, row in enumerate(csv.reader(f)):
            if not row:
                continue
            try:
                values = [float(x) for x in row]
            except ValueError:
                if i == 0:
                    continue  # header
                raise InvalidInputError(f"{path}: row {i + 1} is not numeric: {row}") from None
            bad = [j for j, v in enumerate(values) if not math.isfinite(v)]
            if bad:
                raise InvalidInputError(f"{path}: row {i + 1}, column {bad[0] + 1} = {values[bad[0]]} must be finite")
            if rows and len(values) != len(rows[0]):
                raise InvalidInputError(
                    f"{path}: row {i + 1} has {len(values)} values, the first waypoint has {len(rows[0])}"
                )
            rows.append(values)
    if not rows:
        raise InvalidInputError(f"{path}: no waypoints (expected one numeric row per waypoint)")
    return np.asarray(rows, dtype=float)
