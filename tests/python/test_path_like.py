"""Bring your own path (issue 22): pathpace paths are callable as toppra's (``path(s, order)``), and
``pp.as_path`` / ``TimeScalingProblem`` take scipy splines (exactly, through their coefficients), toppra
interpolators and plain vectorised callables. Each kind is checked against the same path built by hand as a
pathpace path, and each kind composes with pickling, solve_many, restart, contacts and the automatic grid."""

import pickle
from pathlib import Path

import numpy as np
import pytest
import scipy.interpolate as si

import pathpace as pp
from pathpace.paths import CallbackPath, InterpolatorPath

from helpers import process_pool

DATA = Path(__file__).resolve().parents[1] / "data"
V, A = np.array([1.0, 1.5, 2.0]), np.array([2.0, 3.0, 4.0])

# Module level, so that the callback paths built on them pickle (and a ProcessPoolExecutor can run them).
KNOTS = np.array([0.0, 0.15, 0.45, 0.6, 1.0])
WAYPOINTS = np.random.default_rng(22).uniform(-1.0, 1.0, (5, 3))
SPLINE = pp.CubicSplinePath(WAYPOINTS, knots=KNOTS)


def spline_values(s):
    """The pathpace spline as a plain callable (q, q', q'') of an array of s."""
    return SPLINE.evaluate(s)


class ToppraLike:
    """An object with toppra's interpolator interface (and nothing else) around the spline."""

    path_interval = np.array([0.0, 1.0])

    def __call__(self, s, order=0):
        return SPLINE(s, order)


class Counting:
    """spline_values, counting its calls and the values of s it saw."""

    def __init__(self):
        self.calls, self.values = 0, 0

    def __call__(self, s):
        self.calls += 1
        self.values += len(s)
        return SPLINE.evaluate(s)


def solve_T(path, grid=200, **solve_kw):
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(-V, V)
    prob.add_acceleration_limits(-A, A)
    res = prob.solve(**solve_kw)
    assert res.ok, res.message
    return res.duration


def close(a, b, rtol=1e-12):
    return abs(a - b) <= rtol * abs(b)


class UserPath(pp.Path):
    """A user's own Python subclass of pathpace.Path: q = (sin s, s²) on [0, 2]."""

    dof = 2
    s_begin = 0.0
    s_end = 2.0

    def evaluate(self, s):
        z = np.zeros_like(s)
        return (np.column_stack([np.sin(s), s * s]), np.column_stack([np.cos(s), 2 * s]),
                np.column_stack([-np.sin(s), 2 + z]))


def rod_arc(th):
    """test_contact.py's rod, its lower end on the origin: q = (x, z, angle) = (-sin θ, cos θ, -θ), s = θ."""
    q = np.column_stack([-np.sin(th), np.cos(th), -th])
    dq = np.column_stack([-np.cos(th), -np.sin(th), -np.ones_like(th)])
    ddq = np.column_stack([np.sin(th), -np.cos(th), np.zeros_like(th)])
    return q, dq, ddq


def every_path_kind():
    s = np.linspace(0.0, 1.0, 7)
    bp = np.array([0.0, 0.5, 1.0])
    coef = np.random.default_rng(1).normal(size=(2, 4, 2))
    return {
        "CubicSplinePath": SPLINE,
        "PiecewisePolynomialPath": pp.PiecewisePolynomialPath(bp, coef),
        "SampledPath": pp.SampledPath(s, SPLINE.q(s), SPLINE.dq(s), SPLINE.ddq(s)),
        "CallbackPath": CallbackPath(spline_values),
        "InterpolatorPath": InterpolatorPath(ToppraLike()),
        "UserPath": UserPath(),
    }


# -- path(s, order) ---------------------------------------------------------------------------------------


@pytest.mark.parametrize("kind", list(every_path_kind()))
def test_call_with_order_is_evaluate(kind):
    path = every_path_kind()[kind]
    s = np.linspace(path.s_begin, path.s_end, 11)
    ref = path.q(s), path.dq(s), path.ddq(s)
    for order in range(3):
        got = path(s, order)
        assert got.shape == (11, path.dof)
        np.testing.assert_array_equal(got, ref[order])
        one = path(float(s[3]), order=order)
        assert one.shape == (path.dof,)
        np.testing.assert_array_equal(one, ref[order][3])
    np.testing.assert_array_equal(path(s), ref[0])  # order defaults to 0


