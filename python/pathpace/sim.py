"""Execution of pathpace trajectories in a physics simulator (MuJoCo): does the robot stay up?

A timing is only as good as the model it was computed with. `Simulator` loads the URDF the
pathpace `RobotModel` came from into MuJoCo (``pip install 'pathpace[sim]'``, MuJoCo 3.3.7), with a
floor, a free joint when the model has a floating base, the joints the model locked welded at their
values, and one small sphere per pathpace `Contact` (with its friction coefficient μ) as the only
geometry that touches the floor. It then tracks a `Trajectory` with joint PD plus feed-forward torques
from *our* model: inverse dynamics with contact forces that realise the motion, the centred
distribution (the analytic centre of the physical force set, continuous in t: `Trajectory.contact_forces`
/ `ContactConstraint.force_distribution`), or plain inverse dynamics (`Trajectory.torques`) for a robot without contacts.
The simulator knows nothing of the plan beyond the joint targets: if the timing asks for forces the
floor cannot give (a pull, a force outside the friction cone, a centre of pressure beyond the sole),
the robot slips, pivots on a sole edge or falls, and `SimResult` says so.

`find_executable_margin` automates the search a user would do by hand (sec. V.D of the paper: a time-
optimal timing sits on the boundary of the feasible set, where a real robot is not safe): the smallest
minimum normal force (or friction margin) whose optimum executes in simulation, with its cost in T.

Everything is deterministic: fixed time step, MuJoCo's deterministic solver (the same inputs give the
same bits), and the only randomness (optional feed-forward torque noise) is seeded.
"""

from __future__ import annotations

import dataclasses
import math
import xml.etree.ElementTree as ET
from pathlib import Path as _FsPath
from typing import Any, Callable, Sequence

import numpy as np

from . import _core

__all__ = ["Simulator", "SimResult", "Box", "MarginTrial", "MarginSearch", "find_executable_margin", "resolve_mesh",
           "contact_configurations"]

FLOATING_JOINTS = ("floating_x", "floating_y", "floating_z", "floating_rz", "floating_ry", "floating_rx")


def _mujoco():
    # Imported lazily: `import pathpace` must not need MuJoCo.
    try:
        import mujoco
    except ImportError as e:
        raise ImportError("pathpace.sim needs MuJoCo: pip install 'pathpace[sim]' (mujoco==3.3.7)") from e
    return mujoco


def _fail(message: str) -> None:
    raise _core.InvalidInputError(message)


@dataclasses.dataclass(frozen=True)
class Box:
    """An axis-aligned box of the scene that contact points may stand on (a ladder rung, a step, a wall).

    centre and half_size (3,) in m, world frame; friction: its μ (default: the smallest of the contacts').
    A contact on a box touches one of its faces, with the face's outward normal as its (world) normal.
    """

    centre: tuple
    half_size: tuple
    name: str = ""
    friction: float | None = None

    def faces(self):
        """(outward normal, point on the face, the face's half extents along x, y, z) of the six faces."""
        c, h = np.asarray(self.centre, dtype=float), np.asarray(self.half_size, dtype=float)
        for axis in range(3):
            for sign in (1.0, -1.0):
                n = np.zeros(3)
                n[axis] = sign
                extent = h.copy()
                extent[axis] = 0.0
                yield n, c + h[axis] * n, extent


def contact_configurations(path: _core.Path, phases: Sequence, contacts: Sequence[_core.Contact]) -> list[np.ndarray]:
    """For each of `contacts`, the path's configuration where the first phase that holds it begins (a
    contact of a link and point in that phase's contacts): where it touches its surface, for
    Simulator(contact_configurations=...). A contact that no phase holds is an InvalidInputError."""
    key = lambda c: (c.link, tuple(np.round(np.asarray(c.point, dtype=float), 12)))  # noqa: E731
    out = []
    for k, c in enumerate(contacts):
        for ph in phases:
            if key(c) in {key(d) for d in ph[2]}:
                out.append(np.asarray(path.q(float(ph[0])), dtype=float))
                break
        else:
            _fail(f"contacts[{k}] ('{c.link}' at {tuple(c.point)}) is in no phase")
    return out


@dataclasses.dataclass
class SimResult:
    """What happened when a trajectory was executed (`Simulator.run`).

    Time series are sampled every `record_dt` from the start of the trajectory (after the settling
    phase) to the end of the hold phase, or to the fall. Displacements of the contact points are
    measured from where they were when the trajectory started (after settling on the floor).
    """

    times: np.ndarray  #: (m,) s since the trajectory started
    base_height: np.ndarray  #: (m,) z of the root link (m)
    base_height_planned: np.ndarray  #: (m,) z of the root link in the plan (held at the end)
    tilt: np.ndarray  #: (m,) angle between the root link's z axis and the plan's (rad)
    #: (m, contacts) displacement of each contact point along its surface (m; horizontal on the floor or a box
    #: top); with phases, its slide since the point made contact (from where it actually landed, the plan's
    #: own motion taken off), and nan while its phase does not hold it
    slip: np.ndarray
    lift: np.ndarray  #: (m, contacts) displacement along the contact's normal, away from its surface (m), the same way
    tracking_error: np.ndarray  #: (m,) largest |q - q_planned| over the actuated joints (rad or m)
    duration: float  #: T of the trajectory (s)
    fell: bool  #: the base dropped by more than fall_height or tilted by more than fall_tilt
    fall_time: float | None  #: when (s since the start of the trajectory), if it fell
    torque_saturation: float  #: fraction of control steps with some actuator at its torque limit
    criteria: dict  #: the thresholds `executed` applies
    feedforward: str  #: "contact", "inverse_dynamics" or "none"
    #: (contacts,) with phases, the largest distance along its surface between where a point landed and where
    #: the plan puts it, over its makes (m; 0 for a point held from the start, and without phases): a tracking
    #: error of the swing, not a slide
    landing: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(0))

    @property
    def max_landing_error(self) -> float:
        return float(np.max(self.landing)) if self.landing.size else 0.0

    @property
    def max_slip(self) -> float:
        return float(np.nanmax(self.slip)) if np.any(np.isfinite(self.slip)) else 0.0

    @property
    def max_lift(self) -> float:
        return float(np.nanmax(self.lift)) if np.any(np.isfinite(self.lift)) else 0.0

    @property
    def max_tilt(self) -> float:
        return float(np.max(self.tilt)) if self.tilt.size else 0.0

    @property
    def max_tracking_error(self) -> float:
        return float(np.max(self.tracking_error)) if self.tracking_error.size else 0.0

    @property
    def min_base_height_error(self) -> float:
        """The largest drop of the base below its planned height (m, >= 0 means it sank)."""
        return float(np.max(self.base_height_planned - self.base_height)) if self.times.size else 0.0

    @property
    def executed(self) -> bool:
        """Did the robot do what the plan says: no fall, feet where they were (slip and lift within the
        criteria: a sole that pivots on its edge lifts its other edge), base upright, joints tracked?"""
        c = self.criteria
        return (not self.fell and self.max_slip <= c["slip"] and self.max_lift <= c["lift"]
                and self.max_tilt <= c["tilt"] and self.max_tracking_error <= c["tracking"]
                and self.max_landing_error <= c["landing"])

    @property
    def criterion_ratios(self) -> dict:
        """Each criterion's worst value over its threshold (slip, lift, tilt, tracking, landing): <= 1 is
        within it. A verdict with room has every ratio <= 0.5 (executes) or some ratio >= 2 or a fall (does
        not)."""
        c = self.criteria
        return {"slip": self.max_slip / c["slip"], "lift": self.max_lift / c["lift"],
                "tilt": self.max_tilt / c["tilt"], "tracking": self.max_tracking_error / c["tracking"],
                "landing": self.max_landing_error / c["landing"]}

    @property
    def worst_criterion(self) -> tuple[str, float]:
        """(name, ratio) of the criterion nearest to or furthest past its threshold."""
        name, ratio = max(self.criterion_ratios.items(), key=lambda kv: kv[1])
        return name, float(ratio)

    def summary(self) -> str:
        verdict = "fell" if self.fell else ("executed" if self.executed else "stood, but off plan")
        return (f"T = {self.duration:.3f} s: {verdict}; slip {1e3 * self.max_slip:.1f} mm, lift {1e3 * self.max_lift:.1f} mm, "
                f"tilt {math.degrees(self.max_tilt):.2f} deg, tracking {self.max_tracking_error:.3f}"
                + (f", landing {1e3 * self.max_landing_error:.1f} mm" if self.landing.size else ""))


