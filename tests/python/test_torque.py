"""Torque limits along the path: the pendulum swing-up, an independent oracle on the Panda."""

from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
from oracles import arm_rows, cvxpy_optimum, max_violation, pinocchio_model
from pathpace.robots import example_robot_urdf

# Torque rows take the CPU's widest SIMD path (8 lanes with AVX-512): every width this CPU runs, each test.
pytestmark = pytest.mark.usefixtures("each_torque_width")

DATA = Path(__file__).resolve().parents[1] / "data"
SWING_UP_OPTIMUM = 2.206316  # 1-D phase-plane integration of the continuous problem (issue statement)


def bezier(P):
    """Cubic Bézier in one coordinate as a one-piece polynomial path on [0, 1]."""
    P0, P1, P2, P3 = P
    c = np.array([[P0], [3 * (P1 - P0)], [3 * (P0 - 2 * P1 + P2)], [P3 - 3 * P2 + 3 * P1 - P0]])
    return pp.PiecewisePolynomialPath([0.0, 1.0], c[None, :, :])


@pytest.fixture(scope="module")
def pendulum():
    return pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))


def test_pendulum_swing_up_approaches_the_continuous_optimum(pendulum):
    path = bezier([0, -np.pi, np.pi, np.pi])  # swings back before rising
    errors = []
    for N in (250, 1000, 4000):
        prob = pp.TimeScalingProblem(path, grid=N)
        prob.add_torque_limits(pendulum)
        res = prob.solve()
        assert res.status == pp.Status.OPTIMAL, res.message
        errors.append(res.duration / SWING_UP_OPTIMUM - 1)
        if N == 1000:
            assert abs(errors[-1]) < 5e-3
            # Torques at the grid points, with s̈ of the interval on each side, stay within ±5.6.
            s, sd = res.s, res.sdot
            th = sd**2
            u = np.diff(th) / (2 * np.diff(s))
            q, dq, ddq = path.q(s)[:, 0], path.dq(s)[:, 0], path.ddq(s)[:, 0]
            for idx, uu in ((np.arange(N), u), (np.arange(1, N + 1), u)):
                tau = ddq[idx] * th[idx] + dq[idx] * uu + 9.81 * np.sin(q[idx])  # m = l = 1
                assert np.max(np.abs(tau)) <= 5.6 * (1 + 1e-9)
            # ... and traj.torques gives the same model's torques along the trajectory.
            traj = res.trajectory()
            t = np.linspace(0, traj.duration, 501)
            tau_t = traj.torques(t)[:, 0]
            q_t, qdd_t = traj.q(t)[:, 0], traj.qdd(t)[:, 0]
            np.testing.assert_allclose(tau_t, qdd_t + 9.81 * np.sin(q_t), atol=1e-9)
    assert errors[0] > errors[1] > errors[2] > -1e-9


def test_monotone_swing_up_is_infeasible_and_says_where(pendulum):
    # The motor adds at most 5.6·π J of work along [0, π]; lifting 1 kg by 2 m needs 19.6 J.
    prob = pp.TimeScalingProblem(bezier([0, 0, np.pi, np.pi]), grid=1000)
    prob.add_torque_limits(pendulum)
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert 0 <= res.infeasible_index <= 1000
    assert any(c.startswith("torque hinge") for c in res.binding_constraints)


def test_panda_torque_limited_optimum_matches_pinocchio_and_cvxpy_oracle():
    pytest.importorskip("pinocchio")
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    fingers = ("panda_finger_joint1", "panda_finger_joint2")
    robot = pp.RobotModel.from_urdf(urdf, locked_joints={n: 0.0 for n in fingers})
    rng = np.random.default_rng(0)
    lo, hi = robot.position_limits
    path = pp.CubicSplinePath(lo + (hi - lo) * rng.uniform(0.1, 0.9, (5, 7)))
    N = 60
    vmax = robot.velocity_limits
    prob = kinematic_problem(path, N, -vmax, vmax, None, None)
    prob.add_torque_limits(robot, scale=0.65)
    res = prob.solve()
    assert res.ok, res.message
    # The torque rows from pinocchio: independent of our dynamics.
    A, B, C = arm_rows(path, prob.grid, -vmax, vmax, np.full(7, -np.inf), np.full(7, np.inf),
                       pinocchio_model(urdf, fingers), 0.65)
    assert max_violation(res.s, res.sdot, A, B, C) <= 1e-9
    ref, _ = cvxpy_optimum(prob.grid, A, B, C)
    assert res.duration == pytest.approx(ref, rel=1e-6)
    # The torque limits bind: without them the path is faster.
    assert res.duration > kinematic_problem(path, N, -vmax, vmax, None, None).solve().duration * 1.01
