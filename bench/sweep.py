"""pathpace against toppra and copp over a seeded corpus of random arm paths (never one path).

Corpus: 4 arms of example-robot-data with 6-7 joints (Franka Panda with the fingers locked, UR5 and UR10 with
joint limits, xArm7) x 20 seeds. Per seed: 5-8 random waypoints at 10-90 % of each joint's position range,
a cubic spline on uniform knots over [0, 1] with not-a-knot ends (pathpace `CubicSplinePath(knots="uniform",
boundary="not-a-knot")`, toppra `SplineInterpolator(bc_type="not-a-knot")`), rest to rest, the same array of
N + 1 uniform grid points passed to both libraries, N = 100, 1000, 10000.
  (a) URDF velocity limits and acceleration limits = 2 x velocity limits;
  (b) the same plus joint torque limits |τ| <= 0.6 x URDF effort (pathpace `add_torque_limits(robot, scale)`,
      its own RNEA; toppra `JointTorqueConstraint` with pinocchio's RNEA as inverse dynamics, Interpolation).
      Where the arm cannot follow the path at 0.6 x effort (holding it against gravity needs more; pathpace
      says INFEASIBLE, toppra fails too), the next of 0.8, 1.0 x effort that it can is used for both
      libraries, and the count is reported.

Timed from the path object onward, one thread, the two libraries interleaved call by call (rounds of:
`block` pathpace calls, one toppra call, in alternating order), median per path; the per-path speed-up
is the ratio of the medians, by thread CPU time (`time.thread_time`: what each library computes,
unaffected by other processes on a shared machine) and by wall clock (`time.perf_counter`). A target
counts as met only if both meet it. toppra: `TOPPRA(..., solver_wrapper="seidel",
parametrizer="ParametrizeConstAccel").compute_parameterization(0, 0)` with its default (Interpolation)
discretisation, which enforces the limits on both sides of every grid point as eq. (26) does.
copp (copp-py, Rust TOPP2-RA, the fastest compiled peer, issue 25), case (a) only (its torque rows take a Python
inverse-dynamics callback per sample, which would time the callback): `copp.solver.topp2_ra.solve` with default
options on the same grid, its p, p', p'' sampled from pathpace's spline inside its timed call (as pathpace
samples its path inside its own), interleaved with the other two; bench/copp.py is the same comparison alone.

Checked by this script, trusting neither library: T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) from each output's ṡ; the
largest relative excess over the velocity, acceleration (numpy, own not-a-knot spline, s̈ of the interval on
each side of every grid point) and torque limits (pinocchio RNEA, both sides) at the grid points.

    .venv/bin/python bench/sweep.py            the full corpus (about 10-15 min); writes
                                               bench/results/sweep.json and the generated section of
                                               bench/README.md
    .venv/bin/python bench/sweep.py --quick    5 seeds per arm, fewer repetitions, README left alone
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (first: pins BLAS/OpenMP to one thread before numpy is imported)
import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402
from pathpace.robots import example_robot_urdf  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
import helpers  # noqa: E402  (the corpus's waypoints and the random walk, shared with test_optimality_corpus.py)

logging.disable(logging.CRITICAL)  # toppra logs at INFO/DEBUG

HERE = Path(__file__).resolve().parent
ARMS = {
    "panda": ("panda_description/urdf/panda.urdf", ("panda_finger_joint1", "panda_finger_joint2")),
    "ur5": ("ur_description/urdf/ur5_joint_limited_robot.urdf", ()),
    "ur10": ("ur_description/urdf/ur10_joint_limited_robot.urdf", ()),
    "xarm7": ("xarm_description/urdf/xarm7.urdf", ()),
}
SIZES = (100, 1000, 10000)
TORQUE_SCALES = (0.6, 0.8, 1.0)
# Per path: `rounds` rounds of (`block` pathpace calls, 1 toppra call, `block` copp calls), after one warm-up
# call of each.
ROUNDS = {100: 5, 1000: 3, 10000: 2}
BLOCK = {100: 5, 1000: 3, 10000: 2}
TARGETS = {("a", 100): (10, 5), ("b", 100): (10, 5), ("a", 1000): (25, 10), ("b", 1000): (25, 10),
           ("a", 10000): (20, None), ("b", 10000): (20, None)}  # (median, worst) speed-up
COPP_TARGETS = (3.0, 1.5)  # issue 25: (median, worst) CPU-time speed-up over copp's TOPP2-RA, case (a)


class Arm:
    def __init__(self, name):
        import pinocchio as pin

        urdf, lock = ARMS[name]
        urdf = str(example_robot_urdf(urdf))
        self.name = name
        self.ours = pp.RobotModel.from_urdf(urdf, locked_joints={n: 0.0 for n in lock})
        full = pin.buildModelFromUrdf(urdf)
        self.model = (pin.buildReducedModel(full, [full.getJointId(n) for n in lock], pin.neutral(full))
                      if lock else full)
        self.data = self.model.createData()
        self.lo, self.hi = self.ours.position_limits
        self.v = np.asarray(self.ours.velocity_limits, float)
        assert self.model.nq == self.model.nv == len(self.v), name
        assert np.allclose(self.model.velocityLimit, self.v), f"{name}: URDF velocity limits disagree"

    def rnea(self, q, qd, qdd):
        import pinocchio as pin

        return pin.rnea(self.model, self.data, q, qd, qdd)


def waypoints(arm, seed):
    return helpers.random_waypoints(arm.lo, arm.hi, np.random.default_rng(seed))


def copp_available():
    try:
        import copp_py  # noqa: F401
    except ImportError:
        return False
    return True


def copp_solver(path, grid, v, a):
    """copp's TOPP2-RA (velocity + acceleration limits, rest to rest) on `grid`, sampling p, p', p'' from
    pathpace's `path` inside the call; returns ṡ at the grid points."""
    import copp_py as copp

    N = len(grid) - 1

    def solve():
        q, dq, ddq = path.q(grid), path.dq(grid), path.ddq(grid)
        robot = copp.Robot(len(v), capacity=N + 1)
        robot.append_s(grid)
        robot.set_q(q, dq, ddq, 0)
        robot.add_velocity_limits(v, -v, start_idx_s=0, length=N + 1)
        robot.add_acceleration_limits(a, -a, start_idx_s=0, length=N + 1)
        problem = copp.solver.topp2_ra.Problem(robot.constraints, idx_s_interval=(0, N), a_boundary=(0.0, 0.0))
        return np.sqrt(np.maximum(copp.solver.topp2_ra.solve(problem), 0.0))

    return solve


