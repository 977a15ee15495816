"""A toppra user's script ported by changing only its imports and its constructor (issue 22's target).

The scripts below are toppra scripts as toppra's users write them. Each test runs one under toppra, then the
same text with the algorithm import and the ``TOPPRA(...)`` line replaced (checked: no other line differs),
under pathpace. toppra's own constraint objects go to ``TimeScalingProblem(path, constraints=[...])`` and
``compute_trajectory`` is toppra's. Oracle: toppra's T on the same grid. On the Interpolation
discretisation (toppra's default for joint accelerations, its recommended one for torque) both solve eq. 26's
rows (each limit at each grid point for the s̈ on both sides); pathpace's T is that discretisation's optimum,
toppra's slightly above it (it lowers each forward step's ṡ² by 1e-8, and its LPs have their own tolerances):
pathpace's T is at most toppra's and within 1e-4 of it (measured -6e-5 to -5e-7 below).
"""

from __future__ import annotations

import difflib
import logging
import pickle

import numpy as np
import pytest

import pathpace as pp

ta = pytest.importorskip("toppra")
import toppra.algorithm as algo  # noqa: E402
import toppra.constraint as constraint  # noqa: E402

PORT = {
    "import toppra.algorithm as algo": "import pathpace as pp",
    "instance = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=gridpoints)":
        "instance = pp.TimeScalingProblem(path, constraints=[pc_vel, pc_acc], grid=gridpoints)",
    "instance = algo.TOPPRA([pc_vel, pc_tau], path, gridpoints=gridpoints)":
        "instance = pp.TimeScalingProblem(path, constraints=[pc_vel, pc_tau], grid=gridpoints)",
}

# toppra's README example, on a fixed grid (pathpace's grid is the constructor's argument, as toppra's).
KINEMATIC = """\
import numpy as np
import toppra as ta
import toppra.constraint as constraint
import toppra.algorithm as algo

ss = np.linspace(0, 1, 6)
way_pts = np.random.default_rng(2022).uniform(-1, 1, (6, 3))
vlim = np.array([[-1.0, 1.0], [-1.5, 1.5], [-2.0, 2.0]])
alim = np.array([[-2.0, 2.0], [-3.0, 3.0], [-4.0, 4.0]])
path = ta.SplineInterpolator(ss, way_pts)
pc_vel = constraint.JointVelocityConstraint(vlim)
pc_acc = constraint.JointAccelerationConstraint(alim)
gridpoints = np.linspace(0, path.path_interval[1], 101)
instance = algo.TOPPRA([pc_vel, pc_acc], path, gridpoints=gridpoints)
jnt_traj = instance.compute_trajectory(0, 0)
ts_sample = np.linspace(0, jnt_traj.duration, 100)
qs_sample = jnt_traj(ts_sample)
qds_sample = jnt_traj(ts_sample, 1)
qdds_sample = jnt_traj(ts_sample, 2)
"""

# A planar two-link arm (unit links, 1 kg point masses at their ends, gravity along -y) in closed form, as
# toppra's JointTorqueConstraint wants it: one sample (q, qd, qdd) at a time.
TORQUE = """\
import numpy as np
import toppra as ta
import toppra.constraint as constraint
import toppra.algorithm as algo


def inv_dyn(q, qd, qdd):
    c2, s2 = np.cos(q[1]), np.sin(q[1])
    c1, c12 = np.cos(q[0]), np.cos(q[0] + q[1])
    m11, m12, m22 = 3.0 + 2.0 * c2, 1.0 + c2, 1.0
    h1, h2 = -s2 * (2.0 * qd[0] * qd[1] + qd[1] ** 2), s2 * qd[0] ** 2
    return np.array([m11 * qdd[0] + m12 * qdd[1] + h1 + 9.81 * (2.0 * c1 + c12),
                     m12 * qdd[0] + m22 * qdd[1] + h2 + 9.81 * c12])


way_pts = np.array([[0.0, -0.3], [0.6, 0.4], [1.1, -0.2], [0.5, 0.9]])
path = ta.SplineInterpolator(np.linspace(0, 1, 4), way_pts)
pc_vel = constraint.JointVelocityConstraint(np.array([[-3.0, 3.0], [-3.0, 3.0]]))
tau_lim = np.array([[-40.0, 40.0], [-15.0, 15.0]])
fs_coef = np.zeros(2)
pc_tau = constraint.JointTorqueConstraint(inv_dyn, tau_lim, fs_coef,
                                          discretization_scheme=constraint.DiscretizationType.Interpolation)
gridpoints = np.linspace(0, 1, N + 1)
instance = algo.TOPPRA([pc_vel, pc_tau], path, gridpoints=gridpoints)
jnt_traj = instance.compute_trajectory()
ts = np.linspace(0, jnt_traj.duration, 50)
tau = np.array([inv_dyn(q, qd, qdd) for q, qd, qdd in zip(jnt_traj(ts), jnt_traj(ts, 1), jnt_traj(ts, 2))])
"""


