"""SecondOrderConstraint (issue 22, items 2, 4 and 5): F(q) w <= g(q) with w from the user's inverse dynamics,
and add_torque_limits(inverse_dynamics=...).

Oracles: pinocchio's RNEA (a code independent of ours) as the callback against our TorqueLimits on the same
URDF; the built-in acceleration limits (w = q̈ is their second-order form); a gripper holding a box by
friction whose limit surface is checked on the timed trajectory at 1 kHz.
"""

import math
import pickle
import threading

import numpy as np
import pytest

import pathpace as pp
from pathpace.robots import example_robot_urdf

from helpers import process_pool

pin = pytest.importorskip("pinocchio")


# ---- module-level callables: they pickle (solve_many on processes, pickle round trips)


class PinRnea:
    """The user's cost: pinocchio's RNEA looped over the rows of a batch. Pickles through its URDF."""

    def __init__(self, urdf, locked=()):
        self.urdf, self.locked = str(urdf), tuple(locked)
        full = pin.buildModelFromUrdf(self.urdf)
        self.model = full if not locked else pin.buildReducedModel(full, [full.getJointId(n) for n in locked],
                                                                  pin.neutral(full))
        self.data = self.model.createData()
        self.calls = 0

    def __call__(self, q, qd, qdd):
        self.calls += 1
        return np.array([pin.rnea(self.model, self.data, a, b, c) for a, b, c in zip(q, qd, qdd)])

    def one(self, q, qd, qdd):
        return pin.rnea(self.model, self.data, q, qd, qdd).copy()

    def __reduce__(self):
        return PinRnea, (self.urdf, self.locked)


# A planar two-link arm (unit lengths, point masses m1 = m2 = 1 kg at the link ends, gravity along -y),
# vectorised with numpy: τ = M(q) q̈ + C(q, q̇) q̇ + g(q) in closed form.
def planar_arm(q, qd, qdd):
    c2, s2 = np.cos(q[:, 1]), np.sin(q[:, 1])
    c1, c12 = np.cos(q[:, 0]), np.cos(q[:, 0] + q[:, 1])
    m11, m12, m22 = 3.0 + 2.0 * c2, 1.0 + c2, np.ones_like(c2)
    h = s2 * (-(2.0 * qd[:, 0] * qd[:, 1] + qd[:, 1] ** 2)), s2 * qd[:, 0] ** 2
    g1, g2 = 9.81 * (2.0 * c1 + c12), 9.81 * c12
    return np.column_stack([m11 * qdd[:, 0] + m12 * qdd[:, 1] + h[0] + g1, m12 * qdd[:, 0] + m22 * qdd[:, 1] + h[1] + g2])


def accelerations(q, qd, qdd):
    """w = q̈: the acceleration limits written as a second-order constraint."""
    return qdd


def arm_path():
    return pp.CubicSplinePath(np.array([[0.0, -0.3], [0.6, 0.4], [1.1, -0.2], [0.5, 0.9]]))


def planar_problem(N=100, torque="callback", **solve_kw):
    prob = pp.TimeScalingProblem(arm_path(), grid=N)
    prob.add_velocity_limits([-3.0, -3.0], [3.0, 3.0])
    prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-40.0, -15.0], tau_max=[40.0, 15.0])
    return prob


def ok(res):
    assert res.status.name == "OPTIMAL", res.message
    return res


# ---- pinocchio's RNEA as the callback against our TorqueLimits

ROBOTS = {  # URDF, locked joints, torque limits as a fraction of the effort (they bind, the paths stay feasible)
    "ur5": ("ur_description/urdf/ur5_robot.urdf", (), 0.5),
    "panda": ("panda_description/urdf/panda.urdf", ("panda_finger_joint1", "panda_finger_joint2"), 0.65),
}


def robot_pair(name):
    rel, locked, _ = ROBOTS[name]
    urdf = example_robot_urdf(rel)
    ours = pp.RobotModel.from_urdf(str(urdf), locked_joints={n: 0.0 for n in locked})
    return ours, PinRnea(urdf, locked)


