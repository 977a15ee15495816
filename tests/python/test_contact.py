"""Frictional contact: the rod of sec. IV.E against its analytic feasible sets (eq. 20-23)."""

from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import linprog

import pathpace as pp
from oracles import generators

DATA = Path(__file__).resolve().parents[1] / "data"
G, MU, TAU = 9.81, 0.5, 2.0


def rod_path(thetas):
    """q = (x, z, angle) with the rod's lower end on the origin: x = -sin θ, z = cos θ, angle = -θ (a
    positive rotation about y tilts the rod's axis toward +x). θ'(s) = 1, θ'' = 0."""
    th = np.asarray(thetas, dtype=float)
    q = np.column_stack([-np.sin(th), np.cos(th), -th])
    dq = np.column_stack([-np.cos(th), -np.sin(th), -np.ones_like(th)])
    ddq = np.column_stack([np.sin(th), -np.cos(th), np.zeros_like(th)])
    return pp.SampledPath(th, q, dq, ddq)


def analytic_rows(theta):
    """eq. (21)-(23) with m = L = 1, H = 1/3, as rows a·X + b·U <= c in X = ṡ², U = s̈."""
    x, y = -np.sin(theta), np.cos(theta)
    fx = np.array([-x, -y, 0.0])  # fx = -m x X - m y U   (coefficients of X, U, and constant)
    fy = np.array([-y, x, G])     # fy = -m y X + m x U + m g
    tau = np.array([0.0, 4.0 / 3.0, x * G])  # τ = (H + m L²) U + m x g
    rows = [
        [tau[0], tau[1], TAU - tau[2]],
        [-tau[0], -tau[1], TAU + tau[2]],
        [-(fx[0] + MU * fy[0]), -(fx[1] + MU * fy[1]), fx[2] + MU * fy[2]],  # fx + μ fy >= 0
        [fx[0] - MU * fy[0], fx[1] - MU * fy[1], -fx[2] + MU * fy[2]],        # -fx + μ fy >= 0
        [-1.0, 0.0, 0.0],                                                   # X >= 0
    ]
    return np.array(rows)


def support(rows, d):
    r = linprog(-np.asarray(d), A_ub=rows[:, :2], b_ub=rows[:, 2], bounds=[(0, 1e4), (-1e4, 1e4)], method="highs")
    assert r.status == 0
    return -r.fun


@pytest.fixture(scope="module")
def rod_problem():
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    thetas = np.linspace(-0.4, 0.4, 17)
    path = rod_path(thetas)
    prob = pp.TimeScalingProblem(path, grid=thetas)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=MU)], cone_edges=4)
    return prob, thetas


def test_rod_projected_sets_match_the_analytic_constraints(rod_problem):
    prob, thetas = rod_problem
    for k in (0, 4, 8, 11, 16):
        fs = prob.feasible_set(k)
        assert not fs.empty
        rows = analytic_rows(thetas[k])
        for ang in np.linspace(0, 2 * np.pi, 64, endpoint=False):
            d = np.array([np.cos(ang), np.sin(ang)])
            ref = support(rows, d)
            if ref > 1e3:  # a direction in which the set is unbounded (only X >= 0 side)
                continue
            mine = np.max(fs.vertices @ d)
            assert mine == pytest.approx(ref, rel=1e-6, abs=1e-6), (k, ang)


def test_rod_observations_of_the_paper(rod_problem):
    prob, thetas = rod_problem
    upright = prob.feasible_set(8)  # θ = 0
    # No feasible speed beyond X = g (friction), and diagonal (friction) bounds above X = g - 2·1.5 ≈ 7.
    assert np.max(upright.vertices[:, 0]) == pytest.approx(G, rel=1e-6)
    on_diagonal = [v for v in upright.vertices if v[0] > 7.0]
    assert on_diagonal  # the top of the set is bounded by the friction diagonals
    # Away from the vertical the rod can only fall: s̈ = 0 is not attainable at rest at θ = 0.4.
    tilted = prob.feasible_set(16)
    assert not tilted.contains(0.0, 0.0)
    assert upright.contains(0.0, 0.0)


def test_contact_validation_and_drift_warning():
    robot = pp.RobotModel.from_urdf(str(DATA / "rod.urdf"))
    path = rod_path(np.linspace(-0.2, 0.2, 5))
    prob = pp.TimeScalingProblem(path, grid=np.linspace(-0.2, 0.2, 5))
    with pytest.raises(pp.InvalidInputError, match=r"link 'foot' is not a link of robot 'rod'"):
        prob.add_contacts(robot, [pp.Contact("foot")])
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\].normal = \(0, 0, 0\) must be nonzero"):
        prob.add_contacts(robot, [pp.Contact("rod", normal=[0, 0, 0])])
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\].friction = 0 must be > 0"):
        prob.add_contacts(robot, [pp.Contact("rod", friction=0.0)])
    with pytest.raises(pp.InvalidInputError, match=r"cone_edges = 2 must be >= 3"):
        prob.add_contacts(robot, [pp.Contact("rod")], cone_edges=2)
    # The rod's centre moves along the path: a contact there does not stay in place. It moves by far more
    # than 10x drift_tolerance: an error by default (drift="auto") and with "error"; "warn" times it.
    for kw in ({}, {"drift": "error"}):
        with pytest.raises(pp.InvalidInputError, match=r"contact 0 \(link 'rod'\) moves by .* m \(farthest at s = "):
            prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, 0])], **kw)
    assert prob.constraints == []
    with pytest.raises(pp.InvalidInputError, match=r"drift = 'never', expected 'auto', 'warn' or 'error'"):
        prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, 0])], drift="never")
    with pytest.warns(UserWarning, match=r"contact 0 \(link 'rod'\) moves by"):
        prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, 0])], drift="warn")



