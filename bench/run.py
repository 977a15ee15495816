"""pathpace against toppra on identical inputs (engine benchmark).

A Panda path (example-robot-data URDF, the 7 arm joints, fingers ignored): cubic spline through 5 seeded random
waypoints inside the position limits, uniform knots on [0, 1], not-a-knot; URDF velocity limits (pinocchio,
cross-checked with the XML); acceleration limits = 2 x velocity limits; rest to rest. N = 100, 1000, 10000
intervals on the same uniform grid (the same array is passed to both libraries).

Timed from the path onward (wall clock, one thread, the three solvers interleaved round by round):
  pathpace:        TimeScalingProblem + add_velocity_limits + add_acceleration_limits + solve
  toppra:          JointVelocityConstraint + JointAccelerationConstraint (its default discretisation, which in
                   toppra 0.6 is Interpolation: both sides of every grid point) + TOPPRA(seidel,
                   ParametrizeConstAccel) + compute_parameterization(0, 0)
  toppra colloc.:  the same with DiscretizationType.Collocation (one side of every grid point)

Checked by this folder's own numpy code on its own not-a-knot spline (trusting neither library): the largest
relative excess of |q̇_j| over v_j and of |q̈_j| over a_j (a) at the grid points, with ṡ at the point and s̈ of
the interval on EACH side of it, and (b) 20 samples inside every interval of each output trajectory
(pathpace traj.qd/qdd, toppra ParametrizeConstAccel evald/evaldd).

    .venv/bin/python bench/run.py              prints the tables, writes bench/results/latest.json and the
                                               generated section of bench/README.md
    .venv/bin/python bench/run.py --quick      fewer repetitions, README left alone
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import statistics
import sys
import textwrap
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (first: pins BLAS/OpenMP to one thread before numpy is imported)
import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402

logging.disable(logging.CRITICAL)  # toppra logs at INFO/DEBUG

HERE = Path(__file__).resolve().parent
SIZES = (100, 1000, 10000)
# One round = for each of the three solvers (rotating order), 1 cold call + BLOCK[N] warm calls.
ROUNDS = {100: 40, 1000: 40, 10000: 12}
BLOCK = {100: 10, 1000: 5, 10000: 2}
DENSE_PER_INTERVAL = 20
TARGET = {"N": 1000, "speedup": 20.0, "T_excess": 1e-3, "grid_violation": 1e-9}
SOLVERS = ("pathpace", "toppra", "toppra_colloc")
LABEL = {"pathpace": "pathpace", "toppra": "toppra (default = Interpolation)",
         "toppra_colloc": "toppra Collocation"}


def make_solvers(waypoints, v, a, N):
    import toppra as ta
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    grid = np.linspace(0.0, 1.0, N + 1)
    knots = np.linspace(0.0, 1.0, waypoints.shape[0])
    ours = pp.CubicSplinePath(waypoints, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
    theirs = ta.SplineInterpolator(knots, waypoints, bc_type="not-a-knot")
    vlim = np.column_stack([-v, v])
    alim = np.column_stack([-a, a])

    def pathpace_solve():
        prob = pp.TimeScalingProblem(ours, grid=grid)
        prob.add_velocity_limits(-v, v)
        prob.add_acceleration_limits(-a, a)
        return prob.solve()

    def toppra_solve(scheme=None):
        def solve():
            vel = constraint.JointVelocityConstraint(vlim)
            acc = (constraint.JointAccelerationConstraint(alim) if scheme is None
                   else constraint.JointAccelerationConstraint(alim, discretization_scheme=scheme))
            inst = algo.TOPPRA([vel, acc], theirs, gridpoints=grid, solver_wrapper="seidel",
                               parametrizer="ParametrizeConstAccel")
            sdd, sd, _ = inst.compute_parameterization(0, 0)
            return inst, acc, sdd, sd

        return solve

    fns = {"pathpace": pathpace_solve, "toppra": toppra_solve(),
           "toppra_colloc": toppra_solve(constraint.DiscretizationType.Collocation)}
    return grid, ours, theirs, fns


def check_pathpace(res, grid, ref, v, a):
    assert res.ok, f"pathpace: {res.status} {res.message}"
    s, sdot = np.asarray(res.s), np.asarray(res.sdot)
    assert np.array_equal(s, grid), "pathpace changed the grid"
    T = float(common.times_from_sdot(grid, sdot)[-1])
    traj = res.trajectory()
    assert abs(res.duration / T - 1) < 1e-12 and abs(traj.duration / T - 1) < 1e-12, "pathpace's T"
    t = common.dense_times(grid, sdot, DENSE_PER_INTERVAL)
    qd, qdd = traj.qd(t), traj.qdd(t)
    rqd, rqdd = common.reconstruct(ref, grid, sdot, t)
    g = common.grid_violation(ref, grid, sdot, v, a)
    t0 = time.perf_counter()
    for _ in range(5):
        res.trajectory()
    return {"T": T, "T_reported": float(res.duration), "T_trajectory": float(traj.duration),
            "sdot_begin_end": [float(sdot[0]), float(sdot[-1])],
            "grid_violation": g[0], "grid_violation_parts": {"vel": g[1], "acc_fwd": g[2], "acc_bwd": g[3]},
            "dense_violation": common.dense_violation(qd, qdd, v, a),
            "dense_violation_own_reconstruction": common.dense_violation(rqd, rqdd, v, a),
            "trajectory_vs_own_reconstruction": float(max(np.abs(qd - rqd).max(), np.abs(qdd - rqdd).max())),
            "trajectory_object_ms": 1e3 * (time.perf_counter() - t0) / 5,
            "stats": {k: (v_ if isinstance(v_, (int, float, str, bool)) else str(v_)) for k, v_ in res.stats.items()}}


def check_toppra(out, grid, theirs, ref, v, a):
    from toppra.parametrizer import ParametrizeConstAccel

    inst, acc, sdd, sd = out
    if sd is None or np.isnan(sd).any():
        return {"failed": True}
    sdot = np.asarray(sd, float)
    T = float(common.times_from_sdot(grid, sdot)[-1])
    t0 = time.perf_counter()
    traj = ParametrizeConstAccel(theirs, grid, sdot)  # what compute_trajectory builds after re-solving
    traj_ms = 1e3 * (time.perf_counter() - t0)
    assert abs(traj.duration / T - 1) < 1e-12, "toppra's T"
    traj2 = inst.compute_trajectory(0, 0)
    assert np.array_equal(traj2._velocities, sdot), "toppra is not deterministic"
    t = common.dense_times(grid, sdot, DENSE_PER_INTERVAL)
    qd, qdd = traj.evald(t), traj.evaldd(t)
    rqd, rqdd = common.reconstruct(ref, grid, sdot, t)
    g = common.grid_violation(ref, grid, sdot, v, a)
    u = (sdot[1:] ** 2 - sdot[:-1] ** 2) / (2 * np.diff(grid))
    return {"T": T, "T_trajectory": float(traj.duration), "discretization": acc.discretization_type.name,
            "sdot_begin_end": [float(sdot[0]), float(sdot[-1])],
            "grid_violation": g[0], "grid_violation_parts": {"vel": g[1], "acc_fwd": g[2], "acc_bwd": g[3]},
            "dense_violation": common.dense_violation(qd, qdd, v, a),
            "dense_violation_own_reconstruction": common.dense_violation(rqd, rqdd, v, a),
            "trajectory_vs_own_reconstruction": float(max(np.abs(qd - rqd).max(), np.abs(qdd - rqdd).max())),
            "sdd_returned_vs_from_sd": float(np.abs(np.asarray(sdd) - u).max()),
            "trajectory_object_ms": traj_ms}


def run(scale=1.0):
    waypoints, v, a = common.panda_problem(seed=0)
    lim = common.panda_limits()
    assert np.all((waypoints > lim["lower"]) & (waypoints < lim["upper"]))
    ref = common.NotAKnotSpline(np.linspace(0, 1, waypoints.shape[0]), waypoints)

    rows, path_check = [], None
    for N in SIZES:
        grid, ours, theirs, fns = make_solvers(waypoints, v, a, N)
        if path_check is None:  # the two libraries' splines against the reference (and so each other)
            s = np.linspace(0, 1, 10001)
            path_check = {}
            for order, f in enumerate((ours.q, ours.dq, ours.ddq)):
                r = ref(s, order)
                d_ours, d_theirs = np.abs(f(s) - r).max(), np.abs(theirs(s, order) - r).max()
                path_check[f"order{order}"] = {"pathpace_vs_ref": float(d_ours), "toppra_vs_ref": float(d_theirs)}
                scale_r = max(1.0, np.abs(r).max())
                assert d_ours < 1e-10 * scale_r and d_theirs < 1e-10 * scale_r, f"paths differ in derivative {order}"
        rounds = max(3, int(round(ROUNDS[N] * scale)))
        load = os.getloadavg()[0]
        timing, last = common.interleaved_timing(fns, rounds, BLOCK[N])
        row = {"N": N, "rounds": rounds, "block": BLOCK[N], "load1_before": load}
        flat = lambda rows: [1e3 * x for r_ in rows for x in r_]  # noqa: E731
        for name in SOLVERS:
            tm = timing[name]
            row[name] = {"wall_ms": common.summary(flat(tm["wall"]["warm"])),
                         "cpu_ms": common.summary(flat(tm["cpu"]["warm"])),
                         "wall_ms_cold": common.summary(flat(tm["wall"]["cold"])),
                         "cpu_ms_cold": common.summary(flat(tm["cpu"]["cold"]))}
        mine = timing["pathpace"]
        for name in ("toppra", "toppra_colloc"):  # per-round ratios of block medians: robust to load drift
            theirs_ = timing[name]
            for clock in ("wall", "cpu"):
                ratios = [statistics.median(t_) / statistics.median(p_)
                          for t_, p_ in zip(theirs_[clock]["warm"], mine[clock]["warm"])]
                row[name][f"speedup_{clock}_per_round"] = common.summary(ratios)
        row["pathpace"].update(check_pathpace(last["pathpace"], grid, ref, v, a))
        row["toppra"].update(check_toppra(last["toppra"], grid, theirs, ref, v, a))
        row["toppra_colloc"].update(check_toppra(last["toppra_colloc"], grid, theirs, ref, v, a))
        rows.append(row)
        m, t = row["pathpace"], row["toppra"]
        print(f"N={N}: {rounds} rounds, pathpace {m['wall_ms']['median']:.3f} ms, toppra "
              f"{t['wall_ms']['median']:.2f} ms, T {m['T']:.6f} vs {t['T']:.6f}, load {load:.2f}", file=sys.stderr)
    return {"waypoints": waypoints.tolist(), "v": v.tolist(), "a": a.tolist(), "path_check": path_check,
            "rows": rows}


def fmt_e(x):
    return f"{x:.1e}" if x > 0 else "0"


def tables(data):
    rows = data["rows"]
    out = ["| N | pathpace ms | toppra ms | speed-up | toppra colloc. ms | speed-up | T pathpace [s] | T toppra [s] "
           "| T pathpace / toppra - 1 | T toppra colloc. [s] |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        m, t, c = r["pathpace"], r["toppra"], r["toppra_colloc"]
        out.append(
            f"| {r['N']} | {m['wall_ms']['median']:.3f} | {t['wall_ms']['median']:.2f} | "
            f"{t['wall_ms']['median'] / m['wall_ms']['median']:.1f}x | {c['wall_ms']['median']:.2f} | "
            f"{c['wall_ms']['median'] / m['wall_ms']['median']:.1f}x | {m['T']:.6f} | {t['T']:.6f} | "
            f"{100 * (m['T'] / t['T'] - 1):+.5f} % | {c['T']:.6f} |")
    out += ["", "Largest relative violation max(|q̇|/v - 1, |q̈|/a - 1, 0): at the grid points (s̈ of both adjacent "
            "intervals) / inside the intervals (20 samples each, on each library's own trajectory object):", "",
            "| N | pathpace grid | toppra grid | toppra colloc. grid | pathpace dense | toppra dense "
            "| toppra colloc. dense |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        m, t, c = r["pathpace"], r["toppra"], r["toppra_colloc"]
        out.append(f"| {r['N']} | {fmt_e(m['grid_violation'])} | {fmt_e(t['grid_violation'])} | "
                   f"{fmt_e(c['grid_violation'])} | {fmt_e(m['dense_violation'])} | {fmt_e(t['dense_violation'])} | "
                   f"{fmt_e(c['dense_violation'])} |")
    return "\n".join(out)


def verdict(data):
    r = next(r for r in data["rows"] if r["N"] == TARGET["N"])
    m, t = r["pathpace"], r["toppra"]
    speed = t["wall_ms"]["median"] / m["wall_ms"]["median"]
    paired = t["speedup_wall_per_round"]
    excess = m["T"] / t["T"] - 1
    cold = m["wall_ms_cold"]["median"]
    checks = [
        (f"at least {TARGET['speedup']:.0f}x faster than toppra", speed >= TARGET["speedup"],
         f"{speed:.1f}x (ratio of the medians of repeated solves; per-round ratios: median {paired['median']:.1f}x, "
         f"quartiles {paired['q25']:.1f}-{paired['q75']:.1f}x; thread-CPU time "
         f"{t['cpu_ms']['median'] / m['cpu_ms']['median']:.1f}x). A pathpace solve right after a toppra one "
         f"(cold caches and pages) takes {cold:.3f} ms, {t['wall_ms']['median'] / cold:.1f}x"),
        (f"T no more than {100 * TARGET['T_excess']:.1f} % above toppra's", excess <= TARGET["T_excess"],
         f"{100 * excess:+.5f} % (against toppra Collocation: {100 * (m['T'] / r['toppra_colloc']['T'] - 1):+.4f} %)"),
        (f"no violation above {TARGET['grid_violation']:.0e} at the grid points",
         m["grid_violation"] <= TARGET["grid_violation"], f"{fmt_e(m['grid_violation'])}"),
    ]
    lines = [f"Target at N = {TARGET['N']}:"]
    for i, (what, ok, detail) in enumerate(checks):
        word = "met" if ok else "NOT met"
        if i == 0 and paired["q25"] < TARGET["speedup"] <= paired["q75"]:
            word = f"at the threshold ({word} by the medians, but the per-round ratios straddle it)"
            ok = False
        lines.append(f"- {what}: **{word}**, {detail}.")
        checks[i] = (what, ok, detail)
    return "\n".join(lines), all(ok for _, ok, _ in checks)


BEGIN = "<!-- generated by bench/run.py: begin -->"
END = "<!-- generated by bench/run.py: end -->"
HEADING = "## pathpace vs toppra: Panda, velocity and acceleration limits"  # where a first run puts the block


def readme_section(data, table, verdict_text):
    mach = data["machine"]
    r = data["rows"]
    rounds = ", ".join(f"{x['rounds']} at N = {x['N']}" for x in r)
    blocks = "/".join(str(x["block"]) for x in r) + " (N = " + "/".join(str(x["N"]) for x in r) + ")"
    loads = ", ".join(f"{x['load1_before']:.2f}" for x in r)
    default_scheme = r[0]["toppra"]["discretization"]
    assert default_scheme == "Interpolation", "toppra's default changed: revise the text below"
    return BEGIN + "\n" + wrap(f"""Command (from the repository root, after `make python`; `make bench` runs it too):

    .venv/bin/python bench/run.py

