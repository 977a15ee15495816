"""The `pathpace` command: problems from files, checks, pictures and a demo.

    pathpace solve problem.yaml --out traj.csv --json result.json      # one problem (YAML or JSON)
    pathpace solve a.yaml b.yaml c.yaml --out-dir results/ --progress   # a batch, in parallel
                                       (--progress: a bar for batches, elapsed time for one long solve)
    pathpace solve waypoints.csv --vmax 1,1 --amax 2,2                  # quick: a waypoint CSV and limits
    pathpace check problem.yaml traj.csv       # audit any trajectory CSV: worst margin per constraint
    pathpace plot problem.yaml --out fig.png   # phase plane, polygons, torques, contacts
    pathpace report problem.yaml --out report.html   # one self-contained HTML page
    pathpace demo                              # a Panda problem file, solved, checked and plotted

Problem files are described in `pathpace.problem_file`. Errors are one line naming the file, key or
argument, with exit code 2; an infeasible problem or a failed check exits with 1.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from types import SimpleNamespace
from typing import NoReturn, Sequence

import numpy as np


class CliError(Exception):
    """A user error: reported as one line by `fail`."""


def fail(message: str) -> NoReturn:
    """The one place an error leaves the CLI: one line on stderr, exit code 2."""
    print(f"pathpace: error: {message}", file=sys.stderr)
    raise SystemExit(2)


class _Parser(argparse.ArgumentParser):
    def error(self, message: str) -> NoReturn:  # argparse's usage errors, also as one line
        # "pathpace: error: solve: ..." (the subcommand, without repeating the program's name)
        sub = self.prog.split(" ", 1)[1] if " " in self.prog else ""
        fail(f"{sub}: {message}" if sub else message)


def _floats(text: str, option: str, n: int) -> np.ndarray:
    """Comma-separated limits, each > 0 and finite; one value stands for all n joints."""
    values = []
    for i, item in enumerate(text.split(",")):
        try:
            v = float(item)
        except ValueError:
            raise CliError(f"{option}[{i}] = {item.strip()!r} is not a number") from None
        if not (np.isfinite(v) and v > 0):
            raise CliError(f"{option}[{i}] = {v} must be > 0 and finite")
        values.append(v)
    if len(values) not in (1, n):
        raise CliError(f"{option} has {len(values)} values, expected 1 or {n} (one per joint)")
    return np.array(values, dtype=float) * np.ones(n)


def _summary(res, name: str = "") -> dict:
    from .io import result_to_dict

    d = {k: v for k, v in result_to_dict(res).items() if k not in ("s", "sdot", "times", "sddot")}
    return ({"problem": name} if name else {}) | d


def _one_line(res, name: str = "") -> str:
    """What a solve prints by default: status, T, N and the solve time; where and why when it failed."""
    st = res.stats
    ms = 1e3 * (st["time_feasible_sets"] + st["time_reachability"] + st["time_slp"])
    head = f"{name}: " if name else ""
    if res.ok:
        line = f"{head}{res.status.name.lower()}, T = {res.duration:.6g} s (N = {len(res.s) - 1}, solved in {ms:.3g} ms)"
        if res.status.name != "OPTIMAL" or res.contact_drift:
            line += f": {res.message}"
        return line
    return f"{head}{res.status.name.lower()}: {res.message}"


def _print_result(res, name: str, stats: bool, indent: int | None = 1) -> None:
    print(json.dumps(_summary(res, name), indent=indent) if stats else _one_line(res, name))


def _check_dt(dt: float) -> None:
    """--dt before any solve: a sample period of 0 is an error found in a second, not after a long solve."""
    if not (np.isfinite(dt) and dt > 0):
        raise CliError(f"--dt = {dt} must be > 0 and finite")


def _urdf_arg(value: str) -> str:
    """--urdf: a file, or "erd:<path>" inside example-robot-data (as in problem files)."""
    if value.startswith("erd:"):
        from .robots import example_robot_urdf

        try:
            return str(example_robot_urdf(value[4:]))
        except FileNotFoundError as e:
            raise CliError(f"argument --urdf: {e}") from None
    if not Path(value).is_file():
        raise CliError(f"argument --urdf: file '{value}' does not exist")
    return value


def _write_outputs(spec, res, out: str | None, json_path: str | None, dt: float, joint_trajectory: str | None) -> None:
    from .io import save_result_json, save_trajectory_csv

    if json_path:
        save_result_json(res, json_path)
    if res.ok:
        traj = res.trajectory()
        if out:
            save_trajectory_csv(traj, out, dt, joint_names=spec.joint_names)
        if joint_trajectory:
            msg = traj.to_joint_trajectory(dt=dt, joint_names=spec.joint_names, robot=spec.robot)
            Path(joint_trajectory).write_text(json.dumps(msg))


def _solve_waypoints(args: argparse.Namespace) -> int:
    """The quick form: a waypoint CSV and limits on the command line."""
    import pathpace as pp

    from .io import load_waypoints_csv

    for option, value in (("--acc-factor", args.acc_factor), ("--torque-scale", args.torque_scale)):
        if not (np.isfinite(value) and value > 0):
            raise CliError(f"{option} = {value} must be > 0 and finite")
    file = args.problems[0]
    try:
        waypoints = load_waypoints_csv(file)
    except OSError as e:
        raise CliError(f"{file}: cannot be read ({e.strerror or e})") from None
    path = pp.CubicSplinePath(waypoints, knots=args.knots)
    prob = pp.TimeScalingProblem(path, grid=args.grid or 1000)
    n = waypoints.shape[1]
    vmax = amax = None
    robot = None
    if args.urdf:
        robot = pp.RobotModel.from_urdf(_urdf_arg(args.urdf), locked_joints=_locked(args.locked_joints))
        vmax = robot.velocity_limits
        amax = args.acc_factor * vmax
    if args.vmax:
        vmax = _floats(args.vmax, "--vmax", n)
    if args.amax:
        amax = _floats(args.amax, "--amax", n)
    if vmax is not None:
        prob.add_velocity_limits(-vmax, vmax)
    if amax is not None:
        prob.add_acceleration_limits(-amax, amax)
    if args.torque:
        if robot is None:
            raise CliError("argument --torque: needs --urdf")
        prob.add_constraint(pp.TorqueLimits(robot, scale=args.torque_scale))
    prob.set_boundary_speeds(*args.boundary_speeds)
    opts = {"tolerance": args.tolerance} if args.tolerance else {}
    res = prob.solve(**opts)
    _print_result(res, Path(file).stem, args.stats)
    names = robot.joint_names if robot is not None and robot.nq == n else [f"joint_{j}" for j in range(n)]
    spec = SimpleNamespace(joint_names=names, robot=robot)
    _write_outputs(spec, res, args.out, args.json, args.dt, args.joint_trajectory)
    return 0 if res.ok else 1


def _locked(items: list[str] | None) -> dict[str, float]:
    out = {}
    for item in items or []:
        name, _, value = item.partition("=")
        try:
            out[name] = float(value or 0.0)
        except ValueError:
            raise CliError(f"argument --locked-joints: '{item}' must be NAME or NAME=VALUE") from None
    return out


def _load(file: str, grid: int | None = None, tolerance: float | None = None):
    from .problem_file import load_problem

    spec = load_problem(file, grid=grid)
    if tolerance:
        spec.solver["tolerance"] = tolerance
    return spec


def cmd_solve(args: argparse.Namespace) -> int:
    _check_dt(args.dt)
    if len(args.problems) == 1 and args.problems[0].lower().endswith(".csv"):
        return _solve_waypoints(args)
    for flag in ("vmax", "amax", "urdf", "torque"):
        if getattr(args, flag):
            raise CliError(f"argument --{flag}: only with a waypoint CSV; a problem file gives its own limits")
    from .batch import solve_many

    specs = [_load(f, args.grid, args.tolerance) for f in args.problems]
    progress = args.progress if args.progress is not None else sys.stderr.isatty()
    if len(specs) == 1:
        from .progress import run_with_progress

        spec = specs[0]
        res = run_with_progress(spec.solve, f"solving {spec.name}", progress)
        _print_result(res, spec.name, args.stats)
        _write_outputs(spec, res, args.out, args.json, args.dt, args.joint_trajectory)
        return 0 if res.ok else 1
    if args.out or args.json or args.joint_trajectory:
        raise CliError("arguments --out/--json/--joint-trajectory: with several problems use --out-dir")
    groups: dict[tuple, list[int]] = {}
    for i, s in enumerate(specs):
        groups.setdefault(tuple(sorted(s.solver.items())), []).append(i)
    results = [None] * len(specs)
    for opts, idx in groups.items():
        for i, r in zip(idx, solve_many([specs[i].problem for i in idx], workers=args.workers, progress=progress,
                                        **dict(opts))):
            results[i] = r
    out_dir = Path(args.out_dir) if args.out_dir else None
    if out_dir:
        out_dir.mkdir(parents=True, exist_ok=True)
    for spec, res in zip(specs, results):
        _print_result(res, spec.name, args.stats, indent=None)
        if out_dir:
            stem = Path(spec.file).stem
            _write_outputs(spec, res, str(out_dir / f"{stem}.csv"), str(out_dir / f"{stem}.json"), args.dt, None)
    return 0 if all(r.ok for r in results) else 1


def cmd_check(args: argparse.Namespace) -> int:
    from .audit import audit_trajectory, load_trajectory_csv

    spec = _load(args.problem)
    traj = load_trajectory_csv(args.trajectory, spec.joint_names)
    rows = audit_trajectory(spec, traj, progress=args.progress if args.progress is not None else sys.stderr.isatty())
    width = max(len(r["constraint"]) for r in rows) if rows else 10
    worst_ok = True
    for r in rows:
        ok = r["margin"] >= -args.tolerance * r["scale"]
        worst_ok &= ok
        where = f" at t = {r['t']:.6g} s" + (f", {r['where']}" if r["where"] else "")
        share = ("(force-distribution margin: the weakest cone weight)" if r["constraint"] == "contact"
                 else f"({100 * r['margin'] / r['scale']:+.3f} % of the limit)")
        print(f"{r['constraint']:<{width}}  worst margin {r['margin']:+.6g} {r['unit']} {share}{where}  "
              f"{'ok' if ok else 'VIOLATED'}")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))
    if not rows:
        print("no constraint to check: the problem file has no limits or contacts")
    return 0 if worst_ok else 1


def _solved(args: argparse.Namespace):
    from .progress import run_with_progress

    spec = _load(args.problem, args.grid, args.tolerance)
    res = run_with_progress(spec.solve, f"solving {spec.name}", sys.stderr.isatty())
    if not res.ok:
        print(_one_line(res, spec.name))
    return spec, res


def cmd_plot(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")  # files only: no display needed
    from . import plot

    import matplotlib.pyplot as plt

    # The format from the suffix, checked before the solve (savefig's own error is a traceback, after it).
    formats = plt.figure().canvas.get_supported_filetypes()
    plt.close("all")
    suffix = Path(args.out).suffix.lower().lstrip(".")
    if suffix not in formats:
        raise CliError(f"argument --out: '{args.out}' has suffix '{suffix}'; supported: "
                       f"{', '.join('.' + f for f in sorted(formats))}")
    spec, res = _solved(args)
    fig = plot.summary_figure(spec, res, polygons_at=args.polygons_at)
    fig.savefig(args.out, dpi=args.dpi)
    print(f"wrote {args.out}")
    return 0 if res.ok else 1


def cmd_report(args: argparse.Namespace) -> int:
    import plotly  # noqa: F401 - before the solve: a missing plotly is an error found in a second

    from .report import write_report

    spec, res = _solved(args)
    write_report(spec, res, args.out)
    print(f"wrote {args.out}")
    return 0 if res.ok else 1


DEMO_PROBLEM = """\
# A Franka Panda through five waypoints (example-robot-data's URDF; the fingers are locked).
name: panda_demo
robot:
  urdf: "erd:panda_description/urdf/panda.urdf"
  locked_joints: {panda_finger_joint1: 0.0, panda_finger_joint2: 0.0}
