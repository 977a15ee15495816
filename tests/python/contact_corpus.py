"""A seeded corpus of humanoid contact problems and an independent exact projection (issue 9).

Robots from example-robot-data with their floating base (Talos, Romeo), standing on flat soles; paths of
our own, built by inverse kinematics that keeps the soles (and a hand, when it leans on a wall) in place:
  sway    the pelvis sideways by ±amplitude · sin(2π s)
  squat   the pelvis down by depth · sin(π s) and back up
  wall    the sway with the left hand pressed on a wall beside the robot (one extra contact)
The oracle is built without pathpace's dynamics: pinocchio's RNEA and frame Jacobians on the same URDF
give the full polytope in (ṡ², s̈, cone weights), and scipy's HiGHS gives its support values. Shared by
tests/python/test_projection_corpus.py (a fast slice) and bench/contact_projection.py (all of it).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import linprog

import pathpace as pp
from pathpace.robots import example_robot_urdf

from oracles import composite_floating_joint, generators

CAP = 1e6  # ContactOptions::cap, the stand-in bounds on ṡ² and |s̈|


@dataclass
class Humanoid:
    name: str
    urdf: str
    soles: tuple[str, str]
    sole_size: tuple[float, float]  # x, y extent of the sole rectangle
    posture: dict[str, float]
    legs: list[str]      # joint-name prefixes moved by the IK for the feet
    arm: list[str]       # joint-name prefixes moved for the hand on the wall
    hand: str
    locked: list[str] = field(default_factory=list)
    sole_origin: tuple[float, float, float] = (0.0, 0.0, 0.0)  # the sole rectangle's centre in the sole frame
    torso: list[str] = field(default_factory=list)  # pitch joints bent by a lean (issue 27)
    robot: pp.RobotModel | None = None
    model: object = None  # pinocchio
    perm: np.ndarray | None = None  # pathpace coordinate i is pinocchio coordinate perm[i]


HUMANOIDS = {
    "talos": dict(urdf="talos_data/robots/talos_full_v2.urdf", soles=("left_sole_link", "right_sole_link"),
                  sole_size=(0.2, 0.1),
                  posture={"leg_left_3_joint": -0.411354, "leg_left_4_joint": 0.859395, "leg_left_5_joint": -0.448041,
                           "leg_right_3_joint": -0.411354, "leg_right_4_joint": 0.859395,
                           "leg_right_5_joint": -0.448041, "arm_left_1_joint": 0.25847, "arm_left_2_joint": 0.173046,
                           "arm_left_4_joint": -0.525366, "arm_right_1_joint": -0.25847,
                           "arm_right_2_joint": -0.173046, "arm_right_4_joint": -0.525366},
                  legs=["leg_"], arm=["arm_left_"], hand="arm_left_7_link"),
    "romeo": dict(urdf="romeo_description/urdf/romeo.urdf", soles=("l_sole", "r_sole"), sole_size=(0.16, 0.08),
                  posture={"LHipPitch": -0.25, "LKneePitch": 0.5, "LAnklePitch": -0.25,
                           "RHipPitch": -0.25, "RKneePitch": 0.5, "RAnklePitch": -0.25,
                           "LShoulderPitch": 1.2, "RShoulderPitch": 1.2, "LElbowYaw": -1.0},
                  legs=["LHip", "LKnee", "LAnkle", "RHip", "RKnee", "RAnkle"],
                  arm=["LShoulder", "LElbow", "LWrist"], hand="l_wrist", locked=["LHand", "RHand"]),
    # Unitree G1 (29 joints): no sole frame; the sole is the plane of the ankle roll link's four contact
    # spheres (x from -0.05 to 0.12, y within ±0.025-0.03, z = -0.03, radius 5 mm).
    "g1": dict(urdf="g1_description/urdf/g1_29dof_rev_1_0.urdf", soles=("left_ankle_roll_link", "right_ankle_roll_link"),
               sole_size=(0.17, 0.05), sole_origin=(0.035, 0.0, -0.035),
               posture={"left_hip_pitch_joint": -0.25, "left_knee_joint": 0.5, "left_ankle_pitch_joint": -0.25,
                        "right_hip_pitch_joint": -0.25, "right_knee_joint": 0.5, "right_ankle_pitch_joint": -0.25,
                        "left_elbow_joint": 0.8, "right_elbow_joint": 0.8},
               legs=["left_hip", "left_knee", "left_ankle", "right_hip", "right_knee", "right_ankle"],
               arm=["left_shoulder", "left_elbow", "left_wrist"], hand="left_rubber_hand", torso=["waist_pitch_joint"]),
}
HUMANOIDS["talos"]["torso"] = ["torso_2_joint"]

_cache: dict[str, Humanoid] = {}


def load(name: str) -> Humanoid:
    """The robot in pathpace and in pinocchio (mimic and listed joints locked at 0 in both)."""
    if name in _cache:
        return _cache[name]
    import pinocchio as pin
    h = Humanoid(name=name, **HUMANOIDS[name])
    urdf = str(example_robot_urdf(h.urdf))
    mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
    locked = mimic + h.locked
    h.robot = pp.RobotModel.from_urdf(urdf, floating_base=True, locked_joints={n: 0.0 for n in locked})
    full = pin.buildModelFromUrdf(urdf, composite_floating_joint())
    h.model = pin.buildReducedModel(full, [full.getJointId(n) for n in locked], pin.neutral(full))
    perm = []
    for i, jn in enumerate(h.robot.joint_names):
        if jn.startswith("floating_"):
            perm.append(i)  # the composite joint's six coordinates come first, in the same order
        else:
            perm.append(h.model.joints[h.model.getJointId(jn)].idx_q)
    h.perm = np.array(perm)
    assert h.model.nq == h.robot.nq and sorted(perm) == list(range(h.robot.nq))
    _cache[name] = h
    return h


def standing_posture(h: Humanoid) -> np.ndarray:
    q = np.zeros(h.robot.nq)
    for jn, v in h.posture.items():
        q[h.robot.joint_names.index(jn)] = v
    q[2] -= _point(h, q, h.soles[0], np.array(h.sole_origin))[2]  # soles on the ground, z = 0
    return q


def _point(h, q, frame, p):
    return (h.robot.frame_placement(q, frame) @ np.append(p, 1.0))[:3]


def hand_point(h: Humanoid) -> np.ndarray:
    return np.zeros(3)


def ik(h: Humanoid, q_ref: np.ndarray, base_y: float = 0.0, base_dz: float = 0.0, hand: bool = False,
       base_pitch: float = 0.0, start: np.ndarray | None = None) -> np.ndarray:
    """Pelvis at lateral offset base_y, height offset base_dz and pitched forward by base_pitch (rad);
    both soles (three marks each) and, with `hand`, the hand point where they are in q_ref; Gauss-Newton
    over the leg (and arm) joints; from `start` (default q_ref) with steps of at most 0.2 rad."""
    names = h.robot.joint_names
    free = [i for i, n in enumerate(names) if any(n.startswith(p) for p in h.legs + (h.arm if hand else []))]
    marks = [np.array(p) for p in ((0.0, 0.0, 0.0), (0.1, 0.0, 0.0), (0.0, 0.05, 0.0))]
    pins = [(f, p) for f in h.soles for p in marks] + ([(h.hand, hand_point(h))] if hand else [])
    targets = np.concatenate([_point(h, q_ref, f, p) for f, p in pins])
    q = (q_ref if start is None else start).copy()
    q[1] = q_ref[1] + base_y
    q[2] = q_ref[2] + base_dz
    q[4] = q_ref[4] + base_pitch  # floating_ry
    for _ in range(60 if start is None else 300):
        r = np.concatenate([_point(h, q, f, p) for f, p in pins]) - targets
        if np.max(np.abs(r)) < 1e-11:
            return q
        J = np.vstack([h.robot.point_jacobian(q, f, p)[:, free] for f, p in pins])
        step = np.linalg.lstsq(J, r, rcond=None)[0]
        q[free] -= step if start is None else step * min(1.0, 0.2 / max(np.max(np.abs(step)), 1e-300))
    raise RuntimeError(f"IK did not converge for {h.name} (residual {np.max(np.abs(r)):.2e})")


def make_path(h: Humanoid, kind: str, knots: int = 21) -> pp.CubicSplinePath:
    q0 = standing_posture(h)
    s = np.linspace(0.0, 1.0, knots)
    wp = [q0]
    for si in s[1:]:
        if kind == "squat":
            wp.append(ik(h, q0, base_dz=-0.04 * np.sin(np.pi * si)))
        else:
            wp.append(ik(h, q0, base_y=0.05 * np.sin(2 * np.pi * si), hand=kind == "wall"))
    return pp.CubicSplinePath(np.array(wp), knots=s)


def contacts(h: Humanoid, kind: str, grid: tuple[int, int] = (2, 2), friction: float = 0.5) -> list[pp.Contact]:
    """Points on a regular nx x ny grid over each sole ((2, 2): the corners), plus the hand on a wall
    beside the robot (normal -y in the world: the wall at +y pushes the hand towards the robot)."""
    lx, ly = h.sole_size
    ox, oy, oz = h.sole_origin
    xs, ys = ox + np.linspace(-lx / 2, lx / 2, grid[0]), oy + np.linspace(-ly / 2, ly / 2, grid[1])
    out = [pp.Contact(link, point=(x, y, oz), normal=(0, 0, 1), friction=friction)
           for link in h.soles for x in xs for y in ys]
    if kind == "wall":
        out.append(pp.Contact(h.hand, point=hand_point(h), normal=(0, -1, 0), friction=0.7))
    return out


# ---------------------------------------------------------------------------------------------------
# Issue 27: the cases where the projection's cost lives. Dense sole grids, per-point margins, strong
# leans and squats, torque limits scaled down until they bind.

HARD_MARGINS = {
    "fn1.5": {"min_normal_force": 1.5},
    "fm0.5+fn0.33": {"friction_margin": 0.5, "min_normal_force": 0.33},
}
# The paper's own margin (sec. V.D), the shifted cone: exact reduction to the sole corners.
SHIFTED_MARGINS = {
    "off1.5": {"cone_offset": 1.5},
    "fm0.5+off0.33": {"friction_margin": 0.5, "cone_offset": 0.33},
}
HARD_GRIDS = {"talos": (6, 5), "romeo": (6, 5), "g1": (8, 4)}  # 30, 30, 32 points per sole
# The smallest torque_scale of the ladder 1, 0.8, 0.6, 0.5, 0.4, 0.3, 0.25, 0.2, 0.15, 0.1 at which both
# HARD_MARGINS are OPTIMAL at N = 50 with 4 edges (hard_torque_scale, run once; 4 edges is the smallest
# cone, so 8 and 16 are feasible too): the limits bind along the motion.
HARD_TORQUE_SCALE = {("talos", "lean"): 0.3, ("talos", "squat"): 0.3, ("romeo", "lean"): 0.3,
                     ("romeo", "squat"): 0.4, ("g1", "lean"): 0.5, ("g1", "squat"): 0.5}


@dataclass(frozen=True)
class HardCase:
    robot: str
    kind: str         # lean | squat
    amplitude: float  # m: the lean's sideways sway, the squat's depth
    tilt: float       # rad: pelvis pitch at mid-path, and as much again in the torso joints


def hard_cases(seed: int = 27) -> list[HardCase]:
    """One seeded draw per robot and kind: a sway of 60-80 % of the half distance between the soles
    (the centre of mass near the sole's edge; the pelvis 3 % of its height lower at mid-path, so that the
    legs reach), or a squat of 10-15 % of the pelvis height; both with the
    pelvis pitched 0.3-0.4 rad forward and the torso as much again (36-46 deg from vertical)."""
    rng = np.random.default_rng(seed)
    out = []
    for robot in HUMANOIDS:
        for kind in ("lean", "squat"):
            frac, tilt = rng.uniform(0.6, 0.8), rng.uniform(0.3, 0.4)
            h = load(robot)
            q0 = standing_posture(h)
            if kind == "lean":
                half = 0.5 * abs(h.robot.frame_placement(q0, h.soles[0])[1, 3] - h.robot.frame_placement(q0, h.soles[1])[1, 3])
                amp = frac * half
            else:
                amp = (0.1 + 0.25 * (frac - 0.6)) * q0[2]
            out.append(HardCase(robot, kind, round(float(amp), 4), round(float(tilt), 3)))
    return out


def make_hard_path(h: Humanoid, case: HardCase, knots: int = 21) -> pp.CubicSplinePath:
    q0 = standing_posture(h)
    torso = [h.robot.joint_names.index(j) for j in h.torso]
    s = np.linspace(0.0, 1.0, knots)
    wp = [q0]
    for si in s[1:]:
        lean = case.tilt * np.sin(np.pi * si)
        if case.kind == "lean":
            q = ik(h, q0, base_y=case.amplitude * np.sin(2 * np.pi * si), base_dz=-0.03 * q0[2] * np.sin(np.pi * si),
                   base_pitch=lean, start=wp[-1])
        else:
            q = ik(h, q0, base_dz=-case.amplitude * np.sin(np.pi * si), base_pitch=lean, start=wp[-1])
        q[torso] = q0[torso] + lean
        wp.append(q)
    return pp.CubicSplinePath(np.array(wp), knots=s)


def hard_problem(robot: str, kind: str, margins: str, edges: int = 4, on_demand: bool = False, grid: int = 100,
                 scale: float | None = None, seed: int = 27) -> pp.TimeScalingProblem:
    """hard_cases(seed)'s (robot, kind) with the named HARD_MARGINS / SHIFTED_MARGINS, its sole grid and torque
    scale (or `scale`), as the tests and benches build it."""
    case = next(c for c in hard_cases(seed) if (c.robot, c.kind) == (robot, kind))
    h = load(robot)
    prob = pp.TimeScalingProblem(make_hard_path(h, case), grid=grid)
    prob.add_contacts(h.robot, contacts(h, "sway", grid=HARD_GRIDS[robot]), cone_edges=edges, drift_tolerance=1e-4,
                      torque_scale=HARD_TORQUE_SCALE[(robot, kind)] if scale is None else scale,
                      project_on_demand=on_demand, **{**HARD_MARGINS, **SHIFTED_MARGINS}[margins])
    return prob


def hard_torque_scale(h: Humanoid, path, cons, ladder=(1.0, 0.8, 0.6, 0.5, 0.4, 0.3, 0.25, 0.2, 0.15, 0.1)) -> float:
    """The smallest scale of the ladder at which every HARD_MARGINS set is OPTIMAL (N = 50, 4 edges)."""
    best = None
    for scale in ladder:
        for margins in HARD_MARGINS.values():
            prob = pp.TimeScalingProblem(path, grid=50)
            prob.add_contacts(h.robot, cons, cone_edges=4, drift_tolerance=1e-4, torque_scale=scale, **margins)
            if not prob.solve().ok:
                return best
        best = scale
    return best


# ---------------------------------------------------------------------------------------------------
# The oracle: the full polytope from pinocchio, support values from HiGHS.

def full_polytope(h: Humanoid, q, dq, ddq, cons, cone_edges, friction_margin=0.0, min_normal_force=0.0,
                  min_link_normal_force=0.0, torque_scale=1.0, cone_offset=0.0):
    """(A, lo, hi, bounds) of {(x, u, λ): lo <= A (x, u, λ) <= hi} in pathpace's coordinate order."""
    import pinocchio as pin
    model = h.model
    data = model.createData()
    P = h.perm
    qp, dqp, ddqp = (np.empty(len(P)) for _ in range(3))
    qp[P], dqp[P], ddqp[P] = q, dq, ddq
    n = model.nv
    c = pin.computeGeneralizedGravity(model, data, qp)
    a = pin.rnea(model, data, qp, dqp, ddqp) - c
    b = pin.rnea(model, data, qp, np.zeros(n), dqp) - c
    pin.forwardKinematics(model, data, qp)
    pin.updateFramePlacements(model, data)
    cols = [a[P, None], b[P, None]]
    w = np.zeros(n)  # the shifted cones' offsets: f_i = cone_offset n_i + G_i λ_i, a constant J_iᵀ n_i each
    for con in cons:
        fid = model.getFrameId(con.link)
        J6 = pin.computeFrameJacobian(model, data, qp, fid, pin.LOCAL)
        J = data.oMf[fid].rotation @ (J6[:3] - np.cross(np.asarray(con.point), J6[3:].T).T)
        G = generators(con.normal, con.friction * (1.0 - friction_margin), cone_edges)
        cols.append((-J.T @ G)[P])
        nrm = np.asarray(con.normal, float)
        w += cone_offset * J.T @ (nrm / np.linalg.norm(nrm))
    A = np.hstack(cols)
    eff = h.robot.effort_limits * torque_scale
    lo, hi = -eff - c[P] + w[P], eff - c[P] + w[P]
    rows, rlo, rhi = [A], [lo], [hi]
    m, k = len(cons), cone_edges
    if min_normal_force > 0:
        rows.append(np.hstack([np.zeros((m, 2)), np.kron(np.eye(m), np.ones(k))]))
        rlo.append(np.full(m, min_normal_force - cone_offset))
        rhi.append(np.full(m, np.inf))
    if min_link_normal_force > 0:
        links = sorted({con.link for con in cons})
        L = np.zeros((len(links), 2 + m * k))
        for i, con in enumerate(cons):
            L[links.index(con.link), 2 + i * k: 2 + (i + 1) * k] = 1.0
        rows.append(L)
        rlo.append(np.full(len(links), min_link_normal_force) - cone_offset * L[:, 2::k].sum(axis=1))
        rhi.append(np.full(len(links), np.inf))
    bounds = [(0, CAP), (-CAP, CAP)] + [(0, None)] * (m * k)
    return np.vstack(rows), np.concatenate(rlo), np.concatenate(rhi), bounds


