"""pathpace's jerk limits (add_jerk_limits) against copp's TOPP3-LP and TOPP3-SOCP (copp-py) on bench/sweep.py's
corpus arms: URDF velocity limits v, acceleration limits a = 2 v, jerk limits j = F a per second (F = 10 by
default, within the issue's 5-20), rest to rest, uniform grid of N intervals. Identical inputs: the same grid
and p, p', p'', p''' sampled from pathpace's not-a-knot spline (copp takes sampled derivatives; p''' as the
slope of p'' between the spline's knots). copp's third-order problems are linearised
at its own TOPP2-RA profile, as its README does. Timed by thread CPU time (the machine is shared), one call each.

Each output is checked here, at the grid points, by the same formula: θ = ṡ², b = s̈ at the nodes,
q̇ = p' √θ, q̈ = p'' θ + p' b, q⃛ = √θ (p' b' + 3 p'' b + p''' θ) with b' the difference quotient of b on each
adjacent interval (pathpace's rest intervals, a constant-jerk ramp, have b' = b_1 / (3 Δs) at their moving end:
docs/method.md "Jerk limits"). Worst relative excess over the limits, max over joints and grid points.

    .venv/bin/python bench/jerk.py --N 100 --seeds 3
    .venv/bin/python bench/jerk.py --N 1000 --seeds 1 --arms panda,ur5
"""

import argparse
import statistics
import time

import numpy as np

import pathpace as pp
from sweep import ARMS, Arm, waypoints


def third_derivative(path, s):
    """p''' of the cubic spline: constant on each piece, the slope of its (linear, continuous) p'' between knots
    (the right piece at a knot)."""
    kn = np.asarray(path.knots)
    slopes = np.diff(path.ddq(kn), axis=0) / np.diff(kn)[:, None]
    i = np.clip(np.searchsorted(kn, s, side="right") - 1, 0, len(kn) - 2)
    return slopes[i]


def violations(grid, theta, b, d, v, a, j, rest_ramps):
    """Worst relative excess of velocity, acceleration and jerk at the grid points (0 if within)."""
    q1, q2, q3 = d
    th = np.maximum(theta, 0.0)
    vel = np.abs(q1 * np.sqrt(th)[:, None]) / v
    acc = np.abs(q2 * th[:, None] + q1 * b[:, None]) / a
    ds = np.diff(grid)
    slope = np.diff(b) / ds
    N = len(grid) - 1
    if rest_ramps:
        slope[0] = b[1] / (3 * ds[0])
        slope[-1] = -b[N - 1] / (3 * ds[-1])
    jerk = 0.0
    for k in range(N + 1):
        for sl in ([slope[k - 1]] if k > 0 else []) + ([slope[k]] if k < N else []):
            jk = np.sqrt(th[k]) * (q1[k] * sl + 3 * q2[k] * b[k] + q3[k] * th[k])
            jerk = max(jerk, np.max(np.abs(jk) / j))
    return max(vel.max() - 1, 0.0), max(acc.max() - 1, 0.0), max(jerk - 1, 0.0)


def run(arm, wp, N, F):
    import copp_py as copp

    grid = np.linspace(0.0, 1.0, N + 1)
    path = pp.CubicSplinePath(wp, knots="uniform", boundary="not-a-knot", s_begin=0.0, s_end=1.0)
    v, a = arm.v, 2.0 * arm.v
    j = F * a
    out = {}

    c0 = time.thread_time()
    prob = pp.TimeScalingProblem(path, grid=grid)
    prob.add_velocity_limits(-v, v)
    prob.add_acceleration_limits(-a, a)
    prob.add_jerk_limits(-j, j)
    res = prob.solve()
    cpu = time.thread_time() - c0
    s = np.asarray(res.s)  # its rest intervals are moved to the jerk ramps
    d = (path.dq(s), path.ddq(s), third_derivative(path, s))
    out["pathpace"] = (cpu, res.duration, violations(s, np.asarray(res.sdot) ** 2, np.asarray(res.sddot_points), d,
                                                     v, a, j, True), str(res.status))

    q, dq, ddq, dddq = path.q(grid), path.dq(grid), path.ddq(grid), third_derivative(path, grid)
    for name in ("topp3_lp", "topp3_socp"):
        c0 = time.thread_time()
        robot = copp.Robot(len(v), capacity=N + 1)
        robot.append_s(grid)
        robot.set_q(q, dq, ddq, 0, dddq=dddq)
        robot.add_velocity_limits(v, -v, start_idx_s=0, length=N + 1)
        robot.add_acceleration_limits(a, -a, start_idx_s=0, length=N + 1)
        robot.add_jerk_limits(j, -j, start_idx_s=0, length=N + 1)
        p2 = copp.solver.topp2_ra.Problem(robot.constraints, idx_s_interval=(0, N), a_boundary=(0.0, 0.0))
        a2 = copp.solver.topp2_ra.solve(p2)
        solver = getattr(copp.solver, name)
        p3 = solver.Problem(robot.constraints, np.maximum(a2, 1e-6), idx_s_start=0, a_boundary=(0.0, 0.0),
                            b_boundary=(0.0, 0.0), num_stationary_max=1)
        prof = solver.solve(p3)
        T = copp.interpolation.s_to_t_topp3(grid, prof)[0]
        cpu = time.thread_time() - c0
        out[name] = (cpu, T, violations(grid, np.asarray(prof.a), np.asarray(prof.b), (dq, ddq, dddq), v, a, j, False),
                     "ok")
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--N", default="100")
    ap.add_argument("--arms", default=",".join(ARMS))
    ap.add_argument("--factor", type=float, default=10.0)
    args = ap.parse_args()
    for N in (int(x) for x in args.N.split(",")):
        rows = []
        for name in args.arms.split(","):
            arm = Arm(name)
            for seed in range(args.seeds):
                r = run(arm, waypoints(arm, seed), N, args.factor)
                rows.append(r)
                print(N, name, seed, {k: (f"{c * 1e3:.1f} ms", f"T={T:.4f}", tuple(f"{x:.1e}" for x in vi), st)
                                      for k, (c, T, vi, st) in r.items()}, flush=True)
        ours = [r["pathpace"] for r in rows]
        for name in ("topp3_lp", "topp3_socp"):
            th = [r[name] for r in rows]
            speed = [t[0] / o[0] for o, t in zip(ours, th)]
            dT = [o[1] / t[1] - 1 for o, t in zip(ours, th)]
            print(f"| {N} | {name} | {len(rows)} | {statistics.median(speed):.2f} / {min(speed):.2f} | "
                  f"{1e3 * statistics.median(o[0] for o in ours):.1f} | {1e3 * statistics.median(t[0] for t in th):.1f} | "
                  f"{statistics.median(dT):+.2e} / {max(dT):+.2e} | "
                  f"{max(max(o[2]) for o in ours):.1e} / {max(max(t[2]) for t in th):.1e} |")


if __name__ == "__main__":
    main()
