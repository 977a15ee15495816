"""Free objects (sec. III.b), combined models and robot–robot contacts, against closed-form optima and
independent LPs (scipy's HiGHS) and dynamics (pinocchio)."""

import numpy as np
import pytest
from scipy.optimize import linprog

import pathpace as pp

G = 9.81

LIFTER = """<robot name="lifter">
 <link name="base"/>
 <link name="carriage"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="platform"><inertial><origin xyz="0 0 -0.05"/><mass value="2"/><inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>
 <link name="tray"/>
 <joint name="slide" type="prismatic"><parent link="base"/><child link="carriage"/><axis xyz="1 0 0"/><limit lower="-10" upper="10" velocity="100" effort="1000"/></joint>
 <joint name="lift" type="prismatic"><parent link="carriage"/><child link="platform"/><axis xyz="0 0 1"/><limit lower="-10" upper="10" velocity="100" effort="100"/></joint>
 <joint name="tray_fixed" type="fixed"><parent link="platform"/><child link="tray"/></joint>
</robot>"""

BOX_URDF = """<robot name="box"><link name="box"><inertial><origin xyz="0.01 -0.02 0.05"/><mass value="2"/>
<inertia ixx="0.011" ixy="0.001" ixz="-0.002" iyy="0.013" iyz="0.0005" izz="0.017"/></inertial></link></robot>"""
BOX_COM = [0.01, -0.02, 0.05]
BOX_INERTIA = [[0.011, 0.001, -0.002], [0.001, 0.013, 0.0005], [-0.002, 0.0005, 0.017]]
M_PLATFORM, M_CARRIAGE, M_BOX = 2.0, 1.0, 2.0


def lifter_with_box(com=BOX_COM):
    robot = pp.RobotModel.from_urdf_string(LIFTER)
    box = pp.RobotModel.free_object("box", M_BOX, com=com, inertia=BOX_INERTIA)
    return pp.RobotModel.combine([robot, box])


def box_corners(friction=0.5):
    """The box's four bottom corners on the platform; the normal (up) is in the platform's frame."""
    return [pp.Contact("box", point=[x, y, 0.0], normal=[0, 0, 1], friction=friction, other_link="platform")
            for x in (-0.1, 0.1) for y in (-0.1, 0.1)]


def carried_path(grid, axis):
    """The platform moves 1 m along `axis` (0: slide, 1: lift) and the box rides on it: q = (slide, lift,
    box x, y, z, rz, ry, rx)."""
    s = np.asarray(grid, dtype=float)
    q = np.zeros((len(s), 8))
    dq = np.zeros_like(q)
    q[:, axis] = s
    q[:, 2 + 2 * axis] = s  # box x follows the slide, box z the lift
    dq[:, axis] = 1.0
    dq[:, 2 + 2 * axis] = 1.0
    return pp.SampledPath(s, q, dq, np.zeros_like(q))


def test_free_object_matches_the_same_body_from_urdf():
    """A free object is the floating-base model of a one-link URDF (itself checked against pinocchio)."""
    obj = pp.RobotModel.free_object("box", 2.0, com=BOX_COM, inertia=BOX_INERTIA)
    ref = pp.RobotModel.from_urdf_string(BOX_URDF, floating_base=True)
    assert obj.nq == 6 and obj.joint_names == ref.joint_names and obj.link_names == ["box"]
    assert np.all(obj.effort_limits == 0.0)
    rng = np.random.default_rng(3)
    for _ in range(5):
        q, qd, qdd = rng.normal(size=(3, 6))
        tau = obj.inverse_dynamics(q, qd, qdd)
        np.testing.assert_allclose(tau, ref.inverse_dynamics(q, qd, qdd), rtol=1e-12, atol=1e-12)
        assert np.max(np.abs(tau)) > 1.0
        np.testing.assert_allclose(obj.mass_matrix(q), ref.mass_matrix(q), rtol=1e-12, atol=1e-12)


def test_free_object_matches_pinocchio():
    pin = pytest.importorskip("pinocchio")
    from test_robot_model import composite_floating_joint

    model = pin.buildModelFromXML(BOX_URDF, composite_floating_joint())
    data = model.createData()
    obj = pp.RobotModel.free_object("box", 2.0, com=BOX_COM, inertia=BOX_INERTIA)
    rng = np.random.default_rng(4)
    for _ in range(5):
        q, qd, qdd = rng.normal(size=(3, 6))
        np.testing.assert_allclose(obj.inverse_dynamics(q, qd, qdd), pin.rnea(model, data, q, qd, qdd), rtol=1e-9, atol=1e-10)


