"""What margin does the simulated Talos need? `find_executable_margin` over a small corpus.

Corpus: the feet-fixed sway of examples/talos_sway.py at three amplitudes (5, 7, 9 cm), each simulated
with three floors (MuJoCo contact time constant 5, 10, 20 ms: stiff to MuJoCo's default) and two
joint-gain levels (full effort at 0.02 rad and at 0.005 rad of error). For each, the bisection on the
minimum normal force (friction margin 0.5, [0, 60] N, 1 N tolerance) and its T cost over the zero-
margin optimum; then the 7 cm sway at time steps 0.25-2 ms. Writes markdown tables to stdout.
`--room` (default 1: a run within every threshold executes) is find_executable_margin's room.

`--part experiments` (issue 21): per humanoid experiment (the Talos and Romeo sways, the Talos stand-up
of examples/humanoid_standup.py, the Talos two steps of examples/humanoid_steps.py with contact phases),
the smallest minimum normal force (friction margin 0.5) whose timing executes *with room* (every
criterion at most half its threshold), T at zero margin and at that margin, and the worst criterion
of the run it found.

    .venv/bin/python bench/sim_margins.py [--grid 100] [--room 1]
    .venv/bin/python bench/sim_margins.py --part experiments [--grid 100] [--ladder]

--ladder adds examples/humanoid_ladder.py's climb (its own N = SIM_GRID and motors at TORQUE_SCALE).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import common  # noqa: E402  (first: pins BLAS/OpenMP to one thread before numpy is imported)
import numpy as np  # noqa: E402

from pathpace.sim import find_executable_margin  # noqa: E402

humanoid_sim = common.import_example("humanoid_sim")
talos_sway = common.import_example("talos_sway")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=100)
    ap.add_argument("--part", choices=["floors", "experiments"], default="floors")
    ap.add_argument("--room", type=float, default=1.0, help="floors: find_executable_margin's room (default 1)")
    ap.add_argument("--ladder", action="store_true", help="experiments: also the ladder climb (~2 min more)")
    args = ap.parse_args(argv)
    if args.part == "experiments":
        return experiments(args)
    robot = talos_sway.load_talos()
    contacts = talos_sway.sole_contacts(4)
    print("| amplitude (cm) | contact time constant (ms) | gains: full effort at (rad) | T, zero margin (s) | "
          "smallest executable min normal force (N) | T (s) | cost | trials | wall (s) |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    found, costs = [], []
    for amplitude in (0.05, 0.07, 0.09):
        path = talos_sway.sway_path(robot, amplitude)
        for timeconst in (0.005, 0.01, 0.02):
            for stiffness_error in (0.02, 0.005):
                sim = humanoid_sim.talos_simulator(robot, path, contacts, contact_timeconst=timeconst,
                                                   stiffness_error=stiffness_error)
                t0 = time.perf_counter()
                out = find_executable_margin(sim, path, contacts, lower=0.0, upper=60.0, tolerance=1.0,
                                             friction_margin=0.5, grid=args.grid, room=args.room)
                wall = time.perf_counter() - t0
                if out.margin is None:
                    margin, T, cost = "none in [0, 60]", "-", "-"
                else:
                    found.append(out.margin)
                    costs.append(out.cost)
                    margin, T, cost = f"{out.margin:.1f}", f"{out.duration:.3f}", f"+{100 * out.cost:.0f} %"
                print(f"| {100 * amplitude:.0f} | {1e3 * timeconst:.0f} | {stiffness_error} | {out.zero_margin_duration:.3f} | "
                      f"{margin} | {T} | {cost} | {len(out.trials)} | {wall:.1f} |", flush=True)
    if found:
        print(f"\nexecutable margin found in {len(found)} of 18 settings: median {np.median(found):.1f} N, "
              f"worst {np.max(found):.1f} N; T cost median +{100 * np.median(costs):.0f} %, worst +{100 * np.max(costs):.0f} %")

    # The same search at other time steps (7 cm, stiff floor, default gains): the closed loop converges.
    path = talos_sway.sway_path(robot, 0.07)
    print("\n| time step (ms) | smallest executable min normal force (N) | T (s) | cost |")
    print("|---:|---:|---:|---:|")
    for dt in (0.00025, 0.0005, 0.001, 0.002):
        sim = humanoid_sim.talos_simulator(robot, path, contacts, timestep=dt)
        out = find_executable_margin(sim, path, contacts, lower=0.0, upper=40.0, tolerance=1.0, friction_margin=0.5,
                                     grid=args.grid, room=args.room)
        if out.margin is None:
            print(f"| {1e3 * dt:g} | none in [0, 40] | - | - |", flush=True)
        else:
            print(f"| {1e3 * dt:g} | {out.margin:.2f} | {out.duration:.3f} | +{100 * out.cost:.0f} % |", flush=True)


def _romeo():
    """Romeo's corner sway (tests/python/contact_corpus.py) and its simulator."""
    import xml.etree.ElementTree as ET

    from pathpace.robots import example_robot_urdf
    from pathpace.sim import Simulator

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
    import contact_corpus as cc

    h = cc.load("romeo")
    urdf = example_robot_urdf(h.urdf)
    mimic = [j.get("name") for j in ET.parse(urdf).getroot().iter("joint") if j.find("mimic") is not None]
    path, cons = cc.make_path(h, "sway"), cc.contacts(h, "sway")
    return path, cons, Simulator(h.robot, urdf, cons, path.q(0.0), locked_joints={n: 0.0 for n in mimic + h.locked})


