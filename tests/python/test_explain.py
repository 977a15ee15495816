"""Boundary states, restarts, and answers to "why is it infeasible?" / "what binds where?"."""

import math
import pickle
import re
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem, two_joint_problem

DATA = Path(__file__).resolve().parents[1] / "data"


def line(length=1.0):
    """q = length * s on s in [0, 1]: ṡ = q̇ / length, so limits on q map exactly to limits on s."""
    return pp.CubicSplinePath(np.array([[0.0], [length]]))


def line_problem(N, v=1.0, a=1.0, length=1.0, sdot=(0.0, 0.0)):
    prob = kinematic_problem(line(length), N, [-v], [v], [-a], [a])
    prob.set_boundary_speeds(*sdot)
    return prob


# ------------------------------------------------------------------------------------ boundary speeds
def trapezoid_time(L, V, A, v0, v1):
    """Fastest time over distance L from speed v0 to v1 with |v| <= V, |a| <= A (cruise reached)."""
    d_acc, d_dec = (V * V - v0 * v0) / (2 * A), (V * V - v1 * v1) / (2 * A)
    assert d_acc + d_dec <= L
    return (V - v0) / A + (V - v1) / A + (L - d_acc - d_dec) / V


@pytest.mark.parametrize("N", [8, 16, 40])
def test_nonzero_start_speed_gives_the_analytic_trapezoid(N):
    # v0 = 0.5: accelerate over 0.375, cruise 0.125, brake over 0.5 -- every switch on the grid of N = 8k,
    # so the piecewise-quadratic timing is the continuous optimum exactly.
    res = line_problem(N, sdot=(0.5, 0.0)).solve()
    assert res.status == pp.Status.OPTIMAL
    assert res.duration == pytest.approx(trapezoid_time(1.0, 1.0, 1.0, 0.5, 0.0), rel=1e-9)
    assert res.sdot[0] == pytest.approx(0.5, abs=1e-12) and res.sdot[-1] == 0.0
    traj = res.trajectory()
    t = np.linspace(0, res.duration, 2001)
    assert np.abs(traj.qd(t)).max() <= 1.0 + 1e-9
    assert np.abs(traj.qdd(t)).max() <= 1.0 + 1e-9


def test_nonzero_speeds_at_both_ends():
    res = line_problem(40, sdot=(0.5, 0.5)).solve()
    assert res.status == pp.Status.OPTIMAL
    assert res.duration == pytest.approx(trapezoid_time(1.0, 1.0, 1.0, 0.5, 0.5), rel=1e-9)
    assert res.sdot[-1] == pytest.approx(0.5, abs=1e-12)


@pytest.mark.parametrize("which", ["sdot_begin", "sdot_end"])
def test_boundary_speed_above_the_velocity_limit_is_named(which):
    speeds = (2.0, 0.0) if which == "sdot_begin" else (0.0, 2.0)
    res = line_problem(10, sdot=speeds).solve()
    assert res.status == pp.Status.INFEASIBLE
    assert res.infeasible_index == (0 if which == "sdot_begin" else 10)
    assert res.message.startswith(f"{which} = 2 is faster than the constraints allow at ")
    assert "(sdot <= 1)" in res.message
    assert res.binding_constraints == ["velocity joint 0"]


def test_start_too_fast_to_stop_is_infeasible_and_explained():
    # From ṡ = 1 a stop within 0.4 needs a deceleration of 1 / (2 * 0.4) = 1.25: acceleration limits x 1.25;
    # no velocity limit can help. The decelerating profile is linear in θ, so exact on any grid.
    res = pp.TimeScalingProblem(line(0.4), grid=40)
    res.add_velocity_limits([-2.0], [2.0])
    res.add_acceleration_limits([-1.0], [1.0])
    res.set_boundary_speeds(1.0 / 0.4, 0.0)  # q̇ = 0.4 ṡ = 1 at the start
    out = res.solve()
    assert out.status == pp.Status.INFEASIBLE
    r = out.relaxation
    assert set(r) == {"velocity", "acceleration", "all"}
    assert r["velocity"] == math.inf
    assert 1.25 <= r["acceleration"] <= 1.25 * (1 + 1e-3)
    assert 1.25 <= r["all"] <= 1.25 * (1 + 1e-3)
    assert "feasible with acceleration limits x 1.25" in out.message
    # The contract behind the number: scaled limits solve, slightly less do not.
    for scale, ok in [(r["acceleration"], True), (r["acceleration"] / (1 + 2e-3), False)]:
        p = pp.TimeScalingProblem(line(0.4), grid=40)
        p.add_velocity_limits([-2.0], [2.0])
        p.add_acceleration_limits([-scale], [scale])
        p.set_boundary_speeds(1.0 / 0.4, 0.0)
        assert p.solve(explain=False).ok == ok


