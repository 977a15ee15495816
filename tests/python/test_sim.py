"""pathpace.sim: the MuJoCo model against our dynamics, its validation, and the paper's fig. 1 in short.

Skipped without MuJoCo (the optional extra `sim`). The Talos runs simulate about 10 s in all.
"""

import math
import runpy
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from pathpace.robots import example_robot_urdf

mujoco = pytest.importorskip("mujoco")
from pathpace.sim import Box, Simulator, contact_configurations, find_executable_margin, resolve_mesh  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
# Torque and contact rows take the CPU's widest SIMD path: every width this CPU runs, each test.
pytestmark = pytest.mark.usefixtures("each_torque_width")
PANDA = "panda_description/urdf/panda.urdf"
# Locked at values that are not zero: a prismatic finger and a revolute joint are welded where they are (the
# second finger mimics the first: locked with it, it must agree with the relation).
PANDA_LOCKED = {"panda_finger_joint1": 0.02, "panda_finger_joint2": 0.02, "panda_joint3": 0.4}


def test_import_pathpace_does_not_import_mujoco():
    code = "import sys, pathpace, pathpace.sim; assert 'mujoco' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)
    # Without MuJoCo, building a Simulator says what to install.
    code = ("import sys; sys.modules['mujoco'] = None\n"
            "import pathpace.sim\n"
            "try:\n    pathpace.sim.Simulator(None, '')\nexcept ImportError as e:\n    print(e)")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    assert "pip install 'pathpace[sim]' (mujoco==3.3.7)" in out


def mj_inverse(sim, q, qd, qdd):
    """MuJoCo's inverse dynamics at our state, for a fixed base or a floating base at rest in rotation
    (base angular velocity and acceleration zero, where Euler rates and body rates coincide)."""
    m, d = sim.model, sim.data
    sim.set_configuration(q)  # at rest; qacc is left from mj_forward
    d.qacc[:] = 0.0
    if sim.floating:
        d.qvel[:3], d.qacc[:3] = qd[:3], qdd[:3]
    d.qvel[sim.dof_index] = qd[sim.actuated]
    d.qacc[sim.dof_index] = qdd[sim.actuated]
    flags = m.opt.disableflags
    m.opt.disableflags = flags | mujoco.mjtDisableBit.mjDSBL_CONSTRAINT  # no joint-limit or floor forces
    try:
        mujoco.mj_inverse(m, d)
    finally:
        m.opt.disableflags = flags
    return d.qfrc_inverse.copy()


def test_fixed_base_model_with_locked_joints_matches_our_dynamics():
    urdf = example_robot_urdf(PANDA)
    robot = pp.RobotModel.from_urdf(str(urdf), locked_joints=PANDA_LOCKED)
    sim = Simulator(robot, urdf, locked_joints=PANDA_LOCKED)
    assert not sim.floating and sim.model.nq == robot.nq == 6
    rng = np.random.default_rng(3)
    for _ in range(5):
        q, qd, qdd = rng.uniform(-1, 1, (3, robot.nq))
        tau = mj_inverse(sim, q, qd, qdd)
        ours = robot.inverse_dynamics(q, qd, qdd)
        assert np.max(np.abs(tau[sim.dof_index] - ours[sim.actuated])) < 1e-6 * max(1.0, np.max(np.abs(ours)))
        M = np.zeros((sim.model.nv, sim.model.nv))
        mujoco.mj_fullM(sim.model, M, sim.data.qM)
        assert np.allclose(M, robot.mass_matrix(q), rtol=0, atol=1e-6)
        X = robot.frame_placement(q, "panda_hand")
        b = sim.model.body("panda_hand").id
        assert np.allclose(sim.data.xpos[b], X[:3, 3], atol=1e-9)
        assert np.allclose(sim.data.xmat[b].reshape(3, 3), X[:3, :3], atol=1e-9)


@pytest.fixture(scope="module")
def sway():
    """Talos, its feet-fixed sway path and sole contacts (examples/talos_sway.py), and the simulator."""
    ns = runpy.run_path(str(EXAMPLES / "humanoid_sim.py"))
    ts = ns["talos_sway"]
    robot = ts.load_talos()
    path = ts.sway_path(robot)
    contacts = ts.sole_contacts(4)
    sim = ns["talos_simulator"](robot, path, contacts)
    return {"ns": ns, "robot": robot, "path": path, "contacts": contacts, "sim": sim}


def test_floating_base_model_matches_our_dynamics(sway):
    sim, robot = sway["sim"], sway["robot"]
    assert sim.floating and sim.model.nq == robot.nq + 1  # quaternion
    rng = np.random.default_rng(4)
    q_stand = sway["path"].q(0.0)
    for _ in range(4):
        q = q_stand + rng.uniform(-0.3, 0.3, robot.nq)
        q[2] += 1.0  # in the air
        qd, qdd = rng.uniform(-1, 1, (2, robot.nq))
        qd[3:6] = qdd[3:6] = 0.0
        tau = mj_inverse(sim, q, qd, qdd)
        ours = robot.inverse_dynamics(q, qd, qdd)
        scale = np.max(np.abs(ours))
        assert np.max(np.abs(tau[sim.dof_index] - ours[sim.actuated])) < 1e-6 * scale
        assert np.max(np.abs(tau[:3] - ours[:3])) < 1e-6 * scale  # the base force, world frame in both
        for link in ("left_sole_link", "head_2_link", "gripper_right_base_link"):
            X = robot.frame_placement(q, link)
            assert np.allclose(sim.data.xpos[sim.model.body(link).id], X[:3, 3], atol=1e-9)


def test_contacts_become_spheres_with_their_friction(sway):
    sim, contacts = sway["sim"], sway["contacts"]
    for k, c in enumerate(contacts):
        g = sim.model.geom(f"pathpace_contact_{k}")
        assert g.type[0] == mujoco.mjtGeom.mjGEOM_SPHERE and g.friction[0] == c.friction
    # Only the spheres touch the floor: 1 mm into it, there are contacts at the 8 spheres and nowhere else.
    q = sway["path"].q(0.0)
    q[2] -= 1e-3
    sim.set_configuration(q)
    pairs = {tuple(sorted(sim.model.geom(g).name for g in sim.data.contact.geom[i])) for i in range(sim.data.ncon)}
    assert pairs == {("floor", f"pathpace_contact_{k}") for k in range(len(contacts))}


