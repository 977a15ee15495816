"""A constraint family defined only in Python (issue 26): a per-joint speed bound |q̇_j| <= v_j g(s), g(s) = 1 + k s²,
as eq. (16)'s bound ṡ² <= (v_j g(s) / p'_j)², subclassing pathpace.Constraint. The same contracts as
tests/cpp/test_constraint_hooks.cpp: its own closed-form optimum (and with k = 0 VelocityLimits' bit for bit),
composition with torque limits and contact phases, restarts, rows given per grid point, relaxation, pickling,
threads (the hooks are called from C++ with the GIL released) and exceptions that come back as they were."""

import gc
import pickle
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from oracles import duration

DATA = Path(__file__).resolve().parents[1] / "data"


class SpeedProfile(pp.Constraint):
    """|q̇_j| <= v_j (1 + k s²): one row per joint, a = 1, b = 0, c = (v_j g / |p'_j|)², none where p'_j = 0."""

    name = "speed profile"

    def __init__(self, v, k=1.0, names=None, relaxable=True):
        super().__init__()
        self.v, self.k, self.names, self.relaxable = np.asarray(v, float), k, names, relaxable
        self.calls = 0

    def evaluate(self, samples):
        self.calls += 1
        d = np.abs(samples.dq)
        g = 1.0 + self.k * samples.s**2
        with np.errstate(divide="ignore"):
            r = self.v[None, :] * g[:, None] / d
        a = np.where(d != 0, 1.0, 0.0)
        c = np.where(d != 0, r * r, np.inf)
        names = self.names or [f"joint {j}" for j in range(len(self.v))]
        return pp.ConstraintRows(a, np.zeros_like(a), c, [f"speed {n}" for n in names])

    def family(self):
        return "speed" if self.relaxable else ""

    def relaxed(self, scale):
        return type(self)(self.v * scale, self.k, self.names) if self.relaxable else None

    def with_joint_names(self, names):
        return None if self.names else type(self)(self.v, self.k, list(names), self.relaxable)

    def __reduce__(self):
        return type(self), (self.v, self.k, self.names, self.relaxable)


class SpeedTable(pp.Constraint):
    """The same bound given per grid point (its rows on one grid): no grid point may be added, a restart keeps
    the rows of the points it keeps."""

    def __init__(self, a, c, labels):
        super().__init__()
        self.a, self.c, self.labels = np.asarray(a), np.asarray(c), list(labels)

    @property
    def name(self):
        return "speed table"

    def evaluate(self, samples):
        if len(samples) != len(self.a):
            raise pp.InvalidInputError("speed table: rows for another grid")
        return pp.ConstraintRows(self.a, np.zeros_like(self.a), self.c, self.labels)

    def per_grid_point(self):
        return True

    def at_grid_points(self, kept):
        return SpeedTable(self.a[kept], self.c[kept], self.labels)

    def __reduce__(self):
        return SpeedTable, (self.a, self.c, self.labels)


def table_of(prob, profile):
    rows = profile.evaluate(prob_samples(prob))
    return SpeedTable(rows.a, rows.c, rows.labels)


def prob_samples(prob):
    """The problem's own samples, through a constraint that records them."""
    seen = []

    class Probe(pp.Constraint):
        name = "probe"

        def evaluate(self, samples):
            seen.append(samples)
            n = len(samples)
            return pp.ConstraintRows(np.zeros((n, 1)), np.zeros((n, 1)), np.full((n, 1), np.inf), ["probe"])

    copy = pp.TimeScalingProblem(prob.path, grid=prob.grid)
    copy.add_constraint(Probe())
    return seen[0]


def bend():
    """p(s) = (s, s²/2) on [0, 1] (not-a-knot reproduces it): p' = (1, s)."""
    s = np.linspace(0.0, 1.0, 5)
    return pp.CubicSplinePath(np.column_stack([s, 0.5 * s * s]), knots=s)


def speed_only_duration(path, grid, v, k, x_begin=0.0, x_end=0.0):
    """The optimum of a bound on ṡ² alone (s̈ free): every grid point at its largest ṡ², the ends at the boundary
    speeds (eq. 27)."""
    d = np.abs(path.dq(grid))
    with np.errstate(divide="ignore"):
        x = np.min(np.where(d != 0, (np.asarray(v)[None, :] * (1 + k * grid**2)[:, None] / d) ** 2, np.inf), axis=1)
    x[0], x[-1] = x_begin, x_end
    return duration(grid, x)


