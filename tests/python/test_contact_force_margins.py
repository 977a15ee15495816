"""The LP's distribution (force_distribution(..., distribution="vertex")) honours every margin of ContactOptions that the projection's polytope holds: the
per-point and per-link minimum normal forces, the friction margin and the torque scale and margin. Each
test checks the returned forces against the margin itself (not against the LP's own margin), and where
it can, shows a state where the forces chosen without that margin break it. (The default, centred distribution
takes the centre of the physical set, without the margins: tests/python/test_force_centre.py.)"""

import numpy as np
import pytest

import pathpace as pp
from test_contact_objects import G, M_BOX, M_PLATFORM, box_corners, lifter_with_box

K = 4  # cone edges along ±x and ±y of the platform: the pyramid's reach along x is μ


def platform_points(friction=0.5, points=((0.0, 0.0),)):
    """The same box-platform contact seen from the platform: link 'platform', its normal (down, into the
    platform) in the box's frame. The box then stands on two links' contacts (per-link sums differ)."""
    return [pp.Contact("platform", point=[x, y, 0.0], normal=[0, 0, -1], friction=friction, other_link="box")
            for x, y in points]


def state(ax=0.0, az=0.0):
    """Everything at rest at q = 0, the platform and the box accelerating by (ax, az) together."""
    q, qd, qdd = np.zeros(8), np.zeros(8), np.zeros(8)
    qdd[[0, 2]] = ax
    qdd[[1, 4]] = az
    return q, qd, qdd


def normal_forces(c, out):
    """n_i·f_i of every contact, n_i the world normal pointing into the contact's link (q = 0: the
    frames are the world's)."""
    return np.array([np.dot(con.normal, f) for con, f in zip(c.contacts, out.forces)])


def link_sums(c, out):
    n = normal_forces(c, out)
    links = sorted({con.link for con in c.contacts})
    return {l: sum(n[i] for i, con in enumerate(c.contacts) if con.link == l) for l in links}


def check_realises_the_motion(c, out, q, qd, qdd):
    """τ = τ_id - Σ J_iᵀ f_i within the constraint's limits, the box (unactuated) balanced."""
    assert out.feasible
    assert np.max(np.abs(out.torques[2:])) < 1e-8
    assert np.all(out.torques >= c.tau_min - 1e-8) and np.all(out.torques <= c.tau_max + 1e-8)


def test_per_link_minimum_normal_force_holds_where_the_plain_distribution_breaks_it():
    """Four corners on link 'box', one point on link 'platform': the most robust distribution without
    per-link rows spreads the weight evenly over the five points' cone weights, so 'platform' carries a
    fifth of it (3.9 N). With min_link_normal_force = 6 N both links carry at least 6 N plus the margin."""
    contacts = box_corners() + platform_points()
    q, qd, qdd = state()
    plain = pp.ContactConstraint(lifter_with_box(), contacts, cone_edges=K)
    free = plain.force_distribution(q, qd, qdd, distribution="vertex")
    check_realises_the_motion(plain, free, q, qd, qdd)
    weight = M_BOX * G
    assert sum(link_sums(plain, free).values()) == pytest.approx(weight, rel=1e-9)
    f_link = 6.0
    assert link_sums(plain, free)["platform"] < f_link - 1.0  # the rows are needed
    c = pp.ContactConstraint(lifter_with_box(), contacts, cone_edges=K, min_link_normal_force=f_link)
    out = c.force_distribution(q, qd, qdd, distribution="vertex")
    check_realises_the_motion(c, out, q, qd, qdd)
    assert out.margin > 0.1
    for link, total in link_sums(c, out).items():
        assert total >= f_link + out.margin - 1e-7, link
    # Asked for more than the weight can give both links, the margin says by how much: the link sums are
    # what they can be (weight/2 each at best), short of the minimum by -margin.
    c = pp.ContactConstraint(lifter_with_box(), contacts, cone_edges=K, min_link_normal_force=0.6 * weight)
    out = c.force_distribution(q, qd, qdd, distribution="vertex")
    assert out.feasible
    assert out.margin == pytest.approx(-0.1 * weight, rel=1e-7)
    assert min(link_sums(c, out).values()) == pytest.approx(0.5 * weight, rel=1e-7)


def test_per_point_minimum_normal_force_holds_on_every_point():
    """The box's centre of mass is off-centre (x = 0.01, y = -0.02), so its corners carry unequal loads;
    with min_normal_force every point pushes at least that plus the margin, accelerating or not. Without
    it, the most robust cone weights leave a corner at 1.3 N when the box accelerates at 3 m/s²."""
    contacts = box_corners() + platform_points(points=((0.05, 0.05),))
    f_min = 1.5
    c = pp.ContactConstraint(lifter_with_box(), contacts, cone_edges=K, min_normal_force=f_min)
    plain = pp.ContactConstraint(lifter_with_box(), contacts, cone_edges=K)
    broken_without = 0
    for ax, az in [(0.0, 0.0), (1.0, 0.0), (-2.0, 1.0), (0.5, -4.0), (3.0, 0.0)]:
        q, qd, qdd = state(ax, az)
        out = c.force_distribution(q, qd, qdd, distribution="vertex")
        check_realises_the_motion(c, out, q, qd, qdd)
        assert out.margin > 0.0
        assert np.all(normal_forces(c, out) >= f_min + out.margin - 1e-7)
        broken_without += np.min(normal_forces(plain, plain.force_distribution(q, qd, qdd, distribution="vertex"))) < f_min
    assert broken_without  # the rows mattered somewhere


