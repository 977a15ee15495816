"""Talos climbs a ladder on hands and feet: 16 changes of contact, timed with contact phases (the paper's fig. 5).

The ladder: RUNGS box rungs (DEPTH deep, THICKNESS thick, WIDTH wide), rung j's top centre at
x = X0 + j RUN, z = j RISE (a steep ladder: atan(RISE / RUN) = 68 degrees). Talos (example-robot-data,
floating base, 38 coordinates) starts with both feet on rung 1 and both hands on rung 6 and moves one limb
at a time up by one rung, in the order left hand, right foot, right hand, left foot, CYCLES times: 2 cycles
climb 2 rungs with 8 swings, i.e. 16 contact changes (8 breaks, 8 makes). The hands end on the top rung.

The contacts are frictional points, no adhesion: four points on the front half of each sole on the rung
top (world normal +z; a rung is narrower than the sole), and a grip per hand: the centre of a ball of radius
BALL (the simulator's contact sphere; the hand turns on it as the body climbs past) on the rung top (+z)
and against a ridge on it that holds it from behind (+x, a pull towards the ladder): two contacts through
the ball's centre, each with its own friction cone (GRIP). The phases, one unit of s each: a shift with all four limbs down (the centre of mass moves
over the next support), then the swing of one limb with the other three down; 8 of each and a final
shift: 17 phases on s in [0, 17].

Each knot of the path (KNOTS_PER_PHASE per phase) is an inverse-kinematics solution on pathpace's frame
Jacobians (RobotModel.frame_jacobian): soles at their placements (position and orientation), the hands'
ball centres at their positions, the centre of mass (central differences of RobotModel.center_of_mass) over
the support, exactly; a posture (the pelvis rising with the feet, half-sitting joints) in the null space;
every joint LIMIT_GAP inside its limits. The path is the C² joint spline through the knots, so it does not
kink at the switches; a swing limb's own plan lands at rest, but the spline brings it down at a small speed,
so the no-impact rule of add_contact_phases puts ṡ = 0 at each make.

Timed with torque limits (the URDF's effort) and the contacts of each phase, μ = 0.5 used with a 50 %
friction margin and a minimum normal force per point (MARGINS), on N intervals with every switch a grid
point (phase_grid). --sweep times it at N = 50..800 and plots run time against N
(examples/output/humanoid_ladder.png). --sim executes it in MuJoCo (pathpace.sim: the rungs as box geoms,
the hands' balls as ball_links, contacts with time constant CONTACT_TIMECONST, the feed-forward's forces in
the plan's friction margin): the N = 100 timing, the one at SIM_GRID with the motors planned at TORQUE_SCALE
and SIM_MIN_NORMAL_FORCE per point, the velocity and acceleration optimum, and the uniform timing at its T;
--seeds K runs the executed timing K more times with seeded feed-forward torque noise. The N = --grid timing's
HTML report (each limb's normal force and centre of pressure in its support polygon) goes to
examples/output/humanoid_ladder.html (--report).

    .venv/bin/python examples/humanoid_ladder.py [--grid 100] [--sweep] [--sim [--seeds 5]] [--repeat 5] [--contact-timeconst 0.002]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

import pathpace as pp

sys.path.insert(0, str(Path(__file__).resolve().parent))
import talos_sway  # noqa: E402  (Talos loader and half-sitting posture)

RISE, RUN = 0.2, 0.08  # m between rungs, vertically and horizontally
X0 = 0.12  # rung j's top centre: x = X0 + j RUN, z = j RISE
DEPTH, THICKNESS, WIDTH = 0.06, 0.03, 0.8  # rung box (m)
RUNGS = 8
FOOT_RUNG, HAND_RUNG = 1, 6  # where the feet and the hands start
CYCLES = 2
FRICTION = 0.5
MARGINS = dict(cone_edges=8, friction_margin=0.5, min_normal_force=10.0)
KNOTS_PER_PHASE = 16
# The spline through the knots keeps every held point within 0.22 mm of its place (max_drift at 401 points per
# phase): the drift tolerance of add_contact_phases, a tenth of the slip that a run with room may have.
DRIFT = 3e-4
# The executed timing: N = 400 (at N = 100 the torques between grid points exceed the limits by up to 4 x
# just after a lift-off, and the robot falls), the motors planned at TORQUE_SCALE x their effort (the rest
# is the feedback's) and SIM_MIN_NORMAL_FORCE per point.
SIM_GRID, TORQUE_SCALE, SIM_MIN_NORMAL_FORCE = 400, 0.8, 30.0
# MuJoCo's contacts in this scene: time constant 2 ms, the stiffest its 1 ms step allows. MuJoCo's friction is
# soft (a held point under a tangential load creeps at a speed proportional to the time constant), and at the
# simulator's default of 5 ms the climb's held points slide 2-3 x as far (bench/README.md).
CONTACT_TIMECONST = 0.002
# The feed-forward's forces keep the friction reserve the plan kept (Simulator.run's feedforward_friction_margin):
# the physical cones' centre asks a hand for up to 0.42 N tangentially per N of normal force at mu = 0.5.
FEEDFORWARD_FRICTION_MARGIN = MARGINS["friction_margin"]

FEET = talos_sway.SOLES  # left, right
HANDS = ("gripper_left_base_link", "gripper_right_base_link")
LIMBS = (HANDS[0], FEET[1], HANDS[1], FEET[0])  # the order of the swings in a cycle
# The front half of a sole: 4 cm x 10 cm, over the middle of the rung (the sole frame 5.5 cm behind it).
SOLE_CENTRE = 0.055
FOOT_POINTS = [(x, y, 0.0) for x in (SOLE_CENTRE - 0.02, SOLE_CENTRE + 0.02) for y in (-0.05, 0.05)]
HAND_POINT = (0.0, 0.0, 0.0)
# A hand holds a rung with a ball of this radius (the simulator's contact sphere) centred on its point: the
# point is BALL above the rung, and the hand may turn on the ball as the body climbs past it (a sole's
# points are on the sole's surface instead: a sole stays flat). pathpace puts the hand's force at the
# ball's centre, the simulator at its bottom: a moment of BALL x the friction force, at most 0.001 m x 0.25 x
# the normal force. Small because a ball that turns rolls: its friction holds the bottom point, so its centre
# moves by BALL x the turn, and a hand turns by up to 0.9 rad over one hold (measured 2026-12-07: the 5 mm
# ball's centre moved as pure rolling predicts, to 0.5 mm, over the first 1.1-1.3 s of a hold; its hands slid up
# to 3.5 mm in all, 1.2 mm with 1 mm; bench/README.md).
BALL = 0.001
HAND_Y = 0.35  # |y| of the hands on the rungs
# A hand hooks its rung (GRIP): besides the rung top (normal +z) its ball is held from behind by a ridge on the
# rung top (the fingers behind the rung: a face with normal +x, a frictional point contact through the ball's
# centre, no adhesion), so a hand can pull the body towards the ladder, not only press down. Not also a face
# in front (-x): two contacts of one rigid link with opposite normals through one point would let the plan
# squeeze the ball between them for free (their normal forces cancel in every torque) and so buy any
# friction it likes, which no rigid hand has (measured: the timing then takes 6.2 s and the robot falls at
# s = 6.7). The ridge in front stays in the scene (the hand closed around the rung), unused by the plan.
# RIDGE: the ridges' thickness along x; they are BALL high (up to the ball's centre, where its equator
# touches them) and 2 RIDGE_Y wide around the hand.
# Off by default: measured 2026-12-02 (N = 400, 30 N per point, motors 0.8 x) the grip does not help: T =
# 10.750 s and the robot falls at s = 7.9 (with ṡ = 0 at the breaks too: 11.394 s, falls at s = 7.3); the
# left hand lands on its ridge at s = 2 (MuJoCo's hand lags the plan's by more than the 0.5 mm play while
# it comes down from behind), lifted 3 mm, and the right hand then slides. A hook wants the hand to come
# down onto the rung from above the ridge, which this path does not do (bench/README.md).
GRIP = False
GRIP_NORMALS = ((0.0, 0.0, 1.0), (1.0, 0.0, 0.0))  # a hand with grip: the rung top and the ridge behind
RIDGE, RIDGE_Y = 0.005, 0.04
RIDGE_GAP = 0.0005  # m between the ball and each ridge where the plan puts it (the grip's play)
LIMIT_GAP = 0.02  # rad (m) that the IK keeps inside every joint limit
LIFT = 0.05  # m above the straight line that a swing limb clears


def rung_top(j: int) -> np.ndarray:
    """World position of the middle of rung j's top surface (rung 0 is the floor under the ladder's foot)."""
    return np.array([X0 + j * RUN, 0.0, j * RISE])


def rung_boxes(grip: bool = GRIP) -> list[dict]:
    """The rungs as axis-aligned boxes: centre and half sizes (m), for pathpace.sim.Simulator(surfaces=...);
    with grip, the ridges that hold the hands' balls on the rungs the hands hold (HAND_RUNG to the top)."""
    half = np.array([DEPTH / 2, WIDTH / 2, THICKNESS / 2])
    out = [dict(centre=rung_top(j) - [0.0, 0.0, THICKNESS / 2], half_size=half, name=f"rung_{j}")
           for j in range(1, RUNGS + 1)]
    if grip:
        ridge = np.array([RIDGE / 2, RIDGE_Y, BALL / 2])
        for j in range(HAND_RUNG, RUNGS + 1):
            for y in (HAND_Y, -HAND_Y):
                for side, name in ((-1.0, "behind"), (1.0, "front")):
                    c = rung_top(j) + [side * (BALL + RIDGE_GAP + RIDGE / 2), y, BALL / 2]
                    out.append(dict(centre=c, half_size=ridge, name=f"rung_{j}_ridge_{name}_{'left' if y > 0 else 'right'}"))
    return out


