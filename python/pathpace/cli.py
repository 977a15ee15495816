"""The `pathpace` command: time a path given as a waypoint CSV under joint limits.

    pathpace solve waypoints.csv --vmax 1,1 --amax 2,2 -N 1000 --out traj.csv --dt 0.01 --json result.json
    pathpace solve waypoints.csv --urdf robot.urdf --acc-factor 2 --torque
"""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np


class _UsageError(Exception):
    """A bad command-line value: reported on one line, exit status 2."""


def _floats(text: str, option: str, n: int) -> np.ndarray:
    """Comma-separated limits, each > 0 and finite; one value stands for all n joints."""
    values = []
    for i, item in enumerate(text.split(",")):
        try:
            v = float(item)
        except ValueError:
            raise _UsageError(f"{option}[{i}] = {item.strip()!r} is not a number") from None
        if not (np.isfinite(v) and v > 0):
            raise _UsageError(f"{option}[{i}] = {v} must be > 0 and finite")
        values.append(v)
    if len(values) not in (1, n):
        raise _UsageError(f"{option} has {len(values)} values, expected 1 or {n} (one per joint)")
    return np.array(values, dtype=float) * np.ones(n)


def _solve(args: argparse.Namespace) -> int:
    import pathpace as pp
    from .io import load_waypoints_csv, result_to_dict, save_result_json, save_trajectory_csv

    for option, value in (("--acc-factor", args.acc_factor), ("--torque-scale", args.torque_scale), ("--dt", args.dt)):
        if not (np.isfinite(value) and value > 0):
            raise _UsageError(f"{option} = {value} must be > 0 and finite")
    waypoints = load_waypoints_csv(args.waypoints)
    path = pp.CubicSplinePath(waypoints, knots=args.knots)
    prob = pp.TimeScalingProblem(path, grid=args.N)
    n = waypoints.shape[1]
    vmax = amax = None
    robot = None
    if args.urdf:
        robot = pp.RobotModel.from_urdf(args.urdf)
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
            print("--torque needs --urdf", file=sys.stderr)
            return 2
        prob.add_constraint(pp.TorqueLimits(robot, scale=args.torque_scale))
    res = prob.solve()
    summary = {k: v for k, v in result_to_dict(res).items() if k not in ("s", "sdot", "times", "sddot")}
    print(json.dumps(summary, indent=1))
    if args.json:
        save_result_json(res, args.json)
    if args.out and res.ok:
        save_trajectory_csv(res.trajectory(), args.out, args.dt)
    return 0 if res.ok else 1


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="pathpace", description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="time-optimal timing of a waypoint spline")
    s.add_argument("waypoints", help="CSV, one waypoint per row (a header row is skipped)")
    s.add_argument("-N", type=int, default=1000, help="grid intervals (default 1000)")
    s.add_argument("--knots", default="uniform", choices=["uniform", "chord"])
    s.add_argument("--vmax", help="velocity limits, comma-separated (one value = all joints)")
    s.add_argument("--amax", help="acceleration limits, comma-separated (one value = all joints)")
    s.add_argument("--urdf", help="robot URDF: velocity limits from it, and torque limits with --torque")
    s.add_argument("--acc-factor", type=float, default=2.0, help="with --urdf: amax = factor * vmax")
    s.add_argument("--torque", action="store_true", help="add the URDF effort limits (needs --urdf)")
    s.add_argument("--torque-scale", type=float, default=1.0)
    s.add_argument("--out", help="write the trajectory as CSV sampled every --dt")
    s.add_argument("--dt", type=float, default=0.01)
    s.add_argument("--json", help="write the full result as JSON")
    args = parser.parse_args(argv)
    if args.command == "solve":
        import pathpace as pp

        # Bad input (ours, numpy's or the file system's) ends in one line on stderr, not a traceback.
        try:
            return _solve(args)
        except (_UsageError, pp.Error, ValueError, TypeError, OSError) as e:
            print(f"pathpace: error: {e}", file=sys.stderr)
            return 2
    return 2


if __name__ == "__main__":
    raise SystemExit(main())