def resolve_mesh(filename: str, search: Sequence[_FsPath]) -> _FsPath | None:
    """A URDF mesh reference as a file, or None if not found. package://pkg/a/b is looked up, like ROS's
    package path, as <dir>/pkg/a/b for each dir in `search`, then without its leading folders (<dir>/a/b,
    ...; example-robot-data writes package:///example-robot-data/robots/...); file:// and relative
    references the same way, absolute ones as they are."""
    for prefix in ("package://", "file://"):
        if filename.startswith(prefix):
            filename = filename[len(prefix):]
            break
    if _FsPath(filename).is_absolute() and _FsPath(filename).is_file():
        return _FsPath(filename)
    parts = [p for p in filename.split("/") if p]
    for first in range(max(1, len(parts))):
        for d in search:
            candidate = _FsPath(d).joinpath(*parts[first:])
            if candidate.is_file():
                return candidate
    return None


def _physical_moments(moments: np.ndarray) -> np.ndarray:
    """The least raise of principal moments (ascending) that makes them those of a physical body: each
    >= 0 and the two smaller ones summing to at least the largest (raised equally)."""
    m = np.maximum(np.sort(np.asarray(moments, dtype=float)), 0.0)
    # 1e-9 past equality: MuJoCo re-diagonalises the full matrix, and A + B = C would fail its check by
    # rounding.
    short = m[2] * (1 + 1e-9) - m[0] - m[1]
    if m[0] + m[1] < m[2]:
        m[0] += short / 2
        m[1] += short / 2
    return m


def _balance_inertias(spec, balance: bool) -> dict:
    """Makes every body's inertia physical (see Simulator's docstring); returns the changes made."""
    changes = {}
    for body in spec.bodies:
        if body.name == "world" or not body.explicitinertial:
            continue
        f = np.asarray(body.fullinertia, dtype=float)
        if np.all(np.isfinite(f)) and np.any(f != 0):  # ixx, iyy, izz, ixy, ixz, iyz about the CoM
            inertia = np.array([[f[0], f[3], f[4]], [f[3], f[1], f[5]], [f[4], f[5], f[2]]])
            moments, axes = np.linalg.eigh(inertia)
        else:  # principal moments in the frame of iquat
            moments, axes = np.asarray(body.inertia, dtype=float), None
        order = np.argsort(moments)
        fixed = _physical_moments(moments)
        scale = max(float(np.max(np.abs(moments))), 1e-300)
        if np.all(np.abs(fixed - moments[order]) <= 1e-9 * scale):
            continue
        if not balance:
            _fail(f"urdf: link '{body.name}' has principal moments of inertia "
                  f"({', '.join(f'{v:.6g}' for v in np.sort(moments))}) kg m^2, which no body has (need each >= 0 "
                  "and the two smaller summing to the largest); pass balance_inertia=True to raise them")
        changes[body.name] = (np.sort(moments), fixed)
        if axes is None:
            new = np.empty(3)
            new[order] = fixed
            body.inertia = new
        else:
            m = np.empty(3)
            m[order] = fixed
            full = axes @ np.diag(m) @ axes.T
            body.fullinertia = [full[0, 0], full[1, 1], full[2, 2], full[0, 1], full[0, 2], full[1, 2]]
    return changes