def limb_contacts(link: str, grip: bool = GRIP) -> list[pp.Contact]:
    """A sole's four points on the rung top; a hand's ball centre on the rung top (+z), and with grip
    against the ridge behind it too (GRIP_NORMALS)."""
    if link in FEET:
        return [pp.Contact(link, point=p, normal=(0, 0, 1), friction=FRICTION) for p in FOOT_POINTS]
    return [pp.Contact(link, point=HAND_POINT, normal=n, friction=FRICTION) for n in (GRIP_NORMALS if grip else GRIP_NORMALS[:1])]


def all_contacts(grip: bool = GRIP) -> list[pp.Contact]:
    return [c for link in (*FEET, *HANDS) for c in limb_contacts(link, grip)]


def schedule(cycles: int = CYCLES) -> list[tuple[float, float, str | None]]:
    """(s_begin, s_end, swinging limb or None) per phase: shift, swing, shift, swing, ..., shift."""
    out, s = [], 0.0
    for _ in range(cycles):
        for limb in LIMBS:
            out += [(s, s + 1.0, None), (s + 1.0, s + 2.0, limb)]
            s += 2.0
    out.append((s, s + 1.0, None))
    return out


def phases(cycles: int = CYCLES, grip: bool = GRIP) -> list[tuple[float, float, list[pp.Contact]]]:
    """The contact phases: every limb's contacts but the swinging one's."""
    return [(s0, s1, [c for c in all_contacts(grip) if c.link != limb]) for s0, s1, limb in schedule(cycles)]


