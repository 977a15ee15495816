"""Type stubs for the compiled module pathpace._core."""

from enum import Enum
from typing import Any, Callable, overload

import os

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]

#: True if the module asked glibc to keep freed heap memory (see PATHPACE_NO_MALLOC_TUNING).
malloc_tuned: bool

class Error(RuntimeError):
    """Base of every error pathpace raises; e.g. Result.trajectory() without a timing, or a problem modified
    while another thread solves it. Infeasible problems are not errors: they are a Result status.

    A RuntimeError.
    """
class InvalidInputError(Error, ValueError):
    """Bad input: the message names the argument, index, value and what was expected.

    A wrong shape, a NaN, a limit of the wrong sign, an unknown link name...: e.g. "vmax[3] = -2 must be > 0".

    Also a ValueError.
    """

class Path:
    """A geometric path q = p(s) for s in [s_begin, s_end] (abstract).

    Joint coordinates q are in rad (revolute) or m (prismatic); s is dimensionless, so p' = dq/ds and
    p'' = d²q/ds² are in rad (or m) per unit s. Implementations are immutable after construction and safe
    to evaluate from several threads at once. ``path(s, order)`` evaluates it as toppra's interpolators do.

    A Python subclass defines ``dof``, ``s_begin``, ``s_end`` (attributes or properties) and ``evaluate(s)``:
    given a float array s of shape (m,), clamped to the domain, it returns (q, dq, ddq), each (m, n) (or (m,)
    when n = 1). It is called once per batch of s, from any thread; its results are checked (shape, finite).
    To pickle, define ``__reduce__``. ``pathpace.as_path`` builds such paths from callables and from toppra-style
    interpolators.

    Attributes
    ----------
    dof : int
        Number of coordinates n of q.
    s_begin : float
        First value of s.
    s_end : float
        Last value of s.
    """
    def __init__(self) -> None: ...
    @property
    def dof(self) -> int:
        """int: Number of coordinates n of q."""
    @property
    def s_begin(self) -> float:
        """float: First value of s."""
    @property
    def s_end(self) -> float:
        """float: Last value of s."""
    def q(self, s: float | ArrayLike) -> Array:
        """p(s).

        Parameters
        ----------
        s : float or array_like (m,)
            Path parameter, clamped to [s_begin, s_end].

        Returns
        -------
        ndarray
            (n,) for a scalar s, (m, n) for an array; rad or m.
        """
    def dq(self, s: float | ArrayLike) -> Array:
        """p'(s) = dq/ds: (n,) for a scalar s, (m, n) for an array."""
    def ddq(self, s: float | ArrayLike) -> Array:
        """p''(s) = d²q/ds²: (n,) for a scalar s, (m, n) for an array."""
    def evaluate(self, s: float | ArrayLike) -> tuple[Array, Array, Array]:
        """(p(s), p'(s), p''(s)) at once; shapes as in ``q``."""
    def __call__(self, s: float | ArrayLike, order: int = 0) -> Array:
        """p(s) (order 0), p'(s) (1) or p''(s) (2), as toppra's ``path(s, order)``.

        Parameters
        ----------
        s : float or array_like (m,)
            Path parameter, clamped to [s_begin, s_end].
        order : {0, 1, 2}

        Returns
        -------
        ndarray
            (n,) for a scalar s, (m, n) for an array.
        """

class PiecewisePolynomialPath(Path):
    """Polynomial pieces between breakpoints.

    On [b_i, b_{i+1}], p(s) = Σ_j coefficients[i, j, :] (s - b_i)**j (lowest degree first). The domain
    is [breakpoints[0], breakpoints[M]]; s outside it is clamped.

    Parameters
    ----------
    breakpoints : array_like (M+1,)
        Strictly increasing.
    coefficients : array_like (M, degree + 1, n)
        coefficients[i, j, :] multiplies (s - breakpoints[i])**j on piece i.

    Attributes
    ----------
    breakpoints : ndarray (M+1,)
    """
    def __init__(self, breakpoints: ArrayLike, coefficients: ArrayLike) -> None: ...
    @property
    def breakpoints(self) -> Array:
        """ndarray (M+1,)"""

class CubicSplinePath(PiecewisePolynomialPath):
    """A C² cubic spline through waypoints, as scipy.interpolate.CubicSpline.

    Parameters
    ----------
    waypoints : array_like (K, n)
        K >= 2 waypoints in rad (or m), one per row.
    knots : {'uniform', 'chord'} or array_like (K,)
        Knot placement on [s_begin, s_end]: equally spaced, proportional to the chord lengths, or explicit
        (strictly increasing; then the domain is [knots[0], knots[-1]]).
    boundary : {'not-a-knot', 'natural', 'clamped'}
        scipy's bc_type: p''' continuous at the second and second-last knots; p'' = 0 at the ends; or
        given end slopes p' (zero when no derivative is given, scipy's "clamped").
    start_derivative, end_derivative : array_like (n,), optional
        p'(s_begin), p'(s_end) for ``boundary='clamped'``.
    s_begin, s_end : float
        Domain for 'uniform' and 'chord' knots.

    Attributes
    ----------
    knots : ndarray (K,)
    waypoints : ndarray (K, n)
    boundary : str
        The end conditions, scipy's bc_type: 'not-a-knot', 'natural' or 'clamped'.
    start_derivative : ndarray (n,) or None
        p'(s_begin) of a clamped spline; None (in C++ empty) for the other boundaries.
    end_derivative : ndarray (n,) or None
        p'(s_end) of a clamped spline; None (in C++ empty) for the other boundaries.
    """
    def __init__(
        self,
        waypoints: ArrayLike,
        knots: str | ArrayLike = "uniform",
        boundary: str = "not-a-knot",
        start_derivative: ArrayLike | None = None,
        end_derivative: ArrayLike | None = None,
        s_begin: float = 0.0,
        s_end: float = 1.0,
    ) -> None: ...
    @property
    def knots(self) -> Array:
        """ndarray (K,)"""
    @property
    def waypoints(self) -> Array:
        """ndarray (K, n)"""
    @property
    def boundary(self) -> str:
        """str: The end conditions, scipy's bc_type: 'not-a-knot', 'natural' or 'clamped'."""
    @property
    def start_derivative(self) -> Array | None:
        """ndarray (n,) or None: p'(s_begin) of a clamped spline; None (in C++ empty) for the other boundaries."""
    @property
    def end_derivative(self) -> Array | None:
        """ndarray (n,) or None: p'(s_end) of a clamped spline; None (in C++ empty) for the other boundaries."""

class SampledPath(PiecewisePolynomialPath):
    """A path known at samples: q, q', q'' given at each s (e.g. from another planner).

    Between samples, the quintic Hermite interpolant: C², and exact at every sample, so a grid on the
    samples sees exactly the data given and a trajectory evaluated in between is smooth.

    Parameters
    ----------
    s : array_like (m,)
        Strictly increasing, m >= 2.
    q, dq, ddq : array_like (m, n)
        p, p', p'' at the samples.

    Attributes
    ----------
    samples : ndarray (m,)
    """
    def __init__(self, s: ArrayLike, q: ArrayLike, dq: ArrayLike, ddq: ArrayLike) -> None: ...
    @property
    def samples(self) -> Array:
        """ndarray (m,)"""

class PathSamples:
    """The path at the grid points, as Constraint.evaluate reads it (read-only).

    Computed once per problem, read by every constraint. Row k of q, dq, ddq belongs to s[k].

    Attributes
    ----------
    s : ndarray (N+1,)
        The grid s_0 < ... < s_N.
    q : ndarray (N+1, n)
        p at s.
    dq : ndarray (N+1, n)
        p' at s.
    ddq : ndarray (N+1, n)
        p'' at s.
    dof : int
        n.
    """
    @property
    def s(self) -> Array:
        """ndarray (N+1,): The grid s_0 < ... < s_N."""
    @property
    def q(self) -> Array:
        """ndarray (N+1, n): p at s."""
    @property
    def dq(self) -> Array:
        """ndarray (N+1, n): p' at s."""
    @property
    def ddq(self) -> Array:
        """ndarray (N+1, n): p'' at s."""
    @property
    def dof(self) -> int:
        """int: n."""
    def __len__(self) -> int: ...

class ConstraintRows:
    """Half-planes a·x + b·u <= c (x = ṡ², u = s̈) at every grid point: what Constraint.evaluate returns.

    Row j at grid point k reads a(k, j)·x + b(k, j)·u <= c(k, j). A row with c = +inf is inactive at that
    grid point (a limit that is absent, or padding when the number of half-planes varies along the path).
    labels[j] names row j for infeasibility reports, e.g. "acceleration joint 3 upper".

    Parameters
    ----------
    a, b, c : array_like (N+1, r), or (N+1,) for one row
        c = inf: the row is inactive at that grid point.
    labels : list of str
        One name per row, for infeasibility reports and Result.binding.

    Attributes
    ----------
    a : ndarray (N+1, r)
        Coefficients of x.
    b : ndarray (N+1, r)
        Coefficients of u.
    c : ndarray (N+1, r)
        Right-hand sides; +inf: inactive.
    labels : list of str
        r names, one per row.
    rows : int
        r.
    """
    def __init__(self, a: ArrayLike, b: ArrayLike, c: ArrayLike, labels: list[str]) -> None: ...
    @property
    def a(self) -> Array:
        """ndarray (N+1, r): Coefficients of x."""
    @property
    def b(self) -> Array:
        """ndarray (N+1, r): Coefficients of u."""
    @property
    def c(self) -> Array:
        """ndarray (N+1, r): Right-hand sides; +inf: inactive."""
    @property
    def labels(self) -> list[str]:
        """list of str: r names, one per row."""
    @property
    def rows(self) -> int:
        """int: r."""

class Constraint:
    """Base of all constraints: half-planes a·x + b·u <= c per grid point, x = ṡ², u = s̈ (eq. 9).

    Implementations are immutable after construction, so one instance can serve several problems and
    threads; evaluate keeps its scratch space local.

    A family of your own subclasses it in Python: give `name` and `evaluate(samples)` (returning
    ConstraintRows), and optionally `family`/`relaxed` (relaxation explains infeasibility with it),
    `per_grid_point`/`at_grid_points` (rows given per grid point only) and `with_joint_names`. It composes
    with torque limits, contacts, restarts and pickling (define `__reduce__`); evaluate may be called from
    any thread, with the GIL taken for it.

    Attributes
    ----------
    name : str
        A short name for messages and infeasibility reports, e.g. "velocity limits".
    """
    def __init__(self) -> None: ...
    @property
    def name(self) -> str:
        """str: A short name for messages and infeasibility reports, e.g. "velocity limits"."""
    def evaluate(self, samples: PathSamples) -> ConstraintRows:
        """The rows at every grid point of samples.

        Parameters
        ----------
        samples : PathSamples
            The path at the grid points.

        Returns
        -------
        ConstraintRows
            The half-planes.

        Raises
        ------
        InvalidInputError
            When the constraint does not fit the path (e.g. a dimension mismatch), naming what does not fit.
        """
    def family(self) -> str:
        """The family of limits relaxation() scales ("velocity", "acceleration", "torque", ...); "" for none.

        Used when an infeasible problem is explained (see TimeScalingProblem.relaxation); a constraint of no
        family is not relaxed.
        """
    def relaxed(self, scale: float) -> Constraint | None:
        """The constraint with its limits widened by scale >= 1 about zero, or None (C++: nullptr) if it has no
        such scale.

        A bound l <= 0 becomes scale·l, a bound l > 0 becomes l / scale, likewise for upper bounds, so that the
        feasible set grows monotonically with the scale.

        Parameters
        ----------
        scale : float
            >= 1; the feasible set must grow with it.
        """
    def per_grid_point(self) -> bool:
        """True if the rows are data given per grid point, with no value between grid points (LinearConstraint):
        the grid then gains no point (contact switches) and a restart begins at a grid point.
        """
    def at_grid_points(self, kept: list[int]) -> Constraint:
        """A per_grid_point() constraint's rows at the old grid points `kept` (the new grid of a restart).

        Any other constraint is evaluated again on the new grid and is never asked.

        Parameters
        ----------
        kept : list of int
            Old grid indices, in order, each >= 0.
        """
    def with_joint_names(self, names: list[str]) -> Constraint | None:
        """The constraint labelled with the problem's joint names, or None (C++: nullptr) if its labels do not
        come from them.

        For one that takes its labels from them and has none yet (limits added before set_joint_names). Only
        its labels may differ: the problem keeps its rows.

        Parameters
        ----------
        names : list of str
            One per path coordinate.
        """

