"""Torque limits from the user's own dynamics (add_torque_limits(inverse_dynamics=...)) against the built-in
model (add_torque_limits(robot)), issue 22's target: <= 2x the built-in time at N = 1000.

    .venv/bin/python bench/callback_dynamics.py [--quick]

(1) A planar two-link arm (point masses 1 kg at 1 m, the URDF below for the built-in model) with its
    dynamics in closed form, vectorised with numpy: one call for the 3(N+1) samples of eq. 12. Seeded corpus
    of random paths (5-8 waypoints), velocity limits and torque limits that bind, N = 1000. Each problem is
    timed from construction to solution (build + add_* + solve), alternating built-in and callback, median
    of 5 each; the table gives the median and worst ratio over the corpus, and |ΔT|/T.
(2) The UR5 with pinocchio's RNEA looped over the rows inside the callback (what a user without a
    vectorised model pays): the same timing, with the time spent inside the callback reported separately.
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import statistics  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402

PLANAR_URDF = """<robot name="planar2">
  <link name="base"/>
  <link name="l1"><inertial><origin xyz="1 0 0"/><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <link name="l2"><inertial><origin xyz="1 0 0"/><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 -1 0"/>
    <limit lower="-3.1" upper="3.1" effort="40" velocity="3"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="1 0 0"/><axis xyz="0 -1 0"/>
    <limit lower="-3.1" upper="3.1" effort="15" velocity="3"/></joint>
</robot>"""


def planar_arm(q, qd, qdd):
    """τ = M(q) q̈ + C(q, q̇) q̇ + g(q) of PLANAR_URDF in closed form (rotation about -y: height = sin)."""
    c2, s2 = np.cos(q[:, 1]), np.sin(q[:, 1])
    c1, c12 = np.cos(q[:, 0]), np.cos(q[:, 0] + q[:, 1])
    m11, m12 = 3.0 + 2.0 * c2, 1.0 + c2
    h1, h2 = -s2 * (2.0 * qd[:, 0] * qd[:, 1] + qd[:, 1] ** 2), s2 * qd[:, 0] ** 2
    return np.column_stack([m11 * qdd[:, 0] + m12 * qdd[:, 1] + h1 + 9.81 * (2.0 * c1 + c12),
                            m12 * qdd[:, 0] + qdd[:, 1] + h2 + 9.81 * c12])


class Timed:
    """The callback with the time spent inside it."""

    def __init__(self, f):
        self.f, self.seconds = f, 0.0

    def __call__(self, q, qd, qdd):
        t0 = time.perf_counter()
        out = self.f(q, qd, qdd)
        self.seconds += time.perf_counter() - t0
        return out


def corpus(nq, lo, hi, count, seed=22):
    rng = np.random.default_rng(seed)
    return [lo + (hi - lo) * rng.uniform(0.1, 0.9, (int(rng.integers(5, 9)), nq)) for _ in range(count)]


def solve(waypoints, N, vmax, tau, robot=None, inverse_dynamics=None):
    t0 = time.perf_counter()
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(waypoints), grid=N)
    prob.add_velocity_limits(-vmax, vmax)
    if robot is not None:
        prob.add_torque_limits(robot, tau_min=-tau, tau_max=tau)
    else:
        prob.add_torque_limits(inverse_dynamics=inverse_dynamics, tau_min=-tau, tau_max=tau)
    res = prob.solve()
    return time.perf_counter() - t0, res


def compare(name, robot, callback, paths, N, vmax, tau, reps):
    ratios, dts, own, net = [], [], [], []
    t_builtin, t_callback = [], []
    for w in paths:
        a, b, inside = [], [], []
        for _ in range(reps):
            ta, ra = solve(w, N, vmax, tau, robot=robot)
            timed = Timed(callback)
            tb, rb = solve(w, N, vmax, tau, inverse_dynamics=timed)
            a.append(ta), b.append(tb), inside.append(timed.seconds)
        assert ra.status.name == rb.status.name == "OPTIMAL", (ra.message, rb.message)
        ma, mb = statistics.median(a), statistics.median(b)
        t_builtin.append(ma), t_callback.append(mb)
        ratios.append(mb / ma)
        own.append(statistics.median(inside) / mb)
        net.append((mb - statistics.median(inside)) / ma)
        dts.append(abs(rb.duration - ra.duration) / ra.duration)
    print(f"| {name} | {len(paths)} | {1e3 * statistics.median(t_builtin):.2f} | {1e3 * statistics.median(t_callback):.2f} "
          f"| {statistics.median(ratios):.2f} / {max(ratios):.2f} | {100 * statistics.median(own):.0f} % "
          f"| {statistics.median(net):.2f} / {max(net):.2f} "
          f"| {statistics.median(dts):.1e} / {max(dts):.1e} |")


def main():
    quick = "--quick" in sys.argv
    reps, count, N = (3, 4, 1000) if quick else (5, 10, 1000)
    print(f"N = {N}, median of {reps} per path, built-in and callback alternating\n")
    print("| robot, callback | paths | built-in ms (median) | callback ms (median) | ratio median / worst "
          "| inside the callback | ratio without the callback's own time | abs(ΔT)/T median / worst |")
    print("|---|---|---|---|---|---|---|---|")
    planar = pp.RobotModel.from_urdf_string(PLANAR_URDF)
    lo, hi = np.array([-1.5, -1.5]), np.array([1.5, 1.5])
    compare("planar 2-link, numpy closed form", planar, planar_arm, corpus(2, lo, hi, count), N,
            np.array([3.0, 3.0]), np.array([40.0, 15.0]), reps)
    try:
        import pinocchio as pin

        from pathpace.robots import example_robot_urdf
    except ImportError:
        print("(pinocchio or example-robot-data missing: UR5 row skipped)")
        return
    urdf = str(example_robot_urdf("ur_description/urdf/ur5_robot.urdf"))
    ur5 = pp.RobotModel.from_urdf(urdf)
    model = pin.buildModelFromUrdf(urdf)
    data = model.createData()

    def rnea(q, qd, qdd):
        return np.array([pin.rnea(model, data, a, b, c) for a, b, c in zip(q, qd, qdd)])

    lo, hi = np.maximum(ur5.position_limits[0], -3.0), np.minimum(ur5.position_limits[1], 3.0)
    compare("UR5, pinocchio rnea per row", ur5, rnea, corpus(6, lo, hi, count), N, ur5.velocity_limits,
            0.5 * ur5.effort_limits, reps)


if __name__ == "__main__":
    main()
