"""guarantee='continuous': limits that hold at every instant, not only at the grid points."""

from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem

DATA = Path(__file__).resolve().parents[1] / "data"


def kinematic(path, N, v, a, guarantee):
    return kinematic_problem(path, N, -np.asarray(v), v, -np.asarray(a), a).solve(guarantee=guarantee)


def at_1khz(res):
    tr = res.trajectory()
    t = np.arange(0.0, res.duration, 1e-3)
    return tr, np.append(t, res.duration)


def test_velocity_peak_between_grid_points():
    # q = 3s² - 2s³: p' = 6s(1 - s) peaks at 1.5 at s = 1/2, midway between the grid points 1/3 and 2/3,
    # where p' = 4/3. The grid sees 4/3 and lets |q̇| reach 1.5 / (4/3) = 1.125 times the limit there.
    path = pp.PiecewisePolynomialPath([0.0, 1.0], [[[0.0], [0.0], [3.0], [-2.0]]])
    grid, cont = (kinematic(path, 3, [1.0], [100.0], g) for g in ("grid", "continuous"))
    tr, t = at_1khz(grid)
    assert np.abs(tr.qd(t)).max() == pytest.approx(1.125, rel=1e-3)
    tr, t = at_1khz(cont)
    assert cont.status == pp.Status.OPTIMAL
    assert np.abs(tr.qd(t)).max() <= 1.0 + 1e-12
    # Not much slower than it must be: the cruise at the peak speed 1 / 1.5 is what any timing that
    # respects the limit at s = 1/2 needs there, and the bound is within a few percent of it.
    assert cont.sdot[1] <= 1 / 1.5 + 1e-12 and cont.sdot[1] >= 0.95 / 1.5


def random_spline(rng, n=3, K=6):
    return pp.CubicSplinePath(rng.uniform(-1, 1, (K, n)))


@pytest.mark.parametrize("N", [20, 100, 400])
def test_kinematic_limits_hold_at_1khz_on_random_splines(N):
    rng = np.random.default_rng(N)
    for trial in range(6):
        path = random_spline(rng)
        v, a = rng.uniform(0.5, 2.0, 3), rng.uniform(1.0, 4.0, 3)
        grid, cont = kinematic(path, N, v, a, "grid"), kinematic(path, N, v, a, "continuous")
        assert grid.status == cont.status == pp.Status.OPTIMAL
        tr, t = at_1khz(cont)
        assert (np.abs(tr.qd(t)) / v).max() <= 1 + 1e-9
        assert (np.abs(tr.qdd(t)) / a).max() <= 1 + 1e-9
        # The price in T: at least the grid optimum, and O(Δs²) more (measured worst over these paths:
        # 24 % at N = 20, whose grid optimum itself breaks the limits by several %; 0.44 % at N = 100;
        # 0.024 % at N = 400).
        assert cont.duration >= grid.duration * (1 - 1e-9)
        assert cont.duration <= grid.duration * (1 + {20: 0.3, 100: 6e-3, 400: 4e-4}[N])
        # Between grid points rows of q̈ name themselves as such when they bind.
        assert all(b == "" or b.startswith(("velocity", "acceleration")) for b in cont.binding)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_torque_limits_hold_at_1khz_after_audit_and_cuts(seed):
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))  # |τ| <= 5.6 N m
    rng = np.random.default_rng(seed)
    path = pp.CubicSplinePath(rng.uniform(-0.5, 0.5, (5, 1)))  # static hold <= 9.81 sin 0.5 = 4.7 N m
    for N in (20, 100):
        prob = pp.TimeScalingProblem(path, grid=N)
        prob.add_velocity_limits([-3.0], [3.0])
        prob.add_torque_limits(robot)
        grid, cont = prob.solve(), prob.solve(guarantee="continuous")
        assert cont.status == pp.Status.OPTIMAL, cont.message
        tr, t = at_1khz(cont)
        assert np.abs(tr.torques(t)).max() <= 5.6 * (1 + 1e-9)
        assert np.abs(tr.qd(t)).max() <= 3.0 * (1 + 1e-9)
        assert cont.stats["audit_rounds"] >= 1 and cont.stats["audit_worst"] <= 1e-9
        assert cont.duration >= grid.duration * (1 - 1e-9)


