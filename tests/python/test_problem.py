"""Contracts of the time-scaling engine: analytic optima, oracles, scaling laws, validation."""

import math

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
from oracles import cvxpy_optimum, kinematic_rows, max_violation


def random_spline(seed, K=5, n=3, scale=1.0):
    rng = np.random.default_rng(seed)
    return pp.CubicSplinePath(scale * rng.uniform(-1, 1, (K, n)))


def limits(n, seed):
    rng = np.random.default_rng(1000 + seed)
    vmax = rng.uniform(0.5, 2.0, n)
    vmin = -rng.uniform(0.5, 2.0, n)
    amax = rng.uniform(1.0, 4.0, n)
    amin = -rng.uniform(1.0, 4.0, n)
    return vmin, vmax, amin, amax


def rows_for(prob, vmin, vmax, amin, amax):
    s = prob.grid
    return kinematic_rows(prob.path.dq(s), prob.path.ddq(s), vmin, vmax, amin, amax)


# ---------------------------------------------------------------------------------------- analytic optima
def test_line_bang_coast_bang_approaches_four_seconds():
    path = pp.CubicSplinePath(np.array([[0.0], [3.0]]))  # two waypoints: the straight line q = 3s
    errors = []
    for N in (64, 256, 1024):
        res = kinematic_problem(path, N, [-1], [1], [-1], [1]).solve()
        assert res.status == pp.Status.OPTIMAL, res.message
        assert res.duration >= 4.0 - 1e-12  # the discrete optimum can only be slower
        errors.append(res.duration - 4.0)
    assert errors[-1] < 1e-4
    assert errors[0] > errors[1] > errors[2]


@pytest.mark.parametrize("seed", range(4))
def test_velocity_only_matches_integral_of_inverse_speed(seed):
    path = random_spline(seed)
    vmin, vmax, _, _ = limits(3, seed)

    def sdot_max(s):
        d = path.dq(np.atleast_1d(s))
        with np.errstate(divide="ignore"):
            r = np.where(d > 0, vmax / d, np.where(d < 0, vmin / d, np.inf))
        return r.min(axis=1)

    # 1/ṡ_max has kinks where the binding joint changes; the trapezoid rule on 4e5 intervals is accurate
    # to ~1e-11 there as well (its error is O(h²) across a kink too).
    fine = np.linspace(0.0, 1.0, 400001)
    exact = np.trapezoid(1.0 / sdot_max(fine), fine)
    durations = []
    for N in (500, 2000):
        prob = pp.TimeScalingProblem(path, grid=N)
        prob.add_velocity_limits(vmin, vmax)
        # Start and end at the limit speed so that the only difference is the quadrature of 1/ṡ.
        prob.set_boundary_speeds(sdot_max(0.0)[0], sdot_max(1.0)[0])
        res = prob.solve()
        assert res.status == pp.Status.OPTIMAL, res.message
        durations.append(res.duration)
    assert abs(durations[1] - exact) / exact < 1e-4
    assert abs(durations[1] - exact) < abs(durations[0] - exact)


@pytest.mark.parametrize("k", [0.5, 3.0])
@pytest.mark.parametrize("method", ["auto", "slp"])
def test_scaling_law_velocity_k_acceleration_k2_gives_T_over_k(k, method):
    path = random_spline(7)
    vmin, vmax, amin, amax = limits(3, 7)
    base = kinematic_problem(path, 200, vmin, vmax, amin, amax).solve(method=method)
    scaled = kinematic_problem(path, 200, k * vmin, k * vmax, k * k * amin, k * k * amax).solve(method=method)
    assert base.ok and scaled.ok
    assert scaled.duration == pytest.approx(base.duration / k, rel=1e-9)


@pytest.mark.parametrize("seed", range(3))
def test_time_reversed_twin_has_same_duration(seed):
    rng = np.random.default_rng(seed)
    wp = rng.uniform(-1, 1, (6, 2))
    fwd = pp.CubicSplinePath(wp)
    rev = pp.CubicSplinePath(wp[::-1].copy())
    vmin, vmax, amin, amax = limits(2, seed)
    a = kinematic_problem(fwd, 300, vmin, vmax, amin, amax).solve()
    # Reversed in time, velocities change sign (limits swap) and accelerations keep theirs.
    b = kinematic_problem(rev, 300, -vmax, -vmin, amin, amax).solve()
    assert a.ok and b.ok
    # Both are certified within their gaps of the same optimum; exact solutions must coincide.
    gap = a.stats["gap"] + b.stats["gap"]
    assert b.duration == pytest.approx(a.duration, rel=gap + 1e-9)
    if gap == 0.0:
        np.testing.assert_allclose(b.sdot[::-1], a.sdot, rtol=1e-7, atol=1e-9 * a.sdot.max())


