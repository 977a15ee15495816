"""Problem files (YAML or JSON): everything a time-scaling problem needs, for the CLI and batch runs.

A file names the robot, the path, the limits, the contacts, the grid, the boundary conditions and the
solver options; relative file names are relative to the problem file. Example (YAML)::

    robot:
      urdf: panda.urdf                  # or an example-robot-data path: "erd:panda_description/urdf/panda.urdf"
      locked_joints: {panda_finger_joint1: 0.0, panda_finger_joint2: 0.0}
      floating_base: false
    path:
      waypoints: [[0, 0, 0, -1.5, 0, 1.5, 0], [0.5, 0.3, 0, -1.2, 0, 1.8, 0.4]]   # or waypoints_csv: w.csv
      knots: uniform                    # uniform | chord | [s_0, ..., s_K-1]
      boundary: not-a-knot              # not-a-knot | natural | clamped
      # or samples: {s: [...], q: [[...]], dq: [[...]], ddq: [[...]]}
    grid: 1000                          # intervals, or a list of s
    limits:
      velocity: {from: urdf, scale: 0.9}          # or [v...] (symmetric), or {min: [...], max: [...]}
      acceleration: {max: [10, 10, 10, 10, 10, 10, 10]}
      torque: {from: urdf, scale: 0.9, margin: 0.5}
      frames:                           # Cartesian limits on a point of a link (FrameLimits), by link name
        - link: panda_hand
          point: [0, 0, 0.1]            # link frame, m (default the link origin)
          frame: world                  # axes of the per-axis limits: world | local
          speed: 0.25                   # m/s, translational speed
          velocity: [0.2, 0.2, 0.1]     # m/s per axis (symmetric), or {min: [...], max: [...]}
          acceleration: {max: [2, 2, 2]}  # m/s² per axis; also angular_velocity, angular_acceleration
    contacts:                           # optional: frictional contacts (replaces limits.torque)
      points: [{link: left_sole_link, point: [0.1, 0.05, 0], normal: [0, 0, 1], friction: 0.5}]
      cone_edges: 8
      friction_margin: 0.0
      min_normal_force: 0.0             # also: torque_scale, torque_margin, min_link_normal_force, cone_offset
      drift_tolerance: 1.0e-6           # m a contact point may move along the path; drift: auto | warn | error
      # or phases: [{s: [0, 1], points: [...]}, {s: [1, 2], points: [...], min_normal_force: 5}]
      #            (add_contact_phases: each phase's points, and options over these)
    boundary: {sdot: [0, 0]}            # or {qd_begin: [...], qd_end: [...]}
    solver: {tolerance: 1e-6, method: auto, max_iterations: 100}

Every error is a :class:`ProblemFileError` naming the file and the key.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from . import _core as pp


class ProblemFileError(ValueError):
    """A problem file that cannot be read or does not describe a problem: the message names file and key."""


_TOP_KEYS = {"robot", "path", "grid", "limits", "contacts", "boundary", "solver", "name"}


@dataclass
class ProblemSpec:
    """A problem read from a file: the problem, its robot (or None), joint names and solver options."""

    file: Path
    problem: pp.TimeScalingProblem
    robot: pp.RobotModel | None
    joint_names: list[str]
    solver: dict[str, Any] = field(default_factory=dict)
    velocity_limits: tuple[np.ndarray, np.ndarray] | None = None
    acceleration_limits: tuple[np.ndarray, np.ndarray] | None = None
    torque_limits: pp.TorqueLimits | None = None
    #: the FrameLimits of limits.frames, in file order
    frame_limits: list = field(default_factory=list)
    contacts: pp.ContactConstraint | None = None
    #: (s_begin, s_end, contacts[, options]) per phase when the file gives contacts.phases
    contact_phases: list | None = None
    name: str = ""

    def solve(self) -> pp.Result:
        return self.problem.solve(**self.solver)


def read_mapping(file: str | os.PathLike) -> dict[str, Any]:
    """The file's top-level mapping (YAML if the name ends in .yaml/.yml, else JSON)."""
    path = Path(file)
    try:
        text = path.read_text()
    except OSError as e:
        raise ProblemFileError(f"{path}: cannot be read ({e.strerror or e})") from None
    try:
        if path.suffix.lower() in (".yaml", ".yml"):
            try:
                import yaml
            except ImportError:
                raise ProblemFileError(f"{path}: reading a YAML problem file needs pyyaml: pip install pyyaml "
                                       "(or pathpace[cli]); a JSON problem file needs nothing") from None

            data = yaml.safe_load(text)
        else:
            data = json.loads(text)
    except ProblemFileError:
        raise
    except Exception as e:  # noqa: BLE001 - any parser error becomes one line naming the file
        raise ProblemFileError(f"{path}: not valid {'YAML' if path.suffix.lower() in ('.yaml', '.yml') else 'JSON'}: "
                               f"{str(e).splitlines()[0]}") from None
    if not isinstance(data, dict):
        raise ProblemFileError(f"{path}: expected a mapping at the top level, got {type(data).__name__}")
    return data


