"""The Python API's conveniences: bool(result), traj(t, order), os.PathLike, scipy's "clamped",
pickling, the centre of mass (against pinocchio) and boundary conditions in joint velocities."""

import pathlib
import pickle
import re

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem, two_joint_problem
from pathpace.robots import example_robot_urdf

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"
PANDA_LOCK = {"panda_finger_joint1": 0.0, "panda_finger_joint2": 0.0}


def too_weak_pendulum():
    """Motors far too weak to hold the pendulum up at 1-2 rad from hanging: no timing exists."""
    robot = pp.RobotModel.from_urdf(DATA / "pendulum.urdf")
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(np.array([[1.0], [2.0]])), grid=50)
    prob.add_torque_limits(robot, tau_min=[-0.01], tau_max=[0.01])
    return prob


def test_result_bool_is_ok():
    res = two_joint_problem().solve()
    assert res.ok and bool(res)
    bad = too_weak_pendulum().solve()
    assert bad.status == pp.Status.INFEASIBLE
    assert not bad.ok and not bool(bad)


def test_trajectory_call_matches_q_qd_qdd():
    traj = two_joint_problem().solve().trajectory()
    t = np.linspace(0, traj.duration, 37)
    np.testing.assert_array_equal(traj(t), traj.q(t))
    np.testing.assert_array_equal(traj(t, 1), traj.qd(t))
    np.testing.assert_array_equal(traj(t, order=2), traj.qdd(t))
    assert traj(0.1).shape == (2,)
    with pytest.raises(pp.InvalidInputError, match=r"order = 3 must be 0, 1 or 2"):
        traj(t, 3)


def test_from_urdf_takes_pathlike():
    a = pp.RobotModel.from_urdf(DATA / "pendulum.urdf")
    b = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    assert a.joint_names == b.joint_names
    with pytest.raises(pp.InvalidInputError, match="cannot be read"):
        pp.RobotModel.from_urdf(DATA / "missing.urdf")


def test_clamped_without_derivatives_is_scipys_clamped():
    from scipy.interpolate import CubicSpline

    rng = np.random.default_rng(3)
    for K in (2, 3, 5, 9):
        w = rng.normal(size=(K, 3))
        path = pp.CubicSplinePath(w, boundary="clamped")
        ref = CubicSpline(np.linspace(0, 1, K), w, bc_type="clamped")
        s = np.linspace(0, 1, 101)
        np.testing.assert_allclose(path.q(s), ref(s), atol=1e-12)
        np.testing.assert_allclose(path.dq(s), ref(s, 1), atol=1e-10)
        np.testing.assert_array_equal(path.start_derivative, np.zeros(3))
        assert path.boundary == "clamped"
    # Explicit slopes are still used.
    d0, d1 = np.array([1.0, 0, 0]), np.array([0, 2.0, 0])
    path = pp.CubicSplinePath(w, boundary="clamped", start_derivative=d0, end_derivative=d1)
    np.testing.assert_allclose(path.dq(0.0), d0, atol=1e-12)
    np.testing.assert_allclose(path.dq(1.0), d1, atol=1e-12)


def roundtrip(obj):
    return pickle.loads(pickle.dumps(obj))


def test_paths_pickle_to_identical_paths():
    rng = np.random.default_rng(5)
    s = np.linspace(0, 1, 53)
    paths = [
        pp.CubicSplinePath(rng.normal(size=(6, 3)), knots="chord", boundary="natural", s_begin=0.2, s_end=0.9),
        pp.CubicSplinePath(rng.normal(size=(4, 2)), boundary="clamped", start_derivative=[1, 2], end_derivative=[0, 1]),
        pp.PiecewisePolynomialPath([0.0, 0.5, 1.0], rng.normal(size=(2, 4, 3))),
        pp.SampledPath(np.linspace(0, 1, 7), rng.normal(size=(7, 2)), rng.normal(size=(7, 2)), rng.normal(size=(7, 2))),
    ]
    for p in paths:
        q = roundtrip(p)
        assert type(q) is type(p)
        x = np.linspace(p.s_begin, p.s_end, 53)
        for a, b in zip(p.evaluate(x), q.evaluate(x)):
            # Spline and polynomial copies are rebuilt by the same arithmetic (bit-equal); a sampled path's
            # last sample is re-evaluated, so its last piece may differ in the last bits.
            np.testing.assert_allclose(a, b, rtol=1e-11, atol=1e-12)
    assert s.size == 53