def test_combined_model_is_its_parts_side_by_side():
    robot = pp.RobotModel.from_urdf_string(LIFTER)
    box = pp.RobotModel.free_object("box", 2.0, com=BOX_COM, inertia=BOX_INERTIA)
    both = pp.RobotModel.combine([robot, box])
    assert both.nq == 8 and both.name == "lifter+box"
    assert both.joint_names[:2] == ["slide", "lift"] and both.joint_names[2] == "floating_x"
    np.testing.assert_array_equal(both.effort_limits, np.concatenate([robot.effort_limits, box.effort_limits]))
    rng = np.random.default_rng(5)
    q, qd, qdd = rng.normal(size=(3, 8))
    tau = both.inverse_dynamics(q, qd, qdd)
    np.testing.assert_allclose(tau[:2], robot.inverse_dynamics(q[:2], qd[:2], qdd[:2]), rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(tau[2:], box.inverse_dynamics(q[2:], qd[2:], qdd[2:]), rtol=1e-13, atol=1e-13)
    M = both.mass_matrix(q)
    assert np.all(M[:2, 2:] == 0.0)
    np.testing.assert_allclose(both.frame_placement(q, "box"), box.frame_placement(q[2:], "box"), atol=1e-14)
    # Two floating parts: the shared virtual joint names are qualified by part.
    two = pp.RobotModel.combine([box, pp.RobotModel.free_object("ball", 1.0)], name="pair")
    assert two.name == "pair" and two.joint_names[0] == "box/floating_x" and two.joint_names[6] == "ball/floating_x"


def test_combine_and_free_object_validation():
    box = pp.RobotModel.free_object("box", 1.0)
    with pytest.raises(pp.InvalidInputError, match=r"parts is empty"):
        pp.RobotModel.combine([])
    with pytest.raises(pp.InvalidInputError, match=r"parts\[1\] \('box'\) has a link 'box' that an earlier part also has"):
        pp.RobotModel.combine([box, box])
    moon = pp.RobotModel.free_object("rock", 1.0, gravity=[0, 0, -1.62])
    with pytest.raises(pp.InvalidInputError, match=r"parts\[1\] \('rock'\) has gravity \(0, 0, -1.62\).*must agree"):
        pp.RobotModel.combine([box, moon])
    with pytest.raises(pp.InvalidInputError, match=r"mass = 0 must be > 0"):
        pp.RobotModel.free_object("b", 0.0)
    with pytest.raises(pp.InvalidInputError, match=r"mass = nan must be > 0"):
        pp.RobotModel.free_object("b", float("nan"))
    with pytest.raises(pp.InvalidInputError, match=r"inertia must be symmetric"):
        pp.RobotModel.free_object("b", 1.0, inertia=[[1, 0.5, 0], [0, 1, 0], [0, 0, 1]])
    with pytest.raises(pp.InvalidInputError, match=r"inertia has eigenvalue -1: it must be positive semi-definite"):
        pp.RobotModel.free_object("b", 1.0, inertia=np.diag([1.0, -1.0, 1.0]))
    with pytest.raises(pp.InvalidInputError, match=r"inertia has shape \(2, 2\), expected \(3, 3\)"):
        pp.RobotModel.free_object("b", 1.0, inertia=np.eye(2))
    with pytest.raises(pp.InvalidInputError, match=r"com has size 2, expected 3"):
        pp.RobotModel.free_object("b", 1.0, com=[0, 0])
    with pytest.raises(pp.InvalidInputError, match=r"name must not be empty"):
        pp.RobotModel.free_object("", 1.0)


@pytest.mark.parametrize("margin", [0.0, 0.2])
def test_sliding_a_box_on_a_platform_is_friction_limited(margin):
    """The platform carries the box 1 m sideways: the box follows only by friction, so |a| <= μ' g with
    μ' = μ (1 - margin) (the 4-edge cone is exact along x), and the optimum is bang-bang,
    T = 2 sqrt(D / (μ' g)) — exact on a grid through the switch at s = 1/2."""
    model = lifter_with_box()
    grid = np.linspace(0.0, 1.0, 41)
    prob = pp.TimeScalingProblem(carried_path(grid, 0), grid=grid)
    prob.add_contacts(model, box_corners(0.5), cone_edges=4, friction_margin=margin)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    a = 0.5 * (1 - margin) * G
    assert res.duration == pytest.approx(2.0 * np.sqrt(1.0 / a), rel=1e-9)
    # Between the grid points the forces exist (margin >= 0 up to the LP tolerance) and the four corner
    # forces add up to the box's m (a, 0, g).
    traj = res.trajectory()
    t = np.linspace(0.0, res.duration, 37)
    cf = traj.contact_forces(t)
    assert cf.forces.shape == (37, 4, 3) and np.all(cf.feasible)
    assert np.min(cf.margin) >= -1e-8
    _, _, sdd = traj.s(t)
    total = cf.forces.sum(axis=1)
    np.testing.assert_allclose(total[:, 0], M_BOX * sdd, atol=1e-7)
    np.testing.assert_allclose(total[:, 2], M_BOX * G, rtol=1e-9)
    # The platform's slide force moves the carriage, the platform and the box.
    np.testing.assert_allclose(cf.torques[:, 0], (M_CARRIAGE + M_PLATFORM + M_BOX) * sdd, atol=1e-7)
    assert np.max(np.abs(cf.torques[:, 2:])) < 1e-8  # the box is unactuated


def test_lifting_a_box_is_limited_by_the_motor_up_and_by_the_normal_force_down():
    """Lift 1 m: upward the lift's 100 N moves carriage-free mass m = platform + box, a_up = F/m - g;
    downward the box must keep 4 x f_min of normal force, a_down = g - 4 f_min / m_box (its centre of
    mass above the middle of the corners, so that all four can be on the minimum at once). Bang-bang
    with the switch at s* = a_down / (a_up + a_down), on the grid."""
    f_min = 1.5
    a_up = 100.0 / (M_PLATFORM + M_BOX) - G
    a_down = G - 4 * f_min / M_BOX
    s_switch = a_down / (a_up + a_down)
    grid = np.unique(np.concatenate([np.linspace(0.0, 1.0, 51), [s_switch]]))
    model = lifter_with_box(com=[0.0, 0.0, 0.05])
    prob = pp.TimeScalingProblem(carried_path(grid, 1), grid=grid)
    prob.add_contacts(model, box_corners(), cone_edges=4, min_normal_force=f_min)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    assert res.duration == pytest.approx(np.sqrt(2.0 * (a_up + a_down) / (a_up * a_down)), rel=1e-9)
    cf = res.trajectory().contact_forces(res.duration * 0.99)
    assert cf.forces.shape == (4, 3)
    np.testing.assert_allclose(cf.forces[:, 2], f_min, rtol=1e-7)  # decelerating: on the minimum


def test_robot_robot_contact_validation_and_drift():
    model = lifter_with_box()
    grid = np.linspace(0.0, 1.0, 5)
    prob = pp.TimeScalingProblem(carried_path(grid, 0), grid=grid)
    with pytest.raises(pp.InvalidInputError, match=r"link 'shelf' is not a link of robot 'lifter\+box'"):
        prob.add_contacts(model, [pp.Contact("box", other_link="shelf")])
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\].other_link = 'box' must differ from its link"):
        prob.add_contacts(model, [pp.Contact("box", other_link="box")])
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\]: links 'tray' and 'platform' are rigidly attached"):
        prob.add_contacts(model, [pp.Contact("tray", other_link="platform")])
    # The box slides relative to the platform when only the platform moves: the contact does not hold.
    s = grid
    q = np.zeros((5, 8))
    q[:, 0] = s
    dq = np.zeros_like(q)
    dq[:, 0] = 1.0
    slipping = pp.SampledPath(s, q, dq, np.zeros_like(q))
    prob = pp.TimeScalingProblem(slipping, grid=s)
    with pytest.raises(pp.InvalidInputError, match=r"contact 0 \(link 'box'\) moves by 1 m \(farthest at s = 1;"):
        prob.add_contacts(model, box_corners())
    with pytest.warns(UserWarning, match=r"contact 0 \(link 'box'\) moves by 1 m"):
        prob.add_contacts(model, box_corners(), drift="warn")
    c = pp.ContactConstraint(model, box_corners())
    assert c.contacts[0].other_link == "platform" and pp.Contact("box").other_link is None
    assert c.max_drift(slipping, s) == (pytest.approx(1.0), 0)