def ported(script):
    """The script with its import and constructor lines replaced, and the proof that nothing else changed."""
    out = "".join(PORT.get(line.rstrip("\n"), line.rstrip("\n")) + "\n" for line in script.splitlines())
    changed = [line for line in difflib.unified_diff(script.splitlines(), out.splitlines(), lineterm="", n=0)
               if line[:1] in "+-" and line[:3] not in ("+++", "---")]
    assert len(changed) == 4, changed  # the import and the constructor, each one line out and one in
    return out


def run(script, **scope):
    exec(compile(script, "toppra_script.py", "exec"), scope)  # noqa: S102 - the test's own script text
    return scope


def same_duration(T_pathpace, T_toppra):
    assert T_pathpace <= T_toppra * (1 + 1e-12)
    assert abs(T_pathpace / T_toppra - 1) < 1e-4


def test_a_kinematic_toppra_script_runs_with_its_imports_and_constructor_changed():
    theirs, ours = run(KINEMATIC), run(ported(KINEMATIC))
    assert isinstance(ours["instance"], pp.TimeScalingProblem) and isinstance(ours["jnt_traj"], pp.Trajectory)
    same_duration(ours["jnt_traj"].duration, theirs["jnt_traj"].duration)
    for name in ("qs_sample", "qds_sample", "qdds_sample"):
        assert ours[name].shape == theirs[name].shape == (100, 3)
    # Both follow the same path from its first to its last waypoint.
    np.testing.assert_allclose(ours["qs_sample"][[0, -1]], theirs["way_pts"][[0, -1]], atol=1e-12)
    np.testing.assert_allclose(ours["qs_sample"][[0, -1]], theirs["qs_sample"][[0, -1]], atol=1e-9)
    # The limits hold on pathpace's trajectory at its grid points.
    traj = ours["jnt_traj"]
    assert np.all(np.abs(traj(traj.times, 1)) <= ours["vlim"][:, 1] * (1 + 1e-9))


@pytest.mark.parametrize("N", [100, 1000])
def test_a_torque_toppra_script_runs_with_its_imports_and_constructor_changed(N):
    """Measured: pathpace below toppra by 4.5e-7 (N = 100) and 2.2e-6 (N = 1000) relative."""
    theirs, ours = run(TORQUE, N=N), run(ported(TORQUE), N=N)
    same_duration(ours["jnt_traj"].duration, theirs["jnt_traj"].duration)
    (c,) = [c for c in ours["instance"].constraints if c.family() == "torque"]
    assert isinstance(c, pp.SecondOrderConstraint) and c.inverse_dynamics is ours["inv_dyn"]
    assert ours["tau"].shape == theirs["tau"].shape == (50, 2)
    # The limits hold on pathpace's trajectory at its grid points (between them by O(Δs²) only).
    traj, inv_dyn = ours["jnt_traj"], ours["inv_dyn"]
    t = traj.times
    tau = np.array([inv_dyn(q, qd, qdd) for q, qd, qdd in zip(traj(t), traj(t, 1), traj(t, 2))])
    assert np.all(np.abs(tau) <= ours["tau_lim"][:, 1] * (1 + 1e-6))


def test_toppras_collocation_torque_rows_are_looser_than_pathpaces():
    """toppra's default scheme for JointTorqueConstraint, Collocation, holds the limits at s_k with the s̈ of
    the interval after s_k only; pathpace holds them with both (eq. 26). So pathpace's feasible set is a
    subset and its T at least toppra's: 1.5e-3 above at N = 100, 1.8e-4 at N = 1000 (measured). On toppra's
    Interpolation scheme the two agree (the test above)."""
    script = TORQUE.replace(",\n                                          discretization_scheme=constraint.DiscretizationType"
                            ".Interpolation)", ")")
    assert "Interpolation" not in script
    theirs, ours = run(script, N=100), run(ported(script), N=100)
    T_ours, T_theirs = ours["jnt_traj"].duration, theirs["jnt_traj"].duration
    assert T_theirs < T_ours < T_theirs * (1 + 3e-3)


