"""Issue 21, deliver 1: the centred force distribution (ForceDistribution::Centre, the default of
Trajectory.contact_forces / contact_wrenches / centers_of_pressure and ContactConstraint.force_distribution).

At every 1 kHz sample of a timed sway (Talos, 4 corners per sole; Romeo, 8 sole corners), seeded amplitude,
several margins: the forces realise the motion (pinocchio's centroidal momentum rate, our unactuated rows) and
keep every physical row (friction pyramid of μ, unilateral, torque limits); they move by less than 2 % of the
weight between samples inside a grid interval; at a grid time no link's load jumps by more than the total
does, plus 2 % of the weight (with jerk limits, which make s̈ continuous: without them no distribution can);
each sole's centre of pressure is in its support polygon; and the centre has
at least the vertex's room in the physical rows."""

import sys
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import contact_corpus as cc  # noqa: E402

pin = pytest.importorskip("pinocchio")

CONE_EDGES = 8
JUMP = 0.02  # of the weight (the targets)
# (robot, (min_normal_force, friction_margin)): the example's margins, and others.
CASES = [("talos", (10.0, 0.5)), ("talos", (20.0, 0.3)), ("romeo", (10.0, 0.5)), ("romeo", (5.0, 0.3))]


def sway_path(h, amplitude):
    q0 = cc.standing_posture(h)
    s = np.linspace(0.0, 1.0, 21)
    wp = [q0] + [cc.ik(h, q0, base_y=amplitude * np.sin(2 * np.pi * si)) for si in s[1:]]
    return pp.CubicSplinePath(np.array(wp), knots=s)


_timed = {}


def timed(name, margins, seed=21, jerk=None):
    """The sway timed with these margins (and |q⃛| <= jerk on every joint), its 1 kHz samples and both
    distributions there."""
    key = (name, margins, jerk)
    if key not in _timed:
        h = cc.load(name)
        amplitude = np.random.default_rng(seed).uniform(0.04, 0.06)
        path = sway_path(h, amplitude)
        cons = cc.contacts(h, "sway")
        prob = pp.TimeScalingProblem(path, grid=100)
        prob.add_contacts(h.robot, cons, cone_edges=CONE_EDGES, min_normal_force=margins[0],
                          friction_margin=margins[1], drift_tolerance=1e-4)
        if jerk is not None:
            prob.add_jerk_limits(np.full(h.robot.nq, -jerk), np.full(h.robot.nq, jerk))
        res = prob.solve()
        assert res.status == pp.Status.OPTIMAL
        traj = res.trajectory()
        t = np.arange(0.0, traj.duration, 1e-3)
        _timed[key] = (h, cons, traj, t, traj.contact_forces(t), traj.contact_forces(t, distribution="vertex"))
    return _timed[key]


