"""Talos's two steps with contact phases over a small corpus: audit and MuJoCo execution.

Corpus: examples/humanoid_steps.py's two-step path at step length 6, 10, 14 cm x swing lift 2, 4 cm x
platform 0 (level) and 8 cm (a step up): 12 paths, N = 100. For each: T with margins (50 % friction
margin, 10 N per point) and without, the worst force-distribution margin with the true cones (no
margins) at 1001 times each with its phase's contacts, and, on level ground (pathpace.sim's floor has no
platform), the execution in MuJoCo (fell?, worst deviation of the held sole points from the plan) of both
timings. The sole drift between knots of the IK spline reaches 0.11 mm at a 4 cm lift, hence
drift_tolerance = 2e-4 m. Writes a markdown table and the median / worst of each column to stdout.

    .venv/bin/python bench/humanoid_steps.py [--grid 100]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (first: pins BLAS/OpenMP to one thread before numpy is imported)
import numpy as np  # noqa: E402

hs = common.import_example("humanoid_steps")


def off(r):
    """The held contact points' largest distance from the plan, mm."""
    return 1e3 * max(r["held_xy"], r["held_z"])


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100)
    args = ap.parse_args(argv)
    robot = hs.talos_sway.load_talos()
    print("| step (cm) | lift (cm) | platform (cm) | T margins (s) | T no margins (s) | worst true-cone margin (N) | "
          "margins: fell / held off plan (mm) | no margins: fell / held off plan (mm) | wall (s) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows = []
    for step in (0.06, 0.10, 0.14):
        for lift in (0.02, 0.04):
            for rise in (0.0, 0.08):
                wall = time.perf_counter()
                path = hs.steps_path(robot, step, lift, rise=rise)
                res = {}
                for name, opts in (("margins", hs.CONTACT_OPTIONS), ("bare", dict(cone_edges=8))):
                    res[name] = hs.phase_timing(robot, path, args.grid, drift_tolerance=2e-4, **opts)[1]
                if not (res["margins"].ok and res["bare"].ok):
                    print(f"| {100 * step:g} | {100 * lift:g} | {100 * rise:g} | {res['margins'].status.name} | "
                          f"{res['bare'].status.name} | | | | |")
                    continue
                trajs = [("margins", res["margins"].trajectory()), ("bare", res["bare"].trajectory())]
                audit = hs.audit(trajs[0][1], robot, 10 * args.grid + 1, cone_edges=16)
                sim_cols = "- | -"
                m = b = None
                if rise == 0.0:
                    with contextlib.redirect_stdout(io.StringIO()):
                        sim = {r["timing"]: r for r in hs.simulate(robot, path, trajs)}
                    m, b = sim["margins"], sim["bare"]
                    sim_cols = f"{'fell' if m['fell'] else 'no'} / {off(m):.1f} | {'fell' if b['fell'] else 'no'} / {off(b):.1f}"
                rows.append((trajs[0][1].duration, trajs[1][1].duration, audit["worst"], m, b))
                print(f"| {100 * step:g} | {100 * lift:g} | {100 * rise:g} | {trajs[0][1].duration:.3f} | "
                      f"{trajs[1][1].duration:.3f} | {audit['worst']:.3f} | {sim_cols} | {time.perf_counter() - wall:.1f} |",
                      flush=True)
    if not rows:
        print("\nno path timed with and without margins")
        return
    a = np.array([[r[0], r[1], r[2]] for r in rows])
    simmed = [r for r in rows if r[3] is not None]
    if not simmed:
        print(f"\n{len(rows)} paths timed, none simulated")
        return
    offs = np.array([off(r[3]) for r in simmed])
    print(f"\n{len(rows)} paths timed, worst true-cone margin at 1001 times: median {np.median(a[:, 2]):.3f} N, "
          f"worst {a[:, 2].min():.3f} N; T cost of the margins: median {100 * np.median(a[:, 0] / a[:, 1] - 1):.1f} %, "
          f"worst {100 * np.max(a[:, 0] / a[:, 1] - 1):.1f} %. In MuJoCo ({len(simmed)} level paths): with margins "
          f"{sum(r[3]['fell'] for r in simmed)} fell, held points off plan median {np.median(offs):.1f} mm, worst "
          f"{offs.max():.1f} mm; without margins {sum(r[4]['fell'] for r in simmed)} fell.")


if __name__ == "__main__":
    main()