def corpus_path(robot, seed):
    rng = np.random.default_rng(seed)
    lo, hi = robot.position_limits
    lo, hi = np.maximum(lo, -3.0), np.minimum(hi, 3.0)
    return pp.CubicSplinePath(lo + (hi - lo) * rng.uniform(0.2, 0.8, (5, robot.nq)))


@pytest.mark.parametrize("name", sorted(ROBOTS))
def test_pinocchio_rnea_as_the_callback_gives_our_torque_limits_rows_and_duration(name):
    """Seeded corpus: 3 paths per robot, N = 150, torque limits at ROBOTS' fraction of the effort (they bind).
    Measured on this corpus (6 problems): |ΔT|/T median 0, worst 6.9e-15; rows apart by at most 1.4e-13 of
    max(1, |entry|) (median 5.3e-14): two RNEA codes' rounding."""
    ours, rnea = robot_pair(name)
    lim = ROBOTS[name][2] * ours.effort_limits
    for seed in range(3):
        path = corpus_path(ours, seed)
        a, b = pp.TimeScalingProblem(path, grid=150), pp.TimeScalingProblem(path, grid=150)
        a.add_torque_limits(ours, tau_min=-lim, tau_max=lim)
        b.set_joint_names(ours.joint_names)
        b.add_torque_limits(inverse_dynamics=rnea, tau_min=-lim, tau_max=lim)
        ra, rb = a.constraints[0], b.constraints[0]
        assert isinstance(rb, pp.SecondOrderConstraint) and rb.family() == "torque"
        samples = sample_of(pp.TimeScalingProblem(path, grid=150))
        rows_a, rows_b = ra.evaluate(samples), rb.evaluate(samples)
        assert rows_b.labels == rows_a.labels
        for x, y in ((rows_b.a, rows_a.a), (rows_b.b, rows_a.b), (rows_b.c, rows_a.c)):
            assert np.max(np.abs(x - y) / np.maximum(1.0, np.abs(y))) < 1e-12
        res_a, res_b = ok(a.solve()), ok(b.solve())
        assert any(lbl.startswith("torque") for lbl in res_a.binding), res_a.binding
        assert res_b.duration == pytest.approx(res_a.duration, rel=1e-12, abs=0)


def sample_of(prob):
    """The problem's PathSamples, through a constraint that hands them back."""
    box = {}

    class Grab(pp.Constraint):
        name = "grab"

        def evaluate(self, samples):
            box["s"] = samples
            n = len(samples)
            return pp.ConstraintRows(np.zeros((n, 1)), np.zeros((n, 1)), np.ones((n, 1)), ["grab"])

    prob.add_constraint(Grab())
    return box["s"]


def test_vectorized_false_takes_toppra_per_sample_functions():
    ours, rnea = robot_pair("ur5")
    lim = 0.25 * ours.effort_limits
    path = corpus_path(ours, 7)
    a, b = pp.TimeScalingProblem(path, grid=60), pp.TimeScalingProblem(path, grid=60)
    a.add_torque_limits(inverse_dynamics=rnea, tau_min=-lim, tau_max=lim)
    b.add_torque_limits(inverse_dynamics=rnea.one, tau_min=-lim, tau_max=lim, vectorized=False)
    ra, rb = ok(a.solve()), ok(b.solve())
    assert rb.duration == ra.duration and np.array_equal(rb.sdot, ra.sdot)
    assert b.constraints[0].vectorized is False


def test_one_call_per_batch():
    ours, rnea = robot_pair("ur5")
    prob = pp.TimeScalingProblem(corpus_path(ours, 1), grid=40)
    prob.add_torque_limits(inverse_dynamics=rnea, tau_min=-ours.effort_limits, tau_max=ours.effort_limits)
    assert rnea.calls == 1  # all 3 (N+1) evaluations of eq. 12 in one call


# ---- guarantee = continuous: the audit samples the callback's rows between grid points


