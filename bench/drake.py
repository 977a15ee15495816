"""pathpace against Drake's Toppra (`pydrake.multibody.optimization.Toppra`) on bench/sweep.py's corpus, case (a)
(issue 25: "Add Drake's Toppra if you can make its runs honest; say what it gets wrong").

Corpus and inputs, as sweep.py's case (a) and copp.py: its 4 arms (Panda with the fingers locked, UR5, UR10,
xArm7) x 20 seeds (5 with --quick), the same random waypoints (sweep.waypoints), URDF velocity limits,
acceleration limits = 2 x velocity, rest to rest, N = 100 / 1000 / 10000 uniform grid points.

Identical path and grid for both:
- pathpace: `CubicSplinePath(knots="uniform", boundary="not-a-knot")` on [0, 1];
- Drake: `PiecewisePolynomial.CubicWithContinuousSecondDerivatives(knots, samples, periodic_end=False)`, Drake's
  not-a-knot cubic on the same uniform knots. Both are evaluated at every grid point before any timing, q, q',
  q'' compared (relative to each joint's largest |value|); the script stops if they differ by more than 1e-10.
- Drake gets the SAME array of grid points (`Toppra(path, plant, gridpoints)`), and its answer is checked to
  have its breaks at exactly those s.
- Its plant: a MultibodyPlant parsed from the same URDF; the Panda's base welded to the world and its two
  finger joints replaced by welds at 0 (as pathpace locks them), so that both have the 6-7 arm joints; its URDF
  velocity limits are checked equal to pathpace's. Only the joint limits are used (no torque), so the plant
  supplies dimensions only.
- Limits: `AddJointVelocityLimit(-v, v)` and `AddJointAccelerationLimit(-a, a, ToppraDiscretization.
  kInterpolation)`: interpolation constrains q̈ at both ends of each interval with that interval's s̈, the
  discretisation of eq. (26) that pathpace solves; kCollocation takes the point's own interval only, a looser
  set, and would not be the same problem.

Timed: pathpace's call is construction + limits + solve() + reading ṡ (as in copp.py); Drake's is Toppra(...)
construction + the two limits + SolvePathParameterization(0, 0), WITHOUT reading ṡ out of the returned
PiecewisePolynomial (done afterwards, untimed: the ratio favours Drake). Both by thread CPU time and wall
clock, interleaved call by call (sweep.timed), median per path. The machine is shared: the CPU-time ratio is
the honest measure, wall times are printed beside it.

Checked by this script, trusting neither library: ṡ_k = ds/dt of Drake's s(t) at its breaks;
T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) from each profile (Drake's own break times are compared with it); the largest
relative excess over the velocity and acceleration limits at every grid point, the acceleration with the s̈ of
the interval on EACH side (bench/common.py's oracle on its own spline), and WHERE the worst one is (grid
index, side). A path on which Drake returns no profile is a failure (its message, from Drake's log, counted).

    .venv/bin/python bench/drake.py --quick     5 seeds per arm (80 paths x 3 N: --seeds 20)
    .venv/bin/python bench/drake.py --help      works without pydrake
"""

from __future__ import annotations

import argparse
import collections
import importlib.metadata
import json
import logging
import re
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (first: pins BLAS/OpenMP to one thread before numpy is imported)
import numpy as np  # noqa: E402

HERE = Path(__file__).resolve().parent
PATH_TOLERANCE = 1e-10  # relative; the two splines are the same polynomials, agreeing to rounding (~1e-13)


def drake_available():
    """Imports pydrake, with this folder off sys.path meanwhile: pydrake imports a top-level package `drake` (its
    LCM types), which this file's name would shadow. Once imported it stays in sys.modules."""
    here = Path(__file__).resolve().parent
    saved = list(sys.path)
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != here]
    try:
        import drake  # noqa: F401
        import pydrake.multibody.optimization  # noqa: F401
        import pydrake.multibody.parsing  # noqa: F401
        import pydrake.trajectories  # noqa: F401
    except ImportError:
        return False
    finally:
        sys.path[:] = saved
    return True


class DrakeLog(logging.Handler):
    """Drake's spdlog messages reach Python's "drake" logger; the failure reasons are counted from them."""

    def __init__(self):
        super().__init__(logging.WARNING)
        self.messages = []

    def emit(self, record):
        self.messages.append(record.getMessage())


