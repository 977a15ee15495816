"""Paths from other libraries (issue 22): ``as_path`` turns a scipy spline, a toppra interpolator or a plain
callable into a pathpace Path, and ``TimeScalingProblem`` calls it on any path it is given.

Polynomial paths (scipy ``PPoly``, ``CubicSpline``, ``BSpline``, toppra's ``SplineInterpolator``) become a
``PiecewisePolynomialPath`` with the same coefficients, so they keep what needs polynomial pieces
(``guarantee="continuous"``, breakpoints in ``grid="auto"``, exact restarts) and pickle as one. Anything else
becomes a Path that calls back into Python, once per batch of s (a vectorised call, never one per sample).
"""

from __future__ import annotations

import math
import pickle
from typing import Any, Callable

import numpy as np

from ._core import InvalidInputError, Path, PiecewisePolynomialPath

__all__ = ["as_path", "CallbackPath", "InterpolatorPath"]


def as_path(path: Any, interval: tuple[float, float] | None = None) -> Path:
    """A pathpace Path from any path-like object.

    Parameters
    ----------
    path : Path, scipy PPoly / CubicSpline / BSpline, toppra-style interpolator or callable
        - a pathpace ``Path``: returned as it is;
        - ``scipy.interpolate.PPoly`` (so ``CubicSpline``, ``Akima1DInterpolator``, ...): a
          ``PiecewisePolynomialPath`` with its coefficients (scipy stores them highest degree first, shape
          (k, m, n); pathpace lowest first, (m, k, n));
        - ``scipy.interpolate.BSpline`` (scalar or vector valued): its pieces by scipy's own
          ``PPoly.from_spline``, on the base interval ``[t[k], t[-k-1]]``;
        - toppra's ``SplineInterpolator`` (it wraps a scipy ``CubicSpline``, ``.cspl``): that spline, exactly;
        - any other object with toppra's ``__call__(s, order)`` and ``path_interval``: an ``InterpolatorPath``
          (three calls per batch of s, orders 0, 1, 2);
        - a callable ``f(s) -> (q, dq, ddq)`` on an array s of shape (m,), each of shape (m, n): a
          ``CallbackPath`` on ``interval``.
    interval : (float, float), optional
        The domain [s_begin, s_end] of a plain callable (default (0, 1)); the other kinds carry their own.

    Returns
    -------
    Path
    """
    if isinstance(path, Path):
        _no_interval(interval, "a pathpace Path")
        return path
    ppoly, bspline = _scipy_types()
    if ppoly is not None and isinstance(path, ppoly):
        _no_interval(interval, "a scipy PPoly")
        return from_ppoly(path)
    if bspline is not None and isinstance(path, bspline):
        _no_interval(interval, "a scipy BSpline")
        return from_bspline(path)
    if callable(path) and hasattr(path, "path_interval"):
        _no_interval(interval, "a toppra-style interpolator (it has path_interval)")
        spline = getattr(path, "cspl", None)
        if ppoly is not None and isinstance(spline, ppoly):
            return _toppra_spline(path, spline)
        return InterpolatorPath(path)
    if callable(path):
        s_begin, s_end = (0.0, 1.0) if interval is None else _interval(interval, "interval")
        return CallbackPath(path, s_begin, s_end)
    raise TypeError("path must be a pathpace.Path, a scipy PPoly/CubicSpline/BSpline, an object with toppra's "
                    "__call__(s, order) and path_interval, or a callable f(s) -> (q, dq, ddq), got "
                    f"{type(path).__name__}")


def from_ppoly(spline: Any, name: str = "path") -> PiecewisePolynomialPath:
    """The ``PiecewisePolynomialPath`` with the pieces of a scipy ``PPoly``: the same numbers, reversed in
    degree (scipy: ``c[k-1-j, i]`` multiplies ``(s - x[i])**j``; pathpace: ``coefficients[i, j]``)."""
    x = np.asarray(spline.x)
    c = np.asarray(spline.c)
    if np.iscomplexobj(c) or np.iscomplexobj(x):
        raise InvalidInputError(f"{name} has complex coefficients: a path must be real")
    x, c = x.astype(float), c.astype(float)
    if c.ndim == 2:
        c = c[:, :, None]
    if c.ndim != 3:
        raise InvalidInputError(f"{name}.c has shape {c.shape}, expected (k, m) or (k, m, n): a path's values "
                                "are vectors (n,)")
    _check_breakpoints(x, f"{name}.x", allow_equal=True)
    bad = np.argwhere(~np.isfinite(c))
    if bad.size:
        j, i, d = bad[0]
        raise InvalidInputError(f"{name}.c[{j}, {i}, {d}] = {float(c[j, i, d])!r} must be finite")
    # Pieces of zero width (PPoly.from_spline's at repeated knots) are never evaluated: no piece here.
    keep = np.diff(x) > 0
    x = np.append(x[:-1][keep], x[-1])
    return PiecewisePolynomialPath(x, np.ascontiguousarray(c[::-1, keep, :].transpose(1, 0, 2)))