@pytest.mark.parametrize("margin", [0.0, 0.5])
def test_friction_margin_keeps_every_force_inside_the_narrowed_cone(margin):
    """friction_margin narrows every cone to μ (1 - margin) (sec. V.D). Sideways at 0.2 g the box needs a
    friction ratio of 0.2: inside μ = 0.5 narrowed by half (0.25), and the forces stay in that cone; at
    0.35 g it is not, and the margin is negative with the narrowed cone while it is positive with the full
    one (the same forces would then break the margin)."""
    mu = 0.5
    c = pp.ContactConstraint(lifter_with_box(), box_corners(mu), cone_edges=K, friction_margin=margin)
    q, qd, qdd = state(0.2 * G)
    out = c.force_distribution(q, qd, qdd, distribution="vertex")
    check_realises_the_motion(c, out, q, qd, qdd)
    assert out.margin > 0.0
    n = out.forces[:, 2]
    tangential = np.hypot(out.forces[:, 0], out.forces[:, 1])
    assert np.all(tangential <= mu * (1 - margin) * n + 1e-9)
    assert np.sum(out.forces[:, 0]) == pytest.approx(M_BOX * 0.2 * G, rel=1e-9)
    fast = c.force_distribution(*state(0.35 * G), distribution="vertex")
    if margin == 0.0:
        assert fast.margin > 0.0
    else:
        assert fast.feasible and fast.margin < -0.1


def test_torque_scale_and_margin_bound_the_torques_or_make_the_state_infeasible():
    """The lift holds the platform and the box (4 kg, 39.2 N at rest) with effort 100 N: scaled by 0.5
    and less a 5 N margin its range is ±45 N, enough; less a 65 N margin (±35 N) it is not, and the torque
    rows are hard: no forces at all (feasible is False)."""
    q, qd, qdd = state()
    hold = (M_PLATFORM + M_BOX) * G
    c = pp.ContactConstraint(lifter_with_box(), box_corners(), cone_edges=K, torque_scale=0.5, torque_margin=5.0)
    assert c.tau_max[1] == pytest.approx(45.0)
    out = c.force_distribution(q, qd, qdd, distribution="vertex")
    check_realises_the_motion(c, out, q, qd, qdd)
    assert out.torques[1] == pytest.approx(hold, rel=1e-9)
    tight = pp.ContactConstraint(lifter_with_box(), box_corners(), cone_edges=K, torque_margin=65.0)
    assert tight.tau_max[1] == pytest.approx(35.0) and tight.tau_max[1] < hold
    bad = tight.force_distribution(q, qd, qdd, distribution="vertex")
    assert not bad.feasible and bad.margin == -np.inf and np.all(np.isnan(bad.forces))


def test_the_margin_is_the_projections_verdict_where_the_per_link_minimum_binds():
    """One polytope for both: lifting the box 1 m with every margin on, the time-optimal deceleration is
    bounded by the per-link minimum (both links keep 6 N: 12 N of the box's 19.6 N weight, so it may fall
    at most g - 12 N / 2 kg = 3.8 m/s²). At the grid points of the decelerating interval the force
    distribution's margin is 0 (the state is on the polygon's edge); 10 % harder it is negative."""
    contacts = box_corners() + platform_points(points=((0.01, -0.02),))  # under the centre of mass
    f_link = 6.0
    opts = dict(cone_edges=K, min_normal_force=0.5, min_link_normal_force=f_link, friction_margin=0.2, torque_margin=5.0)
    grid = np.linspace(0.0, 1.0, 21)
    qs = np.zeros((len(grid), 8))
    dqs = np.zeros_like(qs)
    qs[:, 1] = qs[:, 4] = grid
    dqs[:, 1] = dqs[:, 4] = 1.0
    prob = pp.TimeScalingProblem(pp.SampledPath(grid, qs, dqs, np.zeros_like(qs)), grid=grid)
    prob.add_contacts(lifter_with_box(), contacts, **opts)
    res = prob.solve()
    assert res.status == pp.Status.OPTIMAL
    a_down = G - 2 * f_link / M_BOX
    assert np.min(res.sddot) == pytest.approx(-a_down, rel=1e-7)
    c = pp.ContactConstraint(lifter_with_box(), contacts, **opts)
    k = len(grid) - 2  # the last interval decelerates; its first grid point
    assert res.sddot[k] == pytest.approx(-a_down, rel=1e-7)
    for harder, check in [(1.0, lambda m: abs(m) <= 1e-6 * M_BOX * G), (1.1, lambda m: m < -0.1)]:
        out = c.force_distribution(qs[k], dqs[k] * res.sdot[k], dqs[k] * harder * res.sddot[k], distribution="vertex")
        assert out.feasible
        assert check(out.margin), (harder, out.margin)
        sums = link_sums(c, out)
        assert min(sums.values()) == pytest.approx(f_link + out.margin, rel=1e-6)