def make(arm, wp, N, scale, **solve_options):
    """The two solvers on identical inputs; scale = None for case (a)."""
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    grid = np.linspace(0.0, 1.0, N + 1)
    ours = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
    theirs = ta.SplineInterpolator(np.linspace(0.0, 1.0, wp.shape[0]), wp, bc_type="not-a-knot")
    v, a = arm.v, 2.0 * arm.v
    vlim, alim = np.column_stack([-v, v]), np.column_stack([-a, a])

    def pathpace_solve():
        prob = pp.TimeScalingProblem(ours, grid=grid)
        prob.add_velocity_limits(-v, v)
        prob.add_acceleration_limits(-a, a)
        if scale is not None:
            prob.add_torque_limits(arm.ours, scale=scale)
        return prob.solve(**solve_options)

    def toppra_solve():
        cons = [constraint.JointVelocityConstraint(vlim), constraint.JointAccelerationConstraint(alim)]
        if scale is not None:
            tau = scale * arm.model.effortLimit
            cons.append(constraint.JointTorqueConstraint(
                arm.rnea, np.column_stack([-tau, tau]), np.zeros(len(v)),
                discretization_scheme=constraint.DiscretizationType.Interpolation))
        inst = algo.TOPPRA(cons, theirs, gridpoints=grid, solver_wrapper="seidel",
                           parametrizer="ParametrizeConstAccel")
        _, sd, _ = inst.compute_parameterization(0, 0)
        return sd

    return grid, ours, pathpace_solve, toppra_solve