class Simulator:
    """A MuJoCo model of a pathpace `RobotModel` standing on a floor at z = `floor_height` (and on `surfaces`).

    robot: the pathpace model; urdf: the file (or XML string) it was loaded from; locked_joints: the
    same dict given to `RobotModel.from_urdf` (every movable URDF joint must be either in robot.joint_names
    or locked); contacts: the pathpace contacts whose points touch the floor (world normal +z), each
    becoming a sphere of `contact_radius` with friction μ = contact.friction; q0: a configuration in
    which the contact points are on the floor (used to place the spheres and to check that MuJoCo's
    kinematics agree with ours).

    surfaces: `Box`es of the scene besides the floor (ladder rungs, steps); a contact may touch the floor
    (normal +z) or a face of a box (its normal that face's outward normal: +z on a rung's top, +x on the far
    side of a rung that a hand hooks). contact_configurations: one configuration per contact in which it
    touches its surface (default q0 for every contact; with contact phases, `contact_configurations(path,
    phases, contacts)`): the contact must be within 1 mm of a surface whose normal is its own, and its
    sphere is placed there, touching it. Slip and lift are measured along that surface and its normal.

    ball_links: links whose contact points are the centres of balls of contact_radius (a fist, a fingertip)
    rather than points on their surface: the point is contact_radius from its surface along the normal, and
    the link may turn on its ball while it holds (a sole's sphere instead touches at the point, so a sole
    that tilts lifts its point off the floor).

    impratio: MuJoCo's ratio of frictional to normal constraint impedance (default 1, MuJoCo's own). At 1 a
    point under a steady tangential load creeps (MuJoCo's friction is soft too): millimetres over seconds, on
    a rung whose points hold the robot's pull and push for the whole climb; 10 makes friction that much
    stiffer without changing μ.

    The floor is stiff: MuJoCo's soft contact with time constant `contact_timeconst` (default 5 ms; MuJoCo's
    own default, 20 ms, lets a sole edge sink by ~5 mm under Talos, and the robot rocks on it).

    Geometry: by default the URDF's visual and collision geometry is dropped (faster; the spheres are the
    contact model). visual_meshes=True keeps the visual STL/OBJ meshes for drawing (never colliding),
    resolving package:// against `package_dirs`, the URDF's folder and two above it, and example-robot-data.

    Inertias: MuJoCo only simulates physical ones (principal moments A, B, C >= 0 with A + B >= C). Some
    URDFs break that (Romeo's shoulder and elbow yaw links: 0.66 + 0.68 < 6.6 g·m²). pathpace plans with the
    URDF's numbers; with balance_inertia (default) the simulator raises the offending principal moments by
    the least that makes them physical (the two smaller ones equally, until A + B = C; negative ones to 0
    first) and records each change in `inertia_adjustments` ({link: (old moments, new moments)}), so the
    simulated robot differs from the planned one on exactly those links. balance_inertia=False makes such
    a URDF an InvalidInputError naming the link.

    effort_limits (robot.joint_names order; default the URDF's) are the motors' torques: the actuators'
    force ranges with torque_limits, and the effort of the default gains. A robot with weaker motors than
    its URDF says (e.g. 0.3 x, timed with torque_scale=0.3) is simulated with 0.3 x robot.effort_limits.

    Gains: kp (N·m/rad) defaults to effort / `stiffness_error` (full torque at that error), capped at
    inertia · max_frequency² (rad/s; the joint's own diagonal mass-matrix entry at q0), which explicit
    integration resolves while max_frequency · timestep <= 1; kd defaults to
    `damping_ratio` · kp (s). Both may be given per actuated joint (arrays in robot.joint_names order
    without the floating coordinates) or as scalars. Damping is integrated implicitly (implicitfast).
    """

    def __init__(
        self,
        robot: _core.RobotModel,
        urdf: str | _FsPath,
        contacts: Sequence[_core.Contact] = (),
        q0: np.ndarray | None = None,
        *,
        locked_joints: dict[str, float] | None = None,
        timestep: float = 1e-3,
        contact_radius: float = 0.005,
        contact_timeconst: float = 0.005,
        floor_height: float = 0.0,
        kp: float | np.ndarray | None = None,
        kd: float | np.ndarray | None = None,
        stiffness_error: float = 0.02,
        damping_ratio: float = 0.02,
        max_frequency: float | None = 500.0,
        torque_limits: bool = True,
        solver_iterations: int = 100,
        visual_meshes: bool = False,
        package_dirs: Sequence[str | _FsPath] = (),
        balance_inertia: bool = True,
        effort_limits: np.ndarray | None = None,
        surfaces: Sequence[Box] = (),
        contact_configurations: Sequence[np.ndarray] | None = None,
        impratio: float = 1.0,
        ball_links: Sequence[str] = (),
    ) -> None:
        mj = _mujoco()
        self.mujoco = mj
        self.robot = robot
        self.contacts = list(contacts)
        self._default_contact_model: _core.ContactConstraint | None = None  # see _contact_model
        locked = dict(locked_joints or {})
        if not (timestep > 0 and math.isfinite(timestep)):
            _fail(f"timestep = {timestep} must be > 0")
        if not (contact_radius > 0):
            _fail(f"contact_radius = {contact_radius} must be > 0")
        if not (impratio >= 1 and math.isfinite(impratio)):
            _fail(f"impratio = {impratio} must be >= 1 (MuJoCo's ratio of frictional to normal impedance)")
        if not (contact_timeconst >= 2 * timestep):
            _fail(f"contact_timeconst = {contact_timeconst} must be >= 2 timestep = {2 * timestep} (MuJoCo's stability limit)")
        names = list(robot.joint_names)
        self.floating = names[:6] == list(FLOATING_JOINTS)
        if any(n in FLOATING_JOINTS for n in names[6 if self.floating else 0:]):
            _fail("robot: floating_* coordinates only as the first six joints of one floating base are simulated")
        self.actuated = [i for i, n in enumerate(names) if n not in FLOATING_JOINTS]
        q0 = np.zeros(robot.nq) if q0 is None else np.asarray(q0, dtype=float)
        if q0.shape != (robot.nq,):
            _fail(f"q0 has shape {q0.shape}, expected ({robot.nq},)")
        self.root_link = robot.link_names[0]

        # The URDF without geometry (the spheres below are the only thing that touches the floor, which
        # is the contact model pathpace planned with) and without joint damping/friction (our model has
        # none, so the feed-forward could not cancel them).
        from_file = not str(urdf).lstrip().startswith("<")
        text = _FsPath(urdf).read_text() if from_file else str(urdf)
        root = ET.fromstring(text)
        search = [_FsPath(d) for d in (package_dirs or ())]
        if from_file:
            # A URDF usually sits in <package>/urdf/ or <package>/robots/: package:// resolves two levels up.
            here = _FsPath(urdf).resolve().parent
            search += [here, here.parent, here.parent.parent]
        if visual_meshes:
            try:
                from .robots import example_robot_data_dir

                search.append(example_robot_data_dir())
            except FileNotFoundError:
                pass
        self.visual_geoms = 0
        for link in root.iter("link"):
            for e in link.findall("collision"):
                link.remove(e)
            for e in link.findall("visual"):
                mesh = e.find("geometry/mesh")
                keep = visual_meshes
                if keep and mesh is not None:
                    found = resolve_mesh(mesh.get("filename", ""), search)
                    # MuJoCo reads STL and OBJ (not COLLADA): other visuals are dropped.
                    keep = found is not None and found.suffix.lower() in (".stl", ".obj")
                    if keep:
                        mesh.set("filename", str(found))
                if keep:
                    self.visual_geoms += 1
                else:
                    link.remove(e)
        urdf_movable = {}
        for j in root.iter("joint"):
            for e in j.findall("dynamics") + j.findall("mimic"):
                j.remove(e)
            if j.get("type") in ("revolute", "continuous", "prismatic"):
                urdf_movable[j.get("name")] = j.get("type")
        for name in names:
            if name not in FLOATING_JOINTS and name not in urdf_movable:
                _fail(f"robot.joint_names: '{name}' is not a movable joint of the URDF")
        for name in urdf_movable:
            if name not in names and name not in locked:
                _fail(f"locked_joints: URDF joint '{name}' is not in the robot model; pass the locked_joints the "
                      "model was loaded with")
        for old in root.findall("mujoco"):
            root.remove(old)
        ext = ET.SubElement(root, "mujoco")
        # Inertias only from the URDF's <inertial> (as in our model), never from geometry.
        ET.SubElement(ext, "compiler", fusestatic="false", discardvisual="false", balanceinertia="false",
                      inertiafromgeom="false", strippath="false")
        spec = mj.MjSpec.from_string(ET.tostring(root, encoding="unicode"))
        self.inertia_adjustments = _balance_inertias(spec, balance_inertia)
        for g in spec.geoms:  # the URDF's visuals: drawn, never touching anything, massless
            g.contype, g.conaffinity, g.group, g.density, g.mass = 0, 0, 1, 0.0, 0.0

        # Locked joints: weld the child body at the locked value, as pathpace's loader does.
        for name, value in locked.items():
            joint = spec.joint(name)
            if joint is None:
                _fail(f"locked_joints: '{name}' is not a joint of the URDF")
            body = joint.parent
            axis = np.asarray(joint.axis, dtype=float)
            axis = axis / np.linalg.norm(axis)
            if joint.type == mj.mjtJoint.mjJNT_SLIDE:
                offset = np.zeros(3)
                mj.mju_rotVecQuat(offset, axis * value, np.asarray(body.quat, dtype=float))
                body.pos = np.asarray(body.pos, dtype=float) + offset
            else:
                turn, out = np.zeros(4), np.zeros(4)
                mj.mju_axisAngle2Quat(turn, axis, float(value))
                mj.mju_mulQuat(out, np.asarray(body.quat, dtype=float), turn)
                body.quat = out
            spec.delete(joint)

        root_body = spec.worldbody.first_body()
        if root_body is None or root_body.name != self.root_link:
            _fail(f"urdf: MuJoCo's root body is not the model's root link '{self.root_link}'")
        if self.floating:
            root_body.add_freejoint(name="floating_base")
        spec.option.timestep = timestep
        spec.option.gravity = np.asarray(robot.gravity_vector, dtype=float)
        spec.option.integrator = mj.mjtIntegrator.mjINT_IMPLICITFAST
        spec.option.cone = mj.mjtCone.mjCONE_ELLIPTIC
        spec.option.iterations = solver_iterations
        spec.option.impratio = impratio

        # Floor, boxes and contact spheres: only sphere-surface pairs collide (contype/conaffinity bits).
        self.floor_height = float(floor_height)
        mu_min = min([c.friction for c in self.contacts], default=1.0)
        spec.worldbody.add_geom(name="floor", type=mj.mjtGeom.mjGEOM_PLANE, size=[0, 0, 0.05],
                                pos=[0, 0, self.floor_height], contype=0, conaffinity=2, condim=3,
                                friction=[mu_min, 0.0, 0.0])
        self.surfaces = self._add_surfaces(spec, surfaces, mu_min)
        if contact_configurations is None:
            configs = [q0] * len(self.contacts)
        else:
            configs = [np.asarray(q, dtype=float) for q in contact_configurations]
            if len(configs) != len(self.contacts):
                _fail(f"contact_configurations has {len(configs)} configurations, expected one per contact ({len(self.contacts)})")
            for k, q in enumerate(configs):
                if q.shape != (robot.nq,):
                    _fail(f"contact_configurations[{k}] has shape {q.shape}, expected ({robot.nq},)")
        balls = set(ball_links)
        for name in balls:
            if name not in robot.link_names:
                _fail(f"ball_links: '{name}' is not a link of the robot")
        #: the surface each contact touches: "floor" or a Box's name
        self.contact_surfaces = []
        self.contact_normals = np.zeros((len(self.contacts), 3))
        ball_geoms: set = set()  # (link, centre) of each ball link's sphere, added once
        for k, c in enumerate(self.contacts):
            if c.other_link is not None:
                _fail(f"contacts[{k}]: link-to-link contacts ('{c.link}' on '{c.other_link}') are not simulated")
            n = np.asarray(c.normal, dtype=float)
            n = n / np.linalg.norm(n)
            X = robot.frame_placement(configs[k], c.link)
            p = (X @ np.append(c.point, 1.0))[:3]
            ball = c.link in balls
            self.contact_surfaces.append(self._surface_at(k, c, p - contact_radius * n if ball else p, n))
            self.contact_normals[k] = n
            body = spec.body(c.link)
            centre = np.asarray(c.point, dtype=float)
            if not ball:
                centre = centre + contact_radius * (X[:3, :3].T @ n)
            elif (c.link, tuple(centre)) in ball_geoms:
                # One ball, several faces (a hand gripping a rung: its top and the sides that hold it): the
                # ball touches each of them; a second sphere in the same place would double its stiffness.
                body.add_site(name=f"pathpace_contact_{k}", pos=centre)
                continue
            else:
                ball_geoms.add((c.link, tuple(centre)))
            # priority: the sphere's μ is the contact's μ (MuJoCo would otherwise take the larger one).
            body.add_geom(name=f"pathpace_contact_{k}", type=mj.mjtGeom.mjGEOM_SPHERE, size=[contact_radius, 0, 0],
                          pos=centre, contype=2, conaffinity=0, condim=3, priority=1, friction=[c.friction, 0.0, 0.0],
                          mass=0.0, density=0.0, group=3, solref=[contact_timeconst, 1.0])
            body.add_site(name=f"pathpace_contact_{k}", pos=np.asarray(c.point, dtype=float))

        # Actuators: force = kp (ctrl - q) - kd q̇ with ctrl = q* + (τ_ff + kd q̇*) / kp, i.e. PD about the plan
        # plus the feed-forward, with the damping term integrated implicitly.
        effort = np.asarray(robot.effort_limits if effort_limits is None else effort_limits, dtype=float)
        if effort.shape != (robot.nq,):
            _fail(f"effort_limits has shape {effort.shape}, expected ({robot.nq},) (robot.joint_names order)")
        bad = np.flatnonzero(~(effort >= 0))
        if bad.size:
            _fail(f"effort_limits[{bad[0]}] = {effort[bad[0]]} must be >= 0 (N·m or N)")
        for i in self.actuated:
            a = spec.add_actuator(name=names[i], target=names[i], trntype=mj.mjtTrn.mjTRN_JOINT)
            a.gaintype = mj.mjtGain.mjGAIN_FIXED
            a.biastype = mj.mjtBias.mjBIAS_AFFINE
            if torque_limits and math.isfinite(effort[i]) and effort[i] > 0:
                a.forcelimited = mj.mjtLimited.mjLIMITED_TRUE
                a.forcerange = [-effort[i], effort[i]]
        if not torque_limits:  # MuJoCo's URDF import also limits the joint's total actuator force
            for j in spec.joints:
                j.actfrclimited = mj.mjtLimited.mjLIMITED_FALSE
        try:
            self.model = model = spec.compile()
        except ValueError as e:
            hint = ""
            if "mjMINVAL" in str(e):
                hint = (" (a link that moves must have mass and inertia in MuJoCo: lock its joint with "
                        "locked_joints, in the model and here)")
            _fail(f"urdf: MuJoCo cannot compile the robot: {' '.join(str(e).split())}{hint}")
        self.spec = spec
        self.data = mj.MjData(model)

        # Index maps pathpace q -> MuJoCo qpos / qvel / actuators.
        self.qpos_index = np.array([model.joint(names[i]).qposadr[0] for i in self.actuated], dtype=int)
        self.dof_index = np.array([model.joint(names[i]).dofadr[0] for i in self.actuated], dtype=int)
        self.site_ids = np.array([model.site(f"pathpace_contact_{k}").id for k in range(len(self.contacts))], dtype=int)
        self.root_body_id = model.body(self.root_link).id

        # Gains.
        self.set_configuration(q0)
        M = np.zeros((model.nv, model.nv))
        mj.mj_fullM(model, M, self.data.qM)
        inertia = np.diag(M)[self.dof_index]
        if kp is None:
            finite_effort = np.where(np.isfinite(effort[self.actuated]) & (effort[self.actuated] > 0), effort[self.actuated], 100.0)
            kp = finite_effort / stiffness_error
            if max_frequency is not None:
                # The stiffness is integrated explicitly: a light joint (a wrist, a foot in the air) must not
                # oscillate faster than max_frequency on its own inertia. Independent of the time step, so
                # that a smaller step converges to the same closed loop.
                kp = np.minimum(kp, inertia * max_frequency**2)
        kp = np.broadcast_to(np.asarray(kp, dtype=float), (len(self.actuated),)).copy()
        kd = damping_ratio * kp if kd is None else np.broadcast_to(np.asarray(kd, dtype=float), (len(self.actuated),)).copy()
        if np.any(~(kp > 0)):
            _fail(f"kp[{int(np.argmin(kp > 0))}] must be > 0")
        if np.any(~(kd >= 0)):
            _fail(f"kd[{int(np.argmin(kd >= 0))}] must be >= 0")
        self.kp, self.kd = kp, kd
        for k in range(len(self.actuated)):
            model.actuator_gainprm[k, 0] = kp[k]
            model.actuator_biasprm[k, :3] = (0.0, -kp[k], -kd[k])
        self._check_kinematics(q0)

    # ----------------------------------------------------------------------------------------------
    def _add_surfaces(self, spec, surfaces: Sequence[Box], friction: float) -> list[Box]:
        """The boxes as MuJoCo geoms that only the contact spheres touch."""
        out = []
        for i, b in enumerate(surfaces):
            if isinstance(b, dict):
                b = Box(**b)
            if not isinstance(b, Box):
                _fail(f"surfaces[{i}]: expected a pathpace.sim.Box, got {type(b).__name__}")
            c, h = np.asarray(b.centre, dtype=float), np.asarray(b.half_size, dtype=float)
            if c.shape != (3,) or not np.all(np.isfinite(c)):
                _fail(f"surfaces[{i}].centre = {b.centre} must be 3 finite numbers (m)")
            if h.shape != (3,) or not np.all(h > 0) or not np.all(np.isfinite(h)):
                _fail(f"surfaces[{i}].half_size = {b.half_size} must be 3 finite numbers > 0 (m)")
            mu = friction if b.friction is None else float(b.friction)
            if not (mu > 0):
                _fail(f"surfaces[{i}].friction = {b.friction} must be > 0")
            name = b.name or f"surface_{i}"
            if name == "floor" or any(o.name == name for o in out):
                _fail(f"surfaces[{i}].name = '{name}' is not unique (nor may it be 'floor')")
            b = Box(tuple(c), tuple(h), name, mu)
            spec.worldbody.add_geom(name=name, type=self.mujoco.mjtGeom.mjGEOM_BOX, size=h, pos=c, contype=0,
                                    conaffinity=2, condim=3, friction=[mu, 0.0, 0.0])
            out.append(b)
        return out

    def _surface_at(self, k: int, c: _core.Contact, p: np.ndarray, n: np.ndarray) -> str:
        """The surface that contact k touches at world point p with world normal n (see the class docstring)."""
        tol = 1e-3
        if not self.surfaces:  # the floor only: its own messages
            if abs(n[2] - 1.0) > 1e-9:
                _fail(f"contacts[{k}].normal = ({', '.join(f'{v:g}' for v in c.normal)}) must be (0, 0, 1): only contacts on the floor are simulated")
            if abs(p[2] - self.floor_height) > tol:
                _fail(f"contacts[{k}] ('{c.link}') is at z = {p[2]:.4g} in q0, expected on the floor (z = {self.floor_height})")
            return "floor"
        if abs(n[2] - 1.0) <= 1e-9 and abs(p[2] - self.floor_height) <= tol:
            return "floor"
        for b in self.surfaces:
            for normal, on_face, extent in b.faces():
                if np.max(np.abs(n - normal)) > 1e-9:
                    continue
                along = np.abs(normal) == 0  # the face's own directions
                inside = np.all(np.abs(p - np.asarray(b.centre))[along] <= extent[along] + tol)
                if abs((p - on_face) @ normal) <= tol and inside:
                    return b.name
        _fail(f"contacts[{k}] ('{c.link}', normal ({', '.join(f'{v:g}' for v in c.normal)})) is at "
              f"({', '.join(f'{v:.4g}' for v in p)}) in its configuration, on no surface with that normal (the floor at "
              f"z = {self.floor_height} or a face of surfaces {[b.name for b in self.surfaces]}, within 1 mm)")

    def _against_plan(self, traj: _core.Trajectory, t: np.ndarray, d: np.ndarray, phases: Sequence) -> np.ndarray:
        """Displacements d (times x contacts x 3) minus the plan's own, nan where no phase holds the point."""
        key = [(c.link, tuple(np.round(np.asarray(c.point, dtype=float), 12))) for c in self.contacts]
        held = []
        for i, ph in enumerate(phases):
            if len(ph) not in (3, 4):
                _fail(f"phases[{i}]: expected (s_begin, s_end, contacts[, options]), got {len(ph)} items")
            names = {(c.link, tuple(np.round(np.asarray(c.point, dtype=float), 12))) for c in ph[2]}
            unknown = names - set(key)
            if unknown:
                link, point = sorted(unknown)[0]
                _fail(f"phases[{i}]: contact on '{link}' at {point} is not one of the simulator's contacts")
            held.append([k in names for k in key])
        # Each time's phase by C++'s rule (the later one at a switch, the nearest beyond every phase).
        mask = np.array(held, dtype=bool)[self._phase_of(traj, t, self._phase_models(phases))]
        links = sorted({c.link for c in self.contacts})
        planned = np.empty((len(t), len(self.contacts), 3))
        for i, qi in enumerate(traj.q(t)):
            X = {link: self.robot.frame_placement(qi, link) for link in links}  # once per link, not per point
            for k, c in enumerate(self.contacts):
                planned[i, k] = (X[c.link] @ np.append(c.point, 1.0))[:3]
        out = d - (planned - planned[0])
        out[~mask] = np.nan
        return out

    def set_configuration(self, q: np.ndarray) -> None:
        """MuJoCo state at the pathpace configuration q, at rest."""
        mj, model, data = self.mujoco, self.model, self.data
        mj.mj_resetData(model, data)
        q = np.asarray(q, dtype=float)
        if self.floating:
            X = self.robot.frame_placement(q, self.root_link)
            quat = np.zeros(4)
            mj.mju_mat2Quat(quat, X[:3, :3].flatten())
            data.qpos[:3] = X[:3, 3]
            data.qpos[3:7] = quat
        data.qpos[self.qpos_index] = q[self.actuated]
        mj.mj_forward(model, data)

    def _check_kinematics(self, q0: np.ndarray) -> None:
        # MuJoCo and pathpace must agree on where every contact link is and on the total weight;
        # a wrong locked value or a misread URDF shows up here rather than as a "fall".
        self.set_configuration(q0)
        for c in self.contacts:
            X = self.robot.frame_placement(q0, c.link)
            b = self.model.body(c.link).id
            err = max(np.max(np.abs(self.data.xpos[b] - X[:3, 3])), np.max(np.abs(self.data.xmat[b].reshape(3, 3) - X[:3, :3])))
            if err > 1e-6:
                _fail(f"urdf: MuJoCo places link '{c.link}' {err:.2e} away from the pathpace model at q0 (locked_joints?)")
        if self.floating:
            weight = self.robot.gravity(q0)[2]  # g(q): the force that holds the base up
            mj_weight = float(np.sum(self.model.body_mass)) * np.linalg.norm(self.model.opt.gravity)
            if abs(weight - mj_weight) > 1e-6 * max(1.0, abs(weight)):
                _fail(f"urdf: MuJoCo's robot weighs {mj_weight:.6g} N, the pathpace model {weight:.6g} N")

    def contact_positions(self) -> np.ndarray:
        """(contacts, 3) world positions of the contact points now."""
        return self.data.site_xpos[self.site_ids].copy()

    # ----------------------------------------------------------------------------------------------
    def _contact_model(self, contact_model: _core.ContactConstraint | None) -> _core.ContactConstraint:
        """`contact_model`, else the simulator's contacts with 8 cone edges and no margins (built on first use
        and kept: the contacts are fixed with the MuJoCo model, and a ContactConstraint is immutable)."""
        if contact_model is not None:
            return contact_model
        if self._default_contact_model is None:
            self._default_contact_model = _core.ContactConstraint(self.robot, self.contacts, cone_edges=8)
        return self._default_contact_model

    def _narrowed(self, model: _core.ContactConstraint, friction_margin: float) -> _core.ContactConstraint:
        """`model`'s contacts with cones of μ (1 - friction_margin) and its physical torque limits (before scale and
        margin): a force set whose centre keeps that share of every cone in reserve."""
        contacts = [_core.Contact(c.link, c.point, c.normal, c.friction * (1.0 - friction_margin), c.other_link)
                    for c in model.contacts]
        return _core.ContactConstraint(model.robot, contacts, cone_edges=8, tau_min=model.physical_tau_min,
                                       tau_max=model.physical_tau_max)

    def feedforward(self, traj: _core.Trajectory, t: np.ndarray, mode: str = "auto",
                    contact_model: _core.ContactConstraint | None = None,
                    friction_margin: float = 0.0, phases: Sequence | None = None) -> tuple[np.ndarray, str]:
        """(len(t), nq) feed-forward torques and the mode used.

        "contact": τ = M q̈ + C q̇ + g - Σ Jᵀ f with f the centred force distribution (continuous in t;
        the LP's vertex only where the physical force set has no interior): the trajectory's own
        contact constraint when it has one (its margins shape the forces), else `contact_model`, else the
        simulator's contacts with 8 cone edges and no margins. "inverse_dynamics": τ = M q̈ + C q̇ + g
        (a robot without contacts). "none": PD only. "auto": "contact" if there are contacts.

        friction_margin (in [0, 1)): the centre is taken in cones of μ (1 - friction_margin) instead of μ
        (each phase's own contacts and physical torque limits, 8 cone edges). The physical set's centre may
        ask a contact for most of its cone (a Talos hand on a ladder rung: 0.42 N tangentially per N of
        normal force at μ = 0.5), and MuJoCo's soft friction creeps there; pass the plan's friction_margin
        to feed forward forces that keep the reserve the plan kept. The plan's LP proved such forces exist
        at its grid points (with its minimum normal forces too); at a sample where the narrowed set has no
        interior or no solution the physical centre is used.

        phases (as for add_contact_phases): for a trajectory without contacts of its own (a velocity and
        acceleration timing) and no contact_model, each sample is fed forward with its phase's contacts (8
        cone edges, no margins; the later phase at a switch) instead of all the simulator's contacts, which
        would ask a swinging limb for forces.
        """
        t = np.asarray(t, dtype=float)
        if not (0.0 <= friction_margin < 1.0):
            _fail(f"friction_margin = {friction_margin} must be in [0, 1)")
        if mode == "auto":
            mode = "contact" if (self.contacts or traj.contacts is not None) else "inverse_dynamics"
        if mode == "none":
            return np.zeros((t.size, self.robot.nq)), mode
        if mode == "inverse_dynamics":
            return np.atleast_2d(traj.torques(t, self.robot)), mode
        if mode != "contact":
            _fail(f"feedforward = '{mode}' must be 'auto', 'contact', 'inverse_dynamics' or 'none'")
        own = traj.contacts is not None and contact_model is None
        if own:  # the trajectory's own forces: one call (C++ batches the samples by phase)
            cf = traj.contact_forces(t)
            tau = np.atleast_2d(np.array(cf.torques, dtype=float))
            feasible = np.atleast_1d(np.asarray(cf.feasible, dtype=bool))
            if friction_margin == 0.0:
                models = []
            else:
                models = list(traj.contact_phases) or [traj.contacts]
                which = (np.atleast_1d(np.asarray(traj.contact_phase(t))) if len(models) > 1
                         else np.zeros(t.size, dtype=int))
        else:  # the sets of `phases` for a timing without contacts, else one set for the whole motion
            if contact_model is None and phases is not None:
                models = self._phase_models(phases)
                which = self._phase_of(traj, t, models)
            else:
                models, which = [self._contact_model(contact_model)], np.zeros(t.size, dtype=int)
            tau, feasible = np.zeros((t.size, self.robot.nq)), np.zeros(t.size, dtype=bool)
        if models:
            q, qd, qdd = traj.evaluate(t)
        for p in np.unique(which) if models else ():
            idx = np.flatnonzero(which == p)
            if not own:
                f = models[p].force_distribution(q[idx], qd[idx], qdd[idx])
                tau[idx] = np.atleast_2d(np.array(f.torques, dtype=float))
                feasible[idx] = np.atleast_1d(np.asarray(f.feasible, dtype=bool))
            if friction_margin > 0.0:
                # The same motion's forces in the narrowed cones, kept where they are that set's centre.
                narrow = self._narrowed(models[p], friction_margin).force_distribution(q[idx], qd[idx], qdd[idx])
                tn = np.atleast_2d(np.array(narrow.torques, dtype=float))
                ok = (np.atleast_1d(np.asarray(narrow.centred, dtype=bool))
                      & np.atleast_1d(np.asarray(narrow.feasible, dtype=bool)) & np.all(np.isfinite(tn), axis=1))
                tau[idx[ok]] = tn[ok]
        # Where no contact forces of any sign meet the torque limits the LP has no answer: the motion is
        # impossible; track it with gravity-and-motion torques and the last good contact forces instead
        # (NaN would stop the simulation, and the robot is about to show what happens anyway).
        bad = ~feasible | ~np.all(np.isfinite(tau), axis=1)
        if np.any(bad):
            good = np.flatnonzero(~bad)
            for k in np.flatnonzero(bad):
                prev = good[good < k]
                tau[k] = tau[prev[-1]] if prev.size else 0.0
        return tau, mode

    def _phase_models(self, phases: Sequence) -> list[_core.ContactConstraint]:
        """One ContactConstraint per phase (as for add_contact_phases): its contacts with 8 cone edges and no
        margins, over its stretch of s."""
        return [_core.ContactConstraint(self.robot, list(ph[2]), cone_edges=8, active_begin=float(ph[0]),
                                        active_end=float(ph[1])) for ph in phases]

    @staticmethod
    def _phase_of(traj: _core.Trajectory, t: np.ndarray, models: Sequence[_core.ContactConstraint]) -> np.ndarray:
        """The index of the phase at each t: contact_phase_of_s at s(t), Trajectory.contact_phase's rule."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return np.asarray(_core.contact_phase_of_s(list(models), traj.s(t)[0]), dtype=int)

    def _static_feedforward(self, q: np.ndarray, mode: str, contact_model: _core.ContactConstraint | None) -> np.ndarray:
        zero = np.zeros_like(q)
        if mode == "none":
            return zero
        if mode == "inverse_dynamics" or not self.contacts:
            return self.robot.gravity(q)
        cf = self._contact_model(contact_model).force_distribution(q, zero, zero)
        return np.asarray(cf.torques, dtype=float) if cf.feasible else self.robot.gravity(q)

    def run(
        self,
        traj: _core.Trajectory,
        *,
        feedforward: str = "auto",
        contact_model: _core.ContactConstraint | None = None,
        settle: float = 0.5,
        hold: float = 1.0,
        record_dt: float = 0.01,
        fall_height: float = 0.15,
        fall_tilt: float = 0.5,
        criteria: dict | None = None,
        torque_noise: float = 0.0,
        seed: int = 0,
        phases: Sequence | None = None,
        feedforward_friction_margin: float = 0.0,
    ) -> SimResult:
        """Execute `traj`: start at rest at q(0), hold it for `settle` s (the contacts load up), track the
        trajectory, hold its last point for `hold` s. Stops early if the robot falls (base `fall_height` m
        below plan or tilted by `fall_tilt` rad). `criteria` (defaults: slip 5 mm, lift 5 mm, tilt 0.05 rad,
        tracking 0.1) are the thresholds of `SimResult.executed`. `torque_noise`: std of Gaussian noise
        (N·m) added to the feed-forward at every step, from a generator seeded with `seed`.

        phases: the contact phases the timing was planned with (as for add_contact_phases: (s_begin,
        s_end, contacts[, options]) each). Then a contact point counts (slip, lift) only while a phase at
        the timing's s(t) holds it (a point of a link and position in that phase's contacts; the phase is
        pathpace.contact_phase_of_s's: the later one at a switch), and it is measured from where the plan puts it: a swing foot that lifts as
        planned is not a lift. Its slip is its slide since it made contact (from the first sample its phase
        holds it), and where it landed against the plan is `SimResult.landing`, criterion "landing"
        (default 10 mm: a placement error of the swing, judged like tracking, not a slide of the contact).

        feedforward_friction_margin: the contact feed-forward's forces in cones of μ (1 - this) (`feedforward`'s
        friction_margin; 0: the physical cones)."""
        mj, model, data = self.mujoco, self.model, self.data
        dt = model.opt.timestep
        crit = {"slip": 0.005, "lift": 0.005, "tilt": 0.05, "tracking": 0.1, "landing": 0.01}
        for key, value in (criteria or {}).items():
            if key not in crit:
                _fail(f"criteria['{key}']: unknown; the criteria are {sorted(crit)}")
            crit[key] = float(value)
        for name, value in (("settle", settle), ("hold", hold)):
            if not (value >= 0):
                _fail(f"{name} = {value} must be >= 0")
        if not (record_dt > 0):
            _fail(f"record_dt = {record_dt} must be > 0")
        T = float(traj.duration)
        n_move = int(math.ceil(T / dt - 1e-9))
        t_ctrl = np.minimum(np.arange(n_move + 1) * dt, T)
        q_des, qd_des, _ = traj.evaluate(t_ctrl)
        tau_ff, mode = self.feedforward(traj, t_ctrl, feedforward, contact_model, feedforward_friction_margin, phases)
        qd_des = qd_des.copy()
        qd_des[-1] = 0.0  # holding the end: at rest whatever the timing's last speed
        rng = np.random.default_rng(seed)
        a = self.actuated

        def ctrl_for(step: int) -> np.ndarray:
            k = min(step, n_move)
            ff = tau_ff[k, a] if step < n_move else static[1][a]
            if torque_noise > 0:
                ff = ff + rng.normal(0.0, torque_noise, ff.shape)
            return q_des[k, a] + (ff + self.kd * qd_des[k, a]) / self.kp

        # Settling and holding use the static torques at the first and last point: a time-optimal timing
        # starts and ends with its largest acceleration (s̈ != 0 at ṡ = 0), which is not what holds the
        # robot still.
        static = [self._static_feedforward(q_des[k], mode, contact_model) for k in (0, n_move)]
        self.set_configuration(q_des[0])
        data.ctrl[:] = q_des[0, a] + static[0][a] / self.kp
        for _ in range(int(round(settle / dt))):
            mj.mj_step(model, data)
        p0 = self.contact_positions()

        n_hold = int(round(hold / dt))
        every = max(1, int(round(record_dt / dt)))
        rec_t, rec_z, rec_zp, rec_tilt, rec_pos, rec_err = [], [], [], [], [], []
        plan_k, z_plan, zaxis_plan = -1, 0.0, np.zeros(3)  # the plan's root link at control step plan_k
        fell, fall_time, saturated = False, None, 0
        # Saturation: the force-limited actuators and their limits, once (not per step).
        limited = np.flatnonzero(model.actuator_forcelimited)
        at_limit = model.actuator_forcerange[limited, 1] * (1 - 1e-9)
        for step in range(n_move + n_hold + 1):
            k = min(step, n_move)
            if step % every == 0 or step == n_move + n_hold:
                if k != plan_k:
                    X = self.robot.frame_placement(q_des[k], self.root_link)
                    plan_k, z_plan, zaxis_plan = k, float(X[2, 3]), X[:3, 2].copy()
                zaxis = data.xmat[self.root_body_id].reshape(3, 3)[:, 2]
                tilt = math.acos(max(-1.0, min(1.0, float(zaxis @ zaxis_plan))))
                z = float(data.xpos[self.root_body_id][2])
                rec_t.append(step * dt)
                rec_z.append(z)
                rec_zp.append(z_plan)
                rec_tilt.append(tilt)
                rec_pos.append(self.contact_positions())
                rec_err.append(float(np.max(np.abs(data.qpos[self.qpos_index] - q_des[k, a]))) if a else 0.0)
                if self.floating and (z_plan - z > fall_height or tilt > fall_tilt):
                    fell, fall_time = True, step * dt
                    break
            if step == n_move + n_hold:
                break
            data.ctrl[:] = ctrl_for(step)
            mj.mj_step(model, data)
            if limited.size and np.any(np.abs(data.actuator_force[limited]) >= at_limit):
                saturated += 1
        pos = np.array(rec_pos).reshape(len(rec_pos), len(self.contacts), 3)
        d = pos - p0
        landing = np.zeros(0)
        if phases is not None:
            d = self._against_plan(traj, np.minimum(np.array(rec_t), T), d, phases)
        lift = np.einsum("mkj,kj->mk", d, self.contact_normals)  # along each contact's normal; +z: d[:, :, 2]
        along = d - lift[:, :, None] * self.contact_normals
        if phases is not None:
            along, landing = _slide_since_make(along)
        return SimResult(
            times=np.array(rec_t), base_height=np.array(rec_z), base_height_planned=np.array(rec_zp),
            tilt=np.array(rec_tilt), slip=np.linalg.norm(along, axis=2), lift=lift,
            tracking_error=np.array(rec_err), duration=T, fell=fell, fall_time=fall_time,
            torque_saturation=saturated / max(1, n_move + n_hold), criteria=crit, feedforward=mode, landing=landing)


def _slide_since_make(along: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Tangential offsets from the plan (times x contacts x 3, nan where not held) -> each point's slide
    since the first sample of each hold, and its largest offset at those first samples (the landing error)."""
    out = np.full_like(along, np.nan)
    landing = np.zeros(along.shape[1])
    held = np.isfinite(along[:, :, 0])
    for k in range(along.shape[1]):
        edges = np.flatnonzero(np.diff(np.concatenate(([0], held[:, k].astype(np.int8), [0]))))
        for begin, end in zip(edges[0::2], edges[1::2]):
            out[begin:end, k] = along[begin:end, k] - along[begin, k]
            landing[k] = max(landing[k], float(np.linalg.norm(along[begin, k])))
    return out, landing


