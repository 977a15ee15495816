"""Random invalid inputs at every public entry point: each call either succeeds or raises a typed
error (pathpace.InvalidInputError, or a TypeError) whose message names the argument; never a crash,
a hang, a pybind11 whole-signature TypeError or another exception type."""

import os
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from fuzz_support import ChildCrashed, exception_info, fuzz_settings, run_isolated

import pathpace as pp
from pathpace import io

DATA = Path(__file__).resolve().parents[2] / "data"
PENDULUM = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))  # 1 joint
ROD = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))  # 3 joints
LINE = pp.CubicSplinePath([[0.0], [1.0], [0.5]])
ROD_PATH = pp.CubicSplinePath([[0.0, 1.0, 0.0], [0.1, 1.0, -0.1]])


def problem(path=LINE, N=10):
    prob = pp.TimeScalingProblem(path, grid=N)
    prob.add_velocity_limits(-np.ones(path.dof), np.ones(path.dof))
    return prob


PROBLEM = problem()
TRAJ = PROBLEM.solve().trajectory()
FSET = PROBLEM.feasible_set(3)
CONTACT = pp.Contact("rod", point=[0, 0, -1])
CC = pp.ContactConstraint(ROD, [CONTACT])
URDF = (DATA / "pendulum.urdf").read_text()
ROWS = np.ones((11, 1))

