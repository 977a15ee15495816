"""Contact polygons on real humanoids (issue 9): exact against an independent projection, nested in the
number of cone edges, composed with torque limits, re-checked before an infeasibility is reported.

The fast slice of the seeded corpus of contact_corpus.py; bench/contact_projection.py runs all of it
(N up to 400, 4-32 cone edges) and the timings."""

import re
import time

import numpy as np
import pytest

import pathpace as pp

pin = pytest.importorskip("pinocchio")
import contact_corpus as cc  # noqa: E402

MARGINS = [
    {},
    {"friction_margin": 0.5},
    {"min_normal_force": 5.0},
    {"min_link_normal_force": 100.0},
    {"friction_margin": 0.3, "min_normal_force": 2.0},
]


def corpus(seed: int, count: int):
    """`count` seeded draws of (robot, path, cone edges, margins)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        out.append((str(rng.choice(["talos", "romeo"])), str(rng.choice(["sway", "squat", "wall"])),
                    int(rng.choice([4, 8, 16, 32])), MARGINS[int(rng.integers(len(MARGINS)))]))
    return out


@pytest.fixture(scope="module")
def paths():
    cache = {}

    def get(robot, kind):
        if (robot, kind) not in cache:
            h = cc.load(robot)
            cache[(robot, kind)] = (h, cc.make_path(h, kind))
        return cache[(robot, kind)]

    return get


@pytest.mark.parametrize("case", corpus(9, 6), ids=lambda c: f"{c[0]}-{c[1]}-k{c[2]}-{'-'.join(c[3]) or 'bare'}")
def test_every_polygon_matches_the_exact_projection(case, paths):
    """Every grid point's set against HiGHS support values of the full polytope built with pinocchio, in
    64 directions: equal within 1e-6 of the polygon's size; empty exactly where the polytope is."""
    robot, kind, k, margins = case
    h, path = paths(robot, kind)
    cons = cc.contacts(h, kind)
    opts = dict(cone_edges=k, **margins)
    prob = pp.TimeScalingProblem(path, grid=8)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
    worst, compared, empty = cc.compare(h, prob, cons, opts)
    # All 9 points but where the path turns back (p' ~ 0: s = 1/4, 3/4 of a sway, 1/2 of the squat): there
    # s̈ is bounded by the stand-in bound only, every direction reads unbounded on both sides.
    assert (compared, empty) == ((8, 0) if kind == "squat" else (7, 0))
    assert worst <= 1e-6


@pytest.mark.parametrize("robot,kind", [("talos", "sway"), ("romeo", "squat"), ("talos", "wall")])
def test_k_edge_polygons_nest_in_2k_edge_ones_and_feasibility_carries_over(robot, kind, paths):
    """A k-edge pyramid (edges at multiples of 2π/k) lies inside the 2k-edge one: so does every polygon,
    a timing feasible with k edges is feasible with 2k, and no slower."""
    h, path = paths(robot, kind)
    cons = cc.contacts(h, kind)
    dirs = cc.directions()
    for margins in ({}, {"friction_margin": 0.5, "min_normal_force": 5.0}):
        polys, results = {}, {}
        for k in (4, 8, 16):
            prob = pp.TimeScalingProblem(path, grid=40)
            prob.add_contacts(h.robot, cons, cone_edges=k, drift_tolerance=1e-4, **margins)
            polys[k] = [prob.feasible_set(i) for i in range(41)]
            results[k] = prob.solve()
        for k in (4, 8):
            for i, (a, b) in enumerate(zip(polys[k], polys[2 * k])):
                if a.empty:
                    continue
                assert not b.empty
                cc.assert_nested(a, b, dirs, 1e-9, f"{margins} point {i}: {k} edges in {2 * k}")
            if results[k].ok:
                assert results[2 * k].ok, results[2 * k].message
                assert results[2 * k].duration <= results[k].duration * (1 + 1e-9)


def test_carrying_a_box_nests_in_the_cone_edges_too():
    """Talos sways with a 3 kg box squeezed between its hands (robot–robot contacts with a free object):
    feasible, k ⊆ 2k, and a budget-free projection at every point."""
    robot, path, cons = cc.box_problem(cc.load("talos"))
    res = {}
    for k in (4, 8):
        prob = pp.TimeScalingProblem(path, grid=30)
        prob.add_contacts(robot, cons, cone_edges=k, drift_tolerance=1e-4, friction_margin=0.3, min_normal_force=2.0)
        res[k] = prob.solve()
        assert res[k].ok, res[k].message
        assert res[k].stats["inexact_points"] == 0
    assert res[8].duration <= res[4].duration * (1 + 1e-9)


