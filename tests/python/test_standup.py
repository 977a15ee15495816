"""examples/humanoid_standup.py (issue 21, Deliver 2): the stand-up's path, without MuJoCo.

Talos rises from a deep squat on both feet along a path built by IK on pathpace's Jacobians: both soles stay
where they are (every sole point within the timing's drift tolerance, 0.1 mm, between the knots too), the
pelvis rises by the squat's depth, and every joint stays inside its limits. What MuJoCo does with its timings
is tests/python/test_sim.py's (test_standup_from_a_squat_...)."""

import runpy
from pathlib import Path

import numpy as np

import pathpace as pp

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_ik_path_keeps_both_soles_fixed_and_rises_from_a_deep_squat():
    ns = runpy.run_path(str(EXAMPLES / "humanoid_standup.py"))
    robot = ns["talos_sway"].load_talos()
    path = ns["standup_path"](robot)
    contacts = ns["talos_sway"].sole_contacts(4)
    s = np.linspace(path.s_begin, path.s_end, 2001)  # 100 samples per knot interval: between the knots too
    drift, _ = pp.ContactConstraint(robot, contacts, cone_edges=8).max_drift(path, s)
    assert drift < 1e-4  # the timing's drift_tolerance (contact_timing)
    q = np.array([path.q(si) for si in s])
    lo, hi = robot.position_limits
    assert np.all(q >= lo) and np.all(q <= hi)
    # From the squat to half-sitting: the pelvis (the floating base's z) rises by DEPTH, monotonically.
    z = q[:, 2]
    assert np.isclose(z[-1] - z[0], ns["DEPTH"], rtol=0, atol=1e-9) and ns["DEPTH"] >= 0.2
    assert np.all(np.diff(z) >= -1e-9)
