"""Pictures of a solved problem (matplotlib, imported only when a function here is called).

* :func:`phase_plane` — ṡ(s) with the maximum-velocity curve, the profile coloured by the binding limit;
* :func:`polygons` — the feasible (ṡ², s̈) polygons at chosen s (the paper's fig. 3) and the solution;
* :func:`torques`, :func:`velocities`, :func:`accelerations` — τ(t), q̇(t), q̈(t) against the problem's limits;
* :func:`contacts` — contact forces and their margin over t;
* :func:`summary_figure` — all of them in one figure (what ``pathpace plot`` saves).

"Against the limits" means the limits the solve held: the problem's (``Result.tau_min``/``tau_max``, the
problem's VelocityLimits and AccelerationLimits), not the URDF's unless those are what the problem used.

The ``*_data`` functions return the plotted arrays (numpy, JSON-ready with ``.tolist()``); the HTML
report (:mod:`pathpace.report`) draws the same data with plotly.
"""

from __future__ import annotations

import re
from typing import Any, Sequence

import numpy as np

from ._core import Result, TimeScalingProblem

CATEGORY_COLORS = {
    "velocity": "#1f77b4",
    "acceleration": "#ff7f0e",
    "torque": "#d62728",
    "friction": "#8c564b",
    "normal force": "#e377c2",
    "contact": "#9467bd",
    "other": "#bcbd22",
    "boundary": "#7f7f7f",
    "free": "#2ca02c",
}
#: What each category of the phase plane means, for its legend.
CATEGORY_NAMES = {
    "velocity": "velocity limit",
    "acceleration": "acceleration limit",
    "torque": "torque limit",
    "friction": "friction cone",
    "normal force": "minimum normal force",
    "contact": "contact (balance, no impact)",
    "other": "other constraint",
    "boundary": "boundary condition",
    "free": "no limit binds (switch)",
}


def _problem(obj) -> TimeScalingProblem:
    return obj.problem if hasattr(obj, "problem") else obj


def _name_joints(label: str, joint_names: Sequence[str] | None) -> str:
    """"acceleration joint 3 upper" -> "acceleration panda_joint4 upper" when names are known."""
    if not joint_names:
        return label
    return re.sub(r"joint (\d+)", lambda m: joint_names[int(m.group(1))] if int(m.group(1)) < len(joint_names)
                  else m.group(0), label)


def _category(label: str) -> str:
    """The family of a binding row's label (contact phases' "phases[i]: " prefix left out)."""
    if not label:
        return "free"
    label = re.sub(r"^phases\[\d+\]: ", "", label)
    word = label.split(" ", 1)[0].lower()
    if word in ("velocity", "acceleration", "torque", "friction", "boundary", "free"):
        return word
    if label.startswith("minimum normal force"):
        return "normal force"
    if label.startswith(("contact forces", "no impact")):
        return "contact"
    if label.startswith(("sdot^2 >= 0", "sddot = 0 at", "sdot_begin", "sdot_end")):
        return "boundary"
    return "torque" if "torque" in label else "other"


