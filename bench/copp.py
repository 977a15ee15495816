"""pathpace against copp (copp-py, Rust TOPP-RA: the fastest compiled peer) on bench/sweep.py's corpus, case (a):
4 arms of example-robot-data x 20 seeds, URDF velocity limits and acceleration limits = 2 x velocity, rest to
rest, N = 100 / 1000 / 10000 uniform grid points. Identical inputs: both get the same grid and the same p, p', p''
(copp takes sampled derivatives, `Robot.set_q`; they are sampled from pathpace's not-a-knot spline, and that
sampling is inside copp's timed call, as evaluating the path is inside pathpace's). Timed by thread CPU time,
interleaved call by call, median per path; T = Σ 2Δs / (ṡ_k + ṡ_{k+1}) from each profile; violations at the grid
points with both adjacent s̈ (bench/common.py's oracle, its own spline).

    .venv/bin/python bench/copp.py            (about 2 min; prints the table in bench/README.md)
    .venv/bin/python bench/copp.py --seeds 5
    .venv/bin/python bench/copp.py --seed0 100    (held out: seeds 100-119, paths no session tuned on)
"""

import argparse
import statistics
import time

import numpy as np

import common
import pathpace as pp
from sweep import ARMS, Arm, copp_solver, waypoints


def solvers(arm, wp, N):
    grid = np.linspace(0.0, 1.0, N + 1)
    path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
    v, a = arm.v, 2.0 * arm.v

    def ours():
        prob = pp.TimeScalingProblem(path, grid=grid)
        prob.add_velocity_limits(-v, v)
        prob.add_acceleration_limits(-a, a)
        return np.asarray(prob.solve().sdot)

    return grid, {"pathpace": ours, "copp": copp_solver(path, grid, v, a)}


def timed(fns, rounds=5):
    cpu = {n: [] for n in fns}
    last = {n: f() for n, f in fns.items()}
    for r in range(rounds):
        for n in (list(fns) if r % 2 == 0 else list(fns)[::-1]):
            c0 = time.thread_time()
            last[n] = fns[n]()
            cpu[n].append(time.thread_time() - c0)
    return {n: statistics.median(x) for n, x in cpu.items()}, last


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--seed0", type=int, default=0, help="first seed (the corpus: 0)")
    ap.add_argument("--N", default="100,1000,10000")
    args = ap.parse_args()
    arms = {name: Arm(name) for name in ARMS}
    print("| N | paths | speed-up over copp (CPU): median / worst / best | pathpace ms | copp ms | "
          "T / T_copp - 1: median, min, max | grid violation pathpace / copp (worst) |")
    print("|---|---|---|---|---|---|---|")
    for N in (int(x) for x in args.N.split(",")):
        ratio, t_ours, t_copp, dT, v_ours, v_copp = [], [], [], [], [], []
        for name, arm in arms.items():
            for seed in range(args.seed0, args.seed0 + args.seeds):
                wp = waypoints(arm, seed)
                grid, fns = solvers(arm, wp, N)
                med, last = timed(fns, rounds=5 if N <= 1000 else 3)
                ratio.append(med["copp"] / med["pathpace"])
                t_ours.append(med["pathpace"])
                t_copp.append(med["copp"])
                T = {n: float(np.sum(2 * np.diff(grid) / (sd[:-1] + sd[1:]))) for n, sd in last.items()}
                dT.append(T["pathpace"] / T["copp"] - 1)
                ref = common.NotAKnotSpline(np.linspace(0, 1, wp.shape[0]), wp)
                v_ours.append(common.grid_violation(ref, grid, last["pathpace"], arm.v, 2.0 * arm.v)[0])
                v_copp.append(common.grid_violation(ref, grid, last["copp"], arm.v, 2.0 * arm.v)[0])
        print(f"| {N} | {len(ratio)} | {statistics.median(ratio):.2f}x / {min(ratio):.2f}x / {max(ratio):.2f}x | "
              f"{1e3 * statistics.median(t_ours):.3f} | {1e3 * statistics.median(t_copp):.3f} | "
              f"{statistics.median(dT):.1e}, {min(dT):.1e}, {max(dT):.1e} | {max(v_ours):.1e} / {max(v_copp):.1e} |",
              flush=True)


if __name__ == "__main__":
    main()