def _panda_on_a_box(**options):
    """Panda (fixed base) at q = 0 with its hand's origin on the top of a box (a rung) under it."""
    urdf = example_robot_urdf(PANDA)
    robot = pp.RobotModel.from_urdf(str(urdf), locked_joints=PANDA_LOCKED)
    q = np.zeros(robot.nq)
    p = robot.frame_placement(q, "panda_hand")[:3, 3]
    rung = Box(centre=(p[0], p[1], p[2] - 0.015), half_size=(0.03, 0.4, 0.015), name="rung")
    return robot, urdf, q, p, rung


def test_contacts_on_boxes_touch_the_face_with_their_normal():
    robot, urdf, q, p, rung = _panda_on_a_box()
    top = pp.Contact("panda_hand", normal=(0, 0, 1), friction=0.7)
    sim = Simulator(robot, urdf, [top], q, locked_joints=PANDA_LOCKED, surfaces=[rung], impratio=10.0)
    assert sim.contact_surfaces == ["rung"] and sim.model.opt.impratio == 10.0
    g = sim.model.geom("rung")
    assert g.type[0] == mujoco.mjtGeom.mjGEOM_BOX and np.allclose(g.size, rung.half_size) and g.friction[0] == 0.7
    # The rung 1 mm higher: the sphere touches it, and nothing else touches anything.
    sim.model.geom_pos[g.id][2] += 1e-3
    sim.set_configuration(q)
    pairs = {tuple(sorted(sim.model.geom(i).name for i in sim.data.contact.geom[k])) for k in range(sim.data.ncon)}
    assert pairs == {("pathpace_contact_0", "rung")}
    # A contact on the rung's far side pushes along +x (a hand that hooks the rung), on its top along +z.
    side = Box(centre=(p[0] - 0.03, p[1], p[2]), half_size=(0.03, 0.4, 0.015), name="far_side")
    hook = pp.Contact("panda_hand", normal=(1, 0, 0))
    sim = Simulator(robot, urdf, [hook], q, locked_joints=PANDA_LOCKED, surfaces=[side])
    assert sim.contact_surfaces == ["far_side"]
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\] \('panda_hand', normal \(0, 1, 0\)\) is at .* on no surface "
                       r"with that normal .*'far_side'"):
        Simulator(robot, urdf, [pp.Contact("panda_hand", normal=(0, 1, 0))], q, locked_joints=PANDA_LOCKED, surfaces=[side])
    # Off the face's extent (the box moved 5 cm along y past its half width): no surface.
    away = Box(centre=(p[0], p[1] + 0.45, p[2] - 0.015), half_size=(0.03, 0.4, 0.015))
    with pytest.raises(pp.InvalidInputError, match="on no surface with that normal"):
        Simulator(robot, urdf, [top], q, locked_joints=PANDA_LOCKED, surfaces=[away])


def test_ball_links_hold_a_surface_with_their_point_at_the_centre():
    robot, urdf, q, p, rung = _panda_on_a_box()
    low = Box(centre=rung.centre - np.array([0, 0, 0.005]), half_size=rung.half_size, name="rung")
    fist = pp.Contact("panda_hand", normal=(0, 0, 1))
    with pytest.raises(pp.InvalidInputError, match="on no surface"):  # 5 mm above the rung: not on it
        Simulator(robot, urdf, [fist], q, locked_joints=PANDA_LOCKED, surfaces=[low])
    sim = Simulator(robot, urdf, [fist], q, locked_joints=PANDA_LOCKED, surfaces=[low], ball_links=["panda_hand"])
    assert sim.contact_surfaces == ["rung"]
    sim.set_configuration(q)
    centre = sim.data.geom_xpos[sim.model.geom("pathpace_contact_0").id]
    assert np.allclose(centre, p, atol=1e-12)  # the sphere is centred on the contact point
    with pytest.raises(pp.InvalidInputError, match="ball_links: 'fist' is not a link of the robot"):
        Simulator(robot, urdf, [fist], q, locked_joints=PANDA_LOCKED, surfaces=[low], ball_links=["fist"])


def test_a_ball_gripping_a_rung_is_one_sphere_on_three_faces():
    # A hand's ball on a rung top between two ridges (a grip): contacts with normals +z, +x (the ridge behind
    # it, whose face looks along +x) and -x (the ridge in front, its face looking along -x). Every face of a
    # box is where it is: the -x face of the front ridge is at its centre - half size (it once was at + half).
    robot, urdf, q, p, rung = _panda_on_a_box()
    r = 0.005
    low = Box(centre=rung.centre - np.array([0, 0, r]), half_size=rung.half_size, name="rung")
    top_z = p[2] - r
    behind = Box(centre=(p[0] - r - 0.0025, p[1], top_z + r / 2), half_size=(0.0025, 0.04, r / 2), name="behind")
    front = Box(centre=(p[0] + r + 0.0025, p[1], top_z + r / 2), half_size=(0.0025, 0.04, r / 2), name="front")
    grip = [pp.Contact("panda_hand", normal=n) for n in ((0, 0, 1), (1, 0, 0), (-1, 0, 0))]
    sim = Simulator(robot, urdf, grip, q, locked_joints=PANDA_LOCKED, surfaces=[low, behind, front], ball_links=["panda_hand"])
    assert sim.contact_surfaces == ["rung", "behind", "front"]
    spheres = [sim.model.geom(i).name for i in range(sim.model.ngeom) if sim.model.geom(i).name.startswith("pathpace_contact_")]
    assert spheres == ["pathpace_contact_0"]  # one ball, not three in the same place
    assert np.allclose(sim.contact_positions(), p, atol=1e-12)  # each contact's site at the ball's centre
    # The rung 1 mm higher and each ridge 1 mm closer: the ball touches all three, nothing else touches.
    sim.model.geom_pos[sim.model.geom("rung").id][2] += 1e-3
    sim.model.geom_pos[sim.model.geom("behind").id] += [1e-3, 0.0, 1e-3]
    sim.model.geom_pos[sim.model.geom("front").id] += [-1e-3, 0.0, 1e-3]
    sim.set_configuration(q)
    pairs = {tuple(sorted(sim.model.geom(i).name for i in sim.data.contact.geom[k])) for k in range(sim.data.ncon)}
    assert pairs == {("pathpace_contact_0", "rung"), ("behind", "pathpace_contact_0"), ("front", "pathpace_contact_0")}
    # The -x contact 2 mm in front of the front ridge's face: on no surface (the face is where the box is).
    far = Box(centre=(p[0] + r + 0.002 + 0.0025, p[1], top_z + r / 2), half_size=(0.0025, 0.04, r / 2), name="front")
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[2\] .* on no surface with that normal"):
        Simulator(robot, urdf, grip, q, locked_joints=PANDA_LOCKED, surfaces=[low, behind, far], ball_links=["panda_hand"])