def test_torque_relaxation_is_the_smallest_feasible_scale():
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))  # 1 kg at 1 m, |τ| <= 5.6 N m
    # Up from rest at 1.2 rad, where gravity alone needs 9.81 sin 1.2 = 9.14 N m: no swing can help.
    path = pp.CubicSplinePath(np.array([[1.2], [1.25], [1.3]]))

    def problem(scale):
        p = pp.TimeScalingProblem(path, grid=100)
        p.add_velocity_limits([-5.0], [5.0])
        p.add_torque_limits(robot, scale=scale)
        return p

    res = problem(1.0).solve()
    assert res.status == pp.Status.INFEASIBLE
    r = res.relaxation
    assert set(r) == {"velocity", "torque", "all"} and r["velocity"] == math.inf
    assert r["torque"] >= 9.81 * math.sin(1.2) / 5.6 * (1 - 1e-9)  # the start from rest
    assert problem(r["torque"]).solve(explain=False).ok
    assert not problem(r["torque"] / (1 + 2e-3)).solve(explain=False).ok
    assert "feasible with torque limits x " in res.message
    # Without explain, nothing is computed.
    assert problem(1.0).solve(explain=False).relaxation == {}


def test_torque_relaxation_beyond_the_empty_points_is_still_the_smallest():
    """Gravity empties the points near 1.3 rad below x 1.69, but braking the start speed to rest needs more:
    the scale bracketed on the empty points alone is too small, and the search must go on from it."""
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    path = pp.CubicSplinePath(np.array([[1.2], [1.25], [1.3]]))

    def problem(scale):
        p = pp.TimeScalingProblem(path, grid=100)
        p.add_velocity_limits([-50.0], [50.0])
        p.add_torque_limits(robot, scale=scale)
        p.set_boundary_speeds(25.0, 0.0)  # q̇ = 2.5 rad/s up at 1.2 rad, at rest at 1.3
        return p

    statics = 9.81 * math.sin(1.3) / 5.6
    assert not problem(statics * 1.01).solve(explain=False).ok  # the points alone would say feasible here
    res = problem(1.0).solve()
    assert res.status == pp.Status.INFEASIBLE
    r = res.relaxation["torque"]
    assert r > 1.5 * statics
    assert problem(r).solve(explain=False).ok
    assert not problem(r / (1 + 2e-3)).solve(explain=False).ok


def test_relaxation_of_a_feasible_problem_is_one_and_validates_its_arguments():
    prob = line_problem(10)
    assert prob.relaxation() == {"velocity": 1.0, "acceleration": 1.0, "all": 1.0}
    with pytest.raises(pp.InvalidInputError, match=r"^max_scale = 1 must be > 1 and finite$"):
        prob.relaxation(max_scale=1.0)
    with pytest.raises(pp.InvalidInputError, match=r"^rel_tolerance = 0 must be in \(0, 1\)$"):
        prob.relaxation(tolerance=0.0)


# ------------------------------------------------------------------------------------ binding labels
def test_binding_labels_follow_the_bang_coast_bang_phases():
    res = line_problem(8, sdot=(0.5, 0.0)).solve()
    b = res.binding
    assert len(b) == 8
    # accelerate on [0, 0.375] (intervals 0-2), cruise on [0.375, 0.5] (3), brake on [0.5, 1] (4-7); at
    # the switch intervals 2 and 4 the speed bound ties with the acceleration row.
    assert b[0] == b[1] == "acceleration joint 0 upper"
    assert b[3] == "velocity joint 0"
    assert b[5] == b[6] == b[7] == "acceleration joint 0 lower"
    assert b[2] in ("acceleration joint 0 upper", "velocity joint 0")
    assert b[4] in ("acceleration joint 0 lower", "velocity joint 0")