@pytest.mark.parametrize("order, error, match", [
    (3, pp.InvalidInputError, r"order = 3 must be in \[0, 2\]"),
    (-1, pp.InvalidInputError, r"order = -1 must be in \[0, 2\]"),
    (1.0, TypeError, r"order must be an int, got float"),
    (None, TypeError, r"order must be an int, got None"),
])
def test_call_refuses_an_order_outside_0_to_2(order, error, match):
    for path in (SPLINE, CallbackPath(spline_values)):
        with pytest.raises(error, match=match):
            path(0.5, order)


def test_a_user_subclass_of_path_solves_like_the_same_path_sampled():
    user = UserPath()
    s = np.linspace(0.0, 2.0, 41)
    sampled = pp.SampledPath(s, *user.evaluate(s))
    for order in range(3):  # the same values at the samples (the quintic pieces to rounding)
        np.testing.assert_allclose(sampled(s, order), user(s, order), rtol=0, atol=1e-12)

    def T(path):
        prob = pp.TimeScalingProblem(path, grid=s)
        prob.add_velocity_limits([-1, -1], [1, 1])
        prob.add_acceleration_limits([-2, -2], [2, 2])
        return prob.solve().duration

    assert close(T(user), T(sampled))


def test_a_user_subclass_must_define_what_path_leaves_abstract():
    class NoEvaluate(pp.Path):
        dof, s_begin, s_end = 1, 0.0, 1.0

    class NoDof(pp.Path):
        s_begin, s_end = 0.0, 1.0

        def evaluate(self, s):
            return s[:, None], s[:, None], s[:, None]

    with pytest.raises(pp.Error, match=r"must define evaluate\(s\)"):
        NoEvaluate()(0.5)
    with pytest.raises(pp.Error, match=r"must define dof"):
        NoDof()(0.5)


# -- scipy: exact through the coefficients -------------------------------------------------------------


@pytest.mark.parametrize("bc", ["not-a-knot", "natural", "clamped"])
def test_scipy_cubic_spline_is_its_coefficients(bc):
    cs = si.CubicSpline(KNOTS, WAYPOINTS, bc_type=bc)
    path = pp.as_path(cs)
    assert type(path) is pp.PiecewisePolynomialPath and path.dof == 3
    np.testing.assert_array_equal(path.breakpoints, KNOTS)
    # Bit-identical to the same pieces written by hand, lowest degree first.
    by_hand = pp.PiecewisePolynomialPath(KNOTS, np.ascontiguousarray(cs.c[::-1].transpose(1, 0, 2)))
    np.testing.assert_array_equal(path.__getstate__()[1], by_hand.__getstate__()[1])
    assert solve_T(path) == solve_T(by_hand)
    # pathpace's own spline of the same waypoints, knots and ends: the same path up to rounding.
    ours = pp.CubicSplinePath(WAYPOINTS, knots=KNOTS, boundary=bc)
    s = np.linspace(0, 1, 301)
    for order in range(3):
        scale = np.abs(ours(s, order)).max()
        np.testing.assert_allclose(path(s, order), cs(s, order), rtol=0, atol=1e-14 * scale)
        np.testing.assert_allclose(path(s, order), ours(s, order), rtol=0, atol=1e-12 * scale)
    assert close(solve_T(cs), solve_T(ours))


def test_scipy_ppoly_of_any_degree_and_scalar_values():
    rng = np.random.default_rng(5)
    x = np.cumsum(rng.uniform(0.1, 0.5, 6))
    c = rng.normal(size=(6, 5))  # degree 5, 5 pieces, one coordinate (c of shape (k, m))
    poly = si.PPoly(c, x)
    path = pp.as_path(poly)
    assert path.dof == 1 and path.s_begin == x[0] and path.s_end == x[-1]
    s = np.linspace(x[0], x[-1], 199)
    for order in range(3):
        ref = poly.derivative(order)(s) if order else poly(s)
        np.testing.assert_allclose(path(s, order)[:, 0], ref, rtol=0, atol=1e-12 * np.abs(ref).max())


