"""Every example runs and says what it should."""

import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_demo_solves_the_panda_path_and_reports_the_locked_joint(capsys):
    ns = runpy.run_path(str(EXAMPLES / "demo.py"), run_name="__main__")
    out = capsys.readouterr().out
    assert "N = 1000: OPTIMAL" in out
    assert ns["margin"] > 0  # the path stays inside the position limits
    # guarantee="continuous": the limits hold at every instant (1 kHz and denser), for a longer T.
    import numpy as np
    tc, vmax, amax = ns["tc"], ns["vmax"], ns["amax"]
    t = np.arange(0.0, tc.duration, 1e-3)
    assert np.max(np.abs(tc.qd(t)) / vmax) <= 1 + 1e-9 and np.max(np.abs(tc.qdd(t)) / amax) <= 1 + 1e-9
    assert ns["cont"].duration >= ns["res"].duration
    assert "INFEASIBLE" in out and "binding: velocity panda_joint4" in out
    # A zero limit cannot be scaled into a nonzero one: no relaxation of velocity limits explains it.
    assert "feasible with velocity limits" not in out
    assert "no single family of limits scaled up to x 1000 makes it feasible" in out
    assert (EXAMPLES / "output" / "panda_trajectory.csv").is_file()


def test_pendulum_swing_up_torque_aware_timing_is_tracked_and_the_others_are_not():
    ns = runpy.run_path(str(EXAMPLES / "pendulum_swing_up.py"))
    rows, res_tau, res_acc, res_mono = ns["main"](plot=False, N=400)
    by = {(r["timing"], r["controller"]): r for r in rows}
    assert by[("optimal, torque limits", "PD+g+ff")]["max_tracking_error"] < 1e-3
    assert by[("optimal, 0.9 x torque", "PD+g")]["max_tracking_error"] < 0.1
    assert by[("optimal, |qdd| <= 5.6", "PD+g+ff")]["max_tracking_error"] > 0.3
    for T in (4, 5, 9):
        assert by[(f"uniform, {T} s", "PD+g")]["final_error"] > 0.5  # never reaches upright
    assert res_tau.duration < res_acc.duration
    assert res_mono.status.name == "INFEASIBLE"
    assert 0.0 <= by[("dense torque excess", "-")]["max_tracking_error"] < 1e-3  # N·m at N = 400


def test_talos_sway_keeps_its_feet_and_the_kinematic_timing_does_not():
    ns = runpy.run_path(str(EXAMPLES / "talos_sway.py"))
    out = ns["main"](["--grid", "40"])
    res, rows = out["result"], {r[0]: r for r in out["rows"]}
    assert res.status.name == "OPTIMAL"
    with_margins = rows["pathpace, contacts with margins"]
    # With the margins the motion needs only forces that exist, between the grid points too; the
    # solver's own (shrunk) cones are met up to the discretisation's small excess between points.
    assert with_margins[3]["worst"] > 0.0 and with_margins[3]["bad"] == 0.0
    assert with_margins[2]["worst"] > -1.0
    # Without margins it is faster and, between grid points, at (or just beyond) the edge of physics.
    no_margins = rows["pathpace, contacts, no margins"]
    assert no_margins[1] < with_margins[1] and no_margins[3]["worst"] < 0.5
    # Joint velocity and acceleration limits alone give a motion the feet cannot produce.
    kin = rows["velocity + acceleration limits"]
    assert kin[1] < no_margins[1] and kin[3]["bad"] > 0.5 and kin[3]["worst"] < -100.0


def test_rod_example_reproduces_the_papers_observations(capsys):
    sets = runpy.run_path(str(EXAMPLES / "rod_contact.py"))["main"]([])
    upright = sets[0.0]
    assert abs(upright.vertices[:, 0].max() - 9.81) < 1e-6  # no speed beyond ṡ² = g
    assert upright.contains(0.0, 0.0) and not sets[0.4].contains(0.0, 0.0)  # it can only stand near the vertical
    assert "0.00     4    9.810" in capsys.readouterr().out


@pytest.mark.parametrize("rise", [0.0, 0.1])
def test_humanoid_two_steps_with_contact_phases_keeps_its_feet(rise):
    """Level ground, and a step up onto a 10 cm platform."""
    out = runpy.run_path(str(EXAMPLES / "humanoid_steps.py"))["main"](["--rise", str(rise)])
    res, robot = out["result"], out["robot"]
    assert res.status.name == "OPTIMAL"
    assert [c.label for c in res.trajectory().contact_phases] == [f"phases[{i}]" for i in range(5)]
    for sole in ("left_sole_link", "right_sole_link"):  # both feet end on the platform
        assert robot.frame_placement(out["path"].q(5.0), sole)[2, 3] == pytest.approx(rise, abs=1e-9)
    # Touchdowns (s = 2, 4): the spline brings the swing foot down at ~7 mm per unit s, so the no-impact rule
    # stops the path there; lift-offs (s = 1, 3) keep their speed.
    k1, k2, k3, k4 = out["switches"]
    assert res.sdot[k2] == 0.0 and res.sdot[k4] == 0.0 and res.sdot[k1] > 1.0 and res.sdot[k3] > 1.0
    # Audit at 1001 times, each with its phase's contacts: the true cones (no margins) hold with at least
    # 0.5 N of cone weight to spare in every phase; the solver's shrunk cones (50 % friction margin, 10 N per
    # point) up to the discretisation's small excess between grid points.
    assert min(out["true_cone"]["worst_per_phase"]) > 0.5
    assert min(out["solver_cone"]["worst_per_phase"]) > -1.5