class VelocityLimits(Constraint):
    """Joint velocity limits vmin <= p'(s) ṡ <= vmax (eq. 13, as the bound on ṡ² of eq. 16).

    Since ṡ >= 0, joint j bounds x = ṡ² by (vmax_j / p'_j)² where p'_j > 0 and by (vmin_j / p'_j)² where
    p'_j < 0; a joint with p'_j = 0 imposes nothing. One row per joint, a = 1, b = 0 (a pure bound on x).

    Parameters
    ----------
    vmin, vmax : array_like (n,)
        rad/s (or m/s); vmin <= 0 <= vmax, ±inf for none; no NaN.
    joint_names : list of str, optional
        One per joint: they name the joints in row labels and messages ("velocity panda_joint2"; default
        "velocity joint 1").

    Attributes
    ----------
    vmin, vmax : ndarray (n,)
    joint_names : list of str
    """
    def __init__(self, vmin: ArrayLike, vmax: ArrayLike, joint_names: list[str] | None = None) -> None: ...
    @property
    def joint_names(self) -> list[str]:
        """list of str"""
    @property
    def vmin(self) -> Array:
        """ndarray (n,)"""
    @property
    def vmax(self) -> Array:
        """ndarray (n,)"""

class AccelerationLimits(Constraint):
    """Joint acceleration limits amin <= p''ṡ² + p's̈ <= amax (eq. 14).

    Two rows per joint, p''_j x + p'_j u <= amax_j and -p''_j x - p'_j u <= -amin_j; infinite limits give
    inactive rows.

    Parameters
    ----------
    amin, amax : array_like (n,)
        rad/s² (or m/s²); amin <= amax, ±inf for none; no NaN.
    joint_names : list of str, optional
        One per joint: they name the joints in row labels and messages ("acceleration panda_joint2 upper";
        default "acceleration joint 1 upper").

    Attributes
    ----------
    amin, amax : ndarray (n,)
    joint_names : list of str
    """
    def __init__(self, amin: ArrayLike, amax: ArrayLike, joint_names: list[str] | None = None) -> None: ...
    @property
    def joint_names(self) -> list[str]:
        """list of str"""
    @property
    def amin(self) -> Array:
        """ndarray (n,)"""
    @property
    def amax(self) -> Array:
        """ndarray (n,)"""

class JerkLimits:
    """Joint jerk limits jmin <= q⃛ <= jmax, with q⃛ = p' s⃛ + 3 p'' ṡ s̈ + p''' ṡ³.

    Not a Constraint: in (θ = ṡ², b = s̈) a jerk limit reads |p' b' + 3 p'' b + p''' θ| <= J / √θ (b' = ds̈/ds),
    which is neither a half-plane nor a function of one grid point. TimeScalingProblem::add_jerk_limits keeps
    it beside the constraints, and solve() linearises it at each iterate (docs/method.md, "Jerk limits").

    Parameters
    ----------
    jmin, jmax : array_like (n,)
        rad/s³ (or m/s³); jmin < 0 < jmax, -inf / inf for none; no NaN.
    joint_names : list of str, optional
        One per joint for messages (default "joint 1").

    Attributes
    ----------
    jmin, jmax : ndarray (n,)
    joint_names : list of str
    """
    def __init__(self, jmin: ArrayLike, jmax: ArrayLike, joint_names: list[str] | None = None) -> None: ...
    @property
    def joint_names(self) -> list[str]:
        """list of str"""
    @property
    def jmin(self) -> Array:
        """ndarray (n,)"""
    @property
    def jmax(self) -> Array:
        """ndarray (n,)"""

class LinearConstraint(Constraint):
    """lo <= A·x + B·u + C <= hi at every grid point (x = ṡ², u = s̈).

    Given on the problem's grid: row k holds the r coefficients at s_k. This is how torques from any
    dynamics source and user-defined Cartesian limits enter. lo may be -inf and hi +inf (one-sided); lo ==
    hi makes an equality.

    Parameters
    ----------
    A, B, C, lo, hi : array_like (N+1, r) (or (N+1,) for one row)
        Row k holds the coefficients at grid point s_k; lo may be -inf and hi +inf.
    label : str
        Names the rows in infeasibility reports.
    """
    def __init__(self, A: ArrayLike, B: ArrayLike, C: ArrayLike, lo: ArrayLike, hi: ArrayLike, label: str = "linear") -> None: ...

class TorqueLimits(Constraint):
    """Joint torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15), by our RNEA.

    At each grid point τ = a·x + b·u + c (RobotModel.path_torque_coefficients); two rows per joint,
    a x + b u <= τ_max - c and -a x - b u <= c - τ_min. The limits are scaled by `scale` and shrunk by
    `margin` on each side: the safety margins of sec. V.D. A joint with τ_min = τ_max = 0 (a floating base)
    gives an equality pair: without contact forces such a path can generally not be timed.

    Parameters
    ----------
    robot : RobotModel
    tau_min, tau_max : array_like (nq,), optional
        N·m (N for prismatic joints); default (None; C++: empty) ∓ the URDF effort.
    scale : float
        Multiplies the limits (sec. V.D's safety margin).
    margin : float
        N·m subtracted from each side after scaling.

    Attributes
    ----------
    tau_min, tau_max : ndarray (nq,)
        After scale and margin.
    """
    def __init__(
        self,
        robot: RobotModel,
        tau_min: ArrayLike | None = None,
        tau_max: ArrayLike | None = None,
        scale: float = 1.0,
        margin: float = 0.0,
    ) -> None: ...
    @property
    def tau_min(self) -> Array:
        """ndarray (nq,): After scale and margin."""
    @property
    def tau_max(self) -> Array:
        """ndarray (nq,): After scale and margin."""

class SecondOrderConstraint(Constraint):
    """F(q) w <= g(q) with w = inverse_dynamics(q, q̇, q̈): toppra's second-order constraint (friction cones,
    an object held by a gripper, a tray that must not slip, torque limits).

    w = A(q) q̈ + q̇ᵀB(q) q̇ + f(q) is quadratic in q̇ and linear in q̈, so on the path (q = p, q̇ = p' ṡ,
    q̈ = p' s̈ + p'' ṡ², eq. 10-12) three evaluations per grid point give w = a ṡ² + b s̈ + c:
    c = id(p, 0, 0), b = id(p, 0, p') - c, a = id(p, p', p'') - c; the rows are (F a) ṡ² + (F b) s̈ <= g - F c.
    All 3(N+1) evaluations are one call of inverse_dynamics, and F and g are called once each with the N+1
    samples of q: vectorise them (numpy), since a call per sample costs more than the solve.

    The callables are called from the solver's threads (the GIL taken for each call), again during
    ``solve(guarantee='continuous')``, whose audit samples the rows between grid points, and on a restart or
    a contact switch (new grid points). What they return is checked (shapes, finite w and F, g a number or
    +inf): InvalidInputError names the callable, the grid point and s. An exception they raise comes out of
    the pathpace call as it was. The constraint pickles when its callables do (module-level functions, or
    objects with ``__reduce__``); pickle.PicklingError names the one that does not.

    Differences from toppra's ``SecondOrderConstraint(inv_dyn, constraint_F, constraint_g, dof)``: the same
    order and meaning of the first three arguments, but vectorised (``vectorized=False`` takes toppra's
    per-sample functions unchanged), F and g may be constant arrays, no ``dof`` (the path's), no
    ``custom_term`` (put it in inverse_dynamics) and no discretization scheme (rows hold at the grid points;
    ``guarantee='continuous'`` holds them between).

    Parameters
    ----------
    inverse_dynamics : callable
        w = f(q, qd, qdd): arrays (m, n) -> (m, nw).
    F : callable or array_like (r, nw)
        F(q): (m, n) -> (m, r, nw), or constant.
    g : callable or array_like (r,)
        g(q): (m, n) -> (m, r), or constant; +inf for an absent row.
    name : str
        Names the constraint in messages, and its rows "<name> row j".
    labels : list of str, optional
        One per row of F, for infeasibility reports and Result.binding.
    family : str
        relaxation() widens g row by row about zero under this family ("" : not relaxed).
    vectorized : bool
        False: the callables take one sample (q (n,) -> w (nw,), F (r, nw), g (r,)), called per sample.

    Attributes
    ----------
    inverse_dynamics : callable
        As given.
    F, g : callable or ndarray
        As given; None for torque_limits.
    vectorized : bool
    tau_min, tau_max : ndarray (n,) or None
        torque_limits' limits after scale and margin; None otherwise.
    """
    def __init__(
        self,
        inverse_dynamics: Callable[..., Any],
        F: Callable[..., Any] | ArrayLike,
        g: Callable[..., Any] | ArrayLike,
        *,
        name: str = "second-order constraint",
        labels: list[str] | None = None,
        family: str = "second order",
        vectorized: bool = True,
    ) -> None: ...
    @staticmethod
    def torque_limits(
        inverse_dynamics: Callable[..., Any],
        tau_min: ArrayLike,
        tau_max: ArrayLike,
        *,
        scale: float = 1.0,
        margin: float = 0.0,
        vectorized: bool = True,
    ) -> SecondOrderConstraint:
        """Torque limits tau_min <= inverse_dynamics(q, q̇, q̈) <= tau_max (eq. 15) from your own dynamics: F =
        [e_0; -e_0; e_1; ...], g = [τ_max,0; -τ_min,0; ...] (TorqueLimits' rows, in its order), family "torque",
        labels "torque <joint> upper/lower" (the problem's joint names, "joint j" without).

        Parameters
        ----------
        inverse_dynamics : callable
            τ = f(q, qd, qdd): arrays (m, n) -> (m, n).
        tau_min, tau_max : array_like (n,)
            N·m (N); ±inf for none.
        scale, margin : float
            The limits are scale·[tau_min, tau_max] shrunk by margin on each side (as TorqueLimits).
        vectorized : bool
            False: f takes one sample.
        """
    @property
    def inverse_dynamics(self) -> Callable[..., Any]:
        """callable: As given."""
    @property
    def F(self) -> Callable[..., Any] | Array | None:
        """callable or ndarray: As given; None for torque_limits."""
    @property
    def g(self) -> Callable[..., Any] | Array | None:
        """callable or ndarray: As given; None for torque_limits."""
    @property
    def vectorized(self) -> bool:
        """bool"""
    @property
    def tau_min(self) -> Array | None:
        """ndarray (n,) or None: torque_limits' limits after scale and margin; None otherwise."""
    @property
    def tau_max(self) -> Array | None:
        """ndarray (n,) or None: torque_limits' limits after scale and margin; None otherwise."""
class FrameLimits(Constraint):
    """Cartesian limits on a point fixed in a robot link (issue 22; Drake's Toppra frame limits), exact at the
    grid points: with v = J p', ω = J_ω p' and the classical acceleration term J p'' + J̇(p') p' of the path,

    - ``"translational_speed"``: ‖v‖ ṡ <= v_max, one row ‖v‖² ṡ² <= v_max²;
    - ``"linear_velocity"``, ``"angular_velocity"``: lo_j <= (e_j·v) ṡ <= hi_j per axis; as ṡ >= 0 only the
      side of e_j·v's sign binds, one row (e_j·v)² ṡ² <= hi_j² (or lo_j²); hi_j = 0 where e_j·v > 0 forces
      ṡ = 0 there;
    - ``"linear_acceleration"``, ``"angular_acceleration"``: lo_j <= e_j·(J p' s̈ + (J p'' + J̇ p') ṡ²) <= hi_j
      per axis, two rows. Per axis only: a bound on the norm of the acceleration is not a half-plane.

    With guarantee='continuous' the audit checks the rows between grid points. Speed and velocity limits also
    bound ṡ² at the grid points so that the rows hold between them for a cubic Hermite model of the frame
    velocity (from its values and s-derivatives at the grid points, with a margin for the model's error): where
    they bind along a stretch the audit then confirms in one round instead of cutting round after round
    (bench/README.md). Family "frame" (relaxation).

    Parameters
    ----------
    robot : RobotModel
    link : str
        A link of `robot` (merged fixed links too, e.g. a tool frame).
    quantity : str
        One of the five above.
    lo, hi : array_like (3,)
        Per axis x, y, z (±inf: no limit); velocities need lo <= 0 <= hi (rest admissible), accelerations
        lo <= hi. For "translational_speed": hi is v_max (m/s, > 0) and lo None.
    frame : str
        "world" (the world's axes) or "local" (the link frame's, turning with it).
    point : array_like (3,)
        In the link frame, m.

    Attributes
    ----------
    robot : RobotModel
    link : str
    quantity : str
    frame : str
        "world" or "local".
    lo : ndarray
        (3,), or (0,) for a speed limit.
    hi : ndarray
        (3,), or (1,) = v_max for a speed limit.
    point : ndarray (3,)
        m, link frame.
    """
    def __init__(
        self,
        robot: RobotModel,
        link: str,
        quantity: str,
        lo: ArrayLike | None = None,
        hi: ArrayLike | float | None = None,
        *,
        frame: str = "world",
        point: ArrayLike = (0.0, 0.0, 0.0),
    ) -> None: ...
    @property
    def robot(self) -> RobotModel:
        """RobotModel"""
    @property
    def link(self) -> str:
        """str"""
    @property
    def quantity(self) -> str:
        """str"""
    @property
    def frame(self) -> str:
        """str: "world" or "local"."""
    @property
    def lo(self) -> Array:
        """ndarray: (3,), or (0,) for a speed limit."""
    @property
    def hi(self) -> Array:
        """ndarray: (3,), or (1,) = v_max for a speed limit."""
    @property
    def point(self) -> Array:
        """ndarray (3,): m, link frame."""
    def evaluate_at(self, q: ArrayLike, dq: ArrayLike, ddq: ArrayLike) -> ConstraintRows:
        """The rows at samples q = p(s), dq = p', ddq = p'' (each (m, nq)), as Constraint.evaluate on a path."""

