"""solve_many: threads by default, any concurrent.futures-style executor, and a local Dask cluster of
processes (problems and results travel pickled)."""


import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem, process_pool


def corpus(count, N=100, seed=0):
    """Seeded random 3-joint splines under velocity and acceleration limits."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(count):
        out.append(kinematic_problem(rng.uniform(-1, 1, (5, 3)), N, [-1, -1.5, -2], [1, 1.5, 2], [-2, -3, -4], [2, 3, 4]))
    return out


def test_threads_give_the_sequential_results_in_order(capsys):
    probs = corpus(24)
    expected = [p.solve().duration for p in probs]
    res = pp.solve_many(probs, workers=2, progress=True)
    assert [r.duration for r in res] == expected
    assert "24/24" in capsys.readouterr().err
    res = pp.solve_many(probs, workers=2, tolerance=1e-3)  # solve options are passed on
    assert all(r.ok for r in res)


def test_any_executor_with_submit():
    probs = corpus(10, seed=1)
    expected = [p.solve().duration for p in probs]
    with process_pool(2) as ex:
        res = pp.solve_many(probs, executor=ex, chunksize=3)
    assert [r.duration for r in res] == expected
    assert all(isinstance(r.trajectory(), pp.Trajectory) for r in res)  # the path came back with the result


def test_validation():
    probs = corpus(2)
    with pytest.raises(pp.InvalidInputError, match=r"problems\[1\] is a str, expected a TimeScalingProblem"):
        pp.solve_many([probs[0], "p"])
    with pytest.raises(pp.InvalidInputError, match=r"workers = 0 must be an int >= 1"):
        pp.solve_many(probs, workers=0)
    with pytest.raises(pp.InvalidInputError, match=r"chunksize = 0 must be an int >= 1"):
        pp.solve_many(probs, chunksize=0)
    assert pp.solve_many([]) == []


def test_local_dask_cluster_of_processes_solves_200_paths():
    distributed = pytest.importorskip("distributed")
    probs = corpus(200, N=100, seed=2)
    expected = [p.solve().duration for p in probs]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=40) as cluster, distributed.Client(cluster) as client:
        res = pp.solve_many(probs, executor=client, progress=True)
        worker_pids = set(client.run(lambda: __import__("os").getpid()).values())
    assert len(res) == 200 and all(r.ok for r in res)
    assert [r.duration for r in res] == expected  # the same problems, rebuilt in the workers
    assert len(worker_pids) == 2 and __import__("os").getpid() not in worker_pids
