"""Builders shared by the Python tests (the independent reference computations are in oracles.py).

Importable from every test folder: tests/python/conftest.py puts this folder on sys.path."""

import concurrent.futures
import multiprocessing

import numpy as np

import pathpace as pp


def process_pool(workers: int = 2) -> concurrent.futures.ProcessPoolExecutor:
    """A process pool whose workers are spawned, not forked. Forking the multi-threaded pytest process (the
    pool's own threads, threads of earlier tests) copies any lock another thread holds at that instant; under
    the sanitizers' allocator a worker then waits on it forever (a CI run hung so, a worker stuck in ASan's
    allocator inside solve())."""
    return concurrent.futures.ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("spawn"))


def kinematic_problem(path, grid, vmin, vmax, amin, amax, **problem_kw):
    """A TimeScalingProblem on `path` (a pp.Path, or waypoints for a pp.CubicSplinePath with its default
    knots and ends) with velocity limits vmin <= q̇ <= vmax (eq. 16) and acceleration limits amin <= q̈ <=
    amax (eq. 14), in the order of oracles.kinematic_rows; a pair given as None is not added. problem_kw go
    to the TimeScalingProblem (grid_tolerance, ...)."""
    if not isinstance(path, pp.Path):
        path = pp.CubicSplinePath(np.asarray(path, dtype=float))
    prob = pp.TimeScalingProblem(path, grid=grid, **problem_kw)
    if vmax is not None:
        prob.add_velocity_limits(vmin, vmax)
    if amax is not None:
        prob.add_acceleration_limits(amin, amax)
    return prob


def two_joint_problem(N=200, vmin=(-1, -1), vmax=(1, 1), **path_kw):
    """Three waypoints in the plane under vmin <= q̇ <= vmax (|q̇| <= 1), |q̈| <= 2, on N intervals; path_kw go
    to the spline."""
    path = pp.CubicSplinePath(np.array([[0.0, 0.0], [1.0, 0.5], [0.2, 1.5]]), **path_kw)
    return kinematic_problem(path, N, list(vmin), list(vmax), [-2, -2], [2, 2])


def random_waypoints(lo, hi, rng):
    """5-8 waypoints (their number drawn first) uniform in 10-90 % of each joint's range [lo, hi]: the paths of
    bench/sweep.py's corpus (which imports it from here) and of test_optimality_corpus.py."""
    return lo + (hi - lo) * rng.uniform(0.1, 0.9, (int(rng.integers(5, 9)), len(lo)))


def random_walk(lo, hi, rng, K):
    """K waypoints of a random walk inside 10-90 % of each joint's range [lo, hi] (the position limits): from
    the middle, steps of 0.2 rad (normal, per joint) reflected at the bounds. The long paths of
    test_optimality_corpus.py and bench/sweep.py (which imports it from here)."""
    lo, hi = lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo)
    q = [0.5 * (lo + hi)]
    for _ in range(K - 1):
        x = q[-1] + rng.normal(0, 0.2, len(lo))
        x = np.where(x > hi, 2 * hi - x, x)
        q.append(np.clip(np.where(x < lo, 2 * lo - x, x), lo, hi))
    return np.array(q)