# -- each toppra constraint type against toppra on the same path and grid ---------------------------------

WAY = np.array([[0.0, -0.3], [0.6, 0.4], [1.1, -0.2], [0.5, 0.9]])
PATH = ta.SplineInterpolator(np.linspace(0, 1, 4), WAY)
GRID = np.linspace(0, 1, 101)
TAU = np.array([[-40.0, 40.0], [-15.0, 15.0]])
F_TORQUE = np.vstack([np.eye(2), -np.eye(2)])
G_TORQUE = np.r_[TAU[:, 1], -TAU[:, 0]]


_ARM = run(TORQUE.split("\n\n\nway_pts")[0])["inv_dyn"]


def arm(q, qd, qdd):
    """The two-link arm of TORQUE, per sample (module level: it pickles)."""
    return _ARM(q, qd, qdd)


def torque_F(q):
    return F_TORQUE


def torque_g(q):
    return G_TORQUE


def varying_vlim(s):
    return np.array([[-1.0 - s, 0.5 + s], [-2.0 + s, 1.5]])


def both(constraints):
    T_toppra = algo.TOPPRA(constraints, PATH, gridpoints=GRID).compute_trajectory(0, 0).duration
    prob = pp.TimeScalingProblem(PATH, grid=GRID, constraints=constraints)
    return prob, prob.compute_trajectory().duration, T_toppra


def velocity():
    return constraint.JointVelocityConstraint(np.array([[-3.0, 3.0], [-3.0, 3.0]]))


@pytest.mark.parametrize("kind", ["SecondOrderConstraint", "joint_torque_constraint", "JointTorqueConstraint"])
def test_second_order_and_torque_constraints_give_toppras_duration(kind):
    make = {"SecondOrderConstraint": lambda: constraint.SecondOrderConstraint(arm, torque_F, torque_g, 2),
            # toppra's own factory: its friction custom term is zero when joint_friction is
            "joint_torque_constraint": lambda: constraint.SecondOrderConstraint.joint_torque_constraint(
                arm, TAU, np.zeros(2)),
            "JointTorqueConstraint": lambda: constraint.JointTorqueConstraint(
                arm, TAU, np.zeros(2), discretization_scheme=constraint.DiscretizationType.Interpolation)}[kind]
    prob, T, T_toppra = both([velocity(), make()])
    same_duration(T, T_toppra)
    if kind == "joint_torque_constraint":  # toppra's factory makes F and g lambdas: pickle says which
        with pytest.raises(pickle.PicklingError, match=r"its F <function SecondOrderConstraint.joint_torque_"):
            pickle.dumps(prob)
        return
    back = pickle.loads(pickle.dumps(prob))  # module-level callables: the problem pickles
    assert back.solve().duration == prob.solve().duration


def test_varying_velocity_limits_give_toppras_duration():
    c = constraint.JointVelocityConstraintVarying(varying_vlim)
    prob, T, T_toppra = both([c, constraint.JointAccelerationConstraint(np.array([[-2.0, 2.0], [-3.0, 3.0]]))])
    same_duration(T, T_toppra)
    assert isinstance(prob.constraints[0], pp.LinearConstraint)  # rows per grid point


def test_the_constraints_mean_what_the_add_calls_mean():
    vlim, alim = np.array([[-1.0, 1.2], [-0.7, 0.9]]), np.array([[-2.0, 2.5], [-3.0, 1.0]])
    mine = pp.TimeScalingProblem(PATH, grid=GRID, constraints=[constraint.JointVelocityConstraint(vlim),
                                                               constraint.JointAccelerationConstraint(alim)])
    ref = pp.TimeScalingProblem(PATH, grid=GRID)
    ref.add_velocity_limits(vlim[:, 0], vlim[:, 1])
    ref.add_acceleration_limits(alim[:, 0], alim[:, 1])
    assert mine.solve().duration == ref.solve().duration
    # toppra's symmetric (dof,) form, and pathpace's own constraints in the same list.
    sym = pp.TimeScalingProblem(PATH, grid=GRID, constraints=[constraint.JointVelocityConstraint([1.0, 0.7]),
                                                              pp.AccelerationLimits(alim[:, 0], alim[:, 1])])
    ref = pp.TimeScalingProblem(PATH, grid=GRID)
    ref.add_velocity_limits([-1.0, -0.7], [1.0, 0.7])
    ref.add_acceleration_limits(alim[:, 0], alim[:, 1])
    assert sym.solve().duration == ref.solve().duration
    assert pp.TimeScalingProblem(PATH, grid=GRID, constraints=[]).constraints == []