# --------------------------------------------------------------------------------------------------
@dataclasses.dataclass
class MarginTrial:
    """One timing tried by `find_executable_margin`."""

    min_normal_force: float
    friction_margin: float
    status: str  #: the solver's status name
    duration: float  #: T (nan if the solver found no timing)
    executed: bool  #: executed with the search's room (see find_executable_margin)
    sim: SimResult | None


@dataclasses.dataclass
class MarginSearch:
    """The smallest margin whose time-optimal timing executes in simulation, and what it costs."""

    parameter: str  #: "min_normal_force" or "friction_margin"
    margin: float | None  #: the smallest executable value found (None: not even the upper bound executes)
    duration: float  #: T at that margin (nan if none)
    zero_margin_duration: float  #: T of the optimum at the lower bound of the search
    trials: list[MarginTrial]

    @property
    def cost(self) -> float:
        """Relative increase of T over the lower bound's optimum (0.25 = 25 % slower)."""
        return self.duration / self.zero_margin_duration - 1.0

    def table(self) -> str:
        rows = [f"{'min normal force (N)':>21s} {'friction margin':>16s} {'T (s)':>8s} {'executes':>9s}  simulation"]
        for tr in sorted(self.trials, key=lambda r: (r.min_normal_force, r.friction_margin)):
            sim = tr.sim.summary() if tr.sim is not None else tr.status
            rows.append(f"{tr.min_normal_force:21.2f} {tr.friction_margin:16.3f} {tr.duration:8.3f} "
                        f"{'yes' if tr.executed else 'no':>9s}  {sim}")
        return "\n".join(rows)