def test_robot_models_pickle_to_identical_models():
    panda = pp.RobotModel.from_urdf(example_robot_urdf("panda_description/urdf/panda.urdf"), locked_joints=PANDA_LOCK)
    box = pp.RobotModel.free_object("box", 2.0, com=(0, 0, 0.05), inertia=0.01 * np.eye(3))
    both = pp.RobotModel.combine([panda, box], name="panda_box")
    rng = np.random.default_rng(2)
    rod = pp.RobotModel.from_urdf(DATA / "rod.urdf", floating_base=True, gravity=(0.1, 0, -9.7))
    for r in (panda, box, both, rod):
        c = roundtrip(r)
        assert (c.name, c.joint_names, c.link_names) == (r.name, r.joint_names, r.link_names)
        np.testing.assert_array_equal(c.effort_limits, r.effort_limits)
        np.testing.assert_array_equal(c.gravity_vector, r.gravity_vector)
        q, qd, qdd = rng.uniform(-1, 1, (3, r.nq))
        np.testing.assert_array_equal(c.inverse_dynamics(q, qd, qdd), r.inverse_dynamics(q, qd, qdd))


def test_problems_results_trajectories_pickle():
    robot = pp.RobotModel.from_urdf(DATA / "pendulum.urdf")
    path = pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]]), boundary="clamped")
    prob = kinematic_problem(path, 300, [-4], [4], [-20], [20])
    prob.add_torque_limits(robot, scale=0.9, margin=0.1)
    N = 301
    prob.add_linear_constraint(np.ones((N, 1)), np.zeros((N, 1)), np.zeros((N, 1)), np.full((N, 1), -np.inf),
                               np.full((N, 1), 3.0), label="cap")
    prob.set_boundary_speeds(0.1, 0.0)
    copy = roundtrip(prob)
    assert [c.name for c in copy.constraints] == [c.name for c in prob.constraints]
    assert (copy.sdot_begin, copy.sdot_end) == (0.1, 0.0)
    np.testing.assert_array_equal(copy.grid, prob.grid)
    res, res2 = prob.solve(), copy.solve()
    assert res.ok and res2.ok
    assert res2.duration == res.duration
    np.testing.assert_array_equal(res2.sdot, res.sdot)

    r = roundtrip(res)
    assert (r.status, r.duration, r.message, r.stats) == (res.status, res.duration, res.message, res.stats)
    np.testing.assert_array_equal(r.sdot, res.sdot)
    t = np.linspace(0, res.duration, 41)
    traj = res.trajectory()
    np.testing.assert_array_equal(r.trajectory().qdd(t), traj.qdd(t))
    tr = roundtrip(traj)
    np.testing.assert_array_equal(tr.q(t), traj.q(t))
    np.testing.assert_allclose(tr.torques(t), traj.torques(t), rtol=0, atol=1e-12)  # the robot came along

    bad = roundtrip(too_weak_pendulum().solve())
    assert bad.status == pp.Status.INFEASIBLE and bad.infeasible_index >= 0 and bad.binding_constraints


def test_contact_constraint_pickles():
    robot = pp.RobotModel.free_object("box", 1.0)
    contacts = [pp.Contact("box", point=(x, y, 0), normal=(0, 0, 1), friction=0.6)
                for x in (-0.1, 0.1) for y in (-0.1, 0.1)]
    c = pp.ContactConstraint(robot, contacts, cone_edges=6, friction_margin=0.2, min_normal_force=0.5)
    d = roundtrip(c)
    assert [x.link for x in d.contacts] == ["box"] * 4
    q = np.zeros((3, 6))
    qdd = np.zeros((3, 6))
    qdd[:, 0] = [0.0, 1.0, 7.0]  # x-acceleration: within, near and beyond friction
    a, b = c.force_distribution(q, q, qdd), d.force_distribution(q, q, qdd)
    np.testing.assert_allclose(b.margin, a.margin, atol=1e-9)


def test_center_of_mass_matches_pinocchio():
    pin = pytest.importorskip("pinocchio")
    urdf = str(example_robot_urdf("panda_description/urdf/panda.urdf"))
    ours = pp.RobotModel.from_urdf(urdf, locked_joints=PANDA_LOCK)
    full = pin.buildModelFromUrdf(urdf)
    theirs = pin.buildReducedModel(full, [full.getJointId(n) for n in PANDA_LOCK], pin.neutral(full))
    data = theirs.createData()
    rng = np.random.default_rng(17)
    for _ in range(10):
        q = rng.uniform(-2, 2, ours.nq)
        np.testing.assert_allclose(ours.center_of_mass(q), pin.centerOfMass(theirs, data, q), atol=1e-12)
    assert ours.mass == pytest.approx(data.mass[0], rel=1e-12)
    with pytest.raises(pp.InvalidInputError, match=r"q has size 3, robot 'panda' has 7 joints"):
        ours.center_of_mass(np.zeros(3))


