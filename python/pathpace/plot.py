"""Pictures of a solved problem (matplotlib, imported only when a function here is called).

* :func:`phase_plane` — ṡ(s) with the maximum-velocity curve, the profile coloured by the binding limit;
* :func:`polygons` — the feasible (ṡ², s̈) polygons at chosen s (the paper's fig. 3) and the solution;
* :func:`torques` — τ(t) against the limits; :func:`contacts` — contact forces and their margin over t;
* :func:`summary_figure` — all of them in one figure (what ``pathpace plot`` saves).

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
    "contact": "#9467bd",
    "boundary": "#7f7f7f",
    "free": "#2ca02c",
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
    word = label.split(" ", 1)[0].lower() if label else "free"
    return word if word in CATEGORY_COLORS else ("torque" if "torque" in label else "free")


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
    """τ(t) (m, nq) by inverse dynamics along the timing, with the limits (the URDF effort unless given)."""
    traj = result.trajectory()
    robot = robot if robot is not None else traj.robot
    if robot is None:
        return None
    t = np.linspace(0.0, traj.duration, samples)
    tau = traj.torques(t, robot)
    hi = robot.effort_limits if tau_max is None else np.asarray(tau_max)
    lo = -robot.effort_limits if tau_min is None else np.asarray(tau_min)
    return {"t": t, "tau": tau, "tau_min": lo, "tau_max": hi, "joint_names": list(robot.joint_names)}


def velocities_data(result: Result, vmin, vmax, joint_names: Sequence[str] | None = None,
                    samples: int = 1000) -> dict[str, Any]:
    """q̇(t) (m, nq) along the timing, with the limits and the joints' names ("joint j" when not given)."""
    traj = result.trajectory()
    t = np.linspace(0.0, traj.duration, samples)
    qd = traj.qd(t)
    names = list(joint_names) if joint_names else [f"joint {j}" for j in range(qd.shape[1])]
    return {"t": t, "qd": qd, "vmin": np.asarray(vmin), "vmax": np.asarray(vmax), "joint_names": names}


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


def _against_limits(ax, t, ratios, ylabel, title):
    """The curves of :func:`limit_ratios` over t, with ±1 marked."""
    for name, y in ratios:
        ax.plot(t, y, lw=1, label=name)
    ax.axhline(1.0, color="k", ls="--", lw=1)
    ax.axhline(-1.0, color="k", ls="--", lw=1)
    ax.set_xlabel("t (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize="x-small", ncol=2)
    return ax


def phase_plane(problem, result: Result, ax=None, joint_names=None):
    """ṡ(s) coloured by the binding limit, over the maximum-velocity curve (dashed)."""
    d = phase_plane_data(problem, result, joint_names)
    ax = _axes(ax)
    finite = np.isfinite(d["sdot_max"])
    ax.plot(d["s"][finite], d["sdot_max"][finite], "k--", lw=1, label="maximum velocity curve")
    s, sd, cat = d["s"], d["sdot"], d["category"]
    seen = set()
    for k in range(len(s) - 1):
        c = cat[k]
        ax.plot(s[k : k + 2], sd[k : k + 2], color=CATEGORY_COLORS[c], lw=2, label=None if c in seen else c)
        seen.add(c)
    top = np.nanmax(np.where(finite, d["sdot_max"], np.nan)) if finite.any() else np.nanmax(sd)
    ax.set_ylim(0, 1.1 * max(top, np.nanmax(np.append(sd, 0.0)), 1e-9))
    ax.set_xlabel("s")
    ax.set_ylabel("ṡ (1/s)")
    ax.set_title("phase plane: profile coloured by the binding limit")
    ax.legend(fontsize="small")
    return ax


def polygons(problem, result: Result, s_values=None, ax=None):
    """Feasible (ṡ², s̈) polygons at chosen s with the solution's point in each (the paper's fig. 3)."""
    ax = _axes(ax)
    for i, p in enumerate(polygons_data(problem, result, s_values)):
        v = p["vertices"]
        color = f"C{i}"
        if len(v):
            closed = np.vstack([v, v[:1]])
            ax.fill(closed[:, 0], closed[:, 1], color=color, alpha=0.2)
            ax.plot(closed[:, 0], closed[:, 1], color=color, label=f"s = {p['s']:.3g} (k = {p['k']})")
        ax.plot([p["x"]], [p["u"]], "o", color=color)
    ax.set_xlabel("x = ṡ² (1/s²)")
    ax.set_ylabel("u = s̈ (1/s²)")
    ax.set_title("feasible polygons and the solution")
    ax.legend(fontsize="small")
    return ax


def torques(result: Result, robot=None, ax=None, tau_min=None, tau_max=None):
    """τ_j(t) / limit for every joint (±1 = the limits; a joint without limit is left out)."""
    d = torques_data(result, robot, tau_min, tau_max)
    ax = _axes(ax)
    if d is None:
        ax.text(0.5, 0.5, "no robot: no torques", ha="center", transform=ax.transAxes)
        return ax
    return _against_limits(ax, d["t"], limit_ratios(d["tau"], d["tau_min"], d["tau_max"], d["joint_names"]),
                           "τ / τ_max", "torques against the limits")


def contacts(result: Result, ax=None):
    """Normal force of each contact (N) and the force-distribution margin (N) over t."""
    d = contacts_data(result)
    ax = _axes(ax)
    if d is None:
        ax.text(0.5, 0.5, "no contacts", ha="center", transform=ax.transAxes)
        return ax
    for i, link in enumerate(d["links"]):
        ax.plot(d["t"], np.linalg.norm(d["forces"][:, i, :], axis=1), lw=1, label=f"|f| {link} #{i}")
    ax.plot(d["t"], d["margin"], "k", lw=2, label="margin")
    ax.axhline(0.0, color="r", ls="--", lw=1)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("N")
    ax.set_title("contact forces and margin")
    ax.legend(fontsize="x-small")
    return ax


def velocities(result: Result, vmin, vmax, ax=None, joint_names=None, samples: int = 1000):
    """q̇_j(t) / limit for every joint with a finite limit (±1 = the limits)."""
    d = velocities_data(result, vmin, vmax, joint_names, samples)
    ax = _axes(ax)
    return _against_limits(ax, d["t"], limit_ratios(d["qd"], d["vmin"], d["vmax"], d["joint_names"]), "q̇ / q̇_max",
                           "joint velocities against the limits")


def summary_figure(spec, result: Result, polygons_at=None):
    """A 2 x 2 figure: phase plane, polygons, torques, contacts (velocities when there are none)."""
    import matplotlib.pyplot as plt

    fig, axs = plt.subplots(2, 2, figsize=(13, 9))
    names = getattr(spec, "joint_names", None)
    phase_plane(spec, result, axs[0, 0], joint_names=names)
    if result.ok:
        polygons(spec, result, polygons_at, axs[0, 1])
        robot = getattr(spec, "robot", None)
        tl = getattr(spec, "torque_limits", None)
        torques(result, robot, axs[1, 0], None if tl is None else tl.tau_min, None if tl is None else tl.tau_max)
        vl = getattr(spec, "velocity_limits", None)
        if getattr(spec, "contacts", None) is None and vl is not None:
            velocities(result, vl[0], vl[1], axs[1, 1], names)
        else:
            contacts(result, axs[1, 1])
    fig.suptitle(f"{getattr(spec, 'name', '')}: {result.status.name.lower()}"
                 + (f", T = {result.duration:.4g} s" if result.ok else f" ({result.message})"))
    fig.tight_layout()
    return fig
