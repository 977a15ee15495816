"""Torque limits: pathpace vs toppra on the Panda, and our RNEA vs pinocchio's.

    .venv/bin/python bench/torque.py

(1) The Panda path of bench/run.py with URDF velocity limits and torque limits at 0.65 x the URDF effort
(so that they bind), N = 100 and 1000, identical grid. toppra: JointTorqueConstraint with the
Interpolation discretisation and pinocchio's RNEA as its inverse-dynamics callback, seidel solver,
ParametrizeConstAccel. Timed from the path onward (median). Torque violations at the grid points are
computed with pinocchio (independent of both), with s̈ of the interval on each side of every point.
(2) Inverse dynamics per call, from Python (each side pays its binding overhead) and, for ours, inside
C++ (path_torque_coefficients runs three RNEA passes per row without Python in between).
"""

import json
import logging
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import pinocchio as pin

import pathpace as pp
from pathpace.robots import example_robot_urdf

logging.disable(logging.CRITICAL)
LOCK = ("panda_finger_joint1", "panda_finger_joint2")
SCALE = 0.65


def panda():
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    ours = pp.RobotModel.from_urdf(urdf, locked_joints={n: 0.0 for n in LOCK})
    full = pin.buildModelFromUrdf(urdf)
    theirs = pin.buildReducedModel(full, [full.getJointId(n) for n in LOCK], pin.neutral(full))
    return ours, theirs


def median_ms(fn, reps):
    ts = []
    for _ in range(reps):
        t0 = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(ts), out


def torque_violation(model, data, q, dq, ddq, s, sdot, tau_max):
    th = sdot**2
    u = np.diff(th) / (2 * np.diff(s))
    worst = 0.0
    for idx in (np.arange(len(u)), np.arange(1, len(s))):
        for k, uu in zip(idx, u):
            tau = pin.rnea(model, data, q[k], dq[k] * sdot[k], ddq[k] * th[k] + dq[k] * uu)
            worst = max(worst, float(np.max(np.abs(tau) / tau_max - 1)))
    return max(0.0, worst)


def main():
    ours, theirs = panda()
    data = theirs.createData()
    rng = np.random.default_rng(0)
    lo, hi = ours.position_limits
    waypoints = lo + (hi - lo) * rng.uniform(0.1, 0.9, (5, 7))
    v = ours.velocity_limits
    tau_max = SCALE * theirs.effortLimit
    path = pp.CubicSplinePath(waypoints)

    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    tpath = ta.SplineInterpolator(np.linspace(0, 1, 5), waypoints, bc_type="not-a-knot")
    rows = []
    for N in (100, 1000):
        grid = np.linspace(0, 1, N + 1)

        def solve_ours():
            prob = pp.TimeScalingProblem(path, grid=N)
            prob.add_velocity_limits(-v, v)
            prob.add_torque_limits(ours, scale=SCALE)
            return prob.solve()

        def solve_toppra():
            vel = constraint.JointVelocityConstraint(np.column_stack([-v, v]))
            trq = constraint.JointTorqueConstraint(
                lambda q, qd, qdd: pin.rnea(theirs, data, q, qd, qdd), np.column_stack([-tau_max, tau_max]),
                np.zeros(7), discretization_scheme=constraint.DiscretizationType.Interpolation)
            inst = algo.TOPPRA([vel, trq], tpath, gridpoints=grid, solver_wrapper="seidel",
                               parametrizer="ParametrizeConstAccel")
            sdd, sd, _ = inst.compute_parameterization(0, 0)
            return sd

        t_ours, res = median_ms(solve_ours, 30 if N == 100 else 10)
        t_tp, sd = median_ms(solve_toppra, 5 if N == 100 else 3)
        q, dq, ddq = path.q(grid), path.dq(grid), path.ddq(grid)
        T_tp = float(np.sum(2 * np.diff(grid) / (sd[:-1] + sd[1:]))) if sd is not None else float("nan")
        rows.append({
            "N": N, "pathpace_ms": t_ours, "toppra_ms": t_tp, "T_pathpace": res.duration, "T_toppra": T_tp,
            "viol_pathpace": torque_violation(theirs, data, q, dq, ddq, grid, res.sdot, tau_max),
            "viol_toppra": torque_violation(theirs, data, q, dq, ddq, grid, sd, tau_max) if sd is not None else float("nan"),
            "stats": res.stats,
        })
        print(rows[-1], file=sys.stderr)

    # (2) inverse dynamics per call
    talos_urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
    import xml.etree.ElementTree as ET

    mimic = [j.get("name") for j in ET.parse(talos_urdf).getroot().iter("joint") if j.find("mimic") is not None]
    talos = pp.RobotModel.from_urdf(talos_urdf, floating_base=True, locked_joints={n: 0.0 for n in mimic})
    jc = pin.JointModelComposite()
    for j in (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(), pin.JointModelRZ(), pin.JointModelRY(), pin.JointModelRX()):
        jc.addJoint(j)
    tfull = pin.buildModelFromUrdf(talos_urdf, jc)
    ttheirs = pin.buildReducedModel(tfull, [tfull.getJointId(n) for n in mimic], pin.neutral(tfull))
    dyn = []
    for name, mine, model in (("Panda", ours, theirs), ("Talos + floating base", talos, ttheirs)):
        d = model.createData()
        n = mine.nq
        q, qd, qdd = rng.uniform(-1, 1, (3, n))
        reps = 20000
        t0 = time.perf_counter()
        for _ in range(reps):
            pin.rnea(model, d, q, qd, qdd)
        t_pin = (time.perf_counter() - t0) / reps * 1e6
        t0 = time.perf_counter()
        for _ in range(reps):
            mine.inverse_dynamics(q, qd, qdd)
        t_mine_py = (time.perf_counter() - t0) / reps * 1e6
        m = 5000
        Q, D, DD = rng.uniform(-1, 1, (3, m, n))
        t0 = time.perf_counter()
        mine.path_torque_coefficients(Q, D, DD)
        t_mine_cpp = (time.perf_counter() - t0) / (3 * m) * 1e6
        dyn.append({"robot": name, "nq": n, "pinocchio_us": t_pin, "pathpace_python_us": t_mine_py, "pathpace_cpp_us": t_mine_cpp})

    print("| N | pathpace ms | toppra ms | speed-up | T pathpace [s] | T toppra [s] | torque viol. pathpace | torque viol. toppra |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['N']} | {r['pathpace_ms']:.2f} | {r['toppra_ms']:.1f} | {r['toppra_ms'] / r['pathpace_ms']:.1f}x | "
              f"{r['T_pathpace']:.6f} | {r['T_toppra']:.6f} | {r['viol_pathpace']:.1e} | {r['viol_toppra']:.1e} |")
    print()
    print("| robot | nq | pinocchio rnea (Python call) µs | pathpace inverse_dynamics (Python call) µs | pathpace RNEA inside C++ µs |")
    print("|---|---|---|---|---|")
    for r in dyn:
        print(f"| {r['robot']} | {r['nq']} | {r['pinocchio_us']:.2f} | {r['pathpace_python_us']:.2f} | {r['pathpace_cpp_us']:.2f} |")
    out = Path(__file__).parent / "results"
    out.mkdir(exist_ok=True)
    (out / "torque.json").write_text(json.dumps({"rows": rows, "dynamics": dyn}, indent=1, default=float))


if __name__ == "__main__":
    main()
