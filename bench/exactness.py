"""Exactness at every grid size (issue 20): OPTIMAL results re-checked at every grid point by an independent
oracle (scipy's spline for p', p''; both adjacent s̈ at each point, eq. 26), as median and worst over a seeded
corpus of random spline paths. Relative violation of a q̈ row: its excess over the limit divided by
max(|limit|, |p'' ṡ²| + |p' s̈|) (with limits twenty decades apart the terms, not the limit, set the rounding).

    .venv/bin/python bench/exactness.py                      # the table in bench/README.md
    .venv/bin/python bench/exactness.py --seeds 5 --N 1e6    # one column
"""

import argparse
import time

import numpy as np
from scipy.interpolate import CubicSpline

import pathpace as pp


def violation(s, sdot, dq, ddq, vmax, amax, amin):
    th = sdot**2
    u = np.diff(th) / (2 * np.diff(s))
    worst = float((np.abs(dq * sdot[:, None]) / vmax - 1).max())
    for ks in (np.arange(len(u)), np.arange(1, len(s))):
        qdd = ddq[ks] * th[ks, None] + dq[ks] * u[:, None]
        terms = np.abs(ddq[ks] * th[ks, None]) + np.abs(dq[ks] * u[:, None])
        d = np.maximum(qdd - amax, amin - qdd)
        worst = max(worst, float(np.max(d / np.maximum(np.maximum(amax, -amin), terms))))
    return worst


def case(seed, N, kind):
    """kind: uniform; spacing (gaps 10^U(-2, 0), normalised: spacings two decades apart); points (N - 1 uniform
    random points: the smallest gap ~1/N^2, below what θ in doubles resolves); mixed (limits over 12-20
    decades, amin != -amax)."""
    rng = np.random.default_rng(seed)
    n, K = int(rng.integers(1, 5)), int(rng.integers(3, 8))
    W = 10.0 ** rng.uniform(-3, 2) * rng.uniform(-1, 1, (K, n))
    if kind == "mixed":
        vmax, amax, amin = 10.0 ** rng.uniform(-3, 9, n), 10.0 ** rng.uniform(-6, 14, n), -(10.0 ** rng.uniform(-6, 14, n))
    else:
        vmax, amax = 10.0 ** rng.uniform(-1, 1, n), 10.0 ** rng.uniform(-1, 1, n)
        amin = -amax
    grid = N
    if kind == "points":
        grid = np.concatenate([[0.0], np.sort(rng.uniform(0, 1, N - 1)), [1.0]])
    elif kind == "spacing":
        gaps = 10.0 ** rng.uniform(-2, 0, N)
        grid = np.concatenate([[0.0], np.cumsum(gaps) / gaps.sum()])
        grid[-1] = 1.0
    prob = pp.TimeScalingProblem(pp.CubicSplinePath(W), grid=grid)
    prob.add_velocity_limits(-vmax, vmax)
    prob.add_acceleration_limits(amin, amax)
    t0 = time.perf_counter()
    r = prob.solve()
    t = time.perf_counter() - t0
    s, sd = np.asarray(r.s), np.asarray(r.sdot)
    sp = CubicSpline(np.linspace(0, 1, K), W)
    v = violation(s, sd, sp(s, 1), sp(s, 2), vmax, amax, amin) if r.status.name == "OPTIMAL" else float("nan")
    return r.status.name, v, t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--base", type=int, default=1000, help="first seed (the corpus: 1000..)")
    ap.add_argument("--N", default="1e4,1e5")
    ap.add_argument("--kinds", default="uniform,spacing,mixed,points")
    a = ap.parse_args()
    print("| grid | N | OPTIMAL | other statuses | violation median | worst | solve s median |")
    print("|---|---:|---:|---|---:|---:|---:|")
    for kind in a.kinds.split(","):
        for N in (int(float(x)) for x in a.N.split(",")):
            out = [case(seed, N, kind) for seed in range(a.base, a.base + a.seeds)]
            v = np.array([o[1] for o in out])
            others = {}
            for o in out:
                if o[0] != "OPTIMAL":
                    others[o[0]] = others.get(o[0], 0) + 1
            ok = np.isfinite(v)
            print(f"| {kind} | {N:.0e} | {ok.sum()}/{len(out)} | {others or '-'} | "
                  f"{np.median(v[ok]) if ok.any() else float('nan'):.1e} | {v[ok].max() if ok.any() else float('nan'):.1e} | "
                  f"{np.median([o[2] for o in out]):.3f} |", flush=True)


if __name__ == "__main__":
    main()
