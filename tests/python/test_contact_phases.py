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


def phase_constraints(*stretches):
    """One ContactConstraint per (active_begin, active_end): the box pushed, then braked, alternately."""
    return [pp.ContactConstraint(hand_box(), on_box(1 if i % 2 == 0 else -1), cone_edges=4, active_begin=a, active_end=b)
            for i, (a, b) in enumerate(stretches)]


def test_contact_phase_of_s_takes_the_later_phase_at_a_switch_and_the_nearest_outside(push_brake):
    phases = phase_constraints((0.0, 1.0), (1.0, 2.0))
    tol = 1e-12  # the ends' tolerance at |s| <= 1 (relative beyond)
    s = np.array([-0.5, 0.0, 0.5, 1.0 - 1e-9, 1.0 - 0.4 * tol, 1.0, 1.0 + 0.4 * tol, 1.5, 2.0, 2.0 + 2.0 * tol, 3.0])
    np.testing.assert_array_equal(pp.contact_phase_of_s(phases, s), [0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1])
    assert pp.contact_phase_of_s(phases, 1.0) == 1 and type(pp.contact_phase_of_s(phases, 1.0)) is int
    # A gap between phases: the nearest, the later one on a tie (1.5 is 0.5 from both).
    gap = phase_constraints((0.0, 1.0), (2.0, 3.0))
    np.testing.assert_array_equal(pp.contact_phase_of_s(gap, [1.0 + 0.5 * tol, 1.4, 1.5, 1.6, 2.0 - 0.5 * tol]),
                                  [0, 0, 1, 1, 1])
    # One unbounded phase (a ContactConstraint's default stretch) holds everywhere.
    whole = [pp.ContactConstraint(hand_box(), on_box(1), cone_edges=4)]
    assert (whole[0].active_begin, whole[0].active_end) == (-np.inf, np.inf)
    np.testing.assert_array_equal(pp.contact_phase_of_s(whole, [-1e300, 0.0, 1e300]), [0, 0, 0])
    # Trajectory.contact_phase is this rule at s(t), on the trajectory's own phases (switch times included).
    prob, res = push_brake
    traj = res.trajectory()
    t = np.sort(np.concatenate([res.times, np.linspace(0.0, traj.duration, 101)]))
    np.testing.assert_array_equal(pp.contact_phase_of_s(traj.contact_phases, traj.s(t)[0]), traj.contact_phase(t))


def test_contact_phase_of_s_and_the_phase_stretch_validate_their_arguments():
    a, b = phase_constraints((0.0, 1.0), (1.0, 2.0))
    with pytest.raises(pp.InvalidInputError, match=r"^phases is empty, expected at least one ContactConstraint$"):
        pp.contact_phase_of_s([], [0.0])
    with pytest.raises(pp.InvalidInputError,
                       match=r"^phases\[1\]\.active_begin = 0 must be >= phases\[0\]\.active_begin = 1 \(phases in order of s\)$"):
        pp.contact_phase_of_s([b, a], [0.0])
    with pytest.raises(TypeError, match=r"^phases\[1\] must be a pathpace\.ContactConstraint, got None$"):
        pp.contact_phase_of_s([a, None], [0.0])
    with pytest.raises(pp.InvalidInputError, match=r"^s\[1\] = nan must be finite$"):
        pp.contact_phase_of_s([a, b], [0.5, np.nan])
    # The stretch a ContactConstraint holds on: kept, pickled, and checked.
    assert (b.active_begin, b.active_end) == (1.0, 2.0)
    again = pickle.loads(pickle.dumps(b))
    assert (again.active_begin, again.active_end) == (1.0, 2.0)
    cases = [(dict(active_begin=2.0, active_end=1.0), r"^active_begin = 2 must be <= active_end = 1$"),
             (dict(active_begin=np.nan), r"^active_begin = nan must be a number < inf$"),
             (dict(active_begin=np.inf), r"^active_begin = inf must be a number < inf$"),
             (dict(active_end=-np.inf), r"^active_end = -inf must be a number > -inf$")]
    for kw, msg in cases:
        with pytest.raises(pp.InvalidInputError, match=msg):
            pp.ContactConstraint(hand_box(), on_box(1), **kw)
    with pytest.raises(TypeError, match=r"^active_end must be a number, got str$"):
        pp.ContactConstraint(hand_box(), on_box(1), active_end="2")


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