def test_flat_soles_reduce_exactly_to_their_corners(paths):
    """30 points per sole (6 x 5 grid): without a per-point minimum only the 4 corners of each sole enter
    the LPs, and every polygon still equals the exact projection over all 60 points (also with a per-link
    minimum); with a per-point minimum and an even k the corners' cones plus every point's cross-section
    weights (test_point_minimum_reduction.py), with an odd k all 60 points."""
    h, path = paths("talos", "sway")
    cons = cc.contacts(h, "sway", grid=(6, 5))
    assert len(cons) == 60
    for opts in ({"cone_edges": 8, "friction_margin": 0.5}, {"cone_edges": 8, "min_link_normal_force": 150.0}):
        c = pp.ContactConstraint(h.robot, cons, **opts)
        corners = [i for i, con in enumerate(cons) if abs(abs(con.point[0]) - 0.1) < 1e-12 and abs(abs(con.point[1]) - 0.05) < 1e-12]
        assert sorted(c.projected_contacts) == corners
        prob = pp.TimeScalingProblem(path, grid=8)
        prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
        worst, compared, _ = cc.compare(h, prob, cons, opts, points=[0, 3, 6])
        assert compared == 2  # at point 6 (s = 3/4) the sway turns back: unbounded in every direction
        assert worst <= 1e-6
    per_point = pp.ContactConstraint(h.robot, cons, min_normal_force=1.0)
    assert sorted(per_point.projected_contacts) == corners and per_point.section_contacts == list(range(60))
    assert len(pp.ContactConstraint(h.robot, cons, cone_edges=5, min_normal_force=1.0).projected_contacts) == 60


def test_torque_limits_and_contacts_compose_on_a_floating_base(paths):
    """add_torque_limits then add_contacts (a new user's first try) is one projection: OPTIMAL, and the
    same timing as add_contacts given the tighter limits directly; in either order."""
    h, path = paths("talos", "sway")
    cons = cc.contacts(h, "sway")
    eff = h.robot.effort_limits
    tight = 0.6 * eff
    direct = pp.TimeScalingProblem(path, grid=30)
    direct.add_contacts(h.robot, cons, drift_tolerance=1e-4, tau_min=-tight, tau_max=tight)
    ref = direct.solve()
    assert ref.ok, ref.message
    for order in ("torque first", "contacts first"):
        prob = pp.TimeScalingProblem(path, grid=30)
        if order == "torque first":
            prob.add_torque_limits(h.robot, -tight, tight)
            prob.add_contacts(h.robot, cons, drift_tolerance=1e-4)
        else:
            prob.add_contacts(h.robot, cons, drift_tolerance=1e-4)
            prob.add_torque_limits(h.robot, -tight, tight)
        assert len(prob.constraints) == 1
        merged = prob.constraints[0]
        assert isinstance(merged, pp.ContactConstraint)
        np.testing.assert_array_equal(merged.tau_max, tight)
        res = prob.solve()
        assert res.ok, res.message
        assert res.duration == pytest.approx(ref.duration, rel=1e-9)
    # Without contacts, the torque limits alone cannot hold the floating base.
    alone = pp.TimeScalingProblem(path, grid=30)
    alone.add_torque_limits(h.robot)
    assert alone.solve().status == pp.Status.INFEASIBLE


def test_add_contacts_validates_its_new_arguments(paths):
    h, path = paths("talos", "sway")
    cons = cc.contacts(h, "sway")
    prob = pp.TimeScalingProblem(path, grid=4)
    n = h.robot.nq
    with pytest.raises(pp.InvalidInputError, match=rf"tau_max has size 3, expected {n}"):
        prob.add_contacts(h.robot, cons, tau_max=np.ones(3), drift_tolerance=1e-4)
    with pytest.raises(pp.InvalidInputError, match=r"min_link_normal_force = -1 must be >= 0"):
        prob.add_contacts(h.robot, cons, min_link_normal_force=-1.0, drift_tolerance=1e-4)
    with pytest.raises(pp.InvalidInputError, match=r"max_lps = 2 must be >= 3"):
        prob.add_contacts(h.robot, cons, max_lps=2, drift_tolerance=1e-4)
    bad = -h.robot.effort_limits
    bad[7] = 1e9
    with pytest.raises(pp.InvalidInputError, match=r"tau_min\[7\] = 1000000000 must be <= tau_max\[7\]"):
        prob.add_contacts(h.robot, cons, tau_min=bad, drift_tolerance=1e-4)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4)
    lo = -h.robot.effort_limits
    lo[8] = 1e6
    with pytest.raises(pp.InvalidInputError, match=r"torque limits of joint 8 .* do not intersect"):
        prob.add_torque_limits(h.robot, lo, np.full(n, 2e6))
    assert len(prob.constraints) == 1 and isinstance(prob.constraints[0], pp.ContactConstraint)  # unchanged


