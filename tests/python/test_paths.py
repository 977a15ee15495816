"""Paths against scipy's interpolants, and their validation."""

import numpy as np
import pytest
from scipy.interpolate import CubicSpline, PPoly

import pathpace as pp


@pytest.mark.parametrize("boundary", ["not-a-knot", "natural", "clamped"])
@pytest.mark.parametrize("K", [2, 3, 5, 9])
@pytest.mark.parametrize("knots", ["uniform", "chord"])
def test_cubic_spline_matches_scipy(boundary, K, knots):
    rng = np.random.default_rng(K)
    n = 1 + K % 4
    wp = rng.uniform(-2, 2, (K, n))
    kwargs = {}
    if boundary == "clamped":
        d0, d1 = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
        kwargs = dict(start_derivative=d0, end_derivative=d1)
        bc = ((1, d0), (1, d1))
    else:
        bc = boundary
    path = pp.CubicSplinePath(wp, knots=knots, boundary=boundary, s_begin=-1.0, s_end=2.0, **kwargs)
    if knots == "uniform":
        t = np.linspace(-1.0, 2.0, K)
    else:
        c = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(wp, axis=0), axis=1))])
        t = -1.0 + 3.0 * c / c[-1]
    ref = CubicSpline(t, wp, bc_type=bc)
    s = rng.uniform(-1, 2, 200)
    for mine, order in ((path.q(s), 0), (path.dq(s), 1), (path.ddq(s), 2)):
        expected = ref(s, order)
        # Relative to the size of the path (a line has p'' = 0, where only rounding remains).
        np.testing.assert_allclose(mine, expected, rtol=1e-12, atol=1e-12 * max(1.0, np.abs(wp).max()))
    np.testing.assert_allclose(path.knots, t, rtol=1e-14, atol=1e-14)
    assert path.dof == n and path.s_begin == -1.0 and path.s_end == 2.0


def test_explicit_knots_and_clamping_outside_the_domain():
    wp = np.array([[0.0, 1.0], [1.0, -1.0], [0.5, 0.5], [2.0, 0.0]])
    knots = np.array([0.0, 0.2, 0.7, 1.5])
    path = pp.CubicSplinePath(wp, knots=knots)
    np.testing.assert_allclose(path.q(knots), wp, atol=1e-14)
    np.testing.assert_array_equal(path.q(-3.0), path.q(0.0))
    np.testing.assert_array_equal(path.q(9.0), path.q(1.5))
    assert path.q(0.3).shape == (2,)


def test_piecewise_polynomial_matches_scipy_ppoly():
    rng = np.random.default_rng(3)
    bp = np.array([0.0, 0.3, 0.5, 1.2])
    coef = rng.uniform(-1, 1, (3, 5, 2))  # pieces, degree + 1 (lowest first), n
    path = pp.PiecewisePolynomialPath(bp, coef)
    ref = PPoly(coef[:, ::-1, :].transpose(1, 0, 2), bp)  # scipy: highest degree first, (k, m, n)
    s = rng.uniform(0, 1.2, 100)
    for mine, order in ((path.q(s), 0), (path.dq(s), 1), (path.ddq(s), 2)):
        np.testing.assert_allclose(mine, ref(s, order), rtol=1e-12, atol=1e-12)