def drake_plant(urdf, locked):
    """A finalized MultibodyPlant of `urdf` with its root welded to the world (if it floats) and each joint of
    `locked` replaced by a weld at its zero position."""
    from pydrake.math import RigidTransform
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    plant = MultibodyPlant(0.0)
    model = Parser(plant).AddModels(urdf)[0]
    if locked:  # the Panda's finger mimic tag became a coupler constraint, moot once both fingers are welds
        for cid in plant.GetConstraintIds():
            plant.RemoveConstraint(cid)
    for name in locked:
        joint = plant.GetJointByName(name)
        parent, child = joint.frame_on_parent(), joint.frame_on_child()
        plant.RemoveJoint(joint)
        plant.WeldFrames(parent, child, RigidTransform())
    children = {plant.get_joint(j).child_body().index() for j in plant.GetJointIndices(model)}
    roots = [b for b in plant.GetBodyIndices(model) if b not in children]
    for b in roots:
        body = plant.get_body(b)
        if body.name() != "world":
            plant.WeldFrames(plant.world_frame(), body.body_frame(), RigidTransform())
    plant.Finalize()
    return plant


def drake_path(wp):
    """Drake's not-a-knot cubic through the waypoints on uniform knots over [0, 1]."""
    from pydrake.trajectories import PiecewisePolynomial

    knots = np.linspace(0.0, 1.0, wp.shape[0])
    return PiecewisePolynomial.CubicWithContinuousSecondDerivatives(knots, wp.T, False)


def path_difference(drake, ours, grid):
    """Largest |Drake - pathpace| of q, q', q'' at the grid, relative to each joint's largest |pathpace value|."""
    worst = 0.0
    for order, f in ((0, ours.q), (1, ours.dq), (2, ours.ddq)):
        theirs = drake.vector_values(grid) if order == 0 else drake.derivative(order).vector_values(grid)
        mine = np.asarray(f(grid))
        scale = np.maximum(np.abs(mine).max(axis=0), 1e-300)
        worst = max(worst, float((np.abs(theirs.T - mine) / scale).max()))
    return worst


def solvers(arm, plant, wp, N, discretization="interpolation"):
    import pathpace as pp
    from pydrake.multibody.optimization import Toppra, ToppraDiscretization

    grid = np.linspace(0.0, 1.0, N + 1)
    ours_path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
    theirs_path = drake_path(wp)
    diff = path_difference(theirs_path, ours_path, grid)
    if diff > PATH_TOLERANCE:
        raise AssertionError(f"{arm.name}: Drake's spline differs from pathpace's by {diff:.1e} (relative)")
    v, a = arm.v, 2.0 * arm.v
    scheme = {"interpolation": ToppraDiscretization.kInterpolation,
              "collocation": ToppraDiscretization.kCollocation}[discretization]

    def ours():
        prob = pp.TimeScalingProblem(ours_path, grid=grid)
        prob.add_velocity_limits(-v, v)
        prob.add_acceleration_limits(-a, a)
        res = prob.solve()
        return res, np.asarray(res.sdot)

    def drake():
        toppra = Toppra(theirs_path, plant, grid)
        toppra.AddJointVelocityLimit(-v, v)
        toppra.AddJointAccelerationLimit(-a, a, scheme)
        return toppra.SolvePathParameterization(0.0, 0.0)

    return grid, theirs_path, diff, {"pathpace": ours, "drake": drake}


def drake_sdot(s_of_t, grid):
    """ṡ at the grid points from Drake's s(t): its breaks are the times of the grid points (checked)."""
    t = np.asarray(s_of_t.get_segment_times())
    s = s_of_t.vector_values(t).ravel()
    if len(t) != len(grid) or np.abs(s - grid).max() > 1e-12:
        raise AssertionError(f"Drake's breaks are not at the grid points ({len(t)} breaks, {len(grid)} points)")
    return np.maximum(s_of_t.derivative(1).vector_values(t).ravel(), 0.0), t


def where(rows):
    side, k = np.unravel_index(np.argmax(rows), rows.shape)
    return float(rows[side, k]), int(k), ("velocity", "accel., interval after", "accel., interval before")[side]


def end_excess(path, s_of_t, a):
    """Drake's own trajectory q(s(t)) just before its end time T, by pydrake's derivatives of its path and of its
    s(t): q̈ = p''(s) ṡ² + p'(s) s̈, as a relative excess over the acceleration limit (no grid, no oracle)."""
    t0, t1 = s_of_t.get_segment_times()[-2:]
    t = t1 - 1e-9 * (t1 - t0)
    s, sd, sdd = (s_of_t.derivative(k).value(t)[0, 0] if k else s_of_t.value(t)[0, 0] for k in range(3))
    qdd = path.derivative(2).value(s).ravel() * sd**2 + path.derivative(1).value(s).ravel() * sdd
    return max(0.0, float((np.abs(qdd) / a - 1).max()))


