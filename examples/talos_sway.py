"""Talos sways its pelvis over each foot and back, as fast as its feet allow (the paper's fig. 1).

Talos (example-robot-data) with its floating base stands on both feet, four corner contacts per sole,
μ = 0.5 used with a 50 % friction margin and a 10 N minimum normal force per contact (sec. V.D). The
path comes from inverse kinematics: the pelvis moves sideways by ±amplitude while both soles stay flat
where they are. pathpace times it at N = 100; then the output is audited between the grid points (the
force-distribution LP at ten times the grid density) and compared with the timing under joint
velocity and acceleration limits only and with uniform timings: which of them need contact forces that
do not exist?

    .venv/bin/python examples/talos_sway.py [--plot] [--grid 100] [--amplitude 0.07]
"""

from __future__ import annotations

import argparse
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

import pathpace as pp
from pathpace.robots import example_robot_urdf

SOLES = ("left_sole_link", "right_sole_link")
# Talos's usual "half-sitting" posture: knees bent, so that the legs are far from singular.
HALF_SITTING = {
    "leg_left_3_joint": -0.411354, "leg_left_4_joint": 0.859395, "leg_left_5_joint": -0.448041,
    "leg_right_3_joint": -0.411354, "leg_right_4_joint": 0.859395, "leg_right_5_joint": -0.448041,
    "arm_left_1_joint": 0.25847, "arm_left_2_joint": 0.173046, "arm_left_4_joint": -0.525366,
    "arm_right_1_joint": -0.25847, "arm_right_2_joint": -0.173046, "arm_right_4_joint": -0.525366,
}


def kinematic_timing(robot: pp.RobotModel, path, grid: int) -> pp.Result:
    """The optimum under joint velocity limits from the URDF (1 where it has none) and 10 rad/s² (m/s²)
    acceleration limits only, no dynamics: what a contact-unaware planner would do."""
    vmax = np.where(np.isfinite(robot.velocity_limits), robot.velocity_limits, 1.0)
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(-vmax, vmax)
    prob.add_acceleration_limits(-10.0 * np.ones(robot.nq), 10.0 * np.ones(robot.nq))
    return prob.solve()


def uniform_timing(path, grid: int, T: float) -> pp.Trajectory:
    """The path at constant speed, in T s (on `grid` + 1 evenly spaced points)."""
    s = np.linspace(path.s_begin, path.s_end, grid + 1)
    return pp.Trajectory(path, s, np.full(grid + 1, (path.s_end - path.s_begin) / T))


# A fall with room (issue 21): still a fall on the timing this much slower, judged with the fall thresholds
# doubled (fall_thresholds(2.0)).
STRETCH = 1.1


def stretched(path, res: pp.Result, factor: float) -> pp.Trajectory:
    """The timing `res` run `factor` times slower (ṡ / factor at every grid point)."""
    return pp.Trajectory(path, np.asarray(res.s), np.asarray(res.sdot) / factor)


def fall_thresholds(factor: float = 2.0) -> dict:
    """Simulator.run's fall thresholds (fall_height, fall_tilt) times `factor`, read from its defaults."""
    import inspect

    from pathpace.sim import Simulator  # MuJoCo is imported only when a Simulator is built

    run = inspect.signature(Simulator.run).parameters
    return {k: factor * run[k].default for k in ("fall_height", "fall_tilt")}


def load_talos() -> pp.RobotModel:
    """Talos with its floating base; the grippers' mimic joints locked at 0 (the grippers do not move here)."""
    urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
    mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
    return pp.RobotModel.from_urdf(urdf, floating_base=True, locked_joints={n: 0.0 for n in mimic})


def standing_posture(robot: pp.RobotModel) -> np.ndarray:
    q = np.zeros(robot.nq)
    for name, value in HALF_SITTING.items():
        q[robot.joint_names.index(name)] = value
    q[2] -= robot.frame_placement(q, SOLES[0])[2, 3]  # soles on the ground, z = 0
    return q


def sole_contacts(per_side: int = 4, friction: float = 0.5) -> list[pp.Contact]:
    """Contact points on a regular grid over each sole (0.2 m x 0.1 m): the 4 corners, or 16 points."""
    side = int(round(np.sqrt(per_side)))
    xs, ys = np.linspace(-0.1, 0.1, side), np.linspace(-0.05, 0.05, side)
    return [pp.Contact(link, point=(x, y, 0.0), normal=(0, 0, 1), friction=friction)
            for link in SOLES for x in xs for y in ys]


