"""Contact polygons on humanoids (issue 9): exactness over a seeded corpus, false INFEASIBLE, speed, and a
direct transcription for comparison.

The corpus (tests/python/contact_corpus.py): Talos and Romeo (example-robot-data, floating base) on paths
of our own (sway, squat, sway with the left hand on a wall; Talos also carrying a 3 kg box squeezed
between its hands, a free object with robot–robot contacts), 4-32 cone edges, with and without friction
margin, per-point and per-link minimum normal force.

    .venv/bin/python bench/contact_projection.py --part exact [--configs 16] [--grid 100]
        every polygon of `configs` seeded cases against pinocchio + HiGHS support values (64 directions)
    .venv/bin/python bench/contact_projection.py --part solve
        every case at N = 50, 100, 200, 400: statuses, k ⊆ 2k feasibility
    .venv/bin/python bench/contact_projection.py --part speed [--repeat 7]
        Talos, 30 points per sole (60 contacts), N = 100, 8 edges, with margins: projection + solve
    .venv/bin/python bench/contact_projection.py --part transcription [--repeat 3]
        pathpace against a direct transcription (cvxpy + Clarabel, forces as variables, exact cones)
    .venv/bin/python bench/contact_projection.py --part corpus [--edges 4 8 16] [--grids 100 400 1000] [--transcription]
        [--projection full on_demand]
        issue 27's corpus (dense soles, per-point margins, strong leans and squats, binding torque limits):
        LPs and half-planes per point, wall time, T against the direct transcription; median and worst

Timings: median (and worst) of --repeat runs, wall and CPU (thread) time, one thread.
"""

from __future__ import annotations

import argparse
import itertools
import os
import statistics
import sys
import time
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "python"))
import contact_corpus as cc  # noqa: E402

import pathpace as pp  # noqa: E402

MARGINS = {
    "bare": {},
    "fm0.5": {"friction_margin": 0.5},
    "fn5": {"min_normal_force": 5.0},
    "link100": {"min_link_normal_force": 100.0},
    "fm0.3+fn2": {"friction_margin": 0.3, "min_normal_force": 2.0},
}
ROBOTS, KINDS, EDGES = ("talos", "romeo"), ("sway", "squat", "wall"), (4, 8, 16, 32)

_paths = {}


def path_of(robot, kind):
    if (robot, kind) not in _paths:
        h = cc.load(robot)
        _paths[(robot, kind)] = (h, cc.make_path(h, kind))
    return _paths[(robot, kind)]


def timed(fn, repeat):
    wall, cpu, out = [], [], None
    for _ in range(repeat):
        c0, w0 = time.thread_time(), time.perf_counter()
        out = fn()
        wall.append(time.perf_counter() - w0)
        cpu.append(time.thread_time() - c0)
    return wall, cpu, out


def fmt_ms(xs):
    return f"{statistics.median(xs) * 1e3:.1f} ({max(xs) * 1e3:.1f})"


def part_exact(args):
    rng = np.random.default_rng(args.seed)
    cases = list(itertools.product(ROBOTS, KINDS, EDGES, MARGINS))
    pick = rng.choice(len(cases), size=min(args.configs, len(cases)), replace=False)
    print(f"every polygon against the exact projection, N = {args.grid}, 64 directions, seed {args.seed}")
    print("| robot | path | edges | margins | points | empty | worst error / size | status | T (s) |")
    print("|---|---|---:|---|---:|---:|---:|---|---:|")
    worst_all = 0.0
    for i in sorted(pick):
        robot, kind, k, mname = cases[i]
        h, path = path_of(robot, kind)
        cons = cc.contacts(h, kind)
        opts = dict(cone_edges=k, **MARGINS[mname])
        prob = pp.TimeScalingProblem(path, grid=args.grid)
        prob.add_contacts(h.robot, cons, drift_tolerance=1e-4, **opts)
        worst, n, empty = cc.compare(h, prob, cons, opts)
        worst_all = max(worst_all, worst)
        res = prob.solve()
        print(f"| {robot} | {kind} | {k} | {mname} | {n} | {empty} | {worst:.1e} | {res.status.name} | "
              f"{res.duration:.4f} |", flush=True)
    print(f"worst over the corpus: {worst_all:.1e} of the polygon's size")