# ---------------------------------------------------------------------------------------- feasibility
@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("method", ["auto", "slp"])
def test_output_satisfies_every_constraint_at_every_grid_point(seed, method):
    path = random_spline(seed, K=4 + seed, n=1 + seed % 4)
    vmin, vmax, amin, amax = limits(path.dof, seed)
    prob = kinematic_problem(path, 150, vmin, vmax, amin, amax)
    res = prob.solve(method=method)
    assert res.ok, res.message
    A, B, C = rows_for(prob, vmin, vmax, amin, amax)
    assert max_violation(res.s, res.sdot, A, B, C) <= 1e-9


# ---------------------------------------------------------------------------------------- oracle
def monotone_path(n, seed):
    """Every joint moves one way with |p''/p'| < 6: for N <= 60 no row couples θ_k and θ_{k+1} positively
    (that needs p''_j > p'_j / (2Δs)), so the feasible set is max-closed."""
    rng = np.random.default_rng(seed)
    s = np.linspace(0, 1, 7)
    scale = rng.uniform(0.5, 2.0, n) * rng.choice([-1.0, 1.0], n)
    return pp.CubicSplinePath(np.outer(s + 0.15 * np.sin(np.pi * s), scale))


@pytest.mark.parametrize("seed", range(3))
def test_shortcut_and_slp_match_cvxpy_clarabel_on_lattice_instances(seed):
    path = monotone_path(2, seed)
    vmin, vmax, amin, amax = limits(2, seed)
    prob = kinematic_problem(path, 60, vmin, vmax, amin, amax)
    ref, _ = cvxpy_optimum(prob.grid, *rows_for(prob, vmin, vmax, amin, amax))
    fast = prob.solve()
    slow = prob.solve(method="slp")
    assert fast.stats["greatest_element"] and fast.stats["lp_solves"] == 0
    assert slow.stats["lp_solves"] > 0
    assert fast.duration == pytest.approx(ref, rel=1e-6)
    assert slow.duration == pytest.approx(ref, rel=1e-6)


def coupled_instance(seed, N=60):
    """Velocity and acceleration limits plus rows w_k·ṡ² + s̈ <= h_k with random w_k up to 3N: after eq.
    (26)'s substitution both coefficients are positive where w_k > N/2, the feasible set is not closed
    under max, and the greedy profile is not the optimum."""
    rng = np.random.default_rng(seed)
    path = pp.CubicSplinePath(rng.uniform(-1, 1, (5, 2)))
    vmin, vmax, amin, amax = -np.ones(2), np.full(2, 1.5), np.full(2, -2.0), np.full(2, 3.0)
    m = N + 1
    w = rng.uniform(0, 3 * N, m)
    h = rng.uniform(0.5, 1.5, m) * 0.3 * N
    prob = kinematic_problem(path, N, vmin, vmax, amin, amax)
    plain = prob.solve()
    prob.add_linear_constraint(w, np.ones(m), np.zeros(m), np.full(m, -np.inf), h, label="coupling")
    A, B, C = rows_for(prob, vmin, vmax, amin, amax)
    A = np.hstack([A, w[:, None]])
    B = np.hstack([B, np.ones((m, 1))])
    C = np.hstack([C, h[:, None]])
    return prob, plain, (A, B, C)


@pytest.mark.parametrize("seed", range(4))
def test_slp_matches_cvxpy_clarabel_where_the_shortcut_does_not_apply(seed):
    prob, plain, (A, B, C) = coupled_instance(seed)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL, res.message
    assert not res.stats["greatest_element"]
    assert res.stats["lp_solves"] > 0
    assert res.stats["gap"] <= 1e-7
    ref, _ = cvxpy_optimum(prob.grid, A, B, C)
    assert res.duration == pytest.approx(ref, rel=1e-6)
    assert max_violation(res.s, res.sdot, A, B, C) <= 1e-9
    # The coupling rows bind, otherwise this instance would test nothing new.
    assert res.duration > plain.duration * (1 + 1e-4)