class Contact:
    """A point contact with Coulomb friction: a point fixed in a link (link coordinates) touching the world, or
    `other_link` when given.

    Robot–robot: two links of one model, e.g. a hand on a free object. `normal` points into `link`, the
    direction in which the other side can push it: in world coordinates for a world contact, in
    `other_link`'s frame for a robot–robot contact (it turns with that link). The other side feels the
    opposite force at the same point. The normal is normalised on use (zero is rejected).

    Parameters
    ----------
    link : str
        The link that touches.
    point : array_like (3,)
        Contact point in the link frame, m.
    normal : array_like (3,)
        Into `link`: world coordinates for a world contact, other_link's frame otherwise.
    friction : float
        Coulomb coefficient μ.
    other_link : str, optional
        The other body of a robot–robot (or robot–object) contact; None: the world.

    Attributes
    ----------
    link : str
        The link that touches.
    point : ndarray (3,)
        m, link frame.
    normal : ndarray (3,)
        Into `link`: world coordinates for a world contact, other_link's frame otherwise.
    friction : float
        Coulomb coefficient μ.
    other_link : str or None
        The other body of a robot–robot contact; None (C++: empty): the world.
    """
    def __init__(self, link: str, point: ArrayLike = (0.0, 0.0, 0.0), normal: ArrayLike = (0.0, 0.0, 1.0),
                 friction: float = 0.5, other_link: str | None = None) -> None: ...
    @property
    def other_link(self) -> str | None:
        """str or None: The other body of a robot–robot contact; None (C++: empty): the world."""
    @property
    def link(self) -> str:
        """str: The link that touches."""
    @property
    def point(self) -> Array:
        """ndarray (3,): m, link frame."""
    @property
    def normal(self) -> Array:
        """ndarray (3,): Into `link`: world coordinates for a world contact, other_link's frame otherwise."""
    @property
    def friction(self) -> float:
        """float: Coulomb coefficient μ."""

class ContactConstraint(Constraint):
    """Torque limits with frictional contact forces (eq. 17-18), projected onto (ṡ², s̈).

    Includes the torque limits: do not add TorqueLimits to the same problem (TimeScalingProblem merges
    TorqueLimits of the same robot into it: both limits hold, the tighter side of each is kept).

    At grid point k: τ = a x + b u + c - Σ_i J_iᵀ f_i (J_i the contact point's Jacobian on `link`, minus
    the same world point's Jacobian on `other_link` for a robot–robot contact) with τ_min <= τ <= τ_max
    (τ_min = τ_max = 0 for an unactuated floating base), f_i = Σ_e λ_ie g_ie with λ >= 0 (the cone's
    generators g_ie = n_i + μ (cos φ_e t1 + sin φ_e t2), so that n·f_i = Σ_e λ_ie), and Σ_e λ_ie >=
    min_normal_force. The polygon's edges become this constraint's half-planes (a varying number per
    point; inactive padding).

    The polygon is the convex hull of LP optima with every edge certified by its own LP (sec. IV.C), so
    it is exact to 1e-9 of its size. Points of one link with one normal and one μ that lie in a plane
    (a flat sole) span the same wrench cone as the vertices of their convex hull (a force at a convex
    combination of points is that combination of forces at the points), so only those vertices' cones
    enter the LPs: an exact reduction (the per-link minimum is kept exactly, as the sum of normal forces
    does not change). A per-point min_normal_force d splits each point's force into its part on the
    cone's cross-section at n·f = d (a regular k-gon around d·n) plus a force in the cone; the cone parts
    reduce to the hull vertices as before, and for an even k each point's cross-section part is d·n (a
    constant) plus k/2 bounded weights (the k-gon is a zonotope): exact, with no per-point rows.

    Parameters
    ----------
    robot : RobotModel
    contacts : list of Contact
    cone_edges : int
        Edges of the polyhedral cone inscribed in each friction cone.
    friction_margin : float
        μ is used as μ (1 - friction_margin) (sec. V.D).
    min_normal_force : float
        N each contact must push at least.
    torque_scale, torque_margin : float
        As TorqueLimits' scale and margin (N·m).
    tau_min, tau_max : array_like (nq,), optional
    active_begin, active_end : float
        The stretch of s where these contacts hold (active_begin <= active_end; default -inf, inf: the
        whole path), as a phase of TimeScalingProblem.add_contact_phases has: what contact_phase_of_s
        looks up.
    min_link_normal_force, max_lps, cone_offset, projection_tolerance, project_on_demand :
        See TimeScalingProblem.add_contacts: points in link frames, normals in the world frame; margins per
        point (min_normal_force, cone_offset) and per link (min_link_normal_force).

    Attributes
    ----------
    robot : RobotModel
    contacts : list of Contact
    tau_min, tau_max : ndarray (nq,)
        After scale and margin (and any merged TorqueLimits).
    projected_contacts : list of int
        Indices of the contacts whose cone weights enter the projection LPs: all of them, or the convex-hull
        vertices of each flat group.
    section_contacts : list of int
        Indices of the contacts whose per-point minimum enters the projection LPs as k/2 bounded tangential
        weights, the tangential part of their force on the cone's cross-section at the minimum
        (min_normal_force > cone_offset, even cone_edges: every point of a reduced flat group); empty
        otherwise.
    active_begin, active_end : float
        The phase's stretch of s (-inf, inf: the whole path; see TimeScalingProblem.add_contact_phases).
    label : str
        Prefix of its row labels, e.g. 'phases[1]'.
    rest_at_begin : str
        The no-impact row's label if the phase forces sdot = 0 at its first point, else ''.
    """
    def __init__(
        self,
        robot: RobotModel,
        contacts: list[Contact],
        *,
        tau_min: ArrayLike | None = None,
        tau_max: ArrayLike | None = None,
        active_begin: float = -np.inf,
        active_end: float = np.inf,
        cone_edges: int = 8,
        friction_margin: float = 0.0,
        min_normal_force: float = 0.0,
        torque_scale: float = 1.0,
        torque_margin: float = 0.0,
        min_link_normal_force: float = 0.0,
        max_lps: int = 2000,
        cone_offset: float = 0.0,
        projection_tolerance: float = 0.0,
        project_on_demand: bool = False,
    ) -> None: ...
    @property
    def tau_min(self) -> Array:
        """ndarray (nq,): After scale and margin (and any merged TorqueLimits)."""
    @property
    def tau_max(self) -> Array:
        """ndarray (nq,): After scale and margin (and any merged TorqueLimits)."""
    @property
    def physical_tau_min(self) -> Array:
        """(nq,): The torque limits before torque_scale and torque_margin (tightened by any merged TorqueLimits):
        the torque rows of the centred force distribution.
        """
    @property
    def physical_tau_max(self) -> Array:
        """(nq,): The torque limits before torque_scale and torque_margin (see physical_tau_min)."""
    @property
    def projected_contacts(self) -> list[int]:
        """list of int: Indices of the contacts whose cone weights enter the projection LPs: all of them, or the convex-hull
        vertices of each flat group.
        """
    @property
    def section_contacts(self) -> list[int]:
        """list of int: Indices of the contacts whose per-point minimum enters the projection LPs as k/2 bounded tangential
        weights, the tangential part of their force on the cone's cross-section at the minimum
        (min_normal_force > cone_offset, even cone_edges: every point of a reduced flat group); empty
        otherwise.
        """
    @property
    def contacts(self) -> list[Contact]:
        """list of Contact"""
    @property
    def robot(self) -> RobotModel:
        """RobotModel"""
    def force_distribution(self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike, distribution: str = "centre") -> ContactForces:
        """Contact forces that realise each configuration, with the force-distribution LP's margin, at each row of
        q, qd, qdd (how a timing is audited between grid points).

        Parameters
        ----------
        q, qd, qdd : array_like (samples, nq) or (nq,)
            Positions (rad, m), velocities (per s), accelerations (per s²).
        distribution : {"centre", "vertex"}
            "centre" (default): the analytic centre of the physical force set, continuous in the motion (the
            vertex where that set has no interior); "vertex": the LP's optimum (ForceDistribution). margin and
            feasible are the LP's either way.

        Returns
        -------
        ContactForces
        """
    def max_drift(self, path: Path, s: ArrayLike) -> tuple[float, int]:
        """How far contact points move along a path (they should not).

        The largest distance a contact point moves (0 for a path that keeps every contact in place): in the
        world for a world contact, relative to `other_link` for a robot–robot contact, over the samples where
        the constraint is active (a phase: its own stretch).

        Parameters
        ----------
        path : Path
            With as many coordinates as the robot has joints.
        s : array_like (m,)
            Where to look along the path.

        Returns
        -------
        (float, int)
            Largest distance in m, and the index of that contact.
        """
    @property
    def active_begin(self) -> float:
        """float: The phase's stretch of s (-inf, inf: the whole path; see TimeScalingProblem.add_contact_phases)."""
    @property
    def active_end(self) -> float:
        """float: The phase's stretch of s (-inf, inf: the whole path; see TimeScalingProblem.add_contact_phases)."""
    @property
    def label(self) -> str:
        """str: Prefix of its row labels, e.g. 'phases[1]'."""
    @property
    def rest_at_begin(self) -> str:
        """str: The no-impact row's label if the phase forces sdot = 0 at its first point, else ''."""

class ContactForces:
    """Contact forces that realise a motion at samples, with the force-distribution LP's margin.

    ``forces`` and ``torques`` are those of the distribution asked for (ForceDistribution: by default the
    analytic centre of the physical force set, continuous in t). ``margin`` and ``feasible`` are the LP's
    whichever distribution is asked for. At each state (q, q̇, q̈) the LP finds the most robust distribution: the one that maximises the margin
      δ = min( min_ie λ_ie , min_i (n_i·f_i - min_normal_force) , min_l (Σ_{i on l} n_i·f_i - min_link_normal_force) )
    in N, over the cone weights λ (f_i = Σ_e λ_ie g_ie, n_i·g_ie = 1), subject to the torque limits (after
    torque_scale and torque_margin; equalities for unactuated joints). The per-link term (l over the links
    that carry contacts) counts only when min_link_normal_force > 0. The rows are those of the projection
    (the same polytope at this state), so δ >= 0 means the motion is realisable with every margin the
    solve used: friction cones of μ (1 - friction_margin), both minimum normal forces, the torque limits;
    δ < 0 means it needs forces that do not exist (pulling, outside a cone, below a minimum) — by δ
    newtons.

    Attributes
    ----------
    feasible : ndarray of bool (samples,) or bool
        False where no forces of any sign meet the torque limits.
    margin : ndarray (samples,) or float
        N: the smallest cone weight or normal force beyond the minimum; < 0 needs forces that do not exist.
    forces : ndarray (samples, contacts, 3)
        World-frame force on each contact's link, N.
    torques : ndarray (samples, nq)
        Joint torques with these forces, N·m.
    phase : ndarray of int (samples,) or int
        Index of the contact phase of each sample (Trajectory.contact_forces with add_contact_phases: the
        later phase at a switch); -1 without phases. forces then has as many rows as the largest phase has
        contacts, NaN beyond a phase's own.
    centred : ndarray of bool (samples,) or bool
        True where forces is the analytic centre; False for the LP's vertex (asked for, or where the
        physical force set has no interior).
    slack : ndarray (samples,) or float
        N: the smallest slack of forces in the physical rows (friction facets of μ, torque limits before
        scale and margin), each row's distance in force space to its boundary; NaN when not feasible.
    """
    @property
    def feasible(self) -> Array | bool:
        """ndarray of bool (samples,) or bool: False where no forces of any sign meet the torque limits."""
    @property
    def margin(self) -> Array | float:
        """ndarray (samples,) or float: N: the smallest cone weight or normal force beyond the minimum; < 0 needs forces that do not exist."""
    @property
    def forces(self) -> Array:
        """ndarray (samples, contacts, 3): World-frame force on each contact's link, N."""
    @property
    def torques(self) -> Array:
        """ndarray (samples, nq): Joint torques with these forces, N·m."""
    @property
    def phase(self) -> Array | int:
        """ndarray of int (samples,) or int: Index of the contact phase of each sample (Trajectory.contact_forces with add_contact_phases: the
        later phase at a switch); -1 without phases. forces then has as many rows as the largest phase has
        contacts, NaN beyond a phase's own.
        """
    @property
    def centred(self) -> Array | bool:
        """ndarray of bool (samples,) or bool: True where forces is the analytic centre; False for the LP's vertex (asked for, or where the
        physical force set has no interior).
        """
    @property
    def slack(self) -> Array | float:
        """ndarray (samples,) or float: N: the smallest slack of forces in the physical rows (friction facets of μ, torque limits before
        scale and margin), each row's distance in force space to its boundary; NaN when not feasible.
        """