def sole_ik(robot: pp.RobotModel, q_start: np.ndarray, base_xy: tuple[float, float], soles: dict[str, np.ndarray],
            iterations: int = 50) -> np.ndarray:
    """The posture with the pelvis at (x, y) = base_xy and each sole at its target pose (a 4x4 world
    placement per sole link; three points per sole pin it), the pelvis orientation and the upper body as
    in q_start; solved by Gauss-Newton over the pelvis height and the twelve leg joints with pathpace's
    point Jacobians, from q_start."""
    free = [2] + [i for i, n in enumerate(robot.joint_names) if n.startswith("leg_")]
    marks = [np.array(p) for p in ((0.0, 0.0, 0.0), (0.1, 0.0, 0.0), (0.0, 0.05, 0.0))]
    targets = [(soles[f] @ np.append(p, 1.0))[:3] for f in SOLES for p in marks]
    q = q_start.copy()
    q[0], q[1] = base_xy
    for _ in range(iterations):
        r = np.concatenate([(robot.frame_placement(q, f) @ np.append(p, 1.0))[:3] for f in SOLES for p in marks])
        r -= np.concatenate(targets)
        if np.max(np.abs(r)) < 1e-12:
            return q
        J = np.vstack([robot.point_jacobian(q, f, p)[:, free] for f in SOLES for p in marks])
        q[free] -= np.linalg.lstsq(J, r, rcond=None)[0]
    raise RuntimeError(f"sole IK did not converge for the pelvis at {base_xy} (residual {np.max(np.abs(r)):.2e})")


def feet_fixed_ik(robot: pp.RobotModel, q_ref: np.ndarray, base_y: float, iterations: int = 50) -> np.ndarray:
    """The posture with the pelvis at lateral offset base_y, both soles where they are in q_ref, the
    pelvis orientation, its x and the upper body unchanged (sole_ik)."""
    soles = {f: robot.frame_placement(q_ref, f) for f in SOLES}
    return sole_ik(robot, q_ref, (q_ref[0], base_y), soles, iterations)


def sway_path(robot: pp.RobotModel, amplitude: float = 0.07, knots: int = 41) -> pp.CubicSplinePath:
    """Pelvis y(s) = amplitude · sin(2π s) on s in [0, 1]: over the left foot, over the right, back; the
    joint-space spline through feet-fixed IK solutions at `knots` values of s (the feet then stay in
    place to about 1e-6 m between knots)."""
    q0 = standing_posture(robot)
    s = np.linspace(0.0, 1.0, knots)
    waypoints = [q0]
    for si in s[1:]:
        waypoints.append(feet_fixed_ik(robot, q0, amplitude * np.sin(2 * np.pi * si)))
    return pp.CubicSplinePath(np.array(waypoints), knots=s)


CONTACT_OPTIONS = dict(cone_edges=8, friction_margin=0.5, min_normal_force=10.0)