class _Reader:
    def __init__(self, file: Path):
        self.file = file

    def fail(self, key: str, msg: str) -> ProblemFileError:
        return ProblemFileError(f"{self.file}: key '{key}': {msg}")

    def mapping(self, value: Any, key: str, allowed: set[str] | None = None) -> dict[str, Any]:
        if not isinstance(value, dict):
            raise self.fail(key, f"expected a mapping, got {type(value).__name__}")
        if allowed is not None:
            extra = sorted(set(value) - allowed)
            if extra:
                raise self.fail(f"{key}.{extra[0]}", f"unknown key (allowed: {', '.join(sorted(allowed))})")
        return value

    def array(self, value: Any, key: str, ndim: int, size: int | None = None, per: str = "one per joint") -> np.ndarray:
        if ndim == 2 and isinstance(value, (list, tuple)) and value and all(isinstance(v, (list, tuple)) for v in value):
            for i, row in enumerate(value):  # ragged rows: name the first that differs from row 0
                if len(row) != len(value[0]):
                    raise self.fail(f"{key}[{i}]", f"has {len(row)} entries, row 0 has {len(value[0])}")
        try:
            a = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            raise self.fail(key, "expected numbers") from None
        if ndim == 1 and a.ndim == 0 and size is not None:
            a = np.full(size, float(a))
        if a.ndim != ndim:
            raise self.fail(key, f"expected a {ndim}-D array of numbers, got shape {a.shape}")
        if size is not None and a.shape[-1] != size:
            raise self.fail(key, f"has {a.shape[-1]} entries per row, expected {size} ({per})")
        return a

    def number(self, value: Any, key: str) -> float:
        if isinstance(value, str):  # YAML 1.1 reads 1e-6 (no dot) as a string
            try:
                return float(value)
            except ValueError:
                pass
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.fail(key, f"expected a number, got {value!r}")
        return float(value)

    def file_path(self, value: Any, key: str) -> Path:
        if not isinstance(value, str):
            raise self.fail(key, f"expected a file name, got {value!r}")
        if value.startswith("erd:"):
            from .robots import example_robot_urdf

            try:
                return example_robot_urdf(value[4:])
            except FileNotFoundError as e:
                raise self.fail(key, str(e)) from None
        p = Path(value)
        p = p if p.is_absolute() else self.file.parent / p
        if not p.is_file():
            raise self.fail(key, f"file '{p}' does not exist")
        return p


def _wrap(reader: _Reader, key: str, fn, *args, **kwargs):
    """Calls into pathpace; its InvalidInputError (naming the argument) is reported under `key`."""
    try:
        return fn(*args, **kwargs)
    except pp.Error as e:
        raise reader.fail(key, str(e)) from None


def _limits(r: _Reader, value: Any, key: str, n: int, urdf_values: np.ndarray | None, name: str,
            per: str = "one per joint"):
    """(min, max) from a list (symmetric), {min, max}, or {from: urdf, scale}."""
    if isinstance(value, dict):
        r.mapping(value, key, {"min", "max", "from", "scale"})
        scale = r.number(value.get("scale", 1.0), f"{key}.scale")
        if "from" in value:
            if value["from"] != "urdf":
                raise r.fail(f"{key}.from", f"expected 'urdf', got {value['from']!r}")
            if urdf_values is None:
                raise r.fail(f"{key}.from", f"'urdf' needs a robot (key 'robot') with {name} limits")
            hi = scale * urdf_values
            return -hi, hi
        if "max" not in value:
            raise r.fail(key, "expected 'max' (and optionally 'min'), or 'from: urdf'")
        hi = scale * r.array(value["max"], f"{key}.max", 1, n, per)
        lo = -hi if "min" not in value else scale * r.array(value["min"], f"{key}.min", 1, n, per)
        return lo, hi
    if value == "urdf":
        return _limits(r, {"from": "urdf"}, key, n, urdf_values, name)
    hi = r.array(value, key, 1, n, per)
    return -hi, hi


_FRAME_QUANTITIES = {"speed": "translational_speed", "velocity": "linear_velocity",
                     "angular_velocity": "angular_velocity", "acceleration": "linear_acceleration",
                     "angular_acceleration": "angular_acceleration"}