def test_continuous_guarantee_holds_callback_torque_between_grid_points():
    """The rows hold at grid points only; with guarantee='continuous' the audit evaluates the callback at
    points between them and cuts. Verdict at 1 kHz with the closed-form dynamics on N = 10: the grid-only
    timing exceeds a limit by 6.8e-3 of it (asserted > 3.4e-3, half the measured room), the continuous one by
    nothing (measured 0; asserted <= 1e-9, the audit tolerance's bound on the limits)."""
    coarse = planar_problem(N=10)
    lo, hi = np.array([-40.0, -15.0]), np.array([40.0, 15.0])

    def worst_excess(res):
        t = np.arange(0.0, res.duration, 1e-3)
        q, qd, qdd = res.trajectory().evaluate(t)
        tau = planar_arm(q, qd, qdd)
        return float(np.max(np.maximum(tau - hi, lo - tau) / hi))

    grid_only = ok(coarse.solve())
    assert worst_excess(grid_only) > 3.4e-3  # the test can fail: between grid points the limits are broken
    cont = ok(coarse.solve(guarantee="continuous"))
    assert worst_excess(cont) <= 1e-9
    assert cont.duration > grid_only.duration


def test_the_audit_calls_the_callback_during_solve():
    class Counting:
        def __init__(self):
            self.n = 0

        def __call__(self, q, qd, qdd):
            self.n += 1
            return planar_arm(q, qd, qdd)

    f = Counting()
    prob = pp.TimeScalingProblem(arm_path(), grid=12)
    prob.add_velocity_limits([-3.0, -3.0], [3.0, 3.0])
    prob.add_torque_limits(inverse_dynamics=f, tau_min=[-40.0, -15.0], tau_max=[40.0, 15.0])
    n = f.n
    ok(prob.solve(guarantee="continuous"))
    assert f.n > n


# ---- item 4: a gripper holding a box by friction

MU, SQUEEZE, PAD = 0.6, 30.0, 0.05  # friction coefficient, each finger's normal force (N), torsion radius (m)
MASS, INERTIA, OFFSET = 2.0, 0.02, np.array([0.0, -0.08])  # the box: kg, kg·m², its centre from the grip (m)
F0, M0 = 2 * MU * SQUEEZE, 2 * PAD * MU * SQUEEZE  # two fingers' friction force (N) and torque (N·m)
GRAVITY = np.array([0.0, -9.81])


def box_wrench(q, qd, qdd):
    """The wrench (f_x, f_z, m) the fingers must apply to the box, in the world's x-z plane, for the gripper at
    q = (x, z, θ): f = m_b (c̈ - g) at the box's centre c = (x, z) + R(θ) r, and about the grip point
    m = I_b θ̈ + (R(θ) r) × f. Quadratic in q̇ (the centripetal θ̇² of c̈), linear in q̈."""
    th, dth, ddth = q[:, 2], qd[:, 2], qdd[:, 2]
    c, s = np.cos(th), np.sin(th)
    rx, rz = c * OFFSET[0] - s * OFFSET[1], s * OFFSET[0] + c * OFFSET[1]  # R(θ) r
    ax = qdd[:, 0] - ddth * rz - dth**2 * rx
    az = qdd[:, 1] + ddth * rx - dth**2 * rz
    fx, fz = MASS * (ax - GRAVITY[0]), MASS * (az - GRAVITY[1])
    return np.column_stack([fx, fz, INERTIA * ddth + rx * fz - rz * fx])


OCTAHEDRON = np.array([[sx, sz, sm] for sx in (1, -1) for sz in (1, -1) for sm in (1, -1)], dtype=float)


def grip_F(q, margin=0.1):
    """The linearised limit surface in the gripper's frame (the fingers' pads turn with θ): an octahedron
    |f'_x|/F0 + |f'_z|/F0 + |m|/M0 <= 1 - margin, inside the ellipsoid (|f'|/F0)² + (m/M0)² <= 1; f' = R(θ)ᵀ f."""
    c, s = np.cos(q[:, 2]), np.sin(q[:, 2])
    rot = np.zeros((len(q), 3, 3))
    rot[:, 0, 0], rot[:, 0, 1], rot[:, 1, 0], rot[:, 1, 1], rot[:, 2, 2] = c, s, -s, c, 1.0
    scale = np.array([1 / F0, 1 / F0, 1 / M0]) / (1.0 - margin)
    return np.einsum("rj,mjk->mrk", OCTAHEDRON * scale, rot)


