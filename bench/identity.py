"""Bit-identity of solves across a refactor (issue 26's "Done when"): every T and status, exactly.

Corpora, all seeded:
  sweep   bench/sweep.py's arms x seeds, case (a) velocity + acceleration and case (b) plus torque at the
          scale sweep.py picks, N = 100, 1000, 10000;
  contact contact_corpus.hard_cases x margins (HARD_MARGINS + SHIFTED_MARGINS) x cone edges 4, 8 x
          projection_tolerance 0, 1e-4, N = 100;
  extra   the paths the pipeline's other stages see: guarantee="continuous" on arms and on two Talos contact
          cases (the audit's slice LPs), restart, contact
          phases (sway on one foot then two), an infeasible torque scale (its status, index and label).

Each row records the status, T as float.hex (infeasible: index, labels, relaxation), and a hash of ṡ's bytes (reported, not required: the issue asks
for T and status). Write a baseline before the change, compare after:

    .venv/bin/python bench/identity.py --write /tmp/identity-before.json
    .venv/bin/python bench/identity.py --compare /tmp/identity-before.json      # exit 1 on any difference

--quick keeps 3 seeds per arm and N <= 1000 (about a minute).
"""

from __future__ import annotations

import argparse
import hashlib
import itertools
import json
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import common  # noqa: E402,F401  (pins BLAS threads before numpy)
import numpy as np  # noqa: E402

import pathpace as pp  # noqa: E402

sys.path.insert(0, str(HERE.parent / "tests" / "python"))
import contact_corpus as cc  # noqa: E402
import sweep  # noqa: E402


def record(res) -> dict:
    sdot = np.ascontiguousarray(np.asarray(res.sdot, float))
    row = dict(status=res.status.name, T=float(res.duration).hex(),
               sdot_hash=hashlib.sha256(sdot.tobytes()).hexdigest()[:16])
    if not res.ok:
        row["index"] = int(res.infeasible_index)
        row["label"] = ",".join(res.binding_constraints)
        row["relaxation"] = {k: float(v).hex() for k, v in res.relaxation.items()}
    return row


def sweep_rows(seeds, sizes):
    for name in sweep.ARMS:
        arm = sweep.Arm(name)
        for seed in range(seeds):
            wp = sweep.waypoints(arm, seed)
            scale = sweep.torque_scale(arm, seed)
            for case, N in itertools.product(("a", "b"), sizes):
                if case == "b" and scale is None:
                    continue
                _, _, solve, _ = sweep.make(arm, wp, N, None if case == "a" else scale)
                yield f"sweep/{name}/{seed}/{case}/{N}", record(solve())


def contact_rows(quick):
    cases = cc.hard_cases(27)
    for case in cases[:2] if quick else cases:
        h = cc.load(case.robot)
        path = cc.make_hard_path(h, case)
        cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[case.robot])
        scale = cc.HARD_TORQUE_SCALE[(case.robot, case.kind)]
        margins = {**cc.HARD_MARGINS, **cc.SHIFTED_MARGINS}
        for mname, k, eps in itertools.product(margins, (4, 8), (0.0, 1e-4)):
            prob = pp.TimeScalingProblem(path, grid=100)
            prob.add_contacts(h.robot, cons, cone_edges=k, drift_tolerance=1e-4, torque_scale=scale,
                              projection_tolerance=eps, **margins[mname])
            yield f"contact/{case.robot}/{case.kind}/{mname}/{k}/{eps:g}", record(prob.solve())


