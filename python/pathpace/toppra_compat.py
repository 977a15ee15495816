"""toppra's constraint objects and ``compute_trajectory`` on a pathpace problem (issue 22): a toppra script
moves over by changing its imports and its constructor line only.

``TimeScalingProblem(path, grid=..., constraints=[...])`` takes toppra's constraint objects (and pathpace
Constraints) and adds each as the pathpace call that means the same, reading the object's public attributes
(argument conversion only: the rows are pathpace's). toppra's ``discretization_scheme`` is not carried over:
pathpace's rows hold at every grid point for both adjacent s̈ (eq. 26), which is toppra's Interpolation
scheme for the kinematic limits; ``solve(guarantee="continuous")`` holds them between grid points too.
"""

from __future__ import annotations

import logging
from typing import Any

import numpy as np

from ._core import Constraint, InvalidInputError

__all__ = ["add_constraints", "compute_trajectory"]

_log = logging.getLogger("pathpace")


def add_constraints(problem: Any, constraints: Any) -> None:
    """Adds each of ``constraints`` (toppra constraint objects or pathpace Constraints) to ``problem``.

    toppra type                          pathpace call
    ``JointVelocityConstraint(vlim)``    ``add_velocity_limits(vlim[:, 0], vlim[:, 1])``
    ``JointAccelerationConstraint(alim)`` ``add_acceleration_limits(alim[:, 0], alim[:, 1])``
    ``JointTorqueConstraint(inv_dyn, tau_lim, fs_coef)``
                                         ``add_torque_limits(inverse_dynamics=inv_dyn, tau_min=tau_lim[:, 0],
                                         tau_max=tau_lim[:, 1], vectorized=False)``; fs_coef must be 0
    ``SecondOrderConstraint(inv_dyn, constraint_F, constraint_g, dof)``
                                         ``add_second_order_constraint(inv_dyn, constraint_F, constraint_g,
                                         vectorized=False)``; custom_term must be None or 0 on the grid
    ``JointVelocityConstraintVarying(vlim_func)``
                                         ``add_linear_constraint``: p'(s_k)² ṡ² <= v(s_k)² per joint and grid
                                         point, v the limit on the side p' points to
    a pathpace ``Constraint``            ``add_constraint``

    Anything else, and what pathpace cannot express (dry friction, a nonzero custom term), is an
    InvalidInputError naming ``constraints[i]`` and its type; so is an error of the pathpace call.
    """
    if isinstance(constraints, (str, bytes)) or not hasattr(constraints, "__iter__"):
        raise TypeError(f"constraints must be a list of constraints, got {type(constraints).__name__}")
    for i, c in enumerate(list(constraints)):
        where = f"constraints[{i}] ({_type_name(c)})"
        try:
            _add_one(problem, c, where)
        except InvalidInputError as e:
            if str(e).startswith(where):
                raise
            raise InvalidInputError(f"{where}: {e}") from None


def compute_trajectory(problem: Any, sd_start: float = 0.0, sd_end: float = 0.0) -> Any:
    """toppra's ``compute_trajectory(sd_start, sd_end)``: the time-optimal Trajectory, or None when the
    solve does not succeed (logged as a warning on the "pathpace" logger with the status and message, as
    toppra logs its return code). ``sd_start``/``sd_end`` are the path speeds ṡ at the ends, set on the
    problem (``set_boundary_speeds``) when they differ from its own. ``solve()`` gives the Result with why."""
    a, b = _number(sd_start, "sd_start"), _number(sd_end, "sd_end")
    if (a, b) != (problem.sdot_begin, problem.sdot_end):
        problem.set_boundary_speeds(a, b)
    res = problem.solve()
    if not res.ok:
        _log.warning("pathpace: no time scaling (%s): %s", res.status.name, res.message)
        return None
    return res.trajectory()