def _frame_limits(r: _Reader, value: Any, robot: pp.RobotModel | None, prob: pp.TimeScalingProblem,
                  spec: ProblemSpec) -> None:
    """limits.frames: a list of {link, point, frame, speed, velocity, ...}, one FrameLimits per quantity given."""
    if robot is None:
        raise r.fail("limits.frames", "needs a robot (key 'robot')")
    if not isinstance(value, list) or not value:
        raise r.fail("limits.frames", "expected a non-empty list of {link: ..., speed: ...}")
    for i, item in enumerate(value):
        key = f"limits.frames[{i}]"
        fd = r.mapping(item, key, {"link", "point", "frame"} | set(_FRAME_QUANTITIES))
        if not isinstance(fd.get("link"), str):
            raise r.fail(f"{key}.link", f"expected a link name of robot '{robot.name}', got {fd.get('link')!r}")
        point = r.array(fd.get("point", [0.0, 0.0, 0.0]), f"{key}.point", 1)
        frame = fd.get("frame", "world")
        given = [k for k in _FRAME_QUANTITIES if k in fd]
        if not given:
            raise r.fail(key, f"expected at least one of {', '.join(_FRAME_QUANTITIES)}")
        for k in given:
            if k == "speed":
                lo, hi = None, r.number(fd[k], f"{key}.speed")
            else:
                lo, hi = _limits(r, fd[k], f"{key}.{k}", 3, None, k, per="one per axis x, y, z")
            c = _wrap(r, f"{key}.{k}", pp.FrameLimits, robot, fd["link"], _FRAME_QUANTITIES[k], lo, hi, frame=frame,
                      point=point)
            _wrap(r, f"{key}.{k}", prob.add_constraint, c)
            spec.frame_limits.append(c)


_CONTACT_OPTIONS = ("friction_margin", "min_normal_force", "torque_scale", "torque_margin", "min_link_normal_force",
                    "cone_offset", "projection_tolerance", "drift_tolerance")


def _contact_points(r: _Reader, points: Any, key: str) -> list:
    if not isinstance(points, list) or not points:
        raise r.fail(key, "expected a non-empty list of contacts")
    out = []
    for i, c in enumerate(points):
        k = f"{key}[{i}]"
        c = r.mapping(c, k, {"link", "point", "normal", "friction", "other_link"})
        if "link" not in c:
            raise r.fail(f"{k}.link", "missing")
        out.append(_wrap(r, k, pp.Contact, str(c["link"]), point=r.array(c.get("point", [0, 0, 0]), f"{k}.point", 1, 3),
                         normal=r.array(c.get("normal", [0, 0, 1]), f"{k}.normal", 1, 3),
                         friction=r.number(c.get("friction", 0.5), f"{k}.friction"), other_link=c.get("other_link")))
    return out


def _contact_options(r: _Reader, cd: dict, key: str) -> dict:
    opts = {k: r.number(cd[k], f"{key}.{k}") for k in _CONTACT_OPTIONS if k in cd}
    if "cone_edges" in cd:
        opts["cone_edges"] = int(r.number(cd["cone_edges"], f"{key}.cone_edges"))
    if "drift" in cd:
        opts["drift"] = cd["drift"]  # auto | warn | error: add_contacts names a bad one
    if "project_on_demand" in cd:
        if not isinstance(cd["project_on_demand"], bool):
            raise r.fail(f"{key}.project_on_demand", f"expected true or false, got {cd['project_on_demand']!r}")
        opts["project_on_demand"] = cd["project_on_demand"]
    return opts