def grip_g(q):
    return np.ones((len(q), 8))


def grip_use(q, w):
    """The fraction of the octahedron used, with the true friction (no margin)."""
    return np.max(np.einsum("mrk,mk->mr", grip_F(q, margin=0.0), w), axis=1)


def gripper_problem(N=80, with_grip=True):
    path = pp.CubicSplinePath(np.array([[0.0, 0.0, 0.0], [0.3, 0.2, 0.15], [0.6, 0.1, -0.1], [0.8, 0.3, 0.0]]))
    prob = pp.TimeScalingProblem(path, grid=N)
    prob.add_velocity_limits([-2.0, -2.0, -4.0], [2.0, 2.0, 4.0])
    if with_grip:
        prob.add_second_order_constraint(box_wrench, grip_F, grip_g, name="grip",
                                         labels=[f"grip {i}" for i in range(8)])
    return prob


def test_a_gripper_holds_a_box_by_friction_at_1khz():
    """The rows keep the wrench inside the limit surface with a 10 % friction margin (F scaled by 1/0.9) and
    guarantee='continuous' holds them between grid points. Verdict at 1 kHz with the true friction: the used
    fraction stays <= 0.95 (half the margin's room), while at the grid points the grip binds (>= 0.85), and the
    same path timed without the grip rows would let the box slip (> 1). Measured: 0.9000 at 1 kHz and at the
    grid points (the rows' 1 - margin), 17 without the grip rows."""
    prob = gripper_problem()
    res = ok(prob.solve(guarantee="continuous"))
    assert any(b.startswith("grip") for b in res.binding), res.binding
    t = np.arange(0.0, res.duration, 1e-3)
    q, qd, qdd = res.trajectory().evaluate(t)
    used = grip_use(q, box_wrench(q, qd, qdd))
    assert used.max() <= 0.95, used.max()
    at_grid = grip_use(*grid_state(res))
    assert at_grid.max() >= 0.85
    free = ok(gripper_problem(with_grip=False).solve())
    q, qd, qdd = free.trajectory().evaluate(np.arange(0.0, free.duration, 1e-3))
    assert grip_use(q, box_wrench(q, qd, qdd)).max() > 1.0  # without the rows the box slips


def grid_state(res):
    """q and w at the grid points' times (both sides of each interval, q̈ taken inside each interval)."""
    tr = res.trajectory()
    t = np.clip(np.concatenate([tr.times[:-1] + 1e-9, tr.times[1:] - 1e-9]), 0.0, res.duration)
    q, qd, qdd = tr.evaluate(t)
    return q, box_wrench(q, qd, qdd)


def test_callable_F_and_constant_F_agree():
    """F(q) and g(q) given as arrays when they do not depend on q: the same rows as callables returning them."""
    path = arm_path()
    F = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]])
    g = np.array([1.5, 1.5, 2.0, np.inf])
    a, b = pp.TimeScalingProblem(path, grid=30), pp.TimeScalingProblem(path, grid=30)
    a.add_second_order_constraint(accelerations, F, g)
    b.add_second_order_constraint(accelerations, lambda q: np.broadcast_to(F, (len(q),) + F.shape),
                                  lambda q: np.broadcast_to(g, (len(q), 4)))
    ra, rb = ok(a.solve()), ok(b.solve())
    assert ra.duration == rb.duration


# ---- item 5: composition (contacts, restart, relaxation, pickling, threads, processes)

DATA = __import__("pathlib").Path(__file__).resolve().parents[1] / "data"


