"""Issue 21, deliver 1: the centred force distribution against the LP vertex on the Talos and Romeo sways
(tests/python/test_force_centre.py's cases): worst force steps at 1 kHz as fractions of the weight, the
smallest physical slack, and the cost per sample.

    .venv/bin/python bench/force_centre.py      # ~1 min
"""

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests/python"))
import test_force_centre as fc  # noqa: E402


def main():
    print("| robot | min normal force (N), friction margin | T (s) | distribution | step inside an interval | "
          "link step - total step at a grid time | smallest slack (N) | centred | ms per sample |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|")
    for name, margins in fc.CASES:
        h, cons, traj, t, _, _ = fc.timed(name, margins)
        weight = h.robot.mass * 9.81
        for dist in ("vertex", "centre"):
            best = np.inf
            for _ in range(3):
                t0 = time.perf_counter()
                cf = traj.contact_forces(t, distribution=dist)
                best = min(best, time.perf_counter() - t0)
            w = traj.contact_wrenches(t, distribution=dist)
            inside, excess, _ = fc.jumps(traj, t, cf.forces, w.force)
            print(f"| {name} | {margins[0]:g}, {margins[1]:g} | {traj.duration:.3f} | {dist} | {inside / weight:.4f} | "
                  f"{excess / weight:.3f} | {np.min(cf.slack):.2f} | {np.mean(cf.centred) * 100:.0f} % | "
                  f"{best / t.size * 1e3:.3f} |")


if __name__ == "__main__":
    main()
