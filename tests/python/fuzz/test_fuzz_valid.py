"""Random valid problems: every OPTIMAL timing is re-checked at every grid point by an independent
checker (scipy's spline for p', p'', numpy for the limits), and T is recomputed from eq. (25)."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline

from fuzz_support import fuzz_settings, kinematic_violation, run_isolated
from helpers import kinematic_problem
from oracles import duration



@st.composite
def mixed_scale_problems(draw):
    """Per-joint limits over many decades, asymmetric acceleration limits (amin != -amax)."""
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    n = 2
    return dict(waypoints=rng.uniform(-1, 1, (5, n)), vmax=10.0 ** rng.uniform(-3, 9, n),
                amax=10.0 ** rng.uniform(-6, 14, n), amin=-(10.0 ** rng.uniform(-6, 14, n)),
                N=draw(st.integers(20, 300)), method="auto")


@st.composite
def problems(draw, min_N=20, max_N=400):
    n = draw(st.integers(1, 4))
    K = draw(st.integers(2, 7))
    scale = 10.0 ** draw(st.integers(-2, 2))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    waypoints = scale * rng.uniform(-1, 1, (K, n))
    vmax = 10.0 ** rng.uniform(-1, 1, n)
    amax = 10.0 ** rng.uniform(-1, 1, n)
    N = draw(st.integers(min_N, max_N))
    return dict(waypoints=waypoints, vmax=vmax, amax=amax, N=N, method=draw(st.sampled_from(["auto", "slp"])))


def solve(p):
    r = kinematic_problem(p["waypoints"], p["N"], -p["vmax"], p["vmax"], p.get("amin", -p["amax"]), p["amax"]).solve(
        method=p["method"])
    return dict(status=r.status.name, message=r.message, s=np.array(r.s), sdot=np.array(r.sdot),
                duration=float(r.duration))


@fuzz_settings(120)
@given(problems())
def test_random_valid_problems_are_optimal_and_meet_every_limit_at_every_grid_point(p):
    check_optimal_and_feasible(p)


@fuzz_settings(60)
@given(problems(min_N=2, max_N=19))
def test_random_valid_problems_on_coarse_grids(p):
    check_optimal_and_feasible(p)


# Before issue 10's fixes, 30 of 300 seeds broke a limit or failed, e.g. OPTIMAL with |q̈| 2.9x its limit
# (vmax ~ (3e8, 4e2), amax ~ (1e8, 7e12), amin ~ (-2e-6, -1e-6)), ITERATION_LIMIT "the timing is feasible"
# with 3e3x, or UNBOUNDED; now 0 of 600 (seeds 0..599 of the same draw).
@fuzz_settings(60)
@given(mixed_scale_problems())
def test_random_mixed_scale_problems(p):
    check_optimal_and_feasible(p)


def check_optimal_and_feasible(p):
    kind, out = run_isolated(solve, p)
    assert kind == "ok", out
    # Rest to rest under finite positive limits is always feasible. ITERATION_LIMIT is an honest
    # answer when its message says the timing it returns is feasible: then that timing is checked too.
    assert out["status"] == "OPTIMAL" or (
        out["status"] == "ITERATION_LIMIT" and "the timing is feasible" in out["message"]), out["message"]
    s, sdot = out["s"], out["sdot"]
    np.testing.assert_allclose(s, np.linspace(0, 1, p["N"] + 1), rtol=0, atol=1e-15)
    assert np.all(sdot >= 0) and sdot[0] == 0 and sdot[-1] == 0
    spline = CubicSpline(np.linspace(0, 1, len(p["waypoints"])), p["waypoints"])
    dq, ddq = spline(s, 1), spline(s, 2)
    viol = kinematic_violation(s, sdot, dq, ddq, p["vmax"], p["amax"], p.get("amin"))
    assert viol <= 1e-6, f"a limit is exceeded by {viol:.3g} (relative)"
    T = duration(s, sdot**2)
    assert np.isfinite(out["duration"]) and abs(out["duration"] - T) <= 1e-9 * T


def coarse_problem():
    w = np.array([[0.27392337], [-0.46042657], [-0.91805295], [-0.96694473], [0.62654048]])
    r = kinematic_problem(w, 6, [-6.69131006], [6.69131006], [-1.63407337], [1.63407337]).solve()
    return r.status.name, r.message


# Found by the long fuzz run: reported INFEASIBLE, the greedy profile having walked into a stop that the
# coupling rows allow (θ_4 at the top of K_4 leaves only θ_5 = 0); see detail::unstopped_profile.
def test_coarse_grid_with_a_feasible_slow_timing_is_not_infeasible():
    # Independent evidence that the problem is feasible: θ = 1e-3 at every interior grid point.
    w = np.array([[0.27392337], [-0.46042657], [-0.91805295], [-0.96694473], [0.62654048]])
    s = np.linspace(0, 1, 7)
    spline = CubicSpline(np.linspace(0, 1, 5), w)
    sdot = np.sqrt([0, 1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 0])
    assert kinematic_violation(s, sdot, spline(s, 1), spline(s, 2), 6.69131006, 1.63407337) <= 0
    kind, out = run_isolated(coarse_problem)
    assert kind == "ok" and out[0] == "OPTIMAL", out