def run_path(arm, plant, seed, N, reps, log, discretization):
    import sweep

    wp = sweep.waypoints(arm, seed)
    grid, path, diff, fns = solvers(arm, plant, wp, N, discretization)
    before = len(log.messages)
    wall, cpu, last = sweep.timed(fns, max(1, int(sweep.ROUNDS[N] * reps)), sweep.BLOCK[N])
    ref = common.NotAKnotSpline(np.linspace(0, 1, wp.shape[0]), wp)
    v, a = arm.v, 2.0 * arm.v
    row = {"arm": arm.name, "seed": seed, "N": N, "path_diff": diff,
           "pathpace_cpu": cpu["pathpace"], "drake_cpu": cpu["drake"],
           "pathpace_wall": wall["pathpace"], "drake_wall": wall["drake"]}
    res, sd = last["pathpace"]
    row["status"], row["gap"] = str(res.status).split(".")[-1], float(res.stats["gap"])
    row["T"] = float(common.times_from_sdot(grid, sd)[-1])
    row["violation"] = common.grid_violation(ref, grid, sd, v, a)[0]
    if last["drake"] is None:
        row["failure"] = log.messages[-1] if len(log.messages) > before else "no profile, no message"
        return row
    sd, t = drake_sdot(last["drake"], grid)
    row["T_drake"] = float(common.times_from_sdot(grid, sd)[-1])
    row["T_drake_breaks"] = float(t[-1] - t[0])
    # Its own s(t) has the s̈ that the checks derive from ṡ: on the last segment, u_{N-1} = -ṡ_{N-1}² / (2Δs).
    u_last = (sd[-1] ** 2 - sd[-2] ** 2) / (2 * (grid[-1] - grid[-2]))
    sdd = last["drake"].derivative(2).value(0.5 * (t[-2] + t[-1]))[0, 0]
    row["last_sdd_rel"] = float(abs(sdd / u_last - 1))
    row["end_excess"] = end_excess(path, last["drake"], a)
    rows = common.grid_excess(ref, grid, sd, v, a)
    row["viol_drake"], row["viol_k"], row["viol_side"] = where(rows)
    row["viol_first"] = float(rows[:, 0].max())
    # all but the first and last grid point
    row["viol_drake_inner"], k, row["viol_inner_side"] = where(rows[:, 1:-1])
    row["viol_inner_k"] = k + 1
    return row


def fmt_k(k, N):
    return "last (N)" if k == N else ("first (0)" if k == 0 else f"{k}")


def report(N, rows):
    ok = [r for r in rows if "T_drake" in r]
    line = f"| {N} | {len(ok)} / {len(rows)} | {1e3 * statistics.median(r['pathpace_cpu'] for r in rows):.3f} | "
    line += f"{1e3 * statistics.median(r['drake_cpu'] for r in ok):.2f} | " if ok else "- | "
    if not ok:
        return line + "- | - | - | - | - |"
    ratio = [r["drake_cpu"] / r["pathpace_cpu"] for r in ok]
    wall = [r["drake_wall"] / r["pathpace_wall"] for r in ok]
    dT = [r["T_drake"] / r["T"] - 1 for r in ok]
    worst = max(ok, key=lambda r: r["viol_drake"])
    inner = max(ok, key=lambda r: r["viol_drake_inner"])
    at = collections.Counter(fmt_k(r["viol_k"], N) + ", " + r["viol_side"] for r in ok if r["viol_drake"] > 1e-9)
    line += (f"{statistics.median(ratio):.0f}x / {min(ratio):.0f}x (wall {statistics.median(wall):.0f}x / "
             f"{min(wall):.0f}x) | {statistics.median(dT):+.1e} / {min(dT):+.1e} / {max(dT):+.1e} | "
             f"{worst['viol_drake']:.1e} at {fmt_k(worst['viol_k'], N)}, {worst['viol_side']} "
             f"({worst['arm']} seed {worst['seed']}) | "
             f"{inner['viol_drake_inner']:.1e} at {inner['viol_inner_k']}, {inner['viol_inner_side']} "
             f"({inner['arm']} seed {inner['seed']}; {sum(r['viol_drake_inner'] > 1e-9 for r in ok)} paths > 1e-9) | "
             + "; ".join(f"{n}: {c}" for c, n in sorted(at.items(), key=lambda x: -x[1])) + " |")
    return line