def test_binding_labels_name_torque_limits_on_a_swing():
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    path = pp.CubicSplinePath(np.array([[0.0], [0.25], [0.5]]))
    prob = pp.TimeScalingProblem(path, grid=100)
    prob.add_torque_limits(robot)
    res = prob.solve()
    assert res.ok and len(res.binding) == 100
    b = res.binding
    assert set(b) <= {"torque hinge upper", "torque hinge lower", ""}
    assert b[0] == "torque hinge upper" and b[-1] == "torque hinge lower"
    # Bang-bang: accelerate at the upper torque limit, brake at the lower one. Where the switch falls
    # inside an interval, neither of its rows is tight (its end speeds are set by its neighbours): that
    # interval, and only that one, has no label.
    first_lower = b.index("torque hinge lower")
    assert all(x == "torque hinge upper" for x in b[: first_lower - 1])
    assert b[first_lower - 1] in ("torque hinge upper", "")
    assert all(x == "torque hinge lower" for x in b[first_lower:])


# ------------------------------------------------------------------------------------ restarts
def test_restart_at_a_grid_point_continues_the_optimum():
    prob = two_joint_problem()
    res = prob.solve()
    traj = res.trajectory()
    k = 77
    tail = prob.restarted(res.s[k], res.sdot[k])
    assert tail.grid[0] == res.s[k] and np.array_equal(tail.grid, res.s[k:])
    assert tail.sdot_begin == res.sdot[k] and tail.sdot_end == 0.0
    out = tail.solve()
    assert out.status == pp.Status.OPTIMAL
    # Bellman: the tail of an optimum is the optimum of the tail (both certified to 1e-7).
    assert out.duration == pytest.approx(res.duration - res.times[k], rel=3e-7)
    tt = out.trajectory()
    np.testing.assert_allclose(tt.q(0.0), traj.q(res.times[k]), rtol=0, atol=1e-12)
    np.testing.assert_allclose(tt.qd(0.0), traj.qd(res.times[k]), rtol=0, atol=1e-12)


def test_restart_inside_an_interval_starts_where_the_trajectory_is():
    prob = two_joint_problem()
    res = prob.solve()
    traj = res.trajectory()
    t_r = 0.5 * (res.times[3] + res.times[4])  # accelerating from rest, far below the speed limits
    s0, sd0, _ = traj.s(t_r)
    tail = prob.restarted(s0, sd0)
    assert tail.grid[0] == s0 and tail.grid[1] == res.s[4] and tail.intervals == 200 - 3
    out = tail.solve()
    assert out.status == pp.Status.OPTIMAL
    tt = out.trajectory()
    np.testing.assert_allclose(tt.q(0.0), traj.q(t_r), rtol=0, atol=1e-12)
    np.testing.assert_allclose(tt.qd(0.0), traj.qd(t_r), rtol=0, atol=1e-12)
    # The restart may only re-time what lies ahead: not slower than the rest of the original, and not
    # faster than the original's remainder by more than the discretisation (one interval's worth).
    rest = res.duration - t_r
    assert out.duration <= rest * (1 + 1e-7)
    assert out.duration >= rest - (res.times[4] - res.times[3])


def settings_problem():
    """Every setting away from its default: boundary speeds, s̈ = 0 at both ends, joint names."""
    prob = two_joint_problem(40)
    prob.set_boundary_speeds(0.3, 0.2)
    prob.set_zero_boundary_accelerations(True, True)
    prob.set_joint_names(["shoulder", "elbow"])
    return prob


@pytest.mark.parametrize("k", [0, 17])
def test_restart_keeps_every_setting_that_pickling_keeps(k):
    # The settings are read from the pickle state itself (a dict of every ProblemSettings field), so a
    # setting added there is checked here too.
    prob = settings_problem()
    settings = prob.__getstate__()[3]
    assert set(settings) == {"sdot_begin", "sdot_end", "zero_sddot_begin", "zero_sddot_end", "joint_names"}
    tail = prob.restarted(prob.grid[k], 0.25)
    # The restart's own start: its speed, and s̈ = 0 there only when it starts where the problem starts
    # (inside the path it continues a running trajectory, whose s̈ is free).
    expected = dict(settings, sdot_begin=0.25, zero_sddot_begin=settings["zero_sddot_begin"] and k == 0)
    assert tail.__getstate__()[3] == expected
    assert tail.joint_names == ["shoulder", "elbow"] and tail.sdot_end == 0.2
    res = tail.solve()
    assert res.status == pp.Status.OPTIMAL and abs(res.sddot[-1]) <= 1e-12
    assert abs(res.sddot[0]) <= 1e-12 if k == 0 else abs(res.sddot[0]) > 1e-3
    # Pickling a restarted problem keeps its settings as well.
    assert pickle.loads(pickle.dumps(tail)).__getstate__()[3] == expected


