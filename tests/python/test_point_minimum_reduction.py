"""Issue 27: a per-point minimum normal force (n·f_i >= d) on a flat sole reduces exactly. Each point's
force is a point of its cone's cross-section at n·f = d (a regular k-gon around d·n) plus a force in the
cone; the cone parts reduce to the sole's hull corners, the cross-section parts are d·n (a constant) plus,
for an even k, k/2 weights in [-d, d] per point (the k-gon is a zonotope; docs/method.md). Tested against
the unreduced polytope (every point with its k weights and its row, pinocchio + HiGHS:
contact_corpus.full_polytope) to 1e-8 of each polygon's size (EXACT, below), on the dense soles of issue 27's corpus and
on random non-grid soles; an odd k keeps every point (no zonotope); the forces force_distribution reports
keep every point's minimum inside its cone."""

import numpy as np
import pytest

import pathpace as pp

pin = pytest.importorskip("pinocchio")
import contact_corpus as cc  # noqa: E402
from scipy.spatial import ConvexHull  # noqa: E402

# Reduced polygons against the exact projection, of each polygon's size. The reduction itself is exact
# (HiGHS on the reduced polytope gives the full polytope's support values to 3e-14 of the size), but
# GLPK's optima of the reduced LP sit up to 7e-9 of the size from them (the unreduced LP's: 7e-10), as
# far as a 1e-10 relative bound tolerance lets them on a balance row of ~1e3 N: a 6e-8 violation of
# every row explains the worst vertex seen. Measured over this file: 7e-9 (romeo, 16 edges).
EXACT = 1e-8


def _hard(robot, kind):
    case = next(c for c in cc.hard_cases() if c.robot == robot and c.kind == kind)
    h = cc.load(robot)
    return h, cc.make_hard_path(h, case), cc.HARD_TORQUE_SCALE[(robot, kind)]


def _sole_corners(h, cons):
    lx, ly = h.sole_size
    ox, oy, _ = h.sole_origin
    return [i for i, con in enumerate(cons)
            if abs(abs(con.point[0] - ox) - lx / 2) < 1e-12 and abs(abs(con.point[1] - oy) - ly / 2) < 1e-12]


def _vertices_have_forces(prob, c, point, fmin):
    """Every (finite) vertex of the reduced polygon at grid point `point`, pulled towards the centroid by 1e-7 of
    the polygon's size, has per-point forces in the unreduced LP (force_distribution(distribution="vertex"): the
    LP with the margins, every point, its
    row, its cone): margin >= 0, every normal force >= fmin."""
    fs = prob.feasible_set(point)
    s = prob.grid[point]
    q, dq, ddq = prob.path.q(s), prob.path.dq(s), prob.path.ddq(s)
    finite = fs.vertices[np.all(np.abs(fs.vertices) < 0.5 * cc.CAP, axis=1)]  # not the cut of an unbounded set
    assert len(finite) >= 2
    cen = finite.mean(axis=0)
    size = cc.polygon_size(fs)
    for v in finite:
        x, u = v - 1e-7 * size * (v - cen) / np.linalg.norm(v - cen)
        f = c.force_distribution(q[None], (dq * np.sqrt(max(x, 0.0)))[None], (ddq * x + dq * u)[None],
                               distribution="vertex")
        assert f.feasible[0] and f.margin[0] >= 0.0, (v, f.margin)
        assert np.all(f.forces[0][:, 2] >= fmin - 1e-9)


def _check_forces(res, cons, k, margins):
    """At the grid points: the LP's most robust forces (distribution="vertex"; the default centre is that of the
    physical set, without margins) keep every margin (normal >= min_normal_force, f - cone_offset·n inside the
    k-edge pyramid of μ (1 - friction_margin))."""
    fs = res.trajectory().contact_forces(res.times, distribution="vertex")
    assert np.all(fs.margin >= -1e-6)
    fmin, off = margins.get("min_normal_force", 0.0), margins.get("cone_offset", 0.0)
    mu = np.array([c.friction for c in cons]) * (1 - margins.get("friction_margin", 0.0))
    normal = fs.forces[..., 2]  # every sole normal is +z
    assert np.all(normal >= fmin - 1e-6)
    # The pyramid: its tangential k-gon of circumradius μ (n·f - offset), faces at φ_e + π/k.
    phi = 2 * np.pi * (np.arange(k) + 0.5) / k
    # The generators' tangent frame for n = z: t1 = z × x = y, t2 = z × t1 = -x.
    t1, t2 = fs.forces[..., 1], -fs.forces[..., 0]
    for p in phi:
        assert np.all(np.cos(p) * t1 + np.sin(p) * t2 <= mu * np.cos(np.pi / k) * (normal - off) + 1e-6)


