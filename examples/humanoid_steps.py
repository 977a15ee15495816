"""Talos takes two steps: double support → single → double → single → double, timed with contact phases.

Talos (example-robot-data, floating base) starts with both soles flat on the ground. The path, on s in
[0, 5], one unit of s per phase:
  [0, 1] both feet: the pelvis shifts over the right foot;
  [1, 2] right foot only: the left foot swings forward by `step` (lifted by `lift`), the pelvis moves
         half a step forward;
  [2, 3] both feet: the pelvis shifts over the (new) left foot and another half step forward;
  [3, 4] left foot only: the right foot swings forward to beside the left one;
  [4, 5] both feet: the pelvis comes back to the middle.
Each posture comes from sole IK (examples/talos_sway.py's Gauss-Newton on pathpace's point Jacobians:
pelvis x, y given, soles at their targets); the path is the joint-space spline through them. The pelvis
keeps moving through the switches (p' != 0 there). The swing foot's own plan lands at zero speed, but
the joint spline through the IK knots brings it down at about 7 mm per unit s, so the no-impact rule of
add_contact_phases stops the path at each touchdown (ṡ = 0 at s = 2 and s = 4); lift-offs need nothing.

The contacts: the four corners of each sole on the ground, μ = 0.5 used with a 50 % friction margin and
a 10 N minimum normal force per point (sec. V.D), one contact set per phase
(TimeScalingProblem.add_contact_phases). The timing is audited between the grid points: the
force-distribution LP with each phase's true cone (no margins) at ten times the grid density.

With --rise h both steps go up onto a platform h high (the swing foot lands h higher; the same contacts,
flat on the platform): a step-up.

With --sim the timings are executed in MuJoCo (pathpace.sim, as examples/humanoid_sim.py does for the sway),
each measured against its contact phases (Simulator.run's phases: a point counts only while its phase holds
it, against where the plan puts it). The executed timing is planned with SIM_MIN_NORMAL_FORCE per point
(55 N) instead of 10 N: at 10 N the sole that has just landed slides 7.7 mm (slip 1.55 x the 5 mm criterion,
s = 2.09, just after the touchdown), and the smallest margin with room (find_executable_margin, ~43 N) sits
at slip 0.49-0.5, on the room's edge (45 N: 0.41, but 0.93 on a 6 ms floor). Its counterparts: the zero-margin
optimum (faster; it falls at the simulator's defaults, but not on a 4 ms floor nor 10 % slower, so no verdict
with room), the optimum under joint velocity and acceleration limits only, which falls, and again when run
STRETCH x slower with the fall thresholds doubled (the room of a fall, as in examples/humanoid_standup.py),
and the uniform timing at the executed one's T.

    .venv/bin/python examples/humanoid_steps.py [--grid 100] [--step 0.1] [--lift 0.03] [--rise 0.05] [--sim]
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

import pathpace as pp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import talos_sway  # noqa: E402  (Talos, its posture, its sole contacts and the sole IK)

LEFT, RIGHT = talos_sway.SOLES
CONTACT_OPTIONS = dict(cone_edges=8, friction_margin=0.5, min_normal_force=10.0)
# The timing executed in MuJoCo (--sim): a minimum normal force per point that executes with room (every
# criterion at most half its threshold; bench/README.md, "Issue 21: the room of the simulator's verdicts").
SIM_MIN_NORMAL_FORCE = 55.0
STRETCH = talos_sway.STRETCH  # a fall with room (talos_sway.stretched, talos_sway.fall_thresholds)


def smooth(u: np.ndarray | float) -> np.ndarray | float:
    """0 -> 1 on u in [0, 1], at rest at both ends (zero first and second derivatives)."""
    u = np.clip(u, 0.0, 1.0)
    return u ** 3 * (10 - 15 * u + 6 * u ** 2)


def step_plan(robot: pp.RobotModel, q0: np.ndarray, step: float, lift: float, shift: float, rise: float = 0.0):
    """Functions of s: the pelvis (x, y) and the world placement of each sole (each step lands `rise` higher
    than it started: a step up onto a platform)."""
    x0 = q0[0]
    home = {f: robot.frame_placement(q0, f) for f in (LEFT, RIGHT)}
    # The pelvis through its stations at the switches (over the right foot in [1, 2], over the left one,
    # a step ahead, in [3, 4]), a C² spline at rest at both ends: it keeps moving through the switches,
    # so that p' != 0 there (a path at rest at a grid point would leave ṡ unbounded there).
    stations = np.array([[x0, 0.0], [x0, -shift], [x0 + step / 2, -shift], [x0 + step, shift], [x0 + step, shift],
                         [x0 + step, 0.0]])
    pelvis_xy = pp.CubicSplinePath(stations, knots=np.arange(6.0), boundary="clamped",
                                   start_derivative=np.zeros(2), end_derivative=np.zeros(2))

    def pelvis(s: float) -> tuple[float, float]:
        x, y = pelvis_xy.q(s)
        return float(x), float(y)

    def sole(f: str, s: float) -> np.ndarray:
        swing = (1.0, 2.0) if f == LEFT else (3.0, 4.0)
        T = home[f].copy()
        u = np.clip(s - swing[0], 0.0, 1.0)
        T[0, 3] += step * smooth(u)
        T[2, 3] += rise * smooth(u) + lift * np.sin(np.pi * u) ** 2  # at rest at lift-off and touchdown
        return T

    return pelvis, sole


def steps_path(robot: pp.RobotModel, step: float = 0.1, lift: float = 0.03, shift: float = 0.07,
               knots_per_phase: int = 12, rise: float = 0.0) -> pp.CubicSplinePath:
    """The joint-space spline through sole-IK postures at `knots_per_phase` knots per phase."""
    q0 = talos_sway.standing_posture(robot)
    pelvis, sole = step_plan(robot, q0, step, lift, shift, rise)
    s = np.linspace(0.0, 5.0, 5 * knots_per_phase + 1)
    q, waypoints = q0, []
    for si in s:
        q = talos_sway.sole_ik(robot, q, pelvis(si), {f: sole(f, si) for f in (LEFT, RIGHT)})
        waypoints.append(q)
    return pp.CubicSplinePath(np.array(waypoints), knots=s)


def phases(friction: float = 0.5) -> list[tuple[float, float, list[pp.Contact]]]:
    both = talos_sway.sole_contacts(4, friction)
    left = [c for c in both if c.link == LEFT]
    right = [c for c in both if c.link == RIGHT]
    return [(0.0, 1.0, both), (1.0, 2.0, right), (2.0, 3.0, both), (3.0, 4.0, left), (4.0, 5.0, both)]


def phase_timing(robot: pp.RobotModel, path: pp.Path, grid: int, drift_tolerance: float = 1e-4,
                 **options) -> tuple[pp.TimeScalingProblem, pp.Result, float, float]:
    """The path timed with the contacts of phases() on `grid` intervals, `options` (cone and margins, e.g.
    CONTACT_OPTIONS) for every phase: (problem, result, projection time, solve time), times in s."""
    prob = pp.TimeScalingProblem(path, grid=grid)
    t0 = time.perf_counter()
    prob.add_contact_phases(robot, phases(), drift_tolerance=drift_tolerance, **options)
    t_sets = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = prob.solve()
    return prob, res, t_sets, time.perf_counter() - t0


def audit(traj: pp.Trajectory, robot: pp.RobotModel, samples: int, **options) -> dict:
    """The force-distribution LP at `samples` uniform times, each with its phase's contacts (the later
    phase at a switch) and the cone given by `options`: the worst margin (N) per phase."""
    t = np.linspace(0.0, traj.duration, samples)
    phase = traj.contact_phase(t)
    margin = np.full(samples, -np.inf)
    for i, (_, _, contacts) in enumerate(phases()):
        at = phase == i
        if at.any():
            cf = pp.ContactConstraint(robot, contacts, **options).force_distribution(traj.q(t[at]), traj.qd(t[at]),
                                                                                       traj.qdd(t[at]))
            margin[at] = np.where(cf.feasible, cf.margin, -np.inf)
    return {"t": t, "phase": phase, "margin": margin, "worst": float(margin.min()),
            "worst_per_phase": [float(margin[phase == i].min()) for i in range(5)]}


def simulate(robot: pp.RobotModel, path: pp.Path, timings: list[tuple[str, pp.Trajectory, dict]]) -> list[dict]:
    """Each timing executed in MuJoCo by pathpace.sim (examples/humanoid_sim.py's Talos simulator: one sphere
    per sole contact point, joint PD about the plan plus feed-forward torques from the force-distribution
    LP of each phase's contacts), with Simulator.run's options given per timing and phases=phases(): a
    contact point is measured only while its phase holds it, against where the plan puts it. A row per run:
    timing, T, fell, (worst criterion, ratio to its threshold), the SimResult and the verdict."""
    import humanoid_sim  # noqa: E402  (MuJoCo; imported only here; examples/ is on sys.path, see the top)

    sim = humanoid_sim.talos_simulator(robot, path, phases()[0][2])  # both soles: the simulator's spheres
    rows = []
    for name, traj, options in timings:
        r = sim.run(traj, phases=phases(), **options)
        crit, ratio = r.worst_criterion
        verdict = ("fell" + (" (2 x thresholds)" if options else "") if r.fell else
                   ("executed, with room" if ratio <= 0.5 else ("executed" if r.executed else "off plan")))
        rows.append({"timing": name, "T": traj.duration, "fell": r.fell, "worst": (crit, ratio), "sim": r,
                     "verdict": verdict})
        print(f"  {name:44s} T = {traj.duration:6.3f} s  {verdict:24s} worst criterion: {crit} {ratio:.2f} x its threshold "
              f"({r.summary().split(': ', 1)[1]})")
    return rows


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100, help="N, grid intervals over the five phases (default 100)")
    ap.add_argument("--step", type=float, default=0.1, help="step length in m (default 0.1)")
    ap.add_argument("--lift", type=float, default=0.03, help="swing foot lift in m (default 0.03)")
    ap.add_argument("--rise", type=float, default=0.0,
                    help="step up onto a platform this high, m (default 0: level ground)")
    ap.add_argument("--sim", action="store_true",
                    help="execute the timing (and the one without margins, and uniform ones) in MuJoCo (pathpace.sim)")
    args = ap.parse_args(argv)

    robot = talos_sway.load_talos()
    t0 = time.perf_counter()
    path = steps_path(robot, args.step, args.lift, rise=args.rise)
    print(f"Talos, nq = {robot.nq}; two-step sole-IK path built in {time.perf_counter() - t0:.2f} s")

    prob, res, t_sets, t_solve = phase_timing(robot, path, args.grid, **CONTACT_OPTIONS)
    print(f"contact-phase timing: {res.status.name}, T = {res.duration:.4f} s (projection {t_sets:.2f} s, "
          f"solve {t_solve * 1e3:.1f} ms, N = {prob.grid.size - 1})")
    if not res.ok:
        print(res.message)
        return {"result": res, "problem": prob}
    k_switch = [int(np.argmin(np.abs(prob.grid - s))) for s in (1.0, 2.0, 3.0, 4.0)]
    print("switches: " + ", ".join(f"s = {prob.grid[k]:.0f} at t = {res.times[k]:.3f} s (sdot {res.sdot[k]:.3f})"
                                   for k in k_switch))
    for c in prob.constraints:
        if isinstance(c, pp.ContactConstraint) and c.rest_at_begin:
            print(f"  {c.label}: {c.rest_at_begin}")
    traj = res.trajectory()
    samples = 10 * (prob.grid.size - 1) + 1
    solver_cone = audit(traj, robot, samples, **CONTACT_OPTIONS)
    true_cone = audit(traj, robot, samples, cone_edges=16)
    print(f"audit at {samples} times, worst margin per phase (N of cone weight):")
    print("  solver cone (margins): " + "  ".join(f"{m:8.3f}" for m in solver_cone["worst_per_phase"]))
    print("  true cone (no margin): " + "  ".join(f"{m:8.3f}" for m in true_cone["worst_per_phase"]))
    sim_rows = None
    if args.sim:
        options = dict(CONTACT_OPTIONS, min_normal_force=SIM_MIN_NORMAL_FORCE)
        res_sim = phase_timing(robot, path, args.grid, **options)[1]
        res_bare = phase_timing(robot, path, args.grid, cone_edges=8)[1]
        kin = talos_sway.kinematic_timing(robot, path, args.grid)
        timings = [("contact phases, margins", res_sim.trajectory(), {}),
                   ("contact phases, no margins", res_bare.trajectory(), {}),
                   ("velocity + acceleration only", kin.trajectory(), {}),
                   (f"velocity + acceleration only, {STRETCH:g} x T", talos_sway.stretched(path, kin, STRETCH),
                    talos_sway.fall_thresholds(2.0)),
                   ("uniform, same T", talos_sway.uniform_timing(path, args.grid, res_sim.duration), {})]
        print("MuJoCo (pathpace.sim), each run measured against the contact phases:")
        sim_rows = simulate(robot, path, timings)
    return {"result": res, "problem": prob, "path": path, "robot": robot, "switches": k_switch, "solver_cone": solver_cone,
            "true_cone": true_cone, "projection_time": t_sets, "solve_time": t_solve, "sim": sim_rows}


if __name__ == "__main__":
    main()
