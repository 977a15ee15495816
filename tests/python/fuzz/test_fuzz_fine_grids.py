"""Fine uniform grids, N = 1e4..1e6, from many seeds: every OPTIMAL timing meets every limit at every grid point
to 1e-9 relative (both adjacent s̈ at each point, eq. 26), checked by an independent oracle (scipy's spline
for p', p''). Before issue 20 one path was checked here, and held-out paths broke s̈ limits by up to 3e-2 at
N = 5e5 while OPTIMAL."""

import numpy as np
from hypothesis import given
from hypothesis import strategies as st
from scipy.interpolate import CubicSpline

from fuzz_support import fuzz_settings, kinematic_violation, run_isolated
from helpers import kinematic_problem


@st.composite
def fine_problems(draw):
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    n = int(rng.integers(1, 4))
    waypoints = 10.0 ** rng.uniform(-2, 2) * rng.uniform(-1, 1, (int(rng.integers(3, 8)), n))
    return dict(waypoints=waypoints, vmax=10.0 ** rng.uniform(-1, 1, n), amax=10.0 ** rng.uniform(-1, 1, n),
                N=int(round(10.0 ** draw(st.floats(4.0, 6.0)))))


def solve(p):
    r = kinematic_problem(p["waypoints"], p["N"], -p["vmax"], p["vmax"], -p["amax"], p["amax"]).solve()
    return r.status.name, r.message, np.array(r.s), np.array(r.sdot)


@fuzz_settings(3)
@given(fine_problems())
def test_fine_grids_are_optimal_and_meet_every_limit_at_every_grid_point(p):
    kind, out = run_isolated(solve, p, timeout=300.0)
    assert kind == "ok", out
    status, message, s, sdot = out
    assert status == "OPTIMAL", message
    spline = CubicSpline(np.linspace(0, 1, len(p["waypoints"])), p["waypoints"])
    viol = kinematic_violation(s, sdot, spline(s, 1), spline(s, 2), p["vmax"], p["amax"])
    assert viol <= 1e-9, f"a limit is exceeded by {viol:.3g} (relative) at N = {p['N']}"