def _exact_with_forces(h, path, cons, c, opts, min_normal_force):
    """The problem on 6 intervals with these contacts: every polygon equals the unreduced projection to
    EXACT of its size (none empty, at least 5 compared), and the polygons' vertices have forces that keep
    the per-point minimum."""
    prob = pp.TimeScalingProblem(path, grid=6)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
    worst, compared, empty = cc.compare(h, prob, cons, opts, dirs=cc.directions(32))
    assert empty == 0 and compared >= 5
    assert worst <= EXACT
    _vertices_have_forces(prob, c, 2, min_normal_force)
    return prob


@pytest.mark.parametrize("robot,kind,k,margins", [
    ("talos", "lean", 4, {"min_normal_force": 1.5}),
    ("talos", "lean", 8, {"friction_margin": 0.5, "min_normal_force": 0.33}),
    ("romeo", "lean", 16, {"min_normal_force": 1.5, "min_link_normal_force": 120.0}),
    ("g1", "lean", 4, {"friction_margin": 0.5, "min_normal_force": 2.0, "cone_offset": 0.5}),
    ("g1", "squat", 8, {"min_normal_force": 1.5}),
], ids=lambda v: str(v) if not isinstance(v, dict) else "-".join(f"{a}{b}" for a, b in v.items()))
def test_dense_soles_with_a_per_point_minimum_reduce_exactly(robot, kind, k, margins):
    """Issue 27's dense soles (30-32 points each): the corners' cones and every point's k/2 weights
    enter the LPs, and every polygon equals the unreduced projection to EXACT of its size; the margin
    binds (T above the timing without it), and the reported forces keep it at every point."""
    h, path, scale = _hard(robot, kind)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[robot])
    opts = dict(cone_edges=k, torque_scale=scale, **margins)
    c = pp.ContactConstraint(h.robot, cons, **opts)
    assert sorted(c.projected_contacts) == _sole_corners(h, cons) and len(c.projected_contacts) == 8
    assert c.section_contacts == list(range(len(cons)))
    prob = _exact_with_forces(h, path, cons, c, opts, margins["min_normal_force"])
    res = prob.solve()
    assert res.ok, res.message
    _check_forces(res, cons, k, margins)
    bare = pp.TimeScalingProblem(path, grid=6)
    bare.add_contacts(h.robot, cons, drift_tolerance=1e-4, cone_edges=k, torque_scale=scale)
    assert res.duration > bare.solve().duration * (1 + 1e-6)


def _random_soles(h, seed, count):
    """`count` points per sole drawn uniformly over the sole rectangle (no grid, corners not included)."""
    rng = np.random.default_rng(seed)
    lx, ly = h.sole_size
    ox, oy, oz = h.sole_origin
    out = []
    for link in h.soles:
        for x, y in rng.uniform(-0.5, 0.5, (count, 2)) * (lx, ly):
            out.append(pp.Contact(link, point=(ox + x, oy + y, oz), normal=(0, 0, 1), friction=0.5))
    return out


@pytest.mark.parametrize("seed,k,margins", [
    (1, 4, {"min_normal_force": 3.0}),
    (2, 8, {"friction_margin": 0.3, "min_normal_force": 2.0}),
    (3, 16, {"min_normal_force": 1.0, "min_link_normal_force": 150.0}),
])
def test_random_soles_reduce_to_their_hull_plus_every_point_section(seed, k, margins):
    """Random points on each sole (25 per sole): the cones of their hull vertices (an independent
    hull, scipy's) and each point's cross-section weights; polygons exact to EXACT of their size."""
    h, path, scale = _hard("talos", "lean")
    cons = _random_soles(h, seed, 25)
    opts = dict(cone_edges=k, torque_scale=scale, **margins)
    c = pp.ContactConstraint(h.robot, cons, **opts)
    hull = []
    for side in range(2):
        pts = np.array([con.point[:2] for con in cons[25 * side: 25 * (side + 1)]])
        hull += sorted(25 * side + int(v) for v in ConvexHull(pts).vertices)
    assert sorted(c.projected_contacts) == hull
    assert c.section_contacts == list(range(50))
    _exact_with_forces(h, path, cons, c, opts, margins["min_normal_force"])