def contact_changes(cycles: int = CYCLES) -> int:
    """Makes plus breaks between consecutive phases (contact points counted per limb)."""
    ph = schedule(cycles)
    return sum((a[2] is None) != (b[2] is None) for a, b in zip(ph, ph[1:]))


def smooth(u):
    """0 -> 1 on u in [0, 1], at rest at both ends (zero first and second derivatives)."""
    u = np.clip(u, 0.0, 1.0)
    return u ** 3 * (10 - 15 * u + 6 * u ** 2)


class ClimbPlan:
    """The limbs' world targets and the centre-of-mass target as functions of s."""

    def __init__(self, cycles: int = CYCLES):
        self.phases = schedule(cycles)
        self.swings = {limb: [(s0, s1) for s0, s1, l in self.phases if l == limb] for limb in (*FEET, *HANDS)}

    def rung(self, limb: str, s: float) -> float:
        """The limb's rung at s, fractional during a swing (the swing's progress, smoothed)."""
        start = FOOT_RUNG if limb in FEET else HAND_RUNG
        return start + sum(float(smooth(s - s0)) if s < s1 else 1.0 for s0, s1 in self.swings[limb] if s > s0)

    def swing_progress(self, limb: str, s: float) -> float | None:
        for s0, s1 in self.swings[limb]:
            if s0 < s < s1:
                return s - s0
        return None

    def limb_position(self, limb: str, s: float) -> np.ndarray:
        """The world target of the limb's contact centre: on its rung's top, or on its way to the next one
        (up first, then forward and down, so that it clears the rung above: see LIFT)."""
        side = 1.0 if limb in (FEET[0], HANDS[0]) else -1.0
        y = side * (0.085 if limb in FEET else HAND_Y)
        u = self.swing_progress(limb, s)
        if u is None:
            return rung_top(int(round(self.rung(limb, s)))) + [0.0, y, 0.0 if limb in FEET else BALL]
        j = int(round(self.rung(limb, s - u)))  # the rung it left
        up = RISE * smooth(u / 0.6) + LIFT * np.sin(np.pi * u) ** 2
        # A foot goes forward sooner than a hand (its ankle would bend past its limit), still clearing the
        # rung above by 1.4 cm; a hand's point starts 3 cm behind the rung above and goes up first.
        fwd = RUN * (smooth((u - 0.15) / 0.7) if limb in FEET else smooth((u - 0.4) / 0.6))
        return rung_top(j) + [fwd, y, up + (0.0 if limb in FEET else BALL)]

    def support(self, s: float) -> list[str]:
        for s0, s1, limb in self.phases:
            if s0 <= s <= s1 and limb is not None:
                return [l for l in (*FEET, *HANDS) if l != limb]
        return [*FEET, *HANDS]

    def com_target(self, s: float, hand_weight: float = 0.1) -> np.ndarray:
        """(x, y): a weighted mean of the support's contact centres (feet 1, hands hand_weight) during a swing;
        in a shift, from the previous swing's target to the next one's, smoothly."""
        def target(limbs: list[str], at: float) -> np.ndarray:
            w = np.array([1.0 if l in FEET else hand_weight for l in limbs])
            p = np.array([self.limb_position(l, at)[:2] for l in limbs])
            return (w[:, None] * p).sum(axis=0) / w.sum()

        for k, (s0, s1, limb) in enumerate(self.phases):
            if s0 <= s <= s1:
                break
        if limb is not None:
            return target([l for l in (*FEET, *HANDS) if l != limb], s)
        prev = self.phases[k - 1][2] if k > 0 else None
        nxt = self.phases[k + 1][2] if k + 1 < len(self.phases) else None
        a = target([l for l in (*FEET, *HANDS) if l != prev], s)
        b = target([l for l in (*FEET, *HANDS) if l != nxt], s)
        return a + (b - a) * float(smooth(s - s0))


