"""The cost of a frame limit (issue 22): rows at N = 1000 on a seeded corpus, and what it adds to a solve.

    .venv/bin/python bench/frame_limits.py [--quick]

Corpus: random cubic-spline paths (5 waypoints inside the middle 60 % of the joint range, seeds 0-9) on the
Panda (fingers locked, link panda_hand), the UR5 (tool0) and Talos with a floating base (mimic joints
locked, link arm_left_7_link: a chain of 15 of its 38 bodies). For each path, N = 1000: the time of
add_frame_* (the rows' evaluation, one forward pass per grid point, plus the problem's bookkeeping),
beside add_velocity_limits and add_torque_limits on the same problem; then a solve with joint velocity and
acceleration limits alone and with a tool speed limit (0.3 m/s) added. Each time is the median of 5
repetitions (wall clock); the table gives the median and the worst over the corpus.

--continuous [--quick]: guarantee = "continuous" on the Panda and the UR5, seeds 0-9 (0-2), N = 1000, joint
velocity 1 rad/s and acceleration 5 rad/s² alone or plus one frame limit (tool speed 0.3 m/s; linear velocity
±0.2 m/s per local axis; linear acceleration ±1 m/s² per world axis) or, for comparison, torque limits at
0.7 x effort; default audit_tolerance 1e-10 and 1e-6; time_limit 30 s; one continuous solve each (wall
clock) beside the grid solve (median of 5); median and worst over the seeds.
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
        res = prob.solve()
        assert res.ok, res.message
        return time.perf_counter() - t0
    return run


def main():
    seeds = range(3) if "--quick" in sys.argv else range(10)
    print(f"| robot | nq | add_frame_translational_speed_limit ms | add_frame_velocity_limits (local) ms | "
          f"add_frame_acceleration_limits ms | add_velocity_limits ms | add_torque_limits ms | "
          f"solve ms (joint limits) | solve ms (+ tool speed) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, robot, link in robots():
        keys = ("speed", "vel", "acc", "jv", "tq", "s0", "s1")
        cols = {k: [] for k in keys}
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
        print(f"| {name} | {n} | " + " | ".join(cell(cols[k]) for k in keys)
              + " |")
    print(f"\n(median / worst over {len(seeds)} seeded paths per robot, N = {N}; each the median of 5 runs)")


def continuous_problem(robot, link, seed, kind):
    prob = pp.TimeScalingProblem(path(robot, seed), N)
    prob.add_velocity_limits(-np.ones(robot.nq), np.ones(robot.nq))
    prob.add_acceleration_limits(-5 * np.ones(robot.nq), 5 * np.ones(robot.nq))
    if kind == "speed":
        prob.add_frame_translational_speed_limit(robot, link, 0.3)
    elif kind == "velocity":
        prob.add_frame_velocity_limits(robot, link, [-0.2] * 3, [0.2] * 3, frame="local")
    elif kind == "acceleration":
        prob.add_frame_acceleration_limits(robot, link, [-1] * 3, [1] * 3)
    elif kind == "torque":
        prob.add_torque_limits(robot, scale=0.7)
    return prob


def continuous():
    seeds = range(3) if "--quick" in sys.argv else range(10)
    print("| robot | limit | audit_tolerance | statuses | grid solve ms | continuous solve ms | continuous / grid | "
          "audit rounds | cuts | T continuous / grid - 1 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name, robot, link in robots()[:2]:
        for kind in ("joint limits only", "speed", "velocity", "acceleration", "torque"):
            for tol in (1e-10, 1e-6):
                cols = {k: [] for k in ("grid", "cont", "ratio", "rounds", "cuts", "dT")}
                statuses = {}
                for seed in seeds:
                    prob = continuous_problem(robot, link, seed, kind)
                    grid = prob.solve()
                    tg = ms(lambda: (lambda t0: (prob.solve(), time.perf_counter() - t0)[1])(time.perf_counter()))
                    t0 = time.perf_counter()
                    r = prob.solve(guarantee="continuous", time_limit=30, audit_tolerance=tol)
                    tc = 1e3 * (time.perf_counter() - t0)
                    statuses[r.status.name] = statuses.get(r.status.name, 0) + 1
                    cols["grid"].append(tg)
                    cols["cont"].append(tc)
                    cols["ratio"].append(tc / tg)
                    cols["rounds"].append(r.stats["audit_rounds"])
                    cols["cuts"].append(r.stats["audit_cuts"])
                    cols["dT"].append(r.duration / grid.duration - 1)

                def cell(v, f):
                    return f"{format(statistics.median(v), f)} / {format(max(v), f)}"
                st = ", ".join(f"{k} {v}" for k, v in sorted(statuses.items()))
                print(f"| {name} | {kind} | {tol:g} | {st} | {cell(cols['grid'], '.2f')} | {cell(cols['cont'], '.0f')} | "
                      f"{cell(cols['ratio'], '.0f')} | {cell(cols['rounds'], 'g')} | {cell(cols['cuts'], 'g')} | "
                      f"{cell(cols['dT'], '.2e')} |", flush=True)
    print(f"\n(median / worst over seeds {seeds.start}-{seeds.stop - 1}, N = {N}; grid solve the median of 5, "
          "continuous one solve)")


if __name__ == "__main__":
    continuous() if "--continuous" in sys.argv else main()