def test_contact_configurations_place_each_contact_where_its_first_phase_makes_it():
    robot, urdf, q, p, rung = _panda_on_a_box()
    q1 = q.copy()
    q1[0] = 0.3  # the hand elsewhere: the contact of phase 1 is made there
    p1 = robot.frame_placement(q1, "panda_hand")[:3, 3]
    assert np.linalg.norm(p1[:2] - p[:2]) > 0.02
    rung = Box(centre=rung.centre, half_size=(0.01, 0.01, 0.015), name="rung")
    other = Box(centre=(p1[0], p1[1], p1[2] - 0.015), half_size=(0.01, 0.01, 0.015), name="other")
    path = pp.CubicSplinePath(np.array([q, q1, q1]), knots=[0.0, 1.0, 2.0])
    a = pp.Contact("panda_hand", point=(0.0, 0.0, 0.0))
    b = pp.Contact("panda_hand", point=(0.0, 0.0, 0.0001))
    phases = [(0.0, 1.0, [a]), (1.0, 2.0, [b])]
    configs = contact_configurations(path, phases, [a, b])
    assert np.allclose(configs[0], q) and np.allclose(configs[1], q1)
    sim = Simulator(robot, urdf, [a, b], q, locked_joints=PANDA_LOCKED, surfaces=[rung, other], contact_configurations=configs)
    assert sim.contact_surfaces == ["rung", "other"]
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[1\] \('panda_hand' at .*\) is in no phase"):
        contact_configurations(path, phases[:1], [a, b])
    with pytest.raises(pp.InvalidInputError, match=r"contact_configurations has 1 configurations, expected one per contact \(2\)"):
        Simulator(robot, urdf, [a, b], q, locked_joints=PANDA_LOCKED, surfaces=[rung, other], contact_configurations=configs[:1])


def test_surface_validation_names_the_argument():
    robot, urdf, q, p, rung = _panda_on_a_box()
    cases = [(dict(surfaces=[Box((0, 0, 0), (0.1, 0.0, 0.1))]), r"surfaces\[0\].half_size = .* must be 3 finite numbers > 0"),
             (dict(surfaces=[Box((0, 0, math.nan), (0.1, 0.1, 0.1))]), r"surfaces\[0\].centre = .* must be 3 finite numbers"),
             (dict(surfaces=[Box((0, 0, 0), (0.1, 0.1, 0.1), name="floor")]), r"surfaces\[0\].name = 'floor' is not unique"),
             (dict(surfaces=[Box((0, 0, 0), (0.1, 0.1, 0.1), friction=0.0)]), r"surfaces\[0\].friction = 0.0 must be > 0"),
             (dict(surfaces=["rung"]), r"surfaces\[0\]: expected a pathpace.sim.Box, got str"),
             (dict(impratio=0.5), r"impratio = 0.5 must be >= 1")]
    for options, message in cases:
        with pytest.raises(pp.InvalidInputError, match=message):
            Simulator(robot, urdf, locked_joints=PANDA_LOCKED, **options)


def test_validation_names_the_argument():
    urdf = example_robot_urdf(PANDA)
    robot = pp.RobotModel.from_urdf(str(urdf), locked_joints=PANDA_LOCKED)
    with pytest.raises(pp.InvalidInputError, match="locked_joints: URDF joint 'panda_finger_joint1' is not in the robot model"):
        Simulator(robot, urdf, locked_joints={"panda_joint3": 0.4})
    with pytest.raises(pp.InvalidInputError, match=r"timestep = 0 must be > 0"):
        Simulator(robot, urdf, locked_joints=PANDA_LOCKED, timestep=0)
    with pytest.raises(pp.InvalidInputError, match=r"contact_timeconst = 0.001 must be >= 2 timestep = 0.002"):
        Simulator(robot, urdf, locked_joints=PANDA_LOCKED, contact_timeconst=0.001)
    q = np.zeros(robot.nq)
    z = robot.frame_placement(q, "panda_hand")[2, 3]
    floor = pp.Contact("panda_hand", normal=(0, 0, 1))
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\] \('panda_hand'\) is at z = .* expected on the floor"):
        Simulator(robot, urdf, [floor], q, locked_joints=PANDA_LOCKED)
    wall = pp.Contact("panda_hand", normal=(1, 0, 0))
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\].normal = \(1, 0, 0\) must be \(0, 0, 1\)"):
        Simulator(robot, urdf, [wall], q, locked_joints=PANDA_LOCKED, floor_height=z)
    link = pp.Contact("panda_hand", other_link="panda_link0")
    with pytest.raises(pp.InvalidInputError, match=r"contacts\[0\]: link-to-link contacts"):
        Simulator(robot, urdf, [link], q, locked_joints=PANDA_LOCKED, floor_height=z)
    with pytest.raises(pp.InvalidInputError, match="kp\\[0\\] must be > 0"):
        Simulator(robot, urdf, locked_joints=PANDA_LOCKED, kp=0.0)
    with pytest.raises(pp.InvalidInputError, match=r"effort_limits has shape \(2,\), expected \(6,\)"):
        Simulator(robot, urdf, locked_joints=PANDA_LOCKED, effort_limits=np.ones(2))
    with pytest.raises(pp.InvalidInputError, match=r"effort_limits\[3\] = nan must be >= 0"):
        Simulator(robot, urdf, locked_joints=PANDA_LOCKED, effort_limits=[1, 1, 1, np.nan, 1, 1])
    weak = Simulator(robot, urdf, locked_joints=PANDA_LOCKED, effort_limits=0.5 * robot.effort_limits)
    assert np.allclose(weak.model.actuator_forcerange[:, 1], 0.5 * robot.effort_limits[weak.actuated], rtol=1e-12)
    sim = Simulator(robot, urdf, locked_joints=PANDA_LOCKED)
    traj = pp.Trajectory(pp.CubicSplinePath(np.zeros((2, robot.nq))), [0.0, 1.0], [1.0, 1.0])
    with pytest.raises(pp.InvalidInputError, match=r"criteria\['slide'\]: unknown; the criteria are \['landing', 'lift', 'slip'"):
        sim.run(traj, criteria={"slide": 0.01})
    with pytest.raises(pp.InvalidInputError, match="hold = -1 must be >= 0"):
        sim.run(traj, hold=-1)
    with pytest.raises(pp.InvalidInputError, match="record_dt = 0 must be > 0"):
        sim.run(traj, record_dt=0)
    with pytest.raises(pp.InvalidInputError, match="feedforward = 'pd' must be 'auto', 'contact'"):
        sim.run(traj, feedforward="pd")


