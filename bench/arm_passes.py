"""Issue 25: how cheap the arm case's reachability analysis can be without polygons (bench/arm_passes.cpp, a
standalone prototype), checked against pathpace on the same grid and the same p', p''.

Corpus: bench/copp.py's case (a) (sweep.py's arms x seeds, URDF velocity limits, acceleration = 2 x velocity,
rest to rest, uniform grid). Per path and N: T of the prototype's relaxed greedy profile θ' (a lower bound on
T*) and of its full greedy profile θ (feasible: an upper bound), against pathpace's certified T; with
--callgrind, the instructions of the two analyses per grid point (valgrind's callgrind, as bench/instructions.py:
this machine exposes no hardware counter).

    .venv/bin/python bench/arm_passes.py                      4 arms x 5 seeds, N = 100, 1000, 10000
    .venv/bin/python bench/arm_passes.py --callgrind --seeds 1
"""

from __future__ import annotations

import argparse
import statistics
import struct
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402
from instructions import Arm, call  # noqa: E402
from sweep import ARMS, waypoints  # noqa: E402


def dump(fn, grid, path, v, A):
    with open(fn, "wb") as f:
        f.write(struct.pack("ii", len(grid) - 1, len(v)))
        for x in (grid, path.dq(grid), path.ddq(grid), v, A):
            f.write(np.ascontiguousarray(x, dtype=np.float64).tobytes())


def instructions(exe, fn):
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp, "cg.out")
        subprocess.run(["valgrind", "--tool=callgrind", "--toggle-collect=*analyses*", f"--callgrind-out-file={out}",
                        exe, fn], check=True, capture_output=True)
        return int(next(l for l in out.read_text().splitlines() if l.startswith("summary:")).split()[1])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--sizes", default="100,1000,10000")
    ap.add_argument("--callgrind", action="store_true")
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        exe = str(Path(tmp, "arm_passes"))
        subprocess.run(["g++", "-O3", "-DNDEBUG", "-std=c++17", str(HERE / "arm_passes.cpp"), "-o", exe], check=True)
        arms = {name: Arm(name) for name in ARMS}
        print("| N | paths | T(θ') / T - 1: median, max | T(θ) / T - 1: median, min, max | (T(θ) - T(θ')) / T(θ') "
              "against pathpace's certified gap: max difference | instructions per grid point: median / max |")
        print("|---|---|---|---|---|---|")
        for N in map(int, args.sizes.split(",")):
            rel, full, bracket_diff, ins = [], [], [], []
            for name, arm in arms.items():
                for seed in range(args.seeds):
                    wp = waypoints(arm, seed)
                    path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
                    grid = np.linspace(0.0, 1.0, N + 1)
                    res = call(arm, path, grid, 0.0)
                    sd = np.asarray(res.sdot)
                    T = float(np.sum(2 * np.diff(grid) / (sd[:-1] + sd[1:])))
                    fn = str(Path(tmp, "in.bin"))
                    dump(fn, grid, path, arm.v, 2.0 * arm.v)
                    out = subprocess.run([exe, fn], capture_output=True, text=True, check=True).stdout.split()
                    T_relaxed, T_full = map(float, out)
                    rel.append(T_relaxed / T - 1)
                    full.append(T_full / T - 1)
                    if res.stats["lp_solves"] == 0:  # proven by the bracket: its gap is the bracket's width
                        bracket_diff.append(abs((T_full - T_relaxed) / T_relaxed - res.stats["gap"]))
                    if args.callgrind:
                        ins.append(instructions(exe, fn) / (N + 1))
            bd = f"{max(bracket_diff):.1e} ({len(bracket_diff)} paths proven by the bracket)" if bracket_diff else "-"
            ic = f"{statistics.median(ins):.0f} / {max(ins):.0f}" if ins else "-"
            print(f"| {N} | {len(rel)} | {statistics.median(rel):+.1e}, {max(rel):+.1e} | {statistics.median(full):+.1e}, "
                  f"{min(full):+.1e}, {max(full):+.1e} | {bd} | {ic} |", flush=True)


if __name__ == "__main__":
    main()