def pyramid_slack(cons, forces):
    """(samples, contacts, k) slack of each facet of the k-edged pyramid of μ inscribed in each cone (N):
    an independent copy of the library's generators n + μ (cos φ t1 + sin φ t2), φ = 2π e / k."""
    out = []
    for i, c in enumerate(cons):
        n = np.asarray(c.normal, float) / np.linalg.norm(c.normal)
        e = np.array([0.0, 1.0, 0.0]) if abs(n[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
        t1 = np.cross(n, e)
        t1 /= np.linalg.norm(t1)
        t2 = np.cross(n, t1)
        g = [n + c.friction * (np.cos(p) * t1 + np.sin(p) * t2) for p in 2 * np.pi * np.arange(CONE_EDGES) / CONE_EDGES]
        facets = []
        for a, b in zip(g, g[1:] + g[:1]):
            w = np.cross(a, b)
            w /= np.linalg.norm(w)
            facets.append(w if w @ n > 0 else -w)
        out.append(forces[:, i] @ np.array(facets).T)
    return np.stack(out, axis=1)


@pytest.mark.parametrize("name,margins", CASES)
def test_the_centre_realises_the_motion_within_every_physical_row(name, margins):
    h, cons, traj, t, cf, _ = timed(name, margins)
    weight = h.robot.mass * 9.81
    assert np.all(cf.feasible) and np.all(cf.centred)
    # Friction pyramid of μ (no margin) and unilateral, at every sample.
    assert np.min(pyramid_slack(cons, cf.forces)) >= -1e-9 * weight
    assert np.all(cf.forces[..., 2] >= -1e-9 * weight)
    # Torque limits (before scale and margin) and the floating base's balance (unactuated: τ = 0).
    con = traj.contacts
    lo, hi = con.physical_tau_min, con.physical_tau_max
    assert np.all(cf.torques >= lo - 1e-9 * weight) and np.all(cf.torques <= hi + 1e-9 * weight)
    unact = (lo == 0) & (hi == 0)
    assert unact.sum() == 6 and np.max(np.abs(cf.torques[:, unact])) <= 1e-6 * weight
    # The same against pinocchio: Σ F = m c̈ - m g and the moments about the centre of mass supply dh_G/dt.
    model, data = h.model, h.model.createData()
    q, qd, qdd = traj.evaluate(t)
    pts = np.array([c.point for c in cons])
    for i in range(0, t.size, 7):
        qp, vp, ap = (np.empty(h.robot.nq) for _ in range(3))
        qp[h.perm], vp[h.perm], ap[h.perm] = q[i], qd[i], qdd[i]
        pin.computeCentroidalMomentumTimeVariation(model, data, qp, vp, ap)
        F = cf.forces[i].sum(axis=0)
        M = np.zeros(3)
        for j, c in enumerate(cons):
            p = (h.robot.frame_placement(q[i], c.link) @ np.append(pts[j], 1.0))[:3]
            M += np.cross(p - data.com[0], cf.forces[i, j])
        assert np.allclose(F + data.mass[0] * model.gravity.linear, data.dhg.linear, rtol=0, atol=1e-6 * weight)
        assert np.allclose(M, data.dhg.angular, rtol=0, atol=1e-6 * weight)


def jumps(traj, t, forces, links_force):
    """Worst force step between consecutive samples inside a grid interval, and at grid times the worst
    (link force step - total force step), all in N."""
    cell = np.searchsorted(traj.times, t, side="right")
    same = cell[1:] == cell[:-1]
    step = np.linalg.norm(np.diff(forces, axis=0), axis=2).max(axis=1)
    link_step = np.linalg.norm(np.diff(links_force, axis=0), axis=2).max(axis=1)
    total_step = np.linalg.norm(np.diff(links_force.sum(axis=1), axis=0), axis=1)
    return step[same].max(), (link_step - total_step)[~same].max(), step[~same].max()


@pytest.mark.parametrize("name,margins", CASES)
def test_the_centre_is_continuous_inside_grid_intervals(name, margins):
    h, cons, traj, t, cf, cv = timed(name, margins)
    weight = h.robot.mass * 9.81
    w = traj.contact_wrenches(t)
    inside, _, _ = jumps(traj, t, cf.forces, w.force)
    assert inside <= JUMP * weight, inside / weight


@pytest.mark.xfail(strict=True, reason="no distribution can: at a switch of s̈ the roll moment's jump must be carried "
                   "by the feet's loads (see least_link_jump's test); with jerk limits s̈ is continuous and the "
                   "target holds (test_with_jerk_limits_no_link_load_jumps_more_than_the_total)")
@pytest.mark.parametrize("name,margins", CASES[:1])
def test_at_a_grid_time_no_link_load_jumps_more_than_the_total(name, margins):
    h, cons, traj, t, cf, cv = timed(name, margins)
    weight = h.robot.mass * 9.81
    _, excess, _ = jumps(traj, t, cf.forces, traj.contact_wrenches(t).force)
    assert excess <= JUMP * weight, excess / weight


@pytest.mark.parametrize("name,margins", CASES)
def test_with_jerk_limits_no_link_load_jumps_more_than_the_total(name, margins):
    """The target that the test above cannot meet, met once s̈ is continuous: with |q⃛| <= 20 rad/s³ on every
    joint the motion's wrench is continuous in t, so is the centre of its force set, and at a grid time no
    link's load moves by more than the total does plus 2 % of the weight, nor by more than that between two
    samples inside an interval. Measured: 0.0035-0.0049 of the weight at grid times, 0.0036-0.0043 inside
    (without jerk limits: 0.45-0.62 at grid times), T 7-19 % above the timing without them."""
    h, cons, traj, t, cf, _ = timed(name, margins, jerk=20.0)
    weight = h.robot.mass * 9.81
    assert np.all(cf.feasible) and np.all(cf.centred)
    inside, excess, _ = jumps(traj, t, cf.forces, traj.contact_wrenches(t).force)
    assert inside <= JUMP * weight, inside / weight
    assert excess <= JUMP * weight, excess / weight


def least_link_jump(h, cons, traj, t, j, link, before):
    """The smallest |N_link(t_j) - before| over every force distribution that realises the motion at t_j
    (pyramid of μ, torque limits, the base's balance): an LP of scipy's, independent of pathpace's rows."""
    from scipy.optimize import linprog
    q = traj.q(t[j])
    tau = traj.torques(t[j], h.robot)
    m, k = len(cons), CONE_EDGES
    JT = np.hstack([h.robot.point_jacobian(q, c.link, c.point).T for c in cons])  # τ = τ_id - Jᵀ f
    con = traj.contacts
    lo, hi = con.physical_tau_min, con.physical_tau_max
    eq = (lo == hi)
    A_ub, b_ub = [JT[~eq], -JT[~eq]], [tau[~eq] - lo[~eq], hi[~eq] - tau[~eq]]
    for i in range(m):
        for e in range(k):
            phi = 2 * np.pi * (e + 0.5) / k
            row = np.zeros(3 * m)
            row[3 * i:3 * i + 3] = [np.cos(phi), np.sin(phi), -cons[i].friction * np.cos(np.pi / k)]
            A_ub.append(row[None])
            b_ub.append([0.0])
    mine = np.zeros(3 * m)
    for i, c in enumerate(cons):
        if c.link == link:
            mine[3 * i + 2] = 1.0
    A_ub = np.vstack([np.hstack([a, np.zeros((a.shape[0], 1))]) for a in A_ub]
                     + [np.append(mine, -1.0)[None], np.append(-mine, -1.0)[None]])  # |N - before| <= d
    b_ub = np.concatenate([np.ravel(b) for b in b_ub] + [[before], [-before]])
    A_eq = np.hstack([JT[eq], np.zeros((eq.sum(), 1))])
    cost = np.zeros(3 * m + 1)
    cost[-1] = 1.0
    r = linprog(cost, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=tau[eq], bounds=[(None, None)] * (3 * m) + [(0, None)])
    assert r.status == 0, r.message
    return r.fun


def test_at_the_sways_middle_switch_every_distribution_moves_the_load_more_than_the_total():
    # Why the previous target cannot hold: where s̈ flips at the sway's middle, the jump of the lateral force
    # needs a jump of the roll moment about the centre of mass that the soles' centres of pressure cannot
    # carry alone; the loads must move between the feet by more than the total force moves.
    h, cons, traj, t, cf, cv = timed(*CASES[0])
    weight = h.robot.mass * 9.81
    w = traj.contact_wrenches(t)
    cell = np.searchsorted(traj.times, t, side="right")
    total = np.linalg.norm(np.diff(w.force.sum(axis=1), axis=0), axis=1)
    at = np.flatnonzero(cell[1:] != cell[:-1])
    i = at[np.argmax(total[at])]  # the largest total jump
    least = max(least_link_jump(h, cons, traj, t, i + 1, link, w.normal_force[i, l]) for l, link in enumerate(w.links))
    assert least > total[i] + 10 * JUMP * weight, (least / weight, total[i] / weight)
    # The centre moves it by no more than the least a distribution must, plus the total's own jump.
    moved = np.abs(w.normal_force[i + 1] - w.normal_force[i]).max()
    assert moved <= least + total[i], (moved / weight, least / weight, total[i] / weight)


def test_the_vertex_jumps_where_the_centre_does_not():
    # The defect the centre mends (issue 21: Talos's normal forces swap 880 N <-> 40 N between samples).
    h, cons, traj, t, cf, cv = timed(*CASES[0])
    weight = h.robot.mass * 9.81
    wv = traj.contact_wrenches(t, distribution="vertex")
    inside, _, _ = jumps(traj, t, cv.forces, wv.force)
    assert inside > 2 * JUMP * weight, inside / weight
    assert not np.any(cv.centred)


@pytest.mark.parametrize("name,margins", CASES)
def test_centres_of_pressure_lie_in_each_sole(name, margins):
    h, cons, traj, t, cf, _ = timed(name, margins)
    w = traj.contact_wrenches(t)
    np.testing.assert_array_equal(traj.centers_of_pressure(t), w.center_of_pressure)
    q = traj.q(t)
    lx, ly = h.sole_size
    for l, link in enumerate(w.links):
        for i in range(t.size):
            X = h.robot.frame_placement(q[i], link)
            local = np.linalg.solve(X, np.append(w.center_of_pressure[i, l], 1.0))[:3] - np.asarray(h.sole_origin)
            assert abs(local[0]) <= lx / 2 + 1e-9 and abs(local[1]) <= ly / 2 + 1e-9 and abs(local[2]) <= 1e-6


@pytest.mark.parametrize("name,margins", CASES)
def test_the_centre_has_the_vertex_room(name, margins):
    h, cons, traj, t, cf, cv = timed(name, margins)
    weight = h.robot.mass * 9.81
    # Over the motion: the analytic centre maximises Σ log slack, not the smallest one, so at a sample its
    # smallest slack can be below the vertex's (bench/README.md, issue 21: >= 0.65 of it); its worst sample
    # has more room than the vertex's worst.
    assert np.min(cf.slack) >= np.min(cv.slack)
    assert np.all(cf.slack > 0)
    # slack is the smallest distance to a physical row: the pyramid's facets among them.
    assert np.all(np.min(pyramid_slack(cons, cf.forces), axis=(1, 2)) >= cf.slack - 1e-9 * weight)
    np.testing.assert_array_equal(cf.margin, cv.margin)  # the LP's, whichever distribution


def test_a_zero_margin_plan_falls_back_to_the_vertex_where_the_set_has_no_interior():
    h = cc.load("talos")
    path = cc.make_path(h, "sway")
    cons = cc.contacts(h, "sway")
    prob = pp.TimeScalingProblem(path, grid=60)
    prob.add_contacts(h.robot, cons, cone_edges=CONE_EDGES, drift_tolerance=1e-4)
    res = prob.solve()
    traj = res.trajectory()
    t = traj.times  # grid points: the optimum is on the polygon's boundary at most of them
    cf, cv = traj.contact_forces(t), traj.contact_forces(t, distribution="vertex")
    assert np.all(cf.feasible)
    fell = ~np.asarray(cf.centred)
    assert 0 < fell.sum() < t.size  # both kinds occur (28 of 61 fall back, bench/README.md)
    # Where not centred the forces are the vertex, as documented; where centred, strictly inside.
    np.testing.assert_array_equal(cf.forces[fell], cv.forces[fell])
    assert np.all(cf.slack[~fell] > 0)
    weight = h.robot.mass * 9.81
    assert np.all(cv.slack[fell] <= 1e-6 * weight)


def test_distribution_is_checked():
    h, cons, traj, t, cf, _ = timed(*CASES[0])
    with pytest.raises(pp.InvalidInputError, match="distribution = 'middle' must be 'centre' or 'vertex'"):
        traj.contact_forces(t[:3], distribution="middle")
    with pytest.raises(pp.InvalidInputError, match="distribution"):
        traj.contact_wrenches(t[:3], distribution="")
    q, qd, qdd = traj.evaluate(t[:3])
    with pytest.raises(pp.InvalidInputError, match="distribution"):
        traj.contacts.force_distribution(q, qd, qdd, distribution="center")
    one = traj.contact_forces(float(t[5]))
    assert one.forces.shape == (len(cons), 3) and isinstance(one.centred, bool) and isinstance(one.slack, float)
    np.testing.assert_allclose(one.forces, cf.forces[5], rtol=0, atol=1e-6)


def test_the_physical_limits_survive_a_pickle_and_the_scaled_ones_stay_the_lps():
    import pickle
    h, cons, traj, t, _, _ = timed(*CASES[0])
    c = pp.ContactConstraint(h.robot, cons, cone_edges=CONE_EDGES, torque_scale=0.5, torque_margin=0.1)
    actuated = ~((c.physical_tau_min == 0) & (c.physical_tau_max == 0))
    np.testing.assert_array_equal(c.physical_tau_max, h.robot.effort_limits)
    np.testing.assert_allclose(c.tau_max[actuated], 0.5 * h.robot.effort_limits[actuated] - 0.1)
    back = pickle.loads(pickle.dumps(c))
    np.testing.assert_array_equal(back.physical_tau_min, c.physical_tau_min)
    np.testing.assert_array_equal(back.physical_tau_max, c.physical_tau_max)
    np.testing.assert_array_equal(back.tau_max, c.tau_max)
    q, qd, qdd = traj.evaluate(t[::100])
    a, b = c.force_distribution(q, qd, qdd), back.force_distribution(q, qd, qdd)
    np.testing.assert_allclose(b.forces, a.forces, rtol=0, atol=1e-9 * h.robot.mass)
    np.testing.assert_array_equal(b.margin, a.margin)