def find_executable_margin(
    sim: Simulator,
    path: _core.Path,
    contacts: Sequence[_core.Contact] | None = None,
    *,
    parameter: str = "min_normal_force",
    lower: float = 0.0,
    upper: float = 40.0,
    tolerance: float = 1.0,
    min_normal_force: float = 0.0,
    friction_margin: float = 0.0,
    grid: int | np.ndarray = 100,
    cone_edges: int = 8,
    drift_tolerance: float = 1e-4,
    configure: Callable[[_core.TimeScalingProblem], Any] | None = None,
    run_options: dict | None = None,
    phases: Sequence | None = None,
    room: float = 0.5,
    contact_options: dict | None = None,
) -> MarginSearch:
    """Bisection on one margin of the contact constraint for the smallest value whose time-optimal timing
    executes in `sim` with room: no fall and every criterion (slip, lift, tilt, tracking, landing) at most
    `room` times its threshold
    (`SimResult.worst_criterion`; room = 1 is `SimResult.executed`). A verdict on its threshold flips
    with the CPU or the MuJoCo build; 0.5 leaves it room.

    phases: contact phases (as for add_contact_phases) instead of `contacts`: every problem is built with
    add_contact_phases and each run measures the held points only (`Simulator.run`'s phases).

    parameter: "min_normal_force" (N per contact; searched in [lower, upper]) or "friction_margin"
    (fraction of μ, in [lower, upper] within [0, 1)); the other margin stays at the value given.
    contact_options: further keyword arguments of add_contacts / add_contact_phases for every problem
    (e.g. torque_scale for motors weaker than the URDF's effort). configure(prob) may add further constraints (velocity, torque limits...) to every problem. The search
    assumes that executability is monotone in the margin (every trial is kept in `trials` to check).
    An upper bound without any timing (too large a margin: infeasible) is halved towards `lower` until
    the problem is feasible. It stops when the bracket is narrower than `tolerance`.
    """
    if parameter not in ("min_normal_force", "friction_margin"):
        _fail(f"parameter = '{parameter}' must be 'min_normal_force' or 'friction_margin'")
    if not (upper > lower >= 0):
        _fail(f"upper = {upper} must be > lower = {lower} >= 0")
    if parameter == "friction_margin" and upper >= 1:
        _fail(f"upper = {upper} must be < 1 for the friction margin")
    if not (tolerance > 0):
        _fail(f"tolerance = {tolerance} must be > 0")
    if not (0 < room <= 1):
        _fail(f"room = {room} must be in (0, 1] (the share of each criterion's threshold a run may use)")
    for key in ("min_normal_force", "friction_margin", parameter):
        if key in (contact_options or {}):
            _fail(f"contact_options['{key}']: pass it as find_executable_margin's own argument")
    if phases is not None and contacts is not None:
        _fail("contacts and phases: give one (phases carry their own contacts)")
    contacts = list(sim.contacts if contacts is None else contacts)
    run_options = dict(run_options or {})
    if phases is not None:
        run_options["phases"] = phases
    trials: list[MarginTrial] = []

    def attempt(value: float) -> MarginTrial:
        opts = {"min_normal_force": min_normal_force, "friction_margin": friction_margin}
        opts[parameter] = value
        extra = {k: v for k, v in (contact_options or {}).items() if k not in opts}
        prob = _core.TimeScalingProblem(path, grid=grid)
        if phases is None:
            prob.add_contacts(sim.robot, contacts, cone_edges=cone_edges, drift_tolerance=drift_tolerance, **opts, **extra)
        else:
            prob.add_contact_phases(sim.robot, phases, cone_edges=cone_edges, drift_tolerance=drift_tolerance, **opts,
                                    **extra)
        if configure is not None:
            configure(prob)
        res = prob.solve()
        if not res.ok:
            trial = MarginTrial(opts["min_normal_force"], opts["friction_margin"], res.status.name, math.nan, False, None)
        else:
            out = sim.run(res.trajectory(), **run_options)
            ok = not out.fell and out.worst_criterion[1] <= room
            trial = MarginTrial(opts["min_normal_force"], opts["friction_margin"], res.status.name, res.duration,
                                ok, out)
        trials.append(trial)
        return trial

    lo = attempt(lower)
    if lo.executed:
        return MarginSearch(parameter, lower, lo.duration, lo.duration, trials)
    hi = attempt(upper)
    # Too large a margin leaves no timing at all (the solver reports infeasible): halve the step towards
    # the lower bound until there is one (solves only, no simulation).
    while hi.sim is None and upper - lower > tolerance:
        upper = 0.5 * (lower + upper)
        hi = attempt(upper)
    if not hi.executed:
        return MarginSearch(parameter, None, math.nan, lo.duration, trials)
    a, b, best = lower, upper, hi
    while b - a > tolerance:
        mid = 0.5 * (a + b)
        tr = attempt(mid)
        if tr.executed:
            b, best = mid, tr
        else:
            a = mid
    return MarginSearch(parameter, b, best.duration, lo.duration, trials)