path:
  waypoints:
%s
grid: 1000
limits:
  velocity: {from: urdf}
  acceleration: {max: %s}
  torque: {from: urdf, scale: 0.9}
boundary: {sdot: [0, 0]}
solver: {tolerance: 1.0e-6}
"""


def cmd_demo(args: argparse.Namespace) -> int:
    from .robots import example_robot_urdf, urdf_joint_limits

    try:
        urdf = example_robot_urdf("panda_description/urdf/panda.urdf")
    except FileNotFoundError as e:
        raise CliError(f"demo: {e}") from None
    joints = [f"panda_joint{i}" for i in range(1, 8)]
    lim = urdf_joint_limits(urdf, joints)
    rng = np.random.default_rng(0)
    w = lim["lower"] + (lim["upper"] - lim["lower"]) * rng.uniform(0.2, 0.8, (5, 7))
    out = Path(args.out_dir)
    out.mkdir(parents=True, exist_ok=True)
    problem = out / "panda_demo.yaml"
    rows = "\n".join("    - [" + ", ".join(f"{x:.6f}" for x in row) + "]" for row in w)
    problem.write_text(DEMO_PROBLEM % (rows, "[" + ", ".join(f"{x:.4f}" for x in 2 * lim["velocity"]) + "]"))
    print(f"problem file: {problem}")
    code = main(["solve", str(problem), "--out", str(out / "panda_demo.csv"), "--json", str(out / "panda_demo.json")])
    if code != 0:
        return code
    print(f"trajectory: {out / 'panda_demo.csv'}; checking it against the problem:")
    code = main(["check", str(problem), str(out / "panda_demo.csv")])
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        print("(matplotlib is not installed: no plot)")
        return code
    main(["plot", str(problem), "--out", str(out / "panda_demo.png")])
    return code


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="pathpace", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    from . import __version__

    parser.add_argument("--version", action="version", version=f"pathpace {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def common(p, grid=True):
        if grid:
            p.add_argument("-N", "--grid", type=int, help="grid intervals (overrides the problem file)")
        p.add_argument("--tolerance", type=float, help="solver tolerance (overrides the problem file)")

    s = sub.add_parser("solve", help="time-optimal timing of one or more problem files (or a waypoint CSV)")
    s.add_argument("problems", nargs="+", help="problem files (.yaml/.yml/.json), or one waypoint CSV")
    common(s)
    s.add_argument("--out", help="trajectory CSV (columns t, q_<joint>, qd_<joint>, qdd_<joint>) sampled every --dt")
    s.add_argument("--json", help="the full result as JSON")
    s.add_argument("--joint-trajectory", help="a JointTrajectory-shaped JSON (the exact timing sampled every --dt)")
    s.add_argument("--dt", type=float, default=0.01, help="sample period of the outputs in s (default 0.01)")
    s.add_argument("--out-dir", help="with several problems: <name>.csv and <name>.json per problem")
    s.add_argument("--workers", type=int, help="threads for several problems (default: all cores)")
    s.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress bar on stderr (default: when stderr is a terminal)")
    s.add_argument("--stats", "-v", action="store_true",
                   help="print the whole result (status, message, solver statistics) as JSON instead of one line")
    q = s.add_argument_group("waypoint CSV only")
    q.add_argument("--knots", default="uniform", choices=["uniform", "chord"],
                   help="spline parameter of the waypoints: uniform (s_k = k / (K-1)) or chord length "
                        "(s proportional to the distance between waypoints) (default uniform)")
    q.add_argument("--vmax", help="velocity limits, comma-separated (one value = all joints)")
    q.add_argument("--amax", help="acceleration limits, comma-separated (one value = all joints)")
    q.add_argument("--urdf", help="robot URDF, or erd:<path> inside example-robot-data: velocity limits from it, and "
                                  "torque limits with --torque")
    q.add_argument("--locked-joints", nargs="*", metavar="NAME[=VALUE]", help="joints of the URDF held fixed")
    q.add_argument("--acc-factor", type=float, default=2.0, help="with --urdf: amax = factor * vmax")
    q.add_argument("--torque", action="store_true", help="add the URDF effort limits (needs --urdf)")
    q.add_argument("--torque-scale", type=float, default=1.0,
                   help="with --torque: the limits are this times the URDF effort (default 1; 0.9 keeps 10 %% in reserve)")
    q.add_argument("--boundary-speeds", nargs=2, type=float, default=(0.0, 0.0), metavar=("SDOT_BEGIN", "SDOT_END"),
                   help="path speed ds/dt in 1/s at the start and the end (default 0 0: rest to rest)")
    s.set_defaults(func=cmd_solve)

    c = sub.add_parser("check", help="audit a trajectory CSV against a problem file: worst margin per constraint")
    c.add_argument("problem")
    c.add_argument("trajectory", help="CSV with t and q_<joint> (or <joint>) columns; qd_, qdd_ optional")
    c.add_argument("--tolerance", type=float, default=1e-3,
                   help="allowed violation relative to each limit (default 1e-3: between grid points a timing at "
                        "N = 1000 exceeds the limits by O(Δs²), about 1e-4)")
    c.add_argument("--json", help="write the audit as JSON")
    c.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None)
    c.set_defaults(func=cmd_check)

    p = sub.add_parser("plot", help="phase plane, polygons, torques and contacts of a solved problem (PNG/PDF/SVG)")
    p.add_argument("problem")
    common(p)
    p.add_argument("--out", default="pathpace.png", help="the figure; its suffix gives the format (.png, .pdf, .svg, ...)")
    p.add_argument("--dpi", type=int, default=120)
    p.add_argument("--polygons-at", type=float, nargs="*", help="s values for the feasible polygons (default: 3)")
    p.set_defaults(func=cmd_plot)

    r = sub.add_parser("report", help="one self-contained HTML page with the plots and a summary")
    r.add_argument("problem")
    common(r)
    r.add_argument("--out", default="pathpace-report.html")
    r.set_defaults(func=cmd_report)

    d = sub.add_parser("demo", help="write, solve, check and plot a Panda problem file")
    d.add_argument("--out-dir", default="pathpace-demo")
    d.set_defaults(func=cmd_demo)
    return parser


#: The extra of pyproject.toml that brings a package the commands import on demand.
_EXTRA_OF = {"matplotlib": "plot", "plotly": "plot", "yaml": "cli", "dask": "batch", "distributed": "batch",
             "mujoco": "sim"}


def main(argv: Sequence[str] | None = None) -> int:
    from ._core import Error
    from .problem_file import ProblemFileError

    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (CliError, ProblemFileError) as e:
        fail(str(e))
    except Error as e:  # pathpace's own errors name the argument, index and value
        fail(f"{args.command}: {e}")
    except OSError as e:
        fail(f"{e.filename or args.command}: {e.strerror or e}")
    except ImportError as e:
        extra = _EXTRA_OF.get((e.name or "").split(".")[0])
        fail(f"{args.command}: needs the Python package '{e.name}' (pip install {e.name}"
             + (f", or pathpace[{extra}])" if extra else ")"))


if __name__ == "__main__":
    raise SystemExit(main())