def linear_constraint_problem(N=60):
    """two_joint_problem with, as a LinearConstraint given per grid point, |s̈| <= (1 + s) / 2 and ṡ² <= (2 - s) / 5."""
    prob = two_joint_problem(N)
    s = prob.grid
    one, zero = np.ones(N + 1), np.zeros(N + 1)
    prob.add_linear_constraint(np.c_[zero, one], np.c_[one, zero], np.c_[zero, zero], np.c_[-(1 + s) / 2, -one * np.inf],
                               np.c_[(1 + s) / 2, (2 - s) / 5], label="user")
    return prob


def test_restart_at_a_grid_point_keeps_a_linear_constraints_rows():
    prob = linear_constraint_problem()
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL and {"user[0] upper", "user[1] upper"} <= set(res.binding)
    k = 23
    tail = prob.restarted(res.s[k], res.sdot[k])
    (user,) = [c for c in tail.constraints if c.name == "user"]
    np.testing.assert_array_equal(user.__getstate__()[4][:, 0], (1 + prob.grid[k:]) / 2)  # hi: the rows of s_k..s_N
    out = tail.solve()
    assert out.status == pp.Status.OPTIMAL
    # Bellman, as for the restart without a LinearConstraint: the tail of the optimum (both certified to 1e-7).
    assert out.duration == pytest.approx(res.duration - res.times[k], rel=3e-7)
    np.testing.assert_allclose(out.sdot, res.sdot[k:], rtol=1e-6, atol=1e-9)


def test_restart_off_the_grid_with_a_linear_constraint_names_the_restart():
    prob = linear_constraint_problem()
    s0 = 0.5 * (prob.grid[10] + prob.grid[11]) + 1e-4
    with pytest.raises(pp.InvalidInputError,
                       match=r"^restarted: s0 = 0.1751 is not a grid point \(nearest: grid\[11\] = 0.183333333333\) and "
                             r"constraint 'user' is given per grid point \(no value between grid points\): restart at a grid point$"):
        prob.restarted(s0, 0.1)


def test_restart_validates_its_arguments():
    prob = two_joint_problem(10)
    with pytest.raises(pp.InvalidInputError, match=r"^s0 = 1 must be in \[s_begin, s_end\) = \[0, 1\)$"):
        prob.restarted(1.0, 0.0)
    with pytest.raises(pp.InvalidInputError, match=r"^s0 = -0.1 must be in"):
        prob.restarted(-0.1, 0.0)
    with pytest.raises(pp.InvalidInputError, match=r"^sdot0 = -1 must be >= 0 and finite$"):
        prob.restarted(0.5, -1.0)
    with pytest.raises(pp.InvalidInputError, match=r"^sdot0 = nan must be >= 0 and finite$"):
        prob.restarted(0.5, float("nan"))
    # s0 a hair before a grid point does not create a degenerate interval.
    tail = prob.restarted(0.3 - 1e-12, 0.0)
    assert tail.grid[1] == pytest.approx(0.4) and tail.intervals == 7


def test_limits_added_before_the_robot_take_its_joint_names():
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    path = pp.CubicSplinePath(np.array([[1.2], [1.25], [1.3]]))
    prob = pp.TimeScalingProblem(path, grid=50)
    prob.add_velocity_limits([-5.0], [5.0])          # before the robot: labelled by index until then
    prob.add_acceleration_limits([-1e-3], [1e-3])
    assert prob.joint_names == []
    prob.add_torque_limits(robot)
    assert prob.joint_names == ["hinge"]
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert all("joint 0" not in c for c in res.binding_constraints), res.binding_constraints
    assert any("hinge" in c for c in res.binding_constraints), res.binding_constraints
    with pytest.raises(pp.InvalidInputError, match=r"^joint_names has 2 entries, the path has 1 coordinates$"):
        prob.set_joint_names(["a", "b"])