def test_boundary_velocities_set_speeds_along_the_tangent():
    prob = two_joint_problem()
    d0, d1 = prob.path.dq(0.0), prob.path.dq(1.0)
    prob.set_boundary_velocities(0.2 * d0, 0.1 * d1)
    assert prob.sdot_begin == pytest.approx(0.2, rel=1e-12)
    assert prob.sdot_end == pytest.approx(0.1, rel=1e-12)
    res = prob.solve()
    assert res.ok
    traj = res.trajectory()
    np.testing.assert_allclose(traj(0.0, 1), 0.2 * d0, rtol=1e-12)
    np.testing.assert_allclose(traj(traj.duration, 1), 0.1 * d1, rtol=1e-12)
    prob.set_boundary_velocities(np.zeros(2), np.zeros(2))
    assert (prob.sdot_begin, prob.sdot_end) == (0.0, 0.0)
    off = 0.3 * d0 + np.array([0.0, 0.05])
    with pytest.raises(pp.InvalidInputError, match=re.escape("qd_begin[") + r".* must be a non-negative multiple of the path tangent"):
        prob.set_boundary_velocities(off, np.zeros(2))
    with pytest.raises(pp.InvalidInputError, match=r"qd_end\[\d\] = .* non-negative multiple"):
        prob.set_boundary_velocities(np.zeros(2), -0.2 * d1)  # backwards along the path
    with pytest.raises(pp.InvalidInputError, match=r"qd_begin has size 3, expected 2"):
        prob.set_boundary_velocities(np.zeros(3), np.zeros(2))
    clamped = two_joint_problem(boundary="clamped")  # p'(0) = 0: only q̇ = 0 is possible
    with pytest.raises(pp.InvalidInputError, match=r"the path does not move at s = 0"):
        clamped.set_boundary_velocities([0.1, 0.0], np.zeros(2))


def test_every_public_class_and_method_has_a_docstring():
    import inspect

    missing = []
    for name in pp.__all__:
        obj = getattr(pp, name)
        if not inspect.isclass(obj) or obj.__module__ != "pathpace._core" or issubclass(obj, Exception):
            continue
        if name != "Status" and ("Parameters" not in (obj.__doc__ or "") and "Attributes" not in (obj.__doc__ or "")):
            missing.append(name)
        for attr, member in vars(obj).items():
            if attr.startswith("_") or isinstance(member, property):
                continue
            doc = getattr(obj, attr).__doc__ or ""
            text = doc.split("\n", 1)[1].strip() if "\n" in doc else ""  # after pybind11's signature line
            if not text:
                missing.append(f"{name}.{attr}")
    assert missing == []


def top_level_split(text):
    """Splits a signature's parameter list at commas outside brackets and quotes."""
    out, depth, quote, cur = [], 0, None, ""
    for ch in text:
        if quote:
            quote = None if ch == quote else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == "," and depth == 0:
            out.append(cur)
            cur = ""
            continue
        cur += ch
    return out + [cur]


def test_stubs_match_the_module():
    """python/pathpace/_core.pyi declares every public class, method and property of _core, with the
    runtime's parameter names in order."""
    import ast
    import inspect

    stub = ast.parse((pathlib.Path(pp.__file__).with_name("_core.pyi")).read_text())
    declared = {}
    for node in stub.body:
        if isinstance(node, ast.ClassDef):
            members = {}
            for f in node.body:
                if isinstance(f, ast.FunctionDef):
                    args = [a.arg for a in f.args.posonlyargs + f.args.args]
                    args += ["*"] + [a.arg for a in f.args.kwonlyargs] if f.args.kwonlyargs else []  # keyword-only too
                    members[f.name] = args[1:] if args and args[0] in ("self", "cls") else args
                elif isinstance(f, ast.AnnAssign):
                    members[f.target.id] = None
            declared[node.name] = members
    problems = []
    for name in pp.__all__:
        obj = getattr(pp, name)
        if not inspect.isclass(obj) or obj.__module__ != "pathpace._core" or issubclass(obj, Exception) or name == "Status":
            continue
        if name not in declared:
            problems.append(name)
            continue
        for attr, member in vars(obj).items():
            if attr.startswith("_") and attr not in ("__init__", "__call__", "__bool__"):
                continue
            if attr == "__init__" and type(member).__name__ == "wrapper_descriptor":  # no constructor bound
                continue
            if attr not in declared[name]:
                problems.append(f"{name}.{attr}")
                continue
            if isinstance(member, property) or declared[name][attr] is None:
                continue
            fn = getattr(obj, attr)
            assert not inspect.isfunction(fn), f"{name}.{attr} is added in Python: bind it in C++ (one docstring source)"
            sig = (fn.__doc__ or "").strip().split("\n", 1)[0]
            params = [p.split(":")[0].split("=")[0].strip() for p in top_level_split(sig[sig.find("(") + 1 : sig.rfind(")")])]
            params = [p for p in params if p and p != "self"]
            if params != declared[name][attr]:
                problems.append(f"{name}.{attr}: runtime {params}, stub {declared[name][attr]}")
    assert problems == [], "\n".join(problems)


