"""Mimic joints (q_mimic = multiplier · q_joint + offset), against pinocchio's mimic support."""

import pickle
import re

import numpy as np
import pytest

import pathpace as pp
from pathpace.robots import example_robot_urdf

pin = pytest.importorskip("pinocchio")


def tree_with_mimics(n_joints, seed):
    """A random tree (revolute and prismatic joints, random axes, origins, inertias) in which some joints
    mimic a joint of the same type with a random multiplier and offset. The mimicked joint is an ancestor
    (pinocchio's mimic support needs it earlier in its depth-first order)."""
    rng = np.random.default_rng(seed)
    links = ['<link name="l0"><inertial><mass value="1.0"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial></link>']
    joints, kinds, parent_of = [], {}, {0: None}
    for i in range(1, n_joints + 1):
        parent = int(rng.integers(0, i))
        parent_of[i] = parent
        ancestors, link = set(), parent
        while link:  # links above the new joint, each the child of joint j<link>
            ancestors.add(f"j{link:02d}")
            link = parent_of[link]
        kind = str(rng.choice(["revolute", "revolute", "prismatic"]))
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        xyz, rpy, com = rng.uniform(-0.3, 0.3, 3), rng.uniform(-np.pi, np.pi, 3), rng.uniform(-0.2, 0.2, 3)
        L = rng.uniform(0.1, 1.0, (3, 3))
        I = L @ L.T + 0.01 * np.eye(3)
        links.append(
            f'<link name="l{i}"><inertial><origin xyz="{com[0]} {com[1]} {com[2]}"/><mass value="{rng.uniform(0.2, 3.0)}"/>'
            f'<inertia ixx="{I[0,0]}" ixy="{I[0,1]}" ixz="{I[0,2]}" iyy="{I[1,1]}" iyz="{I[1,2]}" izz="{I[2,2]}"/></inertial></link>')
        same = [j for j, k in kinds.items() if k == kind and j in ancestors]
        mimic = ""
        if same and rng.uniform() < 0.4:
            mimic = f'<mimic joint="{same[int(rng.integers(len(same)))]}" multiplier="{rng.uniform(-2, 2)}" offset="{rng.uniform(-0.5, 0.5)}"/>'
        else:
            kinds[f"j{i:02d}"] = kind
        joints.append(
            f'<joint name="j{i:02d}" type="{kind}"><parent link="l{parent}"/><child link="l{i}"/>'
            f'<origin xyz="{xyz[0]} {xyz[1]} {xyz[2]}" rpy="{rpy[0]} {rpy[1]} {rpy[2]}"/><axis xyz="{axis[0]} {axis[1]} {axis[2]}"/>'
            f'<limit lower="-3" upper="3" effort="50" velocity="2"/>{mimic}</joint>')
    return '<robot name="tree">' + "".join(links + joints) + "</robot>"


def compare(ours, theirs, links, seed, samples=4):
    data = theirs.createData()
    rng = np.random.default_rng(seed)
    assert ours.nq == theirs.nq == theirs.nv
    for _ in range(samples):
        q, qd, qdd = rng.uniform(-1.2, 1.2, (3, ours.nq))
        tau = pin.rnea(theirs, data, q, qd, qdd)
        np.testing.assert_allclose(ours.inverse_dynamics(q, qd, qdd), tau, rtol=1e-9, atol=1e-9 * np.abs(tau).max())
        # M column by column from pinocchio's RNEA (its CRBA fills M differently with mimic joints).
        z = np.zeros(ours.nq)
        M = np.column_stack([pin.rnea(theirs, data, q, z, e) - pin.rnea(theirs, data, q, z, z) for e in np.eye(ours.nq)])
        np.testing.assert_allclose(ours.mass_matrix(q), M, rtol=1e-9, atol=1e-9 * np.abs(M).max())
        np.testing.assert_allclose(ours.center_of_mass(q), pin.centerOfMass(theirs, data, q), atol=1e-12)
        # eq. (12) through the fused sweep (two samples per SIMD sweep, plus an odd tail).
        Q, D, DD = rng.uniform(-1, 1, (3, 3, ours.nq))
        a, b, c = ours.path_torque_coefficients(Q, D, DD)
        for k in range(3):
            np.testing.assert_allclose(a[k] + c[k], pin.rnea(theirs, data, Q[k], D[k], DD[k]), rtol=1e-9, atol=1e-8)
            z = np.zeros(ours.nq)
            np.testing.assert_allclose(b[k], pin.rnea(theirs, data, Q[k], z, D[k]) - pin.rnea(theirs, data, Q[k], z, z),
                                       rtol=1e-9, atol=1e-8)
        pin.forwardKinematics(theirs, data, q)
        pin.updateFramePlacements(theirs, data)
        for link in links:
            fid = theirs.getFrameId(link)
            np.testing.assert_allclose(ours.frame_placement(q, link), data.oMf[fid].homogeneous, atol=1e-12)
            J = pin.computeFrameJacobian(theirs, data, q, fid, pin.LOCAL_WORLD_ALIGNED)[:3]
            np.testing.assert_allclose(ours.point_jacobian(q, link), J, atol=1e-12)


def test_panda_with_its_finger_mimic_matches_pinocchio():
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    ours = pp.RobotModel.from_urdf(urdf)
    theirs = pin.buildModelFromUrdf(urdf, mimic=True)
    assert ours.mimic_joints == [("panda_finger_joint2", "panda_finger_joint1", 1.0, 0.0)]
    assert ours.joint_names == [f"panda_joint{i}" for i in range(1, 8)] + ["panda_finger_joint1"]
    compare(ours, theirs, ["panda_leftfinger", "panda_rightfinger", "panda_hand"], 0)