def test_scipy_bspline_vector_valued_is_the_interpolating_spline():
    b = si.make_interp_spline(KNOTS, WAYPOINTS, k=3)  # not-a-knot interpolation, as CubicSplinePath's default
    path = pp.as_path(b)
    s = np.linspace(0, 1, 301)
    for order in range(3):
        ref = b(s, nu=order)
        np.testing.assert_allclose(path(s, order), ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    np.testing.assert_array_equal(path.breakpoints, [0.0, 0.45, 1.0])  # not-a-knot: no knots at 0.15, 0.6
    assert close(solve_T(b), solve_T(SPLINE))


def test_scipy_bspline_with_repeated_knots_and_low_degree():
    # A quadratic spline with a double interior knot (its derivative jumps there): zero-width knot intervals
    # carry no piece.
    t = np.array([0, 0, 0, 0.4, 0.4, 1, 1, 1], dtype=float)
    c = np.random.default_rng(3).normal(size=(5, 2))
    b = si.BSpline(t, c, 2)
    path = pp.as_path(b)
    np.testing.assert_array_equal(path.breakpoints, [0.0, 0.4, 1.0])
    s = np.linspace(0, 1, 101)
    for order in range(3):
        np.testing.assert_allclose(path(s, order), b(s, nu=order), rtol=0, atol=1e-12)


# -- toppra ----------------------------------------------------------------------------------------------


def test_toppra_spline_interpolator_is_its_cubic_spline():
    ta = pytest.importorskip("toppra")
    ss = np.linspace(0, 1, WAYPOINTS.shape[0])
    theirs = ta.SplineInterpolator(ss, WAYPOINTS)
    path = pp.as_path(theirs)
    assert type(path) is pp.PiecewisePolynomialPath
    s = np.linspace(0, 1, 201)
    for order in range(3):
        np.testing.assert_allclose(path(s, order), theirs(s, order), rtol=0, atol=1e-12 * np.abs(theirs(s, order)).max())


def test_a_toppra_style_object_is_called_once_per_order_and_batch():
    class Interp:
        path_interval = np.array([0.0, 1.0])
        calls = 0

        def __call__(self, s, order=0):
            Interp.calls += 1
            return SPLINE(s, order)

    path = pp.as_path(Interp())
    assert isinstance(path, InterpolatorPath) and path.dof == 3
    Interp.calls = 0
    pp.TimeScalingProblem(path, grid=500)
    assert Interp.calls == 3  # the grid: one batch, orders 0, 1, 2
    assert solve_T(path) == solve_T(SPLINE)


def test_a_toppra_users_script_gives_toppras_duration():
    """toppra's TOPPRA and pathpace on the same SplineInterpolator, limits and grid. Both solve the same
    discretisation (toppra's default JointAccelerationConstraint scheme, Interpolation, is eq. 26's rows on
    both sides of each grid point); pathpace's T is that discretisation's optimum, toppra's is slightly above
    it (it lowers each forward step's ṡ² by 1e-8, bench/README.md, and its LPs have their own tolerances).
    So: pathpace's T at most toppra's (to rounding), and within 1e-4 relative at N = 100 (measured here
    -6.1e-5; -2.9e-6 at N = 1000; bench/README.md's corpus -1.4e-5 at N = 100)."""
    ta = pytest.importorskip("toppra")
    import toppra.algorithm as algo
    import toppra.constraint as constraint

    rng = np.random.default_rng(2022)
    way_pts = rng.uniform(-1, 1, (6, 3))
    ss = np.linspace(0, 1, 6)
    grid = np.linspace(0, 1, 101)
    vlim, alim = np.column_stack([-V, V]), np.column_stack([-A, A])
    path = ta.SplineInterpolator(ss, way_pts)

    inst = algo.TOPPRA([constraint.JointVelocityConstraint(vlim), constraint.JointAccelerationConstraint(alim)],
                       path, gridpoints=grid, solver_wrapper="seidel")
    T_toppra = inst.compute_trajectory(0, 0).duration

    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(vlim[:, 0], vlim[:, 1])
    prob.add_acceleration_limits(alim[:, 0], alim[:, 1])
    traj = prob.solve().trajectory()
    assert traj.duration <= T_toppra * (1 + 1e-12)
    assert abs(traj.duration / T_toppra - 1) < 1e-4
    np.testing.assert_allclose(traj(traj.duration, 0), way_pts[-1], atol=1e-12)


# -- plain callables --------------------------------------------------------------------------------------


def test_a_callback_path_is_the_polynomial_path_it_samples():
    grid = np.linspace(0, 1, 201)
    f = Counting()
    prob = pp.TimeScalingProblem(f, grid=grid)
    assert f.calls == 2 and f.values == 2 + 201  # its dof (two values of s), then the grid in one batch
    ref = pp.TimeScalingProblem(SPLINE, grid=grid)
    for order in range(3):
        np.testing.assert_array_equal(prob.path(grid, order), SPLINE(grid, order))
    for k in (0, 57, 200):  # the problem's rows at the grid points: the same half-planes
        np.testing.assert_array_equal(prob.feasible_set(k).halfplanes, ref.feasible_set(k).halfplanes)
    assert close(solve_T(CallbackPath(spline_values), grid), solve_T(SPLINE, grid))


def test_a_callback_path_on_its_interval():
    path = pp.as_path(lambda s: (np.column_stack([s, -s]), np.ones((len(s), 2)) * [1, -1], np.zeros((len(s), 2))),
                      interval=(-1.0, 3.0))
    assert (path.s_begin, path.s_end, path.dof) == (-1.0, 3.0, 2)
    np.testing.assert_array_equal(path([-5.0, 5.0]), [[-1.0, 1.0], [3.0, -3.0]])  # s clamped before the call


class Boom(Exception):
    pass


def raising_after(n):
    """A path callable that works for n calls and then raises Boom."""
    count = [0]

    def f(s):
        count[0] += 1
        if count[0] > n:
            raise Boom(f"call {count[0]}")
        return SPLINE.evaluate(s)

    return f


def test_a_callback_exception_comes_out_of_the_call_that_made_it():
    with pytest.raises(Boom, match="call 2"):
        pp.TimeScalingProblem(raising_after(1), grid=10)  # the dof was read, the grid's batch raises
    with pytest.raises(Boom):
        pp.TimeScalingProblem(raising_after(1), grid="auto")  # auto_grid releases the GIL: raised all the same
    prob = pp.TimeScalingProblem(raising_after(2), grid=50)
    prob.add_velocity_limits(-V, V)
    res = prob.solve()
    with pytest.raises(Boom):
        res.trajectory().q(0.3)  # the trajectory evaluates the path again
    # Inside solve (the GIL released): guarantee = continuous audits the torque rows between grid points, on
    # the path evaluated there; on solve_many's threads too.
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    sampled = pp.SampledPath(np.linspace(-0.2, 0.2, 41), *rod_arc(np.linspace(-0.2, 0.2, 41)))
    for run in (lambda p: p.solve(guarantee="continuous"), lambda p: pp.solve_many([p], workers=2, guarantee="continuous")):
        calls = [0]

        def f(s):
            calls[0] += 1
            if calls[0] > 2:
                raise Boom("in the audit")
            return sampled.evaluate(s)

        prob = pp.TimeScalingProblem(pp.as_path(f, interval=(-0.2, 0.2)), grid=sampled.samples)
        prob.add_torque_limits(robot, [-20.0] * 3, [20.0] * 3)
        with pytest.raises(Boom, match="in the audit"):
            run(prob)


def test_the_continuous_guarantee_needs_polynomial_pieces():
    prob = pp.TimeScalingProblem(CallbackPath(spline_values), grid=50)
    prob.add_velocity_limits(-V, V)
    with pytest.raises(pp.InvalidInputError, match="piecewise-polynomial paths .* this path has no polynomial pieces"):
        prob.solve(guarantee="continuous")
    # The same spline through scipy keeps its pieces, so it can.
    prob = pp.TimeScalingProblem(si.CubicSpline(KNOTS, WAYPOINTS), grid=50)
    prob.add_velocity_limits(-V, V)
    assert prob.solve(guarantee="continuous").ok


# -- validation: every branch names the argument and the value ----------------------------------------------


class NoTuple(pp.Path):
    dof, s_begin, s_end = 1, 0.0, 1.0

    def evaluate(self, s):
        return np.zeros((len(s), 3))


class TwoItems(NoTuple):
    def evaluate(self, s):
        return np.zeros((len(s), 1)), np.zeros((len(s), 1))


def n_values(s, shapes=((None, 3), (None, 3), (None, 3)), bad=None):
    out = [np.zeros((len(s) if m is None else m, n)) for m, n in shapes]
    if bad is not None and len(s) > 3:  # the grid's batch, not the two values that tell the dof
        out[bad[0]][bad[1]] = np.nan
    return tuple(out)


@pytest.mark.parametrize("make, error, match", [
    (lambda: pp.as_path(42), TypeError, r"path must be a pathpace.Path, a scipy .* got int"),
    (lambda: pp.as_path("spline.csv"), TypeError, r"path must be a pathpace.Path.* got str"),
    (lambda: pp.TimeScalingProblem(np.zeros((3, 2))), TypeError, r"path must be a pathpace.Path.* got ndarray"),
    (lambda: pp.as_path(SPLINE, interval=(0, 1)), pp.InvalidInputError, r"interval = \(0, 1\) is only for a plain callable"),
    (lambda: pp.as_path(spline_values, interval=(1, 0)), pp.InvalidInputError, r"interval = \(1.0, 0.0\) must be finite with s_begin < s_end"),
    (lambda: pp.as_path(spline_values, interval=(0, np.inf)), pp.InvalidInputError, r"interval = \(0.0, inf\) must be finite"),
    (lambda: pp.as_path(spline_values, interval="ab"), pp.InvalidInputError, r"interval = 'ab' must be two numbers"),
    (lambda: pp.as_path(si.PPoly(np.ones((2, 2)), [1.0, 0.5, 0.0])), pp.InvalidInputError,
     r"path.x\[1\] = 0.5 must be > path.x\[0\] = 1.0: breakpoints must be strictly increasing"),
    (lambda: pp.as_path(si.PPoly(np.ones((2, 2, 2, 2)), [0.0, 0.5, 1.0])), pp.InvalidInputError,
     r"path.c has shape \(2, 2, 2, 2\), expected \(k, m\) or \(k, m, n\)"),
    (lambda: pp.as_path(si.PPoly(np.array([[1.0, np.nan], [0.0, 1.0]]), [0.0, 0.5, 1.0])), pp.InvalidInputError,
     r"path.c\[0, 1, 0\] = nan must be finite"),
    (lambda: pp.as_path(si.PPoly(np.ones((2, 2)) * 1j, [0.0, 0.5, 1.0])), pp.InvalidInputError, r"complex coefficients"),
    (lambda: pp.as_path(si.BSpline([0, 0, 1, 1], np.array([0.0, np.inf]), 1)), pp.InvalidInputError,
     r"path.c\[1, 0\] = inf must be finite"),
    (lambda: pp.as_path(si.BSpline([0, 0, 1, 1], np.ones((2, 2, 2)), 1)), pp.InvalidInputError,
     r"path.c has shape \(2, 2, 2\), expected \(nc,\) or \(nc, n\)"),
    (lambda: pp.as_path(lambda s: s), pp.InvalidInputError, r"path: function\(s\) returned ndarray, expected a tuple \(q, dq, ddq\)"),
    (lambda: pp.as_path(lambda s: (s, s)), pp.InvalidInputError, r"returned tuple, expected a tuple \(q, dq, ddq\)"),
    (lambda: pp.as_path(lambda s: (np.zeros((3, 2)),) * 3), pp.InvalidInputError,
     r"returned q of shape \(3, 2\) for 2 values of s, expected \(2, n\)"),
    (lambda: pp.as_path(lambda s, shape=((None, 3), (1, 3), (None, 3)): n_values(s, shape))(np.linspace(0, 1, 5)),
     pp.InvalidInputError, r"CallbackPath.evaluate\(s\)\[1\] \(dq\) has shape \(1, 3\) for 5 values of s, expected \(5, 3\)"),
    (lambda: pp.TimeScalingProblem(lambda s, bad=(2, (3, 1)): n_values(s, bad=bad), grid=np.linspace(0, 1, 5)),
     pp.InvalidInputError, r"CallbackPath.evaluate\(s\)\[2\] \(ddq\)\[3, 1\] = nan at s = 0.75 must be finite"),
    (lambda: pp.as_path(lambda s: (np.zeros((len(s), 2)), np.zeros((len(s), 2)), [[1, "a"]] * len(s)))(0.5),
     TypeError, r"CallbackPath.evaluate\(s\)\[2\] \(ddq\)\[0, 1\] must be a number, got str"),
    (lambda: pp.as_path(si.PPoly.construct_fast(np.ones((2, 2)), np.array([0.0, np.nan, 1.0]))), pp.InvalidInputError,
     r"path.x\[1\] = nan must be finite"),
    (lambda: pp.as_path(si.PPoly.construct_fast(np.ones((2, 2)), np.array([0.5, 0.5, 0.5]))), pp.InvalidInputError,
     r"path.x spans \[0.5, 0.5\]: a path needs s_begin < s_end"),
    (lambda: pp.as_path(si.BSpline([0, 0, 1, 1], np.array([0.0, 1j]), 1)), pp.InvalidInputError, r"complex coefficients"),
    (lambda: pp.as_path(si.BSpline.construct_fast(np.array([0.0, 0, 0, 0]), np.array([0.0, 1.0]), 1)),
     pp.InvalidInputError, r"path has an empty base interval \[t\[k\], t\[-k-1\]\] = \[0.0, 0.0\]"),
    (lambda: NoTuple()(0.5), TypeError, r"NoTuple.evaluate\(s\) must be a tuple \(q, dq, ddq\), got ndarray"),
    (lambda: TwoItems()(0.5), pp.InvalidInputError, r"TwoItems.evaluate\(s\) returned 2 items, expected 3 \(q, dq, ddq\)"),
    (lambda: CallbackPath(42), TypeError, r"function must be callable, got int"),
    (lambda: InterpolatorPath(42), TypeError, r"interpolator must be callable as interpolator\(s, order\), got int"),
    (lambda: InterpolatorPath(type("I", (), {"path_interval": (1.0, 1.0), "__call__": lambda self, s, k: s})()),
     pp.InvalidInputError, r"path.path_interval = \(1.0, 1.0\) must be finite with s_begin < s_end"),
])
def test_as_path_validation_names_the_argument_and_value(make, error, match):
    with pytest.raises(error, match=match):
        make()


# -- composition: pickling, solve_many, restart, contacts, auto grid ----------------------------------------


def problem_of(path, grid=120):
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(-V, V)
    prob.add_acceleration_limits(-A, A)
    return prob


def ppoly_of_splrep():
    """A 3-D PPoly from FITPACK's interpolating splines (with the zero-width pieces of its repeated end knots)."""
    polys = [si.PPoly.from_spline(si.splrep(KNOTS, WAYPOINTS[:, j])) for j in range(3)]
    return si.PPoly(np.dstack([p.c for p in polys]), polys[0].x)


def path_likes():
    return {"CubicSpline": si.CubicSpline(KNOTS, WAYPOINTS),
            "PPoly": ppoly_of_splrep(),
            "BSpline": si.make_interp_spline(KNOTS, WAYPOINTS),
            "callable": spline_values,
            "toppra-like": ToppraLike()}


@pytest.mark.parametrize("kind", list(path_likes()))
def test_a_problem_from_each_kind_pickles(kind):
    prob = problem_of(path_likes()[kind])
    back = pickle.loads(pickle.dumps(prob))
    assert type(back.path) is type(prob.path)
    assert back.solve().duration == prob.solve().duration


def test_a_callback_path_that_does_not_pickle_says_so():
    path = pp.as_path(lambda s: SPLINE.evaluate(s))
    with pytest.raises(pickle.PicklingError, match=r"<CallbackPath function=.*<lambda>.* does not pickle: its function"):
        pickle.dumps(problem_of(path))


def test_solve_many_on_threads_and_processes():
    probs = [problem_of(p) for p in (spline_values, si.CubicSpline(KNOTS, WAYPOINTS), Counting())]
    expected = [p.solve().duration for p in probs]
    assert [r.duration for r in pp.solve_many(probs, workers=2)] == expected
    with process_pool(2) as ex:
        res = pp.solve_many(probs[:2], executor=ex)  # a Counting instance pickles too, but once is enough
    assert [r.duration for r in res] == expected[:2]


def test_restart_of_a_callback_path_is_the_restart_of_its_polynomial():
    for s0, sdot0 in ((0.3, 0.1), (0.4321, 0.2)):
        mine, ref = problem_of(spline_values).restarted(s0, sdot0), problem_of(SPLINE).restarted(s0, sdot0)
        assert mine.solve().ok and close(mine.solve().duration, ref.solve().duration, 1e-12)
        back = pickle.loads(pickle.dumps(mine))  # the tail of a callback path pickles with its parent
        assert back.solve().duration == mine.solve().duration
        assert back.path.s_begin == s0


def test_contacts_on_a_scipy_spline_and_on_a_callback_path():
    """The rod of test_contact.py on its frictional contact. A scipy CubicSpline through the rod's path gives
    the T of the same pieces written by hand (bit for bit), and a callback returning a SampledPath's values
    the T of that SampledPath; against pathpace's own spline through the same points (other arithmetic,
    the same path to rounding) T agrees to 1e-8 only: the contact rows are a polytope projection solved with
    GLPK's 1e-9 feasibility tolerance, which turns rounding-level changes of the path into ~1e-9 relative
    changes of T (measured 3.3e-10)."""
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    contact = [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)]
    thetas = np.linspace(-0.2, 0.2, 9)  # beyond |θ| ~ 0.3 its torque limit cannot hold it (infeasible)
    grid = np.linspace(-0.2, 0.2, 41)

    rod = rod_arc

    def T(path):
        prob = pp.TimeScalingProblem(path, grid=grid)
        prob.add_contacts(robot, contact, cone_edges=4, drift_tolerance=np.inf)  # a spline of the arc drifts ~1e-6
        res = prob.solve()
        assert res.ok, res.message
        return res.duration

    cs = si.CubicSpline(thetas, rod(thetas)[0])
    assert T(cs) == T(pp.PiecewisePolynomialPath(thetas, np.ascontiguousarray(cs.c[::-1].transpose(1, 0, 2))))
    assert close(T(cs), T(pp.CubicSplinePath(rod(thetas)[0], knots=thetas)), 1e-8)
    sampled = pp.SampledPath(grid, *rod(grid))
    assert T(pp.as_path(sampled.evaluate, interval=(-0.2, 0.2))) == T(sampled)


