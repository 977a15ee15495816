"""Throughput of pp.solve_many on threads: 1 vs 2 worker threads (solve releases the GIL).

    .venv/bin/python bench/batch.py

Corpus: 64 torque-limited Panda problems (the problem of bench/torque.py: URDF velocity limits, torques
at 0.65 x URDF effort, N = 1000), each a cubic spline through 5 seeded random waypoints inside the joint
limits. The problems are built once; only solve_many is timed. Rounds alternate 1 and 2 threads (which
goes first rotates); throughput = problems / wall time. "process CPU / wall" above 1 shows both threads
computing at once (the GIL is released during solve); it is capped by what the machine's other load
leaves. Prints a Markdown table.
"""

import os
import platform
import statistics
import time

import numpy as np

import pathpace as pp
from pathpace.robots import example_robot_urdf

ROUNDS = 7
COUNT = 64


def corpus():
    urdf = example_robot_urdf("panda_description/urdf/panda.urdf")
    robot = pp.RobotModel.from_urdf(urdf, locked_joints={"panda_finger_joint1": 0.0, "panda_finger_joint2": 0.0})
    lo, hi = robot.position_limits
    v = robot.velocity_limits
    rng = np.random.default_rng(0)
    probs = []
    for _ in range(COUNT):
        prob = pp.TimeScalingProblem(pp.CubicSplinePath(lo + (hi - lo) * rng.uniform(0.1, 0.9, (5, 7))), grid=1000)
        prob.add_velocity_limits(-v, v)
        prob.add_torque_limits(robot, scale=0.65)
        probs.append(prob)
    return probs


def main():
    probs = corpus()
    pp.solve_many(probs, workers=2)  # warm-up
    rate = {1: [], 2: []}
    cpu = {1: [], 2: []}
    load = []
    for r in range(ROUNDS):
        for w in ((1, 2) if r % 2 == 0 else (2, 1)):
            load.append(os.getloadavg()[0])
            t0, c0 = time.perf_counter(), time.process_time()
            res = pp.solve_many(probs, workers=w)
            wall = time.perf_counter() - t0
            rate[w].append(COUNT / wall)
            cpu[w].append((time.process_time() - c0) / wall)
            assert all(x.ok for x in res)
    m1, m2 = statistics.median(rate[1]), statistics.median(rate[2])
    print(f"Machine: nproc = {os.cpu_count()}, {platform.platform()}; 1-minute load average before the runs "
          f"{min(load):.2f}-{max(load):.2f}; {ROUNDS} rounds of {COUNT} problems.")
    print("| threads | problems/s median | worst | speed-up (medians) | process CPU / wall, median |")
    print("|---|---|---|---|---|")
    print(f"| 1 | {m1:.1f} | {min(rate[1]):.1f} | 1.00x | {statistics.median(cpu[1]):.2f} |")
    print(f"| 2 | {m2:.1f} | {min(rate[2]):.1f} | {m2 / m1:.2f}x | {statistics.median(cpu[2]):.2f} |")


if __name__ == "__main__":
    main()