def ok(res):
    assert res.status.name == "OPTIMAL", res.message
    return res


V = (1.0, 0.6)


def test_a_python_family_alone_has_its_closed_form_optimum_and_velocity_limits_bit_for_bit():
    prob = pp.TimeScalingProblem(bend(), grid=40)
    prob.add_constraint(SpeedProfile(V))
    res = ok(prob.solve())
    assert res.duration == pytest.approx(speed_only_duration(bend(), prob.grid, V, 1.0), rel=1e-9)
    fs = prob.feasible_set(40)  # joint 1 binds at s = 1: (0.6 · 2 / 1)² = 1.44 < (1 · 2)²
    assert fs.x_max == pytest.approx(1.44, rel=1e-12)
    assert fs.x_max_label == "speed joint 1"
    constant, builtin = pp.TimeScalingProblem(bend(), grid=40), pp.TimeScalingProblem(bend(), grid=40)
    constant.add_constraint(SpeedProfile(V, k=0.0))
    builtin.add_velocity_limits(-np.array(V), V)
    rc, rb = ok(constant.solve()), ok(builtin.solve())
    assert rc.duration == rb.duration
    assert np.array_equal(rc.sdot, rb.sdot)
    assert rc.duration != res.duration


def test_the_python_object_lives_while_cpp_holds_it_and_takes_joint_names():
    prob = pp.TimeScalingProblem(bend(), grid=10)
    prob.add_constraint(SpeedProfile(V))  # no reference kept here
    gc.collect()
    (c,) = prob.constraints
    assert isinstance(c, SpeedProfile) and c.calls == 1 and c.name == "speed profile"
    prob.set_joint_names(["x", "y"])  # with_joint_names: a new SpeedProfile in its place
    gc.collect()
    assert prob.constraints[0].names == ["x", "y"]
    assert prob.feasible_set(10).x_max_label == "speed y"
    tail = prob.restarted(0.5, 0.5)  # evaluated again, on the tail's grid, by the object C++ holds
    assert tail.constraints[0] is prob.constraints[0] and prob.constraints[0].calls == 2


def pendulum_problem(*constraints, N=50):
    pend = pp.RobotModel.from_urdf(str(DATA / "pendulum.urdf"))
    s = np.linspace(0.0, 1.0, 3)
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(0.5 * s[:, None], knots=s), grid=N)  # to 0.5 rad, held there
    for c in constraints:
        prob.add_constraint(c(pend) if callable(c) and not isinstance(c, pp.Constraint) else c)
    return prob, pend


def test_composes_with_torque_limits():
    torque = lambda robot: pp.TorqueLimits(robot)  # noqa: E731
    v = [0.5]  # ṡ² <= (1 + s²)²: binds mid-swing, the torque at the ends
    both, pend = pendulum_problem(torque, SpeedProfile(v))
    assert [c.name for c in both.constraints] == ["torque limits", "speed profile"]
    r = ok(both.solve())
    rt, rs = ok(pendulum_problem(torque)[0].solve()), ok(pendulum_problem(SpeedProfile(v))[0].solve())
    tr = r.trajectory()
    assert tr.robot is not None and tr.robot.name == pend.name and tr.contacts is None
    assert np.array_equal(r.tau_max, both.constraints[0].tau_max)
    assert r.duration > rt.duration * (1 + 1e-3) and r.duration > rs.duration * (1 + 1e-3)
    const, _ = pendulum_problem(torque, SpeedProfile(v, k=0.0))
    builtin, _ = pendulum_problem(torque, pp.VelocityLimits(-np.array(v), v))
    rc, rb = ok(const.solve()), ok(builtin.solve())
    assert rc.duration == rb.duration and np.array_equal(rc.sdot, rb.sdot)


# hand_box.urdf: a hand pushes a box (s in [0, 1]) then brakes it (s in [1, 2]), x = s for both; its force
# within ±4 N on 2 kg: |s̈| <= 2, s̈ >= 0 while pushing, <= 0 while braking.
def hand_box():
    return pp.RobotModel.from_urdf(str(DATA / "hand_box.urdf"))


def on_box(nx):
    return [pp.Contact("box", point=(0, 0, 0), normal=(nx, 0, 0), friction=0.5, other_link="hand")]


