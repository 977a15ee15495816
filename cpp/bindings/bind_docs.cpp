// numpy-style docstrings (with units) of the public classes, methods and properties, kept apart from
// the binding code so that the bindings stay short: add_docstrings() runs last and attaches them.
// Methods keep pybind11's signature line; the text below replaces the short inline description.
#include <pybind11/pybind11.h>

#include <cstring>
#include <string>

namespace py = pybind11;

namespace pathpace::python {

namespace {

struct Doc {
  const char* cls;
  const char* member;  // nullptr: the class itself
  const char* text;
};

// Angles in rad and lengths in m (revolute / prismatic joints); time in s; s is the dimensionless path
// parameter, so ṡ is in 1/s and s̈ in 1/s²; torques in N·m (forces in N for prismatic joints).
const Doc kDocs[] = {
    // ------------------------------------------------------------------------------------------ paths
    {"Path", nullptr, R"(A geometric path q = p(s) for s in [s_begin, s_end] (abstract).

Joint coordinates q are in rad (revolute) or m (prismatic); s is dimensionless, so p' = dq/ds and
p'' = d²q/ds² are in rad (or m) per unit s.

Attributes
----------
dof : int
    Number of coordinates n.
s_begin, s_end : float
    The parameter's range.)"},
    {"Path", "q", R"(p(s).

Parameters
----------
s : float or array_like (m,)
    Path parameter, clamped to [s_begin, s_end].

Returns
-------
ndarray
    (n,) for a scalar s, (m, n) for an array; rad or m.)"},
    {"Path", "dq", R"(p'(s) = dq/ds: (n,) for a scalar s, (m, n) for an array.)"},
    {"Path", "ddq", R"(p''(s) = d²q/ds²: (n,) for a scalar s, (m, n) for an array.)"},
    {"Path", "evaluate", R"((p(s), p'(s), p''(s)) at once; shapes as in ``q``.)"},
    {"PiecewisePolynomialPath", nullptr, R"(Polynomial pieces between breakpoints.

On [b_i, b_{i+1}], p(s) = Σ_j coefficients[i, j, :] (s - b_i)**j (lowest degree first).

Parameters
----------
breakpoints : array_like (M+1,)
    Strictly increasing.
coefficients : array_like (M, degree + 1, n)

Attributes
----------
breakpoints : ndarray (M+1,))"},
    {"CubicSplinePath", nullptr, R"(A C² cubic spline through waypoints, as scipy.interpolate.CubicSpline.

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
start_derivative, end_derivative : ndarray (n,) or None)"},
    {"SampledPath", nullptr, R"(A path known at samples: q, q', q'' given at each s (e.g. from another planner).

Between samples, the quintic Hermite interpolant: C², and exact at every sample.

Parameters
----------
s : array_like (m,)
    Strictly increasing, m >= 2.
q, dq, ddq : array_like (m, n)
    p, p', p'' at the samples.

Attributes
----------
samples : ndarray (m,))"},
    // ------------------------------------------------------------------------------------ constraints
    {"Constraint", nullptr, R"(Base of all constraints: half-planes a·x + b·u <= c per grid point, x = ṡ², u = s̈ (eq. 9).

Attributes
----------
name : str
    Used in infeasibility reports.)"},
    {"VelocityLimits", nullptr, R"(Joint velocity limits vmin <= p'(s) ṡ <= vmax (eq. 13, as the bound on ṡ² of eq. 16).

Parameters
----------
vmin, vmax : array_like (n,)
    rad/s (or m/s); vmin <= 0 <= vmax, ±inf for none.
joint_names : list of str, optional
    Name the joints in row labels and messages ("velocity panda_joint2"; default "velocity joint 1").)"},
    {"AccelerationLimits", nullptr, R"(Joint acceleration limits amin <= p''ṡ² + p's̈ <= amax (eq. 14).

Parameters
----------
amin, amax : array_like (n,)
    rad/s² (or m/s²); amin <= amax, ±inf for none.
joint_names : list of str, optional
    Name the joints in row labels and messages ("acceleration panda_joint2 upper").)"},
    {"LinearConstraint", nullptr, R"(lo <= A·x + B·u + C <= hi at every grid point (x = ṡ², u = s̈).

Parameters
----------
A, B, C, lo, hi : array_like (N+1, r) (or (N+1,) for one row)
    Row k holds the coefficients at grid point s_k; lo may be -inf and hi +inf.
label : str
    Names the rows in infeasibility reports.)"},
    {"TorqueLimits", nullptr, R"(Joint torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15), by our RNEA.

Parameters
----------
robot : RobotModel
tau_min, tau_max : array_like (nq,), optional
    N·m (N for prismatic joints); default ∓ the URDF effort.
scale : float
    Multiplies the limits (sec. V.D's safety margin).
margin : float
    N·m subtracted from each side after scaling.

Attributes
----------
tau_min, tau_max : ndarray (nq,)
    After scale and margin.)"},
    {"Contact", nullptr, R"(A point contact with Coulomb friction.

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
    The other body of a robot–robot (or robot–object) contact; None: the world.)"},
    {"ContactForces", nullptr, R"(Force-distribution LP results at samples.

Attributes
----------
feasible : ndarray of bool (samples,) or bool
    False where no forces of any sign meet the torque limits.
margin : ndarray (samples,) or float
    N: the smallest cone weight or normal force beyond the minimum; < 0 needs forces that do not exist.
forces : ndarray (samples, contacts, 3)
    World-frame force on each contact's link, N.
torques : ndarray (samples, nq)
    Joint torques with these forces, N·m.)"},
    {"ContactWrenches", nullptr, R"(Per-link totals of a contact-force distribution (``Trajectory.contact_wrenches``).

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
    Sum of the normal forces into each link, N.)"},
    {"ContactConstraint", nullptr, R"(Torque limits with frictional contact forces (eq. 17-18), projected onto (ṡ², s̈).

Includes the torque limits: do not add TorqueLimits to the same problem.

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
    As TorqueLimits' scale and margin (N·m).)"},
    {"ContactConstraint", "force_distribution", R"(The most robust contact forces at each configuration.

Parameters
----------
q, qd, qdd : array_like (samples, nq) or (nq,)
    Positions (rad, m), velocities (per s), accelerations (per s²).

Returns
-------
ContactForces)"},
    {"ContactConstraint", "max_drift", R"(How far contact points move along a path (they should not).

Returns
-------
(float, int)
    Largest distance in m, and the index of that contact.)"},
    // ------------------------------------------------------------------------------------ robot model
    {"RobotModel", nullptr, R"(A rigid-body tree from a URDF (immutable, shareable across threads).

Joint coordinates are in rad (revolute) or m (prismatic); fixed joints are merged into their parent.

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
    kg, of the moving bodies.
mimic_joints : list of (str, str, float, float)
    URDF mimic joints (name, joint, multiplier, offset): q_name = multiplier · q_joint + offset, as in
    pinocchio. They have no coordinate in q; their torque acts on their joint, times the multiplier.)"},
    {"RobotModel", "from_urdf", R"(Loads a URDF file.

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
    Unreadable file, invalid URDF, unknown locked joint.)"},
    {"RobotModel", "from_urdf_string", R"(As ``from_urdf``, from the URDF's XML text.)"},
    {"RobotModel", "from_urdf_file", R"(The same as ``from_urdf`` (the C++ name, RobotModel::from_urdf_file).)"},
    {"RobotModel", "gravity_torques", R"(The same as ``gravity(q)`` (the C++ name, RobotModel::gravity_torques): (nq,) in N·m.)"},
    {"RobotModel", "inverse_dynamics", R"(τ = M(q) q̈ + C(q, q̇) q̇ + g(q) by RNEA.

Parameters
----------
q, qd, qdd : array_like (nq,)
    rad, rad/s, rad/s² (m, m/s, m/s² for prismatic joints).

Returns
-------
ndarray (nq,)
    N·m (N).)"},
    {"RobotModel", "mass_matrix", R"(M(q), (nq, nq), in kg·m² (kg for prismatic coordinates).)"},
    {"RobotModel", "gravity", R"(g(q): the joint torques that hold the robot still at q, (nq,) in N·m.)"},
    {"RobotModel", "frame_placement", R"(World placement of a link's frame at q: a 4x4 homogeneous matrix (translation in m).)"},
    {"RobotModel", "point_jacobian", R"(World-frame linear Jacobian (3, nq) of a point fixed in a link.

Parameters
----------
q : array_like (nq,)
link : str
point : array_like (3,)
    In the link frame, m.)"},
    {"RobotModel", "path_torque_coefficients", R"(Eq. (12): τ = a ṡ² + b s̈ + c along a path, at each row.

Parameters
----------
q, dq, ddq : array_like (m, nq)
    p, p', p'' at m samples.

Returns
-------
(a, b, c) : ndarrays (m, nq)
    a = M p'' + C(q, p') p', b = M p', c = g(q), in N·m per the units of ṡ², s̈ and 1.)"},
    // --------------------------------------------------------------------------- problem and results
    {"FeasibleSet", nullptr, R"(The pruned feasible polygon of (x, u) = (ṡ², s̈) at one grid point.

Attributes
----------
index : int
s : float
halfplanes : ndarray (r, 3)
    Rows [a, b, c] of a·x + b·u <= c.
labels : list of str
    The constraint row behind each half-plane.
x_min, x_max : float
    Range of ṡ² (1/s²); x_max_label names what sets x_max.
vertices : ndarray (v, 2)
    Counter-clockwise vertices (x, u).
empty, bounded : bool)"},
    {"FeasibleSet", "contains", R"(Whether (x, u) = (ṡ², s̈) satisfies every half-plane to within tol (absolute).)"},
    {"Trajectory", nullptr, R"(The timed path: q(t) = p(s(t)) with s(t) piecewise quadratic through the grid (eq. 24).

Parameters
----------
path : Path
s : array_like (N+1,)
    Grid.
sdot : array_like (N+1,)
    ṡ at the grid points, 1/s; >= 0 with no two consecutive zeros.

Attributes
----------
duration : float
    T in s.
times : ndarray (N+1,)
    t_k of the grid points, s.
grid, sdot_grid : ndarray (N+1,)
path : Path
robot : RobotModel or None
    The robot whose torque limits or contacts shaped it.
contacts : ContactConstraint or None

Calling ``traj(t, order)`` gives q (order 0), q̇ (1) or q̈ (2), as toppra's trajectories.)"},
    {"Trajectory", "q", R"(q(t), rad (m).

Parameters
----------
t : float or array_like (m,)
    s, clamped to [0, duration].

Returns
-------
ndarray
    (n,) for a scalar t, (m, n) for an array.)"},
    {"Trajectory", "qd", R"(q̇(t) = p'(s) ṡ (eq. 10), rad/s; shapes as ``q``.)"},
    {"Trajectory", "qdd", R"(q̈(t) = p''(s) ṡ² + p'(s) s̈ (eq. 11), rad/s²; s̈ of the interval to the right of t.)"},
    {"Trajectory", "evaluate", R"((q, q̇, q̈) at t; shapes as ``q``.)"},
    {"Trajectory", "s", R"((s, ṡ, s̈) at t: floats for a scalar t, arrays (m,) otherwise; ṡ in 1/s, s̈ in 1/s².)"},
    {"Trajectory", "sample", R"(Uniform resampling.

Parameters
----------
dt : float
    Period in s; T is appended when it is not a multiple of dt.

Returns
-------
dict
    ``t`` (m,) in s, ``q``, ``qd``, ``qdd`` (m, n).)"},
    {"Trajectory", "sample_times", R"(The times 0, dt, 2 dt, ... (and T) of ``sample``, in s.)"},
    {"Trajectory", "torques", R"(τ(t) by inverse dynamics along the timing.

Parameters
----------
t : float or array_like (m,)
    s.
robot : RobotModel, optional
    Default: the robot whose limits shaped the trajectory.

Returns
-------
ndarray
    (nq,) or (m, nq), N·m.)"},
    {"Trajectory", "contact_forces", R"(Contact forces at t from the force-distribution LP (the solver looked only at grid points).

With contact phases (``add_contact_phases``) each t uses the contacts of its phase, the later one at a
switch time; ``.phase`` gives the phase of each t and ``forces`` has as many rows as the largest phase
has contacts (NaN beyond a phase's own).

Returns
-------
ContactForces)"},
    {"Trajectory", "contact_wrenches", R"(Per-link wrenches and centres of pressure of ``contact_forces(t)``.

For every link on either side of a contact (first appearance over the contacts and phases): the total
force (world frame, N), its moment about the link's origin (world axes, N·m), the sum of the normal
forces into the link (N), and the centre of pressure Σ (n·f_i) p_i / Σ n·f_i (world frame, m; NaN
where the link does not push, or its contacts have several normals). A link its phase does not hold
has zero force there; an infeasible sample is NaN.

Returns
-------
ContactWrenches)"},
    {"Trajectory", "centers_of_pressure", R"(``contact_wrenches(t).center_of_pressure``: (samples, links, 3), m.

The links are ``contact_wrenches(t).links``; NaN where a link does not push.)"},
    {"Result", nullptr, R"(What a solve returns. ``bool(result)`` is ``result.ok``.

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
    drift_tolerance): constraint, contact, link, s, drift (m), tolerance (m), message.
tau_min, tau_max : ndarray (nq,) or None
    The torque limits the solve held (after scale and margin), None without torque limits.
duration : float
    T in s (nan without a timing).
s, sdot, times : ndarray (N+1,)
    Grid, ṡ (1/s) and t (s) at the grid points.
sddot : ndarray (N,)
    s̈ on each interval, 1/s².
infeasible_index : int
    First grid index where no timing exists (-1 if feasible).
infeasible_s : float
binding_constraints : list of str
    The constraint rows that bind there.
stats : dict
    slp_iterations, lp_solves, greatest_element (exact optimum without SLP), gap (certified bound on
    (T - T*) / T*), average_halfplanes, time_feasible_sets, time_reachability, time_slp (s).)"},
    {"Result", "trajectory", R"(The timed trajectory (Trajectory); raises pathpace.Error when there is no timing.)"},
    {"TimeScalingProblem", nullptr, R"(Time-optimal timing of a path under constraints (sec. V).

Minimises T = Σ 2Δs_k / (ṡ_k + ṡ_{k+1}) (eq. 25, 27) over the speeds at the grid points, with every
constraint enforced at every grid point with the s̈ of the interval on each side (eq. 26). Build once,
then ``solve`` (it releases the GIL; a built problem may be solved from several threads).

Parameters
----------
path : Path
grid : int or array_like (N+1,)
    N uniform intervals over the path, or a strictly increasing grid from s_begin to s_end.

Attributes
----------
grid : ndarray (N+1,)
intervals : int
path : Path
constraints : list of Constraint
sdot_begin, sdot_end : float
    Boundary speeds in 1/s.)"},
    {"TimeScalingProblem", "add_velocity_limits", R"(Joint velocity limits (eq. 13).

Parameters
----------
vmin, vmax : array_like (n,)
    rad/s (m/s); vmin <= 0 <= vmax, ±inf for none.)"},
    {"TimeScalingProblem", "add_acceleration_limits", R"(Joint acceleration limits (eq. 14).

Parameters
----------
amin, amax : array_like (n,)
    rad/s² (m/s²); amin <= amax.)"},
    {"TimeScalingProblem", "add_linear_constraint", R"(lo <= A·ṡ² + B·s̈ + C <= hi per grid point; arrays (N+1, r). See LinearConstraint.)"},
    {"TimeScalingProblem", "add_torque_limits", R"(Torque limits τ_min <= τ <= τ_max along the path (eq. 12, 15).

Parameters
----------
robot : RobotModel
tau_min, tau_max : array_like (nq,), optional
    N·m; default ∓ the URDF effort.
scale : float
    Multiplies the limits (sec. V.D).
margin : float
    N·m taken off each side.)"},
    {"TimeScalingProblem", "add_contacts", R"(Torque limits with frictional contact forces (eq. 17-18), projected to (ṡ², s̈) per grid point
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
    (T can only grow). Edges kept by ε are labelled "contact forces" in Result.binding.)"},
    {"TimeScalingProblem", "add_contact_phases", R"(Contacts that change along the path: one contact set per phase.

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
min_link_normal_force, max_lps, cone_offset, projection_tolerance :
    As in ``add_contacts``, for every phase.
drift_tolerance, drift :
    As in ``add_contacts``, for each phase's contacts on that phase's stretch.
impact_tolerance : float
    Relative tolerance of the no-impact rule (default 1e-6).)"},
    {"TimeScalingProblem", "add_constraint", R"(Adds any Constraint; its rows are evaluated now, so errors surface here.)"},
    {"TimeScalingProblem", "set_boundary_speeds", R"(ṡ at s_begin and s_end.

Parameters
----------
sdot_begin, sdot_end : float
    1/s, >= 0 (default 0: rest to rest). For joint velocities use ``set_boundary_velocities``.)"},
    {"TimeScalingProblem", "feasible_set", R"(The pruned feasible polygon at grid index k (0 <= k <= N): a FeasibleSet.)"},
    {"TimeScalingProblem", "solve", R"(Solves the problem (the GIL is released meanwhile).

Parameters
----------
method : {'auto', 'slp'}
    'auto': reachability analysis, exact when the feasible set has a greatest element, SLP otherwise;
    'slp': always run sequential linear programming.
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
    the largest relative violation left, negative = the margin reached).
audit_points, audit_tolerance, max_audit_rounds :
    Of the continuous audit: points per interval, relative violation accepted, solve-audit rounds.
time_limit : float
    Seconds (inf for none) for the whole solve: TIME_LIMIT with the best feasible timing found and its
    certified gap.

Returns
-------
Result
    Never raises for an infeasible problem: see ``status`` and ``message``.)"},
};

// pybind11 keeps a method's doc in its PyMethodDef; its first line is the signature, which we keep.
void set_function_doc(py::handle fn, const char* text) {
  py::handle f = fn;
  if (PyInstanceMethod_Check(f.ptr())) f = PyInstanceMethod_GET_FUNCTION(f.ptr());
  if (Py_TYPE(f.ptr()) == &PyStaticMethod_Type) f = py::getattr(f, "__func__");
  if (!PyCFunction_Check(f.ptr())) return;
  auto* cf = reinterpret_cast<PyCFunctionObject*>(f.ptr());
  const std::string old = cf->m_ml->ml_doc ? cf->m_ml->ml_doc : "";
  const std::string signature = old.substr(0, old.find('\n'));
  // Owned by the module for the life of the process, as pybind11's own docs are.
  cf->m_ml->ml_doc = strdup((signature + "\n\n" + text + "\n").c_str());
}

}  // namespace

void add_docstrings(py::module_& m) {
  const py::object property = py::module_::import("builtins").attr("property");
  for (const Doc& d : kDocs) {
    py::object cls = m.attr(d.cls);
    if (!d.member) {
      cls.attr("__doc__") = py::str(d.text);
      continue;
    }
    py::object entry = cls.attr("__dict__")[d.member];
    if (py::isinstance(entry, property)) {
      entry.attr("__doc__") = py::str(d.text);
    } else {
      set_function_doc(entry, d.text);
    }
  }
}

}  // namespace pathpace::python