def make_copp(arm, path, grid, scale):
    """copp on make()'s inputs, or None in case (b) (torque) or when copp-py is not installed."""
    return copp_solver(path, grid, arm.v, 2.0 * arm.v) if scale is None and copp_available() else None


def torque_violation(arm, wp, s, sdot, scale):
    ref = common.NotAKnotSpline(np.linspace(0, 1, wp.shape[0]), wp)
    q, dq, ddq = ref(s, 0), ref(s, 1), ref(s, 2)
    th = sdot**2
    u = np.diff(th) / (2 * np.diff(s))
    tau_max = scale * arm.model.effortLimit
    worst = 0.0
    for k in range(len(s)):
        for uu in ([u[k]] if k < len(u) else []) + ([u[k - 1]] if k > 0 else []):
            tau = arm.rnea(q[k], dq[k] * sdot[k], ddq[k] * th[k] + dq[k] * uu)
            worst = max(worst, float(np.max(np.abs(tau) / tau_max - 1)))
    return max(0.0, worst)


def violation(arm, wp, s, sdot, scale):
    ref = common.NotAKnotSpline(np.linspace(0, 1, wp.shape[0]), wp)
    g = common.grid_violation(ref, s, sdot, arm.v, 2.0 * arm.v)[0]
    if scale is not None:
        g = max(g, torque_violation(arm, wp, s, sdot, scale))
    return g


def timed(fns, rounds, block):
    """Interleaved: each round runs `block` pathpace (and copp) calls and one toppra call, the order reversed
    every other round."""
    out = {n: [] for n in fns}
    cpu = {n: [] for n in fns}
    last = {n: f() for n, f in fns.items()}  # warm-up
    for r in range(rounds):
        order = list(fns) if r % 2 == 0 else list(fns)[::-1]
        for n in order:
            for _ in range(1 if n == "toppra" else block):
                c0, t0 = time.thread_time(), time.perf_counter()
                last[n] = fns[n]()
                t1, c1 = time.perf_counter(), time.thread_time()
                out[n].append(t1 - t0)
                cpu[n].append(c1 - c0)
    return {n: statistics.median(x) for n, x in out.items()}, {n: statistics.median(x) for n, x in cpu.items()}, last


def run_case(arm, seed, case, N, scale, reps):
    wp = waypoints(arm, seed)
    grid, path, ours, theirs = make(arm, wp, N, scale)
    copp = make_copp(arm, path, grid, scale)
    fns = {"pathpace": ours, "toppra": theirs} | ({"copp": copp} if copp else {})
    med, cpu, last = timed(fns, max(1, int(ROUNDS[N] * reps)), BLOCK[N])
    res, sd = last["pathpace"], last["toppra"]
    row = {"arm": arm.name, "seed": seed, "case": case, "N": N, "scale": scale, "waypoints": int(wp.shape[0]),
           "status": str(res.status).split(".")[-1], "pathpace_ms": 1e3 * med["pathpace"],
           "toppra_ms": 1e3 * med["toppra"], "speedup": med["toppra"] / med["pathpace"],
           "pathpace_cpu_ms": 1e3 * cpu["pathpace"], "toppra_cpu_ms": 1e3 * cpu["toppra"],
           "speedup_cpu": cpu["toppra"] / max(cpu["pathpace"], 1e-9),
           "stats": {k: v for k, v in res.stats.items()}}
    if res.ok:
        sdot = np.asarray(res.sdot)
        row["T"] = float(common.times_from_sdot(grid, sdot)[-1])
        row["violation"] = violation(arm, wp, grid, sdot, scale)
    toppra_ok = sd is not None and not np.isnan(sd).any()
    row["toppra_ok"] = bool(toppra_ok)
    if toppra_ok:
        sd = np.asarray(sd, float)
        row["T_toppra"] = float(common.times_from_sdot(grid, sd)[-1])
        row["violation_toppra"] = violation(arm, wp, grid, sd, scale)
    if copp:
        sd = np.asarray(last["copp"], float)
        row["copp_cpu_ms"] = 1e3 * cpu["copp"]
        row["speedup_copp_cpu"] = cpu["copp"] / max(cpu["pathpace"], 1e-9)
        row["T_copp"] = float(common.times_from_sdot(grid, sd)[-1])
        row["violation_copp"] = violation(arm, wp, grid, sd, scale)
    return row