def test_infeasibility_is_rechecked_on_the_full_polytope(paths):
    h, path = paths("talos", "sway")
    cons = cc.contacts(h, "sway")
    # Torque limits far too weak to stand: empty everywhere, rest included.
    weak = pp.TimeScalingProblem(path, grid=10)
    weak.add_contacts(h.robot, cons, drift_tolerance=1e-4, torque_scale=0.01)
    res = weak.solve()
    assert res.status == pp.Status.INFEASIBLE
    assert "re-checked by one LP on the full (sdot^2, sddot, torque, force) polytope at that point: infeasible, " \
           "rest state (0, 0) infeasible" in res.message
    # Standing is fine, but the path cannot start at 50 rad/s: the rest state is feasible there.
    fast = pp.TimeScalingProblem(path, grid=10)
    fast.add_contacts(h.robot, cons, drift_tolerance=1e-4)
    fast.set_boundary_speeds(50.0, 0.0)
    res = fast.solve()
    assert res.status == pp.Status.INFEASIBLE
    # (the speed cannot be shed before grid point 1: the polygon there is fine, the start speed is not)
    assert res.infeasible_index <= 1
    assert "polytope at that point: feasible, rest state (0, 0) feasible" in res.message


@pytest.mark.parametrize("on_demand", [False, True])
def test_a_turning_point_on_a_grid_point_is_infeasible_not_a_failed_projection(on_demand):
    """A held-out squat (hard_cases(99), Talos) whose bottom is a grid point: p'(0.5) ~ 1e-11 is the rounding
    residue of a turning point, so the polytope there is feasible only at |s̈| ~ 1e13 (b = M p'), beyond the
    largest stand-in, and the robot cannot hold that pose at any speed with 0.3x its torque limits. The
    problem is infeasible there (it was reported NUMERICAL_ERROR: the full LP without caps found that s̈).
    Off the turning point by 1e-12 the projection grows its stand-in instead: the same verdict. The relaxation
    it names holds."""
    case = next(c for c in cc.hard_cases(99) if (c.robot, c.kind) == ("talos", "squat"))
    h = cc.load("talos")
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["talos"])
    scale = cc.HARD_TORQUE_SCALE[("talos", "squat")]

    def solve(offset, torque_scale):
        grid = np.linspace(0.0, 1.0, 101)
        grid[50] += offset
        prob = pp.TimeScalingProblem(path, grid=grid)
        prob.add_contacts(h.robot, cons, cone_edges=4, drift_tolerance=1e-4, torque_scale=torque_scale,
                          project_on_demand=on_demand, **cc.SHIFTED_MARGINS["off1.5"])
        return prob.solve()

    assert np.abs(path.dq(0.5)).max() < 1e-9  # the turning point (measured 9.6e-12)
    for offset in (0.0, 1e-12):
        res = solve(offset, scale)
        assert res.status == pp.Status.INFEASIBLE, (offset, res.message)
        assert 48 <= res.infeasible_index <= 52  # measured: 50 on the point, 52 off it
        factor = float(re.search(r"feasible with torque limits x ([0-9.]+)", res.message).group(1))
        assert 1.0 < factor < 1.2  # measured 1.048
    assert solve(0.0, scale * 1.1).status == pp.Status.OPTIMAL


