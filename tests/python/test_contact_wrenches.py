"""Trajectory.contact_wrenches / centers_of_pressure: per-link totals of the force distribution, against
pinocchio's centroidal dynamics (an independent oracle: the contact wrenches must supply the rate of the
robot's momentum), with centres of pressure inside each sole."""

import runpy
import sys
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import contact_corpus as cc  # noqa: E402

pin = pytest.importorskip("pinocchio")
EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def sway():
    h = cc.load("talos")
    path = cc.make_path(h, "sway")
    cons = cc.contacts(h, "sway", grid=(3, 3))  # 9 points per sole: interior points too
    prob = pp.TimeScalingProblem(path, grid=100)
    prob.add_contacts(h.robot, cons, cone_edges=8, min_normal_force=5.0, friction_margin=0.3, drift_tolerance=1e-4)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    return h, cons, res.trajectory()


def test_the_contact_wrenches_supply_the_rate_of_momentum_pinocchio_computes(sway):
    h, cons, traj = sway
    t = np.linspace(0.0, traj.duration, 157)
    w = traj.contact_wrenches(t)
    assert w.links == list(cc.HUMANOIDS["talos"]["soles"])
    assert w.force.shape == w.moment.shape == w.center_of_pressure.shape == (t.size, 2, 3)
    assert w.normal_force.shape == (t.size, 2)
    cf = traj.contact_forces(t)
    assert np.all(cf.feasible)
    # Per-link sums of the distribution's own forces.
    for l, link in enumerate(w.links):
        mine = [i for i, c in enumerate(cons) if c.link == link]
        assert np.allclose(w.force[:, l], cf.forces[:, mine].sum(axis=1), rtol=0, atol=1e-9)
        assert np.allclose(w.normal_force[:, l], cf.forces[:, mine, 2].sum(axis=1), rtol=0, atol=1e-9)
    # Newton-Euler about the centre of mass, by pinocchio: Σ F = m c̈ - m g, and Σ (M_o + (o - c) x F) = dh_G/dt
    # (angular), o each sole link's origin.
    model, data = h.model, h.model.createData()
    q, qd, qdd = traj.evaluate(t)
    weight = h.robot.mass * 9.81
    for i in range(t.size):
        qp, vp, ap = (np.empty(h.robot.nq) for _ in range(3))
        qp[h.perm], vp[h.perm], ap[h.perm] = q[i], qd[i], qdd[i]
        pin.computeCentroidalMomentumTimeVariation(model, data, qp, vp, ap)
        dh = data.dhg  # about the centre of mass, world axes
        c = data.com[0]
        grav = data.mass[0] * model.gravity.linear
        F = w.force[i].sum(axis=0)
        M = sum(w.moment[i, l] + np.cross(h.robot.frame_placement(q[i], link)[:3, 3] - c, w.force[i, l])
                for l, link in enumerate(w.links))
        assert np.allclose(F + grav, dh.linear, rtol=0, atol=1e-6 * weight)
        assert np.allclose(M, dh.angular, rtol=0, atol=1e-6 * weight)


def test_centres_of_pressure_lie_in_each_sole_and_weight_its_points(sway):
    h, cons, traj = sway
    t = np.linspace(0.0, traj.duration, 1001)
    cop = traj.centers_of_pressure(t)
    w = traj.contact_wrenches(t)
    np.testing.assert_array_equal(cop, w.center_of_pressure)
    q = traj.q(t)
    for l, link in enumerate(w.links):
        mine = [c for c in cons if c.link == link]
        assert np.all(w.normal_force[:, l] > 0)
        for i in range(0, t.size, 10):
            # The sole's points at that sample (the IK path keeps them to a few micrometres, not exactly): the
            # centre of pressure is in their box, on their plane.
            X = h.robot.frame_placement(q[i], link)
            pts = np.array([(X @ np.append(c.point, 1.0))[:3] for c in mine])
            assert np.all(cop[i, l, :2] >= pts[:, :2].min(axis=0) - 1e-9) and np.all(cop[i, l, :2] <= pts[:, :2].max(axis=0) + 1e-9)
            assert abs((cop[i, l] - X[:3, 3]) @ X[:3, 2]) < 1e-9  # in the sole's plane (points at z = 0 of the link)
    one = traj.contact_wrenches(0.5 * traj.duration)
    assert one.force.shape == (2, 3) and one.normal_force.shape == (2,)
    np.testing.assert_allclose(one.force, traj.contact_wrenches([0.5 * traj.duration]).force[0], rtol=0, atol=0)


@pytest.fixture(scope="module")
def steps():
    """examples/humanoid_steps.py: Talos steps, phases both, right, both, left, both."""
    out = runpy.run_path(str(EXAMPLES / "humanoid_steps.py"))["main"](["--grid", "50"])
    return out["result"].trajectory()