def test_auto_grid_keeps_the_breakpoints_of_a_scipy_spline():
    cs = si.CubicSpline(KNOTS, WAYPOINTS)
    grid = pp.TimeScalingProblem(cs, grid="auto").grid
    assert set(KNOTS) <= set(grid)
    # Without pieces to read, the callback's grid comes from its values alone: a valid grid all the same.
    g = pp.TimeScalingProblem(spline_values, grid="auto").grid
    assert g[0] == 0.0 and g[-1] == 1.0 and np.all(np.diff(g) > 0)
    assert np.array_equal(g, pp.auto_grid(CallbackPath(spline_values)))


def test_readme_paths_example_runs_as_pasted():
    pytest.importorskip("toppra")
    readme = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    (block,) = [b for b in __import__("re").findall(r"```python\n(.*?)```", readme, __import__("re").S)
                if "ta.SplineInterpolator(ss, way_pts)" in b]
    scope = {}
    exec(compile(block, "README.md", "exec"), scope)  # noqa: S102 - the README's own example
    traj, path = scope["traj"], scope["path"]
    np.testing.assert_allclose(traj(traj.duration), scope["way_pts"][-1], atol=1e-12)
    assert [c.name for c in scope["instance"].constraints] == ["velocity limits", "acceleration limits"]
    assert isinstance(pp.as_path(path), pp.PiecewisePolynomialPath)


