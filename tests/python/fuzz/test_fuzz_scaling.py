"""Scaling laws over 1e-12..1e12: the discretised problem (eq. 25-27) is exactly homogeneous, so

* velocity limits only: scaling the path's coordinates by L (or the limits by 1/L) scales T by L;
* acceleration limits only: scaling the limits by a scales T by 1/sqrt(a) (the coordinates by L: T by sqrt(L)).

Any departure is the solver's numerics, not the problem. The solver works in units where the speeds are
~1 (detail::Scale, powers of two); before that, a cap ṡ² <= 1e15 made L = 1e-9 (or c = 1e9) UNBOUNDED and
absolute tolerances left T 7e-4 short at a = 1e-9.
"""

import numpy as np
import pytest

from fuzz_support import run_isolated
from helpers import kinematic_problem

EXPONENTS = [-12, -9, -6, -3, 3, 6, 9, 12]
# What tests/cpp/test_scaling.cpp asserts of the same laws on its own waypoints (the scaled problems are the
# same problem up to powers of two and rounding): 1e-12 with velocity limits, 1e-11 with acceleration
# limits (certified to 1e-7 only). Measured here: at most 1.3e-15.
RTOL_VELOCITY = 1e-12
RTOL_ACCELERATION = 1e-11


def duration(seed, coord_scale, vmax, amax, N=60):
    rng = np.random.default_rng(seed)
    w = coord_scale * rng.uniform(-1, 1, (5, 2))
    v = None if vmax is None else vmax * np.ones(2)
    a = None if amax is None else amax * np.ones(2)
    r = kinematic_problem(w, N, None if v is None else -v, v, None if a is None else -a, a).solve()
    return r.status.name, float(r.duration), r.message


def law(seed, base, scaled, factor, rtol):
    kind, ref = run_isolated(duration, seed, *base)
    assert kind == "ok" and ref[0] == "OPTIMAL", ref
    kind, out = run_isolated(duration, seed, *scaled)
    assert kind == "ok", out
    assert out[0] == "OPTIMAL", f"status {out[0]}: {out[2]}"
    assert out[1] == pytest.approx(factor * ref[1], rel=rtol), f"T = {out[1]:.12g}, expected {factor * ref[1]:.12g}"


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", EXPONENTS)
def test_velocity_limits_time_scales_with_path_length(seed, e):
    L = 10.0**e
    law(seed, (1.0, 1.0, None), (L, 1.0, None), L, RTOL_VELOCITY)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", EXPONENTS)
def test_velocity_limits_time_scales_inversely_with_the_limit(seed, e):
    c = 10.0**e
    law(seed, (1.0, 1.0, None), (1.0, c, None), 1.0 / c, RTOL_VELOCITY)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", EXPONENTS)
def test_acceleration_limits_time_scales_with_one_over_sqrt_a(seed, e):
    a = 10.0**e
    law(seed, (1.0, None, 1.0), (1.0, None, a), 1.0 / np.sqrt(a), RTOL_ACCELERATION)


@pytest.mark.parametrize("seed", [0, 1])
@pytest.mark.parametrize("e", EXPONENTS)
def test_acceleration_limits_time_scales_with_sqrt_path_length(seed, e):
    L = 10.0**e
    law(seed, (1.0, None, 1.0), (L, None, 1.0), np.sqrt(L), RTOL_ACCELERATION)
