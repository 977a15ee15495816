"""Scaling laws over 1e-12..1e12: the discretised problem (eq. 25-27) is exactly homogeneous, so

* velocity limits only: scaling the path's coordinates by L (or the limits by 1/L) scales T by L;
* acceleration limits only: scaling the limits by a scales T by 1/sqrt(a) (the coordinates by L: T by sqrt(L)).

Any departure is the solver's numerics, not the problem. Cases that fail today are xfail(strict=True)
with the reason, so they turn into failures (to be un-marked) once fixed.
"""

import numpy as np
import pytest

from fuzz_support import run_isolated

import pathpace as pp

EXPONENTS = [-12, -9, -6, -3, 3, 6, 9, 12]
RTOL = 1e-8


def duration(seed, coord_scale, vmax, amax, N=60):
    rng = np.random.default_rng(seed)
    w = coord_scale * rng.uniform(-1, 1, (5, 2))
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(w), grid=N)
    if vmax is not None:
        prob.add_velocity_limits(-vmax * np.ones(2), vmax * np.ones(2))
    if amax is not None:
        prob.add_acceleration_limits(-amax * np.ones(2), amax * np.ones(2))
    r = prob.solve()
    return r.status.name, float(r.duration), r.message


def law(seed, base, scaled, factor):
    kind, ref = run_isolated(duration, seed, *base)
    assert kind == "ok" and ref[0] == "OPTIMAL", ref
    kind, out = run_isolated(duration, seed, *scaled)
    assert kind == "ok", out
    assert out[0] == "OPTIMAL", f"status {out[0]}: {out[2]}"
    assert out[1] == pytest.approx(factor * ref[1], rel=RTOL), f"T = {out[1]:.12g}, expected {factor * ref[1]:.12g}"


# The solver bounds ṡ² and s̈ by a box at 1e15 (detail::kInfinityCap) instead of rescaling: a problem
# whose optimum has ṡ² beyond it comes back UNBOUNDED (or capped). Fixing this means rescaling inside
# the solve (TimeScalingProblem::solve / reachability / SLP), sequenced after the solver rewrite.
CAP = "internal cap ṡ² <= 1e15 (detail::kInfinityCap): needs rescaling inside the solver (issue 10, after issue 8)"


# Under acceleration limits alone the solver is not scale-invariant beyond ~1e3 either way: measured
# (seed 0, N = 60) T·sqrt(a) = 8.56720 at a = 1e-3..1e3 but 8.56825 (OPTIMAL, 1.2e-4 long) at a = 1e6,
# ITERATION_LIMIT at a = 1e-6, and OPTIMAL with the limits exceeded by 1 % at a = 1e-12: absolute
# tolerances in the reachability/SLP code. The windowed SLP of issue 8 (normalised LP columns and rows)
# fixed 1e±6 and the large ones; a <= 1e-9 and coordinates >= 1e9 still fail.
ACC = "solver tolerances are absolute, not scale-invariant (T 1.2e-4 long at a = 1e6; 1 % violation at 1e-12)"


def mark(e, failing, reason=CAP):
    return pytest.param(e, marks=pytest.mark.xfail(strict=True, reason=reason)) if e in failing else e


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", [mark(e, {-12, -9}) for e in EXPONENTS])
def test_velocity_limits_time_scales_with_path_length(seed, e):
    L = 10.0**e
    law(seed, (1.0, 1.0, None), (L, 1.0, None), L)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", [mark(e, {9, 12}) for e in EXPONENTS])
def test_velocity_limits_time_scales_inversely_with_the_limit(seed, e):
    c = 10.0**e
    law(seed, (1.0, 1.0, None), (1.0, c, None), 1.0 / c)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", [mark(e, {-12, -9}, ACC) for e in EXPONENTS])
def test_acceleration_limits_time_scales_with_one_over_sqrt_a(seed, e):
    a = 10.0**e
    law(seed, (1.0, None, 1.0), (1.0, None, a), 1.0 / np.sqrt(a))


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", [mark(e, {9, 12}, ACC) for e in EXPONENTS])
def test_acceleration_limits_time_scales_with_sqrt_path_length(seed, e):
    L = 10.0**e
    law(seed, (1.0, None, 1.0), (L, None, 1.0), np.sqrt(L))
