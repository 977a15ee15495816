"""Many problems at once: ``solve_many`` on threads (the solve releases the GIL) or on any
``concurrent.futures``-style executor, e.g. a Dask ``distributed.Client`` or Ray, across machines."""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Iterable

from ._core import InvalidInputError, Result, TimeScalingProblem
from .progress import ProgressBar


def _solve_chunk(problems: list[TimeScalingProblem], options: dict[str, Any]) -> list[Result]:
    """Runs on the worker: module-level so that process and cluster executors can pickle it."""
    return [p.solve(**options) for p in problems]


def solve_many(
    problems: Iterable[TimeScalingProblem],
    executor: Any = None,
    workers: int | None = None,
    progress: bool = False,
    chunksize: int | None = None,
    **solve_options: Any,
) -> list[Result]:
    """Solves every problem; results in the order of `problems`.

    Parameters
    ----------
    problems : iterable of TimeScalingProblem
    executor : object with ``submit(fn, *args)`` returning futures with ``result()`` (and ``done()``), optional
        None: a thread pool of `workers` threads in this process (``solve`` releases the GIL, so threads run
        in parallel). A ``concurrent.futures.ProcessPoolExecutor``, a Dask ``distributed.Client`` or a Ray
        adapter (see the README) runs them in other processes or machines: problems and results are
        pickled (a problem is rebuilt there from its path, grid, constraints and boundary speeds).
    workers : int, optional
        Threads of the default pool (default: ``os.cpu_count()``); ignored with an executor.
    progress : bool
        Draw a progress bar on stderr.
    chunksize : int, optional
        Problems per task. Default: 1 on threads; with an executor, enough to make about 4 tasks per
        worker-sized share (at most 64 tasks in flight per 1000 problems), which amortises pickling.
    **solve_options
        Passed to every ``TimeScalingProblem.solve`` (``method``, ``tolerance``, ...).

    Returns
    -------
    list of Result
    """
    items = list(problems)
    for i, p in enumerate(items):
        if not isinstance(p, TimeScalingProblem):
            raise InvalidInputError(f"problems[{i}] is a {type(p).__name__}, expected a TimeScalingProblem")
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise InvalidInputError(f"workers = {workers!r} must be an int >= 1")
    if chunksize is not None and (not isinstance(chunksize, int) or chunksize < 1):
        raise InvalidInputError(f"chunksize = {chunksize!r} must be an int >= 1")
    own = executor is None
    if own:
        executor = ThreadPoolExecutor(max_workers=workers or os.cpu_count() or 1)
        size = chunksize or 1
    else:
        size = chunksize or max(1, math.ceil(len(items) / 64))
    chunks = [items[i : i + size] for i in range(0, len(items), size)]
    try:
        futures = [executor.submit(_solve_chunk, c, solve_options) for c in chunks]
        out: list[list[Result] | None] = [None] * len(futures)
        with ProgressBar(len(items), "solving", enabled=progress) as bar:
            pending = set(range(len(futures)))
            while pending:
                finished = [i for i in pending if futures[i].done()] if progress else sorted(pending)
                for i in finished:
                    out[i] = futures[i].result()
                    pending.discard(i)
                    bar.update(len(chunks[i]))
                if pending and progress and not finished:
                    time.sleep(0.01)
    finally:
        if own:
            executor.shutdown(wait=True)
    return [r for chunk in out for r in chunk]  # type: ignore[union-attr]