def test_stats_time_the_projection_and_report_an_exhausted_budget(paths):
    h, path = paths("talos", "wall")
    cons = cc.contacts(h, "wall")
    prob = pp.TimeScalingProblem(path, grid=20)
    t0 = time.perf_counter()
    prob.add_contacts(h.robot, cons, cone_edges=16, drift_tolerance=1e-4)
    wall = time.perf_counter() - t0
    res = prob.solve()
    st = res.stats
    assert 0 < st["time_projection"] <= wall
    assert st["time_constraints"] >= st["time_projection"]
    assert st["projection_lp_solves"] >= 21 * 4
    assert st["inexact_points"] == 0
    assert all(prob.feasible_set(k).exact for k in range(21))
    # A budget of 3 LPs per point (the initial triangle; edges whose endpoint's basis certifies them
    # need no LP): the polygons that need more are inner hulls, and say so.
    cut = pp.TimeScalingProblem(path, grid=20)
    cut.add_contacts(h.robot, cons, cone_edges=16, drift_tolerance=1e-4, max_lps=3)
    res_cut = cut.solve()
    inexact = sum(not cut.feasible_set(k).exact for k in range(21))
    assert res_cut.stats["inexact_points"] == inexact >= 15
    dirs = cc.directions()
    for k in range(0, 21, 5):
        cc.assert_nested(cut.feasible_set(k), prob.feasible_set(k), dirs, 1e-9, f"point {k}: inner hull in the exact set")


@pytest.mark.parametrize("robot, kind, mname", [("talos", "lean", "fm0.5+fn0.33"), ("romeo", "lean", "fn1.5")])
def test_hard_corpus_polygons_are_exact_and_torque_limits_bind(robot, kind, mname):
    """Issue 27's corpus (dense soles, per-point margins, strong lean or squat, torque limits scaled down):
    every polygon of a coarse grid equals the exact projection over all 60-64 points (pinocchio + HiGHS),
    the polygons are complex (well over the 4-8 edges of a bare sole), and some edges are torque limits."""
    case = next(c for c in cc.hard_cases() if c.robot == robot and c.kind == kind)
    h = cc.load(robot)
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[robot])
    assert len(cons) >= 60
    opts = dict(cone_edges=4, torque_scale=cc.HARD_TORQUE_SCALE[(robot, kind)], **cc.HARD_MARGINS[mname])
    prob = pp.TimeScalingProblem(path, grid=6)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
    worst, compared, empty = cc.compare(h, prob, cons, opts, dirs=cc.directions(32))
    assert empty == 0 and compared >= 5
    assert worst <= 1e-6
    sets = [prob.feasible_set(k) for k in range(7)]
    assert max(len(fs.halfplanes) for fs in sets) >= 12
    assert any("torque" in label for fs in sets for label in fs.labels)
    res = prob.solve()
    assert res.ok, res.message
    st = res.stats
    causes = ("initial", "vertex", "certificate", "cap_growth", "cold_retry")
    assert sum(st[f"projection_lps_{c}"] for c in causes) == st["projection_lp_solves"]
    assert st["projection_lps_initial"] == 3 * 7


@pytest.mark.parametrize("robot, kind, margins", [("talos", "lean", {"cone_offset": 1.5}),
                                                   ("romeo", "lean", {"friction_margin": 0.5, "cone_offset": 0.33,
                                                                      "min_link_normal_force": 60.0})])
def test_shifted_cone_reduces_exactly_to_the_sole_corners(robot, kind, margins):
    """The shifted cone (f - cone_offset·n in the friction cone, sec. V.D): each sole's 30 points reduce to
    its 4 corners plus a constant offset wrench, and every polygon equals the exact projection over all
    60 points (pinocchio + HiGHS, the offsets of every point in its rows) to 1e-9 of its size; a per-link
    minimum counts the offsets of every point of the link. The margin binds: T above the bare optimum."""
    case = next(c for c in cc.hard_cases() if c.robot == robot and c.kind == kind)
    h = cc.load(robot)
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[robot])
    opts = dict(cone_edges=4, torque_scale=cc.HARD_TORQUE_SCALE[(robot, kind)], **margins)
    c = pp.ContactConstraint(h.robot, cons, **opts)
    lx, ly = h.sole_size
    corners = [i for i, con in enumerate(cons)
               if abs(abs(con.point[0]) - lx / 2) < 1e-12 and abs(abs(con.point[1]) - ly / 2) < 1e-12]
    assert len(corners) == 8 and sorted(c.projected_contacts) == corners
    prob = pp.TimeScalingProblem(path, grid=6)
    prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
    worst, compared, empty = cc.compare(h, prob, cons, opts, dirs=cc.directions(32))
    assert empty == 0 and compared >= 5
    assert worst <= 1e-9
    bare = pp.TimeScalingProblem(path, grid=6)
    bare.add_contacts(h.robot, cons, drift_tolerance=1e-4, cone_edges=4, torque_scale=opts["torque_scale"])
    res, res_bare = prob.solve(), bare.solve()
    assert res.ok and res_bare.ok
    assert res.duration > res_bare.duration * (1 + 1e-6)
    # At the grid points (where the timing is feasible) the forces the constraint reports keep every
    # point's offset along its normal, with friction to spare: f - cone_offset·n in the reduced cone (the
    # LP's forces, distribution="vertex": the default centre is that of the physical set, without margins).
    fs = res.trajectory().contact_forces(res.times, distribution="vertex")
    assert np.all(fs.margin >= -1e-6)
    off = margins["cone_offset"]
    normal = fs.forces[..., 2]
    assert np.all(normal >= off - 1e-6)
    mu = 0.5 * (1 - margins.get("friction_margin", 0.0))
    assert np.all(np.hypot(fs.forces[..., 0], fs.forces[..., 1]) <= mu * (normal - off) + 1e-6)
    # The torques left after the offset forces (tau_id - sum J^T f, offsets included) are within the limits:
    # the offsets' wrench is counted once, not also in the LP's torque rows a second time.
    assert np.all(fs.torques >= c.tau_min - 1e-6) and np.all(fs.torques <= c.tau_max + 1e-6)


