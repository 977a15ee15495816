"""Contact phases (TimeScalingProblem.add_contact_phases): a hand that pushes a box, then brakes it (closed-form
discrete optimum, and single-phase problems on each piece), the no-impact rule, the Python API's validation,
contact forces per phase, pickling and restarts."""

import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from oracles import duration

DATA = Path(__file__).resolve().parents[1] / "data"
A = 5.0  # the hand's 10 N on hand + box (2 kg)


def hand_box():
    return pp.RobotModel.from_urdf(str(DATA / "hand_box.urdf"))


def on_box(nx):
    """The hand on the box: behind it (nx = +1, pushes) or in front (nx = -1, brakes)."""
    return [pp.Contact("box", point=(0, 0, 0), normal=(nx, 0, 0), friction=0.5, other_link="hand")]


def together(s0=0.0, s1=2.0):
    """Hand and box together, x = s on [s0, s1]."""
    s = np.linspace(s0, s1, 3)
    return pp.CubicSplinePath(np.column_stack([s, s]), knots=s)


def closed_form(grid, k):
    """θ = 2as up to the grid point before the switch k, constant over the two intervals at the switch (both
    stances hold there: s̈ >= 0 and s̈ <= 0), 2a(2 - s) after; T = Σ 2Δs / (ṡ_k + ṡ_{k+1})."""
    th = np.minimum(2 * A * grid, 2 * A * (2.0 - grid))
    th[k] = min(th[k - 1], th[k + 1])
    return duration(grid, th)


@pytest.fixture(scope="module")
def push_brake():
    prob = pp.TimeScalingProblem(together(), grid=20)
    prob.add_contact_phases(hand_box(), [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))], cone_edges=4)
    return prob, prob.solve()


def test_push_then_brake_is_the_closed_form_optimum_and_the_pieces_agree(push_brake):
    prob, res = push_brake
    assert res.status.name == "OPTIMAL"
    assert res.duration == pytest.approx(closed_form(prob.grid, 10), rel=1e-12)
    # Each piece as a single-phase problem (add_contacts), with the phased optimum's speed at the switch.
    v = res.sdot[10]
    T = 0.0
    for (s0, s1), nx, speeds in (((0.0, 1.0), 1, (0.0, v)), ((1.0, 2.0), -1, (v, 0.0))):
        piece = pp.TimeScalingProblem(together(s0, s1), grid=10)
        piece.add_contacts(hand_box(), on_box(nx), cone_edges=4)
        piece.set_boundary_speeds(*speeds)
        r = piece.solve()
        assert r.status.name == "OPTIMAL"
        T += r.duration
    assert T == pytest.approx(res.duration, rel=1e-12)
    # A switch off the grid (grid = 7: points at multiples of 2/7) is inserted.
    off = pp.TimeScalingProblem(together(), grid=7)
    off.add_contact_phases(hand_box(), [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))], cone_edges=4)
    assert off.grid.size == 9 and off.grid[4] == 1.0
    assert off.solve().duration == pytest.approx(closed_form(off.grid, 4), rel=1e-12)


def test_contact_forces_use_the_phase_at_each_time_the_later_one_at_a_switch(push_brake):
    prob, res = push_brake
    traj = res.trajectory()
    t_switch = res.times[10]
    t = np.array([0.1, t_switch, traj.duration - 0.1])
    cf = traj.contact_forces(t)
    assert list(cf.phase) == [0, 1, 1] and traj.contact_phase(t_switch) == 1
    assert cf.forces[:, 0, 0] == pytest.approx([5.0, 0.0, -5.0], abs=1e-6)  # push, nothing at s̈ = 0, brake
    assert [c.label for c in traj.contact_phases] == ["phases[0]", "phases[1]"]
    assert res.binding[3] == "phases[0]: torque hand_x upper" and res.binding[16] == "phases[1]: torque hand_x lower"
    # Pickled, the trajectory keeps its phases.
    again = pickle.loads(pickle.dumps(traj))
    assert list(again.contact_forces(t).phase) == [0, 1, 1]
    back = pickle.loads(pickle.dumps(res))
    assert back.trajectory().contact_phases[1].active_begin == 1.0
    assert back.binding == res.binding and len(res.binding) == len(res.s) - 1
    # plot.contacts_data lays the forces out over every contact of every phase (NaN where it does not hold).
    from pathpace.plot import contacts_data

    data = contacts_data(res, samples=4)  # t = 0, T/3, 2T/3, T
    assert data["forces"].shape == (4, 2, 3) and list(data["phase"]) == [0, 0, 1, 1]
    assert np.isnan(data["forces"][:2, 1]).all() and np.isnan(data["forces"][2:, 0]).all()
    assert data["forces"][1, 0, 0] == pytest.approx(5.0, abs=1e-6) and data["forces"][2, 1, 0] == pytest.approx(-5.0, abs=1e-6)
    # Phases with different numbers of contacts: NaN beyond a phase's own.
    p2 = pp.TimeScalingProblem(together(), grid=20)
    p2.add_contact_phases(hand_box(), [(0.0, 1.0, on_box(1) * 2), (1.0, 2.0, on_box(-1))], cone_edges=4)
    cf2 = p2.solve().trajectory().contact_forces(t)
    assert cf2.forces.shape == (3, 2, 3) and np.isnan(cf2.forces[2, 1]).all() and not np.isnan(cf2.forces[0]).any()


def test_restarted_and_continuous_keep_the_phases(push_brake):
    prob, res = push_brake
    tail = prob.restarted(prob.grid[5], res.sdot[5]).solve()
    assert tail.duration == pytest.approx(res.duration - res.times[5], rel=1e-12)
    cont = prob.solve(guarantee="continuous")
    assert cont.status.name == "OPTIMAL" and cont.duration == pytest.approx(res.duration, rel=1e-9)


