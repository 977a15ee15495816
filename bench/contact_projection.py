"""Projection cost for a humanoid (baseline for the contact issue; not yet the issue's sway benchmark).

Talos (example-robot-data, floating base, gripper mimic joints locked) standing on both feet: four
corner contacts per sole (8 contacts) or sixteen per sole (32), μ = 0.5 with 50 % friction margin,
10 N minimum normal force. The path sways the base sideways by ±2 cm around the neutral posture with
the joints fixed, so the feet do not stay exactly in place: this measures the projection only
(drift check off), at N = 100.

    .venv/bin/python bench/contact_projection.py
"""

import time
import xml.etree.ElementTree as ET

import numpy as np

import pathpace as pp
from pathpace.robots import example_robot_urdf

urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
robot = pp.RobotModel.from_urdf(urdf, floating_base=True, locked_joints={n: 0.0 for n in mimic})
n = robot.nq
q0 = np.zeros(n)
q0[2] = 1.02  # base height with straight legs
foot_z = robot.frame_placement(q0, "left_sole_link")[2, 3]
q0[2] -= foot_z  # soles on the ground
wp = np.tile(q0, (3, 1))
wp[:, 1] += [-0.02, 0.02, -0.02]
path = pp.CubicSplinePath(wp)


def soles(per_side):
    side = int(np.sqrt(per_side))
    xs, ys = np.linspace(-0.1, 0.1, side), np.linspace(-0.05, 0.05, side)
    pts = [(x, y, 0.0) for x in xs for y in ys]
    return [pp.Contact(link, point=p, normal=[0, 0, 1], friction=0.5) for link in ("left_sole_link", "right_sole_link") for p in pts]


for per_side in (4, 16):
    contacts = soles(per_side)
    prob = pp.TimeScalingProblem(path, grid=100)
    t0 = time.perf_counter()
    prob.add_contacts(robot, contacts, cone_edges=8, friction_margin=0.5, min_normal_force=10.0, drift_tolerance=np.inf)
    t_proj = time.perf_counter() - t0
    edges = [prob.feasible_set(k).halfplanes.shape[0] for k in range(101)]
    t0 = time.perf_counter()
    res = prob.solve()
    t_solve = time.perf_counter() - t0
    print(f"{len(contacts)} contacts, nq = {n}, N = 100: projection {t_proj * 1e3:.1f} ms ({t_proj / 101 * 1e3:.2f} ms per grid point), "
          f"{np.mean(edges):.1f} edges per point; solve {t_solve * 1e3:.1f} ms, {res.status.name}, T = {res.duration:.3f} s")