def line_on_0_2(s):
    """Hand and box together, x = s (test_contact_phases.py's path) as a callback."""
    one = np.ones((len(s), 2))
    return np.column_stack([s, s]), one, 0 * one


def test_contact_phases_insert_their_switch_on_a_callback_path_and_a_scipy_spline():
    """test_contact_phases.py's push-then-brake (a 10 N hand on hand + box, 2 kg: |s̈| <= 5): with the switch
    at s = 1 off the grid (7 intervals on [0, 2]) the problem inserts it, evaluating the path there again;
    T is the closed form θ = min(2as, 2a(2 - s)), θ at the switch the smaller neighbour's."""
    hand_box = pp.RobotModel.from_urdf(str(DATA / "hand_box.urdf"))

    def on_box(nx):
        return [pp.Contact("box", point=(0, 0, 0), normal=(nx, 0, 0), friction=0.5, other_link="hand")]

    s = np.linspace(0.0, 2.0, 3)
    for path in (pp.as_path(line_on_0_2, interval=(0.0, 2.0)), si.CubicSpline(s, np.column_stack([s, s]))):
        prob = pp.TimeScalingProblem(path, grid=7)
        prob.add_contact_phases(hand_box, [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))], cone_edges=4)
        g = prob.grid
        assert g.size == 9 and g[4] == 1.0
        th = np.minimum(10.0 * g, 10.0 * (2.0 - g))
        th[4] = min(th[3], th[5])
        T = np.sum(2 * np.diff(g) / (np.sqrt(th[:-1]) + np.sqrt(th[1:])))
        res = prob.solve()
        assert res.status.name == "OPTIMAL" and close(res.duration, T)
        assert pickle.loads(pickle.dumps(prob)).solve().duration == res.duration


