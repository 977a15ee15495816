"""Independent reference computations for the tests: plain numpy, cvxpy, scipy and pinocchio, no pathpace numerics."""

import warnings

import numpy as np


def kinematic_rows(dq, ddq, vmin, vmax, amin, amax):
    """Rows a·x + b·u <= c at each grid point from velocity (eq. 16) and acceleration (eq. 14) limits.

    Returns A, B, C of shape (N+1, r) (velocity rows have b = 0) -- written from the paper, not from
    pathpace's code.
    """
    m, n = dq.shape
    A, B, C = [], [], []
    with np.errstate(divide="ignore"):
        lim = np.where(dq > 0, vmax / dq, np.where(dq < 0, vmin / dq, np.inf))
    A.append(np.ones((m, n)))
    B.append(np.zeros((m, n)))
    C.append(np.where(np.isfinite(lim), lim**2, np.inf))
    A += [ddq, -ddq]
    B += [dq, -dq]
    C += [np.broadcast_to(amax, (m, n)), np.broadcast_to(-np.asarray(amin), (m, n))]
    return np.hstack(A), np.hstack(B), np.hstack(C).astype(float)


def max_violation(s, sdot, A, B, C):
    """Largest relative violation of a·ṡ² + b·s̈ <= c at every grid point, with s̈ of the interval on
    each side of the point (eq. 26), relative to max(1, |c|)."""
    theta = sdot**2
    ds = np.diff(s)
    u = (theta[1:] - theta[:-1]) / (2 * ds)
    worst = 0.0
    for side, ks, us in (("fwd", np.arange(len(ds)), u), ("bwd", np.arange(1, len(s)), u)):
        a, b, c = A[ks], B[ks], C[ks]
        lhs = a * theta[ks, None] + b * us[:, None]
        finite = np.isfinite(c)
        scale = np.maximum(1.0, np.abs(np.where(finite, c, 0.0)))
        viol = np.where(finite, (lhs - np.where(finite, c, 0.0)) / scale, -np.inf)
        worst = max(worst, float(np.max(viol)))
    return worst


def shrink_to_feasible(s, theta, A, B, C):
    """θ / f with the smallest f >= 1 that meets every row a·θ + b·u <= c (all c > 0) at every grid point,
    with u of the interval on each side (eq. 26): the rows are homogeneous in (θ, u), so dividing θ by f
    divides each left side by f. Turns a solver's θ that breaks the rows slightly into a feasible timing
    (its T grows by √f)."""
    ds = np.diff(s)
    u = (theta[1:] - theta[:-1]) / (2 * ds)
    f = 1.0
    for ks in (np.arange(len(ds)), np.arange(1, len(s))):
        lhs = A[ks] * theta[ks, None] + B[ks] * u[:, None]
        finite = np.isfinite(C[ks])
        c = np.where(finite, C[ks], 1.0)
        assert np.all(c > 0)
        f = max(f, float(np.max(np.where(finite, lhs / c, 0.0))))
    shrunk = theta / f
    # Its own promise, checked (a comparison with an infeasible θ would test nothing).
    assert max_violation(s, np.sqrt(np.maximum(shrunk, 0.0)), A, B, C) <= 1e-9
    return shrunk


def cvxpy_optimum(s, A, B, C, theta_begin=0.0, theta_end=0.0):
    """The optimum of eq. (26)-(27) by cvxpy + Clarabel, each term written as 2Δs·inv_pos(w_k + w_{k+1})
    with w_k <= sqrt(θ_k)."""
    import cvxpy as cp

    N = len(s) - 1
    ds = np.diff(s)
    theta = cp.Variable(N + 1)
    w = cp.Variable(N + 1)
    finite = np.isfinite(C)
    Cf = np.where(finite, C, 0.0)
    Af = np.where(finite, A, 0.0)
    Bf = np.where(finite, B, 0.0)
    cons = [theta >= 0, w >= 0, w <= cp.sqrt(theta), theta[0] == theta_begin, theta[N] == theta_end]
    # Velocity rows (b = 0) as bounds; the rest as rows on both sides of each grid point.
    u = cp.multiply(theta[1:] - theta[:-1], 1.0 / (2 * ds))
    for j in range(A.shape[1]):
        fk = finite[:-1, j]
        bk = finite[1:, j]
        if fk.any():
            expr = cp.multiply(Af[:-1, j], theta[:-1]) + cp.multiply(Bf[:-1, j], u)
            cons.append(expr[np.flatnonzero(fk)] <= Cf[:-1, j][fk])
        if bk.any():
            expr = cp.multiply(Af[1:, j], theta[1:]) + cp.multiply(Bf[1:, j], u)
            cons.append(expr[np.flatnonzero(bk)] <= Cf[1:, j][bk])
    obj = cp.Minimize(cp.sum(cp.multiply(2 * ds, cp.inv_pos(w[:-1] + w[1:]))))
    prob = cp.Problem(obj, cons)
    # √θ at θ = 0 (rest at the ends) makes the cone program badly conditioned; Clarabel sometimes stops
    # at "optimal_inaccurate" with its defaults. Settings are tried in turn until one reports OPTIMAL.
    for settings in ({}, {"max_iter": 1000}, {"equilibrate_enable": False}, {"tol_gap_abs": 1e-7, "tol_gap_rel": 1e-7}):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", UserWarning)  # "may be inaccurate": the status says it
            prob.solve(solver=cp.CLARABEL, **settings)
        if prob.status == cp.OPTIMAL:
            break
    assert prob.status == cp.OPTIMAL, prob.status
    # prob.value is T at w, and w <= sqrt(θ) holds only to the solver's tolerance, which lets the value
    # undercut the true T by ~1e-6; T recomputed from the returned θ is the honest number.
    # The same holds at the ends: θ_N = 0 is met to ~1e-9 only, and √θ_N ~ 3e-5 there shortens the last
    # interval visibly. The ends are set to their exact values.
    th = np.maximum(np.asarray(theta.value), 0.0)
    th[0], th[N] = theta_begin, theta_end
    return duration(s, th), th