def test_force_distribution_margin_matches_highs():
    """The margin LP solved by pathpace equals the same LP written out here and solved by HiGHS, at
    random states of the box on the tilted, moving platform."""
    model = lifter_with_box()
    k = 5
    contacts = box_corners(0.6)
    c = pp.ContactConstraint(model, contacts, cone_edges=k, min_normal_force=0.5)
    rng = np.random.default_rng(11)
    checked_negative = checked_positive = 0
    for _ in range(12):
        q = np.zeros(8)
        q[:2] = rng.uniform(-0.5, 0.5, 2)
        q[2], q[4] = q[0], q[1]
        qd, qdd = np.zeros(8), np.zeros(8)
        qd[[0, 2]] = rng.normal()
        qdd[[0, 2]] = rng.uniform(-8, 8)
        qdd[[1, 4]] = rng.uniform(-12, 6)
        out = c.force_distribution(q, qd, qdd)
        # Independent LP over (λ, δ): max δ, λ_ie >= δ, Σ_e λ_ie - f_min >= δ, τ_L <= τ_id - Σ JᵀGλ <= τ_U.
        tau = model.inverse_dynamics(q, qd, qdd)
        cols = []
        for con in contacts:
            J = model.point_jacobian(q, "box", con.point)  # the platform does not rotate: its Jacobian at the
            J -= model.point_jacobian(q, "platform", model.frame_placement(q, "box")[:3, :3] @ con.point
                                      + model.frame_placement(q, "box")[:3, 3] - model.frame_placement(q, "platform")[:3, 3])
            phis = 2 * np.pi * np.arange(k) / k
            t1, t2 = np.array([0.0, 1.0, 0.0]), np.array([-1.0, 0.0, 0.0])
            Gm = np.array([0, 0, 1.0])[:, None] + con.friction * (np.cos(phis) * t1[:, None] + np.sin(phis) * t2[:, None])
            cols.append(-J.T @ Gm)
        A = np.hstack(cols)
        n, mk = 8, 4 * k
        lo, hi = -model.effort_limits - tau, model.effort_limits - tau
        act = lo != hi
        A_eq, b_eq = A[~act], lo[~act]
        A_ub = [np.hstack([A[act], np.zeros((act.sum(), 1))]), np.hstack([-A[act], np.zeros((act.sum(), 1))])]
        b_ub = [hi[act], -lo[act]]
        A_ub.append(np.hstack([-np.eye(mk), np.ones((mk, 1))]))  # δ - λ <= 0
        b_ub.append(np.zeros(mk))
        A_ub.append(np.hstack([-np.kron(np.eye(4), np.ones(k)), np.ones((4, 1))]))  # δ - Σλ <= -f_min
        b_ub.append(-0.5 * np.ones(4))
        obj = np.zeros(mk + 1)
        obj[-1] = -1.0
        r = linprog(obj, A_ub=np.vstack(A_ub), b_ub=np.concatenate(b_ub), A_eq=np.hstack([A_eq, np.zeros((len(b_eq), 1))]),
                    b_eq=b_eq, bounds=[(None, None)] * mk + [(None, 1e6)], method="highs")
        assert r.status == 0
        assert out.feasible
        assert out.margin == pytest.approx(-r.fun, rel=1e-7, abs=1e-7)
        checked_negative += out.margin < -1e-3
        checked_positive += out.margin > 1e-3
        # The reported forces and torques are consistent: τ = τ_id - Σ J_iᵀ f_i.
        assert np.max(np.abs(out.torques[2:])) < 1e-8
    assert checked_negative and checked_positive


def test_a_box_that_no_contact_can_hold_is_reported_where_and_why():
    """The corners' normals point down (the platform would have to pull the box): no contact forces
    balance the box at any speed, and the solver says so at the first grid point."""
    model = lifter_with_box()
    grid = np.linspace(0.0, 1.0, 11)
    prob = pp.TimeScalingProblem(carried_path(grid, 0), grid=grid)
    upside_down = [pp.Contact("box", point=c.point, normal=[0, 0, -1], friction=0.5, other_link="platform") for c in box_corners()]
    prob.add_contacts(model, upside_down, cone_edges=4)
    assert prob.feasible_set(5).empty
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE and not res.ok
    assert res.infeasible_index == 0 and res.infeasible_s == 0.0
    assert "contact forces cannot balance the robot" in res.binding_constraints
    assert "contact forces cannot balance the robot" in res.message
    with pytest.raises(pp.Error, match=r"no trajectory: the solve ended with status infeasible"):
        res.trajectory()