def _rotation_error(R_target: np.ndarray, R: np.ndarray) -> np.ndarray:
    """The rotation vector of R_target Rᵀ (world frame): what the angular rows of a frame Jacobian close."""
    E = R_target @ R.T
    angle = math.acos(max(-1.0, min(1.0, (np.trace(E) - 1.0) / 2.0)))
    w = np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
    return w * (0.5 if angle < 1e-8 else angle / (2.0 * math.sin(angle)))


class ClimbIK:
    """Whole-body IK on pathpace's Jacobians: limbs at their placements and the centre of mass (x, y) at its
    target exactly (Gauss-Newton); a posture in their null space."""

    def __init__(self, robot: pp.RobotModel):
        self.robot = robot
        names = robot.joint_names
        self.free = [i for i, n in enumerate(names) if not (n.startswith("head") or n.startswith("gripper"))]
        self.q_half = talos_sway.standing_posture(robot)
        # Posture weights: the floating base (position, orientation), then the joints.
        self.weight = np.array([1.0 if i < 6 or names[i].startswith("torso") else 0.3 for i in self.free])

    def com_jacobian(self, q: np.ndarray, h: float = 1e-7) -> np.ndarray:
        J = np.empty((2, len(self.free)))
        for j, i in enumerate(self.free):
            e = np.zeros(self.robot.nq)
            e[i] = h
            J[:, j] = (self.robot.center_of_mass(q + e)[:2] - self.robot.center_of_mass(q - e)[:2]) / (2 * h)
        return J

    def _tasks(self, q: np.ndarray, limbs: dict, com_xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        robot, rows, err = self.robot, [], []
        for link, (p, R) in limbs.items():
            point = np.array([SOLE_CENTRE, 0, 0]) if link in FEET else np.array(HAND_POINT)
            X = robot.frame_placement(q, link)
            J = robot.frame_jacobian(q, link, point)[:, self.free]
            err.append(p - (X[:3, :3] @ point + X[:3, 3]))
            rows.append(J[:3])
            if R is not None:
                err.append(_rotation_error(R, X[:3, :3]))
                rows.append(J[3:])
        err.append(com_xy - robot.center_of_mass(q)[:2])
        rows.append(self.com_jacobian(q))
        return np.vstack(rows), np.concatenate(err)

    def _step(self, J1: np.ndarray, e1: np.ndarray, e2: np.ndarray, cols: np.ndarray) -> np.ndarray:
        """The Gauss-Newton step of the limb/CoM task, plus the posture's in its null space, over `cols`."""
        J = J1[:, cols]
        Jp = np.linalg.pinv(J, rcond=1e-10)
        dq1 = Jp @ e1
        N = np.eye(len(cols)) - Jp @ J
        W = np.diag(self.weight[cols])
        out = np.zeros(len(self.free))
        out[cols] = dq1 + np.linalg.pinv(W @ N, rcond=1e-10) @ (self.weight[cols] * e2[cols] - W @ dq1)
        return out

    def solve(self, q_start: np.ndarray, limbs: dict[str, tuple[np.ndarray, np.ndarray | None]], com_xy: np.ndarray,
              q_ref: np.ndarray, iterations: int = 1000) -> np.ndarray:
        """limbs: {link: (world position of the link's point HAND_POINT / the sole's contact centre,
        world rotation or None for position only)}. Joints stay LIMIT_GAP inside their limits: a joint at a
        limit that the step pushes out of it is held there (an active set) for that step."""
        free = np.array(self.free)
        lo, hi = (np.asarray(b, dtype=float)[free] for b in self.robot.position_limits)
        lo, hi = lo + LIMIT_GAP, hi - LIMIT_GAP
        q = q_start.copy()
        q[free] = np.clip(q[free], lo, hi)
        everything = np.arange(len(free))
        for _ in range(iterations):
            J1, e1 = self._tasks(q, limbs, com_xy)
            e2 = q_ref[free] - q[free]
            dq = self._step(J1, e1, e2, everything)
            x = q[free]
            held = ((x <= lo + 1e-12) & (dq < 0)) | ((x >= hi - 1e-12) & (dq > 0))
            if held.any():
                dq = self._step(J1, e1, e2, np.flatnonzero(~held))
            scale = min(1.0, 0.2 / max(float(np.max(np.abs(dq))), 1e-300))
            new = np.clip(x + scale * dq, lo, hi)
            moved = float(np.max(np.abs(new - x)))
            q[free] = new
            if np.max(np.abs(e1)) < 1e-10 and moved < 1e-6:
                return q
        if np.max(np.abs(e1)) < 1e-7:  # the limbs within 0.1 µm (rad), the posture's slow tail cut short
            return q
        raise RuntimeError(f"climb IK did not converge (limbs {list(limbs)}, CoM {com_xy}; limb/CoM residual "
                           f"{np.max(np.abs(e1)):.2e}, step {moved:.2e})")


def posture_reference(ik: ClimbIK, plan: ClimbPlan, s: float) -> np.ndarray:
    """The null-space posture: half-sitting joints, the pelvis and the torso each leaning 0.2 rad towards the
    ladder, the pelvis over the centre of mass's target and 0.8 m above the mean foot height."""
    q = ik.q_half.copy()
    feet = np.mean([plan.limb_position(f, s) for f in FEET], axis=0)
    q[0], q[1] = plan.com_target(s)
    q[2] = feet[2] + 0.8
    q[3], q[4], q[5] = 0.0, 0.2, 0.0
    q[ik.robot.joint_names.index("torso_2_joint")] = 0.2
    return q


def initial_posture(robot: pp.RobotModel) -> np.ndarray:
    """A first guess at s = 0: half-sitting moved onto FOOT_RUNG."""
    q = talos_sway.standing_posture(robot)
    q[0] += rung_top(FOOT_RUNG)[0] - SOLE_CENTRE + 0.009
    q[2] += rung_top(FOOT_RUNG)[2]
    return q


def _ik_sweep(robot: pp.RobotModel, plan: ClimbPlan, s: np.ndarray) -> list[np.ndarray]:
    """IK postures at the values s, each from the one before: soles at their placements, hands' points at
    their positions."""
    ik = ClimbIK(robot)

    def targets(si: float) -> dict:
        return {l: (plan.limb_position(l, si), np.eye(3) if l in FEET else None) for l in (*FEET, *HANDS)}

    def reach(q: np.ndarray, s_from: float, s_to: float, depth: int = 0) -> np.ndarray:
        # Continuation: a knot that the previous one's posture does not lead to is reached through the
        # middle of the interval (Gauss-Newton from too far away lands in another branch or stalls).
        try:
            return ik.solve(q, targets(s_to), plan.com_target(s_to), posture_reference(ik, plan, s_to))
        except RuntimeError as e:
            if depth == 4:
                raise RuntimeError(f"at s = {s_to:.4f}: {e}") from None
            mid = 0.5 * (s_from + s_to)
            return reach(reach(q, s_from, mid, depth + 1), mid, s_to, depth + 1)

    waypoints = [reach(initial_posture(robot), s[0], s[0])]
    for a, b in zip(s, s[1:]):
        waypoints.append(reach(waypoints[-1], a, b))
    return waypoints


def climb_path(robot: pp.RobotModel, cycles: int = CYCLES, knots_per_phase: int = KNOTS_PER_PHASE) -> pp.CubicSplinePath:
    """The C² joint spline through the IK postures at `knots_per_phase` knots per phase: soles flat on their
    rungs, the hands' ball centres at theirs (a hand turns on its ball as the body climbs past it)."""
    plan = ClimbPlan(cycles)
    s_end = plan.phases[-1][1]
    s = np.linspace(0.0, s_end, int(round(s_end)) * knots_per_phase + 1)
    waypoints = _ik_sweep(robot, plan, s)
    lo, hi = robot.position_limits
    for si, q in zip(s, waypoints):
        bad = np.flatnonzero((q < lo) | (q > hi))
        if bad.size:
            i = bad[0]
            raise RuntimeError(f"climb IK at s = {si:.3f}: {robot.joint_names[i]} = {q[i]:.3f} outside [{lo[i]:.3f}, {hi[i]:.3f}]")
    return pp.CubicSplinePath(np.array(waypoints), knots=s)


def phase_grid(n: int, cycles: int = CYCLES) -> np.ndarray:
    """n intervals with every switch on the grid: n // phases per phase, one more in the first n % phases
    (a uniform grid of n would have the switches inserted, n + 16 intervals)."""
    ph = schedule(cycles)
    per = [n // len(ph) + (1 if i < n % len(ph) else 0) for i in range(len(ph))]
    if min(per) < 1:
        raise ValueError(f"grid = {n}: at least one interval per phase ({len(ph)})")
    return np.concatenate([np.linspace(s0, s1, m + 1)[:-1] for (s0, s1, _), m in zip(ph, per)] + [[ph[-1][1]]])


def timing(robot: pp.RobotModel, path: pp.Path, grid: int, cycles: int = CYCLES, drift_tolerance: float = DRIFT,
           **options) -> tuple[pp.TimeScalingProblem, pp.Result, float, float]:
    """(problem, result, add_contact_phases time, solve time), times in s; N = grid intervals (phase_grid)."""
    prob = pp.TimeScalingProblem(path, grid=phase_grid(grid, cycles))
    t0 = time.perf_counter()
    prob.add_contact_phases(robot, phases(cycles), drift_tolerance=drift_tolerance, **options)
    t_sets = time.perf_counter() - t0
    t0 = time.perf_counter()
    res = prob.solve()
    return prob, res, t_sets, time.perf_counter() - t0


def simulator(robot: pp.RobotModel, path: pp.Path, cycles: int = CYCLES, grip: bool = GRIP, **options):
    """pathpace.sim's Talos on the ladder: every contact a sphere, placed where its first phase makes it, the
    rungs as boxes (humanoid_sim.talos_simulator's URDF and locked grippers), contacts with time constant
    CONTACT_TIMECONST unless `options` say otherwise."""
    import humanoid_sim  # noqa: E402  (MuJoCo; imported only here)
    from pathpace.sim import Box, contact_configurations

    contacts = all_contacts(grip)
    options.setdefault("contact_timeconst", CONTACT_TIMECONST)
    return humanoid_sim.talos_simulator(robot, path, contacts, surfaces=[Box(**b) for b in rung_boxes(grip)],
                                        ball_links=HANDS, contact_radius=BALL,
                                        contact_configurations=contact_configurations(path, phases(cycles, grip), contacts),
                                        **options)


def run_time_sweep(robot: pp.RobotModel, path: pp.Path, grids=(50, 100, 200, 400, 800), repeat: int = 5) -> list[dict]:
    """add_contact_phases + solve at each N, `repeat` times: wall-clock median and worst (s), and the median
    CPU time of this process (the wall time of a quiet machine: the work is single-threaded)."""
    rows = []
    for n in grids:
        runs = []
        for _ in range(repeat):
            c0 = time.process_time()
            _, res, t_sets, t_solve = timing(robot, path, n, **MARGINS)
            runs.append((t_sets, t_solve, t_sets + t_solve, time.process_time() - c0))
        runs = np.array(runs)
        rows.append({"N": n, "status": res.status.name, "T": res.duration, "projection": float(np.median(runs[:, 0])),
                     "solve": float(np.median(runs[:, 1])), "median": float(np.median(runs[:, 2])),
                     "worst": float(np.max(runs[:, 2])), "cpu": float(np.median(runs[:, 3]))})
        r = rows[-1]
        print(f"| {n:4d} | {r['status']} | {r['T']:.4f} | {1e3 * r['projection']:8.1f} | {1e3 * r['solve']:7.1f} | "
              f"{1e3 * r['median']:8.1f} | {1e3 * r['worst']:8.1f} | {1e3 * r['cpu']:8.1f} |", flush=True)
    return rows


def plot_sweep(rows: list[dict], out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = np.array([r["N"] for r in rows], dtype=float)
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for key, label in (("projection", "add_contact_phases (projection)"), ("solve", "solve"), ("median", "total"),
                       ("cpu", "total, CPU time")):
        ax.plot(n, [r[key] for r in rows], "o-", label=label)
    slope = np.polyfit(n, [r["cpu"] for r in rows], 1)
    ax.plot(n, np.polyval(slope, n), "k:", lw=0.8, label=f"CPU time, linear fit: {1e3 * slope[0]:.2f} ms per interval")
    ax.set_xlabel("N (grid intervals)")
    ax.set_ylabel("run time (s), median")
    ax.set_title(f"Talos ladder climb ({contact_changes()} contact changes): run time against N")
    ax.legend(fontsize=8)
    out.parent.mkdir(exist_ok=True)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)


def _verdict(r) -> str:
    """A run's verdict with the project's room: every criterion at most half its threshold."""
    ratio = r.worst_criterion[1]
    return "fell" if r.fell else ("executed, with room" if ratio <= 0.5 else ("executed" if r.executed else "off plan"))


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100, help="N, grid intervals (default 100)")
    ap.add_argument("--repeat", type=int, default=5, help="timed runs per N (median and worst; default 5)")
    ap.add_argument("--sweep", action="store_true", help="run time against N = 50..800, plotted")
    ap.add_argument("--sim", action="store_true", help="execute in MuJoCo (pathpace.sim with the rungs)")
    ap.add_argument("--sim-grid", type=int, default=SIM_GRID,
                    help=f"N of the timing that is executed (default {SIM_GRID}; see SIM_GRID)")
    ap.add_argument("--min-normal-force", type=float, default=SIM_MIN_NORMAL_FORCE,
                    help=f"N per point of the executed timing (default {SIM_MIN_NORMAL_FORCE})")
    ap.add_argument("--contact-timeconst", type=float, default=CONTACT_TIMECONST,
                    help=f"MuJoCo's contact time constant in s (default {CONTACT_TIMECONST}, see CONTACT_TIMECONST; the "
                         "simulator's own default is 0.005)")
    ap.add_argument("--feedforward-friction-margin", type=float, default=FEEDFORWARD_FRICTION_MARGIN,
                    help=f"the feed-forward's cones are mu (1 - this) (default {FEEDFORWARD_FRICTION_MARGIN}, the plan's; 0: "
                         "the physical cones)")
    ap.add_argument("--seeds", type=int, default=0,
                    help="also run the executed timing this many times with seeded feed-forward torque noise (--torque-noise)")
    ap.add_argument("--torque-noise", type=float, default=1.0, help="N·m, std of the noise of --seeds (default 1)")
    ap.add_argument("--report", default=str(Path(__file__).resolve().parent / "output" / "humanoid_ladder.html"),
                    help="the N = --grid timing's HTML report, with each limb's centre of pressure in its support "
                         "polygon (default examples/output/humanoid_ladder.html; '' for none)")
    args = ap.parse_args(argv)

    robot = talos_sway.load_talos()
    t0 = time.perf_counter()
    path = climb_path(robot)
    ph = phases()
    mean_contacts = np.mean([len(p[2]) for p in ph])
    print(f"Talos, nq = {robot.nq}; ladder path: {RUNGS} rungs, {CYCLES} rungs climbed, {contact_changes()} contact "
          f"changes, {len(ph)} phases, {mean_contacts:.1f} contacts per phase on average; IK built in "
          f"{time.perf_counter() - t0:.1f} s")
    runs, cpu = [], []
    for _ in range(args.repeat):
        c0 = time.process_time()
        runs.append(timing(robot, path, args.grid, **MARGINS))
        cpu.append(time.process_time() - c0)
    prob, res = runs[0][0], runs[0][1]
    total = np.array([r[2] + r[3] for r in runs])
    print(f"timing (torque limits, contacts, margins {MARGINS}): {res.status.name}, T = {res.duration:.4f} s at N = "
          f"{prob.grid.size - 1}; add_contact_phases + solve median {1e3 * np.median(total):.0f} ms, worst "
          f"{1e3 * total.max():.0f} ms over {args.repeat} runs (projection {1e3 * np.median([r[2] for r in runs]):.0f} ms, "
          f"solve {1e3 * np.median([r[3] for r in runs]):.1f} ms); CPU time median {1e3 * np.median(cpu):.0f} ms, "
          f"worst {1e3 * np.max(cpu):.0f} ms")
    out = {"path": path, "robot": robot, "problem": prob, "result": res, "plan_times": total, "plan_cpu": np.array(cpu)}
    if not res.ok:
        print(res.message)
        return out
    talos_sway.write_report(prob, res, args.report)
    rest = [c.label for c in prob.constraints if isinstance(c, pp.ContactConstraint) and c.rest_at_begin]
    print(f"no-impact rule: sdot = 0 at {len(rest)} makes")
    if args.sweep:
        print("| N | status | T (s) | projection (ms) | solve (ms) | total, median (ms) | total, worst (ms) | CPU, median (ms) |")
        print("|---:|---|---:|---:|---:|---:|---:|---:|")
        out["sweep"] = run_time_sweep(robot, path, repeat=args.repeat)
        png = Path(__file__).resolve().parent / "output" / "humanoid_ladder.png"
        plot_sweep(out["sweep"], png)
        print(f"wrote {png}")
    if args.sim:
        sim = simulator(robot, path, contact_timeconst=args.contact_timeconst)
        options = dict(MARGINS, min_normal_force=args.min_normal_force, torque_scale=TORQUE_SCALE)
        executed = timing(robot, path, args.sim_grid, **options)[1]
        rows = [("N = 100, margins of the timing above", res.trajectory() if res.ok else None),
                (f"N = {args.sim_grid}, {args.min_normal_force:g} N per point, motors {TORQUE_SCALE} x",
                 executed.trajectory() if executed.ok else None)]
        # The paper's comparisons: a contact-unaware optimum (URDF velocity limits, 10 rad/s²) and the path at
        # a constant speed in the executed timing's T (its feed-forward: each phase's contacts, no margins).
        kinematic = talos_sway.kinematic_timing(robot, path, phase_grid(args.sim_grid))
        rows.append((f"N = {args.sim_grid}, velocity + acceleration limits only", kinematic.trajectory() if kinematic.ok else None))
        if executed.ok:
            rows.append(("uniform, T of the executed timing",
                         talos_sway.uniform_timing(path, args.sim_grid, executed.duration)))
        print(f"{'timing (executed in MuJoCo)':48s} {'T (s)':>7s}  {'verdict':20s} worst criterion / threshold")
        out["sim"] = []
        run = dict(phases=ph, feedforward_friction_margin=args.feedforward_friction_margin)
        for name, traj in rows:
            if traj is None:
                print(f"{name:48s} {'-':>7s}  no timing")
                continue
            r = sim.run(traj, **run)
            crit, ratio = r.worst_criterion
            print(f"{name:48s} {traj.duration:7.3f}  {_verdict(r):20s} {crit} {ratio:.2f}   ({r.summary()})", flush=True)
            out["sim"].append({"timing": name, "T": traj.duration, "verdict": _verdict(r), "worst": (crit, ratio), "sim": r})
        if args.seeds and executed.ok:
            worst = []
            for seed in range(args.seeds):
                r = sim.run(executed.trajectory(), torque_noise=args.torque_noise, seed=seed, **run)
                worst.append(r.worst_criterion[1])
                print(f"  seed {seed}, torque noise {args.torque_noise:g} N·m: {_verdict(r)}, {r.worst_criterion[0]} "
                      f"{r.worst_criterion[1]:.2f}   ({r.summary()})", flush=True)
            print(f"  worst criterion / threshold over {args.seeds} seeds: median {np.median(worst):.2f}, worst {np.max(worst):.2f}")
            out["seeds"] = worst
    return out


if __name__ == "__main__":
    main()