@pytest.mark.parametrize("N", [20, 7])
def test_alongside_contact_phases_it_is_the_built_in_acceleration_limits(N):
    """hand_box.urdf: a hand pushes a box then brakes it; contacts and torque limits allow |s̈| <= 2. A callback
    w = q̈ with |w| <= 1.5 is the acceleration limit's second-order form: the same duration as the built-in
    limit beside the same contacts (1e-12), and slower than the contacts alone. N = 7: the switch s = 1 is no
    grid point, so it is inserted and the callback evaluated again on the new grid."""
    robot = pp.RobotModel.from_urdf(str(DATA / "hand_box.urdf"))
    hand = robot.joint_names.index("hand_x")
    lo, hi = np.zeros(2), np.zeros(2)
    lo[hand], hi[hand] = -4.0, 4.0

    def on_box(nx):
        return [pp.Contact("box", point=(0, 0, 0), normal=(nx, 0, 0), friction=0.5, other_link="hand")]

    s = np.linspace(0.0, 2.0, 3)
    path = pp.CubicSplinePath(np.column_stack([s, s]), knots=s)
    phases = [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))]
    probs = [pp.TimeScalingProblem(path, grid=N) for _ in range(3)]
    F = np.vstack([np.eye(2), -np.eye(2)])
    probs[0].add_second_order_constraint(accelerations, F, np.full(4, 1.5))  # before the phases: re-evaluated
    probs[1].add_acceleration_limits([-1.5, -1.5], [1.5, 1.5])
    for p in probs:
        p.add_contact_phases(robot, phases, cone_edges=4, tau_min=lo, tau_max=hi)
    r0, r1, r2 = (ok(p.solve()) for p in probs)
    assert len(probs[0].grid) == (N + 1 if N == 20 else N + 2)
    assert r0.duration == pytest.approx(r1.duration, rel=1e-12, abs=0)
    assert r0.duration > r2.duration * (1 + 1e-3)
    assert r0.trajectory().contact_phases  # the contacts still shape the result


def test_restart_evaluates_the_callback_on_the_new_grid():
    prob = planar_problem(N=60)
    res = ok(prob.solve())
    k = 20
    s0, sdot0 = float(prob.grid[k] + 0.37 * (prob.grid[k + 1] - prob.grid[k])), 0.5 * float(min(res.sdot[k:k + 2]))
    back = prob.restarted(s0, sdot0)
    ref = pp.TimeScalingProblem(arm_path(), grid=60).restarted(s0, sdot0)
    ref.add_velocity_limits([-3.0, -3.0], [3.0, 3.0])
    ref.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-40.0, -15.0], tau_max=[40.0, 15.0])
    assert np.array_equal(back.grid, ref.grid)
    assert ok(back.solve()).duration == ok(ref.solve()).duration


def test_relaxation_scales_the_callback_torque_like_torque_limits():
    ours, rnea = robot_pair("ur5")
    lim = 0.04 * ours.effort_limits  # too weak to hold the arm against gravity
    path = corpus_path(ours, 3)
    a, b = pp.TimeScalingProblem(path, grid=40), pp.TimeScalingProblem(path, grid=40)
    a.add_torque_limits(ours, tau_min=-lim, tau_max=lim)
    b.add_torque_limits(inverse_dynamics=rnea, tau_min=-lim, tau_max=lim)
    assert b.solve().status.name == "INFEASIBLE"
    ra, rb = a.relaxation(), b.relaxation()
    assert ra["torque"] > 1.0
    assert rb["torque"] == pytest.approx(ra["torque"], rel=1e-9)


def test_relaxation_widens_g_of_a_general_constraint():
    prob = pp.TimeScalingProblem(arm_path(), grid=30)
    prob.set_boundary_speeds(1.0, 0.0)  # must brake from ṡ = 1 under |q̈| <= 0.2: not enough
    F = np.vstack([np.eye(2), -np.eye(2)])
    prob.add_second_order_constraint(accelerations, F, np.full(4, 0.2), family="grip")
    assert prob.solve().status.name == "INFEASIBLE"
    scale = prob.relaxation()["grip"]
    assert 1.0 < scale < math.inf
    wide = pp.TimeScalingProblem(arm_path(), grid=30)
    wide.set_boundary_speeds(1.0, 0.0)
    wide.add_second_order_constraint(accelerations, F, np.full(4, 0.2 * scale))
    ok(wide.solve())
    narrow = pp.TimeScalingProblem(arm_path(), grid=30)
    narrow.set_boundary_speeds(1.0, 0.0)
    narrow.add_second_order_constraint(accelerations, F, np.full(4, 0.2 * scale / 1.01))
    assert narrow.solve().status.name == "INFEASIBLE"