def problem_limits(problem) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The problem's joint velocity and acceleration limits, {"velocity": (lo, hi), "acceleration": (lo, hi)}
    (the tightest of several constraints of a kind; a kind the problem does not have is left out)."""
    out: dict[str, tuple[np.ndarray, np.ndarray]] = {}
    from ._core import AccelerationLimits, VelocityLimits

    for c in _problem(problem).constraints:
        for kind, cls, lo, hi in (("velocity", VelocityLimits, "vmin", "vmax"),
                                  ("acceleration", AccelerationLimits, "amin", "amax")):
            if isinstance(c, cls):
                a, b = np.asarray(getattr(c, lo)), np.asarray(getattr(c, hi))
                if kind in out:
                    a, b = np.maximum(out[kind][0], a), np.minimum(out[kind][1], b)
                out[kind] = (a, b)
    return out


def phase_plane_data(problem, result: Result, joint_names: Sequence[str] | None = None,
                     rel_tol: float = 1e-6) -> dict[str, Any]:
    """s (N+1,), ṡ (N+1,), the maximum-velocity curve ṡ_max(s) (√x_max of each grid point's polygon),
    and per grid point the binding constraint (the half-plane with the least slack at the solution,
    with the interval's s̈ on the right; "free" when none is within rel_tol of its bound) and its category."""
    prob = _problem(problem)
    s = np.asarray(prob.grid)
    N = len(s) - 1
    ok = result.ok and len(result.sdot) == N + 1
    sd = np.asarray(result.sdot) if ok else np.full(N + 1, np.nan)
    u = np.asarray(result.sddot) if ok else np.zeros(N)
    sd_max = np.empty(N + 1)
    binding, category = [], []
    for k in range(N + 1):
        fs = prob.feasible_set(k)
        sd_max[k] = np.sqrt(fs.x_max) if np.isfinite(fs.x_max) else np.inf
        if not ok:
            binding.append("")
            category.append("free")
            continue
        x = sd[k] ** 2
        label = "free"
        H = np.asarray(fs.halfplanes)
        # The speed bound x <= x_max is kept apart from the half-planes; s̈ on both sides (eq. 26).
        if np.isfinite(fs.x_max) and x >= fs.x_max - rel_tol * max(1.0, fs.x_max):
            label = _name_joints(fs.x_max_label, joint_names)
        elif H.size:
            best = np.inf
            for uk in {u[max(k - 1, 0)], u[min(k, N - 1)]}:
                slack = H[:, 2] - (H[:, 0] * x + H[:, 1] * uk)
                scale = np.maximum(1.0, np.abs(H[:, 2]))
                j = int(np.argmin(slack / scale))
                if slack[j] <= rel_tol * scale[j] and slack[j] / scale[j] < best:
                    best = slack[j] / scale[j]
                    label = _name_joints(fs.labels[j], joint_names)
        if k in (0, N) and label == "free":
            label = "boundary"
        binding.append(label)
        category.append(_category(label))
    return {"s": s, "sdot": sd, "sdot_max": sd_max, "binding": binding, "category": category}


def polygons_data(problem, result: Result, s_values: Sequence[float] | None = None, count: int = 3) -> list[dict[str, Any]]:
    """The feasible polygon in (x, u) = (ṡ², s̈) at the grid points nearest to s_values (default: `count`
    evenly spaced interior points): vertices (v, 2), and the solution's (x, u) there."""
    prob = _problem(problem)
    s = np.asarray(result.s)
    N = len(s) - 1
    if s_values is None:
        ks = np.unique(np.linspace(0, N, count + 2).round().astype(int)[1:-1])
    else:
        ks = [int(np.argmin(np.abs(s - v))) for v in s_values]
    out = []
    for k in ks:
        fs = prob.feasible_set(int(k))
        out.append({"k": int(k), "s": float(s[k]), "vertices": np.asarray(fs.vertices), "bounded": bool(fs.bounded),
                    "x": float(result.sdot[k] ** 2), "u": float(result.sddot[min(k, N - 1)])})
    return out


def torques_data(result: Result, robot=None, tau_min=None, tau_max=None, samples: int = 1000) -> dict[str, Any] | None:
    """τ(t) (m, nq) by inverse dynamics along the timing, with the limits: those given, else the ones the
    solve held (``result.tau_min``/``tau_max``), else the URDF effort (``limits`` says which)."""
    traj = result.trajectory()
    robot = robot if robot is not None else traj.robot
    if robot is None:
        return None
    t = np.linspace(0.0, traj.duration, samples)
    tau = traj.torques(t, robot)
    if tau_min is not None or tau_max is not None:
        source = "given"
    elif result.tau_max is not None and len(result.tau_max) == robot.nq:
        source, tau_min, tau_max = "problem", result.tau_min, result.tau_max
    else:
        source = "urdf"
    hi = robot.effort_limits if tau_max is None else np.asarray(tau_max)
    lo = -robot.effort_limits if tau_min is None else np.asarray(tau_min)
    return {"t": t, "tau": tau, "tau_min": lo, "tau_max": hi, "joint_names": list(robot.joint_names), "limits": source}


def _joint_series(result: Result, which: str, samples: int, joint_names: Sequence[str] | None):
    traj = result.trajectory()
    t = np.linspace(0.0, traj.duration, samples)
    values = traj.qd(t) if which == "qd" else traj.qdd(t)
    names = list(joint_names) if joint_names else [f"joint {j}" for j in range(values.shape[1])]
    return t, values, names


def velocities_data(result: Result, vmin, vmax, joint_names: Sequence[str] | None = None,
                    samples: int = 1000) -> dict[str, Any]:
    """q̇(t) (m, nq) along the timing, with the limits and the joints' names ("joint j" when not given)."""
    t, qd, names = _joint_series(result, "qd", samples, joint_names)
    return {"t": t, "qd": qd, "vmin": np.asarray(vmin), "vmax": np.asarray(vmax), "joint_names": names}


def accelerations_data(result: Result, amin, amax, joint_names: Sequence[str] | None = None,
                       samples: int = 1000) -> dict[str, Any]:
    """q̈(t) (m, nq) along the timing (eq. 11: p'' ṡ² + p' s̈; it jumps where s̈ does), with the limits."""
    t, qdd, names = _joint_series(result, "qdd", samples, joint_names)
    return {"t": t, "qdd": qdd, "amin": np.asarray(amin), "amax": np.asarray(amax), "joint_names": names}


def limit_ratios(values, lo, hi, names) -> list[tuple[str, np.ndarray]]:
    """(name, values[:, j] / max(|lo_j|, |hi_j|)) for every joint with a finite nonzero limit: ±1 are the
    limits. What both backends (matplotlib here, plotly in :mod:`pathpace.report`) draw against ±1."""
    out = []
    for j, name in enumerate(names):
        lim = max(abs(lo[j]), abs(hi[j]))
        if np.isfinite(lim) and lim > 0:
            out.append((name, values[:, j] / lim))
    return out


def contacts_data(result: Result, samples: int = 300) -> dict[str, Any] | None:
    """Contact forces (m, contacts, 3) in N and the force-distribution margin (m,) in N over t."""
    traj = result.trajectory()
    if traj.contacts is None:
        return None
    t = np.linspace(0.0, traj.duration, samples)
    cf = traj.contact_forces(t)
    if not traj.contact_phases:
        return {"t": t, "forces": np.asarray(cf.forces), "margin": np.asarray(cf.margin),
                "links": [c.link for c in traj.contacts.contacts]}
    # Contact phases: each sample's forces belong to its phase's contacts; lay them out over every contact
    # of every phase (NaN where a contact does not hold), so that a column is one contact throughout.
    keys: list[tuple] = []
    links: list[str] = []
    columns = []
    for phase in traj.contact_phases:
        cols = []
        for c in phase.contacts:
            key = (c.link, c.other_link, tuple(np.asarray(c.point, dtype=float)), tuple(np.asarray(c.normal, dtype=float)))
            if key not in keys:
                keys.append(key)
                links.append(c.link)
            cols.append(keys.index(key))
        columns.append(cols)
    forces = np.full((samples, len(keys), 3), np.nan)
    for i, p in enumerate(np.asarray(cf.phase)):
        forces[i, columns[p]] = cf.forces[i, : len(columns[p])]
    return {"t": t, "forces": forces, "margin": np.asarray(cf.margin), "links": links, "phase": np.asarray(cf.phase)}


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt

        _, ax = plt.subplots()
    return ax


#: Joints drawn in colour on a plot against the limits (the closest to their limits); the rest in grey.
HIGHLIGHT = 8


def ranked_ratios(ratios: list[tuple[str, np.ndarray]], highlight: int = HIGHLIGHT):
    """The curves of :func:`limit_ratios` ordered by their peak |value| (the joints nearest their limits
    first): (highlighted, others), at most `highlight` highlighted. Both backends draw these."""
    order = sorted(ratios, key=lambda r: -float(np.nanmax(np.abs(r[1]))) if len(r[1]) else 0.0)
    return order[:highlight], order[highlight:]


def _legend_outside(ax, **kw):
    """A legend right of the axes, so that it never hides a curve."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0, fontsize="x-small", **kw)


def _against_limits(ax, t, ratios, ylabel, title):
    """The curves of :func:`limit_ratios` over t with ±1 (the limits) marked: the joints nearest their
    limits in distinct colours, with their peak in the legend; the others thin and grey, one legend entry."""
    top, rest = ranked_ratios(ratios)
    for name, y in rest:
        ax.plot(t, y, lw=0.6, color="0.7", zorder=1)
    if rest:
        peak = max(float(np.nanmax(np.abs(y))) for _, y in rest)
        ax.plot([], [], lw=0.6, color="0.7", label=f"{len(rest)} other joints (peak {100 * peak:.0f} %)")
    for i, (name, y) in enumerate(top):
        ax.plot(t, y, lw=1.2, color=f"C{i}", label=f"{name} (peak {100 * float(np.nanmax(np.abs(y))):.0f} %)",
                zorder=2)
    ax.axhline(1.0, color="k", ls="--", lw=1)
    ax.axhline(-1.0, color="k", ls="--", lw=1)
    ax.set_ylim(-1.15, 1.15)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize="medium")
    if ratios:
        _legend_outside(ax)
    else:
        ax.text(0.5, 0.5, "no joint has a finite limit", ha="center", transform=ax.transAxes)
    return ax


def _unbounded_spans(s: np.ndarray, finite: np.ndarray) -> list[tuple[float, float]]:
    """[s_a, s_b] stretches of grid points where the maximum-velocity curve is infinite."""
    spans, k, n = [], 0, len(s)
    while k < n:
        if finite[k]:
            k += 1
            continue
        j = k
        while j + 1 < n and not finite[j + 1]:
            j += 1
        spans.append((float(s[k]), float(s[j])))
        k = j + 1
    return spans


def phase_plane_ylim(d: dict[str, Any]) -> tuple[float, tuple[float, float] | None]:
    """The ṡ axis' top for :func:`phase_plane_data`'s arrays: the maximum-velocity curve's top, unless it
    towers over the profile (a point where the path nearly stops, p' -> 0): then 3x the profile's top,
    and (peak, s) of the curve it clips."""
    finite = np.isfinite(d["sdot_max"])
    prof = float(np.nanmax(np.append(d["sdot"], 0.0)))
    top = float(np.nanmax(np.where(finite, d["sdot_max"], np.nan))) if finite.any() else prof
    if prof > 0 and top > 3.0 * prof:
        k = int(np.nanargmax(np.where(finite, d["sdot_max"], np.nan)))
        return 3.0 * prof, (top, float(d["s"][k]))
    return 1.1 * max(top, prof, 1e-9), None


def clipped_note(d: dict[str, Any], ymax: float, clipped: tuple[float, float]) -> str:
    """What the phase plane says when its ṡ range clips the maximum-velocity curve."""
    finite = d["sdot_max"][np.isfinite(d["sdot_max"])]
    if len(finite) and finite.min() > ymax:
        return f"maximum-velocity curve above this range everywhere (min {finite.min():.3g}, peak {clipped[0]:.3g})"
    return f"maximum-velocity curve clipped (peak {clipped[0]:.3g} at s = {clipped[1]:.3g})"


def polygons_view(polys: list[dict[str, Any]]) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """Axis limits that show the bounded polygons and the solution's points when some polygon is unbounded
    (drawn cut at the solver's stand-in bound, 1e14 and more, which would hide everything else); None
    when all are bounded."""
    if all(p["bounded"] for p in polys):
        return None
    pts = [np.array([[p["x"], p["u"]]]) for p in polys]
    pts += [p["vertices"] for p in polys if p["bounded"] and len(p["vertices"])]
    v = np.vstack(pts)
    lo, hi = v.min(axis=0), v.max(axis=0)
    span = np.maximum(hi - lo, 0.5 * np.maximum(np.abs(hi), 1e-3))
    return (min(0.0, lo[0] - 0.1 * span[0]), hi[0] + 0.5 * span[0]), (lo[1] - 0.5 * span[1], hi[1] + 0.5 * span[1])


def phase_plane(problem, result: Result, ax=None, joint_names=None):
    """ṡ(s) coloured by the binding limit, over the maximum-velocity curve (dashed); where that curve is
    infinite (nothing bounds ṡ alone there) the stretch is shaded and labelled."""
    d = phase_plane_data(problem, result, joint_names)
    ax = _axes(ax)
    finite = np.isfinite(d["sdot_max"])
    s, sd, cat = d["s"], d["sdot"], d["category"]
    ax.plot(np.where(finite, s, np.nan), np.where(finite, d["sdot_max"], np.nan), "k--", lw=1,
            label="maximum-velocity curve")
    spans = _unbounded_spans(s, finite)
    for i, (a, b) in enumerate(spans):
        half = 0.5 * (s[1] - s[0]) if a == b and len(s) > 1 else 0.0
        ax.axvspan(a - half, b + half, color="0.85", zorder=0,
                   label="maximum-velocity curve infinite (shaded):\nnothing bounds ṡ alone there" if i == 0 else None)
    seen = set()
    for k in range(len(s) - 1):
        c = cat[k]
        ax.plot(s[k : k + 2], sd[k : k + 2], color=CATEGORY_COLORS[c], lw=2,
                label=None if c in seen else f"bound by: {CATEGORY_NAMES[c]}")
        seen.add(c)
    ymax, clipped = phase_plane_ylim(d)
    ax.set_ylim(0, ymax)
    if clipped is not None:
        ax.text(0.99, 0.99, clipped_note(d, ymax, clipped), ha="right", va="top", transform=ax.transAxes,
                fontsize="x-small", color="0.3")
    ax.set_xlim(s[0], s[-1])
    ax.set_xlabel("s (path parameter)")
    ax.set_ylabel("ṡ (1/s)")
    ax.set_title("phase plane: ṡ(s), coloured by the limit that binds", fontsize="medium")
    _legend_outside(ax)
    return ax


def polygons(problem, result: Result, s_values=None, ax=None):
    """Feasible (ṡ², s̈) polygons at chosen s with the solution's point in each (the paper's fig. 3)."""
    ax = _axes(ax)
    polys = polygons_data(problem, result, s_values)
    for i, p in enumerate(polys):
        v = p["vertices"]
        color = f"C{i}"
        if len(v):
            closed = np.vstack([v, v[:1]])
            ax.fill(closed[:, 0], closed[:, 1], color=color, alpha=0.2)
            # An unbounded polygon is drawn cut at the solver's stand-in bound, which is no limit: dashed.
            ax.plot(closed[:, 0], closed[:, 1], color=color, ls="-" if p["bounded"] else "--",
                    label=f"s = {p['s']:.3g} (k = {p['k']})" + ("" if p["bounded"] else ", unbounded: cut off"))
        ax.plot([p["x"]], [p["u"]], "o", color=color)
    ax.set_xlabel("x = ṡ² (1/s²)")
    ax.set_ylabel("u = s̈ (1/s²)")
    view = polygons_view(polys)
    if view is not None:
        ax.set_xlim(*view[0])
        ax.set_ylim(*view[1])
        ax.text(0.99, 0.01, "unbounded polygons extend beyond the view", ha="right", va="bottom",
                transform=ax.transAxes, fontsize="x-small", color="0.3")
    ax.set_title("feasible (ṡ², s̈) polygons and the solution (dots)", fontsize="medium")
    _legend_outside(ax)
    return ax


def torques(result: Result, robot=None, ax=None, tau_min=None, tau_max=None):
    """τ_j(t) / limit for every joint (±1 = the limits the solve held: ``result.tau_min``/``tau_max``, or
    the ones given; the URDF effort only when the problem has no torque limits, and the title says so)."""
    d = torques_data(result, robot, tau_min, tau_max)
    ax = _axes(ax)
    if d is None:
        return _nothing(ax, "torques", "no robot in this problem: no torques")
    title = {"problem": "torques against the problem's limits", "given": "torques against the given limits",
             "urdf": "torques against the URDF effort (the problem has no torque limits)"}[d["limits"]]
    return _against_limits(ax, d["t"], limit_ratios(d["tau"], d["tau_min"], d["tau_max"], d["joint_names"]),
                           "τ / τ_limit", title)


def _nothing(ax, title: str, text: str):
    """An axes that says why it is empty (instead of an empty frame)."""
    ax.set_title(title, fontsize="medium")
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, wrap=True)
    ax.set_xticks([])
    ax.set_yticks([])
    return ax


def wrenches_data(result: Result, samples: int = 300) -> dict[str, Any] | None:
    """Per-link totals over t (Trajectory.contact_wrenches): links, normal force (m, links) in N, centre of
    pressure (m, links, 3) in m, and the force-distribution margin (m,) in N, feasibility and phase of the
    forces summed (one evaluation: no second solve for the margin)."""
    traj = result.trajectory()
    if traj.contacts is None:
        return None
    t = np.linspace(0.0, traj.duration, samples)
    w = traj.contact_wrenches(t)
    return {"t": t, "links": list(w.links), "normal_force": np.asarray(w.normal_force),
            "cop": np.asarray(w.center_of_pressure), "margin": np.asarray(w.margin),
            "feasible": np.asarray(w.feasible), "phase": np.asarray(w.phase)}


def contacts(result: Result, ax=None, per_point: bool = False):
    """The normal force on each contact link (N; Trajectory.contact_wrenches) and the force-distribution
    margin (N) over t. per_point=True draws |f| of every contact point instead (one line each)."""
    # One evaluation of the forces either way: the margin comes with the forces drawn.
    d = (contacts_data if per_point else wrenches_data)(result) if result.ok else None
    ax = _axes(ax)
    if d is None:
        return _nothing(ax, "contact forces", "no contacts in this problem" if result.ok else "no timing")
    if per_point:
        mags = [(i, link, np.linalg.norm(d["forces"][:, i, :], axis=1)) for i, link in enumerate(d["links"])]
        for n, (i, link, f) in enumerate(mags):
            ax.plot(d["t"], f, lw=1, color=plt_color(n, len(mags)), label=f"|f| {link} #{i}")
    else:
        mags = list(d["links"])
        for n, link in enumerate(mags):
            ax.plot(d["t"], d["normal_force"][:, n], lw=1.5, color=plt_color(n, len(mags)), label=f"normal force on {link}")
    ax.plot(d["t"], d["margin"], "k", lw=2, label="margin (weakest cone weight)")
    ax.axhline(0.0, color="r", ls="--", lw=1)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("force (N)")
    ax.set_title("contact forces and their margin", fontsize="medium")
    _legend_outside(ax, ncol=1 if len(mags) <= 12 else 2)
    return ax


def support_polygons(result: Result, links) -> dict[str, np.ndarray | None]:
    """Each link's support polygon in the world's (x, y) at t = 0: the closed hull of its contact points (over
    every phase), None for a link with fewer than three points."""
    traj = result.trajectory()
    phases = traj.contact_phases or [traj.contacts]
    robot = phases[0].robot
    q0 = traj.q(np.array([0.0]))[0]
    out = {}
    for link in links:
        pts = {tuple((robot.frame_placement(q0, c.link) @ np.append(c.point, 1.0))[:2])
               for ph in phases for c in ph.contacts if c.link == link}
        out[link] = _hull(np.array(sorted(pts))) if len(pts) >= 3 else None
    return out


def centers_of_pressure(result: Result, ax=None):
    """Each contact link's centre of pressure over the motion (x, y in the world, m) inside its support
    polygon (the hull of its contact points at t = 0): a balance check at a glance."""
    ax = _axes(ax)
    w = wrenches_data(result) if result.ok else None
    if w is None:
        return _nothing(ax, "centres of pressure", "no contacts in this problem" if result.ok else "no timing")
    hulls = support_polygons(result, w["links"])
    for n, link in enumerate(w["links"]):
        color = plt_color(n, len(w["links"]))
        if hulls[link] is not None:
            ax.fill(hulls[link][:, 0], hulls[link][:, 1], color=color, alpha=0.15, lw=1, label=f"support of {link}")
        cop = w["cop"][:, n, :2]
        ax.plot(cop[:, 0], cop[:, 1], color=color, lw=1.5, label=f"centre of pressure of {link}")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("centres of pressure in their support polygons", fontsize="medium")
    _legend_outside(ax, ncol=1)
    return ax


def _hull(xy: np.ndarray) -> np.ndarray:
    """Convex hull of 2-D points, counter-clockwise, closed (monotone chain)."""
    pts = sorted(map(tuple, xy))

    def half(points):
        out: list = []
        for p in points:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(pts[::-1])
    ring = lower[:-1] + upper[:-1]
    return np.array(ring + ring[:1])


def plt_color(i: int, n: int):
    """Colour i of n, distinct for any n (tab10 up to 10, then tab20, then a continuous map)."""
    import matplotlib

    if n <= 10:
        return f"C{i}"
    if n <= 20:
        return matplotlib.colormaps["tab20"](i)
    return matplotlib.colormaps["turbo"](i / max(n - 1, 1))


def velocities(result: Result, vmin=None, vmax=None, ax=None, joint_names=None, samples: int = 1000, problem=None):
    """q̇_j(t) / limit for every joint with a finite limit (±1 = the limits; default: the problem's)."""
    return _kinematic(result, "velocity", vmin, vmax, ax, joint_names, samples, problem)


def accelerations(result: Result, amin=None, amax=None, ax=None, joint_names=None, samples: int = 1000, problem=None):
    """q̈_j(t) / limit for every joint with a finite limit (±1 = the limits; default: the problem's)."""
    return _kinematic(result, "acceleration", amin, amax, ax, joint_names, samples, problem)


def _kinematic(result, kind, lo, hi, ax, joint_names, samples, problem):
    ax = _axes(ax)
    if lo is None or hi is None:
        if problem is None:
            return _nothing(ax, f"joint {kind}", f"no {kind} limits given (pass problem=, or the limits)")
        lim = problem_limits(problem).get(kind)
        if lim is None:
            return _nothing(ax, f"joint {kind}", f"no {kind} limits in this problem")
        lo, hi = lim
        joint_names = joint_names or list(_problem(problem).joint_names) or None
    if kind == "velocity":
        d = velocities_data(result, lo, hi, joint_names, samples)
        return _against_limits(ax, d["t"], limit_ratios(d["qd"], d["vmin"], d["vmax"], d["joint_names"]),
                               "q̇ / q̇_limit", "joint velocities against the limits")
    d = accelerations_data(result, lo, hi, joint_names, samples)
    return _against_limits(ax, d["t"], limit_ratios(d["qdd"], d["amin"], d["amax"], d["joint_names"]),
                           "q̈ / q̈_limit", "joint accelerations against the limits")


def summary_figure(spec, result: Result, polygons_at=None):
    """A 3 x 2 figure: phase plane and polygons; velocities and accelerations; torques and contacts, each
    against the problem's limits (a panel without data says why)."""
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(3, 2, figsize=(16, 13))
    names = getattr(spec, "joint_names", None)
    phase_plane(spec, result, axs[0, 0], joint_names=names)
    if result.ok:
        polygons(spec, result, polygons_at, axs[0, 1])
        velocities(result, ax=axs[1, 0], joint_names=names, problem=spec)
        accelerations(result, ax=axs[1, 1], joint_names=names, problem=spec)
        torques(result, getattr(spec, "robot", None), axs[2, 0])
        contacts(result, axs[2, 1])
    else:
        for ax in (axs[0, 1], axs[1, 0], axs[1, 1], axs[2, 0], axs[2, 1]):
            _nothing(ax, "", "no timing: " + result.status.name.lower())
    name = getattr(spec, "name", "")
    fig.suptitle(f"{name + ': ' if name else ''}{result.status.name.lower()}"
                 + (f", T = {result.duration:.4g} s" if result.ok else f" ({result.message})"), wrap=True)
    fig.tight_layout()
    return fig