def test_sampled_path_reproduces_samples_and_converges_at_sixth_order():
    spline = pp.CubicSplinePath(np.array([[0.0], [1.0], [-1.0], [0.5]]), boundary="natural")
    ref = lambda s: np.sin(3 * s) + s**2  # noqa: E731  a smooth non-polynomial path
    dref = lambda s: 3 * np.cos(3 * s) + 2 * s  # noqa: E731
    ddref = lambda s: -9 * np.sin(3 * s) + 2  # noqa: E731
    errors = []
    fine = np.linspace(0, 1, 1001)
    for m in (9, 17, 33):
        s = np.linspace(0, 1, m)
        path = pp.SampledPath(s, ref(s)[:, None], dref(s)[:, None], ddref(s)[:, None])
        np.testing.assert_allclose(path.q(s)[:, 0], ref(s), atol=1e-13)
        np.testing.assert_allclose(path.dq(s)[:, 0], dref(s), atol=1e-12)
        np.testing.assert_allclose(path.ddq(s)[:, 0], ddref(s), atol=1e-11)
        errors.append(np.abs(path.q(fine)[:, 0] - ref(fine)).max())
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all(ratios > 2**6 * 0.7), ratios  # halving h divides the error by ~64
    # And a spline sampled at its knots is reproduced exactly (cubic ⊂ quintic).
    s = np.linspace(0, 1, 4)
    sp = pp.SampledPath(s, spline.q(s), spline.dq(s), spline.ddq(s))
    np.testing.assert_allclose(sp.q(fine), spline.q(fine), atol=1e-12)


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: pp.CubicSplinePath(np.zeros((1, 2))), r"waypoints has 1 rows, expected at least 2"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [np.nan]])), r"waypoints\[1\] = nan must be finite"),
        (lambda: pp.CubicSplinePath(np.array([0.0, 1.0])), r"waypoints has shape \(2,\), expected a 2-D array"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0], [1.0]]), knots="chord"),
         r"waypoints\[2\] equals waypoints\[1\]: chord-length knots need distinct consecutive waypoints"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), knots="cubic"),
         r"knots = 'cubic' must be 'uniform', 'chord' or an array of s"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), knots=np.array([0.0, 0.0])),
         r"knots\[1\] = 0 must be > knots\[0\] = 0 \(strictly increasing\)"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), knots=np.array([0.0, 1.0, 2.0])),
         r"knots has size 3, expected 2 \(one per waypoint\)"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), boundary="periodic"),
         r"boundary = 'periodic' must be one of 'not-a-knot', 'natural', 'clamped'"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), boundary="clamped", start_derivative=[0.0, 1.0],
                                    end_derivative=[0.0]),
         r"start_derivative has size 2, expected 1 \(one per coordinate\)"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), start_derivative=[1.0]),
         r"start_derivative and end_derivative are only used with the clamped boundary"),
        (lambda: pp.CubicSplinePath(np.array([[0.0], [1.0]]), s_begin=1.0, s_end=1.0),
         r"s_begin = 1 must be < s_end = 1"),
        (lambda: pp.PiecewisePolynomialPath([0.0, 1.0], np.zeros((2, 2, 1))),
         r"coefficients has size 2, expected 1 \(one piece per interval of breakpoints, which has 2 entries\)"),
        (lambda: pp.PiecewisePolynomialPath([0.0, 1.0], np.zeros((2, 1))),
         r"coefficients has shape \(2, 1\), expected \(pieces, degree \+ 1, n\)"),
        (lambda: pp.PiecewisePolynomialPath([1.0, 0.0], np.zeros((1, 2, 1))),
         r"breakpoints\[1\] = 0 must be > breakpoints\[0\] = 1"),
        (lambda: pp.SampledPath([0.0, 1.0], np.zeros((2, 1)), np.zeros((3, 1)), np.zeros((2, 1))),
         r"dq has shape \(3, 1\), expected \(2, 1\) \(as q\)"),
        (lambda: pp.SampledPath([0.0], np.zeros((1, 1)), np.zeros((1, 1)), np.zeros((1, 1))),
         r"s has 1 entries, expected at least 2"),
        (lambda: pp.SampledPath([0.0, 1.0], np.zeros((2, 1)), np.zeros((2, 1)), np.full((2, 1), np.inf)),
         r"ddq\[0\] = inf must be finite"),
    ],
)
def test_path_validation(make, message):
    with pytest.raises(pp.InvalidInputError, match=message):
        make()


def test_evaluation_rejects_nan():
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    with pytest.raises(pp.InvalidInputError, match=r"s\[1\] = nan must be a number"):
        path.q([0.5, np.nan])