def duration(s, theta):
    """T of eq. (27) for squared speeds θ at the grid s."""
    w = np.sqrt(np.maximum(theta, 0.0))
    return float(np.sum(2 * np.diff(s) / (w[:-1] + w[1:])))


def frank_wolfe_gap(s, theta, A, B, C, theta_begin=0.0, theta_end=0.0):
    """An upper bound on T(θ) - T* for a feasible θ, by scipy's HiGHS: T is convex in θ (eq. 27) and the rows
    of eq. (26) are linear in θ, so T(θ) - T* <= ∇T(θ)·(θ - θ_lp) where θ_lp minimises ∇T(θ)·θ over the
    feasible set (the Frank-Wolfe gap). Independent of pathpace and of cvxpy."""
    from scipy.optimize import linprog
    from scipy.sparse import coo_matrix

    N = len(s) - 1
    ds = np.diff(s)
    w = np.sqrt(np.maximum(theta, 0.0))
    term = ds / (w[:-1] + w[1:]) ** 2
    g = np.zeros(N + 1)
    g[:-1] -= term
    g[1:] -= term
    g /= np.maximum(w, 1e-300)
    g[0] = g[N] = 0.0  # fixed ends
    rows, cols, vals, rhs = [], [], [], []
    r = 0
    h = 1.0 / (2 * ds)
    for side in (0, 1):  # 0: the row of grid point k with interval k; 1: of grid point k+1 with interval k
        a, b, c = A[side:N + side], B[side:N + side], C[side:N + side]
        for j in range(A.shape[1]):
            fin = np.isfinite(c[:, j])
            k = np.flatnonzero(fin)
            ck = a[k, j] * (1 - side) - b[k, j] * h[k]      # coefficient of θ_k
            ck1 = a[k, j] * side + b[k, j] * h[k]           # coefficient of θ_{k+1}
            idx = r + np.arange(len(k))
            rows += [idx, idx]
            cols += [k, k + 1]
            vals += [ck, ck1]
            rhs.append(c[k, j])
            r += len(k)
    M = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(r, N + 1)).tocsr()
    bounds = [(0, None)] * (N + 1)
    bounds[0] = (theta_begin, theta_begin)
    bounds[N] = (theta_end, theta_end)
    lp = linprog(g, A_ub=M, b_ub=np.concatenate(rhs), bounds=bounds, method="highs")
    assert lp.status == 0, lp.message
    return float(g @ (theta - lp.x))


def pinocchio_model(urdf, locked=()):
    """pinocchio's model of the URDF with the joints named in `locked` fixed at their neutral position."""
    import pinocchio as pin

    full = pin.buildModelFromUrdf(str(urdf))
    if not locked:
        return full
    return pin.buildReducedModel(full, [full.getJointId(n) for n in locked], pin.neutral(full))


def arm_rows(path, grid, vmin, vmax, amin, amax, model=None, scale=None):
    """kinematic_rows of `path` on `grid` and, with a pinocchio `model`, its torque_rows at `scale` x effort
    beside them: the rows of an arm problem, as A, B, C of shape (N+1, r)."""
    A, B, C = kinematic_rows(path.dq(grid), path.ddq(grid), vmin, vmax, amin, amax)
    if model is None:
        return A, B, C
    At, Bt, Ct = torque_rows(model, path, grid, scale)
    return np.hstack([A, At]), np.hstack([B, Bt]), np.hstack([C, Ct])


def torque_rows(model, path, grid, scale):
    """τ = a x + b u + c along the path (eq. 12) from pinocchio's RNEA on `model`, as rows a x + b u <= τ_max - c
    and -a x - b u <= τ_max + c, with τ_max = scale x the model's effort limits."""
    import pinocchio as pin

    data = model.createData()
    q, dq, ddq = path.q(grid), path.dq(grid), path.ddq(grid)
    zero = np.zeros(model.nv)
    c = np.array([pin.computeGeneralizedGravity(model, data, qk) for qk in q])
    a = np.array([pin.rnea(model, data, q[k], dq[k], ddq[k]) for k in range(len(grid))]) - c
    b = np.array([pin.rnea(model, data, q[k], zero, dq[k]) for k in range(len(grid))]) - c
    tau_max = scale * model.effortLimit
    return np.hstack([a, -a]), np.hstack([b, -b]), np.hstack([tau_max - c, c + tau_max])


def generators(normal, mu, k):
    """The k edges of the friction pyramid inscribed in the cone of friction mu about `normal`, as columns: the
    normal plus mu times unit tangents at multiples of 2π/k (the first tangent normal x e_x, or x e_y when the
    normal is near x)."""
    nrm = np.asarray(normal, float) / np.linalg.norm(normal)
    e = np.array([0.0, 1.0, 0.0]) if abs(nrm[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
    t1 = np.cross(nrm, e)
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(nrm, t1)
    phis = 2 * np.pi * np.arange(k) / k
    return nrm[:, None] + mu * (np.cos(phis) * t1[:, None] + np.sin(phis) * t2[:, None])


def composite_floating_joint():
    """pinocchio's counterpart of our floating base: x, y, z, then rotations about z, y, x."""
    import pinocchio as pin

    jc = pin.JointModelComposite()
    for j in (pin.JointModelPX(), pin.JointModelPY(), pin.JointModelPZ(), pin.JointModelRZ(), pin.JointModelRY(),
              pin.JointModelRX()):
        jc.addJoint(j)
    return jc