@pytest.mark.parametrize("seed", range(5))
def test_random_trees_with_mimics_match_pinocchio(seed):
    xml = tree_with_mimics(16, seed)
    ours = pp.RobotModel.from_urdf_string(xml)
    theirs = pin.buildModelFromXML(xml, mimic=True)
    assert len(ours.mimic_joints) >= 1
    assert ours.joint_names == [n for n in theirs.names[1:] if n not in {m[0] for m in ours.mimic_joints}]
    compare(ours, theirs, [f"l{i}" for i in (3, 9, 16)], seed)


def test_talos_grippers_mimic_joints_that_come_first():
    """Talos's gripper joints are mimicked by joints that precede them in depth-first order, which
    pinocchio 4.1 cannot load; locking the gripper joints (which fixes their mimics at multiplier · value
    + offset) must give the same kinematics and dynamics for the other joints."""
    urdf = str(example_robot_urdf("talos_data/robots/talos_full_v2.urdf"))
    free = pp.RobotModel.from_urdf(urdf, floating_base=True)
    assert len(free.mimic_joints) >= 8 and any(m[2] == -1.0 for m in free.mimic_joints)
    grippers = sorted({m[1] for m in free.mimic_joints})
    held = pp.RobotModel.from_urdf(urdf, floating_base=True, locked_joints={g: 0.4 for g in grippers})
    keep = [free.joint_names.index(n) for n in held.joint_names]
    rng = np.random.default_rng(4)
    q, qd, qdd = rng.uniform(-0.5, 0.5, (3, free.nq))
    for g in grippers:
        q[free.joint_names.index(g)] = 0.4
        qd[free.joint_names.index(g)] = qdd[free.joint_names.index(g)] = 0.0
    for link in ("gripper_left_fingertip_1_link", "gripper_right_fingertip_3_link", "left_sole_link"):
        np.testing.assert_allclose(free.frame_placement(q, link), held.frame_placement(q[keep], link), atol=1e-12)
        np.testing.assert_allclose(free.point_jacobian(q, link)[:, keep], held.point_jacobian(q[keep], link), atol=1e-12)
    np.testing.assert_allclose(free.inverse_dynamics(q, qd, qdd)[keep], held.inverse_dynamics(q[keep], qd[keep], qdd[keep]),
                               rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(free.center_of_mass(q), held.center_of_mass(q[keep]), atol=1e-12)


def test_locked_joint_fixes_its_mimic():
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    free = pp.RobotModel.from_urdf(urdf)
    held = pp.RobotModel.from_urdf(urdf, locked_joints={"panda_finger_joint1": 0.03})
    assert held.nq == 7 and held.mimic_joints == []
    q = np.random.default_rng(3).uniform(-1, 1, 7)
    qf = np.append(q, 0.03)
    for link in ("panda_leftfinger", "panda_rightfinger"):
        np.testing.assert_allclose(held.frame_placement(q, link), free.frame_placement(qf, link), atol=1e-14)
    np.testing.assert_allclose(held.gravity(q), free.gravity(qf)[:7], atol=1e-12)


def test_mimic_models_time_pickle_and_combine():
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    robot = pp.RobotModel.from_urdf(urdf)
    lo, hi = robot.position_limits
    w = lo + (hi - lo) * np.random.default_rng(0).uniform(0.2, 0.8, (4, 8))
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(w), grid=300)
    prob.add_velocity_limits(-robot.velocity_limits, robot.velocity_limits)
    prob.add_torque_limits(robot, scale=0.5)
    res = prob.solve()
    assert res.ok
    copy = pickle.loads(pickle.dumps(robot))
    assert copy.mimic_joints == robot.mimic_joints
    q, qd, qdd = np.random.default_rng(1).uniform(-1, 1, (3, 8))
    np.testing.assert_array_equal(copy.inverse_dynamics(q, qd, qdd), robot.inverse_dynamics(q, qd, qdd))
    box = pp.RobotModel.free_object("box", 2.0, com=(0, 0, 0.1), inertia=0.01 * np.eye(3))
    both = pp.RobotModel.combine([robot, box])
    assert both.nq == 14 and both.mimic_joints == robot.mimic_joints
    qb, qdb, qddb = np.random.default_rng(2).uniform(-1, 1, (3, 6))
    np.testing.assert_allclose(both.inverse_dynamics(np.append(q, qb), np.append(qd, qdb), np.append(qdd, qddb)),
                               np.append(robot.inverse_dynamics(q, qd, qdd), box.inverse_dynamics(qb, qdb, qddb)),
                               rtol=1e-12, atol=1e-12)


def mimic_urdf(target, second_mimic=""):
    return ('<robot name="m"><link name="a"/><link name="b"/><link name="c"/><link name="d"/>'
            '<joint name="j1" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
            '<joint name="j2" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>'
            f'<limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="{target}"/></joint>'
            '<joint name="j3" type="revolute"><parent link="c"/><child link="d"/><axis xyz="0 0 1"/>'
            f'<limit lower="-1" upper="1" effort="1" velocity="1"/>{second_mimic}</joint></robot>')


@pytest.mark.parametrize("xml, message", [
    (mimic_urdf("nowhere"), "joint 'j2' mimics 'nowhere', which is not a movable joint of robot 'm'"),
    (mimic_urdf("j1", '<mimic joint="j2"/>'), "joint 'j3' mimics 'j2', itself a mimic joint"),
])
def test_mimic_validation(xml, message):
    with pytest.raises(pp.InvalidInputError, match=re.escape(message)):
        pp.RobotModel.from_urdf_string(xml)