def test_cone_offset_is_validated_named_and_pickled():
    h = cc.load("talos")
    cons = cc.contacts(h, "sway")
    for bad in (-1.0, float("nan"), float("inf")):
        with pytest.raises(pp.InvalidInputError, match=r"cone_offset = .* must be >= 0 and finite"):
            pp.ContactConstraint(h.robot, cons, cone_offset=bad)
    import pickle
    path = cc.make_path(h, "sway")
    a, b = (pp.TimeScalingProblem(path, grid=4) for _ in range(2))
    c = pp.ContactConstraint(h.robot, cons, cone_offset=20.0)
    a.add_constraint(c)
    b.add_constraint(pickle.loads(pickle.dumps(c)))
    bare = pp.TimeScalingProblem(path, grid=4)
    bare.add_constraint(pp.ContactConstraint(h.robot, cons))
    for k in range(5):
        np.testing.assert_array_equal(a.feasible_set(k).vertices, b.feasible_set(k).vertices)
    assert not np.array_equal(a.feasible_set(2).vertices, bare.feasible_set(2).vertices)


def _projection_size(fs) -> float:
    """The projection's size as C++ computes it: the larger extent in x or u over the vertices whose
    coordinate is not on a stand-in bound."""
    v = fs.vertices
    ext = []
    for j in range(2):
        c = v[np.abs(v[:, j]) < 0.5 * cc.CAP, j]
        ext.append(float(np.ptp(c)) if len(c) else 0.0)
    return max(ext)


@pytest.mark.parametrize("eps", [1e-4, 1e-3, 1e-2])
def test_projection_tolerance_keeps_an_inner_polygon_within_eps_and_T_can_only_grow(eps):
    """projection_tolerance = ε on a strong Talos lean with a per-point minimum (polygons of ~80 edges):
    at every grid point the polygon lies inside the exact one and its support function is within ε times
    its size of the exact one in 720 directions; fewer LPs; T >= the exact T (an inner set is
    conservative), and the timing is still OPTIMAL."""
    case = next(c for c in cc.hard_cases() if c.robot == "talos" and c.kind == "lean")
    h = cc.load("talos")
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["talos"])
    opts = dict(cone_edges=4, torque_scale=cc.HARD_TORQUE_SCALE[("talos", "lean")], min_normal_force=1.5,
                drift_tolerance=1e-4)
    exact, approx = pp.TimeScalingProblem(path, grid=6), pp.TimeScalingProblem(path, grid=6)
    exact.add_contacts(h.robot, cons, **opts)
    approx.add_contacts(h.robot, cons, projection_tolerance=eps, **opts)
    dirs = cc.directions(720)
    worst = 0.0
    for k in range(7):
        fe, fa = exact.feasible_set(k), approx.feasible_set(k)
        assert fe.empty == fa.empty
        if fe.empty:
            continue
        he, ha = cc.polygon_support(fe, dirs), cc.polygon_support(fa, dirs)
        ok = cc.same_unbounded_directions(ha, he, f"k = {k}")
        gap = (he[ok] - ha[ok]) / _projection_size(fe)
        assert np.all(gap >= -1e-9), f"k = {k}: not inside the exact polygon ({gap.min():.2e})"
        assert np.all(gap <= eps), f"k = {k}: support gap {gap.max():.2e} > ε = {eps}"
        worst = max(worst, gap.max())
    assert worst > 0.0  # the approximation was used
    re, ra = exact.solve(), approx.solve()
    assert re.ok and ra.ok, (re.message, ra.message)
    assert ra.duration >= re.duration * (1 - 1e-12)
    assert ra.stats["projection_lp_solves"] < re.stats["projection_lp_solves"]