def foot_problem(landing):
    """A foot comes down (z = 1 - s, arriving at speed) or lifts off (z = s - 1 after the switch) while an arm
    moves x = s; a kink at s = 1. Returns the problem with the ground contact in the phase after (landing)
    or before (lift-off)."""
    robot = pp.RobotModel.from_urdf(str(DATA / "foot_arm.urdf"))
    z, x = robot.joint_names.index("foot_z"), robot.joint_names.index("arm_x")
    coef = np.zeros((2, 2, 2))
    coef[:, 1, x] = 1.0
    coef[1, 0, x] = 1.0
    if landing:
        coef[0, :, z] = (1.0, -1.0)
    else:
        coef[1, 1, z] = 1.0
    path = pp.PiecewisePolynomialPath([0.0, 1.0, 2.0], coef)
    sole = [pp.Contact("foot", normal=(0, 0, 1))]
    ph = [(0.0, 1.0, []), (1.0, 2.0, sole)] if landing else [(0.0, 1.0, sole), (1.0, 2.0, [])]
    prob = pp.TimeScalingProblem(path, grid=20)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the foot moves in its free phase only; checked below
        prob.add_contact_phases(robot, ph)
    return prob, robot, path, ph


def test_a_contact_made_moving_along_its_normal_stops_the_path_breaking_does_not():
    prob, *_ = foot_problem(landing=True)
    res = prob.solve()
    assert res.status.name == "OPTIMAL"
    assert res.sdot[10] == 0.0 and res.sdot[9] > 0.1
    fs = prob.feasible_set(10)
    assert fs.x_max == 0.0 and fs.x_max_label.startswith("phases[1]: no impact: contact 0 (link 'foot') is made at s = 1")
    lift, *_ = foot_problem(landing=False)
    r = lift.solve()
    assert r.status.name == "OPTIMAL" and r.sdot[10] > 0.1
    assert all(c.rest_at_begin == "" for c in lift.constraints)


def test_drift_is_checked_per_phase():
    _, robot, path, ph = foot_problem(landing=True)
    prob = pp.TimeScalingProblem(path, grid=20)
    with pytest.raises(pp.InvalidInputError, match=r"phases\[0\]: contact 0 \(link 'foot'\) moves by 1 m"):
        prob.add_contact_phases(robot, [(0.0, 1.0, ph[1][2]), (1.0, 2.0, [])])
    assert prob.constraints == []
    with pytest.warns(UserWarning, match=r"phases\[0\]: contact 0 \(link 'foot'\) moves by 1 m"):
        prob.add_contact_phases(robot, [(0.0, 1.0, ph[1][2]), (1.0, 2.0, [])], drift="warn")
    assert [d["constraint"] for d in prob.solve().contact_drift] == ["phases[0]"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pp.TimeScalingProblem(path, grid=20).add_contact_phases(robot, ph)  # held only where it stays: no warning


def test_invalid_phases_are_named():
    prob = pp.TimeScalingProblem(together(), grid=20)
    robot = hand_box()
    ok = [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))]
    cases = [
        ([], r"^phases is empty, expected at least one \(s_begin, s_end, contacts\)$"),
        ([(0.0, 1.0, on_box(1)), (1.2, 2.0, on_box(-1))],
         r"^phases\[1\]\.s_begin = 1\.2 must equal phases\[0\]\.s_end = 1 \(the phases are contiguous\)$"),
        ([(0.0, 1.0, on_box(1)), (1.0, 1.5, on_box(-1))],
         r"^phases\[1\]\.s_end = 1\.5 must equal the path's s_end = 2 \(the phases cover the path\)$"),
        ([(0.0, 1.0, on_box(1)), (1.0, 2.0)], r"^phases\[1\] has 2 entries, expected a tuple \(s_begin, s_end, contacts\)"),
        ([ok[0], (1.0, 2.0, on_box(-1), {"friction_margn": 0.5})],
         r"^phases\[1\]\.options has key 'friction_margn', expected friction_margin, min_normal_force"),
        ([ok[0], (1.0, 2.0, on_box(-1), {"friction_margin": 1.5})], r"^phases\[1\]: friction_margin = 1\.5 must be in \[0, 1\)$"),
    ]
    for phases, msg in cases:
        with pytest.raises(pp.InvalidInputError, match=msg):
            prob.add_contact_phases(robot, phases)
    with pytest.raises(TypeError, match=r"phases\[0\]\.contacts\[0\] must be a pathpace\.Contact"):
        prob.add_contact_phases(robot, [(0.0, 2.0, [1.0])])
    with pytest.raises(pp.InvalidInputError, match=r"^impact_tolerance = -1 must be >= 0 and finite$"):
        prob.add_contact_phases(robot, ok, impact_tolerance=-1.0)
    assert prob.constraints == [] and prob.grid.size == 21
    # Per-phase margins: phase 0 must push with >= 1 N (s̈ >= 1), phase 1 brakes (s̈ <= 0): infeasible at the
    # switch, and the message names the phase.
    prob.add_contact_phases(robot, [(0.0, 1.0, on_box(1), {"min_normal_force": 1.0}), ok[1]])
    res = prob.solve()
    assert res.status.name == "INFEASIBLE" and res.infeasible_index == 10
    named = res.binding_constraints
    assert "phases[0]: minimum normal force at link 'box' point (0, 0, 0)" in named, res.message
    assert "phases[1]: friction at link 'box' point (0, 0, 0)" in named, res.message