def test_panda_tracks_a_torque_limited_optimum_with_margin_and_not_one_without():
    urdf = example_robot_urdf(PANDA)
    robot = pp.RobotModel.from_urdf(str(urdf), locked_joints=PANDA_LOCKED)
    rng = np.random.default_rng(0)
    lo, hi = robot.position_limits
    path = pp.CubicSplinePath(lo + (hi - lo) * rng.uniform(0.2, 0.8, (4, robot.nq)))
    sim = Simulator(robot, urdf, locked_joints=PANDA_LOCKED)
    runs = {}
    for scale in (0.8, 1.0):
        prob = pp.TimeScalingProblem(path, grid=200)
        prob.add_torque_limits(robot, scale=scale)
        res = prob.solve()
        assert res.ok
        runs[scale] = [sim.run(res.trajectory(), feedforward=ff, settle=0.2, hold=0.2) for ff in ("auto", "none")]
    with_ff, without = runs[0.8]
    assert with_ff.feedforward == "inverse_dynamics" and without.feedforward == "none"
    # PD alone lags under gravity and the motion; with our model's torques the error is 20x smaller.
    assert with_ff.max_tracking_error < 2e-3 and with_ff.max_tracking_error < 0.05 * without.max_tracking_error
    # At 100 % of the effort limits the motors have nothing left to correct with: the shoulder sags onto its
    # joint limit.
    assert runs[1.0][0].max_tracking_error > 0.5 and runs[1.0][0].torque_saturation > 0.1


def timing(sway, min_normal_force=0.0, friction_margin=0.0):
    return sway["ns"]["contact_timing"](sway["robot"], sway["path"], sway["contacts"], 100, min_normal_force,
                                        friction_margin).trajectory()


def test_talos_sway_zero_margin_optimum_and_uniform_timing_fall_the_margin_optimum_executes(sway):
    """Verdicts with room. The zero-margin optimum and the uniform timing at its T fall, and 10 % slower
    they still do not execute with room: a fall or a criterion at least twice its threshold (bench/README.md,
    "Issue 21: the room of the simulator's verdicts"). That check, not the stand-up's (a fall again with the
    fall thresholds doubled), because 10 % slower the uniform timing tips a sole onto its edge without
    falling. The margin optimum executes with every criterion at most half its threshold; the velocity and
    acceleration optimum slides and lifts a sole more than twice the 5 mm criteria."""
    sim = sway["sim"]
    bare_res = sway["ns"]["contact_timing"](sway["robot"], sway["path"], sway["contacts"], 100, 0.0, 0.0)
    bare = sim.run(bare_res.trajectory())
    assert bare.fell and bare.fall_time < bare.duration + 1.0
    slow = sim.run(sway["ns"]["talos_sway"].stretched(sway["path"], bare_res, 1.1))
    assert slow.duration == pytest.approx(1.1 * bare.duration, rel=1e-9)
    assert slow.fell or slow.worst_criterion[1] >= 2.0, slow.summary()
    # Margins where the verdict has room (every criterion at no more than half its threshold): at 20 N and
    # 0.5 the slip sat at the 5 mm criterion, and another CPU or MuJoCo build flipped it.
    safe_traj = timing(sway, 50.0, 0.7)
    safe = sim.run(safe_traj)
    assert safe.feedforward == "contact" and not safe.fell
    assert max(safe.criterion_ratios.values()) <= 0.5, (safe.summary(), safe.criterion_ratios)
    assert safe.duration > bare.duration
    # As fast as the zero-margin optimum at a constant rate: the abrupt start and stop throw it over.
    uniform = sim.run(sway["ns"]["uniform"](sway["path"], 100, bare.duration))
    assert uniform.fell
    slow = sim.run(sway["ns"]["uniform"](sway["path"], 100, 1.1 * bare.duration))
    assert slow.fell or slow.worst_criterion[1] >= 2.0, slow.summary()
    # The optimum under joint velocity and acceleration limits only: a sole pivots on its edge and slides.
    kin = sim.run(sway["ns"]["kinematic_timing"](sway["robot"], sway["path"], 100).trajectory())
    assert kin.duration < bare.duration and not kin.executed
    assert kin.max_lift > 0.01 and kin.max_slip > 0.01  # both at least twice the 5 mm criteria (measured: 4.8 x, 6.3 x)
    # Deterministic: the same run again gives the same numbers, bit for bit.
    again = sim.run(safe_traj)
    assert np.array_equal(again.base_height, safe.base_height) and np.array_equal(again.slip, safe.slip)