def _contacts(r: _Reader, value: Any, robot: pp.RobotModel, prob: pp.TimeScalingProblem, spec: ProblemSpec) -> None:
    """contacts: {points: [...], options...} (one set for the whole path) or {phases: [{s: [s0, s1],
    points: [...], options...}, ...], options...} (TimeScalingProblem.add_contact_phases: each phase's
    options over the shared ones)."""
    allowed = {"points", "phases", "cone_edges", "drift", "project_on_demand", *_CONTACT_OPTIONS}
    cd = r.mapping(value, "contacts", allowed)
    if ("points" in cd) == ("phases" in cd):
        raise r.fail("contacts", "expected either 'points' (one set of contacts) or 'phases' (contact phases)")
    opts = _contact_options(r, cd, "contacts")
    if "points" in cd:
        # add_contacts checks that the path keeps the contacts in place (check_contact_drift in C++).
        _wrap(r, "contacts", prob.add_contacts, robot, _contact_points(r, cd["points"], "contacts.points"), **opts)
        spec.contacts = [c for c in prob.constraints if isinstance(c, pp.ContactConstraint)][-1]
        return
    phases = cd["phases"]
    if not isinstance(phases, list) or not phases:
        raise r.fail("contacts.phases", "expected a non-empty list of phases")
    out = []
    for i, ph in enumerate(phases):
        key = f"contacts.phases[{i}]"
        ph = r.mapping(ph, key, {"s", "points", "cone_edges", "drift", *_CONTACT_OPTIONS})
        if "s" not in ph:
            raise r.fail(f"{key}.s", "missing: [s_begin, s_end]")
        span = r.array(ph["s"], f"{key}.s", 1, 2)
        own = {k: v for k, v in _contact_options(r, ph, key).items() if k not in ("drift_tolerance", "drift", "cone_edges")}
        for k in ("drift_tolerance", "drift", "cone_edges"):
            if k in ph:
                raise r.fail(f"{key}.{k}", "is one for all phases: give it under 'contacts'")
        points = _contact_points(r, ph.get("points"), f"{key}.points")
        out.append((float(span[0]), float(span[1]), points, own) if own else (float(span[0]), float(span[1]), points))
    _wrap(r, "contacts.phases", prob.add_contact_phases, robot, out, **opts)
    spec.contact_phases = out