def together():
    s = np.linspace(0.0, 2.0, 3)
    return pp.CubicSplinePath(np.column_stack([s, s]), knots=s)


PHASES = [(0.0, 1.0, on_box(1)), (1.0, 2.0, on_box(-1))]


def hand_limits(robot):
    hand = robot.joint_names.index("hand_x")
    lo, hi = np.zeros(2), np.zeros(2)
    lo[hand], hi[hand] = -4.0, 4.0
    return hand, lo, hi


class PushCap(SpeedProfile):
    """|q̇_j| <= sqrt(2 + 0.5 min(s, 2 - s)): rising while pushing, falling while braking, slower than 2a = 4."""

    def evaluate(self, samples):
        rows = super().evaluate(samples)
        cap = 2.0 + 0.5 * np.minimum(samples.s, 2.0 - samples.s)
        return pp.ConstraintRows(rows.a, rows.b, np.where(np.isfinite(rows.c), cap[:, None], np.inf), rows.labels)


def push_brake_capped(grid, k_switch, capped=True):
    """min(2as, 2a(2 - s), cap(s)) with a = 2, and at the switch (s̈ = 0 on both intervals) the smaller neighbour."""
    th = np.minimum(4 * grid, 4 * (2.0 - grid))
    if capped:
        th = np.minimum(th, 2.0 + 0.5 * np.minimum(grid, 2.0 - grid))
    th[k_switch] = min(th[k_switch - 1], th[k_switch + 1])
    return duration(grid, th)


@pytest.mark.parametrize("speed_first", [True, False])
def test_composes_with_contact_phases_and_torque(speed_first):
    robot = hand_box()
    hand, lo, hi = hand_limits(robot)
    prob, without = pp.TimeScalingProblem(together(), grid=20), pp.TimeScalingProblem(together(), grid=20)
    if speed_first:
        prob.add_constraint(PushCap(V))
    prob.add_contact_phases(robot, PHASES, cone_edges=4)
    prob.add_torque_limits(robot, tau_min=lo, tau_max=hi)
    if not speed_first:
        prob.add_constraint(PushCap(V))
    without.add_contact_phases(robot, PHASES, cone_edges=4)
    without.add_torque_limits(robot, tau_min=lo, tau_max=hi)
    names = [c.name for c in prob.constraints]
    assert len(names) == 3 and names.count("speed profile") == 1  # torque merged into both phases
    for c in prob.constraints:
        if isinstance(c, pp.ContactConstraint):
            assert c.tau_max[hand] == 4.0
    r, r0 = ok(prob.solve()), ok(without.solve())
    tr = r.trajectory()
    assert r.tau_max[hand] == 4.0 and tr.robot is not None and tr.contacts is not None and len(tr.contact_phases) == 2
    assert r.duration == pytest.approx(push_brake_capped(prob.grid, 10), rel=1e-9)
    assert r0.duration == pytest.approx(push_brake_capped(prob.grid, 10, capped=False), rel=1e-9)
    assert r.duration > r0.duration * (1 + 1e-3)


def test_a_contact_switch_reevaluates_it_and_rows_per_grid_point_refuse_the_insertion():
    robot = hand_box()
    _, lo, hi = hand_limits(robot)
    prob = pp.TimeScalingProblem(together(), grid=7)  # multiples of 2/7: s = 1 is not a grid point
    prob.add_constraint(PushCap(V))
    prob.add_torque_limits(robot, tau_min=lo, tau_max=hi)
    prob.add_contact_phases(robot, PHASES, cone_edges=4)
    assert prob.intervals == 8 and prob.grid[4] == 1.0
    assert ok(prob.solve()).duration == pytest.approx(push_brake_capped(prob.grid, 4), rel=1e-9)
    table = pp.TimeScalingProblem(together(), grid=7)
    table.add_constraint(table_of(table, PushCap(V)))
    with pytest.raises(pp.InvalidInputError, match=r"phases\[1\]\.s_begin = 1 is not a grid point .*\('speed table'\)"):
        table.add_contact_phases(robot, PHASES, cone_edges=4)
    assert table.intervals == 7