def experiments(args):
    """Issue 21's table: each experiment's smallest margin with room (see the module docstring)."""
    standup = common.import_example("humanoid_standup")
    steps = common.import_example("humanoid_steps")
    talos = talos_sway.load_talos()
    rows = []
    sway = talos_sway.sway_path(talos)
    feet = talos_sway.sole_contacts(4)
    rows.append(("Talos sway (7 cm)", sway, dict(contacts=feet), humanoid_sim.talos_simulator(talos, sway, feet), None))
    path, cons, sim = _romeo()
    rows.append(("Romeo sway (5 cm)", path, dict(contacts=cons), sim, None))
    up = standup.standup_path(talos)
    weak = standup.TORQUE_SCALE * np.asarray(talos.effort_limits)
    rows.append((f"Talos stand-up (0.25 m squat, motors {standup.TORQUE_SCALE} x)", up, dict(contacts=feet),
                 humanoid_sim.talos_simulator(talos, up, feet, effort_limits=weak),
                 {"torque_scale": standup.TORQUE_SCALE}))
    walk = steps.steps_path(talos, 0.1, 0.03)
    rows.append(("Talos two steps (contact phases)", walk, dict(phases=steps.phases()),
                 humanoid_sim.talos_simulator(talos, walk, steps.phases()[0][2]), None))
    if args.ladder:
        ladder = common.import_example("humanoid_ladder")
        climb = ladder.climb_path(talos)
        # N = ladder.SIM_GRID on its phase grid (every switch a grid point), motors planned at TORQUE_SCALE; its
        # scene (2 ms contacts) and feed-forward (in the plan's friction margin).
        rows.append((f"Talos ladder, 2 rungs, 16 contact changes (N = {ladder.SIM_GRID}, motors {ladder.TORQUE_SCALE} x)",
                     climb, dict(phases=ladder.phases()), ladder.simulator(talos, climb),
                     {"torque_scale": ladder.TORQUE_SCALE, "grid": ladder.phase_grid(ladder.SIM_GRID),
                      "drift_tolerance": ladder.DRIFT,
                      "run_options": {"feedforward_friction_margin": ladder.FEEDFORWARD_FRICTION_MARGIN}}))
    print("| experiment | T at 0 N (s) | 0 N: worst criterion | smallest min normal force with room (N) | "
          "T (s) | cost | worst criterion there | trials | wall (s) |")
    print("|---|---:|---|---:|---:|---:|---|---:|---:|")
    for name, path, where, sim, extra in rows:
        options = dict(lower=0.0, upper=60.0, tolerance=1.0, friction_margin=0.5, grid=args.grid, room=0.5)
        extra = dict(extra or {})
        for key in ("grid", "drift_tolerance", "upper", "run_options"):  # the ladder's own
            if key in extra:
                options[key] = extra.pop(key)
        extra = extra or None
        t0 = time.perf_counter()
        out = find_executable_margin(sim, path, **where, **options, contact_options=extra)
        wall = time.perf_counter() - t0
        zero = out.trials[0]
        worst0 = "no timing" if zero.sim is None else "fell" if zero.sim.fell else "{} {:.2f}".format(*zero.sim.worst_criterion)
        if out.margin is None:
            tried = ", ".join(f"{tr.min_normal_force:g} N: " + ("no timing" if tr.sim is None else "fell" if tr.sim.fell else
                              "{} {:.2f}".format(*tr.sim.worst_criterion)) for tr in out.trials)
            print(f"| {name} | {out.zero_margin_duration:.3f} | {worst0} | none in [0, {options['upper']:g}] | - | - | {tried} | "
                  f"{len(out.trials)} | {wall:.0f} |", flush=True)
            continue
        best = min((t for t in out.trials if t.executed), key=lambda t: t.min_normal_force)
        print(f"| {name} | {out.zero_margin_duration:.3f} | {worst0} | {out.margin:.1f} | {out.duration:.3f} | "
              f"+{100 * out.cost:.1f} % | {best.sim.worst_criterion[0]} {best.sim.worst_criterion[1]:.2f} | {len(out.trials)} | {wall:.0f} |",
              flush=True)


if __name__ == "__main__":
    main()