class DurationVerdict:
    """What find_executable_margin reads of a simulation: executed, and a summary for its table."""

    def __init__(self, duration, executed):
        self.duration, self.executed, self.fell = duration, executed, False
        self.worst_criterion = ("stand-in", 0.0 if executed else 2.0)

    def summary(self):
        return f"T = {self.duration:.3f} s: {'executes' if self.executed else 'fell'} (stand-in)"


class StandInSimulator:
    """The Talos simulator's robot and contacts, with a verdict by the timing's duration (executes from t_min
    on): executability monotone in the margin, which is all the bisection assumes. The search's logic is
    tested on it; physical verdicts only where they have room (the sway test). A real simulation at 20 N sat
    on its 5 mm slip criterion, and the bisection's last trial flipped with the CPU."""

    def __init__(self, sim, t_min):
        self.robot, self.contacts, self.t_min = sim.robot, sim.contacts, t_min

    def run(self, traj, **options):
        return DurationVerdict(traj.duration, traj.duration >= self.t_min)


def test_find_executable_margin_bisects_on_the_minimum_normal_force(sway):
    # 90 N per contact leaves no timing (the unloaded foot cannot push that hard): the upper bound
    # is halved towards 10 N: 50 N, then the bracket [10, 50] is bisected to within 10 N. The stand-in
    # executes from T = 2.1 s on: between the optima at 20 N (2.03 s) and 30 N (2.25 s), 3 % from each.
    stand_in = StandInSimulator(sway["sim"], 2.1)
    out = find_executable_margin(stand_in, sway["path"], lower=10.0, upper=90.0, tolerance=10.0, friction_margin=0.5)
    assert [t.min_normal_force for t in out.trials] == [10.0, 90.0, 50.0, 30.0, 20.0]
    # No timing at 90 N. Since the exact projection (issue 9) the solver says NUMERICAL_ERROR there rather
    # than INFEASIBLE: the polygon at s = 0.25 comes out empty while one LP on the full polytope finds a
    # point (a sliver of a set; see the note on issue 9). Either way the search must treat it as no timing.
    assert out.trials[1].status in ("INFEASIBLE", "NUMERICAL_ERROR")
    assert out.trials[1].sim is None and math.isnan(out.trials[1].duration)
    assert [t.executed for t in out.trials] == [False, False, True, True, False]
    assert out.margin == 30.0 and out.parameter == "min_normal_force"
    assert out.duration == out.trials[3].duration and out.zero_margin_duration == out.trials[0].duration
    assert out.cost == pytest.approx(out.duration / out.zero_margin_duration - 1.0, rel=1e-12)
    assert "yes" in out.table() and "fell" in out.table()
    with pytest.raises(pp.InvalidInputError, match="parameter = 'mu' must be"):
        find_executable_margin(sway["sim"], sway["path"], parameter="mu")
    with pytest.raises(pp.InvalidInputError, match="upper = 1.5 must be < 1 for the friction margin"):
        find_executable_margin(sway["sim"], sway["path"], parameter="friction_margin", upper=1.5)


class RatioVerdict(DurationVerdict):
    """Stands, with its worst criterion at a fixed share of its threshold."""

    def __init__(self, duration, ratio):
        super().__init__(duration, ratio <= 1.0)
        self.worst_criterion = ("slip", ratio)


class RecordingStandIn(StandInSimulator):
    def __init__(self, sim, ratio):
        super().__init__(sim, 0.0)
        self.ratio, self.options = ratio, []

    def run(self, traj, **options):
        self.options.append(options)
        return RatioVerdict(traj.duration, self.ratio)


def test_find_executable_margin_wants_room_and_takes_phases(sway):
    # A run at 0.7 of a threshold is executed, but without room: the default search (room 0.5) finds
    # no margin, room = 1 accepts the lower bound.
    stand_in = RecordingStandIn(sway["sim"], 0.7)
    assert find_executable_margin(stand_in, sway["path"], lower=10.0, upper=20.0, tolerance=10.0).margin is None
    assert find_executable_margin(stand_in, sway["path"], lower=10.0, upper=20.0, room=1.0).margin == 10.0
    # Phases: the problems come from add_contact_phases and every run measures against them.
    contacts = sway["contacts"]
    left = [c for c in contacts if c.link == "left_sole_link"]
    phases = [(0.0, 0.5, contacts), (0.5, 1.0, contacts, {"min_normal_force": 5.0})]
    stand_in.options.clear()
    out = find_executable_margin(stand_in, sway["path"], phases=phases, lower=10.0, upper=20.0, room=1.0)
    assert out.margin == 10.0 and out.trials[0].status == "OPTIMAL"
    assert stand_in.options == [{"phases": phases}]
    # contact_options reach every problem: weaker motors, a slower optimum.
    strong = find_executable_margin(stand_in, sway["path"], lower=10.0, upper=20.0, room=1.0)
    weak = find_executable_margin(stand_in, sway["path"], lower=10.0, upper=20.0, room=1.0,
                                  contact_options={"torque_scale": 0.2})
    assert weak.margin == strong.margin == 10.0 and weak.duration > strong.duration * 1.01
    for bad, match in ((dict(room=0.0), r"room = 0.0 must be in \(0, 1\]"), (dict(room=1.5), "room = 1.5"),
                       (dict(contact_options={"min_normal_force": 1.0}), r"contact_options\['min_normal_force'\]"),
                       (dict(phases=phases, contacts=left), "give one")):
        with pytest.raises(pp.InvalidInputError, match=match):
            find_executable_margin(stand_in, sway["path"], **bad)