def _rest_slice(fs):
    """The s̈ interval of a feasible set at ṡ² = 0 (its vertices on x = 0), or None."""
    v = np.asarray(fs.vertices)
    at_rest = v[v[:, 0] <= 1e-12 * max(1.0, np.abs(v[:, 0]).max()), 1] if len(v) else v
    return (at_rest.min(), at_rest.max()) if len(at_rest) else None


def test_projection_tolerance_keeps_the_rest_slice_exact():
    """Where the path can start or stop is the slice of each polygon at ṡ² = 0, often far shorter than
    the polygon's size. With ε = 1e-4 it stays the exact one at every grid point of a squat whose inner
    polygons once kept only s̈ < 0 at rest there (seed-27 Talos squat, 8 edges, shifted cone: it became
    INFEASIBLE), and the timing stays OPTIMAL with T within ε of the exact one."""
    case = next(c for c in cc.hard_cases() if c.robot == "talos" and c.kind == "squat")
    h = cc.load("talos")
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["talos"])
    opts = dict(cone_edges=8, torque_scale=cc.HARD_TORQUE_SCALE[("talos", "squat")], drift_tolerance=1e-4,
                **cc.SHIFTED_MARGINS["off1.5"])
    exact, approx = pp.TimeScalingProblem(path, grid=100), pp.TimeScalingProblem(path, grid=100)
    exact.add_contacts(h.robot, cons, **opts)
    approx.add_contacts(h.robot, cons, projection_tolerance=1e-4, **opts)
    for k in range(101):
        fe, fa = exact.feasible_set(k), approx.feasible_set(k)
        se, sa = _rest_slice(fe), _rest_slice(fa)
        assert (se is None) == (sa is None), k
        if se is not None:
            scale = max(1.0, np.ptp(np.asarray(fe.vertices)[:, 1]))
            assert abs(se[0] - sa[0]) <= 1e-9 * scale and abs(se[1] - sa[1]) <= 1e-9 * scale, (k, se, sa)
    re, ra = exact.solve(), approx.solve()
    assert re.ok and ra.ok, (re.message, ra.message)
    assert re.duration * (1 - 1e-12) <= ra.duration <= re.duration * (1 + 1e-4)


def test_projection_tolerance_is_validated_named_and_pickled():
    h = cc.load("talos")
    cons = cc.contacts(h, "sway")
    path = cc.make_path(h, "sway")
    for bad in (-1e-3, 1.0, float("nan"), float("inf")):
        with pytest.raises(pp.InvalidInputError, match=r"projection_tolerance = .* must be in \[0, 1\)"):
            pp.ContactConstraint(h.robot, cons, projection_tolerance=bad)
        with pytest.raises(pp.InvalidInputError, match=r"projection_tolerance = "):
            pp.TimeScalingProblem(path, grid=4).add_contacts(h.robot, cons, projection_tolerance=bad)
    import pickle
    # The hard lean's polygons (per-point minima, binding torques): on the plain sway's small polygons every
    # edge is certified by an endpoint's basis (ranging) or touches the rest state x = 0, which the
    # approximation always solves exactly, so ε has no edge left to skip there.
    case = next(c for c in cc.hard_cases() if c.robot == "talos" and c.kind == "lean")
    path = cc.make_hard_path(h, case)
    cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["talos"])
    opts = dict(torque_scale=cc.HARD_TORQUE_SCALE[("talos", "lean")], **cc.HARD_MARGINS["fn1.5"])
    a, b = (pp.TimeScalingProblem(path, grid=8) for _ in range(2))
    c = pp.ContactConstraint(h.robot, cons, projection_tolerance=0.05, **opts)
    a.add_constraint(c)
    b.add_constraint(pickle.loads(pickle.dumps(c)))
    exact = pp.TimeScalingProblem(path, grid=8)
    exact.add_constraint(pp.ContactConstraint(h.robot, cons, **opts))
    for k in range(9):
        np.testing.assert_array_equal(a.feasible_set(k).vertices, b.feasible_set(k).vertices)
    # The tolerance is what the pickle kept: ε = 0.05 changes a polygon of this path.
    assert any(not np.array_equal(a.feasible_set(k).vertices, exact.feasible_set(k).vertices) for k in range(9))