def test_pickle_state_and_tolerance_validation():
    with pytest.raises(pp.InvalidInputError, match=r"CubicSplinePath pickle state has 1 entries, expected 5"):
        pp.CubicSplinePath.__new__(pp.CubicSplinePath).__setstate__((1,))
    with pytest.raises(pp.InvalidInputError, match=r"TimeScalingProblem pickle state has 2 entries, expected 6"):
        pp.TimeScalingProblem.__new__(pp.TimeScalingProblem).__setstate__((1, 2))
    with pytest.raises(pp.InvalidInputError, match=r"RobotModel pickle state kind = 'mesh' must be 'urdf', 'combine' or 'free_object'"):
        pp.RobotModel.__new__(pp.RobotModel).__setstate__(("mesh",))
    with pytest.raises(pp.InvalidInputError, match=r"Contact pickle state: point and normal must have size 3"):
        pp.Contact.__new__(pp.Contact).__setstate__(("a", [0.0, 0.0], [0.0, 0.0, 1.0], 0.5, ""))
    prob = two_joint_problem()
    with pytest.raises(pp.InvalidInputError, match=r"tolerance = -1 must be >= 0 and finite"):
        prob.set_boundary_velocities(np.zeros(2), np.zeros(2), tolerance=-1.0)
    box = pp.RobotModel.free_object("box", 1.0)
    assert box.mass == 1.0
    np.testing.assert_allclose(box.center_of_mass(np.array([1.0, 2.0, 3.0, 0.0, 0.0, 0.0])), [1.0, 2.0, 3.0])


def test_joint_names_in_limit_labels_and_messages():
    names = ["shoulder", "elbow"]
    prob = two_joint_problem()
    prob2 = pp.TimeScalingProblem(prob.path, grid=200)
    prob2.add_constraint(pp.VelocityLimits([-1, -1], [1, 1], joint_names=names))
    prob2.add_constraint(pp.AccelerationLimits([-2, -2], [2, 2], joint_names=names))
    fs = prob2.feasible_set(100)
    assert all(("shoulder" in lab or "elbow" in lab) and "joint" not in lab for lab in fs.labels + [fs.x_max_label])
    assert prob2.solve().duration == prob.solve().duration  # names change nothing else
    with pytest.raises(pp.InvalidInputError, match=re.escape("vmax[1] (elbow) = -1 must be >= 0")):
        pp.VelocityLimits([-1, -1], [1, -1], joint_names=names)
    with pytest.raises(pp.InvalidInputError, match=re.escape("amin[0] (shoulder) = 3 must be <= amax[0] = 2")):
        pp.AccelerationLimits([3, -2], [2, 2], joint_names=names)
    with pytest.raises(pp.InvalidInputError, match=re.escape("joint_names has size 1, expected 2 (one per joint, as vmax)")):
        pp.VelocityLimits([-1, -1], [1, 1], joint_names=["a"])
    v = roundtrip(pp.VelocityLimits([-1, -1], [1, 1], joint_names=names))
    assert v.joint_names == names
    # Without names, as before: indices.
    assert "velocity joint" in two_joint_problem().feasible_set(100).x_max_label


def test_cpp_names_work_in_python():
    a = pp.RobotModel.from_urdf_file(DATA / "pendulum.urdf")
    q = np.array([0.7])
    np.testing.assert_array_equal(a.gravity_torques(q), a.gravity(q))
    assert a.joint_names == pp.RobotModel.from_urdf(DATA / "pendulum.urdf").joint_names