def test_run_with_phases_measures_held_points_against_the_plan(sway):
    sim, contacts = sway["sim"], sway["contacts"]
    traj = timing(sway, 50.0, 0.7)
    plain = sim.run(traj)
    # The same contacts in every phase: the feet are planned still, so the measure is the same to the
    # IK's few micrometres.
    same = sim.run(traj, phases=[(0.0, 0.5, contacts), (0.5, 1.0, contacts)])
    assert abs(same.max_slip - plain.max_slip) < 1e-4 and abs(same.max_lift - plain.max_lift) < 1e-4
    # Only the left sole held after s = 0.5: the right sole's points are not measured there.
    left = [c for c in contacts if c.link == "left_sole_link"]
    part = sim.run(traj, phases=[(0.0, 0.5, contacts), (0.5, 1.0, left)])
    s = traj.s(np.minimum(part.times, traj.duration))[0]
    right = np.array([c.link == "right_sole_link" for c in contacts])
    assert np.all(np.isnan(part.slip[np.ix_(s > 0.5, right)])) and np.all(np.isfinite(part.slip[:, ~right]))
    assert np.all(np.isfinite(part.slip[np.ix_(s < 0.5, right)]))
    with pytest.raises(pp.InvalidInputError, match=r"phases\[0\]: contact on 'left_sole_link'"):
        sim.run(traj, phases=[(0.0, 1.0, [pp.Contact("left_sole_link", (0.3, 0.0, 0.0), (0, 0, 1), 0.5)])])
    # Held from the start, so nothing landed: no landing error, and the slip counts from the first sample.
    assert same.landing.shape == (len(contacts),) and same.max_landing_error == 0.0
    assert "landing" in same.criterion_ratios and plain.criterion_ratios["landing"] == 0.0


def test_feedforward_in_narrowed_cones_and_by_phase_for_a_timing_without_contacts(sway):
    """friction_margin: the centre of the cones of μ (1 - margin), with the physical torque limits; phases: a
    timing without contacts of its own is fed forward with each phase's contacts, not all of them."""
    sim, robot, contacts = sway["sim"], sway["robot"], sway["contacts"]
    traj = timing(sway, 20.0, 0.5)
    t = np.linspace(0.0, traj.duration, 7)
    wide, _ = sim.feedforward(traj, t)
    narrow, mode = sim.feedforward(traj, t, friction_margin=0.5)
    half = [pp.Contact(c.link, c.point, c.normal, 0.5 * c.friction) for c in contacts]
    own = traj.contacts
    cf = pp.ContactConstraint(robot, half, cone_edges=8, tau_min=own.physical_tau_min,
                              tau_max=own.physical_tau_max).force_distribution(*traj.evaluate(t))
    assert mode == "contact" and np.all(cf.centred)
    np.testing.assert_array_equal(narrow, cf.torques)
    # Without a friction margin: the trajectory's own centred distribution (issue 21, deliver 1), not the LP's
    # vertex.
    own_forces = traj.contact_forces(t)
    assert np.all(own_forces.centred)
    np.testing.assert_array_equal(wide, own_forces.torques)
    assert np.max(np.abs(wide - traj.contact_forces(t, distribution="vertex").torques)) > 1e-2
    assert np.max(np.abs(narrow - wide)) > 1e-2  # N·m (0.15 here): another distribution of the same motion
    with pytest.raises(pp.InvalidInputError, match=r"friction_margin = 1.0 must be in \[0, 1\)"):
        sim.feedforward(traj, t, friction_margin=1.0)
    # No contacts of its own: the phase's contacts (the right sole only after s = 0.5) shape the forces.
    bare = pp.Trajectory(sway["path"], np.linspace(0.0, 1.0, 11), np.full(11, 1.0 / 3.0))
    left = [c for c in contacts if c.link == "left_sole_link"]
    right = [c for c in contacts if c.link == "right_sole_link"]
    t = np.array([0.3, 1.2, 2.4])  # s = 0.1, 0.4, 0.8
    tau, _ = sim.feedforward(bare, t, phases=[(0.0, 0.5, contacts), (0.5, 1.0, right)])
    q, qd, qdd = bare.evaluate(t)
    both = pp.ContactConstraint(robot, contacts, cone_edges=8).force_distribution(q[:2], qd[:2], qdd[:2])
    np.testing.assert_array_equal(tau[:2], both.torques)
    one = pp.ContactConstraint(robot, right, cone_edges=8).force_distribution(q[2:], qd[2:], qdd[2:])
    np.testing.assert_array_equal(tau[2:], np.where(np.atleast_1d(one.feasible)[:, None], one.torques, tau[1:2]))
    assert left  # (the left sole carries nothing after s = 0.5)


def test_slide_since_make_splits_landing_from_slide():
    from pathpace.sim import _slide_since_make
    nan = np.nan
    # One point: held, released, landed 3 mm off (x), slides 1 mm more (y), released again.
    x = np.array([[0, 0, 0], [1e-3, 0, 0], [nan] * 3, [3e-3, 0, 0], [3e-3, 1e-3, 0], [nan] * 3], dtype=float)
    out, landing = _slide_since_make(x[:, None, :])
    assert landing.tolist() == [3e-3]
    assert np.allclose(np.linalg.norm(out[[0, 1, 3, 4], 0], axis=1), [0, 1e-3, 0, 1e-3], atol=1e-15)
    assert np.all(np.isnan(out[[2, 5], 0]))


def test_visual_meshes_resolve_package_paths_and_change_no_dynamics(sway, tmp_path):
    urdf = example_robot_urdf("talos_data/robots/talos_full_v2.urdf")
    refs = {m.get("filename") for m in ET.parse(urdf).getroot().iter("mesh")}
    stl = [r for r in refs if r.lower().endswith(".stl")]
    assert stl and all(r.split("example-robot-data/robots/")[0] in ("package://", "package:///") for r in stl)
    robots = urdf.parents[2]
    assert all(resolve_mesh(r, [robots]) is not None for r in stl)
    assert resolve_mesh("package://nowhere/x.stl", [robots]) is None
    (tmp_path / "m.stl").write_text("solid x\nendsolid x\n")
    assert resolve_mesh("m.stl", [tmp_path]) == tmp_path / "m.stl"
    assert resolve_mesh(f"file://{tmp_path / 'm.stl'}", []) == tmp_path / "m.stl"
    plain = sway["sim"]
    drawn = sway["ns"]["talos_simulator"](sway["robot"], sway["path"], sway["contacts"], visual_meshes=True)
    assert drawn.model.nmesh > 30 and plain.model.nmesh == 0
    assert np.all(drawn.model.geom_contype[drawn.model.geom_group == 1] == 0)
    assert np.array_equal(drawn.model.body_mass, plain.model.body_mass)
    assert np.array_equal(drawn.model.body_inertia, plain.model.body_inertia)


