"""Instructions per pathpace call on the arm corpus (issue 25): a measure that other processes on a shared machine
do not change, unlike wall or CPU time.

One call = what bench/copp.py times: TimeScalingProblem(path, grid) + add_velocity_limits + add_acceleration_limits
(+ add_torque_limits with --torque) + solve(), from the path object on. Counted by valgrind's callgrind (this
machine's VMs expose no hardware counter to `perf stat -e instructions:u`): the script re-runs itself under
callgrind, collecting only inside functools.reduce, through which each measured call is made (after one uncounted
warm-up call of the same path and grid), and dumping the count after each; so one count per path and N, Python's
own work in the call included (argument conversion, the Result object).

    .venv/bin/python bench/instructions.py                    4 arms x 5 seeds, N = 100, 1000, 10000
    .venv/bin/python bench/instructions.py --json out.json    also the per-path counts
"""

from __future__ import annotations

import argparse
import functools
import json
import os
import statistics
import subprocess
import tempfile
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402
from pathpace.robots import example_robot_urdf  # noqa: E402
from sweep import ARMS, waypoints  # noqa: E402


class Arm:
    """sweep.Arm without pinocchio (not needed here, and slow to import under callgrind)."""

    def __init__(self, name):
        urdf, lock = ARMS[name]
        self.name = name
        self.ours = pp.RobotModel.from_urdf(str(example_robot_urdf(urdf)), locked_joints={n: 0.0 for n in lock})
        self.lo, self.hi = self.ours.position_limits
        self.v = np.asarray(self.ours.velocity_limits, float)


def call(arm, path, grid, torque):
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(-arm.v, arm.v)
    prob.add_acceleration_limits(-2.0 * arm.v, 2.0 * arm.v)
    if torque:
        prob.add_torque_limits(arm.ours, torque)
    return prob.solve()


def measure(args):
    """Under callgrind: the calls, one reduce() each, their order written to args.order."""
    order = []
    for name in args.arms.split(","):
        arm = Arm(name)
        for seed in range(args.seeds):
            wp = waypoints(arm, seed)
            path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
            for N in map(int, args.sizes.split(",")):
                grid = np.linspace(0.0, 1.0, N + 1)
                res = call(arm, path, grid, args.torque)  # warm-up, not counted
                functools.reduce(lambda _, __: call(arm, path, grid, args.torque), [0], None)
                order.append({"arm": name, "seed": seed, "N": N, "status": str(res.status), "T": res.duration})
    Path(args.order).write_text(json.dumps(order))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--arms", default=",".join(ARMS))
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--sizes", default="100,1000,10000")
    ap.add_argument("--torque", type=float, default=0.0, help="torque limits at this x effort (0: none)")
    ap.add_argument("--json")
    ap.add_argument("--order", help=argparse.SUPPRESS)  # set when running under callgrind
    args = ap.parse_args()
    if args.order:
        return measure(args)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        order = os.path.join(tmp, "order.json")
        subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no", "--toggle-collect=functools_reduce",
                        "--dump-after=functools_reduce", f"--callgrind-out-file={out}", sys.executable,
                        os.path.abspath(__file__), "--order", order] + sys.argv[1:], check=True,
                       stderr=subprocess.DEVNULL)
        rows = json.loads(Path(order).read_text())
        dumps = sorted((f for f in os.listdir(tmp) if f.startswith("cg.out.")), key=lambda f: int(f.rsplit(".", 1)[1]))
        assert len(dumps) == len(rows), (len(dumps), len(rows))
        for r, f in zip(rows, dumps):
            text = Path(tmp, f).read_text()
            r["instructions"] = int(next(l for l in text.splitlines() if l.startswith("summary:")).split()[1])
    print(f"{'N':>6} {'median':>12} {'worst':>12}  (instructions per call, {len(rows) // len(args.sizes.split(','))} paths)")
    for N in map(int, args.sizes.split(",")):
        c = [r["instructions"] for r in rows if r["N"] == N]
        print(f"{N:>6} {statistics.median(c):>12.0f} {max(c):>12.0f}")
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