def _number(value: Any, name: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise TypeError(f"{name} must be a number, got {type(value).__name__}")
    return float(value)


# -- one constraint ----------------------------------------------------------------------------------------


def _type_name(obj: Any) -> str:
    t = type(obj)
    module = t.__module__.split(".")[0]
    return f"{module}.{t.__name__}" if module in ("toppra", "pathpace") else t.__name__


def _toppra_types() -> dict[str, type]:
    """toppra's constraint classes by name: toppra is optional, and an object can only be one of them when
    toppra is imported (it made the object)."""
    try:
        import toppra.constraint as tc
    except ImportError:
        return {}
    names = ("JointVelocityConstraint", "JointVelocityConstraintVarying", "JointAccelerationConstraint",
             "JointTorqueConstraint", "SecondOrderConstraint")
    return {n: getattr(tc, n) for n in names if hasattr(tc, n)}


def _add_one(problem: Any, c: Any, where: str) -> None:
    if isinstance(c, Constraint):
        problem.add_constraint(c)
        return
    kinds = _toppra_types()
    # type(c) is exactly one of them: a user's subclass may compute other rows than its base's attributes say.
    kind = next((name for name, t in kinds.items() if type(c) is t), None)
    if kind == "JointVelocityConstraint":
        lim = _limits(c.vlim, f"{where}.vlim")
        problem.add_velocity_limits(lim[:, 0], lim[:, 1])
    elif kind == "JointAccelerationConstraint":
        lim = _limits(c.alim, f"{where}.alim")
        problem.add_acceleration_limits(lim[:, 0], lim[:, 1])
    elif kind == "JointTorqueConstraint":
        lim = _limits(c.tau_lim, f"{where}.tau_lim")
        fs = np.asarray(c.fs_coef, dtype=float).reshape(-1)
        nonzero = np.flatnonzero(fs != 0)
        if nonzero.size:
            j = int(nonzero[0])
            raise InvalidInputError(
                f"{where}.fs_coef[{j}] = {float(fs[j])!r}: dry friction fs·sign(q̇) is not supported (it depends on the "
                "sign of p', not on q, so no inverse dynamics of (q, q̇, q̈) can hold it); give fs_coef = 0, or "
                "the friction as per-grid rows through add_linear_constraint")
        problem.add_torque_limits(inverse_dynamics=c.inv_dyn, tau_min=lim[:, 0], tau_max=lim[:, 1],
                                  vectorized=False)
    elif kind == "SecondOrderConstraint":
        _no_custom_term(problem, c, where)
        problem.add_second_order_constraint(c.inv_dyn, c.constraint_F, c.constraint_g, vectorized=False)
    elif kind == "JointVelocityConstraintVarying":
        _add_varying_velocity(problem, c.vlim_func, where)
    else:
        raise InvalidInputError(
            f"{where} is not a constraint pathpace takes: give toppra's JointVelocityConstraint, "
            "JointVelocityConstraintVarying, JointAccelerationConstraint, JointTorqueConstraint or "
            "SecondOrderConstraint, or a pathpace Constraint (or add it with the problem's add_* methods)")


def _limits(value: Any, name: str) -> np.ndarray:
    lim = np.asarray(value, dtype=float)
    if lim.ndim != 2 or lim.shape[1] != 2:
        raise InvalidInputError(f"{name} has shape {lim.shape}, expected (dof, 2): lower and upper per joint")
    return lim


def _no_custom_term(problem: Any, c: Any, where: str) -> None:
    """toppra's custom_term(path, s) adds to c at each s (its joint_torque_constraint puts dry friction there).
    pathpace's rows come from inverse_dynamics alone: a term that is zero at every grid point (friction 0)
    is no term; any other is refused."""
    term = getattr(c, "custom_term", None)
    if term is None:
        return
    path = problem.path
    for k, s in enumerate(problem.grid):
        v = np.asarray(term(path, float(s)), dtype=float)
        if np.any(v != 0):
            raise InvalidInputError(
                f"{where}.custom_term(path, s) = {v.tolist()!r} at grid point {k} (s = {float(s)!r}): a custom term is not "
                "supported (pathpace's rows come from inverse_dynamics alone); put a term of q into inv_dyn")


def _add_varying_velocity(problem: Any, vlim_func: Any, where: str) -> None:
    """|p'_j ṡ| within [lo_j(s), hi_j(s)] at each grid point, as ṡ² rows: p'_j² ṡ² <= hi_j² where p'_j > 0,
    <= lo_j² where p'_j < 0 (ṡ >= 0, so p'_j ṡ takes p'_j's sign); needs lo_j <= 0 <= hi_j."""
    grid = np.asarray(problem.grid, dtype=float)
    dq = np.asarray(problem.path(grid, 1), dtype=float).reshape(grid.size, -1)
    n = dq.shape[1]
    lim = np.empty((grid.size, n, 2))
    for k, s in enumerate(grid):
        v = np.asarray(vlim_func(float(s)), dtype=float)
        if v.shape != (n, 2):
            raise InvalidInputError(f"{where}.vlim_func(s) returned shape {v.shape} at s = {float(s)!r}, "
                                    f"expected ({n}, 2)")
        bad = np.argwhere(~np.isfinite(v) | (v[:, [0]] > 0) | (v[:, [1]] < 0) | (v[:, [0]] >= v[:, [1]]))
        if bad.size:
            j = int(bad[0, 0])
            raise InvalidInputError(f"{where}.vlim_func(s)[{j}] = {v[j].tolist()!r} at s = {float(s)!r}: expected "
                                    "finite lower <= 0 <= upper, lower < upper")
        lim[k] = v
    bound = np.where(dq >= 0, lim[:, :, 1], lim[:, :, 0]) ** 2
    zeros = np.zeros_like(dq)
    problem.add_linear_constraint(dq ** 2, zeros, zeros, np.full_like(dq, -np.inf), bound,
                                  label="varying velocity")
