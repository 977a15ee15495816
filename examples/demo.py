"""The main job: time a real robot path.

A Franka Panda (example-robot-data URDF) moves through five waypoints inside its joint limits. pathpace
finds the fastest timing under the URDF velocity limits and accelerations of 2x those, then checks the
result on a dense resampling and writes the trajectory to examples/output/panda_trajectory.csv.
A variant with one joint locked (velocity limit 0) shows how a path that cannot be followed is
reported.
"""

from pathlib import Path

import numpy as np

import pathpace as pp
from pathpace.io import save_trajectory_csv
from pathpace.robots import example_robot_urdf, urdf_joint_limits

joints = [f"panda_joint{i}" for i in range(1, 8)]
limits = urdf_joint_limits(example_robot_urdf("panda_description/urdf/panda.urdf"), joints)
lo, hi, vmax = limits["lower"], limits["upper"], limits["velocity"]
amax = 2.0 * vmax

rng = np.random.default_rng(0)
# Waypoints in the middle 60 % of each joint's range: the spline between them overshoots the waypoints, and a
# path must stay inside the position limits (time scaling cannot fix a path that leaves them).
waypoints = lo + (hi - lo) * rng.uniform(0.2, 0.8, (5, 7))
path = pp.CubicSplinePath(waypoints)
q_dense = path.q(np.linspace(0.0, 1.0, 10001))
margin = np.min(np.minimum(q_dense - lo, hi - q_dense) / (hi - lo))
assert margin > 0, "the path leaves the joint position limits"
print(f"Path inside the joint position limits (closest: {100 * margin:.1f} % of a joint's range from a limit)")

prob = pp.TimeScalingProblem(path, grid=1000)
prob.add_velocity_limits(-vmax, vmax)
prob.add_acceleration_limits(-amax, amax)
res = prob.solve()
print(f"Panda, 5 waypoints, N = 1000: {res.status.name}, T = {res.duration:.4f} s")
st = res.stats
print(f"  solve: feasible sets {1e3 * st['time_feasible_sets']:.2f} ms, reachability "
      f"{1e3 * st['time_reachability']:.2f} ms, SLP {1e3 * st['time_slp']:.2f} ms "
      f"({st['lp_solves']} LPs); certified gap to the optimum {st['gap']:.1e}")

traj = res.trajectory()
t = np.linspace(0.0, traj.duration, 20001)
qd, qdd = traj.qd(t), traj.qdd(t)
print(f"  peak |qd|/vmax = {np.max(np.abs(qd) / vmax):.6f}, peak |qdd|/amax = {np.max(np.abs(qdd) / amax):.6f} "
      "(dense resampling; between grid points s̈ is constant, so q̈ may exceed a limit by O(Δs))")
# Limits at every instant, not only at the grid points: guarantee="continuous" bounds p'(s), p''(s) over each
# interval (Bernstein bounds of the spline pieces), for a slightly longer T.
cont = prob.solve(guarantee="continuous")
tc = cont.trajectory()
t = np.linspace(0.0, tc.duration, 20001)
print(f"  guarantee='continuous': {cont.status.name}, T = {cont.duration:.4f} s "
      f"(+{100 * (cont.duration / res.duration - 1):.3f} %), peak |qd|/vmax = {np.max(np.abs(tc.qd(t)) / vmax):.6f}, "
      f"peak |qdd|/amax = {np.max(np.abs(tc.qdd(t)) / amax):.6f}")
out = Path(__file__).parent / "output"
out.mkdir(exist_ok=True)
save_trajectory_csv(traj, out / "panda_trajectory.csv", dt=0.01, joint_names=joints)
print(f"  trajectory written to {out / 'panda_trajectory.csv'}")

# A path that cannot be followed: panda_joint4 must not move, but the path moves it.
stuck = vmax.copy()
stuck[3] = 0.0
bad = pp.TimeScalingProblem(path, grid=1000)
bad.set_joint_names(joints)  # messages name the joint
bad.add_velocity_limits(-stuck, stuck)
r = bad.solve()
print(f"With panda_joint4 locked by a zero velocity limit: {r.status.name}: {r.message}")