def test_grid_guarantee_breaks_torque_between_grid_points_where_continuous_does_not():
    # The contract the audit exists for: at N = 20 the grid optimum's torque overshoots between grid points.
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    path = pp.CubicSplinePath(np.array([[0.0], [0.3], [-0.2], [0.4]]))
    prob = pp.TimeScalingProblem(path, grid=20)
    prob.add_torque_limits(robot)
    grid, cont = prob.solve(), prob.solve(guarantee="continuous")
    tg, t = at_1khz(grid)
    assert np.abs(tg.torques(t)).max() > 5.6 * (1 + 1e-4)
    tc, t = at_1khz(cont)
    assert np.abs(tc.torques(t)).max() <= 5.6 * (1 + 1e-9)
    assert cont.stats["audit_cuts"] >= 1


def test_restarted_problems_keep_polynomial_pieces():
    rng = np.random.default_rng(9)
    path = random_spline(rng)
    prob = kinematic_problem(path, 60, -np.ones(3), np.ones(3), -2 * np.ones(3), 2 * np.ones(3))
    tail = prob.restarted(0.4321, 0.0)
    assert isinstance(tail.path, pp.PiecewisePolynomialPath)
    s = np.linspace(0.4321, 1.0, 50)
    for f in ("q", "dq", "ddq"):
        np.testing.assert_allclose(getattr(tail.path, f)(s), getattr(path, f)(s), rtol=0, atol=1e-12)
    res = tail.solve(guarantee="continuous")
    assert res.status == pp.Status.OPTIMAL


def test_continuous_validation_messages():
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    prob = pp.TimeScalingProblem(path, grid=10)
    prob.add_velocity_limits([-1.0], [1.0])
    with pytest.raises(pp.InvalidInputError, match=r"^guarantee = 'everywhere' must be one of 'grid', 'continuous'$"):
        prob.solve(guarantee="everywhere")
    with pytest.raises(pp.InvalidInputError, match=r"^audit_points = 0 must be in \[1, 1000\]$"):
        prob.solve(guarantee="continuous", audit_points=0)
    with pytest.raises(pp.InvalidInputError, match=r"^audit_tolerance = -1 must be in \[0, 1\)$"):
        prob.solve(guarantee="continuous", audit_tolerance=-1.0)
    with pytest.raises(pp.InvalidInputError, match=r"^max_audit_rounds = 0 must be >= 1$"):
        prob.solve(guarantee="continuous", max_audit_rounds=0)


def test_circle_at_the_speed_limit_converges_to_the_analytic_time_from_above():
    # q = (cos x, sin x), x = 0.3 + 2πs: with |q̇_j| <= v only, the fastest traversal keeps the faster
    # joint at v: T* = ∫ max_j |p'_j| / v ds = 4√2 / v over the full circle. Continuous-time feasible
    # timings are never faster; the grid's are (they break the limit between grid points).
    v = 1.0
    s = np.linspace(0, 1, 129)
    x = 0.3 + 2 * np.pi * s
    q = np.stack([np.cos(x), np.sin(x)], 1)
    dq = 2 * np.pi * np.stack([-np.sin(x), np.cos(x)], 1)
    path = pp.SampledPath(s, q, dq, -(2 * np.pi) ** 2 * q)  # quintic Hermite: the circle to ~1e-9
    sd = [0.99 * v / np.abs(path.dq(np.array([e]))).max() for e in (0.0, 1.0)]  # start and end just below
    T_star = 4 * np.sqrt(2) / v
    for N, slack in [(100, 1.5e-3), (400, 1.5e-4)]:
        res = {}
        for g in ("grid", "continuous"):
            prob = pp.TimeScalingProblem(path, grid=N)
            prob.add_velocity_limits([-v, -v], [v, v])
            prob.set_boundary_speeds(*sd)
            res[g] = prob.solve(guarantee=g)
            assert res[g].status == pp.Status.OPTIMAL
        cont = res["continuous"]
        assert T_star * (1 - 1e-9) <= cont.duration <= T_star * (1 + slack)
        tr, t = at_1khz(cont)
        assert np.abs(tr.qd(t)).max() <= v * (1 + 1e-9)
        tr, t = at_1khz(res["grid"])
        assert np.abs(tr.qd(t)).max() > v * (1 + 1e-4)