# -- auto_grid on any path-like (what TimeScalingProblem(path, grid="auto") takes) -------------------------


def test_auto_grid_takes_every_path_like_as_path_takes():
    ta = pytest.importorskip("toppra")
    for kind, obj in {**path_likes(), "toppra": ta.SplineInterpolator(KNOTS, WAYPOINTS)}.items():
        grid = pp.auto_grid(obj, tolerance=1e-3)
        assert np.array_equal(grid, pp.auto_grid(pp.as_path(obj), tolerance=1e-3)), kind
        assert np.array_equal(grid, pp.TimeScalingProblem(obj, grid="auto").grid), kind
    with pytest.raises(TypeError, match=r"path must be a pathpace.Path, a scipy PPoly.*got str"):
        pp.auto_grid("not a path")
    with pytest.raises(TypeError, match=r"path must be a pathpace.Path, got None"):
        pp.auto_grid(None)


# -- pickling a user's subclass ----------------------------------------------------------------------------


class UserPathThatPickles(UserPath):
    """UserPath with what pickle needs: how to make it again."""

    def __reduce__(self):
        return UserPathThatPickles, ()


def test_a_user_subclass_without_reduce_says_how_to_make_it_pickle():
    msg = (r"^UserPath does not pickle: a Python subclass of pathpace.Path needs its own __reduce__ \(e.g. `def "
           r"__reduce__\(self\): return UserPath, \(<constructor arguments>,\)`\) or __getstate__/__setstate__; or give "
           r"the path as a module-level function f\(s\) -> \(q, dq, ddq\) through pathpace.paths.CallbackPath")
    with pytest.raises(TypeError, match=msg):
        pickle.dumps(UserPath())
    prob = pp.TimeScalingProblem(UserPath(), grid=40)
    with pytest.raises(TypeError, match=r"^UserPath does not pickle"):  # inside a problem too
        pickle.dumps(prob)
    # With __reduce__ it pickles, alone and in a problem; the concrete paths keep their own state.
    prob = pp.TimeScalingProblem(UserPathThatPickles(), grid=40)
    prob.add_velocity_limits([-1, -1], [1, 1])
    back = pickle.loads(pickle.dumps(prob))
    assert type(back.path) is UserPathThatPickles and back.solve().duration == prob.solve().duration
    for kind, path in every_path_kind().items():
        if kind != "UserPath":
            assert np.array_equal(pickle.loads(pickle.dumps(path))(0.3, 1), path(0.3, 1)), kind