def bad_velocity(s):
    return np.array([[0.2, 1.0], [-1.0, 1.0]])


@pytest.mark.parametrize("constraints, error, match", [
    ([velocity(), 3], pp.InvalidInputError, r"^constraints\[1\] \(int\) is not a constraint pathpace takes"),
    ([velocity(), constraint.RobustLinearConstraint(velocity(), [0.1, 0.1, 0.1])], pp.InvalidInputError,
     r"^constraints\[1\] \(toppra.RobustLinearConstraint\) is not a constraint pathpace takes"),
    ([constraint.JointTorqueConstraint(arm, TAU, [0.0, 0.5])], pp.InvalidInputError,
     r"^constraints\[0\] \(toppra.JointTorqueConstraint\).fs_coef\[1\] = 0.5: dry friction"),
    ([constraint.SecondOrderConstraint.joint_torque_constraint(arm, TAU, np.array([0.1, 0.0]))], pp.InvalidInputError,
     r"^constraints\[0\] \(toppra.SecondOrderConstraint\).custom_term\(path, s\) = \[0.1, 0.0\] at grid point 0"),
    ([constraint.JointVelocityConstraint(np.ones((3, 2)) * [-1, 1])], pp.InvalidInputError,
     r"^constraints\[0\] \(toppra.JointVelocityConstraint\): velocity limits have 3 entries, the path has 2"),
    ([constraint.JointVelocityConstraintVarying(bad_velocity)], pp.InvalidInputError,
     r"^constraints\[0\] \(toppra.JointVelocityConstraintVarying\).vlim_func\(s\)\[0\] = \[0.2, 1.0\] at s = 0.0: "
     r"expected finite lower <= 0 <= upper"),
    (velocity(), TypeError, r"constraints must be a list of constraints, got JointVelocityConstraint"),
])
def test_what_pathpace_cannot_take_is_named_with_its_index_and_type(constraints, error, match):
    with pytest.raises(error, match=match):
        pp.TimeScalingProblem(PATH, grid=GRID, constraints=constraints)


def test_compute_trajectory_returns_none_when_infeasible_and_says_why(caplog):
    # Velocity 0 on joint 1 where the path moves it: only ṡ = 0 is allowed, so no timing exists.
    prob = pp.TimeScalingProblem(PATH, grid=GRID, constraints=[pp.VelocityLimits([-1.0, -1.0], [1.0, 1.0])])
    prob.add_linear_constraint(np.ones(GRID.size), np.zeros(GRID.size), np.zeros(GRID.size),
                               np.full(GRID.size, 1.0), np.full(GRID.size, 2.0), label="sdot2 in [1, 2]")
    with caplog.at_level(logging.WARNING, logger="pathpace"):
        assert prob.compute_trajectory() is None
    assert "no time scaling (INFEASIBLE)" in caplog.text
    assert not prob.solve().ok


def test_compute_trajectory_takes_toppras_end_speeds():
    prob = pp.TimeScalingProblem(PATH, grid=GRID, constraints=[velocity()])
    traj = prob.compute_trajectory(0.1, 0.2)
    assert (prob.sdot_begin, prob.sdot_end) == (0.1, 0.2)
    np.testing.assert_allclose(traj.sdot_grid[[0, -1]], [0.1, 0.2], rtol=1e-12)
    assert traj.duration == prob.solve().duration
    prob.compute_trajectory()  # toppra's defaults: at rest at both ends again
    assert (prob.sdot_begin, prob.sdot_end) == (0.0, 0.0)
    with pytest.raises(TypeError, match=r"^sd_end must be a number, got str"):
        prob.compute_trajectory(0.0, "0")
    with pytest.raises(pp.InvalidInputError, match=r"sdot_begin"):  # the problem's own check of the value
        prob.compute_trajectory(-1.0)


def test_solve_many_takes_problems_built_from_toppra_constraints():
    probs = [pp.TimeScalingProblem(PATH, grid=n, constraints=[velocity(), constraint.JointAccelerationConstraint(
        np.array([[-2.0, 2.0], [-3.0, 3.0]]))]) for n in (50, 100)]
    assert [r.duration for r in pp.solve_many(probs, workers=2)] == [p.solve().duration for p in probs]
