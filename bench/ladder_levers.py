"""The ladder climb in MuJoCo under one setting of the levers of bench/README.md ("Margins with room", the
session of 2026-12-07): one row per call, the worst criterion against its threshold and each held point's
largest slide.

    .venv/bin/python bench/ladder_levers.py                          # the example's settings (~30-60 s)
    .venv/bin/python bench/ladder_levers.py --ball 0.005 --ff-friction-margin 0   # the settings before
    .venv/bin/python bench/ladder_levers.py --jerk 100 --no-impact   # jerk limits (they need no rest inside)
    .venv/bin/python bench/ladder_levers.py --handover 0.2           # the limb out of the plan near a switch

Defaults are examples/humanoid_ladder.py's (N = SIM_GRID on its phase grid, SIM_MIN_NORMAL_FORCE per point,
motors at TORQUE_SCALE, BALL, CONTACT_TIMECONST, FEEDFORWARD_FRICTION_MARGIN). The levers:
--handover d: the limb about to lift (just landed) is left out of the plan's contacts for the last (first) d of
each shift phase, so the feed-forward unloads it while it still touches; the no-impact rule is then replaced
by ṡ = 0 rows at the real makes (add_contact_phases would put a rest where the limb re-enters the plan).
--rest-at-breaks: ṡ = 0 at each lift-off too. --jerk j: add_jerk_limits(-j, j) on every coordinate (it cannot
take a rest inside the path: use --no-impact). --swing-min-normal-force f, --swing-friction-margin m: the
foot-swing phases' own minimum normal force per point and friction margin.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import common
import pathpace as pp

ladder = common.import_example("humanoid_ladder")


def plan_phases(handover: float, swing_min_normal_force: float | None, swing_friction_margin: float | None = None) -> list[tuple]:
    """The example's phases, with each shift's ends given to the neighbouring swing's support (--handover)."""
    sched, every = ladder.schedule(), ladder.all_contacts()
    without = lambda limb: [c for c in every if c.link != limb]  # noqa: E731
    out = []
    for i, (s0, s1, limb) in enumerate(sched):
        if limb is not None:
            own = {}
            if limb in ladder.FEET and swing_min_normal_force is not None:
                own["min_normal_force"] = swing_min_normal_force
            if limb in ladder.FEET and swing_friction_margin is not None:
                own["friction_margin"] = swing_friction_margin
            out.append((s0, s1, without(limb), own) if own else (s0, s1, without(limb)))
            continue
        prev = sched[i - 1][2] if i > 0 else None
        nxt = sched[i + 1][2] if i + 1 < len(sched) else None
        a0 = s0 + handover if prev and handover else s0
        a1 = s1 - handover if nxt and handover else s1
        if a0 > s0:
            out.append((s0, a0, without(prev)))
        out.append((a0, a1, without(None)))
        if a1 < s1:
            out.append((a1, s1, without(nxt)))
    return out


def grid_for(phases: list[tuple], n: int) -> np.ndarray:
    """About n intervals, in proportion to each phase's length, every switch a grid point."""
    bounds = np.array([p[0] for p in phases] + [phases[-1][1]])
    per = np.maximum(1, np.round(n * np.diff(bounds) / (bounds[-1] - bounds[0])).astype(int))
    return np.concatenate([np.linspace(a, b, m + 1)[:-1] for a, b, m in zip(bounds[:-1], bounds[1:], per)] + [bounds[-1:]])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--grid", type=int, default=ladder.SIM_GRID)
    ap.add_argument("--min-normal-force", type=float, default=ladder.SIM_MIN_NORMAL_FORCE)
    ap.add_argument("--ball", type=float, default=ladder.BALL)
    ap.add_argument("--contact-timeconst", type=float, default=ladder.CONTACT_TIMECONST)
    ap.add_argument("--impratio", type=float, default=1.0)
    ap.add_argument("--ff-friction-margin", type=float, default=ladder.FEEDFORWARD_FRICTION_MARGIN)
    ap.add_argument("--handover", type=float, default=0.0)
    ap.add_argument("--rest-at-breaks", action="store_true")
    ap.add_argument("--no-impact", action="store_true", help="no rest at the makes (add_contact_phases' rule off)")
    ap.add_argument("--jerk", type=float, default=None)
    ap.add_argument("--swing-min-normal-force", type=float, default=None)
    ap.add_argument("--swing-friction-margin", type=float, default=None, help="the foot-swing phases' own friction margin")
    ap.add_argument("--torque-noise", type=float, default=0.0)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()

    ladder.BALL = a.ball  # read at call time by the path, the rungs' contact data and the simulator
    robot = ladder.talos_sway.load_talos()
    path = ladder.climb_path(robot)
    phases = plan_phases(a.handover, a.swing_min_normal_force, a.swing_friction_margin)
    plain = a.handover == 0
    grid = ladder.phase_grid(a.grid) if plain else grid_for(phases, a.grid)
    prob = pp.TimeScalingProblem(path, grid=grid)
    options = dict(ladder.MARGINS, min_normal_force=a.min_normal_force, torque_scale=ladder.TORQUE_SCALE)
    own_rests = a.handover > 0 or a.no_impact
    t0 = time.perf_counter()
    prob.add_contact_phases(robot, phases, drift_tolerance=ladder.DRIFT,
                            impact_tolerance=1e9 if own_rests else 1e-6, **options)
    sched = ladder.schedule()
    rest = ([s1 for s0, s1, limb in sched if limb is not None] if a.handover > 0 and not a.no_impact else [])
    rest += [s0 for s0, s1, limb in sched if limb is not None] if a.rest_at_breaks else []
    if rest:  # ṡ² <= 0 at those grid points
        A = np.zeros((grid.size, 1))
        A[[int(np.argmin(np.abs(grid - s))) for s in rest], 0] = 1.0
        hi = np.where(A > 0, 0.0, np.inf)
        prob.add_linear_constraint(A, np.zeros_like(A), np.zeros_like(A), np.full_like(A, -np.inf), hi, label="rest")
    if a.jerk is not None:
        j = np.full(robot.nq, a.jerk)
        prob.add_jerk_limits(-j, j)
    res = prob.solve()
    plan = time.perf_counter() - t0
    setting = " ".join(f"{k}={v}" for k, v in vars(a).items())
    if not res.ok:
        print(f"{setting}: {res.status.name} after {plan:.1f} s: {res.message}")
        return
    sim = ladder.simulator(robot, path, contact_timeconst=a.contact_timeconst, impratio=a.impratio)
    t0 = time.perf_counter()
    r = sim.run(res.trajectory(), phases=ladder.phases(), feedforward_friction_margin=a.ff_friction_margin,
                torque_noise=a.torque_noise, seed=a.seed)
    crit, ratio = r.worst_criterion
    slides = 1e3 * np.nan_to_num(r.slip, nan=0.0).max(axis=0)
    rests = int(np.sum(np.asarray(res.sdot)[1:-1] == 0.0))
    print(f"{setting}: N = {grid.size - 1}, T = {res.duration:.3f} s, {rests} rests inside; {ladder._verdict(r)}, worst "
          f"{crit} {ratio:.2f} ({', '.join(f'{k} {v:.2f}' for k, v in r.criterion_ratios.items())}); slide per point "
          f"(mm; left sole, right sole, left hand, right hand): {np.round(slides, 1).tolist()}; plan {plan:.1f} s, "
          f"simulation {time.perf_counter() - t0:.0f} s", flush=True)


if __name__ == "__main__":
    main()