def test_torque_noise_is_seeded():
    urdf = example_robot_urdf(PANDA)
    robot = pp.RobotModel.from_urdf(str(urdf), locked_joints=PANDA_LOCKED)
    path = pp.CubicSplinePath(np.array([np.full(robot.nq, 0.1), np.full(robot.nq, -0.2)]))
    traj = pp.Trajectory(path, np.linspace(0, 1, 11), np.full(11, 2.0))
    sim = Simulator(robot, urdf, locked_joints=PANDA_LOCKED)
    a, b, c = (sim.run(traj, torque_noise=1.0, seed=k, settle=0.1, hold=0.1) for k in (1, 1, 2))
    assert np.array_equal(a.tracking_error, b.tracking_error)
    assert not np.array_equal(a.tracking_error, c.tracking_error)


def test_example_quick_run_prints_the_fig1_rows(capsys):
    out = runpy.run_path(str(EXAMPLES / "humanoid_sim.py"))["main"](["--quick"])
    verdicts = {(r["timing"], r["min_normal_force"]): r["verdict"] for r in out["rows"]}
    assert verdicts == {("pathpace, contacts", 0.0): "fell", ("pathpace, contacts", 50.0): "yes",
                        ("velocity + acceleration limits only", None): "no",
                        ("uniform, 1.0 x T(zero margin)", None): "fell"}
    # The verdicts have room: "yes" with every criterion at most half its threshold (measured: 0.25), "no"
    # with one at least twice it (measured: slip 6.3; tilt 0.11 rad, a fifth of a fall's). The two falls are
    # the timings of test_talos_sway_zero_margin_..., which checks their room (10 % slower, still a fall or a
    # criterion at least twice its threshold), so they are not run again here.
    sims = {(r["timing"], r["min_normal_force"]): r["sim"] for r in out["rows"]}
    assert max(sims[("pathpace, contacts", 50.0)].criterion_ratios.values()) <= 0.5
    assert sims[("velocity + acceleration limits only", None)].worst_criterion[1] >= 2.0
    assert "| pathpace, contacts" in capsys.readouterr().out


def test_talos_two_steps_with_contact_phase_margins_executes_the_contact_unaware_timing_falls_with_room():
    """examples/humanoid_steps.py --sim, each run measured against its contact phases: the contact-phase timing
    with margins (50 % friction, SIM_MIN_NORMAL_FORCE = 55 N per point) walks its two steps with every
    criterion at most half its threshold. At the example's planning margins (10 N) it slid more than the slip
    criterion after the first touchdown, and at the smallest margin with room (find_executable_margin) it sits
    on 0.5. The optimum under joint velocity and acceleration limits only falls, and falls again when run 10 %
    slower with the fall thresholds doubled, the stand-up test's room of a fall. The zero-margin optimum is
    faster, but its fall has no room (it stands on a 4 ms floor, and 10 % slower), so no verdict on it is
    asserted. One deterministic run each; the measured ratios are in bench/README.md ("Issue 21: the room of
    the simulator's verdicts")."""
    ns = runpy.run_path(str(EXAMPLES / "humanoid_steps.py"))
    out = ns["main"](["--sim"])
    rows = {r["timing"]: r for r in out["sim"]}
    ours, bare = rows["contact phases, margins"], rows["contact phases, no margins"]
    assert ns["SIM_MIN_NORMAL_FORCE"] == 55.0
    assert not ours["fell"] and max(ours["sim"].criterion_ratios.values()) <= 0.5, ours["sim"].criterion_ratios
    assert ours["sim"].landing.shape == (8,)  # measured against the phases: the swing feet's landings too
    assert bare["T"] < ours["T"]
    kin, slow = rows["velocity + acceleration only"], rows["velocity + acceleration only, 1.1 x T"]
    assert kin["T"] < bare["T"] and kin["fell"], kin["sim"].summary()
    assert slow["T"] == pytest.approx(1.1 * kin["T"], rel=1e-9)
    assert slow["fell"] and slow["verdict"] == "fell (2 x thresholds)", slow["sim"].summary()
    # The doubled thresholds are the simulator's defaults (0.15 m, 0.5 rad) twice.
    assert ns["talos_sway"].fall_thresholds(2.0) == {"fall_height": 0.3, "fall_tilt": 1.0}


def test_the_default_contact_model_is_built_once_and_kept(sway, monkeypatch):
    """A timing without contacts of its own is fed forward with the simulator's contacts (8 cone edges, no
    margins): that ContactConstraint is built on first use and kept (it was built three times per run: for
    the motion and for the two static holds)."""
    import pathpace.sim

    sim, path = sway["sim"], sway["path"]
    built = []
    original = pathpace.sim._core.ContactConstraint

    def counting(*args, **kwargs):
        built.append(args)
        return original(*args, **kwargs)

    monkeypatch.setattr(pathpace.sim._core, "ContactConstraint", counting)
    monkeypatch.setattr(sim, "_default_contact_model", None)
    traj = pp.Trajectory(path, np.linspace(0.0, 1.0, 11), np.full(11, 1.0 / 3.0))  # uniform, T = 3 s
    assert traj.contacts is None
    first = sim.run(traj, settle=0.05, hold=0.05)
    assert first.feedforward == "contact" and len(built) == 1
    assert built[0][1] == sway["contacts"]
    second = sim.run(traj, settle=0.05, hold=0.05)
    assert len(built) == 1
    np.testing.assert_array_equal(first.tracking_error, second.tracking_error)


ROMEO_SMALL = "romeo_description/urdf/romeo_small.urdf"