def test_restart_carries_it_and_rows_per_grid_point_need_a_grid_point():
    prob = pp.TimeScalingProblem(bend(), grid=40)
    prob.add_constraint(SpeedProfile(V))
    prob.set_boundary_speeds(0.0, 0.5)
    s0, sdot0 = 0.4321, 0.7  # between grid points 17 and 18
    tail = prob.restarted(s0, sdot0)
    assert [c.name for c in tail.constraints] == ["speed profile"] and tail.grid[0] == s0
    expected = speed_only_duration(bend(), tail.grid, V, 1.0, sdot0**2, 0.25)
    assert ok(tail.solve()).duration == pytest.approx(expected, rel=1e-9)
    x0 = (1 + s0**2) ** 2  # joint 0 binds at s0
    assert prob.restarted(s0, np.sqrt(x0) * 1.01).solve().status.name == "INFEASIBLE"
    assert prob.restarted(s0, np.sqrt(x0) * 0.99).solve().status.name == "OPTIMAL"

    table = pp.TimeScalingProblem(bend(), grid=40)
    table.add_constraint(table_of(table, SpeedProfile(V)))
    table.set_boundary_speeds(0.0, 0.5)
    with pytest.raises(pp.InvalidInputError, match=r"s0 = 0\.4321 is not a grid point \(nearest: grid\[17\].*"
                                                   r"constraint 'speed table' is given per grid point"):
        table.restarted(s0, sdot0)
    at_grid, same = table.restarted(table.grid[17], sdot0), prob.restarted(prob.grid[17], sdot0)
    assert at_grid.intervals == 23 and at_grid.constraints[0].name == "speed table"
    ra, rs = ok(at_grid.solve()), ok(same.solve())
    assert ra.duration == rs.duration and np.array_equal(ra.sdot, rs.sdot)


@pytest.mark.parametrize("relaxable", [True, False])
def test_relaxation_scales_the_family(relaxable):
    prob = pp.TimeScalingProblem(bend(), grid=20)
    prob.add_constraint(SpeedProfile(V, relaxable=relaxable))
    prob.set_boundary_speeds(3.0, 0.0)  # ṡ² <= 1 at s = 0: needs the speeds x 3
    assert prob.solve().status.name == "INFEASIBLE"
    m = prob.relaxation(tolerance=1e-3)
    if not relaxable:
        assert m == {}
        return
    assert list(m) == ["speed"]
    assert 3.0 * (1 - 1e-12) <= m["speed"] <= 3.0 * (1 + 1e-3) * (1 + 1e-12)


def test_a_problem_holding_it_pickles_to_the_same_optimum():
    robot = hand_box()
    _, lo, hi = hand_limits(robot)
    prob = pp.TimeScalingProblem(together(), grid=20)
    prob.add_contact_phases(robot, PHASES, cone_edges=4)
    prob.add_torque_limits(robot, tau_min=lo, tau_max=hi)
    prob.add_constraint(PushCap(V))
    table = pp.TimeScalingProblem(bend(), grid=30)
    table.add_constraint(table_of(table, SpeedProfile(V)))
    for p in (prob, table):
        back = pickle.loads(pickle.dumps(p))
        assert [type(c) for c in back.constraints] == [type(c) for c in p.constraints]
        r, rb = ok(p.solve()), ok(back.solve())
        assert rb.duration == r.duration and np.array_equal(rb.sdot, r.sdot)