def load_problem(file: str | os.PathLike, grid: int | None = None) -> ProblemSpec:
    """Reads a problem file (see the module docstring) into a :class:`ProblemSpec`; `grid` overrides the file's."""
    path = Path(file)
    data = read_mapping(path)
    r = _Reader(path)
    extra = sorted(set(data) - _TOP_KEYS)
    if extra:
        raise r.fail(extra[0], f"unknown key (allowed: {', '.join(sorted(_TOP_KEYS))})")

    robot = None
    if "robot" in data:
        rd = r.mapping(data["robot"], "robot", {"urdf", "locked_joints", "floating_base", "gravity"})
        if "urdf" not in rd:
            raise r.fail("robot.urdf", "missing: the robot's URDF file")
        urdf = r.file_path(rd["urdf"], "robot.urdf")
        locked = rd.get("locked_joints") or {}
        r.mapping(locked, "robot.locked_joints")
        for k, v in locked.items():
            r.number(v, f"robot.locked_joints.{k}")
        gravity = r.array(rd.get("gravity", [0.0, 0.0, -9.81]), "robot.gravity", 1, 3)
        robot = _wrap(r, "robot", pp.RobotModel.from_urdf, urdf, floating_base=bool(rd.get("floating_base", False)),
                      locked_joints={str(k): float(v) for k, v in locked.items()}, gravity=gravity)

    if "path" not in data:
        raise r.fail("path", "missing: waypoints, waypoints_csv or samples")
    pd = r.mapping(data["path"], "path", {"waypoints", "waypoints_csv", "samples", "knots", "boundary", "start_derivative",
                                          "end_derivative"})
    if "samples" in pd:
        sd = r.mapping(pd["samples"], "path.samples", {"s", "q", "dq", "ddq"})
        for k in ("s", "q", "dq", "ddq"):
            if k not in sd:
                raise r.fail(f"path.samples.{k}", "missing")
        s = r.array(sd["s"], "path.samples.s", 1)
        q = r.array(sd["q"], "path.samples.q", 2)
        path_obj = _wrap(r, "path.samples", pp.SampledPath, s, q, r.array(sd["dq"], "path.samples.dq", 2),
                         r.array(sd["ddq"], "path.samples.ddq", 2))
    else:
        if "waypoints_csv" in pd:
            from .io import load_waypoints_csv

            wfile = r.file_path(pd["waypoints_csv"], "path.waypoints_csv")
            w = _wrap(r, "path.waypoints_csv", load_waypoints_csv, wfile)
        elif "waypoints" in pd:
            w = r.array(pd["waypoints"], "path.waypoints", 2)
        else:
            raise r.fail("path", "expected 'waypoints', 'waypoints_csv' or 'samples'")
        knots = pd.get("knots", "uniform")
        if not isinstance(knots, str):
            knots = r.array(knots, "path.knots", 1)
        kw = {}
        for k in ("start_derivative", "end_derivative"):
            if k in pd:
                kw[k] = r.array(pd[k], f"path.{k}", 1, w.shape[1] if w.ndim == 2 else None)
        path_obj = _wrap(r, "path", pp.CubicSplinePath, w, knots=knots, boundary=str(pd.get("boundary", "not-a-knot")), **kw)
    n = path_obj.dof

    joint_names = list(robot.joint_names) if robot is not None else [f"joint_{j}" for j in range(n)]
    if robot is not None and robot.nq != n:
        raise r.fail("path", f"has {n} coordinates, robot '{robot.name}' has {robot.nq} joints ({', '.join(joint_names)}); "
                             "lock the others with robot.locked_joints")

    g = grid if grid is not None else data.get("grid", 1000)
    if isinstance(g, bool) or not isinstance(g, (int, list)):
        raise r.fail("grid", f"expected a number of intervals or a list of s, got {g!r}")
    prob = _wrap(r, "grid", pp.TimeScalingProblem, path_obj, grid=g if isinstance(g, int) else r.array(g, "grid", 1))

    spec = ProblemSpec(file=path, problem=prob, robot=robot, joint_names=joint_names, name=str(data.get("name", path.stem)))
    lim = r.mapping(data.get("limits", {}), "limits", {"velocity", "acceleration", "torque", "frames"})
    if "velocity" in lim:
        lo, hi = _limits(r, lim["velocity"], "limits.velocity", n, None if robot is None else robot.velocity_limits,
                         "velocity")
        names = joint_names if robot is not None else None  # messages then name the joints
        _wrap(r, "limits.velocity", prob.add_constraint, _wrap(r, "limits.velocity", pp.VelocityLimits, lo, hi, names))
        spec.velocity_limits = (lo, hi)
    if "acceleration" in lim:
        lo, hi = _limits(r, lim["acceleration"], "limits.acceleration", n, None, "acceleration")
        names = joint_names if robot is not None else None
        _wrap(r, "limits.acceleration", prob.add_constraint,
              _wrap(r, "limits.acceleration", pp.AccelerationLimits, lo, hi, names))
        spec.acceleration_limits = (lo, hi)
    if "torque" in lim and "contacts" in data:
        raise r.fail("limits.torque", "contacts include the torque limits: give torque_scale/torque_margin under "
                                      "'contacts' instead")
    if "torque" in lim:
        t = lim["torque"]
        if robot is None:
            raise r.fail("limits.torque", "needs a robot (key 'robot')")
        if t is True or t == "urdf":
            t = {}
        t = r.mapping(t, "limits.torque", {"from", "scale", "margin", "min", "max"})
        lo = r.array(t["min"], "limits.torque.min", 1, n) if "min" in t else None
        hi = r.array(t["max"], "limits.torque.max", 1, n) if "max" in t else None
        spec.torque_limits = _wrap(r, "limits.torque", pp.TorqueLimits, robot, lo, hi,
                                   scale=r.number(t.get("scale", 1.0), "limits.torque.scale"),
                                   margin=r.number(t.get("margin", 0.0), "limits.torque.margin"))
        _wrap(r, "limits.torque", prob.add_constraint, spec.torque_limits)
    if "frames" in lim:
        _frame_limits(r, lim["frames"], robot, prob, spec)
    if "contacts" in data:
        if robot is None:
            raise r.fail("contacts", "needs a robot (key 'robot')")
        _contacts(r, data["contacts"], robot, prob, spec)

    if "boundary" in data:
        b = r.mapping(data["boundary"], "boundary", {"sdot", "qd_begin", "qd_end"})
        if "sdot" in b:
            sd = r.array(b["sdot"], "boundary.sdot", 1)
            if sd.shape != (2,):
                raise r.fail("boundary.sdot", f"expected [sdot_begin, sdot_end], got {len(sd)} numbers")
            _wrap(r, "boundary.sdot", prob.set_boundary_speeds, float(sd[0]), float(sd[1]))
        if "qd_begin" in b or "qd_end" in b:
            qb = r.array(b.get("qd_begin", np.zeros(n)), "boundary.qd_begin", 1, n)
            qe = r.array(b.get("qd_end", np.zeros(n)), "boundary.qd_end", 1, n)
            _wrap(r, "boundary", prob.set_boundary_velocities, qb, qe)

    solver = r.mapping(data.get("solver", {}), "solver", {"tolerance", "method", "max_iterations", "initial_trust_region",
                                                          "lp_feasibility_tolerance"})
    for k, v in solver.items():
        if k == "method":
            if v not in ("auto", "slp"):
                raise r.fail("solver.method", f"expected 'auto' or 'slp', got {v!r}")
            spec.solver[k] = v
        elif k == "max_iterations":
            spec.solver[k] = int(r.number(v, f"solver.{k}"))
        else:
            spec.solver[k] = r.number(v, f"solver.{k}")
    return spec