def torque_scale(arm, seed):
    """0.6 x effort, or the next scale at which pathpace finds the path feasible (N = 100)."""
    wp = waypoints(arm, seed)
    for scale in TORQUE_SCALES:
        _, _, ours, _ = make(arm, wp, 100, scale)
        if ours().ok:
            return scale
    return None


def best_of(fn, rounds):
    """(wall ms, thread-CPU ms, last result): the best of `rounds` calls."""
    ts, cpu = [], []
    for _ in range(rounds):
        t0, c0 = time.perf_counter(), time.thread_time()
        out = fn()
        ts.append(time.perf_counter() - t0)
        cpu.append(time.thread_time() - c0)
    return 1e3 * min(ts), 1e3 * min(cpu), out


def random_walk(N, seed=0, K=400):
    """The issue's long path: a K-waypoint (400) random walk of the Panda (steps of 0.2 rad, reflected at 10 %
    and 90 % of each range), velocity + acceleration limits; pathpace only (and toppra at N = 1000). Timed by
    wall clock and thread CPU time (best of 3, one call at N = 100000)."""
    arm = Arm("panda")
    wp = helpers.random_walk(arm.lo, arm.hi, np.random.default_rng(seed), K)  # test_optimality_corpus's walk
    # A budget, so that the benchmark ends: the target is 2 s at N = 100000.
    grid, path, ours, theirs = make(arm, wp, N, None, time_limit=10.0)
    copp = make_copp(arm, path, grid, None)
    rounds = 3 if N <= 10000 else 1
    ms, cpu_ms, res = best_of(ours, rounds)
    row = {"N": N, "K": K, "ms": ms, "cpu_ms": cpu_ms, "status": str(res.status).split(".")[-1],
           "gap": res.stats["gap"], "newton_steps": res.stats["newton_steps"],
           "T": res.duration, "lp_solves": res.stats["lp_solves"], "windows": res.stats["windows"],
           "window_points": res.stats["window_points"], "time_slp_ms": 1e3 * res.stats["time_slp"]}
    if copp:
        row["copp_ms"], row["copp_cpu_ms"], sd = best_of(copp, rounds)
        row["T_copp"] = float(common.times_from_sdot(grid, np.asarray(sd, float))[-1])
    if N <= 1000:
        t0 = time.perf_counter()
        sd = theirs()
        row["toppra_ms"] = 1e3 * (time.perf_counter() - t0)
        if sd is not None:
            row["T_toppra"] = float(common.times_from_sdot(grid, np.asarray(sd, float))[-1])
    return row