def test_unphysical_urdf_inertias_are_raised_to_the_nearest_physical_ones_and_reported():
    urdf = example_robot_urdf(ROMEO_SMALL)
    robot = pp.RobotModel.from_urdf(str(urdf), floating_base=True)
    sim = Simulator(robot, urdf)
    # Two links of this URDF break A + B >= C (A <= B <= C its principal moments); nothing else changes.
    assert set(sim.inertia_adjustments) == {"RShoulderYawLink", "RElbowYawLink"}
    for link, (old, new) in sim.inertia_adjustments.items():
        assert old[0] + old[1] < old[2]
        assert new[2] == old[2] and np.isclose(new[0] + new[1], new[2], rtol=1e-8, atol=0)
        assert np.allclose(new[:2] - old[:2], (old[2] - old[0] - old[1]) / 2, rtol=1e-6, atol=0)  # raised equally
        body = sim.model.body(link)
        assert np.allclose(np.sort(sim.model.body_inertia[body.id]), new, rtol=1e-6, atol=0)
    with pytest.raises(pp.InvalidInputError, match=r"link 'RShoulderYawLink' has principal moments of inertia"):
        Simulator(robot, urdf, balance_inertia=False)
    # A link that moves but has no mass (romeo_laas_small's grippers) is named, with what to do.
    laas = example_robot_urdf("romeo_description/urdf/romeo_laas_small.urdf")
    with pytest.raises(pp.InvalidInputError, match=r"'l_gripper'.*lock its joint"):
        Simulator(pp.RobotModel.from_urdf(str(laas), floating_base=True), laas)


@pytest.mark.parametrize("name", ["romeo", "g1"])
def test_humanoid_sway_executes_with_margins_and_not_without(name):
    """Every humanoid of example-robot-data that pathpace times (tests/python/contact_corpus.py: Talos, Romeo,
    Unitree G1) runs in its simulator (issue 21): Romeo's and G1's sways on their sole corners, 8 cone edges,
    N = 100. Verdicts with room: at 20 N per point and a 50 % friction margin every criterion is at most half
    its threshold, and without margins one criterion is at least twice it. The room of the second is in the
    criterion, not in T: 10 % slower the zero-margin optimum executes, so it is not run slower here. 10 N is
    not asserted: on G1 it lost its room at N = 200 on a 4 ms floor (bench/README.md, "Issue 21: the room of
    the simulator's verdicts")."""
    import xml.etree.ElementTree as ET

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import contact_corpus as cc

    h = cc.load(name)
    urdf = example_robot_urdf(h.urdf)
    mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
    path = cc.make_path(h, "sway")
    cons = cc.contacts(h, "sway")
    sim = Simulator(h.robot, urdf, cons, path.q(0.0), locked_joints={n: 0.0 for n in mimic + h.locked})
    assert sim.inertia_adjustments == {} and len(sim.contacts) == len(cons)

    def run(min_normal_force, friction_margin):
        prob = pp.TimeScalingProblem(path, grid=100)
        # The IK path keeps the soles in place to a few micrometres.
        prob.add_contacts(h.robot, cons, cone_edges=8, min_normal_force=min_normal_force,
                          friction_margin=friction_margin, drift_tolerance=1e-4)
        res = prob.solve()
        assert res.status == pp.Status.OPTIMAL
        return sim.run(res.trajectory())

    bare = run(0.0, 0.0)
    assert bare.fell or bare.worst_criterion[1] >= 2.0, bare.summary()
    safe = run(20.0, 0.5)
    assert not safe.fell and max(safe.criterion_ratios.values()) <= 0.5, (safe.summary(), safe.criterion_ratios)
    assert safe.duration > bare.duration


def test_standup_from_a_squat_torque_timing_executes_the_others_fall_with_room(capsys, tmp_path):
    """examples/humanoid_standup.py (the paper's fig. 6), motors at 0.3 x the URDF effort: the timing under
    torque and contact limits stands up, the velocity/acceleration-only timing and the uniform one at the
    same T fall. Room, on two grids (N = 100 and 200, each its own plan and its own timings): the plan
    executes with every criterion at most half its threshold; each of the other two falls at the
    simulator's thresholds, and falls again when run 10 % slower with the fall thresholds doubled (a drop
    of 0.3 m or a tilt of 1 rad), so no verdict rests on a threshold or on T. It writes the plan's report
    with each sole's centre of pressure in its support polygon."""
    page = tmp_path / "standup.html"
    ns = runpy.run_path(str(EXAMPLES / "humanoid_standup.py"))
    out = ns["main"](["--report", str(page)])
    text = page.read_text(encoding="utf-8")
    assert "Centres of pressure in their support polygons" in text
    assert "centre of pressure of left_sole_link" in text and "normal force on right_sole_link" in text
    assert "executed, with room" in capsys.readouterr().out
    robot, path, contacts, sim = out["robot"], out["path"], out["contacts"], out["sim"]
    _, res200 = ns["contact_timing"](robot, path, contacts, 200, ns["TORQUE_SCALE"], **ns["MARGINS"])
    assert res200.status == pp.Status.OPTIMAL
    for grid, res, rows in ((100, out["result"], out["rows"]),
                            (200, res200, ns["run_three"](robot, path, 200, sim, res200))):
        rows = {r["timing"]: r for r in rows}
        ours = rows.pop("torque + contacts, margins")
        assert not ours["fell"] and ours["worst"][1] <= 0.5, (grid, ours["sim"].summary())
        assert ours["T"] == pytest.approx(res.duration, rel=1e-12)
        assert set(rows) == {"velocity + acceleration only", "uniform, same T",
                             "velocity + acceleration only, 1.1 x T", "uniform, 1.1 x T"}
        for name, r in rows.items():
            assert r["fell"], (grid, name, r["sim"].summary())
        assert rows["velocity + acceleration only"]["T"] < ours["T"]
        assert rows["uniform, same T"]["T"] == pytest.approx(ours["T"], rel=1e-12)
        assert rows["uniform, 1.1 x T"]["T"] == pytest.approx(1.1 * ours["T"], rel=1e-12)
        assert rows["velocity + acceleration only, 1.1 x T"]["T"] == pytest.approx(
            1.1 * rows["velocity + acceleration only"]["T"], rel=1e-9)