def test_zero_boundary_acceleration_cruises_the_end_intervals():
    # Start and end at half the speed limit with s̈ = 0 on the first and last intervals: q̈ = p''ṡ² = 0
    # there (a line), so the timing cruises them at 0.5 before it accelerates.
    prob = line_problem(40, sdot=(0.5, 0.5))
    prob.set_zero_boundary_accelerations(True, True)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    assert res.sddot[0] == 0.0 and res.sddot[-1] == 0.0
    assert res.sdot[1] == pytest.approx(0.5, abs=1e-12) and res.sdot[-2] == pytest.approx(0.5, abs=1e-12)
    # Exactly the trapezoid moved in by one interval at each end: cruise 0.025 at 0.5 (0.05 s) at each end.
    assert res.duration == pytest.approx(0.1 + trapezoid_time(0.95, 1.0, 1.0, 0.5, 0.5), rel=1e-9)
    assert res.binding[0] == "sddot = 0 at s_begin" and res.binding[-1] == "sddot = 0 at s_end"
    only_begin = line_problem(40, sdot=(0.5, 0.0))
    only_begin.set_zero_boundary_accelerations(True, False)
    assert only_begin.solve().sddot[0] == 0.0
    with pytest.raises(pp.InvalidInputError, match=r"^sddot = 0 at s_end needs sdot_end > 0"):
        only_begin.set_zero_boundary_accelerations(True, True)
        only_begin.solve()
    with pytest.raises(pp.InvalidInputError, match=r"^sddot = 0 at s_begin needs sdot_begin > 0"):
        rest = line_problem(40)
        rest.set_zero_boundary_accelerations(True, False)
        rest.solve()


def test_contact_problems_explain_themselves_in_torque_and_friction():
    # The rod of sec. IV.E standing on its end, leaning to 0.15 rad at the ends, where it rests: holding it
    # needs 9.81 sin 0.15 = 1.47 N m, the motor at torque_scale 0.7 gives 1.4 N m. A torque problem that no
    # friction can fix: the relaxation says so, and its torque scale is the smallest that works.
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from test_contact import rod_path

    th = np.linspace(-0.15, 0.15, 41)
    path = rod_path(th)
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    rod = [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)]

    def problem(torque_scale):
        p = pp.TimeScalingProblem(path, grid=th)
        p.add_contacts(robot, rod, cone_edges=4, torque_scale=torque_scale)
        return p

    res = problem(0.7).solve()
    assert res.status == pp.Status.INFEASIBLE
    r = res.relaxation
    assert set(r) == {"torque", "friction", "all"}
    assert r["friction"] == math.inf
    assert r["torque"] * 1.4 >= 9.81 * math.sin(0.15) * (1 - 1e-6)
    assert problem(0.7 * r["torque"]).solve(explain=False).ok
    assert not problem(0.7 * r["torque"] / (1 + 2e-3)).solve(explain=False).ok
    assert "feasible with torque limits x " in res.message


def test_contact_polygon_edges_are_named_by_what_binds_them():
    # The rod of sec. IV.E (fig. 3): its polygons are bounded by the motor's torque (upper, lower) and by
    # the friction cone at its one contact; the edges say which, not their place in the polygon.
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from test_contact import rod_path

    th = np.linspace(-0.5, 0.5, 21)
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    prob = pp.TimeScalingProblem(rod_path(th), grid=th)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)], cone_edges=4)
    friction = "friction at link 'rod' point (0, 0, -1)"
    seen = set()
    for k in range(len(th)):
        for label in prob.feasible_set(k).labels:
            # A second edge held by the same limit says so: "... [polygon edge 2 of this limit]".
            base = re.sub(r" \[polygon edge \d+ of this limit\]$", "", label)
            assert base in {friction, "torque theta upper", "torque theta lower"}, label
            seen.add(base)
    assert seen == {friction, "torque theta upper", "torque theta lower"}
    # Leaning to 0.5 rad needs more than the motor's 2 N m: the infeasibility names the torque limit.
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE and res.binding_constraints == ["torque theta upper"]