def summarize(rows):
    out = []
    for case in ("a", "b"):
        for N in SIZES:
            rs = [r for r in rows if r["case"] == case and r["N"] == N and "T" in r and r["toppra_ok"]]
            if not rs:
                continue
            sp = [r["speedup"] for r in rs]
            spc = [r["speedup_cpu"] for r in rs]
            rel = [r["T"] / r["T_toppra"] - 1 for r in rs]
            out.append({
                "case": case, "N": N, "paths": len(rs),
                "not_solved": sum(1 for r in rows if r["case"] == case and r["N"] == N and ("T" not in r or not r["toppra_ok"])),
                "median": statistics.median(sp), "worst": min(sp), "best": max(sp),
                "median_cpu": statistics.median(spc), "worst_cpu": min(spc), "best_cpu": max(spc),
                "pathpace_cpu_ms_median": statistics.median(r["pathpace_cpu_ms"] for r in rs),
                "toppra_cpu_ms_median": statistics.median(r["toppra_cpu_ms"] for r in rs),
                "pathpace_ms_median": statistics.median(r["pathpace_ms"] for r in rs),
                "toppra_ms_median": statistics.median(r["toppra_ms"] for r in rs),
                "lp_share": sum(r["stats"]["lp_solves"] > 0 for r in rs) / len(rs),
                "optimal_share": sum(r["status"] == "OPTIMAL" for r in rs) / len(rs),
                "gap_max": max(r["stats"]["gap"] for r in rs),
                "T_rel_median": statistics.median(rel), "T_rel_max": max(rel), "T_rel_min": min(rel),
                "viol_max": max(r["violation"] for r in rs),
                "viol_toppra_max": max(r["violation_toppra"] for r in rs),
                "slp_ms_median": 1e3 * statistics.median(r["stats"]["time_slp"] for r in rs),
                "slp_ms_max": 1e3 * max(r["stats"]["time_slp"] for r in rs),
                "sets_ms_median": 1e3 * statistics.median(r["stats"]["time_feasible_sets"] for r in rs),
                "reach_ms_median": 1e3 * statistics.median(r["stats"]["time_reachability"] for r in rs),
            })
            rc = [r for r in rows if r["case"] == case and r["N"] == N and "T" in r and "T_copp" in r]
            if rc:
                sp = [r["speedup_copp_cpu"] for r in rc]
                rel = [r["T"] / r["T_copp"] - 1 for r in rc]
                out[-1]["copp"] = {
                    "paths": len(rc), "median_cpu": statistics.median(sp), "worst_cpu": min(sp), "best_cpu": max(sp),
                    "pathpace_cpu_ms_median": statistics.median(r["pathpace_cpu_ms"] for r in rc),
                    "copp_cpu_ms_median": statistics.median(r["copp_cpu_ms"] for r in rc),
                    "T_rel_median": statistics.median(rel), "T_rel_min": min(rel), "T_rel_max": max(rel),
                    "viol_max": max(r["violation"] for r in rc), "viol_copp_max": max(r["violation_copp"] for r in rc),
                }
    return out


def fmt_e(x):
    return f"{x:.1e}" if x > 0 else "0"