@pytest.mark.parametrize("k", [3, 5])
def test_an_odd_cone_keeps_every_point_and_is_exact(k):
    """An odd k-gon is not centrally symmetric, so not a zonotope: every point enters with its row (the
    unreduced LP), still exact; without the per-point minimum (or with it below cone_offset, where its
    rows are void) the corners alone."""
    h, path, scale = _hard("romeo", "lean")
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["romeo"])
    opts = dict(cone_edges=k, torque_scale=scale, min_normal_force=1.5)
    c = pp.ContactConstraint(h.robot, cons, **opts)
    assert c.projected_contacts == list(range(60)) and c.section_contacts == []
    for void in ({}, {"min_normal_force": 1.0, "cone_offset": 1.0}):
        d = pp.ContactConstraint(h.robot, cons, cone_edges=k, **void)
        assert len(d.projected_contacts) == 8 and d.section_contacts == []
    prob = pp.TimeScalingProblem(path, grid=4)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
    worst, compared, empty = cc.compare(h, prob, cons, opts, dirs=cc.directions(32))
    assert empty == 0 and compared >= 3
    assert worst <= 1e-9  # the unreduced LP, as before
    res = prob.solve()
    assert res.ok, res.message
    fs = res.trajectory().contact_forces(res.times, distribution="vertex")  # the LP's forces keep the margins
    assert np.all(fs.margin >= -1e-6) and np.all(fs.forces[..., 2] >= 1.5 - 1e-6)


def test_small_or_corner_only_groups_keep_their_rows():
    """A group whose points are mostly hull vertices (the 4 corners alone, or 5 points with 4 on the
    hull) keeps every point with its own row: k/2 weights per point would cost more than they save."""
    h = cc.load("talos")
    corners = cc.contacts(h, "sway")
    c = pp.ContactConstraint(h.robot, corners, cone_edges=4, min_normal_force=2.0)
    assert c.projected_contacts == list(range(8)) and c.section_contacts == []
    five = corners[:4] + [pp.Contact(h.soles[0], point=(0.0, 0.0, 0.0), normal=(0, 0, 1), friction=0.5)]
    c = pp.ContactConstraint(h.robot, five, cone_edges=4, min_normal_force=2.0)
    assert c.projected_contacts == list(range(5)) and c.section_contacts == []


@pytest.mark.parametrize("robot,kind,margins", [
    ("talos", "squat", "off1.5"),
    ("romeo", "lean", "fm0.5+off0.33"),
])
def test_shifted_cone_forces_balance_the_base(robot, kind, margins):
    """The shifted cone's offset wrench (cone_offset · Σ_i J_iᵀ n_i over all 60 sole points, which the LPs move
    into the torque rows' bounds): the forces reported at the grid times, offsets included, carry the base's
    six unactuated rows of inverse dynamics with pathpace's rows left out: τ_id = Σ_i J_iᵀ f_i there, with
    J_i from point_jacobian per point, to 1e-6 of the robot's weight."""
    h, path, scale = _hard(robot, kind)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[robot])
    prob = pp.TimeScalingProblem(path, grid=6)
    prob.add_contacts(h.robot, cons, cone_edges=4, drift_tolerance=1e-4, torque_scale=scale,
                      **cc.SHIFTED_MARGINS[margins])
    res = prob.solve()
    assert res.ok, res.message
    traj = res.trajectory()
    fs = traj.contact_forces(res.times, distribution="vertex")
    q0 = traj.q(0.0)
    weight = abs(float(h.robot.inverse_dynamics(q0, 0 * q0, 0 * q0)[2]))  # the base's vertical row at rest
    worst = 0.0
    for j, t in enumerate(res.times):
        q = traj.q(t)
        tau_id = h.robot.inverse_dynamics(q, traj.qd(t), traj.qdd(t))
        JT = np.hstack([h.robot.point_jacobian(q, c.link, c.point).T for c in cons])
        worst = max(worst, float(np.max(np.abs(tau_id[:6] - JT[:6] @ fs.forces[j].reshape(-1)))))
    assert worst <= 1e-6 * weight, (worst, weight)