@pytest.mark.parametrize("robot_robot", [False, True])
@pytest.mark.parametrize("seed", range(4))
def test_projection_matches_the_full_lp_solved_by_highs(seed, robot_robot):
    """Random floating-base trees with random contacts: the projected polygon's support value in 64
    directions equals the optimum of the full LP over (ṡ², s̈, cone weights) built from pinocchio's
    dynamics and solved by scipy's HiGHS. With robot_robot, each contact is between two links of the
    tree, its normal turning with the second link, and the reaction acting on it."""
    pin = pytest.importorskip("pinocchio")
    from test_robot_model import composite_floating_joint, random_tree_urdf

    xml = random_tree_urdf(8, 100 + seed)
    robot = pp.RobotModel.from_urdf_string(xml, floating_base=True)
    model = pin.buildModelFromXML(xml, composite_floating_joint())
    data = model.createData()
    rng = np.random.default_rng(seed)
    n = robot.nq
    links = [f"l{i}" for i in rng.choice(np.arange(1, 9), 4, replace=False)]
    others = [f"l{i}" for i in rng.choice(np.arange(0, 9), 4, replace=False)]
    contacts = []
    for link, other in zip(links, others):
        normal = np.array([0.0, 0.0, 1.0]) + 0.3 * rng.normal(size=3)
        point, mu = rng.uniform(-0.2, 0.2, 3), rng.uniform(0.4, 1.0)
        if not robot_robot:
            contacts.append(pp.Contact(link, point=point, normal=normal, friction=mu))
            continue
        # The first link from `other` on that is not welded to `link` (fixed joints merge links).
        for cand in [other] + [f"l{i}" for i in range(9)]:
            con = pp.Contact(link, point=point, normal=normal, friction=mu, other_link=cand)
            try:
                pp.ContactConstraint(robot, [con])
            except pp.InvalidInputError:
                continue
            contacts.append(con)
            break
    assert len(contacts) == 4
    q, dq, ddq = rng.uniform(-0.5, 0.5, (3, n))
    dq *= 0.5
    path = pp.SampledPath([0.0, 1.0], np.vstack([q, q]), np.vstack([dq, dq]), np.vstack([ddq, ddq]))
    prob = pp.TimeScalingProblem(path, grid=1)
    k_edges = 6
    prob.add_contacts(robot, contacts, cone_edges=k_edges, min_normal_force=1.0, drift_tolerance=np.inf)
    fs = prob.feasible_set(0)

    # The full LP from pinocchio: τ = a x + b u + c - Σ J_iᵀ G_i λ_i within the limits (base: = 0).
    c = pin.computeGeneralizedGravity(model, data, q)
    a = pin.rnea(model, data, q, dq, ddq) - c
    b = pin.rnea(model, data, q, np.zeros(n), dq) - c
    pin.forwardKinematics(model, data, q)
    pin.updateFramePlacements(model, data)
    cols = [a[:, None], b[:, None]]
    def world_jacobian(frame, local_point):
        fid = model.getFrameId(frame)
        J6 = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL)
        return data.oMf[fid].rotation @ (J6[:3] - np.cross(local_point, J6[3:].T).T)

    for con in contacts:
        J = world_jacobian(con.link, con.point)  # world-frame Jacobian of the contact point
        R_normal = np.eye(3)
        if con.other_link is not None:
            # The same world point, moving with the other link, which feels the reaction.
            pose = data.oMf[model.getFrameId(con.other_link)]
            p_world = data.oMf[model.getFrameId(con.link)].act(np.asarray(con.point))
            J = J - world_jacobian(con.other_link, pose.actInv(p_world))
            R_normal = pose.rotation
        G = generators(con.normal, con.friction, k_edges)
        cols.append(-J.T @ (R_normal @ G))
    A = np.hstack(cols)
    eff = robot.effort_limits
    m = len(contacts)
    A_eq, b_eq = A[:6], -c[:6]
    A_ub = np.vstack([A[6:], -A[6:], np.hstack([np.zeros((m, 2)), -np.kron(np.eye(m), np.ones(k_edges))])])
    b_ub = np.concatenate([eff[6:] - c[6:], eff[6:] + c[6:], -np.ones(m)])
    bounds = [(0, 1e4), (-1e4, 1e4)] + [(0, None)] * (m * k_edges)
    probe = linprog(np.zeros(A.shape[1]), A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds, method="highs")
    if probe.status == 2:  # infeasible: no contact forces hold this configuration
        assert fs.empty
        return
    assert not fs.empty
    checked = 0
    for ang in np.linspace(0, 2 * np.pi, 64, endpoint=False):
        d = np.array([np.cos(ang), np.sin(ang)])
        obj = np.zeros(A.shape[1])
        obj[:2] = -d
        r = linprog(obj, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds, method="highs")
        assert r.status == 0
        if np.max(np.abs(r.x[:2])) > 1e3:  # on the stand-in bounds: a direction without a limit
            continue
        ref = -r.fun
        assert np.max(fs.vertices @ d) == pytest.approx(ref, rel=1e-6, abs=1e-6 * max(1.0, abs(ref)))
        checked += 1
    assert checked >= 16
