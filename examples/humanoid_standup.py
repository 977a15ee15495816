"""Talos stands up from a deep squat, timed three ways and executed in MuJoCo (the paper's fig. 6).

The path: both soles fixed, the pelvis 0.22 m below its standing height and pitched 0.4 rad forward
(torso pitched 0.2 rad more, arms 0.3 rad forward) at s = 0, rising to the half-sitting posture at s = 1.
Each knot is a feet-fixed IK solution by Gauss-Newton on pathpace's point Jacobians (the centre of mass's
by central differences of RobotModel.center_of_mass), with the centre of mass 6 cm ahead of the middle of
the soles in the squat (on the balls of the feet, as a person rises from a deep squat), moving back to
the middle as the robot stands.

The robot's motors are weaker than its URDF says (TORQUE_SCALE x its effort, in the plan and in the
simulator): just strong enough for the hips to hold the squat, as on the paper's robot, so that torque
limits bind where the rise begins. The three timings:
- torque and contact limits, with margins (20 N per sole point, half the friction in reserve);
- joint velocity and acceleration limits only (what a contact-unaware planner does: the URDF's velocity
  limits and 10 rad/s²);
- a constant rate in the first timing's T.
The first leaves the squat slowly, where the hips have little torque to spare, and stands with every
criterion within half its threshold; the other two ask the hips for more than they have there, the upper
body sags forward over the toes and the robot falls on its face.

Room (issue 21): the falls are checked again on the timings stretched by 10 % (slower) with the
simulator's fall thresholds doubled (a fall past twice the tilt or drop that counts as one), so that
neither verdict rests on a threshold or on the exact T.

Printed (fig. 6 style): T, the simulator's verdict and the worst criterion against its threshold, then
the room rows. The planned timing's HTML report (each sole's normal force and centre of pressure in its
support polygon) goes to examples/output/humanoid_standup.html.

    python examples/humanoid_standup.py [--grid 100] [--depth 0.22] [--torque-scale 0.3] [--report PATH]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import talos_sway  # noqa: E402  (examples/: Talos loader, sole contacts, kinematic and uniform timings)

import pathpace as pp  # noqa: E402
from pathpace.sim import Simulator  # noqa: E402  (MuJoCo is imported only when a Simulator is built)

TORQUE_SCALE = 0.3
MARGINS = dict(cone_edges=8, min_normal_force=20.0, friction_margin=0.5)
DEPTH = 0.22
# How far ahead of the soles' middle the centre of mass is in the squat (m; the soles reach 0.1 m ahead).
COM_FORWARD = 0.06
STRETCH, stretched, fall_thresholds = talos_sway.STRETCH, talos_sway.stretched, talos_sway.fall_thresholds
MARKS = [np.array(p) for p in ((0.0, 0.0, 0.0), (0.1, 0.0, 0.0), (0.0, 0.05, 0.0))]  # three points pin a sole


def _com_x_jacobian(robot: pp.RobotModel, q: np.ndarray, free: list[int], h: float = 1e-7) -> np.ndarray:
    row = np.empty((1, len(free)))
    for j, i in enumerate(free):
        e = np.zeros(robot.nq)
        e[i] = h
        row[0, j] = (robot.center_of_mass(q + e)[0] - robot.center_of_mass(q - e)[0]) / (2 * h)
    return row


def squat_ik(robot: pp.RobotModel, q_stand: np.ndarray, dz: float, pitch: float, torso: float, arms: float,
             start: np.ndarray, com_forward: float = 0.0) -> np.ndarray:
    """The posture with the pelvis dz below q_stand's and pitched forward by `pitch`, the torso pitched by
    `torso` more and both arms raised forward by `arms`; both soles where q_stand has them and the centre
    of mass `com_forward` ahead of their middle (x). Unknowns: the twelve leg joints and the pelvis x; from
    `start`, steps of at most 0.2 rad."""
    names = robot.joint_names
    soles = {f: robot.frame_placement(q_stand, f) for f in talos_sway.SOLES}
    pins = [(f, p) for f in talos_sway.SOLES for p in MARKS]
    targets = np.concatenate([(soles[f] @ np.append(p, 1.0))[:3] for f, p in pins])
    com_x = np.mean([soles[f][0, 3] for f in talos_sway.SOLES]) + com_forward
    q = start.copy()
    q[2], q[4] = q_stand[2] + dz, q_stand[4] + pitch
    q[names.index("torso_2_joint")] = q_stand[names.index("torso_2_joint")] + torso
    for arm in ("arm_left_1_joint", "arm_right_1_joint"):
        q[names.index(arm)] = q_stand[names.index(arm)] - arms
    free = [i for i, n in enumerate(names) if n.startswith("leg_")] + [0]
    for _ in range(100):
        r = np.concatenate([(robot.frame_placement(q, f) @ np.append(p, 1.0))[:3] for f, p in pins]) - targets
        r = np.append(r, robot.center_of_mass(q)[0] - com_x)
        if np.max(np.abs(r)) < 1e-11:
            return q
        J = np.vstack([robot.point_jacobian(q, f, p)[:, free] for f, p in pins] + [_com_x_jacobian(robot, q, free)])
        step = np.linalg.lstsq(J, r, rcond=None)[0]
        q[free] -= step * min(1.0, 0.2 / max(np.max(np.abs(step)), 1e-300))
    raise RuntimeError(f"squat IK did not converge (dz = {dz}, residual {np.max(np.abs(r)):.2e})")


def standup_path(robot: pp.RobotModel, depth: float = DEPTH, pitch: float = 0.4, torso: float = 0.2,
                 arms: float = 0.3, com_forward: float = COM_FORWARD, knots: int = 21) -> pp.CubicSplinePath:
    """From the squat (s = 0) to half-sitting (s = 1); the squat's share w(s) = 1 - (3s² - 2s³) of each
    offset, so the path starts and ends tangentially. Solved from the standing end down, each knot from
    the one above."""
    q_stand = talos_sway.standing_posture(robot)
    s = np.linspace(0.0, 1.0, knots)
    q, waypoints = q_stand.copy(), []
    for si in s[::-1]:
        w = 1.0 - (3 * si**2 - 2 * si**3)
        q = squat_ik(robot, q_stand, -depth * w, pitch * w, torso * w, arms * w, q, com_forward * w)
        waypoints.append(q.copy())
    return pp.CubicSplinePath(np.array(waypoints[::-1]), knots=s)


def contact_timing(robot: pp.RobotModel, path: pp.Path, contacts: list[pp.Contact], grid: int,
                   torque_scale: float, **margins) -> tuple[pp.TimeScalingProblem, pp.Result]:
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_contacts(robot, contacts, torque_scale=torque_scale, drift_tolerance=1e-4, **margins)
    return prob, prob.solve()


def run_three(robot: pp.RobotModel, path: pp.Path, grid: int, sim: Simulator, res: pp.Result) -> list[dict]:
    """The three timings in `sim` (res: the torque and contact timing), then the two that should fall
    again with room: STRETCH x slower, with the fall thresholds doubled. A row per run: timing, T,
    SimResult, fell, (worst criterion, ratio), and the verdict."""
    kin = talos_sway.kinematic_timing(robot, path, grid)
    runs = [("torque + contacts, margins", res.trajectory(), {}),
            ("velocity + acceleration only", kin.trajectory(), {}),
            ("uniform, same T", talos_sway.uniform_timing(path, grid, res.duration), {}),
            (f"velocity + acceleration only, {STRETCH:g} x T", stretched(path, kin, STRETCH), fall_thresholds(2.0)),
            (f"uniform, {STRETCH:g} x T", talos_sway.uniform_timing(path, grid, STRETCH * res.duration),
             fall_thresholds(2.0))]
    rows = []
    for name, traj, fall in runs:
        r = sim.run(traj, **fall)
        crit, ratio = r.worst_criterion
        verdict = ("fell" + (" (2 x thresholds)" if fall else "") if r.fell else
                   ("executed, with room" if ratio <= 0.5 else ("executed" if r.executed else "off plan")))
        rows.append({"timing": name, "T": traj.duration, "fell": r.fell, "worst": (crit, ratio), "sim": r,
                     "verdict": verdict})
    return rows



def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100, help="N, grid intervals (default 100)")
    ap.add_argument("--depth", type=float, default=DEPTH, help=f"squat depth: pelvis drop in m (default {DEPTH})")
    ap.add_argument("--com-forward", type=float, default=COM_FORWARD,
                    help=f"centre of mass ahead of the soles' middle in the squat, m (default {COM_FORWARD})")
    ap.add_argument("--torque-scale", type=float, default=TORQUE_SCALE,
                    help=f"the motors' torque as a fraction of the URDF effort, planned and simulated (default {TORQUE_SCALE})")
    ap.add_argument("--contact-timeconst", type=float, default=0.005,
                    help="the simulated floor's contact time constant in s (default 0.005, the Simulator's)")
    ap.add_argument("--report", default=str(Path(__file__).resolve().parent / "output" / "humanoid_standup.html"),
                    help="the planned timing's HTML report, with each sole's centre of pressure in its support polygon "
                         "(default examples/output/humanoid_standup.html; '' for none)")
    args = ap.parse_args(argv)

    import humanoid_sim  # noqa: E402  (MuJoCo; the Talos simulator of examples/humanoid_sim.py)

    robot = talos_sway.load_talos()
    t0 = time.perf_counter()
    path = standup_path(robot, depth=args.depth, com_forward=args.com_forward)
    print(f"Talos, nq = {robot.nq}; stand-up path (squat {args.depth} m, centre of mass {args.com_forward} m ahead) "
          f"built in {time.perf_counter() - t0:.2f} s; motors at {args.torque_scale} x the URDF effort")
    contacts = talos_sway.sole_contacts(4)
    t0 = time.perf_counter()
    prob, res = contact_timing(robot, path, contacts, args.grid, args.torque_scale, **MARGINS)
    t_plan = time.perf_counter() - t0
    if not res.ok:
        print(res.message)
        return {"result": res, "path": path}
    talos_sway.write_report(prob, res, args.report)
    sim = humanoid_sim.talos_simulator(robot, path, contacts, contact_timeconst=args.contact_timeconst,
                                       effort_limits=args.torque_scale * np.asarray(robot.effort_limits))
    print(f"planned in {t_plan:.2f} s (projection + solve, N = {args.grid})")
    print(f"{'timing':40s} {'T (s)':>7s}  {'fell at (s)':>11s}  {'verdict':26s} worst criterion / threshold")
    rows = run_three(robot, path, args.grid, sim, res)
    for r in rows:
        crit, ratio = r["worst"]
        fell_at = f"{r['sim'].fall_time:.2f}" if r["fell"] else "-"
        print(f"{r['timing']:40s} {r['T']:7.3f}  {fell_at:>11s}  {r['verdict']:26s} {crit} {ratio:.2f}   "
              f"({r['sim'].summary()})")
    return {"result": res, "path": path, "rows": rows, "plan_time": t_plan, "robot": robot, "contacts": contacts,
            "sim": sim}


if __name__ == "__main__":
    main()