def failures(rows):
    """Drake's failure messages with the knot index taken out, each with how many paths and where on the path
    (knot / N) it failed, and Drake's median CPU time to the failure."""
    out = collections.defaultdict(list)
    for r in rows:
        if "failure" in r:
            m = re.search(r" at knot (\d+)/(\d+)", r["failure"])
            out[r["failure"].replace(m.group(0), " at knot k/N") if m else r["failure"]].append(
                (int(m.group(1)) / int(m.group(2)) if m else float("nan"), r["drake_cpu"]))
    return {msg: f"{len(x)} paths, at k/N = {min(f for f, _ in x):.3f}..{max(f for f, _ in x):.3f}, "
                 f"{1e3 * statistics.median(c for _, c in x):.1f} ms CPU to fail (median)" for msg, x in out.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="5 seeds per arm, half the repetitions")
    ap.add_argument("--seeds", type=int, default=None, help="seeds per arm (default 20, 5 with --quick)")
    ap.add_argument("--N", default="100,1000,10000", help="comma-separated grid sizes")
    ap.add_argument("--arms", default=None, help="comma-separated subset of sweep.ARMS")
    ap.add_argument("--discretization", choices=("interpolation", "collocation"), default="interpolation",
                    help="Drake's ToppraDiscretization of the acceleration limits (interpolation: eq. 26)")
    args = ap.parse_args()
    if not drake_available():
        print("pydrake is not installed (pip install drake): skipped", file=sys.stderr)
        return
    import sweep  # pinocchio, pathpace, example-robot-data (and it silences logging: re-enabled below)
    from pathpace.robots import example_robot_urdf

    logging.disable(logging.NOTSET)
    log = DrakeLog()
    logging.getLogger("drake").addHandler(log)
    logging.getLogger("drake").propagate = False
    seeds = args.seeds or (5 if args.quick else 20)
    reps = 0.5 if args.quick else 1.0
    arms, plants = {}, {}
    for name in (args.arms.split(",") if args.arms else sweep.ARMS):
        arms[name] = sweep.Arm(name)
        urdf, locked = sweep.ARMS[name]
        plants[name] = drake_plant(str(example_robot_urdf(urdf)), locked)
        dv = plants[name].GetVelocityUpperLimits()
        assert np.array_equal(dv, arms[name].v), f"{name}: Drake's URDF velocity limits {dv} != {arms[name].v}"
    print("| N | Drake solved / paths | pathpace ms CPU | Drake ms CPU | Drake / pathpace CPU: median / worst "
          "| T_drake / T_pathpace - 1: median / min / max | Drake's worst violation, where | Drake's worst "
          "off the first and last point | paths with a violation > 1e-9, at |")
    print("|---|---|---|---|---|---|---|---|---|")
    t0, everything = time.time(), []
    for N in (int(x) for x in args.N.split(",")):
        rows = [run_path(arms[n], plants[n], seed, N, reps, log, args.discretization)
                for n in arms for seed in range(seeds)]
        line = report(N, rows)
        print(line, flush=True)
        everything += rows
        print(f"N = {N}: largest path difference {max(r['path_diff'] for r in rows):.1e}; pathpace's worst "
              f"violation {max(r['violation'] for r in rows):.1e}; largest |T_drake(breaks) / T_drake - 1| "
              f"{max((abs(r['T_drake_breaks'] / r['T_drake'] - 1) for r in rows if 'T_drake' in r), default=0):.1e}; "
              f"pathpace OPTIMAL {sum(r['status'] == 'OPTIMAL' for r in rows)}/{len(rows)}, largest certified gap "
              f"{max(r['gap'] for r in rows):.1e}; worst excess of Drake's own q(s(t)) just before T "
              f"{max((r['end_excess'] for r in rows if 'T_drake' in r), default=0):.1e}; "
              f"Drake's worst at the first point {max((r['viol_first'] for r in rows if 'T_drake' in r), default=0):.1e}; "
              f"largest |s̈ of Drake's last segment / u_(N-1) - 1| "
              f"{max((r['last_sdd_rel'] for r in rows if 'T_drake' in r), default=0):.1e}; failures {failures(rows)}; {time.time() - t0:.0f} s", file=sys.stderr, flush=True)

    (HERE / "results").mkdir(exist_ok=True)
    with open(HERE / "results" / "drake.json", "w") as f:
        json.dump({"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "machine": common.machine(),
                   "build": common.build_info(), "drake": importlib.metadata.version("drake"), "seeds": seeds,
                   "discretization": args.discretization,
                   "rows": everything}, f, indent=1)


if __name__ == "__main__":
    main()
