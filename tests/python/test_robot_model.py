"""Our rigid-body dynamics against pinocchio, and the robot's validation."""

import numpy as np
import pytest

import pathpace as pp
from pathpace.robots import example_robot_urdf

pin = pytest.importorskip("pinocchio")
from oracles import composite_floating_joint  # noqa: E402  (re-exported for test_contact*)


def random_tree_urdf(n_joints, seed):
    """A random tree: revolute, prismatic and fixed joints with random axes, origins and inertias."""
    rng = np.random.default_rng(seed)
    links = ['<link name="l0"><inertial><mass value="1.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>']
    joints = []
    for i in range(1, n_joints + 1):
        parent = int(rng.integers(0, i))
        kind = rng.choice(["revolute", "revolute", "prismatic", "fixed"])
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        xyz = rng.uniform(-0.3, 0.3, 3)
        rpy = rng.uniform(-np.pi, np.pi, 3)
        L = rng.uniform(0.1, 1.0, (3, 3))
        inertia = L @ L.T + 0.01 * np.eye(3)
        com = rng.uniform(-0.2, 0.2, 3)
        crpy = rng.uniform(-1, 1, 3)
        links.append(
            f'<link name="l{i}"><inertial><origin xyz="{com[0]} {com[1]} {com[2]}" rpy="{crpy[0]} {crpy[1]} {crpy[2]}"/>'
            f'<mass value="{rng.uniform(0.2, 3.0)}"/><inertia ixx="{inertia[0,0]}" ixy="{inertia[0,1]}" ixz="{inertia[0,2]}" '
            f'iyy="{inertia[1,1]}" iyz="{inertia[1,2]}" izz="{inertia[2,2]}"/></inertial></link>')
        limit = '<limit lower="-3" upper="3" effort="50" velocity="2"/>' if kind != "fixed" else ""
        joints.append(
            f'<joint name="j{i:02d}" type="{kind}"><parent link="l{parent}"/><child link="l{i}"/>'
            f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="{rpy[0]} {rpy[1]} {rpy[2]}"/>'
            f'<axis xyz="{axis[0]} {axis[1]} {axis[2]}"/>{limit}</joint>')
    return '<robot name="tree">' + "".join(links + joints) + "</robot>"


def models(name):
    if name == "panda":
        urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
        lock = {"panda_finger_joint1": 0.0, "panda_finger_joint2": 0.0}
        ours = pp.RobotModel.from_urdf(urdf, locked_joints=lock)
        full = pin.buildModelFromUrdf(urdf)
        theirs = pin.buildReducedModel(full, [full.getJointId(n) for n in lock], pin.neutral(full))
        return ours, theirs, "panda_hand"
    if name == "ur5":
        urdf = str(example_robot_urdf("ur_description/urdf/ur5_robot.urdf"))
        return pp.RobotModel.from_urdf(urdf), pin.buildModelFromUrdf(urdf), "tool0"
    if name == "talos":
        # Talos's grippers have mimic joints (tests/python/test_mimic.py); both models lock them at 0 here.
        urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
        import xml.etree.ElementTree as ET

        mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
        assert mimic
        ours = pp.RobotModel.from_urdf(urdf, floating_base=True, locked_joints={n: 0.0 for n in mimic})
        full = pin.buildModelFromUrdf(urdf, composite_floating_joint())
        theirs = pin.buildReducedModel(full, [full.getJointId(n) for n in mimic], pin.neutral(full))
        return ours, theirs, "left_sole_link"
    if name == "tree30":
        xml = random_tree_urdf(30, 7)
        return pp.RobotModel.from_urdf_string(xml), pin.buildModelFromXML(xml), "l17"
    raise KeyError(name)


def joint_order(model):
    names = []
    for i in range(1, model.njoints):
        if model.joints[i].shortname() == "JointModelComposite":
            names += ["floating_x", "floating_y", "floating_z", "floating_rz", "floating_ry", "floating_rx"]
        else:
            names.append(model.names[i])
    return names