def from_bspline(spline: Any, name: str = "path") -> PiecewisePolynomialPath:
    """The pieces of a scipy ``BSpline`` on its base interval [t[k], t[-k-1]], by scipy's own
    ``PPoly.from_spline`` (one component at a time: it takes scalar splines only); knot intervals of zero
    width (repeated knots) carry no piece."""
    from scipy.interpolate import BSpline, PPoly

    t, c, k = np.asarray(spline.t, dtype=float), np.asarray(spline.c), int(spline.k)
    if np.iscomplexobj(c):
        raise InvalidInputError(f"{name} has complex coefficients: a path must be real")
    if c.ndim not in (1, 2):
        raise InvalidInputError(f"{name}.c has shape {c.shape}, expected (nc,) or (nc, n)")
    bad = np.argwhere(~np.isfinite(c.reshape(c.shape[0], -1)))
    if bad.size:
        i, d = bad[0]
        raise InvalidInputError(f"{name}.c[{i}, {d}] = {float(c.reshape(c.shape[0], -1)[i, d])!r} must be finite")
    lo, hi = float(t[k]), float(t[len(t) - k - 1])
    keep = (t[:-1] >= lo) & (t[1:] <= hi) & (t[1:] > t[:-1])
    if not keep.any():
        raise InvalidInputError(f"{name} has an empty base interval [t[k], t[-k-1]] = [{lo!r}, {hi!r}]")
    columns = c.reshape(c.shape[0], -1).astype(float)
    pieces = [PPoly.from_spline(BSpline(t, columns[:, d], k, extrapolate=True)) for d in range(columns.shape[1])]
    coeffs = np.stack([p.c for p in pieces], axis=2)  # (k + 1, len(t) - 1, n), highest degree first
    x = np.append(t[:-1][keep], t[1:][keep][-1])
    _check_breakpoints(x, f"{name}.t")
    return PiecewisePolynomialPath(x, np.ascontiguousarray(coeffs[::-1, keep, :].transpose(1, 0, 2)))


def _toppra_spline(interpolator: Any, spline: Any) -> PiecewisePolynomialPath:
    """toppra's SplineInterpolator: its CubicSpline (``cspl``) is its path; a domain other than the spline's
    would mean another interpolator that only looks like it."""
    a, b = _interval(_path_interval(interpolator), "path.path_interval")
    x = np.asarray(spline.x, dtype=float)
    if x.size < 2 or x[0] != a or x[-1] != b:
        return InterpolatorPath(interpolator)
    return from_ppoly(spline, "path.cspl")