def test_it_pickles_with_module_level_callables():
    for prob in (planar_problem(N=50), gripper_problem(N=40)):
        back = pickle.loads(pickle.dumps(prob))
        assert [type(c) for c in back.constraints] == [type(c) for c in prob.constraints]
        r, rb = ok(prob.solve()), ok(back.solve())
        assert rb.duration == r.duration and np.array_equal(rb.sdot, r.sdot)
    c = pickle.loads(pickle.dumps(gripper_problem(N=10).constraints[1]))
    assert c.name == "grip" and c.inverse_dynamics is box_wrench and c.F is grip_F


def test_a_relaxed_constraint_pickles_with_its_scale():
    F = np.vstack([np.eye(2), -np.eye(2)])
    c = pp.SecondOrderConstraint(accelerations, F, np.full(4, 0.2)).relaxed(3.0)
    prob = pp.TimeScalingProblem(arm_path(), grid=10)
    prob.add_constraint(c)
    back = pickle.loads(pickle.dumps(prob))
    assert np.array_equal(back.feasible_set(5).halfplanes, prob.feasible_set(5).halfplanes)


def test_a_lambda_does_not_pickle_and_the_error_names_it():
    prob = pp.TimeScalingProblem(arm_path(), grid=10)
    prob.add_torque_limits(inverse_dynamics=lambda q, qd, qdd: planar_arm(q, qd, qdd), tau_min=[-40, -15],
                           tau_max=[40, 15])
    with pytest.raises(pickle.PicklingError, match=r"constraint 'torque limits': its inverse_dynamics <function .*"
                                                   r"<lambda>.* does not pickle .*module level"):
        pickle.dumps(prob)
    F = np.vstack([np.eye(2), -np.eye(2)])
    c = pp.SecondOrderConstraint(accelerations, F, lambda q: np.ones((len(q), 4)), name="cap")
    with pytest.raises(pickle.PicklingError, match=r"constraint 'cap': its g <function"):
        pickle.dumps(c)


def test_solve_many_on_threads_and_processes():
    probs = [planar_problem(N=40 + 5 * k) for k in range(4)]
    serial = [ok(p.solve(guarantee="continuous")).duration for p in probs]
    assert [r.duration for r in pp.solve_many(probs, workers=2, guarantee="continuous")] == serial
    with process_pool(2) as ex:
        assert [r.duration for r in pp.solve_many(probs, executor=ex)] == [ok(p.solve()).duration for p in probs]