# name: (call, valid keyword arguments)
ENTRY_POINTS = {
    "CubicSplinePath": (pp.CubicSplinePath, dict(waypoints=[[0.0], [1.0]], knots="uniform", boundary="natural",
                                                 start_derivative=None, end_derivative=None, s_begin=0.0, s_end=1.0)),
    "PiecewisePolynomialPath": (pp.PiecewisePolynomialPath, dict(breakpoints=[0.0, 1.0], coefficients=[[[0.0], [1.0]]])),
    "SampledPath": (pp.SampledPath, dict(s=[0.0, 1.0], q=[0.0, 1.0], dq=[1.0, 1.0], ddq=[0.0, 0.0])),
    "Path.evaluate": (LINE.evaluate, dict(s=[0.0, 0.5])),
    "TimeScalingProblem": (pp.TimeScalingProblem, dict(path=LINE, grid=10)),
    "add_velocity_limits": (lambda **kw: problem().add_velocity_limits(**kw), dict(vmin=[-1.0], vmax=[1.0])),
    "add_acceleration_limits": (lambda **kw: problem().add_acceleration_limits(**kw), dict(amin=[-1.0], amax=[1.0])),
    "add_linear_constraint": (lambda **kw: problem().add_linear_constraint(**kw),
                              dict(A=ROWS, B=ROWS, C=0 * ROWS, lo=-ROWS, hi=ROWS, label="x")),
    "set_boundary_speeds": (lambda **kw: problem().set_boundary_speeds(**kw), dict(sdot_begin=0.0, sdot_end=0.0)),
    "feasible_set": (PROBLEM.feasible_set, dict(k=3)),
    "solve": (PROBLEM.solve, dict(method="auto", max_iterations=50, tolerance=1e-9, initial_trust_region=1.0,
                                  lp_feasibility_tolerance=1e-9)),
    "FeasibleSet.contains": (FSET.contains, dict(x=0.1, u=0.0, tol=1e-9)),
    "Trajectory": (pp.Trajectory, dict(path=LINE, s=[0.0, 1.0], sdot=[1.0, 1.0])),
    "Trajectory.q": (TRAJ.q, dict(t=[0.0, 0.1])),
    "Trajectory.s": (TRAJ.s, dict(t=0.1)),
    "Trajectory.sample": (TRAJ.sample, dict(dt=0.01, max_memory=1e9)),
    "Trajectory.sample_times": (TRAJ.sample_times, dict(dt=0.01)),
    "Trajectory.torques": (TRAJ.torques, dict(t=[0.0], robot=PENDULUM)),
    "from_urdf_string": (pp.RobotModel.from_urdf_string, dict(xml=URDF, floating_base=False, locked_joints=None,
                                                              gravity=[0.0, 0.0, -9.81])),
    "from_urdf": (pp.RobotModel.from_urdf, dict(path=str(DATA / "pendulum.urdf"), floating_base=False,
                                                locked_joints={"hinge": 0.1}, gravity=[0.0, 0.0, -9.81])),
    "inverse_dynamics": (PENDULUM.inverse_dynamics, dict(q=[0.1], qd=[0.0], qdd=[0.0])),
    "frame_placement": (PENDULUM.frame_placement, dict(q=[0.1], link="arm")),
    "point_jacobian": (PENDULUM.point_jacobian, dict(q=[0.1], link="arm", point=[0.0, 0.0, 0.0])),
    "path_torque_coefficients": (PENDULUM.path_torque_coefficients, dict(q=[[0.1]], dq=[[1.0]], ddq=[[0.0]])),
    "free_object": (pp.RobotModel.free_object, dict(name="box", mass=1.0, com=[0, 0, 0], inertia=np.eye(3),
                                                    gravity=[0, 0, -9.81])),
    "combine": (pp.RobotModel.combine, dict(parts=[PENDULUM, ROD], name="both")),
    "TorqueLimits": (pp.TorqueLimits, dict(robot=PENDULUM, tau_min=None, tau_max=None, scale=1.0, margin=0.0)),
    "add_torque_limits": (lambda **kw: problem().add_torque_limits(**kw),
                          dict(robot=PENDULUM, tau_min=None, tau_max=None, scale=1.0, margin=0.0)),
    "Contact": (pp.Contact, dict(link="rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5, other_link=None)),
    "ContactConstraint": (pp.ContactConstraint, dict(robot=ROD, contacts=[CONTACT], cone_edges=4, friction_margin=0.0,
                                                     min_normal_force=0.0, torque_scale=1.0, torque_margin=0.0)),
    "force_distribution": (CC.force_distribution, dict(q=[0.0, 1.0, 0.0], qd=[0.0] * 3, qdd=[0.0] * 3)),
    "max_drift": (CC.max_drift, dict(path=ROD_PATH, s=[0.0, 0.5])),
    "add_contacts": (lambda **kw: problem(ROD_PATH, 4).add_contacts(**kw),
                     dict(robot=ROD, contacts=[CONTACT], cone_edges=4, friction_margin=0.0, min_normal_force=0.0,
                          torque_scale=1.0, torque_margin=0.0, drift_tolerance=1e9)),
    "add_constraint": (lambda **kw: problem().add_constraint(**kw), dict(constraint=pp.VelocityLimits([-1.0], [1.0]))),
    "result_to_dict": (io.result_to_dict, dict(res=PROBLEM.solve())),
    "trajectory_to_dict": (io.trajectory_to_dict, dict(traj=TRAJ, dt=0.1)),
    "save_trajectory_csv": (io.save_trajectory_csv, dict(traj=TRAJ, path=os.devnull, dt=0.1, joint_names=["a"])),
    "load_waypoints_csv": (io.load_waypoints_csv, dict(path=str(DATA / "waypoints_2x1.csv"))),
    "VelocityLimits": (pp.VelocityLimits, dict(vmin=[-1.0], vmax=[1.0], joint_names=["a"])),
    "AccelerationLimits": (pp.AccelerationLimits, dict(amin=[-1.0], amax=[1.0], joint_names=["a"])),
    # Parameters once typed (pybind11 converted them), now py::handle converted by convert.hpp, which names them.
    "auto_grid": (pp.auto_grid, dict(path=LINE, tolerance=1e-2, min_intervals=4, max_intervals=1000)),
    "relaxation": (PROBLEM.relaxation, dict(max_scale=1e3, tolerance=1e-3, guarantee="grid")),
    "restarted": (PROBLEM.restarted, dict(s0=0.5, sdot0=0.1)),
    "set_joint_names": (lambda **kw: problem().set_joint_names(**kw), dict(names=["a"])),
    "set_zero_boundary_accelerations": (lambda **kw: problem().set_zero_boundary_accelerations(**kw),
                                        dict(at_begin=True, at_end=False)),
    "set_boundary_velocities": (lambda **kw: problem().set_boundary_velocities(**kw),
                                dict(qd_begin=[0.0], qd_end=[0.0], tolerance=1e-6)),
    "Trajectory.__call__": (TRAJ, dict(t=0.1, order=1)),
    "LinearConstraint": (pp.LinearConstraint, dict(A=ROWS, B=ROWS, C=0 * ROWS, lo=-ROWS, hi=ROWS, label="x")),
}

BAD_VALUES = [
    None, "abc", "", b"x", [], [[1.0], [2.0, 3.0]], {}, {"a": 1}, {1: "a"}, object(), True, 2**31, 2**63, -(2**63) - 1,
    10**400, float("nan"), float("inf"), -float("inf"), -1, 0, -1.0, 1e308, -1e308, 5e-324, 1e-300, complex(1, 1),
    np.array([]), np.array([[np.nan]]), np.full(3, np.nan), np.array(["a", "b"]), np.zeros((2, 2, 2)), np.ones(1000),
    [1, "a"], (1.0,), [None], np.float32(1.5), np.int64(2), np.array(1.0), [[0.0], [np.inf]], np.arange(5.0)[::-1],
    CONTACT, PENDULUM, LINE, pp.Status.OPTIMAL,
    # None, str and complex inside arrays; gravity far beyond any planet's (issue 20's fuzz run).
    [0.0, None], [[0.0], [None]], np.array([1.0, None], dtype=object), [1.0, "a"], [1.0, 1j], (0.0, 0.0, 1e308),
    [0.0, 0.0, -1e4],
]


def call_with(entry, arg, value):
    fn, kwargs = ENTRY_POINTS[entry]
    kwargs = dict(kwargs)
    kwargs[arg] = value
    fn(**kwargs)
    return None


def call_each(entry, arg):
    """Every bad value for one argument, in one child (cheap); the outcome of each."""
    out = []
    for i, value in enumerate(BAD_VALUES):
        try:
            call_with(entry, arg, value)
            out.append((i, "ok", None))
        except BaseException as e:  # noqa: BLE001 - judged by the parent
            out.append((i, "raised", exception_info(e)))
    return out


# Messages may name an argument by a more precise name: an index into it, or an item's field.
ALIASES = {"waypoints": ["waypoint"], "coefficients": ["coefficients", "piece"], "xml": ["urdf"],
           "path": ["urdf", "file", "No such file"]}


def check(entry, arg, value, kind, out):
    if kind == "ok":
        return
    # A file path that cannot be opened is the file system's OSError, as everywhere in Python.
    file_error = arg == "path" and out.get("os_error", False)
    assert out["type_error"] or out["invalid_input"] or file_error, \
        f"{entry}({arg}={value!r:.80}): {out['type']}: {out['message']}"
    msg = out["message"]
    assert "incompatible function arguments" not in msg and "C++ type" not in msg, msg
    assert any(name in msg for name in [arg] + ALIASES.get(arg, [])), \
        f"{entry}({arg}={value!r:.80}) raised {out['type']} without naming {arg!r}: {msg}"


@pytest.mark.parametrize("entry, arg", [(e, a) for e in sorted(ENTRY_POINTS) for a in sorted(ENTRY_POINTS[e][1])])
def test_every_bad_value_at_every_argument(entry, arg):
    """The whole table, deterministically: one child per argument; if it dies, one child per value so
    the failure names the value that crashed."""
    try:
        kind, results = run_isolated(call_each, entry, arg, timeout=120)
    except ChildCrashed:
        for value in BAD_VALUES:
            run_isolated(call_with, entry, arg, value, timeout=60)  # raises ChildCrashed naming the value
        raise
    assert kind == "ok", results
    for i, k, out in results:
        check(entry, arg, BAD_VALUES[i], k, out)


@st.composite
def random_values(draw):
    """Beyond the table: random floats (any), ints, arrays of random shape with random entries."""
    floats = st.floats(allow_nan=True, allow_infinity=True, width=64)
    elements = st.one_of(floats, st.none(), st.text(max_size=2), st.complex_numbers(), st.booleans())
    return draw(st.one_of(
        floats, st.integers(), st.sampled_from(BAD_VALUES),
        st.lists(floats, max_size=5),
        st.lists(st.lists(floats, min_size=0, max_size=4), max_size=4),
        st.lists(elements, max_size=5), st.lists(st.lists(elements, min_size=2, max_size=2), min_size=2, max_size=3),
        st.builds(lambda shape, seed: np.random.default_rng(seed).standard_normal(shape) * 10.0 ** np.random.default_rng(
            seed).integers(-300, 300), st.lists(st.integers(0, 4), max_size=3).map(tuple), st.integers(0, 2**32 - 1)),
    ))


@fuzz_settings(250)
@given(st.sampled_from(sorted(ENTRY_POINTS)), st.data())
def test_random_bad_arguments_give_typed_errors_that_name_them(entry, data):
    arg = data.draw(st.sampled_from(sorted(ENTRY_POINTS[entry][1])))
    value = data.draw(random_values())
    kind, out = run_isolated(call_with, entry, arg, value, timeout=60)
    check(entry, arg, value, kind, out)


def gravity_outcome(g):
    """A model under gravity g: refused (InvalidInputError naming gravity), or finite torques on a path and
    a torque-limited timing whose torques are finite."""
    try:
        robot = pp.RobotModel.from_urdf_string(URDF, gravity=g)
        box = pp.RobotModel.free_object("box", 2.0, inertia=np.eye(3), gravity=g)
    except pp.InvalidInputError as e:
        return ("refused", str(e))
    path = pp.CubicSplinePath([[0.1], [0.6], [0.3]])
    q, dq, ddq = path.evaluate(np.linspace(0, 1, 21))
    a, b, c = robot.path_torque_coefficients(q, dq, ddq)
    box_tau = box.gravity_torques(np.zeros(6))
    prob = pp.TimeScalingProblem(path, grid=20)
    prob.add_velocity_limits([-10.0], [10.0])
    prob.add_torque_limits(robot, tau_min=[-1e7], tau_max=[1e7])
    res = prob.solve()
    tau = res.trajectory().torques(np.linspace(0, res.duration, 11)) if res.ok else np.zeros(1)
    finite = all(np.all(np.isfinite(x)) for x in (a, b, c, box_tau, tau))
    return ("accepted", finite, res.status.name, stable_norm(g))


def stable_norm(g):
    m = float(np.max(np.abs(g)))
    return m * float(np.linalg.norm(np.asarray(g) / m)) if 0 < m < np.inf else m


@fuzz_settings(50)
@given(st.lists(st.one_of(st.just(0.0), st.floats(-1e3, 1e3), st.floats(allow_nan=True, allow_infinity=True),
                          st.integers(-3, 308).map(lambda e: -(10.0**e))), min_size=3, max_size=3))
def test_random_gravity_is_refused_by_name_or_gives_finite_torques(g):
    kind, out = run_isolated(gravity_outcome, g)
    assert kind == "ok", out
    if out[0] == "refused":
        assert out[1].startswith("gravity"), out[1]
        assert not (np.all(np.isfinite(g)) and stable_norm(g) <= 1e3), out[1]
    else:
        assert out[1] and out[2] == "OPTIMAL" and out[3] <= 1e3, out