def extra_rows():
    arm = sweep.Arm("panda")
    for seed in range(3):
        wp = sweep.waypoints(arm, seed)
        path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
        for guarantee, N in itertools.product(("grid", "continuous"), (50, 400)):
            prob = pp.TimeScalingProblem(path, grid=N)
            prob.add_velocity_limits(-arm.v, arm.v)
            prob.add_acceleration_limits(-2 * arm.v, 2 * arm.v)
            prob.add_torque_limits(arm.ours, scale=0.8)
            yield f"extra/continuous/{seed}/{guarantee}/{N}", record(prob.solve(guarantee=guarantee))
        prob = pp.TimeScalingProblem(path, grid=200)
        prob.add_velocity_limits(-arm.v, arm.v)
        prob.add_acceleration_limits(-2 * arm.v, 2 * arm.v)
        first = prob.solve()
        yield f"extra/restart/{seed}", record(prob.restarted(0.5, float(first.sdot[100])).solve())
        prob = pp.TimeScalingProblem(path, grid=200)
        prob.add_torque_limits(arm.ours, scale=0.05)
        yield f"extra/infeasible/{seed}", record(prob.solve())
    # guarantee="continuous" on contacts: the audit's slice LPs and cut projections (two rows of the
    # continuous bench's corpus).
    for case in cc.hard_cases(27):
        if case.robot != "talos":
            continue
        h = cc.load("talos")
        cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS["talos"])
        mname = "off1.5" if case.kind == "squat" else "fn1.5"
        prob = pp.TimeScalingProblem(cc.make_hard_path(h, case), grid=100)
        prob.add_contacts(h.robot, cons, cone_edges=4, drift_tolerance=1e-4,
                          torque_scale=cc.HARD_TORQUE_SCALE[("talos", case.kind)],
                          **{**cc.HARD_MARGINS, **cc.SHIFTED_MARGINS}[mname])
        yield f"extra/continuous-contacts/talos/{case.kind}/{mname}", record(prob.solve(guarantee="continuous"))
    h = cc.load("talos")
    path = cc.make_path(h, "sway")
    cons = cc.contacts(h, "sway")
    left = [c for c in cons if "left" in c.link]
    prob = pp.TimeScalingProblem(path, grid=80)
    prob.add_contact_phases(h.robot, [(0.0, 0.5, left), (0.5, 1.0, cons)],
                            min_normal_force=20.0, friction_margin=0.1, drift_tolerance=1e-4)
    yield "extra/phases/talos-one-foot", record(prob.solve())
    prob = pp.TimeScalingProblem(path, grid=80)
    prob.add_contact_phases(h.robot, [(0.0, 0.5, cons, {"min_normal_force": 20.0}), (0.5, 1.0, cons)],
                            friction_margin=0.1, drift_tolerance=1e-4, torque_scale=0.6)
    yield "extra/phases/talos-margins", record(prob.solve())


VERDICT = ("status", "T", "index", "label", "relaxation")  # what must be identical


def verdict(row: dict) -> dict:
    return {f: row.get(f) for f in VERDICT}


def sdot_hash(row: dict):
    return row.get("sdot_hash", row.get("theta"))  # baselines written before the key's rename call it "theta"


def main():
    ap = argparse.ArgumentParser()
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", type=Path)
    g.add_argument("--compare", type=Path)
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    seeds, sizes = (3, (100, 1000)) if args.quick else (20, sweep.SIZES)
    rows = {}
    for gen in (sweep_rows(seeds, sizes), contact_rows(args.quick), extra_rows()):
        for key, row in gen:
            rows[key] = row
            print(key, row, flush=True)
    if args.write:
        args.write.write_text(json.dumps(rows, indent=1, sort_keys=True))
        print(f"{len(rows)} rows written to {args.write}")
        return 0
    before = json.loads(args.compare.read_text())
    differ = [k for k in rows if k in before and verdict(before[k]) != verdict(rows[k])]
    sdot = [k for k in rows if k in before and sdot_hash(before[k]) != sdot_hash(rows[k])]
    missing = [k for k in before if k not in rows] if not args.quick else []
    print(f"{len(rows)} rows: {len(differ)} differ in T/status, {len(sdot)} in ṡ bytes, {len(missing)} missing")
    for k in differ[:20]:
        print("  DIFFER", k, before[k], rows[k])
    for k in sdot[:5]:
        print("  sdot", k)
    return 1 if differ or missing else 0


if __name__ == "__main__":
    sys.exit(main())