@pytest.mark.parametrize("name", ["panda", "ur5", "talos", "tree30"])
def test_dynamics_match_pinocchio(name):
    ours, theirs, link = models(name)
    data = theirs.createData()
    assert ours.nq == theirs.nq
    assert ours.joint_names == joint_order(theirs)
    rng = np.random.default_rng(11)
    fid = theirs.getFrameId(link)
    for _ in range(4):
        q, qd, qdd = rng.uniform(-1.5, 1.5, (3, ours.nq))
        tau = pin.rnea(theirs, data, q, qd, qdd)
        np.testing.assert_allclose(ours.inverse_dynamics(q, qd, qdd), tau, rtol=1e-9, atol=1e-9 * np.abs(tau).max())
        M = pin.crba(theirs, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        np.testing.assert_allclose(ours.mass_matrix(q), M, rtol=1e-9, atol=1e-9 * np.abs(M).max())
        g = pin.computeGeneralizedGravity(theirs, data, q)
        np.testing.assert_allclose(ours.gravity(q), g, rtol=1e-9, atol=1e-9 * max(1.0, np.abs(g).max()))
        pin.forwardKinematics(theirs, data, q)
        pin.updateFramePlacements(theirs, data)
        np.testing.assert_allclose(ours.frame_placement(q, link), data.oMf[fid].homogeneous, atol=1e-12)
        point = rng.uniform(-0.2, 0.2, 3)
        J6 = pin.computeFrameJacobian(theirs, data, q, fid, pin.LOCAL)
        R = data.oMf[fid].rotation
        # Jacobian of a point fixed in the frame: v_p = R (v + ω × point) in LOCAL coordinates.
        Jp = R @ (J6[:3] - np.cross(point, J6[3:].T).T)
        np.testing.assert_allclose(ours.point_jacobian(q, link, point), Jp, atol=1e-11)


def test_path_torque_coefficients_reproduce_inverse_dynamics():
    ours, _, _ = models("panda")
    rng = np.random.default_rng(2)
    q, dq, ddq = rng.uniform(-1, 1, (3, 5, 7))
    a, b, c = ours.path_torque_coefficients(q, dq, ddq)
    for k in range(5):
        sd, sdd = rng.uniform(0.1, 2.0), rng.uniform(-3, 3)
        tau = ours.inverse_dynamics(q[k], dq[k] * sd, ddq[k] * sd**2 + dq[k] * sdd)
        np.testing.assert_allclose(a[k] * sd**2 + b[k] * sdd + c[k], tau, rtol=1e-12, atol=1e-10)


def test_pendulum_analytic():
    xml = PENDULUM
    r = pp.RobotModel.from_urdf_string(xml)
    for q, qd, qdd in [(0.3, 1.0, -2.0), (2.0, -0.5, 0.7)]:
        # point mass 1 kg at 1 m, rotating about y; q = 0 hangs straight down
        expected = 1.0 * qdd + 9.81 * np.sin(q)
        assert r.inverse_dynamics([q], [qd], [qdd])[0] == pytest.approx(expected, rel=1e-12)
    assert r.effort_limits[0] == 5.6


PENDULUM = """<robot name="pendulum">
  <link name="base"/>
  <link name="arm">
    <inertial><origin xyz="0 0 -1"/><mass value="1"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>
  </link>
  <joint name="hinge" type="continuous"><parent link="base"/><child link="arm"/><axis xyz="0 1 0"/>
    <limit effort="5.6" velocity="100"/></joint>
</robot>"""


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: pp.RobotModel.from_urdf_string("<robot"), r"urdf: the XML is not a valid URDF robot"),
        (lambda: pp.RobotModel.from_urdf("/nonexistent.urdf"), r"urdf file '/nonexistent.urdf' cannot be read"),
        (lambda: pp.RobotModel.from_urdf_string(PENDULUM, locked_joints={"elbow": 0.0}),
         r"locked_joints: 'elbow' is not a movable joint of robot 'pendulum'"),
        (lambda: pp.RobotModel.from_urdf_string(PENDULUM, gravity=[0, 0]), r"gravity has size 2, expected 3"),
        (lambda: pp.RobotModel.from_urdf_string(PENDULUM).inverse_dynamics([0, 0], [0], [0]),
         r"q has size 2, robot 'pendulum' has 1 joints"),
        (lambda: pp.RobotModel.from_urdf_string(PENDULUM).frame_placement([0], "hand"),
         r"link 'hand' is not a link of robot 'pendulum'"),
        (lambda: pp.TorqueLimits(pp.RobotModel.from_urdf_string(PENDULUM), tau_min=[1.0], tau_max=[0.0]),
         r"tau_min\[0\] = 1 must be <= tau_max\[0\] = 0"),
        (lambda: pp.TorqueLimits(pp.RobotModel.from_urdf_string(PENDULUM), scale=0.0), r"scale = 0 must be > 0"),
        (lambda: pp.TorqueLimits(pp.RobotModel.from_urdf_string(PENDULUM), margin=6.0),
         r"margin = 6 closes the torque range of joint 'hinge'"),
    ],
)
def test_robot_validation(make, message):
    with pytest.raises(pp.InvalidInputError, match=message):
        make()