def audit(contacts: pp.ContactConstraint, traj: pp.Trajectory, samples: int) -> dict:
    """The force-distribution LP at `samples` uniform times: worst margin, and how much of the motion
    needs forces that do not exist (margin below -1e-6 N)."""
    t = np.linspace(0.0, traj.duration, samples)
    cf = contacts.force_distribution(traj.q(t), traj.qd(t), traj.qdd(t))
    margin = np.where(cf.feasible, cf.margin, -np.inf)
    return {"worst": float(np.min(margin)), "bad": float(np.mean(margin < -1e-6)), "t": t, "margin": margin, "cf": cf}


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100, help="N, grid intervals (default 100)")
    ap.add_argument("--amplitude", type=float, default=0.07, help="pelvis sway amplitude in m (default 0.07)")
    ap.add_argument("--plot", action="store_true", help="write examples/output/talos_sway.png")
    args = ap.parse_args(argv)

    robot = load_talos()
    t0 = time.perf_counter()
    path = sway_path(robot, args.amplitude)
    print(f"Talos, nq = {robot.nq}; feet-fixed IK path built in {time.perf_counter() - t0:.2f} s")
    contacts = sole_contacts(4)
    solver_cone = pp.ContactConstraint(robot, contacts, **CONTACT_OPTIONS)
    true_cone = pp.ContactConstraint(robot, contacts, cone_edges=16)  # no margins: what physics allows
    drift, which = solver_cone.max_drift(path, np.linspace(0.0, 1.0, 1001))
    print(f"largest sole drift along the path: {drift:.2e} m (contact {which})")

    prob = pp.TimeScalingProblem(path, grid=args.grid)
    t0 = time.perf_counter()
    prob.add_contacts(robot, contacts, drift_tolerance=1e-4, **CONTACT_OPTIONS)
    t_sets = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = prob.solve()
    t_solve = time.perf_counter() - t0
    print(f"contact-aware timing: {res.status.name}, T = {res.duration:.4f} s "
          f"(projection {t_sets * 1e3:.0f} ms, solve {t_solve * 1e3:.1f} ms, N = {args.grid})")
    if not res.ok:
        print(res.message)
        return {"result": res}

    # Joint velocity and acceleration limits only (no dynamics): URDF velocities, 10 rad/s² or m/s².
    res_kin = kinematic_timing(robot, path, args.grid)

    # The same without any safety margin (sec. V.D): faster, and on the edge of what the feet can do.
    bare = pp.TimeScalingProblem(path, grid=args.grid)
    bare.add_contacts(robot, contacts, cone_edges=8, drift_tolerance=1e-4)
    res_bare = bare.solve()

    samples = 10 * args.grid + 1
    timings = [("pathpace, contacts with margins", res.trajectory()), ("pathpace, contacts, no margins", res_bare.trajectory()),
               ("velocity + acceleration limits", res_kin.trajectory())]
    for factor in (1.0, 1.5, 2.0, 3.0):
        timings.append((f"uniform, T = {factor:.1f} T*", uniform_timing(path, args.grid, factor * res.duration)))
    rows = []
    print(f"\naudit at {samples} times per timing (force-distribution LP; margin in N of cone weight):")
    print(f"{'timing':34s} {'T (s)':>8s} {'worst margin, solver cone':>26s} {'worst margin, true cone':>24s} {'needs nonexistent forces':>25s}")
    for name, traj in timings:
        a_solver = audit(solver_cone, traj, samples)
        a_true = audit(true_cone, traj, samples)
        rows.append((name, traj.duration, a_solver, a_true))
        print(f"{name:34s} {traj.duration:8.3f} {a_solver['worst']:26.3f} {a_true['worst']:24.3f} {100 * a_true['bad']:24.1f}%")

    if args.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(2, 1, figsize=(8, 7))
        traj = res.trajectory()
        a = rows[0][2]
        nz = a["cf"].forces[:, :, 2]
        ax[0].plot(a["t"], nz[:, :4].sum(axis=1), label="left sole")
        ax[0].plot(a["t"], nz[:, 4:].sum(axis=1), label="right sole")
        ax[0].set_ylabel("normal force (N)")
        ax[0].set_title(f"Talos sway, contact-aware timing T = {traj.duration:.3f} s")
        ax[0].legend()
        for name, T, a_solver, a_true in rows:
            ax[1].plot(a_true["t"] / T, np.maximum(a_true["margin"], -20), label=f"{name} ({T:.2f} s)")
        ax[1].axhline(0.0, color="k", lw=0.5)
        ax[1].set_xlabel("t / T")
        ax[1].set_ylabel("margin, true cone (N)")
        ax[1].legend(fontsize=7)
        out = Path(__file__).resolve().parent / "output"
        out.mkdir(exist_ok=True)
        fig.tight_layout()
        fig.savefig(out / "talos_sway.png", dpi=110)
        print(f"plot: {out / 'talos_sway.png'}")
    return {"result": res, "rows": rows, "projection_time": t_sets, "solve_time": t_solve}


def write_report(prob: pp.TimeScalingProblem, res: pp.Result, out: str) -> None:
    """pathpace's HTML report of the timing (phase plane, torques, each link's normal force and its centre of
    pressure in its support polygon) at `out` ('' for none); says so where plotly is missing."""
    if not out:
        return
    try:
        from pathpace.report import write_report as _write
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        print(f"wrote {_write(prob, res, out)}")
    except ImportError as e:
        print(f"(no report: {e.name} is not installed)")


if __name__ == "__main__":
    main()
