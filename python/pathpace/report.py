"""``pathpace report``: one self-contained HTML page (plotly, its JavaScript inline) with the plots of
:mod:`pathpace.plot` and a summary of the problem and the result. plotly is imported only here."""

from __future__ import annotations

import html
import json
import os
from pathlib import Path
from typing import Any

import numpy as np

from . import plot as _plot


def _segments(x: np.ndarray, y: np.ndarray, category: list[str]) -> dict[str, tuple[list, list]]:
    """One polyline per category with gaps (None) between its runs, for plotly."""
    out: dict[str, tuple[list, list]] = {}
    for k in range(len(x) - 1):
        xs, ys = out.setdefault(category[k], ([], []))
        if xs and xs[-1] is not None and xs[-1] != x[k]:
            xs.append(None)
            ys.append(None)
        if not xs or xs[-1] != x[k]:
            xs.append(float(x[k]))
            ys.append(float(y[k]))
        xs.append(float(x[k + 1]))
        ys.append(float(y[k + 1]))
    return out


def _against_limits(t, ratios, ytitle: str):
    """The curves of :func:`pathpace.plot.limit_ratios` over t, with ±1 marked."""
    import plotly.graph_objects as go

    f = go.Figure()
    for name, y in ratios:
        f.add_trace(go.Scatter(x=t, y=y, mode="lines", name=name))
    for y in (-1, 1):
        f.add_hline(y=y, line={"dash": "dash", "color": "black", "width": 1})
    f.update_layout(xaxis_title="t (s)", yaxis_title=ytitle)
    return f


def figures(spec, result) -> list[tuple[str, Any]]:
    """(title, plotly Figure) for every plot that applies to this problem and result."""
    import plotly.graph_objects as go

    figs = []
    names = getattr(spec, "joint_names", None)
    d = _plot.phase_plane_data(spec, result, names)
    f = go.Figure()
    finite = np.isfinite(d["sdot_max"])
    f.add_trace(go.Scatter(x=d["s"][finite], y=d["sdot_max"][finite], mode="lines", name="maximum velocity curve",
                           line={"dash": "dash", "color": "black", "width": 1}))
    if result.ok:
        for cat, (xs, ys) in _segments(d["s"], d["sdot"], d["category"]).items():
            f.add_trace(go.Scatter(x=xs, y=ys, mode="lines", name=cat, line={"color": _plot.CATEGORY_COLORS[cat], "width": 3}))
        f.add_trace(go.Scatter(x=d["s"], y=d["sdot"], mode="markers", marker={"size": 2, "opacity": 0}, showlegend=False,
                               text=d["binding"], hovertemplate="s=%{x:.4f}<br>ṡ=%{y:.4f}<br>%{text}<extra></extra>"))
    f.update_layout(xaxis_title="s", yaxis_title="ṡ (1/s)")
    figs.append(("Phase plane: ṡ(s), coloured by the binding limit", f))
    if not result.ok:
        return figs

    f = go.Figure()
    for i, p in enumerate(_plot.polygons_data(spec, result)):
        v = p["vertices"]
        color = f"hsl({(i * 110) % 360}, 60%, 45%)"
        if len(v):
            closed = np.vstack([v, v[:1]])
            f.add_trace(go.Scatter(x=closed[:, 0], y=closed[:, 1], fill="toself", mode="lines", line={"color": color},
                                   name=f"s = {p['s']:.3g} (k = {p['k']})", opacity=0.6))
        f.add_trace(go.Scatter(x=[p["x"]], y=[p["u"]], mode="markers", marker={"color": color, "size": 9},
                               showlegend=False))
    f.update_layout(xaxis_title="x = ṡ² (1/s²)", yaxis_title="u = s̈ (1/s²)")
    figs.append(("Feasible polygons in (ṡ², s̈) and the solution (the paper's fig. 3)", f))

    tl = getattr(spec, "torque_limits", None)
    td = _plot.torques_data(result, getattr(spec, "robot", None), None if tl is None else tl.tau_min,
                            None if tl is None else tl.tau_max)
    if td is not None:
        figs.append(("Torques against the limits",
                     _against_limits(td["t"], _plot.limit_ratios(td["tau"], td["tau_min"], td["tau_max"], td["joint_names"]),
                                     "τ / τ_max")))

    vl = getattr(spec, "velocity_limits", None)
    if vl is not None:
        vd = _plot.velocities_data(result, vl[0], vl[1], names)
        figs.append(("Joint velocities against the limits",
                     _against_limits(vd["t"], _plot.limit_ratios(vd["qd"], vd["vmin"], vd["vmax"], vd["joint_names"]),
                                     "q̇ / q̇_max")))

    cd = _plot.contacts_data(result)
    if cd is not None:
        f = go.Figure()
        for i, link in enumerate(cd["links"]):
            f.add_trace(go.Scatter(x=cd["t"], y=np.linalg.norm(cd["forces"][:, i, :], axis=1), mode="lines",
                                   name=f"|f| {link} #{i}"))
        f.add_trace(go.Scatter(x=cd["t"], y=cd["margin"], mode="lines", name="margin", line={"color": "black", "width": 3}))
        f.add_hline(y=0.0, line={"dash": "dash", "color": "red", "width": 1})
        f.update_layout(xaxis_title="t (s)", yaxis_title="N")
        figs.append(("Contact forces and their margin", f))
    return figs


def summary(spec, result) -> dict[str, Any]:
    prob = spec.problem if hasattr(spec, "problem") else spec
    out = {
        "problem": getattr(spec, "name", ""),
        "status": result.status.name.lower(),
        "duration (s)": float(result.duration) if result.ok else None,
        "grid intervals N": int(prob.intervals),
        "constraints": ", ".join(c.name for c in prob.constraints),
        "boundary speeds ṡ": f"{prob.sdot_begin:g}, {prob.sdot_end:g}",
    }
    if getattr(spec, "robot", None) is not None:
        out["robot"] = f"{spec.robot.name} ({spec.robot.nq} joints)"
    if not result.ok:
        out["message"] = result.message
        out["binding constraints"] = ", ".join(result.binding_constraints)
    st = result.stats
    out["certified gap"] = st.get("gap")
    out["solve time (ms)"] = round(1e3 * (st["time_feasible_sets"] + st["time_reachability"] + st["time_slp"]), 3)
    return out


def write_report(spec, result, out: str | os.PathLike) -> Path:
    """Writes the page to `out` (plotly.js inline: it opens offline) and returns its path."""
    import plotly.io as pio

    figs = figures(spec, result)
    parts = []
    for i, (title, fig) in enumerate(figs):
        fig.update_layout(height=430, margin={"l": 60, "r": 20, "t": 30, "b": 50}, template="plotly_white")
        parts.append(f"<h2>{html.escape(title)}</h2>\n" + pio.to_html(fig, full_html=False, include_plotlyjs=(i == 0),
                                                                      div_id=f"fig{i}"))
    rows = "\n".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
                     for k, v in summary(spec, result).items())
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>pathpace report: {html.escape(getattr(spec, 'name', ''))}</title>
<style>body{{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}} table{{border-collapse:collapse}}
th,td{{border:1px solid #ccc;padding:4px 8px;text-align:left}} th{{background:#f4f4f4}}</style></head>
<body><h1>pathpace report: {html.escape(getattr(spec, 'name', ''))}</h1>
<table id="summary">{rows}</table>
{''.join(parts)}
<script type="application/json" id="pathpace-summary">{json.dumps(summary(spec, result))}</script>
</body></html>
"""
    path = Path(out)
    path.write_text(page, encoding="utf-8")
    return path
