"""grid='auto': a grid fitted to the path's shape (pp.auto_grid)."""

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem


def bent_path():
    return pp.CubicSplinePath(np.array([[0.0, 0.0], [1.0, 0.5], [0.2, 1.5], [0.4, -0.3], [1.2, 0.1]]))


def chord_deviations(path, g):
    """Independent check: |f(mid) - (f(a) + f(b)) / 2| of p, p', p'' per interval, over their path scales."""
    mid = 0.5 * (g[:-1] + g[1:])
    dense = np.linspace(g[0], g[-1], 20001)
    out = []
    for f in (path.q, path.dq, path.ddq):
        fd = f(dense)
        scale = (fd.max(0) - fd.min(0)).max() if f == path.q else np.abs(fd).max()
        dev = np.abs(f(mid) - 0.5 * (f(g[:-1]) + f(g[1:]))).max(axis=1)
        out.append(dev / scale)
    return out


def test_a_straight_line_needs_no_refinement():
    path = pp.CubicSplinePath(np.array([[0.0, 1.0], [2.0, -1.0]]))
    np.testing.assert_array_equal(pp.auto_grid(path, 1e-6), np.linspace(0.0, 1.0, 17))


@pytest.mark.parametrize("tol", [1e-2, 1e-3, 1e-4, 1e-5])
def test_every_interval_meets_the_tolerance_and_knots_are_grid_points(tol):
    path = bent_path()
    g = pp.auto_grid(path, tol)
    assert g[0] == path.s_begin and g[-1] == path.s_end and np.all(np.diff(g) > 0)
    for knot in path.breakpoints:
        assert np.min(np.abs(g - knot)) <= 1e-12
    # 1 % slack: the scales are read off a finite sample of the path, here off a denser one.
    for dev in chord_deviations(path, g):
        assert dev.max() <= 1.01 * tol


def test_refinement_is_local_and_scales_as_the_square_root():
    path = bent_path()
    n3, n5 = len(pp.auto_grid(path, 1e-3)) - 1, len(pp.auto_grid(path, 1e-5)) - 1
    assert 5 <= n5 / n3 <= 20  # deviation ~ Δs², so Δs ~ sqrt(tol): about 10x the points for 100x
    # A straight piece then a bent one: only the bent one is refined.
    coeffs = np.array([[[0.0], [1.0], [0.0], [0.0]], [[0.5], [1.0], [0.0], [3.0]]])
    g = pp.auto_grid(pp.PiecewisePolynomialPath([0.0, 0.5, 1.0], coeffs), 1e-4)
    np.testing.assert_allclose(g[g <= 0.5], np.linspace(0.0, 0.5, 9), rtol=0, atol=1e-15)
    assert np.diff(g[g >= 0.5]).max() <= 1 / 16 / 8


def test_auto_grid_shrinks_the_excursions_between_grid_points():
    path = bent_path()
    viol = []
    for tol in [1e-3, 1e-4, 1e-5]:
        prob = kinematic_problem(path, "auto", [-1, -1], [1, 1], [-2, -2], [2, 2], grid_tolerance=tol)
        assert np.array_equal(prob.grid, pp.auto_grid(path, tol))
        res = prob.solve()
        assert res.status == pp.Status.OPTIMAL
        tr = res.trajectory()
        t = np.linspace(0, res.duration, 20001)
        viol.append(max(np.abs(tr.qd(t)).max() - 1, np.abs(tr.qdd(t)).max() / 2 - 1, 0))
        # The grid bounds the path's deviation; the excursions also depend on the speed profile, and come
        # out of the same order (measured 4-13x the tolerance on this path).
        assert viol[-1] <= 20 * tol
    assert viol[0] > viol[1] > viol[2]


def test_auto_grid_validation_messages():
    path = bent_path()
    with pytest.raises(pp.InvalidInputError, match=r"^grid_tolerance = 0 must be in \(0, 1\)$"):
        pp.auto_grid(path, 0.0)
    with pytest.raises(pp.InvalidInputError, match=r"^min_intervals = 0 must be >= 1$"):
        pp.auto_grid(path, 1e-3, min_intervals=0)
    with pytest.raises(pp.InvalidInputError, match=r"^max_intervals = 8 must be >= min_intervals = 16$"):
        pp.auto_grid(path, 1e-3, max_intervals=8)
    with pytest.raises(pp.InvalidInputError, match=r"^grid = 'auto' needs more than max_intervals = 100 intervals"):
        pp.auto_grid(path, 1e-6, max_intervals=100)
    with pytest.raises(pp.InvalidInputError, match=r"^grid = 'fine' must be 'auto', an int or an array of s$"):
        pp.TimeScalingProblem(path, grid="fine")
    with pytest.raises(pp.InvalidInputError, match=r"^grid_tolerance = 2 must be in \(0, 1\)$"):
        pp.TimeScalingProblem(path, grid="auto", grid_tolerance=2.0)
