"""pathpace against toppra on identical inputs (issue: engine benchmark).

A Panda path (example-robot-data URDF, the 7 arm joints, fingers left out): cubic spline through 5 seeded
random waypoints inside the position limits, uniform knots on [0, 1], not-a-knot; URDF velocity limits;
acceleration limits = 2 x velocity limits; rest to rest. N = 100, 1000, 10000 intervals on the same
uniform grid for both.

Timed from the path onward (median of repeated runs, single thread):
  pathpace: TimeScalingProblem + add limits + solve
  toppra:   constraint objects + TOPPRA(seidel, ParametrizeConstAccel) + compute_parameterization(0, 0)

Checked by this script's own numpy code (trusting neither library): the largest relative excess of
|q̇_j| over v_j and of |q̈_j| over a_j (a) at the grid points, with ṡ at the point and s̈ of the interval
on EACH side of it, and (b) on a dense resampling of each output trajectory in time.

    .venv/bin/python bench/run.py            (writes bench/results/latest.json and prints the table)
"""

from __future__ import annotations

import json
import logging
import os
import platform
import statistics
import sys
import time
from pathlib import Path

import numpy as np

import pathpace as pp
from pathpace.robots import example_robot_urdf, urdf_joint_limits

logging.disable(logging.CRITICAL)  # toppra logs at INFO/DEBUG

JOINTS = [f"panda_joint{i}" for i in range(1, 8)]
REPEATS = {100: 200, 1000: 40, 10000: 5}


def setup(seed=0):
    lim = urdf_joint_limits(example_robot_urdf("panda_description/urdf/panda.urdf"), JOINTS)
    rng = np.random.default_rng(seed)
    lo, hi = lim["lower"], lim["upper"]
    waypoints = lo + (hi - lo) * rng.uniform(0.1, 0.9, (5, 7))
    return waypoints, lim["velocity"], 2.0 * lim["velocity"]


def violations_at_grid(s, sdot, dq, ddq, v, a):
    """Largest relative excess at the grid points: velocity at each point, acceleration with the s̈ of
    the interval on each side (eq. 26)."""
    theta = sdot**2
    u = (theta[1:] - theta[:-1]) / (2 * np.diff(s))
    vel = np.abs(dq * sdot[:, None]) / v - 1
    acc_fwd = np.abs(ddq[:-1] * theta[:-1, None] + dq[:-1] * u[:, None]) / a - 1
    acc_bwd = np.abs(ddq[1:] * theta[1:, None] + dq[1:] * u[:, None]) / a - 1
    return max(0.0, vel.max(), acc_fwd.max(), acc_bwd.max())


def violations_dense(qd, qdd, v, a):
    return max(0.0, (np.abs(qd) / v - 1).max(), (np.abs(qdd) / a - 1).max())


def run_pathpace(waypoints, v, a, N):
    path = pp.CubicSplinePath(waypoints)

    def solve():
        prob = pp.TimeScalingProblem(path, grid=N)
        prob.add_velocity_limits(-v, v)
        prob.add_acceleration_limits(-a, a)
        return prob.solve()

    times = []
    for _ in range(REPEATS[N]):
        t0 = time.perf_counter()
        res = solve()
        times.append(time.perf_counter() - t0)
    assert res.ok, res.message
    s = res.s
    grid_v = violations_at_grid(s, res.sdot, path.dq(s), path.ddq(s), v, a)
    traj = res.trajectory()
    t = np.linspace(0, traj.duration, 20 * N + 1)
    dense_v = violations_dense(traj.qd(t), traj.qdd(t), v, a)
    return {"time_ms": 1e3 * statistics.median(times), "T": res.duration, "grid_violation": grid_v,
            "dense_violation": dense_v, "stats": res.stats}


