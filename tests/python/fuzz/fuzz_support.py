"""Shared pieces of the fuzz suite: budgets, crash isolation and the independent checker.

Budget: the default run (inside `make test`) is seeded (derandomised) and small; the long mode runs
many more examples from a fresh seed each time:

    PATHPACE_FUZZ=long .venv/bin/python -m pytest -q tests/python/fuzz        # ~20x the examples
    PATHPACE_FUZZ_EXAMPLES=5000 .venv/bin/python -m pytest -q tests/python/fuzz
    PATHPACE_FUZZ_SEED=123 ...                                                  # a reproducible long run

The long mode draws its seed from the OS unless PATHPACE_FUZZ_SEED gives one; pytest's header says which
(`pathpace fuzz: ... seed ...`), so that a run's findings can be repeated.

Each example runs in a forked child (run_isolated): a segfault, an abort from a sanitizer or a hang
ends that child, and the parent reports it as the failure of that example (hypothesis then shrinks
it), instead of ending the pytest run.
"""

from __future__ import annotations

import os
import pickle
import random
import shutil
import signal
import tempfile
import traceback

import numpy as np
from hypothesis import HealthCheck, seed, settings

LONG = os.environ.get("PATHPACE_FUZZ", "") == "long"
EXAMPLES_OVERRIDE = int(os.environ.get("PATHPACE_FUZZ_EXAMPLES", "0"))
# Every hypothesis test of the run starts from this seed (None: the default run, derandomised).
SEED = os.environ.get("PATHPACE_FUZZ_SEED") or (str(random.SystemRandom().randrange(2**32))
                                                if LONG or EXAMPLES_OVERRIDE else None)


def fuzz_settings(examples: int):
    """`examples` in the default run; 20x that in the long mode (or PATHPACE_FUZZ_EXAMPLES); from SEED."""
    n = EXAMPLES_OVERRIDE or (20 * examples if LONG else examples)
    s = settings(
        max_examples=n,
        deadline=None,
        database=None,
        derandomize=SEED is None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much],
        print_blob=True,
    )
    return s if SEED is None else (lambda test: seed(int(SEED))(s(test)))


class ChildCrashed(AssertionError):
    pass


def exception_info(e: BaseException) -> dict:
    """What the parent judges of an exception raised in a child (picklable): its type name, message, kind
    (TypeError, InvalidInputError, pathpace.Error, OSError) and the last frames of its traceback. Call it
    inside the `except` block (the traceback is the one being handled)."""
    import pathpace as pp

    return {
        "type": type(e).__module__ + "." + type(e).__qualname__,
        "message": str(e),
        "type_error": isinstance(e, TypeError),
        "invalid_input": isinstance(e, pp.InvalidInputError),
        "pp_error": isinstance(e, pp.Error),
        "os_error": isinstance(e, OSError),
        "traceback": traceback.format_exc(limit=4),
    }


def run_isolated(fn, *args, timeout: float = 60.0):
    """fn(*args) in a forked child. Returns ("ok", value) or ("raised", exception_info(e)). A child
    that dies (signal, sanitizer abort) or runs past `timeout` seconds raises ChildCrashed."""
    scratch = tempfile.mkdtemp(prefix="pathpace-fuzz-")  # files a bad "path" argument may create land here
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: never return into pytest
        os.close(r)
        code = 0
        try:
            os.chdir(scratch)
            signal.alarm(int(max(1, timeout)))
            try:
                out = ("ok", fn(*args))
            except BaseException as e:  # noqa: BLE001 - the parent judges every exception
                out = ("raised", exception_info(e))
            signal.alarm(0)
            data = pickle.dumps(out)
        except BaseException:  # noqa: BLE001
            data, code = b"", 3
        with os.fdopen(w, "wb") as f:
            f.write(data)
        os._exit(code)
    os.close(w)
    with os.fdopen(r, "rb") as f:
        data = f.read()
    _, status = os.waitpid(pid, 0)
    shutil.rmtree(scratch, ignore_errors=True)
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        what = "timed out" if sig == signal.SIGALRM else f"died with signal {signal.Signals(sig).name}"
        raise ChildCrashed(f"{getattr(fn, '__name__', fn)}{args!r:.300} {what}")
    if os.WEXITSTATUS(status) != 0 or not data:
        raise ChildCrashed(f"{getattr(fn, '__name__', fn)} exited with status {os.WEXITSTATUS(status)}")
    return pickle.loads(data)


def kinematic_violation(s, sdot, dq, ddq, vmax, amax, amin=None):
    """Largest violation, relative to the limit, of |q̇| <= vmax and amin <= q̈ <= amax (amin = -amax
    when not given) at every grid point, with s̈ of the interval on each side (eq. 26). Written from
    eq. (10)-(11) and (24)-(25): q̇ = p' ṡ, q̈ = p'' ṡ² + p' s̈, s̈ constant on each interval."""
    amin = -np.asarray(amax, dtype=float) if amin is None else np.asarray(amin, dtype=float)
    theta = np.asarray(sdot, dtype=float) ** 2
    u = np.diff(theta) / (2 * np.diff(s))
    worst = 0.0
    v = np.abs(dq * np.asarray(sdot)[:, None]) / vmax - 1.0
    worst = max(worst, float(v.max()))
    for ks, us in ((np.arange(len(u)), u), (np.arange(1, len(s)), u)):
        qdd = ddq[ks] * theta[ks, None] + dq[ks] * us[:, None]
        worst = max(worst, float(np.max(qdd / amax - 1.0)), float(np.max(qdd / amin - 1.0)))
    return worst