def swaying_rod(amplitude):
    """The rod of test_contact.py (sec. IV.E) rocking on its lower end: lean θ(s) = A sin 2πs, s in [0, 1]."""
    w = 2 * np.pi

    def lean(s):
        return amplitude * np.sin(w * s), amplitude * w * np.cos(w * s), -amplitude * w * w * np.sin(w * s)

    s = np.linspace(0.0, 1.0, 81)
    t, t1, t2 = lean(s)
    q = np.column_stack([-np.sin(t), np.cos(t), -t])
    dq = np.column_stack([-np.cos(t) * t1, -np.sin(t) * t1, -t1])
    ddq = np.column_stack([np.sin(t) * t1**2 - np.cos(t) * t2, -np.cos(t) * t1**2 - np.sin(t) * t2, -t2])
    return pp.SampledPath(s, q, dq, ddq), lean


def rod_excess(res, lean):
    """Largest relative excess over the rod's analytic contact and torque rows (eq. 21-23, test_contact.py),
    at 1 kHz on the returned trajectory: an oracle that shares nothing with the projection or the audit."""
    from test_contact import analytic_rows

    t = np.append(np.arange(0.0, res.duration, 1e-3), res.duration)
    s, sd, sdd = res.trajectory().s(t)
    worst = -np.inf
    for si, x, u in zip(s, sd**2, sdd):
        th, th1, th2 = lean(si)
        R = analytic_rows(th)  # in (θ̇², θ̈) = (θ'² ṡ², θ'' ṡ² + θ' s̈)
        a, b, c = R[:, 0] * th1**2 + R[:, 1] * th2, R[:, 1] * th1, R[:, 2]
        scale = np.maximum(np.abs(c), np.abs(a * x) + np.abs(b * u))
        ok = scale > 0
        worst = max(worst, float(np.max((a * x + b * u - c)[ok] / scale[ok])))
    return worst


@pytest.mark.parametrize("amplitude, N", [(0.15, 4), (0.18, 6), (0.18, 10)])
def test_contact_limits_hold_between_grid_points_of_a_coarse_grid(amplitude, N):
    # The grid optimum asks for forces that do not exist between grid points (24-78 % beyond a row of eq.
    # 21-23); the continuous audit must find every such interval, whatever screening it does before
    # searching one: few samples per interval (audit_points = 2) are its hardest case.
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    path, lean = swaying_rod(amplitude)
    prob = pp.TimeScalingProblem(path, grid=N)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)], cone_edges=4)
    grid = prob.solve()
    assert rod_excess(grid, lean) > 0.1
    for points in (1, 2, 8):
        cont = prob.solve(guarantee="continuous", audit_points=points)
        assert cont.status == pp.Status.OPTIMAL, cont.message
        assert cont.stats["audit_cuts"] >= 1
        assert cont.duration >= grid.duration * (1 - 1e-9)
        # The polygons are exact to 1e-9 of their size (sec. IV.C), which is up to 1e-8 of a row's own terms
        # where they are small; measured worst over these cases: -1.2e-8.
        assert rod_excess(cont, lean) <= 1e-7
        t = np.append(np.arange(0.0, cont.duration, 1e-3), cont.duration)
        assert np.min(cont.trajectory().contact_forces(t).margin) >= -1e-6
        # The audit asks the contact constraint only for the slices at the timing's own s̈ (at most two LPs
        # per sample) and cuts along the polygon's edge at a slice's end; it projects a polygon only where a
        # cut point's slice is empty (at most one point per interval and round).
        assert cont.stats["audit_lps"] > 0
        assert 0 <= cont.stats["audit_projections"] <= cont.stats["audit_rounds"] * N
        # Later rounds settle samples from the slices' edges kept from earlier rounds (no LP).
        assert cont.stats["audit_reused"] > 0


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_screen_does_not_depend_on_rounding(seed):
    # The coarse rod at 2 samples per interval once let a 1.3e-7 excess through after a rounding-level
    # change of its polygons (the screen's curvature came from each interval's own neighbouring samples,
    # which rounding left on a line). Grids moved by 1e-13 are such changes; the path-wide curvature of
    # the screen (docs/method.md, "What the screen assumes") must hold the contract on every one.
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    path, lean = swaying_rod(0.18)
    rng = np.random.default_rng(seed)
    grid = np.linspace(0.0, 1.0, 11)
    grid[1:-1] += rng.uniform(-1e-13, 1e-13, 9)
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)], cone_edges=4)
    for points in (1, 2):
        cont = prob.solve(guarantee="continuous", audit_points=points)
        assert cont.status == pp.Status.OPTIMAL, cont.message
        assert rod_excess(cont, lean) <= 1e-7