class ContactWrenches:
    """Per-link totals of a contact-force distribution (``Trajectory.contact_wrenches``).

    At each sample, for every link that carries contacts (on either side of a contact: `link`, or
    `other_link` of a robot–robot contact, which receives the opposite force), in first-appearance order
    over the contacts (and phases): the force Σ_i F_i (world frame, N); its moment Σ_i (p_i - o) × F_i about
    the link's origin o (world axes, N·m: what a sole's force/torque sensor at o would read, in world
    axes); the normal force Σ_i n_i·F_i with n_i the contact's normal into the link (N); the centre of
    pressure Σ_i (n_i·F_i) p_i / Σ_i n_i·F_i (world frame, m: the point of the contact plane where the
    normal forces' resultant acts, the zero-moment point of a flat sole; NaN where the link's contacts do
    not share one normal or push with no normal force). A link whose phase does not hold it at a sample has
    zero force and NaN centre of pressure there; a sample whose distribution is infeasible is NaN
    throughout.

    Attributes
    ----------
    links : list of str
        Every link on either side of a contact, in first appearance over the contacts (and phases).
    force : ndarray (samples, links, 3)
        World-frame total force on each link, N.
    moment : ndarray (samples, links, 3)
        Its moment about the link's origin, world axes, N·m.
    center_of_pressure : ndarray (samples, links, 3)
        Σ (n·f_i) p_i / Σ n·f_i, world frame, m; NaN where the link does not push or has several normals.
    normal_force : ndarray (samples, links)
        Sum of the normal forces into each link, N.
    margin : ndarray (samples,) or float
        N: the force-distribution LP's margin at the state of each sample, as ContactForces.margin of
        ``contact_forces(t)`` (the same evaluation whose forces are summed here); -inf where not feasible.
    feasible : ndarray of bool (samples,) or bool
        As ContactForces.feasible: False where no forces of any sign meet the torque limits (the totals are
        NaN there).
    phase : ndarray of int (samples,) or int
        As ContactForces.phase: the contact phase whose contacts served each sample (the later one at a
        switch); -1 without phases.
    """
    @property
    def links(self) -> list[str]:
        """list of str: Every link on either side of a contact, in first appearance over the contacts (and phases)."""
    @property
    def force(self) -> Array:
        """ndarray (samples, links, 3): World-frame total force on each link, N."""
    @property
    def moment(self) -> Array:
        """ndarray (samples, links, 3): Its moment about the link's origin, world axes, N·m."""
    @property
    def center_of_pressure(self) -> Array:
        """ndarray (samples, links, 3): Σ (n·f_i) p_i / Σ n·f_i, world frame, m; NaN where the link does not push or has several normals."""
    @property
    def normal_force(self) -> Array:
        """ndarray (samples, links): Sum of the normal forces into each link, N."""
    @property
    def margin(self) -> Array | float:
        """ndarray (samples,) or float: N: the force-distribution LP's margin at the state of each sample, as ContactForces.margin of
        ``contact_forces(t)`` (the same evaluation whose forces are summed here); -inf where not feasible.
        """
    @property
    def feasible(self) -> NDArray[np.bool_] | bool:
        """ndarray of bool (samples,) or bool: As ContactForces.feasible: False where no forces of any sign meet the torque limits (the totals are
        NaN there).
        """
    @property
    def phase(self) -> NDArray[np.int32] | int:
        """ndarray of int (samples,) or int: As ContactForces.phase: the contact phase whose contacts served each sample (the later one at a
        switch); -1 without phases.
        """

class RobotModel:
    """A rigid-body tree from a URDF (immutable, shareable across threads).

    Joint coordinates are in rad (revolute) or m (prismatic). One body per movable joint (fixed joints
    merged into their parent, inertias combined), in depth-first order from the root with children in
    urdfdom's order, which is also pinocchio's.

    Mimic joints (URDF <mimic>, e.g. the second finger of a gripper) have a body but no coordinate:
    q_mimic = multiplier · q_joint + offset, as in pinocchio. q, q̇, q̈ and τ are then over the other joints
    only (nq is less than the number of bodies); the mimic joint's torque acts on its joint scaled by the
    multiplier (τ = Eᵀ τ_bodies by virtual work, E = ∂q_bodies/∂q), and its own effort limit is not used.

    Attributes
    ----------
    nq : int
    name : str
    joint_names, link_names : list of str
    velocity_limits : ndarray (nq,)
        URDF velocity limits, rad/s (m/s).
    effort_limits : ndarray (nq,)
        URDF effort limits, N·m (N).
    position_limits : ndarray (2, nq)
        Lower and upper, rad (m).
    gravity_vector : ndarray (3,)
        m/s² in the world frame.
    mass : float
        kg, of the moving bodies (the weight of center_of_mass).
    mimic_joints : list of (str, str, float, float)
        URDF mimic joints (name, joint, multiplier, offset): q_name = multiplier · q_joint + offset, as in
        pinocchio. They have no coordinate in q; their torque acts on their joint, times the multiplier.
    frozen_mimic_joints : list of str
        Mimic joints locked without their joint (locked_joints): frozen at their value while their joint
        moves, the relation dropped (as in a model reduced on them alone, e.g. pinocchio's
        buildReducedModel); lock their joint to keep it. A mimic locked with its joint at values that break
        the relation is an InvalidInputError.
    joint_units : list of str
        The unit of each coordinate q[j]: 'rad' (revolute) or 'm' (prismatic; a floating base's x, y, z).
    """
    @staticmethod
    def combine(parts: list[RobotModel], name: str = "") -> RobotModel:
        """One model of several independent trees (robots and free objects, sec. III.b); q concatenates the parts'.

        Link names must be unique across the parts (contacts refer to links); a joint name shared by parts
        becomes '<part>/<joint>' (e.g. the floating_* coordinates of two floating parts). Gravity must agree.

        Parameters
        ----------
        parts : list of RobotModel
        name : str
            The combined model's name.
        """
    @staticmethod
    def free_object(name: str, mass: float, com: ArrayLike = (0.0, 0.0, 0.0), inertia: ArrayLike = ...,
                    gravity: ArrayLike = (0.0, 0.0, -9.81)) -> RobotModel:
        """A free rigid body (sec. III.b): one link `name` with six floating coordinates (x, y, z, rz, ry, rx, as
        a floating base's) and zero effort.

        Parameters
        ----------
        name : str
        mass : float
            kg.
        com : array_like (3,)
            Centre of mass in the link frame, m.
        inertia : array_like (3, 3)
            About the centre of mass `com`, in the link frame, kg·m²; symmetric positive semi-definite.
        gravity : array_like (3,)
            m/s², world frame.
        """
    @staticmethod
    def from_urdf(
        path: str | os.PathLike[str], floating_base: bool = False, locked_joints: dict[str, float] | None = None,
        gravity: ArrayLike = (0.0, 0.0, -9.81),
    ) -> RobotModel:
        """Loads a URDF file.

        Parameters
        ----------
        path : str or os.PathLike
        floating_base : bool
            Six unactuated virtual joints in front of the root (x, y, z in m, then rotations about z, y, x in rad).
        locked_joints : dict of str to float, optional
            Joints held at a value (rad or m) and removed from q (e.g. gripper fingers).
        gravity : array_like (3,)
            m/s², world frame.

        Returns
        -------
        RobotModel

        Raises
        ------
        InvalidInputError
            Unreadable file, invalid URDF, unknown locked joint.
        """
    @staticmethod
    def from_urdf_file(
        path: str | os.PathLike[str], floating_base: bool = False, locked_joints: dict[str, float] | None = None,
        gravity: ArrayLike = (0.0, 0.0, -9.81),
    ) -> RobotModel:
        """The same as ``from_urdf`` (the C++ name, RobotModel::from_urdf_file)."""
    def gravity_torques(self, q: ArrayLike) -> Array:
        """The same as ``gravity(q)`` (the C++ name, RobotModel::gravity_torques): (nq,) in N·m."""
    @staticmethod
    def from_urdf_string(
        xml: str, floating_base: bool = False, locked_joints: dict[str, float] | None = None,
        gravity: ArrayLike = (0.0, 0.0, -9.81),
    ) -> RobotModel:
        """As ``from_urdf``, from the URDF's XML text."""
    @property
    def nq(self) -> int:
        """int"""
    @property
    def name(self) -> str:
        """str"""
    @property
    def joint_names(self) -> list[str]:
        """list of str"""
    @property
    def link_names(self) -> list[str]:
        """list of str"""
    @property
    def velocity_limits(self) -> Array:
        """ndarray (nq,): URDF velocity limits, rad/s (m/s)."""
    @property
    def effort_limits(self) -> Array:
        """ndarray (nq,): URDF effort limits, N·m (N)."""
    @property
    def position_limits(self) -> Array:
        """ndarray (2, nq): Lower and upper, rad (m)."""
    @property
    def gravity_vector(self) -> Array:
        """ndarray (3,): m/s² in the world frame."""
    def inverse_dynamics(self, q: ArrayLike, qd: ArrayLike, qdd: ArrayLike) -> Array:
        """τ = M(q) q̈ + C(q, q̇) q̇ + g(q) by RNEA (the recursive Newton-Euler algorithm).

        Parameters
        ----------
        q, qd, qdd : array_like (nq,)
            rad, rad/s, rad/s² (m, m/s, m/s² for prismatic joints).

        Returns
        -------
        ndarray (nq,)
            N·m (N).
        """
    def mass_matrix(self, q: ArrayLike) -> Array:
        """M(q), (nq, nq), in kg·m² (kg for prismatic coordinates)."""
    def gravity(self, q: ArrayLike) -> Array:
        """g(q): the joint torques that hold the robot still at q, (nq,) in N·m."""
    def frame_placement(self, q: ArrayLike, link: str) -> Array:
        """World placement of a link's frame at q: a 4x4 homogeneous matrix (translation in m)."""
    def frame_jacobian(self, q: ArrayLike, link: str, point: ArrayLike = (0.0, 0.0, 0.0)) -> Array:
        """World-frame Jacobian (6, nq) of a point fixed in a link: rows 0-2 the point's linear velocity, rows 3-5
        the link's angular velocity (pinocchio's LOCAL_WORLD_ALIGNED layout).

        Parameters
        ----------
        q : array_like (nq,)
        link : str
        point : array_like (3,)
            In the link frame, m.
        """
    def path_frame_motion(
        self, q: ArrayLike, dq: ArrayLike, ddq: ArrayLike, link: str, point: ArrayLike = (0.0, 0.0, 0.0)
    ) -> tuple[Array, Array, Array, Array]:
        """The motion of a point fixed in a link along a path, per sample, by one forward pass (no Jacobian formed).

        Parameters
        ----------
        q, dq, ddq : array_like (m, nq)
            p, p', p'' at m samples.
        link : str
        point : array_like (3,)
            In the link frame, m.

        Returns
        -------
        (v, w, a, alpha) : ndarrays (m, 3), world frame
            v = J p' and w = J_ω p' (velocity and angular velocity at ṡ = 1); a = J p'' + J̇(p') p' (the
            classical acceleration at ṡ = 1, s̈ = 0) and alpha = J_ω p'' + J̇_ω(p') p'. At speed ṡ and s̈ the
            point moves at v ṡ and accelerates at a ṡ² + v s̈.
        """
    def point_jacobian(self, q: ArrayLike, link: str, point: ArrayLike = (0.0, 0.0, 0.0)) -> Array:
        """World-frame linear Jacobian (3, nq) of a point fixed in a link.

        Parameters
        ----------
        q : array_like (nq,)
        link : str
        point : array_like (3,)
            In the link frame, m.
        """
    def path_torque_coefficients(self, q: ArrayLike, dq: ArrayLike, ddq: ArrayLike) -> tuple[Array, Array, Array]:
        """Eq. (12): τ = a ṡ² + b s̈ + c along a path, at each row (q = p(s)).

        Parameters
        ----------
        q, dq, ddq : array_like (m, nq)
            p, p', p'' at m samples.

        Returns
        -------
        (a, b, c) : ndarrays (m, nq)
            a = M p'' + C(q, p') p', b = M p', c = g(q), in N·m per the units of ṡ², s̈ and 1.
        """
    def center_of_mass(self, q: ArrayLike) -> Array:
        """Centre of mass of the moving bodies at q.

        Parameters
        ----------
        q : array_like (nq,)
            Joint positions (rad or m).

        Returns
        -------
        ndarray (3,)
            World coordinates in m. Links fixed to the world (a fixed base's root link) do not move and are not
            counted (as pinocchio's centerOfMass).
        """
    @property
    def mimic_joints(self) -> list[tuple[str, str, float, float]]:
        """list of (str, str, float, float): URDF mimic joints (name, joint, multiplier, offset): q_name = multiplier · q_joint + offset, as in
        pinocchio. They have no coordinate in q; their torque acts on their joint, times the multiplier.
        """
    @property
    def frozen_mimic_joints(self) -> list[str]:
        """list of str: Mimic joints locked without their joint (locked_joints): frozen at their value while their joint
        moves, the relation dropped (as in a model reduced on them alone, e.g. pinocchio's
        buildReducedModel); lock their joint to keep it. A mimic locked with its joint at values that break
        the relation is an InvalidInputError.
        """
    @property
    def joint_units(self) -> list[str]:
        """list of str: The unit of each coordinate q[j]: 'rad' (revolute) or 'm' (prismatic; a floating base's x, y, z)."""
    @property
    def mass(self) -> float:
        """float: kg, of the moving bodies (the weight of center_of_mass)."""

