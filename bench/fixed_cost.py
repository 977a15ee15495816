"""Issue 25, Deliver 2 (the Python call's fixed cost): thread CPU time of each part of one arm call (problem
construction, add_velocity_limits + add_acceleration_limits, solve(), reading sdot), median of 60 calls per path
after 5 warm-ups, on 4 arms x seeds 0-2 of bench/sweep.py's corpus (URDF velocity limits, 2x acceleration).

    PYTHONPATH=bench .venv/bin/python bench/fixed_cost.py      (about 1 min)
"""

import time

import numpy as np

import pathpace as pp
from sweep import ARMS, Arm, waypoints


def parts(path, grid, v, a):
    t = [time.thread_time()]
    prob = pp.TimeScalingProblem(path, grid=grid)
    t.append(time.thread_time())
    prob.add_velocity_limits(-v, v)
    prob.add_acceleration_limits(-a, a)
    t.append(time.thread_time())
    r = prob.solve()
    t.append(time.thread_time())
    np.asarray(r.sdot)
    t.append(time.thread_time())
    return np.diff(t)


def main():
    arms = [Arm(n) for n in ARMS]
    for N in (100, 1000):
        grid = np.linspace(0.0, 1.0, N + 1)
        res = []
        for arm in arms:
            for seed in range(3):
                path = pp.CubicSplinePath(waypoints(arm, seed), knots="uniform", boundary="not-a-knot",
                                          s_begin=0.0, s_end=1.0)
                for _ in range(5):
                    parts(path, grid, arm.v, 2.0 * arm.v)
                res.append(np.median([parts(path, grid, arm.v, 2.0 * arm.v) for _ in range(60)], axis=0) * 1e6)
        res = np.array(res)
        outside = 1.0 - res[:, 2] / res.sum(axis=1)
        print(f"N = {N}, {len(res)} paths, median µs: construct {np.median(res[:, 0]):.1f}, add_* "
              f"{np.median(res[:, 1]):.1f}, solve {np.median(res[:, 2]):.1f}, sdot {np.median(res[:, 3]):.1f}; "
              f"outside solve(): median {100 * np.median(outside):.1f} %, max {100 * outside.max():.1f} %")


if __name__ == "__main__":
    main()