# ---------------------------------------------------------------------------------------- outputs
def test_trajectory_reproduces_grid_and_derivatives():
    path = random_spline(3)
    vmin, vmax, amin, amax = limits(3, 3)
    res = kinematic_problem(path, 100, vmin, vmax, amin, amax).solve()
    traj = res.trajectory()
    assert traj.duration == pytest.approx(res.duration, rel=1e-14)
    np.testing.assert_allclose(traj.q(res.times), path.q(res.s), atol=1e-12)
    np.testing.assert_allclose(traj.qd(res.times), path.dq(res.s) * res.sdot[:, None], atol=1e-12)
    # Inside an interval, q̈ = p''ṡ² + p's̈ with the interval's constant s̈ (eq. 11, 24).
    tm = 0.5 * (res.times[:-1] + res.times[1:])
    s, sd, sdd = traj.s(tm)
    np.testing.assert_allclose(sdd, res.sddot, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(traj.qdd(tm), path.ddq(s) * sd[:, None] ** 2 + path.dq(s) * sdd[:, None], atol=1e-12)
    smp = traj.sample(0.01)
    assert smp["t"][0] == 0.0 and smp["t"][-1] == pytest.approx(res.duration)
    assert smp["q"].shape == (len(smp["t"]), 3)
    assert traj.q(0.0).shape == (3,)


def test_feasible_set_is_inspectable_and_pruned():
    path = random_spline(1, n=7)
    vmin, vmax, amin, amax = limits(7, 1)
    prob = kinematic_problem(path, 50, vmin, vmax, amin, amax)
    fs = prob.feasible_set(10)
    assert fs.halfplanes.shape[1] == 3
    assert 1 <= fs.halfplanes.shape[0] < 14  # 14 acceleration rows, most of them redundant
    assert len(fs.labels) == fs.halfplanes.shape[0]
    assert fs.bounded and not fs.empty
    # Each pruned-away row is implied: every vertex satisfies all original rows.
    A, B, C = rows_for(prob, vmin, vmax, amin, amax)
    for x, u in fs.vertices:
        assert np.all(A[10] * x + B[10] * u <= C[10] + 1e-9 * np.maximum(1, np.abs(C[10])))
    # ... and every kept half-plane supports an edge (two vertices lie on it).
    for a, b, c in fs.halfplanes:
        on = np.abs(fs.vertices @ np.array([a, b]) - c) <= 1e-9 * max(1.0, abs(c))
        assert on.sum() >= 2


def test_non_uniform_grid():
    path = random_spline(5)
    vmin, vmax, amin, amax = limits(3, 5)
    grid = np.sort(np.concatenate([[0.0, 1.0], np.random.default_rng(0).uniform(0, 1, 200)]))
    res = kinematic_problem(path, grid, vmin, vmax, amin, amax).solve()
    assert res.ok
    np.testing.assert_array_equal(res.s, grid)
    A, B, C = kinematic_rows(path.dq(grid), path.ddq(grid), vmin, vmax, amin, amax)
    assert max_violation(res.s, res.sdot, A, B, C) <= 1e-9


# ---------------------------------------------------------------------------------------- infeasible
def test_infeasible_reports_index_s_and_binding_rows():
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    N = 20
    prob = pp.TimeScalingProblem(path, grid=N)
    prob.add_velocity_limits([-1], [1])
    m = N + 1
    # s̈ >= 1 everywhere: impossible to come to rest at the end.
    prob.add_linear_constraint(np.zeros(m), np.ones(m), np.zeros(m), np.ones(m), np.full(m, np.inf), label="push")
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert not res.ok
    assert 0 <= res.infeasible_index <= N
    assert res.infeasible_s == pytest.approx(res.infeasible_index / N)
    assert any("push" in c for c in res.binding_constraints)
    assert "grid index" in res.message
    with pytest.raises(pp.Error, match="infeasible"):
        res.trajectory()


def test_unbounded_when_nothing_limits_speed():
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    prob = pp.TimeScalingProblem(path, grid=10)
    prob.add_acceleration_limits([-np.inf], [np.inf])
    assert prob.solve().status == pp.Status.UNBOUNDED


# ---------------------------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "call, message",
    [
        (lambda p: p.add_velocity_limits([-1, -1, -1], [1, 1, np.nan]), r"vmax\[2\] = nan must be a number"),
        (lambda p: p.add_velocity_limits([-1, -1, -1], [1, 1, -2]), r"vmax\[2\] = -2 must be >= 0"),
        (lambda p: p.add_velocity_limits([-1, 0.5, -1], [1, 1, 1]), r"vmin\[1\] = 0.5 must be <= 0"),
        (lambda p: p.add_velocity_limits([-1, -1], [1, 1, 1]), r"vmin has size 2, expected 3"),
        (lambda p: p.add_velocity_limits([-1, -1], [1, 1]), r"velocity limits have 2 entries, the path has 3"),
        (lambda p: p.add_velocity_limits([[-1, -1, -1]], [1, 1, 1]), r"vmin has shape \(1, 3\), expected a 1-D array"),
        (lambda p: p.add_acceleration_limits([-1, 2, -1], [1, 1, 1]), r"amin\[1\] = 2 must be <= amax\[1\] = 1"),
        (lambda p: p.add_acceleration_limits([-1, -1, -1], [1, -np.inf, 1]), r"amax\[1\] = -inf must be > -inf"),
        (lambda p: p.add_acceleration_limits("abc", [1, 1, 1]), r"amin must be an array of numbers"),
        (lambda p: p.add_linear_constraint(np.zeros(11), np.zeros(11), np.zeros(11), np.zeros(11), np.ones(10)),
         r"hi has shape \(10, 1\), expected \(11, 1\)"),
        (lambda p: p.add_linear_constraint(np.zeros(9), np.zeros(9), np.zeros(9), np.zeros(9), np.ones(9)),
         r"A has 9 rows, expected one per grid point \(11\)"),
        (lambda p: p.add_linear_constraint(np.zeros(11), np.full(11, np.inf), np.zeros(11), np.zeros(11), np.ones(11)),
         r"B\[0\] = inf must be finite"),
        (lambda p: p.add_linear_constraint(np.zeros(11), np.zeros(11), np.zeros(11), np.ones(11), np.zeros(11)),
         r"lo\[0, 0\] = 1 must be <= hi\[0, 0\] = 0"),
        (lambda p: p.set_boundary_speeds(-1.0, 0.0), r"sdot_begin = -1 must be >= 0 and finite"),
        (lambda p: p.set_boundary_speeds(0.0, np.inf), r"sdot_end = inf must be >= 0 and finite"),
        (lambda p: p.feasible_set(11), r"k = 11 must be in \[0, 10\]"),
        (lambda p: p.solve(method="fast"), r"method = 'fast' must be one of 'auto', 'slp'"),
        (lambda p: p.solve(max_iterations=-1), r"max_iterations = -1 must be >= 0"),
    ],
)
def test_bad_input_names_the_argument(call, message):
    prob = pp.TimeScalingProblem(random_spline(0), grid=10)
    with pytest.raises(pp.InvalidInputError, match=message):
        call(prob)