class Status(Enum):
    """How a solve ended: OPTIMAL, INFEASIBLE, ITERATION_LIMIT, NUMERICAL_ERROR, UNBOUNDED or TIME_LIMIT (see
    Result.status).
    """
    OPTIMAL = ...
    INFEASIBLE = ...
    ITERATION_LIMIT = ...
    NUMERICAL_ERROR = ...
    UNBOUNDED = ...
    TIME_LIMIT = ...

class FeasibleSet:
    """The pruned feasible polygon of (x, u) = (ṡ², s̈) at one grid point.

    The set {(x, u) : a_i x + b_i u <= c_i, x_min <= x <= x_max} at grid point `index`, reduced to its
    supporting half-planes (the redundant ones pruned, sec. IV.A).

    Attributes
    ----------
    index : int
    s : float
    halfplanes : ndarray (r, 3)
        Supporting half-planes, rows [a, b, c] of a·x + b·u <= c. Bounds on x alone (b = 0) are folded into
        x_min / x_max and not repeated here.
    labels : list of str
        The constraint row behind each half-plane.
    x_min : float
        Lower bound on ṡ² (1/s²): 0 unless a constraint raises it.
    x_max : float
        Upper bound on ṡ² (1/s²): eq. (16) and any other bound on x alone.
    x_max_label : str
        The constraint row giving x_max ('' if none).
    vertices : ndarray (v, 2)
        Counter-clockwise vertices (x, u). An unbounded set (e.g. velocity limits only: u is free) is shown
        cut at 1e15 times the problem's typical ṡ² and s̈ (those the solve is scaled by), with bounded =
        False.
    empty, bounded : bool
    exact : bool
        False where a projected constraint (contacts) is only an inner approximation at this grid point:
        its LP solver failed or its LP budget ran out, and the polygon is the hull found so far.
    """
    @property
    def index(self) -> int:
        """int"""
    @property
    def s(self) -> float:
        """float"""
    @property
    def halfplanes(self) -> Array:
        """ndarray (r, 3): Supporting half-planes, rows [a, b, c] of a·x + b·u <= c. Bounds on x alone (b = 0) are folded into
        x_min / x_max and not repeated here.
        """
    @property
    def labels(self) -> list[str]:
        """list of str: The constraint row behind each half-plane."""
    @property
    def x_min(self) -> float:
        """float: Lower bound on ṡ² (1/s²): 0 unless a constraint raises it."""
    @property
    def x_max(self) -> float:
        """float: Upper bound on ṡ² (1/s²): eq. (16) and any other bound on x alone."""
    @property
    def x_max_label(self) -> str:
        """str: The constraint row giving x_max ('' if none)."""
    @property
    def vertices(self) -> Array:
        """ndarray (v, 2): Counter-clockwise vertices (x, u). An unbounded set (e.g. velocity limits only: u is free) is shown
        cut at 1e15 times the problem's typical ṡ² and s̈ (those the solve is scaled by), with bounded =
        False.
        """
    @property
    def empty(self) -> bool:
        """bool"""
    @property
    def bounded(self) -> bool:
        """bool"""
    @property
    def exact(self) -> bool:
        """bool: False where a projected constraint (contacts) is only an inner approximation at this grid point:
        its LP solver failed or its LP budget ran out, and the polygon is the hull found so far.
        """
    def contains(self, x: float, u: float, tol: float = 1e-9) -> bool:
        """Whether (x, u) = (ṡ², s̈) satisfies every half-plane to within tol, relative to the row's own terms
        (max(1, |a x|, |b u|, |c|); the bounds on x relative to max(1, |x|)). Non-finite points are outside.
        """

class Trajectory:
    """The timed path: q(t) = p(s(t)) with s(t) piecewise quadratic through the grid (eq. 24).

    Parameters
    ----------
    path : Path
    s : array_like (N+1,)
        Grid.
    sdot : array_like (N+1,)
        ṡ at the grid points, 1/s; >= 0 with no two consecutive zeros.
    sddot_points : array_like (N+1,), optional
        s̈ at the grid points of a jerk-limited timing (add_jerk_limits): s̈ is linear in s between them, with
        θ = ṡ² consistent (θ_{k+1} = θ_k + Δs_k (s̈_k + s̈_{k+1}), to 1e-9 relative), and an end at rest (ṡ = 0) has
        constant s⃛ on its interval (s̈ = 0 there, θ_1 = 1.5 Δs_0 s̈_1). None: s̈ constant per interval (eq. 24).

    Attributes
    ----------
    duration : float
        T in s.
    times : ndarray (N+1,)
        t_k of the grid points, s.
    grid : ndarray (N+1,)
        s at the grid points, s_0..s_N.
    sdot_grid : ndarray (N+1,)
        ṡ at the grid points, 1/s.
    sddot_points : ndarray (N+1,) or None
        s̈ at the grid points of a jerk-limited timing (s̈ continuous); None (C++: empty) otherwise.
    path : Path
    robot : RobotModel or None
        The robot whose torque limits or contacts shaped it; None (C++: null) if none did.
    contacts : ContactConstraint or None
    contact_phases : list of ContactConstraint
        The ContactConstraint of each phase (add_contact_phases), in order of s; [] without phases.

    Calling ``traj(t, order)`` gives q (order 0), q̇ (1) or q̈ (2), as toppra's trajectories.
    """
    def __init__(self, path: Path, s: ArrayLike, sdot: ArrayLike, sddot_points: ArrayLike | None = None) -> None: ...
    def contact_forces(self, t: ArrayLike, distribution: str = "centre") -> ContactForces:
        """Contact forces at t that realise the motion (the solver looked only at grid points).

        With contact phases (``add_contact_phases``) each t uses the contacts of its phase, the later one at a
        switch time; ``.phase`` gives the phase of each t and ``forces`` has as many rows as the largest phase
        has contacts (NaN beyond a phase's own). Raises Error if no contact constraint shaped the trajectory.

        Parameters
        ----------
        t : float or array_like
            Times, s.
        distribution : {"centre", "vertex"}
            "centre" (default): at each t the analytic centre of the physical force set, continuous in t
            wherever the motion is (the LP's vertex where that set has no interior; ``centred`` says which);
            "vertex": the force-distribution LP's optimum (ForceDistribution).

        Returns
        -------
        ContactForces
        """
    def contact_wrenches(self, t: float | ArrayLike, distribution: str = "centre") -> ContactWrenches:
        """Per-link wrenches and centres of pressure of ``contact_forces(t)``: what a controller or a balance check
        reads (the centre of pressure inside each sole). Raises Error if no contact constraint shaped the
        trajectory.

        For every link on either side of a contact (first appearance over the contacts and phases): the total
        force (world frame, N), its moment about the link's origin (world axes, N·m), the sum of the normal
        forces into the link (N), and the centre of pressure Σ (n·f_i) p_i / Σ n·f_i (world frame, m; NaN
        where the link does not push, or its contacts have several normals). A link its phase does not hold
        has zero force there; an infeasible sample is NaN.

        Parameters
        ----------
        t : float or array_like
            Times, s.
        distribution : {"centre", "vertex"}
            As for contact_forces (default "centre").

        Returns
        -------
        ContactWrenches
        """
    def centers_of_pressure(self, t: float | ArrayLike, distribution: str = "centre") -> Array:
        """``contact_wrenches(t, distribution).center_of_pressure``: (samples, links, 3), m.

        The links are ``contact_wrenches(t).links``; NaN where a link does not push.
        """
    def contact_phase(self, t: float | ArrayLike) -> Any:
        """Index into contact_phases of the phase at each t (the later one at a switch); -1 without phases.

        contact_phase_of_s(contact_phases, s(t)): the phase whose [active_begin, active_end] holds s(t); at a
        switch the later one, the contacts that hold after it.
        """
    @property
    def contact_phases(self) -> list[ContactConstraint]:
        """list of ContactConstraint: The ContactConstraint of each phase (add_contact_phases), in order of s; [] without phases."""
    @property
    def contacts(self) -> ContactConstraint | None:
        """ContactConstraint or None"""
    @property
    def duration(self) -> float:
        """float: T in s."""
    @property
    def times(self) -> Array:
        """ndarray (N+1,): t_k of the grid points, s."""
    @property
    def grid(self) -> Array:
        """ndarray (N+1,): s at the grid points, s_0..s_N."""
    @property
    def sdot_grid(self) -> Array:
        """ndarray (N+1,): ṡ at the grid points, 1/s."""
    @property
    def path(self) -> Path:
        """Path"""
    def s(self, t: float | ArrayLike) -> tuple[Any, Any, Any]:
        """(s, ṡ, s̈) at t: floats for a scalar t, arrays (m,) otherwise; ṡ in 1/s, s̈ in 1/s².

        t is clamped to [0, T]; s̈ is that of the interval to the right of t (to the left at t = T).
        """
    def q(self, t: float | ArrayLike) -> Array:
        """q(t), rad (m).

        Parameters
        ----------
        t : float or array_like (m,)
            Times in s, clamped to [0, duration].

        Returns
        -------
        ndarray
            (n,) for a scalar t, (m, n) for an array.
        """
    def qd(self, t: float | ArrayLike) -> Array:
        """q̇(t) = p'(s) ṡ (eq. 10), rad/s; shapes as ``q``."""
    def qdd(self, t: float | ArrayLike) -> Array:
        """q̈(t) = p''(s) ṡ² + p'(s) s̈ (eq. 11), rad/s²; s̈ of the interval to the right of t."""
    def qddd(self, t: float | ArrayLike) -> Array:
        """The jerk q⃛(t) = p' s⃛ + 3 p'' ṡ s̈ + p''' ṡ³, rad/s³: (len(t), n). Needs a path of polynomial pieces (p''').

        For a jerk-limited timing s⃛ is finite; for the piecewise-constant s̈ of other timings s⃛ = 0 inside each
        interval and a jump of q̈ at grid points is not shown.
        """
    @property
    def sddot_points(self) -> Array | None:
        """ndarray (N+1,) or None: s̈ at the grid points of a jerk-limited timing (s̈ continuous); None (C++: empty) otherwise."""
    def evaluate(self, t: float | ArrayLike) -> tuple[Array, Array, Array]:
        """(q, q̇ = p'ṡ, q̈ = p''ṡ² + p's̈) at t; shapes as ``q``."""
    def sample(self, dt: float, max_memory: float = 1e9) -> dict[str, Array]:
        """Uniform resampling.

        Parameters
        ----------
        dt : float
            Period in s; T is appended when it is not a multiple of dt.
        max_memory : float
            Bytes (> 0): a dt that would need more (t, q, q̇, q̈ and the path's own p, p', p'' while evaluating)
            is an InvalidInputError saying how much, before anything is allocated (a dt meant in ms but given in
            s would otherwise fill the memory).

        Returns
        -------
        dict
            ``t`` (m,) in s, ``q``, ``qd``, ``qdd`` (m, n).
        """
    def sample_times(self, dt: float) -> Array:
        """The times 0, dt, 2 dt, ... of ``sample``, in s, with T appended when it is not a multiple of dt."""
    def torques(self, t: float | ArrayLike, robot: RobotModel | None = None) -> Array:
        """τ(t) = RNEA(q, q̇, q̈) along the timing, so that usage can be plotted against the limits.

        Parameters
        ----------
        t : float or array_like (m,)
            Times in s.
        robot : RobotModel, optional
            Default: the robot whose limits shaped the trajectory.

        Returns
        -------
        ndarray
            (nq,) or (m, nq), N·m.
        """
    def __call__(self, t: float | ArrayLike, order: int = 0) -> Array:
        """q(t) (order 0, rad or m), q̇(t) (1, per s) or q̈(t) (2, per s²), as toppra's ``traj(t, order)``.

        Parameters
        ----------
        t : float or array_like (m,)
            Times in s, clamped to [0, duration].
        order : {0, 1, 2}

        Returns
        -------
        ndarray
            (n,) for a scalar t, (m, n) for an array.
        """
    def time_spline(self) -> CubicSplinePath:
        """A C² cubic spline in time through the grid (toppra's ParametrizeSpline).

        Returns
        -------
        CubicSplinePath
            Parameter t in s (knots = ``times``), through q(t_k) = p(s_k), clamped to q̇ = p'(s) ṡ at both ends;
            its ``q``, ``dq``, ``ddq`` are q(t), q̇(t), q̈(t) with q̈ continuous. Between grid points it departs
            from the exact timing by O(Δt⁴), so check it against the limits.

        For controllers that interpolate between points: unlike the exact timing, its q̈ is continuous, and its
        q̇, q̈ may exceed the limits by a little between grid points; check it with the problem's limits before
        sending it to a robot.
        """
    @property
    def robot(self) -> RobotModel | None:
        """RobotModel or None: The robot whose torque limits or contacts shaped it; None (C++: null) if none did."""
    def to_joint_trajectory(self, dt: float | None = None, joint_names: list[str] | None = None,
                            robot: RobotModel | None = None, spline: bool = False) -> dict[str, Any]:
        """The trajectory as a ``trajectory_msgs/JointTrajectory``-shaped dict, ready for ``json.dumps``.

        Parameters
        ----------
        dt : float, optional
            Controller period in s; None: one point per grid time of the solver.
        joint_names : sequence of str, optional
            Default: the robot's joint names, else ``joint_0``, ``joint_1``, ...
        robot : RobotModel, optional
            For ``effort`` (N·m or N, by inverse dynamics of the exported motion). Default: the robot whose
            torque limits or contacts shaped the trajectory; without one, ``effort`` lists are empty (as ROS
            allows).
        spline : bool
            See ``resample``.

        Returns
        -------
        dict
            ``{"joint_names": [...], "points": [{"positions", "velocities", "accelerations", "effort",
            "time_from_start": {"sec", "nanosec"}}, ...]}`` (ROS 2 field names; plain Python floats and ints).
        """
    def resample(self, dt: float | None = None, spline: bool = False) -> dict[str, Array]:
        """Samples of the trajectory at a controller rate.

        Parameters
        ----------
        dt : float, optional
            Sample period in s (e.g. 0.001 for a 1 kHz controller); the duration T is appended when it is not a
            multiple of dt. None: the solver's grid times. Refused as ``sample`` is beyond 1 GB.
        spline : bool
            False (default): the exact timing, sampled (q̈ jumps at grid points, between samples): every sample
            meets the limits the problem was solved under (at every instant with ``guarantee="continuous"``).
            True: from ``time_spline()``, the C² cubic spline in t through the grid (continuous q̈), which rings
            where the exact q̈ jumps: up to 1.26x the acceleration limits (measured, any N); solve with
            acceleration limits x 0.75 if the spline is what the robot executes.

        Returns
        -------
        dict
            ``t`` (m,) in s; ``q`` (m, n) in rad or m; ``qd`` (m, n) per s; ``qdd`` (m, n) per s².
        """

