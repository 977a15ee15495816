"""The cost of a frame limit (issue 22): rows at N = 1000 on a seeded corpus, and what it adds to a solve.

    .venv/bin/python bench/frame_limits.py [--quick]

Corpus: random cubic-spline paths (5 waypoints inside the middle 60 % of the joint range, seeds 0-9) on the
Panda (fingers locked, link panda_hand), the UR5 (tool0) and Talos with a floating base (mimic joints
locked, link arm_left_7_link: a 13-body chain of 44 coordinates). For each path, N = 1000: the time of
add_frame_* (the rows' evaluation, one forward pass per grid point, plus the problem's bookkeeping),
beside add_velocity_limits and add_torque_limits on the same problem; then a solve with joint velocity and
acceleration limits alone and with a tool speed limit added. Each time is the median of 5 repetitions;
the table gives the median and the worst over the corpus.
"""

import statistics
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

import pathpace as pp
from pathpace.robots import example_robot_urdf

N = 1000


def robots():
    panda_urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    panda = pp.RobotModel.from_urdf(panda_urdf, locked_joints={"panda_finger_joint1": 0.0, "panda_finger_joint2": 0.0})
    ur5 = pp.RobotModel.from_urdf(example_robot_urdf("ur_description/urdf/ur5_robot.urdf"))
    talos_urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
    mimic = [j.get("name") for j in ET.parse(talos_urdf).getroot().iter("joint") if j.find("mimic") is not None]
    talos = pp.RobotModel.from_urdf(talos_urdf, floating_base=True, locked_joints={n: 0.0 for n in mimic})
    return [("panda", panda, "panda_hand"), ("ur5", ur5, "tool0"), ("talos", talos, "arm_left_7_link")]


def path(robot, seed):
    rng = np.random.default_rng(seed)
    lo = np.maximum(robot.position_limits[0], -2.5)
    hi = np.minimum(robot.position_limits[1], 2.5)
    return pp.CubicSplinePath(rng.uniform(lo + 0.2 * (hi - lo), hi - 0.2 * (hi - lo), (5, robot.nq)))


def ms(fn, reps=5):
    out = []
    for _ in range(reps):
        t = fn()
        out.append(t)
    return 1e3 * statistics.median(out)


def timed_add(p, add):
    def run():
        prob = pp.TimeScalingProblem(p, N)
        t0 = time.perf_counter()
        add(prob)
        return time.perf_counter() - t0
    return run


def timed_solve(p, robot, link, with_frame):
    prob = pp.TimeScalingProblem(p, N)
    prob.add_velocity_limits(-np.ones(robot.nq), np.ones(robot.nq))
    prob.add_acceleration_limits(-5 * np.ones(robot.nq), 5 * np.ones(robot.nq))
    if with_frame:
        prob.add_frame_translational_speed_limit(robot, link, 0.3)

    def run():
        t0 = time.perf_counter()
        prob.solve()
        return time.perf_counter() - t0
    return run


def main():
    seeds = range(3) if "--quick" in sys.argv else range(10)
    print(f"| robot | nq | add_frame_translational_speed_limit ms | add_frame_velocity_limits (local) ms | "
          f"add_frame_acceleration_limits ms | add_velocity_limits ms | add_torque_limits ms | "
          f"solve ms (joint limits) | solve ms (+ tool speed) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, robot, link in robots():
        cols = {k: [] for k in ("speed", "vel", "acc", "jv", "tq", "s0", "s1")}
        n = robot.nq
        for seed in seeds:
            p = path(robot, seed)
            cols["speed"].append(ms(timed_add(p, lambda pr: pr.add_frame_translational_speed_limit(robot, link, 0.3))))
            cols["vel"].append(ms(timed_add(p, lambda pr: pr.add_frame_velocity_limits(
                robot, link, [-0.3] * 3, [0.3] * 3, frame="local"))))
            cols["acc"].append(ms(timed_add(p, lambda pr: pr.add_frame_acceleration_limits(robot, link, [-2] * 3, [2] * 3))))
            cols["jv"].append(ms(timed_add(p, lambda pr: pr.add_velocity_limits(-np.ones(n), np.ones(n)))))
            cols["tq"].append(ms(timed_add(p, lambda pr: pr.add_torque_limits(robot))))
            if name != "talos":  # its floating base has no joint limits to time a solve against
                cols["s0"].append(ms(timed_solve(p, robot, link, False)))
                cols["s1"].append(ms(timed_solve(p, robot, link, True)))

        def cell(v):
            return f"{statistics.median(v):.3f} / {max(v):.3f}" if v else "-"
        print(f"| {name} | {n} | " + " | ".join(cell(cols[k]) for k in ("speed", "vel", "acc", "jv", "tq", "s0", "s1"))
              + " |")
    print(f"\n(median / worst over {len(seeds)} seeded paths per robot, N = {N}; each the median of 5 runs)")


if __name__ == "__main__":
    main()