def test_python_threads_solving_one_problem_together():
    prob = planar_problem(N=30)
    ref = ok(prob.solve(guarantee="continuous")).duration
    out = [None] * 4

    def run(i):
        out[i] = prob.solve(guarantee="continuous").duration

    ts = [threading.Thread(target=run, args=(i,)) for i in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join(timeout=120)
    assert out == [ref] * 4


# ---- exceptions of the callbacks come back as they were


class Boom(Exception):
    pass


class RaisesAfter:
    def __init__(self, n):
        self.n, self.calls = n, 0

    def __call__(self, q, qd, qdd):
        self.calls += 1
        if self.calls >= self.n:
            raise Boom(f"call {self.calls}")
        return planar_arm(q, qd, qdd)


def test_a_callback_exception_comes_out_of_the_call():
    prob = pp.TimeScalingProblem(arm_path(), grid=12)
    with pytest.raises(Boom, match="call 1"):
        prob.add_torque_limits(inverse_dynamics=RaisesAfter(1), tau_min=[-40, -15], tau_max=[40, 15])
    assert prob.constraints == []
    prob.add_velocity_limits([-3.0, -3.0], [3.0, 3.0])
    prob.add_torque_limits(inverse_dynamics=RaisesAfter(2), tau_min=[-40, -15], tau_max=[40, 15])
    with pytest.raises(Boom, match="call 2"):
        prob.solve(guarantee="continuous")  # the audit calls it again, with the GIL released
    with pytest.raises(Boom):
        prob.restarted(0.5, 0.0)
    bad_F = pp.SecondOrderConstraint(accelerations, lambda q: 1 / 0, np.ones(2))
    with pytest.raises(ZeroDivisionError):
        pp.TimeScalingProblem(arm_path(), grid=5).add_constraint(bad_F)


# ---- every validation branch names the argument and value


def test_validation_of_what_the_callbacks_return():
    F = np.vstack([np.eye(2), -np.eye(2)])
    g = np.ones(4)

    def add(id_=accelerations, F_=F, g_=g, **kw):
        pp.TimeScalingProblem(arm_path(), grid=10).add_second_order_constraint(id_, F_, g_, **kw)

    with pytest.raises(pp.InvalidInputError, match=r"inverse_dynamics\(q, qd, qdd\) returned shape \(11, 2\), "
                                                   r"expected \(33, nw\)"):
        add(lambda q, qd, qdd: qdd[:11])
    with pytest.raises(pp.InvalidInputError, match=r"the value inverse_dynamics\(q, qd, qdd\) returned has shape "
                                                   r"\(33, 2, 1\), expected a 2-D array"):
        add(lambda q, qd, qdd: qdd[:, :, None])
    with pytest.raises(pp.InvalidInputError, match=r"the value inverse_dynamics\(q, qd, qdd\) returned must be an "
                                                   r"array, got None"):
        add(lambda q, qd, qdd: None)

    def nan_at(q, qd, qdd):
        w = qdd.copy()
        w[11 + 4, 1] = np.nan
        return w

    with pytest.raises(pp.InvalidInputError, match=r"constraint 'second-order constraint': inverse_dynamics returned "
                                                   r"w\[1\] = nan at grid point 4 \(s = 0\.4\), in id\(p, 0, p'\)"):
        add(nan_at)
    with pytest.raises(pp.InvalidInputError, match=r"returned w\[0\] = inf at grid point 0"):
        add(lambda q, qd, qdd: np.full_like(qdd, np.inf))
    with pytest.raises(pp.InvalidInputError, match=r"F\(q\) returned has shape \(11, 4\), expected \(11, r, nw\)"):
        add(F_=lambda q: np.ones((len(q), 4)))
    with pytest.raises(pp.InvalidInputError, match=r"F\(q\) returned shape \(44, 3\), expected \(11·r, 2\)"):
        add(F_=lambda q: np.ones((len(q), 4, 3)))

    def F_nan(q):
        out = np.broadcast_to(F, (len(q), 4, 2)).copy()
        out[6, 2, 1] = np.nan
        return out

    with pytest.raises(pp.InvalidInputError, match=r"F\(q\) returned F\[2, 1\] = nan at grid point 6"):
        add(F_=F_nan)
    with pytest.raises(pp.InvalidInputError, match=r"g\(q\) returned shape \(11, 3\), expected \(11, 4\)"):
        add(g_=lambda q: np.ones((len(q), 3)))
    with pytest.raises(pp.InvalidInputError, match=r"g\(q\) returned g\[0\] = -inf at grid point 0"):
        add(g_=lambda q: np.full((len(q), 4), -np.inf))
    with pytest.raises(pp.InvalidInputError, match=r"g\[2\] = nan must be a number or \+inf"):
        add(g_=np.array([1.0, 1.0, np.nan, 1.0]))
    with pytest.raises(pp.InvalidInputError, match=r"g has size 3, expected 4 \(one per row of F\)"):
        add(g_=np.ones(3))
    with pytest.raises(pp.InvalidInputError, match=r"F\[1, 0\] = inf must be finite"):
        add(F_=np.array([[1.0, 0.0], [np.inf, 0.0]]), g_=np.ones(2))
    with pytest.raises(pp.InvalidInputError, match=r"labels has 3 entries, expected 4 \(one per row of F\)"):
        add(labels=["a", "b", "c"])
    with pytest.raises(pp.InvalidInputError, match=r"w of size 2, expected 3 \(the columns of F\)"):
        add(F_=np.ones((4, 3)))


def test_validation_of_per_sample_callbacks():
    F = np.vstack([np.eye(2), -np.eye(2)])

    def add(id_, F_=F, g_=np.ones(4)):
        pp.TimeScalingProblem(arm_path(), grid=10).add_second_order_constraint(id_, F_, g_, vectorized=False)

    calls = []

    def grows(q, qd, qdd):
        calls.append(1)
        return np.zeros(2 if len(calls) <= 5 else 3)

    with pytest.raises(pp.InvalidInputError, match=r"inverse_dynamics\(q\[i\], qd\[i\], qdd\[i\]\) returned at row 5 "
                                                   r"has size 3, expected 2 \(as at row 0\)"):
        add(grows)
    with pytest.raises(pp.InvalidInputError, match=r"F\(q\[i\]\) returned at grid point 0 has shape \(4,\), "
                                                   r"expected a 2-D array"):
        add(lambda q, qd, qdd: qdd, F_=lambda q: np.ones(4))
    with pytest.raises(pp.InvalidInputError, match=r"g\(q\[i\]\) returned at grid point 1 has size 3, expected 4"):
        add(lambda q, qd, qdd: qdd, g_=lambda q: np.ones(4 if q[0] == 0.0 else 3))


def test_validation_of_the_arguments():
    prob = pp.TimeScalingProblem(arm_path(), grid=10)
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    with pytest.raises(pp.InvalidInputError, match=r"add_torque_limits: robot = <.*> and inverse_dynamics given: "
                                                   r"give one"):
        prob.add_torque_limits(robot, inverse_dynamics=planar_arm, tau_min=[-1, -1], tau_max=[1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"tau_min must be given \(one per joint\) with inverse_dynamics"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_max=[1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"tau_max must be given"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"tau_min\[1\] = 2 must be <= tau_max\[1\] = 1"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-1, 2], tau_max=[1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"tau_min has size 3, expected 2"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-1, -1, -1], tau_max=[1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"tau_max\[0\] = nan must be a number"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-1, -1], tau_max=[np.nan, 1])
    with pytest.raises(pp.InvalidInputError, match=r"path has 2 coordinates, constraint 'torque limits' has 3 joints"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-1, -1, -1], tau_max=[1, 1, 1])
    with pytest.raises(pp.InvalidInputError, match=r"margin = 2 closes the torque range of joint 1"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-9, -1], tau_max=[9, 1], margin=2.0)
    with pytest.raises(pp.InvalidInputError, match=r"scale = 0 must be > 0"):
        prob.add_torque_limits(inverse_dynamics=planar_arm, tau_min=[-9, -1], tau_max=[9, 1], scale=0.0)
    with pytest.raises(TypeError, match=r"robot must be a pathpace.RobotModel, got None"):
        prob.add_torque_limits()  # neither robot nor inverse_dynamics: today's message
    with pytest.raises(TypeError, match=r"inverse_dynamics must be a callable w = f\(q, qd, qdd\), got ndarray"):
        prob.add_second_order_constraint(np.ones(3), np.eye(2), np.ones(2))
    with pytest.raises(TypeError, match=r"F must be a callable F\(q\) or an array \(r, nw\), got None"):
        prob.add_second_order_constraint(accelerations, None, np.ones(2))
    with pytest.raises(TypeError, match=r"g must be a callable g\(q\) or an array \(r,\), got None"):
        prob.add_second_order_constraint(accelerations, np.eye(2), None)
    with pytest.raises(TypeError, match=r"vectorized must be a bool, got str"):
        prob.add_second_order_constraint(accelerations, np.eye(2), np.ones(2), vectorized="no")
    with pytest.raises(TypeError, match=r"add_second_order_constraint\(\): incompatible function arguments(.|\n)*g: object"):
        prob.add_second_order_constraint(accelerations, np.eye(2))
    assert prob.constraints == []


def test_today_add_torque_limits_with_a_robot_is_unchanged():
    robot = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    s = np.linspace(0.0, 1.0, 3)
    path = pp.CubicSplinePath(0.5 * s[:, None], knots=s)
    a, b = pp.TimeScalingProblem(path, grid=30), pp.TimeScalingProblem(path, grid=30)
    a.add_torque_limits(robot)
    b.add_constraint(pp.TorqueLimits(robot))
    assert type(a.constraints[0]) is pp.TorqueLimits
    assert ok(a.solve()).duration == ok(b.solve()).duration