Machine: {mach['cpu']}, nproc = {mach['nproc']}, {mach['os']}. Versions: pathpace {mach['pathpace']},
toppra {mach['toppra']}, numpy {mach['numpy']}, scipy {mach['scipy']}, pin {mach['pin']}, Python {mach['python']}.
Run {data['date']}; 1-minute load average before each N: {loads} (the benchmark itself counts for about 1).

Problem, identical for both libraries: the Franka Panda of example-robot-data (7 arm joints, fingers
ignored), a cubic spline through 5 seeded random waypoints inside the joint position limits (uniform
knots on [0, 1], not-a-knot: `pp.CubicSplinePath(..., knots="uniform", boundary="not-a-knot")` and
`toppra.SplineInterpolator(..., bc_type="not-a-knot")` both agree with the script's own not-a-knot
spline to {max(max(d.values()) for d in data['path_check'].values()):.0e} in q, q', q''), URDF velocity limits (pinocchio `model.velocityLimit`,
equal to the XML), acceleration limits 2 x velocity limits, rest to rest, the same array of N + 1
uniform grid points passed to both.

Methodology. Wall-clock medians of repeated solves, one thread (OMP/OpenBLAS/MKL pinned to 1; neither
library starts threads). The three solvers are block-interleaved: each round runs, for each solver in
rotating order, one call that is set apart ("cold": it follows the other library's calls) and then
{blocks} consecutive calls that are the samples (rounds: {rounds}; one warm-up round; Python's garbage
collector at its defaults). Timed from the path object onward: pathpace `TimeScalingProblem` +
`add_velocity_limits` + `add_acceleration_limits` + `solve`; toppra `JointVelocityConstraint` +
`JointAccelerationConstraint` + `TOPPRA(..., solver_wrapper="seidel", parametrizer="ParametrizeConstAccel")`
+ `compute_parameterization(0, 0)`. Building the trajectory object is not timed for either (toppra's
`compute_trajectory` re-runs the whole parameterisation, then builds `ParametrizeConstAccel`). Both produce ṡ at the grid points and a
trajectory with constant s̈ per interval; T = Σ 2Δs_k / (ṡ_k + ṡ_k+1) from each output's ṡ (equal to
each library's reported duration).

"toppra" is `JointAccelerationConstraint` with its default discretisation, which in toppra {mach['toppra']} is
`{default_scheme}`: like eq. (26), it enforces the limits at s_k+1 with interval k's s̈ too, i.e. on both
sides of every grid point. "toppra colloc." passes `DiscretizationType.Collocation`, which checks each
grid point only with the s̈ of the interval to its right; its T is shorter because its output exceeds
the limits at the grid points (see the violation table). Violations are computed by the script's own
numpy code on its own spline, trusting neither library: at the grid points with ṡ there and the s̈ of
the interval on each side, and at 20 points inside every interval of each library's trajectory object
(pathpace `traj.qd/qdd`, toppra `ParametrizeConstAccel.evald/evaldd`).

{table}

{verdict_text}

Raw numbers (quartiles, thread-CPU times, per-round speed-ups, T as reported by each library, violation
parts, pathpace's solver stats): `bench/results/latest.json` (not tracked).""") + "\n" + END


def wrap(markdown, width=105):
    """Re-flow the prose paragraphs and list items of a generated block (tables and code left alone)."""
    out = []
    for para in markdown.split("\n\n"):
        first = para.lstrip("\n")
        if first.startswith(("|", "    ", "<!--")) or not first:
            out.append(para)
        elif all(line.startswith("- ") or not line.startswith(" ") for line in para.splitlines()) and "\n- " in "\n" + para:
            items, cur = [], []
            for line in para.splitlines():
                if line.startswith("- ") and cur:
                    items.append(" ".join(cur))
                    cur = []
                cur.append(line.strip())
            items.append(" ".join(cur))
            out.append("\n".join(textwrap.fill(it, width, subsequent_indent="  ", break_on_hyphens=False,
                                               break_long_words=False) if it.startswith("- ") else it
                                 for it in items))
        else:
            out.append(textwrap.fill(" ".join(para.split()), width, break_on_hyphens=False, break_long_words=False))
    return "\n\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="a tenth of the repetitions; README not written")
    ap.add_argument("--scale", type=float, default=1.0, help="multiply the number of rounds")
    ap.add_argument("--no-readme", action="store_true", help="do not rewrite bench/README.md")
    ap.add_argument("--from-json", metavar="PATH", help="no run: re-render tables and README from saved raw numbers")
    args = ap.parse_args()
    scale = args.scale * (0.1 if args.quick else 1.0)
    if args.from_json:
        data = json.loads(Path(args.from_json).read_text())
        table = tables(data)
        print(table + "\n\n" + verdict(data)[0])
        if not args.no_readme:
            common.write_generated_section(readme_section(data, table, verdict(data)[0]), BEGIN, END, HEADING)
        return

    t0 = time.time()
    data = {"date": time.strftime("%Y-%m-%d %H:%M %Z"), "machine": common.machine(), "build": common.build_info(),
            "command": " ".join(sys.argv)}
    data.update(run(scale))
    data["elapsed_s"] = time.time() - t0
    table = tables(data)
    verdict_text, ok = verdict(data)
    data["target_met"] = ok
    print(table)
    print()
    print(verdict_text)
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "latest.json").write_text(json.dumps(data, indent=1, default=float))
    if not (args.quick or args.no_readme):
        common.write_generated_section(readme_section(data, table, verdict_text), BEGIN, END, HEADING)
    print(f"\n{data['elapsed_s']:.0f} s; raw numbers in bench/results/latest.json", file=sys.stderr)


if __name__ == "__main__":
    main()