def test_the_wrenches_carry_the_margin_feasibility_and_phase_of_the_forces_they_sum(sway, steps):
    """ContactWrenches.margin / feasible / phase are those of contact_forces(t) at the same t, bit for bit: the
    verdict on the very forces summed, so a plot of the totals and their margin needs one evaluation."""
    for traj in (sway[2], steps):
        # Every grid time (the phase switches among them) and samples between.
        t = np.sort(np.concatenate([traj.times, np.linspace(0.0, traj.duration, 201)]))
        w, cf = traj.contact_wrenches(t), traj.contact_forces(t)
        assert w.margin.shape == w.feasible.shape == w.phase.shape == (t.size,)
        assert w.feasible.dtype == bool and np.issubdtype(w.phase.dtype, np.integer)
        np.testing.assert_array_equal(w.margin, cf.margin)
        np.testing.assert_array_equal(w.feasible, cf.feasible)
        np.testing.assert_array_equal(w.phase, cf.phase)
        np.testing.assert_array_equal(w.phase, traj.contact_phase(t))
        one, at = traj.contact_wrenches(t[7]), traj.contact_forces(t[7])
        assert (type(one.margin), type(one.feasible), type(one.phase)) == (float, bool, int)
        assert (one.margin, one.feasible, one.phase) == (at.margin, at.feasible, at.phase)
    # Not trivially equal: the sway has no phases, the steps visit all five, and the margins vary.
    assert np.all(sway[2].contact_wrenches([0.0, 1.0]).phase == -1)
    w = steps.contact_wrenches(np.linspace(0.0, steps.duration, 201))
    assert sorted(set(w.phase.tolist())) == [0, 1, 2, 3, 4] and np.ptp(w.margin) > 1.0 and np.all(w.feasible)


def test_a_phase_that_does_not_hold_a_link_gives_it_no_force(steps):
    traj = steps
    t = np.linspace(0.0, traj.duration, 301)
    w = traj.contact_wrenches(t)
    phase = traj.contact_phase(t)
    left, right = w.links.index("left_sole_link"), w.links.index("right_sole_link")
    # Phases: both, right, both, left, both (examples/humanoid_steps.py).
    assert np.all(w.force[phase == 1, left] == 0) and np.all(np.isnan(w.center_of_pressure[phase == 1, left]))
    assert np.all(w.force[phase == 3, right] == 0) and np.all(np.isnan(w.center_of_pressure[phase == 3, right]))
    assert np.all(w.normal_force[phase == 1, right] > 0) and np.all(np.isfinite(w.center_of_pressure[phase == 1, right]))


def test_without_contacts_it_says_so():
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    traj = pp.Trajectory(path, [0.0, 1.0], [1.0, 1.0])
    with pytest.raises(pp.Error, match="no contact constraint shaped this trajectory"):
        traj.contact_wrenches([0.0])


def test_a_robot_object_contact_pushes_both_ways_and_the_object_balances():
    """Talos sways with a box squeezed between its hands (a free object in the same model): the box is a
    contact link too; it receives the opposite of the hands' forces, and with nothing else touching it,
    its forces must carry its weight and accelerate it (the box's own Newton equation)."""
    h = cc.load("talos")
    robot, path, cons = cc.box_problem(h, mass=3.0)
    prob = pp.TimeScalingProblem(path, grid=60)
    prob.add_contacts(robot, cons, cone_edges=8, drift_tolerance=1e-4)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    traj = res.trajectory()
    t = np.linspace(0.0, traj.duration, 41)
    w = traj.contact_wrenches(t)
    assert w.links == ["left_sole_link", "right_sole_link", "arm_left_7_link", "box", "arm_right_7_link"]
    box, hands = w.links.index("box"), [w.links.index("arm_left_7_link"), w.links.index("arm_right_7_link")]
    np.testing.assert_allclose(w.force[:, box], -w.force[:, hands].sum(axis=1), rtol=0, atol=1e-9)
    # The box's centre (its first three coordinates, world) accelerates as its forces and gravity say.
    qdd = traj.qdd(t)
    acc = qdd[:, h.robot.nq:h.robot.nq + 3]
    np.testing.assert_allclose(w.force[:, box] + 3.0 * np.array([0, 0, -9.81]), 3.0 * acc, rtol=0, atol=1e-6 * 3.0 * 9.81)
    # Each hand's two points share a normal: a centre of pressure; the box's sides face two ways: none.
    assert np.all(np.isfinite(w.center_of_pressure[:, hands])) and np.all(np.isnan(w.center_of_pressure[:, box]))


def test_the_standups_centres_of_pressure_stay_in_their_soles_at_every_millisecond():
    """Issue 21's target on examples/humanoid_standup.py's plan (torque and contact limits, margins): at every
    1 kHz sample each sole carries weight and its centre of pressure lies in the box of its points, on their
    plane (a weighted mean of unilateral point forces: inside their hull whatever the distribution, which
    this checks end to end)."""
    ns = runpy.run_path(str(EXAMPLES / "humanoid_standup.py"))
    robot = ns["talos_sway"].load_talos()
    contacts = ns["talos_sway"].sole_contacts(4)
    _, res = ns["contact_timing"](robot, ns["standup_path"](robot), contacts, 100, ns["TORQUE_SCALE"], **ns["MARGINS"])
    assert res.status == pp.Status.OPTIMAL
    traj = res.trajectory()
    t = np.arange(0.0, traj.duration, 1e-3)
    w = traj.contact_wrenches(t)
    q = traj.q(t)
    for l, link in enumerate(w.links):
        assert np.all(w.normal_force[:, l] > 0)
        mine = [c for c in contacts if c.link == link]
        for i in range(t.size):
            X = robot.frame_placement(q[i], link)
            pts = np.array([(X @ np.append(c.point, 1.0))[:3] for c in mine])
            cop = w.center_of_pressure[i, l]
            assert np.all(cop[:2] >= pts[:, :2].min(axis=0) - 1e-9) and np.all(cop[:2] <= pts[:, :2].max(axis=0) + 1e-9)
            assert abs((cop - X[:3, 3]) @ X[:3, 2]) < 1e-9