class CallbackPath(Path):
    """A path p, p', p'' = f(s) from a vectorised Python callable, on [s_begin, s_end].

    ``f`` is called with a 1-D float array of s (clamped to the domain) and returns (q, dq, ddq), each of shape
    (m, n) (or (m,) when n = 1); it is called once per batch of s, from any thread (pathpace takes the GIL).
    Its results are checked on every call: a wrong shape or a non-finite value raises InvalidInputError
    naming it. It pickles when ``f`` does (a module-level function, not a lambda or a closure).
    """

    def __init__(self, function: Callable[[np.ndarray], Any], s_begin: float = 0.0, s_end: float = 1.0):
        Path.__init__(self)
        if not callable(function):
            raise TypeError(f"function must be callable, got {type(function).__name__}")
        self._function = function
        self._interval = _interval((s_begin, s_end), "(s_begin, s_end)")
        self._dof = _dof_of(function(np.array(self._interval)), "path: function(s)")

    dof = property(lambda self: self._dof, doc="Number of coordinates n.")
    s_begin = property(lambda self: self._interval[0], doc="The start of the domain.")
    s_end = property(lambda self: self._interval[1], doc="The end of the domain.")

    @property
    def function(self) -> Callable[[np.ndarray], Any]:
        """The callable f(s) -> (q, dq, ddq)."""
        return self._function

    def evaluate(self, s: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(s, dtype=float)
        if x.ndim == 0:
            return tuple(Path.__call__(self, x, k) for k in range(3))
        return self._function(np.clip(x, *self._interval))

    def __reduce__(self):
        _check_pickles(self._function, self, "its function")
        return (CallbackPath, (self._function, *self._interval))

    def __repr__(self) -> str:
        name = getattr(self._function, "__qualname__", type(self._function).__name__)
        return f"<CallbackPath function={name} s=[{self._interval[0]:g}, {self._interval[1]:g}] dof={self._dof}>"


class InterpolatorPath(Path):
    """A path from an object with toppra's interface: ``obj(s, order)`` for order 0, 1, 2 (arrays of s) and
    ``path_interval`` ([s_begin, s_end]); ``dof`` is read from it when it has one. Three calls per batch of s.
    It pickles when the object does."""

    def __init__(self, interpolator: Any):
        Path.__init__(self)
        if not callable(interpolator):
            raise TypeError(f"interpolator must be callable as interpolator(s, order), got {type(interpolator).__name__}")
        self._interpolator = interpolator
        self._interval = _interval(_path_interval(interpolator), "path.path_interval")
        self._dof = _dof_of(self.evaluate(np.array(self._interval)), "path(s, order)")

    dof = property(lambda self: self._dof, doc="Number of coordinates n.")
    s_begin = property(lambda self: self._interval[0], doc="The start of the domain.")
    s_end = property(lambda self: self._interval[1], doc="The end of the domain.")

    @property
    def interpolator(self) -> Any:
        """The wrapped object."""
        return self._interpolator

    def evaluate(self, s: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        x = np.asarray(s, dtype=float)
        if x.ndim == 0:
            return tuple(Path.__call__(self, x, k) for k in range(3))
        x = np.clip(x, *self._interval)
        return tuple(self._interpolator(x, k) for k in range(3))

    def __reduce__(self):
        _check_pickles(self._interpolator, self, "its interpolator")
        return (InterpolatorPath, (self._interpolator,))

    def __repr__(self) -> str:
        return (f"<InterpolatorPath of {type(self._interpolator).__name__} s=[{self._interval[0]:g}, "
                f"{self._interval[1]:g}] dof={self._dof}>")


def _scipy_types():
    try:
        from scipy.interpolate import BSpline, PPoly
    except ImportError:  # scipy is optional: without it no object can be one of its splines
        return None, None
    return PPoly, BSpline


def _no_interval(interval: Any, what: str) -> None:
    if interval is not None:
        raise InvalidInputError(f"interval = {interval!r} is only for a plain callable; {what} has its own domain")


def _interval(value: Any, name: str) -> tuple[float, float]:
    try:
        a, b = (float(v) for v in np.asarray(value, dtype=float).reshape(-1))
    except (TypeError, ValueError):
        raise InvalidInputError(f"{name} = {value!r} must be two numbers (s_begin, s_end)") from None
    if not (math.isfinite(a) and math.isfinite(b) and a < b):
        raise InvalidInputError(f"{name} = ({a!r}, {b!r}) must be finite with s_begin < s_end")
    return a, b


def _path_interval(obj: Any) -> Any:
    value = obj.path_interval
    return value() if callable(value) else value


def _check_breakpoints(x: np.ndarray, name: str, allow_equal: bool = False) -> None:
    if x.ndim != 1 or x.size < 2:
        raise InvalidInputError(f"{name} has shape {x.shape}, expected (m + 1,) breakpoints with m >= 1")
    for i in range(x.size):
        if not math.isfinite(x[i]):
            raise InvalidInputError(f"{name}[{i}] = {float(x[i])!r} must be finite")
    d = np.flatnonzero(np.diff(x) < 0 if allow_equal else np.diff(x) <= 0)
    if d.size:
        i = int(d[0])
        raise InvalidInputError(f"{name}[{i + 1}] = {float(x[i + 1])!r} must be > {name}[{i}] = {float(x[i])!r}: "
                                "breakpoints must be strictly increasing")
    if x[-1] <= x[0]:
        raise InvalidInputError(f"{name} spans [{float(x[0])!r}, {float(x[-1])!r}]: a path needs s_begin < s_end")


def _dof_of(result: Any, name: str) -> int:
    """n from what a path callable returned for two values of s (the full checks are made in C++ on every
    call)."""
    if not isinstance(result, (tuple, list)) or len(result) != 3:
        raise InvalidInputError(f"{name} returned {type(result).__name__}, expected a tuple (q, dq, ddq)")
    q = np.asarray(result[0])
    if q.ndim == 1 and q.shape[0] == 2:
        return 1
    if q.ndim == 2 and q.shape[0] == 2 and q.shape[1] >= 1:
        return int(q.shape[1])
    raise InvalidInputError(f"{name} returned q of shape {q.shape} for 2 values of s, expected (2, n) or (2,)")


def _check_pickles(obj: Any, path: Path, what: str) -> None:
    try:
        pickle.dumps(obj)
    except Exception as e:  # noqa: BLE001 - any failure of pickle means the same thing here
        raise pickle.PicklingError(f"{path!r} does not pickle: {what} {obj!r} does not ({type(e).__name__}: {e}); "
                                   "use a module-level function or a picklable object") from e