def table(summary, walk):
    lines = ["| case | N | paths | speed-up CPU: median / worst / best | wall: median / worst / best "
             "| pathpace ms CPU / wall (median) | toppra ms CPU / wall (median) "
             "| needed LPs | SLP ms median / max | T / T_toppra - 1: median, min, max | max certified gap "
             "| grid violation pathpace / toppra |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for s in summary:
        lines.append(
            f"| {s['case']} | {s['N']} | {s['paths']} | {s['median_cpu']:.1f}x / {s['worst_cpu']:.1f}x / {s['best_cpu']:.1f}x | "
            f"{s['median']:.1f}x / {s['worst']:.1f}x / {s['best']:.1f}x | "
            f"{s['pathpace_cpu_ms_median']:.3f} / {s['pathpace_ms_median']:.3f} | "
            f"{s['toppra_cpu_ms_median']:.2f} / {s['toppra_ms_median']:.2f} | {100 * s['lp_share']:.0f} % | "
            f"{s['slp_ms_median']:.3f} / {s['slp_ms_max']:.2f} | {s['T_rel_median']:+.1e}, {s['T_rel_min']:+.1e}, "
            f"{s['T_rel_max']:+.1e} | {fmt_e(s['gap_max'])} | {fmt_e(s['viol_max'])} / {fmt_e(s['viol_toppra_max'])} |")
    copp = [s for s in summary if "copp" in s]
    if copp:
        lines += ["", "| against copp (TOPP2-RA): case | N | paths | speed-up CPU: median / worst / best "
                  "| pathpace ms CPU (median) | copp ms CPU (median) | T / T_copp - 1: median, min, max "
                  "| grid violation pathpace / copp |", "|---|---|---|---|---|---|---|---|"]
        for s in copp:
            c = s["copp"]
            lines.append(
                f"| {s['case']} | {s['N']} | {c['paths']} | {c['median_cpu']:.2f}x / {c['worst_cpu']:.2f}x / "
                f"{c['best_cpu']:.2f}x | {c['pathpace_cpu_ms_median']:.3f} | {c['copp_cpu_ms_median']:.3f} | "
                f"{c['T_rel_median']:+.1e}, {c['T_rel_min']:+.1e}, {c['T_rel_max']:+.1e} | "
                f"{fmt_e(c['viol_max'])} / {fmt_e(c['viol_copp_max'])} |")
    if walk:
        lines += ["", "| random walk (Panda, a): waypoints | N | pathpace ms wall / CPU | status | certified gap | LPs | "
                  "Newton steps | windows (points) | toppra ms | copp ms wall / CPU | T / T_copp - 1 |",
                  "|---|---|---|---|---|---|---|---|---|---|---|"]
        for w in walk:
            cp = (f"{w['copp_ms']:.2f} / {w['copp_cpu_ms']:.2f} | {w['T'] / w['T_copp'] - 1:+.1e}"
                  if "copp_ms" in w else "- | -")
            lines.append(f"| {w['K']} | {w['N']} | {w['ms']:.2f} / {w['cpu_ms']:.2f} | {w['status']} | {fmt_e(w['gap'])} | "
                         f"{w['lp_solves']} | {w['newton_steps']} | {w['windows']} ({w['window_points']}) | "
                         f"{w.get('toppra_ms', float('nan')):.1f} | {cp} |")
    return "\n".join(lines)


def verdicts(summary, walk, rows):
    out = []
    for s in summary:
        med_t, worst_t = TARGETS[(s["case"], s["N"])]
        ok = all(s[f"median{c}"] >= med_t and (worst_t is None or s[f"worst{c}"] >= worst_t) for c in ("", "_cpu"))
        want = f"median >= {med_t}x" + (f", worst >= {worst_t}x" if worst_t else "")
        out.append(f"- ({s['case']}) N = {s['N']}: {want}: **{'met' if ok else 'NOT met'}** "
                   f"(CPU time: {s['median_cpu']:.1f}x, worst {s['worst_cpu']:.1f}x; wall clock: {s['median']:.1f}x, "
                   f"worst {s['worst']:.1f}x).")
    worst_T = max((r["T"] / r["T_toppra"] - 1 for r in rows if "T" in r and r["toppra_ok"]), default=float("nan"))
    out.append(f"- T <= toppra's T + 1e-9 relative on every path: **{'met' if worst_T <= 1e-9 else 'NOT met'}** "
               f"(largest T / T_toppra - 1: {worst_T:+.1e}).")
    gmax = max((r["stats"]["gap"] for r in rows if "T" in r), default=float("nan"))
    nonopt = sum(1 for r in rows if "T" in r and r["status"] != "OPTIMAL")
    out.append(f"- certified gap <= 1e-7: **{'met' if gmax <= 1e-7 and not nonopt else 'NOT met'}** (largest "
               f"{gmax:.1e}; {nonopt} solved paths not OPTIMAL).")
    med_t, worst_t = COPP_TARGETS
    for s in summary:
        if "copp" not in s:
            continue
        c = s["copp"]
        ok = c["median_cpu"] >= med_t and c["worst_cpu"] >= worst_t and c["T_rel_max"] <= 1e-9
        out.append(f"- ({s['case']}) N = {s['N']} against copp (issue 25): median >= {med_t:g}x, worst >= {worst_t:g}x, "
                   f"T <= T_copp + 1e-9: **{'met' if ok else 'NOT met'}** (CPU time: {c['median_cpu']:.2f}x, worst "
                   f"{c['worst_cpu']:.2f}x; largest T / T_copp - 1: {c['T_rel_max']:+.1e}).")
    for w in walk:
        lim = 20.0 if w["N"] == 1000 else (2000.0 if w["N"] == 100000 else None)
        if lim and w["K"] == 400:
            out.append(f"- random walk N = {w['N']} < {lim:g} ms: **{'met' if w['ms'] < lim and w['status'] == 'OPTIMAL' else 'NOT met'}** "
                       f"({w['ms']:.1f} ms, {w['status']}).")
    return "\n".join(out)


BEGIN = "<!-- generated by bench/sweep.py: begin -->"
END = "<!-- generated by bench/sweep.py: end -->"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="5 seeds per arm, fewer repetitions, README left alone")
    ap.add_argument("--seeds", type=int, default=None)
    ap.add_argument("--sizes", type=str, default=None, help="comma-separated N (default 100,1000,10000)")
    args = ap.parse_args()
    seeds = args.seeds or (5 if args.quick else 20)
    sizes = tuple(int(x) for x in args.sizes.split(",")) if args.sizes else SIZES
    reps = 0.5 if args.quick else 1.0
    arms = [Arm(n) for n in ARMS]
    t_start = time.time()
    rows, scales = [], {}
    for arm in arms:
        for seed in range(seeds):
            scales[(arm.name, seed)] = torque_scale(arm, seed)
    for N in sizes:
        load = os.getloadavg()[0]
        for arm in arms:
            for seed in range(seeds):
                rows.append(run_case(arm, seed, "a", N, None, reps))
                sc = scales[(arm.name, seed)]
                if sc is not None:
                    rows.append(run_case(arm, seed, "b", N, sc, reps))
        done = [r for r in rows if r["N"] == N]
        print(f"N = {N}: {len(done)} solves, load before {load:.2f}, {time.time() - t_start:.0f} s so far",
              file=sys.stderr)
    # The walk at three N and, at N = 10000, with 4x the waypoints: solve time ~linear in N and in the pieces.
    walk = [random_walk(N, K=K) for N, K in (((1000, 400), (10000, 400), (100000, 400), (10000, 1600))
                                             if not args.quick else ((1000, 400),))]
    summary = summarize(rows)
    scale_counts = {str(s): sum(1 for v in scales.values() if v == s) for s in TORQUE_SCALES + (None,)}
    data = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": common.machine(),
            "build": common.build_info(), "seeds": seeds, "torque_scales": scale_counts, "summary": summary,
            "walk": walk, "rows": rows, "seconds": time.time() - t_start}
    (HERE / "results").mkdir(exist_ok=True)
    with open(HERE / "results" / ("sweep_quick.json" if args.quick else "sweep.json"), "w") as f:
        json.dump(data, f, indent=1, default=str)
    tab = table(summary, walk)
    ver = verdicts(summary, walk, rows)
    print(tab)
    print(ver)
    print(f"torque scales used (paths): {scale_counts}; {data['seconds']:.0f} s", file=sys.stderr)
    if not args.quick and args.seeds is None and args.sizes is None:
        write_readme(data, tab, ver)