def exact_support(A, lo, hi, bounds, directions):
    """Support values of the shadow in each direction (nan where the optimum is on a stand-in bound), or
    None when the polytope is empty. Equalities where lo == hi."""
    eq = lo == hi
    A_eq, b_eq = A[eq], lo[eq]
    ub_rows, ub = [], []
    fin_hi, fin_lo = (~eq) & np.isfinite(hi), (~eq) & np.isfinite(lo)
    A_ub = np.vstack([A[fin_hi], -A[fin_lo]])
    b_ub = np.concatenate([hi[fin_hi], -lo[fin_lo]])
    out = []
    for d in directions:
        obj = np.zeros(A.shape[1])
        obj[:2] = -d
        # HiGHS at tight tolerances; once or twice in thousands of LPs it stops without a status
        # ("Not Set"): then its defaults, then its interior-point method.
        for method, options in (("highs", {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}),
                                ("highs-ds", {}), ("highs-ipm", {})):
            r = linprog(obj, A_ub=A_ub, b_ub=b_ub, A_eq=A_eq, b_eq=b_eq, bounds=bounds, method=method, options=options)
            if r.status in (0, 2):
                break
        if r.status == 2:
            return None
        assert r.status == 0, r.message
        out.append(np.nan if np.max(np.abs(r.x[:2])) > 0.5 * CAP else -r.fun)
    return np.array(out)