class Result:
    """What a solve returns.

    ``bool(result)`` is ``result.ok``.

    Attributes
    ----------
    status : Status
        OPTIMAL, INFEASIBLE (see infeasible_*), ITERATION_LIMIT (feasible, maybe not optimal),
        TIME_LIMIT (``time_limit`` reached: feasible, stats['gap'] bounds its distance to the optimum),
        NUMERICAL_ERROR (the LP solver failed) or UNBOUNDED (nothing bounds the speed).
    ok : bool
        True for OPTIMAL, ITERATION_LIMIT and TIME_LIMIT (a feasible timing).
    message : str
        Why a solve failed, with grid index, s and binding constraint; for a timing whose path moves its
        contacts (``contact_drift``), which contacts move.
    contact_drift : list of dict
        Contacts that the path moves although they should hold (drift='warn', or 'auto' within 10x
        drift_tolerance): constraint, contact, link, s, drift (m), tolerance (m), message. The contact forces
        of this timing assume they stay; message says so too.
    tau_min, tau_max : ndarray (nq,) or None
        The torque limits the solve held (N·m or N, after scale and margin; the problem's TorqueLimits, else
        its (last) contact constraint's), None (C++: empty) without torque limits: what a plot "against the
        limits" shows.
    duration : float
        T in s (nan without a timing).
    s : ndarray (N+1,)
        The grid s_0..s_N.
    sdot : ndarray (N+1,)
        ṡ_k at the grid points, 1/s.
    times : ndarray (N+1,)
        t_k at the grid points, s; t_0 = 0.
    sddot : ndarray (N,)
        s̈ on each interval, 1/s².
    sddot_points : ndarray (N+1,) or None
        s̈ at the grid points of a jerk-limited timing (s̈ linear in s between them; ``sddot`` is then each
        interval's mean); None (C++: empty) otherwise.
    infeasible_index : int
        First grid index where no timing exists (-1 if feasible).
    infeasible_s : float
    binding_constraints : list of str
        The constraint rows that bind there.
    stats : dict
        slp_iterations, lp_solves, greatest_element (exact optimum without SLP), gap (certified bound on
        (T - T*) / T*), average_halfplanes, time_feasible_sets, time_reachability, time_slp (s).
        With jerk limits: jerk_iterations (linearisation rounds), jerk_linearised_gap (bound on (T - T_lin*) / T,
        T_lin* the optimum of the convex problem linearised at the final timing; also in gap: not a bound to
        the global optimum of this non-convex problem) and second_order_duration (T without jerk limits on the
        same grid: a lower bound of the continuous-time optimum as N grows, not of this grid's; 0 without jerk limits).
    relaxation : dict of str to float
        For an INFEASIBLE result (when solved with explain): family -> smallest scale of that family's limits
        that makes the problem feasible, e.g. {'torque': 1.18, 'velocity': inf} (see
        TimeScalingProblem.relaxation).
    binding : list of str
        For a timed result: per interval (N entries) the label of the constraint that binds there (the row
        with the least relative slack at the solution, if below 1e-6), '' where none does: typically the
        interval of a bang-bang switch, whose end speeds are set by its neighbours' limits (to colour a
        phase-plane plot by the active limit).
    """
    @property
    def status(self) -> Status:
        """Status: OPTIMAL, INFEASIBLE (see infeasible_*), ITERATION_LIMIT (feasible, maybe not optimal),
        TIME_LIMIT (``time_limit`` reached: feasible, stats['gap'] bounds its distance to the optimum),
        NUMERICAL_ERROR (the LP solver failed) or UNBOUNDED (nothing bounds the speed).
        """
    @property
    def message(self) -> str:
        """str: Why a solve failed, with grid index, s and binding constraint; for a timing whose path moves its
        contacts (``contact_drift``), which contacts move.
        """
    @property
    def duration(self) -> float:
        """float: T in s (nan without a timing)."""
    @property
    def s(self) -> Array:
        """ndarray (N+1,): The grid s_0..s_N."""
    @property
    def sdot(self) -> Array:
        """ndarray (N+1,): ṡ_k at the grid points, 1/s."""
    @property
    def times(self) -> Array:
        """ndarray (N+1,): t_k at the grid points, s; t_0 = 0."""
    @property
    def sddot(self) -> Array:
        """ndarray (N,): s̈ on each interval, 1/s²."""
    @property
    def sddot_points(self) -> Array | None:
        """ndarray (N+1,) or None: s̈ at the grid points of a jerk-limited timing (s̈ linear in s between them; ``sddot`` is then each
        interval's mean); None (C++: empty) otherwise.
        """
    @property
    def ok(self) -> bool:
        """bool: True for OPTIMAL, ITERATION_LIMIT and TIME_LIMIT (a feasible timing)."""
    @property
    def infeasible_index(self) -> int:
        """int: First grid index where no timing exists (-1 if feasible)."""
    @property
    def infeasible_s(self) -> float:
        """float"""
    @property
    def binding_constraints(self) -> list[str]:
        """list of str: The constraint rows that bind there."""
    @property
    def relaxation(self) -> dict[str, float]:
        """dict of str to float: For an INFEASIBLE result (when solved with explain): family -> smallest scale of that family's limits
        that makes the problem feasible, e.g. {'torque': 1.18, 'velocity': inf} (see
        TimeScalingProblem.relaxation).
        """
    @property
    def binding(self) -> list[str]:
        """list of str: For a timed result: per interval (N entries) the label of the constraint that binds there (the row
        with the least relative slack at the solution, if below 1e-6), '' where none does: typically the
        interval of a bang-bang switch, whose end speeds are set by its neighbours' limits (to colour a
        phase-plane plot by the active limit).
        """
    @property
    def stats(self) -> dict[str, Any]:
        """dict: slp_iterations, lp_solves, greatest_element (exact optimum without SLP), gap (certified bound on
        (T - T*) / T*), average_halfplanes, time_feasible_sets, time_reachability, time_slp (s).
        With jerk limits: jerk_iterations (linearisation rounds), jerk_linearised_gap (bound on (T - T_lin*) / T,
        T_lin* the optimum of the convex problem linearised at the final timing; also in gap: not a bound to
        the global optimum of this non-convex problem) and second_order_duration (T without jerk limits on the
        same grid: a lower bound of the continuous-time optimum as N grows, not of this grid's; 0 without jerk limits).
        """
    @property
    def contact_drift(self) -> list[dict[str, Any]]:
        """list of dict: Contacts that the path moves although they should hold (drift='warn', or 'auto' within 10x
        drift_tolerance): constraint, contact, link, s, drift (m), tolerance (m), message. The contact forces
        of this timing assume they stay; message says so too.
        """
    @property
    def tau_min(self) -> Array | None:
        """ndarray (nq,) or None: The torque limits the solve held (N·m or N, after scale and margin; the problem's TorqueLimits, else
        its (last) contact constraint's), None (C++: empty) without torque limits: what a plot "against the
        limits" shows.
        """
    @property
    def tau_max(self) -> Array | None:
        """ndarray (nq,) or None: The torque limits the solve held (N·m or N, after scale and margin; the problem's TorqueLimits, else
        its (last) contact constraint's), None (C++: empty) without torque limits: what a plot "against the
        limits" shows.
        """
    def trajectory(self) -> Trajectory:
        """The timed trajectory (Trajectory); raises pathpace.Error when there is no timing."""
    def __bool__(self) -> bool:
        """True when the timing is usable (``ok``): ``if res: ...``"""