def write_readme(data, tab, ver):
    mach = data["machine"]
    sc = data["torque_scales"]
    section = f"""{BEGIN}
Command (from the repository root, after `make python`; about {data['seconds'] / 60:.0f} min):

    .venv/bin/python bench/sweep.py            (--quick: 5 seeds per arm, no README update)

Run {data['date']} on {mach['cpu']}, nproc = {mach['nproc']}; pathpace {mach['pathpace']} (commit
{data['build'].get('commit', '?')}), toppra {mach['toppra']}, pin {mach['pin']}. The corpus and the
method are described in the script's docstring: 4 arms (Panda, UR5, UR10, xArm7) x {data['seeds']} seeds,
5-8 random waypoints, not-a-knot spline, (a) velocity + acceleration (2 x velocity) limits, (b) plus
torque limits; identical spline and grid for both libraries, interleaved timing, medians per path.
Torque scale used in (b), paths: {sc['0.6']} at 0.6 x effort, {sc['0.8']} at 0.8, {sc['1.0']} at 1.0,
{sc['None']} infeasible at all three (left out). "needed LPs": share of paths on which the relaxation's
bracket was not within the tolerance, so that SLP ran on windows. copp-py {mach.get('copp', '?')} (TOPP2-RA)
in case (a) and the walk: CPU-time ratio copp / pathpace per path, the three libraries interleaved.

{tab}

Targets (issue #8; against copp, issue 25):
{ver}

Per-path rows (status, times, T of both, violations, solver stats): `bench/results/sweep.json`
(not tracked).
{END}"""
    common.write_generated_section(section, BEGIN, END, "## pathpace vs toppra: a corpus of random arm paths")


if __name__ == "__main__":
    main()