def directions(count: int = 64) -> np.ndarray:
    """`count` unit directions, evenly spaced and half a step off the axes: along an axis, e.g. (-1, 1e-16)
    on the edge ṡ² = 0 of a set unbounded in s̈, a point on the stand-in bound and one off it are equally
    good to the LP, and which one it returns decides whether the direction reads as unbounded."""
    ang = (np.arange(count) + 0.5) * (2 * np.pi / count)
    return np.stack([np.cos(ang), np.sin(ang)], axis=1)


def polygon_support(fs, dirs):
    """Support values in each direction; nan where attained on a stand-in bound or pathpace's 1e15 cut of
    an unbounded set (nothing about the limits there)."""
    vals = fs.vertices @ dirs.T
    out = vals.max(axis=0)
    on_cut = np.any(np.abs(fs.vertices[vals.argmax(axis=0)]) > 0.5 * CAP, axis=1)
    return np.where(on_cut, np.nan, out)


def polygon_size(fs) -> float:
    v = fs.vertices[np.all(np.abs(fs.vertices) < 0.5 * CAP, axis=1)]
    if len(v) == 0:
        return 0.0
    return float(max(np.ptp(v[:, 0]), np.ptp(v[:, 1])))


def same_unbounded_directions(ha, hb, what: str):
    """Asserts that two support vectors are unbounded (nan: on a stand-in bound) in the same directions;
    returns where both are finite, the directions to compare."""
    na, nb = np.isnan(ha), np.isnan(hb)
    assert np.array_equal(na, nb), (f"{what}: unbounded in directions {np.flatnonzero(na).tolist()} and "
                                    f"{np.flatnonzero(nb).tolist()} (of {len(ha)})")
    return ~na