def run_toppra(waypoints, v, a, N, interpolation=False):
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    ss = np.linspace(0, 1, waypoints.shape[0])
    path = ta.SplineInterpolator(ss, waypoints, bc_type="not-a-knot")
    grid = np.linspace(0, 1, N + 1)
    scheme = constraint.DiscretizationType.Interpolation if interpolation else constraint.DiscretizationType.Collocation

    def solve():
        vel = constraint.JointVelocityConstraint(np.column_stack([-v, v]))
        acc = constraint.JointAccelerationConstraint(np.column_stack([-a, a]), discretization_scheme=scheme)
        inst = algo.TOPPRA([vel, acc], path, gridpoints=grid, solver_wrapper="seidel",
                           parametrizer="ParametrizeConstAccel")
        sdd, sd, _ = inst.compute_parameterization(0, 0)  # toppra returns (sdd, sd, v)
        return inst, sd

    times = []
    for _ in range(max(3, REPEATS[N] // 2)):
        t0 = time.perf_counter()
        inst, sd = solve()
        times.append(time.perf_counter() - t0)
    if sd is None:
        return {"time_ms": 1e3 * statistics.median(times), "T": float("nan"), "grid_violation": float("nan"),
                "dense_violation": float("nan")}
    sdot = np.sqrt(np.maximum(sd**2, 0))
    T = float(np.sum(2 * np.diff(grid) / (sdot[:-1] + sdot[1:])))
    grid_v = violations_at_grid(grid, sdot, path(grid, 1), path(grid, 2), v, a)
    traj = inst.compute_trajectory(0, 0)
    t = np.linspace(0, traj.duration, 20 * N + 1)
    dense_v = violations_dense(traj(t, 1), traj(t, 2), v, a)
    return {"time_ms": 1e3 * statistics.median(times), "T": T, "T_trajectory": float(traj.duration),
            "grid_violation": grid_v, "dense_violation": dense_v}


def machine():
    cpu = "unknown"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    import toppra

    return {"cpu": cpu, "cores": os.cpu_count(), "python": platform.python_version(), "pathpace": pp.__version__,
            "toppra": getattr(toppra, "__version__", "?"), "numpy": np.__version__}


def main():
    waypoints, v, a = setup()
    # The two libraries must time the same path.
    import toppra as ta

    ours = pp.CubicSplinePath(waypoints)
    theirs = ta.SplineInterpolator(np.linspace(0, 1, 5), waypoints, bc_type="not-a-knot")
    s = np.linspace(0, 1, 1001)
    for order, f in enumerate((ours.q, ours.dq, ours.ddq)):
        assert np.allclose(f(s), theirs(s, order), rtol=1e-10, atol=1e-10), f"paths differ in derivative {order}"

    rows = []
    for N in (100, 1000, 10000):
        mine = run_pathpace(waypoints, v, a, N)
        tp = run_toppra(waypoints, v, a, N)
        tpi = run_toppra(waypoints, v, a, N, interpolation=True)
        rows.append({"N": N, "pathpace": mine, "toppra": tp, "toppra_interpolation": tpi})
        print(f"N={N}: pathpace {mine['time_ms']:.3f} ms T={mine['T']:.6f} | toppra {tp['time_ms']:.3f} ms "
              f"T={tp['T']:.6f}", file=sys.stderr)

    lines = [
        "| N | pathpace ms | toppra ms | speed-up | T pathpace [s] | T toppra [s] | T diff | grid viol. pathpace | grid viol. toppra | dense viol. pathpace | dense viol. toppra | toppra-interp. ms / T / grid viol. |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        m, t, ti = r["pathpace"], r["toppra"], r["toppra_interpolation"]
        lines.append(
            f"| {r['N']} | {m['time_ms']:.3f} | {t['time_ms']:.2f} | {t['time_ms'] / m['time_ms']:.1f}x | {m['T']:.6f} | "
            f"{t['T']:.6f} | {100 * (m['T'] / t['T'] - 1):+.4f} % | {m['grid_violation']:.1e} | {t['grid_violation']:.1e} | "
            f"{m['dense_violation']:.1e} | {t['dense_violation']:.1e} | {ti['time_ms']:.2f} / {ti['T']:.6f} / {ti['grid_violation']:.1e} |"
        )
    table = "\n".join(lines)
    print(table)
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "latest.json").write_text(json.dumps({"machine": machine(), "rows": rows}, indent=1, default=float))
    print(json.dumps(machine()))


if __name__ == "__main__":
    main()