class TimeScalingProblem:
    """Time-optimal timing of a path under constraints (sec. V).

    Minimises T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) (eq. 25, 27) over the speeds at the grid points, with every
    constraint enforced at every grid point with the s̈ of the interval on each side (eq. 26). Build once,
    then ``solve``: a built problem may be solved from several threads.

    Threads: a problem is either read (any number of solve, feasible_set, relaxation, restarted at once)
    or modified (one add_* / set_* at a time), never both. A call that would overlap the other kind in
    another thread raises Error at once instead of waiting (a program that does this has a race it
    should know about): "add_contacts: this TimeScalingProblem is being solved in another thread; ...".

    solve releases the GIL.

    Parameters
    ----------
    path : Path or path-like
        A pathpace Path, or anything ``pathpace.as_path`` takes: a scipy PPoly / CubicSpline / BSpline, a toppra
        interpolator, a callable f(s) -> (q, dq, ddq).
    grid : int, array_like (N+1,) or 'auto'
        N uniform intervals over the path, a strictly increasing grid from s_begin to s_end, or 'auto'
        (pathpace.auto_grid(path, grid_tolerance): refined where the path bends; the N used is
        ``intervals``).
    grid_tolerance : float
        Of grid='auto'.
    constraints : list, optional
        Keyword only. toppra's constraint objects (JointVelocityConstraint, JointAccelerationConstraint,
        JointTorqueConstraint, SecondOrderConstraint, JointVelocityConstraintVarying) or pathpace Constraints,
        each added as the add_* call that means the same (pathpace.toppra_compat.add_constraints), so that a
        toppra script keeps its constraint lines. Another type, dry friction (fs_coef != 0) or a nonzero
        custom_term is an InvalidInputError naming ``constraints[i]`` and its type.

    Attributes
    ----------
    grid : ndarray (N+1,)
    intervals : int
    path : Path
    constraints : list of Constraint
    sdot_begin : float
        ṡ at s_begin in 1/s (set_boundary_speeds).
    sdot_end : float
        ṡ at s_end in 1/s (set_boundary_speeds).
    joint_names : list of str
        See ``set_joint_names``.
    """
    def __init__(
        self,
        path: Path | Any,
        grid: int | str | ArrayLike = 100,
        grid_tolerance: float = 1e-3,
        *,
        constraints: list[Any] | None = None,
    ) -> None: ...
    def add_velocity_limits(self, vmin: ArrayLike, vmax: ArrayLike) -> None:
        """Joint velocity limits (eq. 13); see VelocityLimits.

        Parameters
        ----------
        vmin, vmax : array_like (n,)
            rad/s (m/s); vmin <= 0 <= vmax, ±inf for none.
        """
    def add_jerk_limits(self, jmin: ArrayLike, jmax: ArrayLike) -> None:
        """Joint jerk limits jmin <= q⃛ <= jmax (see JerkLimits): the timing's s̈ becomes continuous.

        s̈ is then linear in s between grid points (ṡ² quadratic), so q̈ is continuous; an end at rest starts or
        stops with constant s⃛ on its interval (s̈ = 0 there). Every other constraint's rows hold at the grid points
        with the s̈ there; the jerk limits hold at the grid points on both sides (the s⃛ of each adjacent interval).
        solve() first solves the problem without jerk limits, then linearises the jerk rows (an inner
        approximation, so every round's timing is feasible) and improves T round by round (docs/method.md).
        OPTIMAL means a first-order (KKT) point of this non-convex problem: within ``tolerance`` of the optimum of the
        convex problem linearised there (stats["jerk_linearised_gap"]); not a global optimum. A second call
        replaces the limits. Needs a path of polynomial pieces (p''') and N >= 4; guarantee = 'continuous' and
        restarted() are not implemented with jerk limits yet (InvalidInput).

        Parameters
        ----------
        jmin, jmax : array_like (n,)
            rad/s³ (m/s³); jmin < 0 < jmax, ∓inf for none.
        """
    def add_acceleration_limits(self, amin: ArrayLike, amax: ArrayLike) -> None:
        """Joint acceleration limits (eq. 14); see AccelerationLimits.

        Parameters
        ----------
        amin, amax : array_like (n,)
            rad/s² (m/s²); amin <= amax.
        """
    def add_linear_constraint(
        self, A: ArrayLike, B: ArrayLike, C: ArrayLike, lo: ArrayLike, hi: ArrayLike, label: str = "linear"
    ) -> None:
        """lo <= A·ṡ² + B·s̈ + C <= hi per grid point; arrays (N+1, r). See LinearConstraint."""
    def add_frame_translational_speed_limit(
        self, robot: RobotModel, link: str, v_max: float, *, point: ArrayLike = (0.0, 0.0, 0.0)
    ) -> None:
        """‖v‖ <= v_max for a point on a link (Drake's AddFrameTranslationalSpeedLimit); see FrameLimits.

        Parameters
        ----------
        robot : RobotModel
        link : str
        v_max : float
            m/s, > 0.
        point : array_like (3,)
            In the link frame, m.
        """
    def add_frame_velocity_limits(
        self,
        robot: RobotModel,
        link: str,
        lo: ArrayLike,
        hi: ArrayLike,
        *,
        angular: bool = False,
        frame: str = "world",
        point: ArrayLike = (0.0, 0.0, 0.0),
    ) -> None:
        """lo <= v <= hi per axis for a point's linear velocity or a link's angular velocity (Drake's
        AddFrameVelocityLimit, which takes [ω, v] together); see FrameLimits.

        Parameters
        ----------
        robot : RobotModel
        link : str
        lo, hi : array_like (3,)
            m/s (rad/s if angular), lo <= 0 <= hi; ±inf: no limit.
        angular : bool
            Bound the angular velocity of the link instead of the point's linear velocity.
        frame : str
            "world" or "local" (the link frame's axes).
        point : array_like (3,)
            In the link frame, m.
        """
    def add_frame_acceleration_limits(
        self,
        robot: RobotModel,
        link: str,
        lo: ArrayLike,
        hi: ArrayLike,
        *,
        angular: bool = False,
        frame: str = "world",
        point: ArrayLike = (0.0, 0.0, 0.0),
    ) -> None:
        """lo <= a <= hi per axis for a point's classical acceleration or a link's angular acceleration (Drake's
        AddFrameAccelerationLimit); see FrameLimits. Per axis only (a norm bound is not a half-plane).

        Parameters
        ----------
        robot : RobotModel
        link : str
        lo, hi : array_like (3,)
            m/s² (rad/s² if angular), lo <= hi; ±inf: no limit.
        angular : bool
        frame : str
            "world" or "local".
        point : array_like (3,)
            In the link frame, m.
        """
    def add_torque_limits(
        self,
        robot: RobotModel | None = None,
        tau_min: ArrayLike | None = None,
        tau_max: ArrayLike | None = None,
        scale: float = 1.0,
        margin: float = 0.0,
        *,
        inverse_dynamics: Callable[..., Any] | None = None,
        vectorized: bool = True,
    ) -> None:
        """Torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15), from the robot's model or from your own
        inverse dynamics.

        Parameters
        ----------
        robot : RobotModel, optional
            Our RNEA on its URDF (TorqueLimits). Give robot or inverse_dynamics, not both.
        tau_min, tau_max : array_like (nq,), optional
            N·m; default ∓ the URDF effort (required with inverse_dynamics).
        scale : float
            Multiplies the limits (sec. V.D).
        margin : float
            N·m taken off each side.
        inverse_dynamics : callable, optional
            τ = f(q, qd, qdd) of your own model (MuJoCo, Drake, pinocchio, ...), vectorised: arrays (m, n) in,
            (m, n) out, one call for all 3(N+1) evaluations of eq. 12. The rows are
            SecondOrderConstraint.torque_limits' (family "torque", labels "torque <joint> upper/lower").
        vectorized : bool
            False: f takes and returns one sample (n,) (toppra's convention), called once per sample.
        """
    def add_second_order_constraint(
        self,
        inverse_dynamics: Callable[..., Any],
        F: Callable[..., Any] | ArrayLike,
        g: Callable[..., Any] | ArrayLike,
        *,
        name: str = "second-order constraint",
        labels: list[str] | None = None,
        family: str = "second order",
        vectorized: bool = True,
    ) -> None:
        """F(q) w <= g(q) with w = inverse_dynamics(q, q̇, q̈) along the path: a SecondOrderConstraint (see it for the
        arguments and what the callables receive), added as add_constraint does.

        starts from `min_intervals` uniform intervals plus the breakpoints of a piecewise-polynomial path.
        Returns the grid points s_0..s_N (the N used is len - 1). InvalidInputError past `max_intervals`.
        """
    def add_contacts(
        self,
        robot: RobotModel,
        contacts: list[Contact],
        *,
        tau_min: ArrayLike | None = None,
        tau_max: ArrayLike | None = None,
        drift_tolerance: float = 1e-6,
        drift: str = "auto",
        cone_edges: int = 8,
        friction_margin: float = 0.0,
        min_normal_force: float = 0.0,
        torque_scale: float = 1.0,
        torque_margin: float = 0.0,
        min_link_normal_force: float = 0.0,
        max_lps: int = 2000,
        cone_offset: float = 0.0,
        projection_tolerance: float = 0.0,
        project_on_demand: bool = False,
    ) -> None:
        """Torque limits with frictional contact forces (eq. 17-18), projected to (ṡ², s̈) per grid point
        (sec. IV.C; each polygon is the hull of LP optima with every edge certified by its own LP); see
        ContactConstraint. add_torque_limits on the same robot, before or after, merges into this one projection
        (both limits hold).

        Parameters
        ----------
        robot : RobotModel
        contacts : list of Contact
            Points in their link's frame, normals in the world frame (other_link's for a robot-robot contact).
        cone_edges : int
            Edges of the inscribed friction pyramid.
        friction_margin : float
            μ is used as μ (1 - friction_margin): every force keeps this fraction of its friction in reserve
            (sec. V.D).
        min_normal_force : float
            N per contact point (n·f >= min_normal_force). With an even cone_edges a flat sole still reduces
            exactly: its hull corners' cones plus cone_edges/2 bounded weights per point (each point's minimal
            force on its cone's cross-section; docs/method.md). With an odd cone_edges every point enters the LPs
            with its own row.
        cone_offset : float
            N per contact point: the shifted cone (sec. V.D's offset of each friction cone along its normal;
            Klampt's forceRobustness): f - cone_offset·n lies in the friction cone, so each point pushes at
            least cone_offset and keeps its friction reserve on top. A flat sole still reduces exactly to its
            hull corners (docs/method.md), so it is cheaper than min_normal_force.
        torque_scale, torque_margin : float
            The torque limits are multiplied by torque_scale and shrunk by torque_margin (N·m per side).
        drift_tolerance : float
            m: how far a contact point may move along the path (it should not: eq. 17-18 hold it in place).
        drift : {'auto', 'warn', 'error'}
            A contact that moves by more than drift_tolerance: 'warn' times it anyway with a UserWarning, and
            the result says so (``Result.contact_drift`` and ``message``); 'error' raises InvalidInputError naming
            the contact, s and the drift; 'auto' (default) warns up to 10 x drift_tolerance and raises beyond.
        tau_min, tau_max : array, optional
            Torque limits (default -/+ URDF effort; 0 on a floating base).
        min_link_normal_force : float
            N per link: the sum of the normal forces of the link's points (e.g. a whole sole).
        max_lps : int
            LPs per grid point before the polygon is reported inexact (FeasibleSet.exact,
            stats['inexact_points']).
        projection_tolerance : float
            Relative ε in [0, 1) of a certified approximation of each grid point's polygon (0: exact). The
            polygon is an inner set whose support function is within ε times its size (its larger extent in
            sdot^2 or sddot) of the exact one in every direction: the timing stays executable, only slower
            (T can only grow). The edges at sdot^2 = 0 are always exact, so the rest state's sddot range, where
            the path can start or stop, is the exact one. Edges kept by ε are labelled "contact forces" in
            Result.binding.
        project_on_demand : bool
            Project each grid point's polygon only where the timing needs it (default False: every polygon in
            full). add_contacts then spends three LPs per point on an outer polygon, and solve() refines it
            round by round: where the timing's (sdot^2, sddot), with both adjacent sddot, lies beyond a polygon
            edge not yet certified, the expansion goes on towards that point only, until it lies inside the
            certified inner polygon or beyond a certified edge. The timing is then that of the full projection
            (the same T, to the projection's 1e-9 of each polygon's size) from the few edges it touches:
            stats['projection_rounds'] counts the solves. feasible_set(k) projects point k in full when asked.
        """
    def add_contact_phases(
        self,
        robot: RobotModel,
        phases: list[tuple[float, float, list[Contact]] | tuple[float, float, list[Contact], dict[str, float]]],
        *,
        tau_min: ArrayLike | None = None,
        tau_max: ArrayLike | None = None,
        drift_tolerance: float = 1e-6,
        drift: str = "auto",
        impact_tolerance: float = 1e-6,
        cone_edges: int = 8,
        friction_margin: float = 0.0,
        min_normal_force: float = 0.0,
        torque_scale: float = 1.0,
        torque_margin: float = 0.0,
        min_link_normal_force: float = 0.0,
        max_lps: int = 2000,
        cone_offset: float = 0.0,
        projection_tolerance: float = 0.0,
        project_on_demand: bool = False,
    ) -> None:
        """Contacts that change along the path: one contact set per phase.

        Phase i holds its contacts (a ContactConstraint with torque limits, eq. 17-18) on the grid points of
        [s_begin, s_end], both ends included: at a switch both adjacent stances hold. Phases must be contiguous,
        cover the path and have s_begin < s_end (errors name the phase). A switch that is not a grid point is
        inserted into the grid (one more interval; constraints already added are re-evaluated; a switch within
        1e-9 of the path's length of a grid point snaps to it); with an ``add_linear_constraint`` (rows per grid
        point) a switch off the grid is an InvalidInputError naming the nearest grid point. TorqueLimits of the
        robot are merged into every phase. Row labels and ``Result.binding`` name the phase ("phases[1]: ...").

        No impact: a contact that phase i has and phase i-1 has not is made at the switch; if its point arrives
        moving along its normal (|n·c'| > impact_tolerance × the point's largest |c'| on the grid, c' = J p' just
        before the switch), ṡ = 0 there (row "phases[i]: no impact: ..."). Breaking contact needs nothing.

        Parameters
        ----------
        robot : RobotModel
        phases : list of (s_begin, s_end, contacts) or (s_begin, s_end, contacts, options)
            options: a dict of this phase's own friction_margin, min_normal_force, min_link_normal_force,
            cone_offset, cone_edges (the others are the call's).
        cone_edges, friction_margin, min_normal_force, torque_scale, torque_margin, tau_min, tau_max,
        min_link_normal_force, max_lps, cone_offset, projection_tolerance, project_on_demand :
            As in ``add_contacts``, for every phase.
        drift_tolerance, drift :
            As in ``add_contacts``, for each phase's contacts on that phase's stretch.
        impact_tolerance : float
            Relative tolerance of the no-impact rule (default 1e-6).
        """
    def add_constraint(self, constraint: Constraint) -> None:
        """Adds any Constraint; its rows are evaluated now, so errors surface here."""
    def set_boundary_speeds(self, sdot_begin: float = 0.0, sdot_end: float = 0.0) -> None:
        """ṡ at s_begin and s_end.

        Parameters
        ----------
        sdot_begin, sdot_end : float
            1/s, >= 0 and finite (default 0: rest to rest). For joint velocities use
            ``set_boundary_velocities``.
        """
    def set_joint_names(self, names: list[str]) -> None:
        """Names of the path's coordinates for the labels and messages of velocity and acceleration limits.

        Names the limits added before as well as after. Set automatically from the robot of the first
        add_torque_limits / add_contacts whose robot has one joint per coordinate.
        """
    def set_zero_boundary_accelerations(self, at_begin: bool = True, at_end: bool = True) -> None:
        """sddot = 0 at s_begin and/or s_end (q̈ = p'' ṡ² there: no jump of q̈ from or to a cruise).

        With sddot constant per interval (eq. 24) it holds on the whole first/last interval, so the boundary
        speed there must be > 0 (set_boundary_speeds); solve() raises InvalidInputError otherwise.
        """
    @property
    def joint_names(self) -> list[str]:
        """list of str: See ``set_joint_names``."""
    def set_boundary_velocities(self, qd_begin: ArrayLike, qd_end: ArrayLike, tolerance: float = 1e-6) -> None:
        """Boundary conditions as joint velocities q̇ (rad/s or m/s) at s_begin and s_end.

        q̇ = p'(s) ṡ (eq. 10): each must be a non-negative multiple of the path tangent p'; the speeds
        ṡ = p'·q̇ / |p'|² are then set as by ``set_boundary_speeds``.

        Parameters
        ----------
        qd_begin, qd_end : array_like (n,)
            Joint velocities at the ends.
        tolerance : float
            Allowed |q̇ - p' ṡ|∞ relative to |q̇|.

        Raises
        ------
        InvalidInputError
            Naming the joint index where q̇ is not along p'.
        """
    @property
    def sdot_begin(self) -> float:
        """float: ṡ at s_begin in 1/s (set_boundary_speeds)."""
    @property
    def sdot_end(self) -> float:
        """float: ṡ at s_end in 1/s (set_boundary_speeds)."""
    @property
    def grid(self) -> Array:
        """ndarray (N+1,)"""
    @property
    def intervals(self) -> int:
        """int"""
    @property
    def path(self) -> Path:
        """Path"""
    @property
    def constraints(self) -> list[Constraint]:
        """list of Constraint"""
    def feasible_set(self, k: int) -> FeasibleSet:
        """The pruned feasible polygon at grid index k (0 <= k <= N): a FeasibleSet."""
    def relaxation(self, max_scale: float = 1e3, tolerance: float = 1e-3, guarantee: str = "grid") -> dict[str, float]:
        """Smallest uniform relaxation of each constraint family that makes the problem feasible.

        Returns a dict (C++: std::map) family -> scale >= 1 ('velocity', 'acceleration', 'torque', and 'all' = every family
        together when there are several): the family's limit intervals widened by that factor about zero, the
        others unchanged, give a feasible problem; within `tolerance` (relative) of the smallest such factor;
        inf if `max_scale` is not enough (e.g. velocity limits cannot fix what acceleration limits forbid).
        1.0 for every family of a feasible problem.

        Each family is Constraint.family(); the scale is found by bisection on a geometric scale (the returned
        scale is feasible, scale / (1 + tolerance) is not), feasibility decided by the reachability analysis
        (O(N) per trial, no SLP). With guarantee = 'continuous', feasibility counts the rows that hold velocity
        and acceleration limits between grid points (not the audit's cuts, which depend on the solution: a
        lower bound then).
        """
    def restarted(self, s0: float, sdot0: float) -> TimeScalingProblem:
        """The problem that continues a running trajectory from path parameter s0 at speed sdot0 (>= 0).

        The path's tail [s0, s_end] on the grid points beyond s0, the same constraints and every setting
        pickling keeps (end speed, sddot = 0 at the end, joint names; sddot = 0 at the start only when
        s0 = s_begin: inside the path the restart continues a running trajectory, whose sddot there is free),
        with boundary speeds (sdot0, sdot_end). s0 itself becomes the first grid point; a grid point closer to
        s0 than 1e-9 of the interval is dropped. A LinearConstraint keeps its rows at the kept grid points (s0
        must then be a grid point: InvalidInputError naming s0 and the nearest grid point otherwise). Its result
        starts at q = p(s0), qd = p'(s0)*sdot0 (no jump in position or velocity); its times count from the
        restart (t = 0 at s0).
        """
    def compute_trajectory(self, sd_start: float = 0.0, sd_end: float = 0.0) -> Trajectory | None:
        """toppra's ``compute_trajectory(sd_start, sd_end)``: the time-optimal Trajectory, or None if the solve fails.

        As toppra: None (not an exception) when there is no timing, with a warning on the "pathpace" logger
        naming the status and why; ``solve()`` returns the Result with the reason (infeasible_s,
        binding_constraints). The path speeds at the ends are set on the problem (set_boundary_speeds) when they
        differ from its own, so they stay for later solves.

        Parameters
        ----------
        sd_start, sd_end : float
            ṡ at s_begin and s_end (1/s), as toppra's.

        Returns
        -------
        Trajectory or None
        """
    def solve(
        self,
        method: str = "auto",
        max_iterations: int = 200,
        tolerance: float = 1e-7,
        initial_trust_region: float = 0.5,
        lp_feasibility_tolerance: float = 1e-9,
        explain: bool = True,
        guarantee: str = "grid",
        audit_points: int = 4,
        audit_tolerance: float = 1e-10,
        max_audit_rounds: int = 30,
        time_limit: float = 60.0,
    ) -> Result:
        """Solves the problem.

        Parameters
        ----------
        method : {'auto', 'slp'}
            'auto': reachability analysis, exact when the feasible set has a greatest element, SLP otherwise;
            'slp': always run sequential linear programming. With jerk limits, 'auto' tries the primal-dual
            interior-point method before the barrier path, 'slp' runs the barrier path alone.
        max_iterations : int
            SLP iterations.
        tolerance : float
            Relative optimality: OPTIMAL when (T - T*) / T* is certified below it.
        initial_trust_region : float
            SLP trust-region half-width relative to the largest ṡ² of the start.
        lp_feasibility_tolerance : float
            GLPK's primal feasibility tolerance.
        explain : bool
            On an infeasible result, also find the smallest relaxation of each constraint family
            (``Result.relaxation``).
        guarantee : {'grid', 'continuous'}
            'grid': limits hold at the grid points (eq. 26); 'continuous': at every instant (velocity and
            acceleration by Bernstein bounds of a piecewise-polynomial path, torque and contact by an audit at
            audit_points interior points per interval with exact cuts until it passes; stats['audit_worst'] is
            the largest relative violation left, negative = the margin reached; above audit_tolerance only where
            no further cut changed the timing, e.g. cuts met to the LP solver's own tolerance: the message then
            says so).
        audit_points, audit_tolerance, max_audit_rounds :
            Of the continuous audit: points per interval, relative violation accepted, solve-audit rounds.
        time_limit : float
            Seconds (inf for none) for the whole solve: TIME_LIMIT with the best feasible timing found and its
            certified gap.

        ``max_iterations`` bounds the SLP iterations per window, ``time_limit`` the whole solve: either ends
        with the best feasible timing found (ITERATION_LIMIT / TIME_LIMIT, stats["gap"] is its certified bound).
        UNBOUNDED means that nothing bounds the speed at a grid point where the path moves (the ends, whose
        speeds are given, never count). A stationary piece of path (p'(s) = 0 on a stretch of the grid) that no
        constraint bounds raises InvalidInputError naming its s-range: it would be crossed in zero time; remove
        it from the path.

        The GIL is released meanwhile.

        Returns
        -------
        Result
            Never raises for an infeasible problem: see ``status`` and ``message``.
        """