def compare(h: Humanoid, prob: pp.TimeScalingProblem, cons, options: dict, points=None, dirs=None):
    """Each grid point's feasible set against the exact projection: returns (worst error / size, number
    of points whose support values were compared, number of empty points); asserts that emptiness and the
    unbounded directions agree."""
    dirs = directions() if dirs is None else dirs
    path = prob.path
    s = prob.grid
    ks = range(len(s)) if points is None else points
    worst, compared, empty = 0.0, 0, 0
    for k in ks:
        q, dq, ddq = path.q(s[k]), path.dq(s[k]), path.ddq(s[k])
        fs = prob.feasible_set(k)
        A, lo, hi, bounds = full_polytope(h, q, dq, ddq, cons, options.get("cone_edges", 8),
                                          options.get("friction_margin", 0.0), options.get("min_normal_force", 0.0),
                                          options.get("min_link_normal_force", 0.0), options.get("torque_scale", 1.0),
                                          options.get("cone_offset", 0.0))
        ref = exact_support(A, lo, hi, bounds, dirs)
        if ref is None:
            assert fs.empty, f"k = {k}: the exact polytope is empty, pathpace's set is not"
            empty += 1
            continue
        assert not fs.empty, f"k = {k}: pathpace's set is empty, the exact polytope is not (false INFEASIBLE)"
        assert fs.exact
        got = polygon_support(fs, dirs)
        ok = same_unbounded_directions(got, ref, f"k = {k}: pathpace's polygon and the exact projection")
        if ok.any():
            size = max(polygon_size(fs), 1e-12)
            worst = max(worst, np.max(np.abs(got[ok] - ref[ok])) / size)
            compared += 1
    return worst, compared, empty