def test_torque_limits_need_matching_path_dimension():
    r = pp.RobotModel.from_urdf_string(PENDULUM)
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(np.zeros((2, 2)) + [[0, 0], [1, 1]]), grid=10)
    with pytest.raises(pp.InvalidInputError, match=r"path has 2 coordinates, robot 'pendulum' has 1 joints"):
        prob.add_torque_limits(r)


def test_floating_base_without_contacts_cannot_be_timed_and_says_so():
    """Six unactuated coordinates make equality rows; nothing can hold the body up without contact."""
    robot = pp.RobotModel.from_urdf_string(PENDULUM, floating_base=True)
    assert robot.nq == 7 and list(robot.effort_limits[:6]) == [0.0] * 6
    wp = np.zeros((3, 7))
    wp[:, 6] = [0.0, 0.5, 1.0]
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(wp), grid=50)
    prob.add_torque_limits(robot)
    res = prob.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert any(c.startswith("torque floating_") for c in res.binding_constraints)
    np.testing.assert_allclose(robot.gravity_vector, [0, 0, -9.81])


def test_a_forced_torque_width_must_be_one_this_cpu_runs(monkeypatch):
    robot = pp.RobotModel.from_urdf(str(example_robot_urdf("panda_description/urdf/panda.urdf")))
    lo, hi = robot.position_limits
    path = pp.CubicSplinePath(lo + (hi - lo) * np.random.default_rng(3).uniform(0.2, 0.8, (4, robot.nq)))
    widest = pp._core._torque_lanes_supported()
    durations = {}
    for lanes in (1, 2, 4, 8):
        if lanes > widest:
            continue
        monkeypatch.setenv("PATHPACE_TORQUE_LANES", str(lanes))
        prob = pp.TimeScalingProblem(path, grid=100)  # 101 samples: a partial group of lanes at every width
        prob.add_torque_limits(robot, scale=0.5)
        res = prob.solve()
        assert res.ok, res.message
        durations[lanes] = res.duration
    # The lanes' own sin/cos (2 ulp of libm's) and FMA in the wide paths: equal to rounding, not to the bit.
    assert all(T == pytest.approx(durations[1], rel=1e-9) for T in durations.values()), durations
    for bad in (str(2 * widest), "3", "0", "eight"):
        monkeypatch.setenv("PATHPACE_TORQUE_LANES", bad)
        prob = pp.TimeScalingProblem(path, grid=13)
        with pytest.raises(pp.InvalidInputError, match=f"PATHPACE_TORQUE_LANES = '{bad}' must be a power of 2 <= {widest}"):
            prob.add_torque_limits(robot)