def auto_grid(path: Path, tolerance: float = 1e-3, min_intervals: int = 16, max_intervals: int = 1000000) -> Array:
    """A grid of s fitted to the path's shape (what grid='auto' uses).

    Every interval is halved until p, p' and p'' deviate from their chords at its midpoint by at most
    `tolerance` times their scale over the path (largest coordinate range, largest |p'_j|, largest |p''_j|);
    starts from `min_intervals` uniform intervals plus the breakpoints of a piecewise-polynomial path (so
    no interval straddles a kink of p''). Returns the grid points s_0..s_N (the N used is len - 1).
    InvalidInputError past `max_intervals`, or for a bad argument.

    The constraints of eq. (26) hold at the grid points; between them q̇ = p'(s)ṡ and q̈ = p''(s)ṡ² + p'(s)s̈
    follow p, p', p'' (eq. 10-11). Deviation from the chord (the linear interpolation between an interval's
    ends) is what the grid cannot see, so the limits' excursions between grid points and the discretisation
    error of T shrink with it (both O(Δs²) for smooth pieces). The excursions also depend on the speed
    profile, so the tolerance bounds the geometry, not the limits' excursions (bench/README.md has them
    measured). For limits that hold between grid points by construction, see solve's guarantee option.
    """

def contact_phase_of_s(phases: list[ContactConstraint], s: float | ArrayLike) -> NDArray[np.int32] | int:
    """The index of the phase that holds at each s.

    The last phase whose [active_begin, active_end], widened by 1e-12 max(1, |s|) as its rows are, holds
    s: at a switch both adjacent phases hold, and the later one has the contacts that hold after it. An s
    that no phase holds (a rounding beyond the path's ends, or a gap between phases) gets the phase
    nearest to it, the later one on a tie. This is Trajectory.contact_phase's rule, and what
    ``pathpace.sim`` uses to tell which of a plan's contacts hold at a time.

    Parameters
    ----------
    phases : list of ContactConstraint
        In order of s (active_begin non-decreasing), at least one: Trajectory.contact_phases, or
        ContactConstraint(..., active_begin=, active_end=) per phase.
    s : float or array_like (m,)
        Path parameters, finite.

    Returns
    -------
    int or ndarray of int (m,)
        Indices into phases.
    """