def part_solve(args):
    print("| N | cases | OPTIMAL | INFEASIBLE | other | k feasible, 2k not | inexact points |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    for N in (50, 100, 200, 400):
        counts = {"OPTIMAL": 0, "INFEASIBLE": 0, "other": 0}
        broken, inexact, total = 0, 0, 0
        notes = []
        for robot, kind, mname in itertools.chain(itertools.product(ROBOTS, KINDS, MARGINS),
                                                  itertools.product(["talos"], ["box"], MARGINS)):
            if kind == "box":
                if ("talos", "box") not in _paths:
                    _paths[("talos", "box")] = cc.box_problem(cc.load("talos"))
                model, path, cons = _paths[("talos", "box")]
            else:
                h, path = path_of(robot, kind)
                model, cons = h.robot, cc.contacts(h, kind)
            ok = {}
            for k in EDGES:
                prob = pp.TimeScalingProblem(path, grid=N)
                prob.add_contacts(model, cons, cone_edges=k, drift_tolerance=1e-4, **MARGINS[mname])
                res = prob.solve()
                total += 1
                inexact += res.stats["inexact_points"]
                name = res.status.name if res.status.name in counts else "other"
                counts[name] += 1
                ok[k] = res.ok
                if not res.ok:
                    notes.append(f"N={N} {robot} {kind} k={k} {mname}: {res.message}")
            broken += sum(ok[k] and not ok[2 * k] for k in (4, 8, 16))
        print(f"| {N} | {total} | {counts['OPTIMAL']} | {counts['INFEASIBLE']} | {counts['other']} | {broken} | {inexact} |",
              flush=True)
        for n in notes[: args.notes]:
            print("   ", n)


def part_speed(args):
    h, path = path_of("talos", "sway")
    print(f"Talos sway (nq = {h.robot.nq}), N = 100, 8 edges, median (worst) of {args.repeat}, ms")
    print("| sole points | margins | LP contacts | projection wall | projection CPU | solve wall | total wall | "
          "LPs per point | status, T (s) |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---|")
    configs = [((2, 2), {"friction_margin": 0.5, "min_normal_force": 10.0}, "fm0.5 + 10 N per point"),
               ((6, 5), {"friction_margin": 0.5, "min_link_normal_force": 150.0}, "fm0.5 + 150 N per sole"),
               ((6, 5), {"friction_margin": 0.5, "min_normal_force": 5.0}, "fm0.5 + 5 N per point"),
               ((6, 5), {}, "none")]
    for grid, margins, label in configs:
        cons = cc.contacts(h, "sway", grid=grid)
        cons_obj = pp.ContactConstraint(h.robot, cons, cone_edges=8, **margins)

        def build():
            prob = pp.TimeScalingProblem(path, grid=100)
            prob.add_contacts(h.robot, cons, cone_edges=8, drift_tolerance=1e-4, **margins)
            return prob

        wb, cb, prob = timed(build, args.repeat)
        ws, cs, res = timed(prob.solve, args.repeat)
        tot = [a + b for a, b in zip(wb, ws)]
        print(f"| {len(cons)} | {label} | {len(cons_obj.projected_contacts)} | {fmt_ms(wb)} | {fmt_ms(cb)} | "
              f"{fmt_ms(ws)} | {fmt_ms(tot)} | {res.stats['projection_lp_solves'] / 101:.1f} | "
              f"{res.status.name} {res.duration:.4f} |", flush=True)


def transcription(h, path, cons, N, margins, fix_theta=None, cone_edges=None, torque_scale=1.0):
    """Direct transcription: θ_k = ṡ², u_k = s̈ per interval, contact forces at both ends of every
    interval (eq. 26's two sides) as variables in each contact's frame, exact second-order friction
    cones, the same torque limits and minimum normal forces; T = Σ 2Δs / (√θ_k + √θ_k+1).
    With `cone_edges`, the forces are pathpace's pyramids instead (f = Σ_e λ_e g_e, λ >= 0, the same
    generators): the same model as pathpace's, so the same optimum."""
    import cvxpy as cp
    import pinocchio as pin
    s = np.linspace(0.0, 1.0, N + 1)
    ds = s[1] - s[0]
    m, n = len(cons), h.robot.nq
    fm = margins.get("friction_margin", 0.0)
    fmin = margins.get("min_normal_force", 0.0)
    flink = margins.get("min_link_normal_force", 0.0)
    off = margins.get("cone_offset", 0.0)  # the shifted cone: f - off·n in the cone
    model, P = h.model, h.perm
    data = model.createData()
    eff = h.robot.effort_limits * torque_scale
    frames = []
    for con in cons:
        nrm = np.asarray(con.normal, float) / np.linalg.norm(con.normal)
        e = np.array([0.0, 1.0, 0.0]) if abs(nrm[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
        t1 = np.cross(nrm, e)
        t1 /= np.linalg.norm(t1)
        frames.append(np.stack([t1, np.cross(nrm, t1), nrm], axis=1))  # local (t1, t2, n) -> world
    theta, u = cp.Variable(N + 1), cp.Variable(N)
    sq = cp.Variable(N + 1)
    cst = [theta >= 0, theta[0] == 0, theta[N] == 0, theta[1:] == theta[:-1] + 2 * ds * u, sq <= cp.sqrt(theta)]
    mus = np.tile([c.friction * (1 - fm) for c in cons], N)
    if cone_edges is None:
        F = {side: cp.Variable((3, N * m)) for side in ("+", "-")}
        for side in ("+", "-"):
            cst.append(cp.SOC(cp.multiply(mus, F[side][2, :] - off), F[side][0:2, :], axis=0))
    else:
        # One μ for all contacts here (the corpus's); local generators (μ' cos φ, μ' sin φ, 1).
        assert len({c.friction for c in cons}) == 1
        mu = cons[0].friction * (1 - fm)
        phi = 2 * np.pi * np.arange(cone_edges) / cone_edges
        G = np.stack([mu * np.cos(phi), mu * np.sin(phi), np.ones(cone_edges)])
        lam = {side: cp.Variable((cone_edges, N * m), nonneg=True) for side in ("+", "-")}
        F = {side: G @ lam[side] + np.array([[0.0], [0.0], [off]]) for side in ("+", "-")}
    for side in ("+", "-"):
        if fmin > 0:
            cst.append(F[side][2, :] >= fmin)
    links = sorted({c.link for c in cons})
    for k in range(N + 1):
        qp, dqp, ddqp = (np.empty(n) for _ in range(3))
        qp[P], dqp[P], ddqp[P] = path.q(s[k]), path.dq(s[k]), path.ddq(s[k])
        cg = pin.computeGeneralizedGravity(model, data, qp)
        a = (pin.rnea(model, data, qp, dqp, ddqp) - cg)[P]
        b = (pin.rnea(model, data, qp, np.zeros(n), dqp) - cg)[P]
        c = cg[P]
        pin.forwardKinematics(model, data, qp)
        pin.updateFramePlacements(model, data)
        JR = []
        for con, R in zip(cons, frames):
            fid = model.getFrameId(con.link)
            J6 = pin.computeFrameJacobian(model, data, qp, fid, pin.LOCAL)
            J = data.oMf[fid].rotation @ (J6[:3] - np.cross(np.asarray(con.point), J6[3:].T).T)
            JR.append((J.T @ R)[P])
        JR = np.hstack(JR)
        for side, (interval, col) in (("+", (k, k)), ("-", (k - 1, k - 1))):
            if interval < 0 or interval >= N:
                continue
            f = F[side][:, col * m:(col + 1) * m]
            tau = a * theta[k] + b * u[interval] + c - JR @ cp.vec(f, order="F")
            act = eff > 0
            cst += [tau[~act] == 0, tau[act] <= eff[act], tau[act] >= -eff[act]]
            if flink > 0:
                for ln in links:
                    idx = [i for i, con in enumerate(cons) if con.link == ln]
                    cst.append(cp.sum(f[2, idx]) >= flink)
    if fix_theta is not None:  # a feasibility check of another solver's timing
        cst.append(theta == fix_theta)
    obj = cp.Minimize(cp.sum(2 * ds * cp.inv_pos(sq[:-1] + sq[1:])))
    prob = cp.Problem(obj, cst)
    prob.solve(solver=cp.CLARABEL)
    # T from the solver's θ with its rest ends at exactly 0, not the objective value. Near rest T is steep in
    # θ: Clarabel's feasibility tolerance leaves θ_0 ~ 5e-9 (√θ_0 ~ 7e-5) and sq <= √θ a little loose, and the
    # end intervals' 2Δs / (sq_k + sq_k+1) then read T up to 4e-5 low (Romeo lean, N = 100).
    th = np.maximum(theta.value, 0.0) if theta.value is not None else None
    if th is not None:
        th[0] = th[-1] = 0.0
    T = float(np.sum(2 * ds / (np.sqrt(th[:-1]) + np.sqrt(th[1:])))) if th is not None else prob.value
    return prob.status, T, prob.solver_stats.solve_time


def part_corpus(args):
    """Issue 27's corpus (contact_corpus.hard_cases): every case x margins x edges x N, one run each;
    per row LPs and half-planes per grid point, wall time of add_contacts + solve; then median and
    worst over the rows. With --transcription, N = 100 rows are also solved by the direct transcription
    with the same pyramids (T to compare) and with exact cones (time to compare)."""
    print(f"issue 27 corpus, seed {args.seed27}, one thread; wall s of add_contacts + solve")
    print("LPs/point by cause: initial directions / edge LPs that found a vertex / edge LPs that certified an edge / "
          "cap growth / cold retries; 'ranged': edges certified by an endpoint's basis, no LP; 'dense': share of the "
          "LPs the dense simplex solved and certified (fallbacks to GLPK in brackets, by cause: pivot cap/small pivot/unbounded/singular/certificate); pivots per LP")
    print("| robot | path | points | torque scale | margins | edges | N | ε | status | T (s) | T - T(ε=0, first mode) | LPs/point | "
          "by cause | ranged/point | dense (fallbacks) | pivots/LP | projection | rounds | "
          "half-planes/point | torque-bound edges | wall (s) | CPU (s) | T direct, pyramids | rel. diff | direct exact cones (s) | speed-up |")
    print("|---|---|---:|---:|---|---:|---:|---:|---|---:|---:|---:|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows = []
    for case in cc.hard_cases(args.seed27):
        if args.robots and case.robot not in args.robots:
            continue
        h = cc.load(case.robot)
        path = cc.make_hard_path(h, case)
        cons = cc.contacts(h, "sway", grid=cc.HARD_GRIDS[case.robot])
        scale = cc.HARD_TORQUE_SCALE[(case.robot, case.kind)]
        exact_T = {}
        for mname, N, k, eps, mode in itertools.product(args.margins, args.grids, args.edges, args.tolerance,
                                                        args.projection):
            margins = {**cc.HARD_MARGINS, **cc.SHIFTED_MARGINS}[mname]

            def run():
                prob = pp.TimeScalingProblem(path, grid=N)
                prob.add_contacts(h.robot, cons, cone_edges=k, drift_tolerance=1e-4, torque_scale=scale,
                                  projection_tolerance=eps, project_on_demand=mode == "on_demand", **margins)
                return prob, prob.solve()

            wall, cpu, (prob, res) = timed(run, args.repeat)
            sets = [prob.feasible_set(i) for i in range(N + 1)]
            hp = [len(fs.halfplanes) for fs in sets]
            labels = [l for fs in sets for l in fs.labels]
            torque = sum("torque" in l for l in labels) / max(len(labels), 1)
            st = res.stats
            row = dict(mode=mode, lps=st["projection_lp_solves"] / (N + 1), hp=statistics.mean(hp),
                       wall=statistics.median(wall), cpu=statistics.median(cpu), T=res.duration,
                       pivots=st["projection_pivots"] / max(st["projection_lp_solves"], 1))
            causes = "/".join(f"{st['projection_lps_' + c] / (N + 1):.1f}"
                              for c in ("initial", "vertex", "certificate", "cap_growth", "cold_retry"))
            dense = (f"{st['projection_lps_dense'] / max(st['projection_lp_solves'], 1):.0%} "
                     f"({st['projection_lps_dense_fallback']}: "
                     + "/".join(str(st['projection_fallback_' + c])
                                for c in ("cap", "small_pivot", "unbounded", "singular", "certificate")) + ")")
            stats_cols = (f"{causes} | {st['projection_ranged_certificates'] / (N + 1):.1f} | {dense} | "
                          f"{row['pivots']:.1f} | {mode} | {st['projection_rounds']}")
            direct = ("", "", "", "")
            if args.transcription and N == 100:
                tp = transcription(h, path, cons, N, margins, cone_edges=k, torque_scale=scale)
                w0 = time.perf_counter()
                transcription(h, path, cons, N, margins, torque_scale=scale)
                wt = time.perf_counter() - w0
                rel = (res.duration - tp[1]) / tp[1]
                row.update(rel=abs(rel), speedup=wt / row["wall"])
                direct = (f"{tp[1]:.6f} {tp[0]}", f"{rel:.1e}", f"{wt:.1f}", f"{wt / row['wall']:.0f}x")
            rows.append(row)
            if eps == 0.0 and mode == args.projection[0]:
                exact_T[(mname, N, k)] = res.duration
            ref = exact_T.get((mname, N, k))
            dT = f"{res.duration - ref:+.2e}" if ref is not None and (eps > 0.0 or mode != args.projection[0]) else ""
            print(f"| {case.robot} | {case.kind} | {len(cons)} | {scale} | {mname} | {k} | {N} | {eps:g} | {res.status.name} | "
                  f"{res.duration:.9f} | {dT} | {row['lps']:.1f} | {stats_cols} | {row['hp']:.1f} | {torque:.0%} | {row['wall']:.3f} | {row['cpu']:.3f} | "
                  + " | ".join(direct) + " |", flush=True)
    for mode in args.projection:
        print(f"\nover the rows, {mode}: median (worst)")
        for key, name, worst in (("lps", "LPs per point", max), ("pivots", "pivots per LP", max),
                                 ("hp", "half-planes per point", max),
                                 ("wall", "wall s", max), ("cpu", "CPU s", max), ("rel", "|T - T direct| / T direct", max),
                                 ("speedup", "speed-up over direct, exact cones", min)):
            xs = [r[key] for r in rows if key in r and r["mode"] == mode]
            if xs:
                print(f"- {name}: {statistics.median(xs):.3g} ({worst(xs):.3g})")


def part_transcription(args):
    print(f"pathpace (8-edge pyramids) vs direct transcription (cvxpy + Clarabel, exact cones), N = {args.grid}, "
          f"median (worst) of {args.repeat}, s")
    print("| robot | path | contacts | margins | pathpace total | transcription total | Clarabel alone | ratio (total) | "
          "T pathpace | T transcription |")
    print("|---|---|---:|---|---:|---:|---:|---:|---:|---:|")
    margins = {"friction_margin": 0.5, "min_link_normal_force": 100.0}
    for robot, kind in itertools.product(ROBOTS, KINDS):
        h, path = path_of(robot, kind)
        cons = cc.contacts(h, kind)

        def ours():
            prob = pp.TimeScalingProblem(path, grid=args.grid)
            prob.add_contacts(h.robot, cons, cone_edges=8, drift_tolerance=1e-4, **margins)
            return prob.solve()

        wp, _, res = timed(ours, max(args.repeat, 5))
        wt, _, tr = timed(lambda: transcription(h, path, cons, args.grid, margins), args.repeat)
        print(f"| {robot} | {kind} | {len(cons)} | fm0.5 + 100 N per link | {statistics.median(wp):.4f} ({max(wp):.4f}) | "
              f"{statistics.median(wt):.2f} ({max(wt):.2f}) | {tr[2]:.2f} | {statistics.median(wt) / statistics.median(wp):.0f}x | "
              f"{res.duration:.4f} {res.status.name} | {tr[1]:.4f} {tr[0]} |", flush=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--part", choices=["exact", "solve", "speed", "transcription", "corpus"], required=True)
    ap.add_argument("--configs", type=int, default=16)
    ap.add_argument("--grid", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--seed", type=int, default=2026)
    ap.add_argument("--notes", type=int, default=10)
    ap.add_argument("--seed27", type=int, default=27, help="corpus: contact_corpus.hard_cases's seed")
    ap.add_argument("--robots", nargs="*", default=None, help="corpus: only these robots")
    ap.add_argument("--margins", nargs="*", default=list(cc.HARD_MARGINS),
                    help="corpus: HARD_MARGINS or SHIFTED_MARGINS names")
    ap.add_argument("--edges", nargs="*", type=int, default=[4, 8], help="corpus: cone edges (16 optional)")
    ap.add_argument("--grids", nargs="*", type=int, default=[100], help="corpus: N (400, 1000 optional)")
    ap.add_argument("--transcription", action="store_true", help="corpus: direct transcription at N = 100")
    ap.add_argument("--projection", nargs="+", choices=["full", "on_demand"], default=["full"],
                    help="corpus: every polygon projected in full, or project_on_demand (each row once per mode)")
    ap.add_argument("--tolerance", nargs="+", type=float, default=[0.0], metavar="EPS",
                    help="corpus: projection_tolerance values (0 = exact, listed first to get T - T(0))")
    args = ap.parse_args()
    if args.part == "corpus" and "--repeat" not in sys.argv:
        args.repeat = 1
    {"exact": part_exact, "solve": part_solve, "speed": part_speed, "transcription": part_transcription,
     "corpus": part_corpus}[args.part](args)


if __name__ == "__main__":
    main()