def test_threads_and_solve_many_call_it_without_deadlock():
    """evaluate runs from C++ with the GIL released: in add_constraint (threads building problems), and in
    solve(guarantee='continuous'), whose audit samples the rows between grid points, on solve_many's threads."""

    def build(k):
        p = pp.TimeScalingProblem(bend(), grid=30 + k)
        p.add_constraint(SpeedProfile(V))
        p.add_acceleration_limits([-2.0, -2.0], [2.0, 2.0])
        return p

    with ThreadPoolExecutor(4) as ex:
        probs = list(ex.map(build, range(8)))
    serial = [p.solve(guarantee="continuous") for p in probs]
    calls = [p.constraints[0].calls for p in probs]
    assert all(r.status.name == "OPTIMAL" for r in serial)
    assert all(c > 1 for c in calls)  # the audit evaluated it during the solve
    threaded = pp.solve_many(probs, workers=4, guarantee="continuous")
    assert [r.duration for r in threaded] == [r.duration for r in serial]
    assert all(p.constraints[0].calls > c for p, c in zip(probs, calls))
    # Python threads solving one problem together, each entering evaluate.
    out = [None] * 4

    def run(i):
        out[i] = probs[0].solve(guarantee="continuous").duration

    ts = [threading.Thread(target=run, args=(i,)) for i in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join(timeout=120)
    assert out == [serial[0].duration] * 4


class Boom(Exception):
    pass


class Raises(pp.Constraint):
    name = "raises"

    def __init__(self, when):
        super().__init__()
        self.when, self.n = when, 0

    def evaluate(self, samples):
        self.n += 1
        if self.n >= self.when:
            raise Boom(f"call {self.n}")
        n = len(samples)
        return pp.ConstraintRows(np.ones((n, 1)), np.zeros((n, 1)), np.ones((n, 1)), ["raises"])

    def __reduce__(self):
        return Raises, (1,)


def test_exceptions_in_python_hooks_come_back_as_they_were():
    prob = pp.TimeScalingProblem(bend(), grid=10)
    with pytest.raises(Boom, match="call 1"):
        prob.add_constraint(Raises(1))  # the GIL released around the add
    assert prob.constraints == []
    prob.add_constraint(Raises(2))
    with pytest.raises(Boom, match="call 2"):
        prob.restarted(0.5, 0.0)
    with pytest.raises(Boom, match="call 1"):
        pickle.loads(pickle.dumps(prob))  # setstate evaluates it again, with the GIL released


def test_python_hooks_that_break_their_contract_are_named():
    class NoEvaluate(pp.Constraint):
        name = "no evaluate"

    class NoName(pp.Constraint):
        def evaluate(self, samples):
            return None

    class WrongRows(pp.Constraint):
        name = "wrong rows"

        def evaluate(self, samples):
            return np.zeros((len(samples), 1))

    class NanRows(pp.Constraint):
        name = "nan rows"

        def evaluate(self, samples):
            n = len(samples)
            return pp.ConstraintRows(np.full((n, 1), np.nan), np.zeros((n, 1)), np.ones((n, 1)), ["nan"])

    prob = pp.TimeScalingProblem(bend(), grid=10)
    with pytest.raises(pp.Error, match="must define evaluate"):
        prob.add_constraint(NoEvaluate())
    with pytest.raises(pp.Error, match="must define name"):
        NoName().name
    with pytest.raises(TypeError, match=r"constraint 'wrong rows': evaluate\(samples\) must be a pathpace.ConstraintRows, "
                                        r"got ndarray"):
        prob.add_constraint(WrongRows())
    with pytest.raises(pp.InvalidInputError, match="nan rows"):
        prob.add_constraint(NanRows())
    assert prob.constraints == []


def test_constraint_rows_and_path_samples():
    rows = pp.ConstraintRows(np.ones(4), np.zeros(4), np.full(4, 2.0), ["one"])  # 1-D: one row
    assert rows.rows == 1 and rows.a.shape == (4, 1) and rows.labels == ["one"]
    with pytest.raises(pp.InvalidInputError, match=r"b has shape \(3, 1\), expected a's \(4, 1\)"):
        pp.ConstraintRows(np.ones(4), np.zeros(3), np.ones(4), ["one"])
    with pytest.raises(pp.InvalidInputError, match=r"c has shape \(4, 2\), expected a's \(4, 1\)"):
        pp.ConstraintRows(np.ones(4), np.zeros(4), np.ones((4, 2)), ["one"])
    with pytest.raises(pp.InvalidInputError, match=r"labels has 2 entries, expected one per row \(1\)"):
        pp.ConstraintRows(np.ones(4), np.zeros(4), np.ones(4), ["one", "two"])
    prob = pp.TimeScalingProblem(bend(), grid=8)
    ps = prob_samples(prob)
    assert len(ps) == 9 and ps.dof == 2 and np.array_equal(ps.s, prob.grid)
    assert np.allclose(ps.dq, bend().dq(prob.grid), rtol=0, atol=1e-12)
    with pytest.raises(ValueError):
        ps.q[0, 0] = 1.0  # read-only
    # A library constraint answers its hooks from Python too.
    vel = pp.VelocityLimits([-1.0, -1.0], [1.0, 1.0])
    assert vel.family() == "velocity" and not vel.per_grid_point()
    assert vel.relaxed(2.0).vmax.tolist() == [2.0, 2.0]
    assert vel.evaluate(ps).labels == ["velocity joint 0", "velocity joint 1"]
