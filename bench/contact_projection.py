"""Contact projection cost for a humanoid: the contact issue's benchmark.

Talos (example-robot-data, floating base, gripper mimic joints locked) sways its pelvis ±7 cm over each
foot with both soles flat (feet-fixed IK path of examples/talos_sway.py): four corner contacts per sole
(8 contacts) or a 4 x 4 grid per sole (32), μ = 0.5 with a 50 % friction margin, 10 N minimum normal
force, 8-edge cones, N = 100. Reports the projection time per grid point and in total, the polygon
edges per grid point, LPs per grid point, and the whole solve (sets + reachability + SLP), median of
--repeat runs on one core.

    .venv/bin/python bench/contact_projection.py [--repeat 5]
"""

import argparse
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "examples"))
import pathpace as pp  # noqa: E402
from talos_sway import CONTACT_OPTIONS, load_talos, sole_contacts, sway_path  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("--repeat", type=int, default=5)
ap.add_argument("--grid", type=int, default=100)
args = ap.parse_args()

robot = load_talos()
path = sway_path(robot)
N = args.grid
print(f"Talos nq = {robot.nq}, sway path, N = {N}, median of {args.repeat}")
print("| contacts | LP columns | projection total (ms) | per grid point (ms) | edges per point | solve (ms) | total (ms) | T (s) |")
print("|---:|---:|---:|---:|---:|---:|---:|---:|")
for per_side in (4, 16):
    contacts = sole_contacts(per_side)
    t_proj, t_solve = [], []
    for _ in range(args.repeat):
        prob = pp.TimeScalingProblem(path, grid=N)
        t0 = time.perf_counter()
        prob.add_contacts(robot, contacts, drift_tolerance=1e-4, **CONTACT_OPTIONS)
        t_proj.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        res = prob.solve()
        t_solve.append(time.perf_counter() - t0)
    edges = [prob.feasible_set(k).halfplanes.shape[0] for k in range(N + 1)]
    tp, ts = statistics.median(t_proj), statistics.median(t_solve)
    print(f"| {len(contacts)} | {2 + len(contacts) * CONTACT_OPTIONS['cone_edges']} | {tp * 1e3:.1f} | {tp / (N + 1) * 1e3:.3f} | "
          f"{np.mean(edges):.2f} | {ts * 1e3:.1f} | {(tp + ts) * 1e3:.1f} | {res.duration:.4f} ({res.status.name}) |")