@pytest.mark.parametrize(
    "grid, message",
    [
        (0, r"grid = 0 must be in \[1, 1e8\]"),
        (np.array([0.0, 0.5, 0.5, 1.0]), r"grid\[2\] = 0.5 must be > grid\[1\] = 0.5 \(strictly increasing\)"),
        (np.array([0.0, np.nan, 1.0]), r"grid\[1\] = nan must be finite"),
        (np.array([0.1, 1.0]), r"grid\[0\] = 0.1 must equal the path's s_begin = 0"),
        (np.array([0.0, 0.9]), r"grid\[1\] = 0.9 must equal the path's s_end = 1"),
        (np.array([0.0]), r"grid has 1 points, expected at least 2"),
        (2.5, r"grid must be an int"),
    ],
)
def test_bad_grid(grid, message):
    with pytest.raises(pp.InvalidInputError, match=message):
        pp.TimeScalingProblem(random_spline(0), grid=grid)


def test_invalid_input_error_is_a_value_error():
    assert issubclass(pp.InvalidInputError, ValueError)
    assert issubclass(pp.InvalidInputError, pp.Error)


def test_zero_velocity_limit_on_a_moving_joint_is_named():
    path = random_spline(2)
    prob = pp.TimeScalingProblem(path, grid=50)
    prob.add_velocity_limits([-1, 0, -1], [1, 0, 1])
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert res.binding_constraints == ["velocity joint 1"]
    assert res.infeasible_index == 1