def assert_nested(inner, outer, dirs, rtol: float, what: str):
    """inner ⊆ outer by their support values: unbounded in the same directions, and in every other
    inner's value <= outer's + rtol · outer's size."""
    ha, hb = polygon_support(inner, dirs), polygon_support(outer, dirs)
    ok = same_unbounded_directions(ha, hb, what)
    assert np.all(ha[ok] <= hb[ok] + rtol * max(polygon_size(outer), 1e-12)), what


def box_problem(h: Humanoid, mass: float = 3.0, knots: int = 21):
    """The sway carrying a box squeezed between the hands: a free object (6 more coordinates) combined
    with the robot, two contact points per hand against the box's sides (normals in the box's frame,
    pushing each hand outwards), μ = 0.7. The feet-fixed IK moves the legs only, so the upper body and
    the box translate with the pelvis. Returns (robot, path, contacts); no pinocchio oracle (statuses,
    nesting and speed only)."""
    hands = {"talos": ("arm_left_7_link", "arm_right_7_link"), "romeo": ("l_wrist", "r_wrist")}[h.name]
    q0 = standing_posture(h)
    s = np.linspace(0.0, 1.0, knots)
    body = [q0] + [ik(h, q0, base_y=0.05 * np.sin(2 * np.pi * si)) for si in s[1:]]
    centre = 0.5 * (h.robot.frame_placement(q0, hands[0])[:3, 3] + h.robot.frame_placement(q0, hands[1])[:3, 3])
    box = pp.RobotModel.free_object("box", mass, inertia=np.diag([0.05, 0.02, 0.05]))
    robot = pp.RobotModel.combine([h.robot, box])
    wp = [np.concatenate([q, centre + (q[:3] - q0[:3]), np.zeros(3)]) for q in body]
    path = pp.CubicSplinePath(np.array(wp), knots=s)
    cons = []
    for hand, side in zip(hands, (1.0, -1.0)):
        R = h.robot.frame_placement(q0, hand)[:3, :3]
        for dx in (-0.03, 0.03):
            cons.append(pp.Contact(hand, point=R.T @ np.array([dx, 0.0, 0.0]), normal=(0.0, side, 0.0),
                                   friction=0.7, other_link="box"))
    return robot, path, contacts(h, "sway") + cons
