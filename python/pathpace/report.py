"""``pathpace report``: one self-contained HTML page (plotly, its JavaScript inline and gzipped) with the
plots of :mod:`pathpace.plot` and a summary of the problem and the result. plotly is imported only here."""

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


def _f32(a) -> np.ndarray:
    """Plotted data as float32 (7 digits: far below a pixel), half the bytes the page embeds."""
    return np.asarray(a, dtype=float).astype(np.float32)


def _against_limits(t, ratios, ytitle: str):
    """The curves of :func:`pathpace.plot.limit_ratios` over t with ±1 marked: as in the matplotlib plot,
    the joints nearest their limits (:func:`pathpace.plot.ranked_ratios`) in colour, the others grey under
    one legend entry (click it to hide them)."""
    import plotly.graph_objects as go

    f = go.Figure()
    top, rest = _plot.ranked_ratios(ratios)
    t32 = _f32(t)
    for i, (name, y) in enumerate(rest):
        f.add_trace(go.Scatter(x=t32, y=_f32(y), mode="lines", name=name, legendgroup="others",
                               showlegend=i == 0, legendgrouptitle=None, line={"color": "#bbbbbb", "width": 1},
                               hovertemplate=f"{name}: %{{y:.3f}}<extra></extra>"))
    if rest:
        f.data[0].name = f"{len(rest)} other joints"
    palette = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf"]
    for i, (name, y) in enumerate(top):
        peak = 100 * float(np.nanmax(np.abs(y)))
        f.add_trace(go.Scatter(x=t32, y=_f32(y), mode="lines", name=f"{name} (peak {peak:.0f} %)",
                               line={"color": palette[i % len(palette)], "width": 2},
                               hovertemplate=f"{name}: %{{y:.3f}}<extra></extra>"))
    for y in (-1, 1):
        f.add_hline(y=y, line={"dash": "dash", "color": "black", "width": 1})
    # showlegend: plotly hides the legend of a single trace, and with it the joint's name and peak.
    f.update_layout(xaxis_title="t (s)", yaxis_title=ytitle, yaxis_range=[-1.15, 1.15], showlegend=True)
    return f


def figures(spec, result) -> list[tuple[str, Any]]:
    """(title, plotly Figure) for every plot that applies to this problem and result."""
    import plotly.graph_objects as go

    figs = []
    names = getattr(spec, "joint_names", None)
    d = _plot.phase_plane_data(spec, result, names)
    f = go.Figure()
    finite = np.isfinite(d["sdot_max"])
    f.add_trace(go.Scatter(x=_f32(d["s"]), y=_f32(np.where(finite, d["sdot_max"], np.nan)), mode="lines",
                           name="maximum-velocity curve", line={"dash": "dash", "color": "black", "width": 1}))
    spans = _plot._unbounded_spans(d["s"], finite)
    for a, b in spans:
        half = 0.5 * (d["s"][1] - d["s"][0]) if a == b and len(d["s"]) > 1 else 0.0
        f.add_vrect(x0=a - half, x1=b + half, fillcolor="#d9d9d9", opacity=0.6, line_width=0, layer="below")
    if spans:  # said in the legend (an annotation per stretch would collide with the others)
        f.add_trace(go.Scatter(x=[None], y=[None], mode="markers", name="ṡ_max = ∞ (shaded): nothing bounds ṡ alone",
                               marker={"symbol": "square", "size": 12, "color": "#d9d9d9"}))
    if result.ok:
        for cat, (xs, ys) in _segments(d["s"], d["sdot"], d["category"]).items():
            f.add_trace(go.Scatter(x=xs, y=ys, mode="lines", name=f"bound by: {_plot.CATEGORY_NAMES[cat]}",
                                   line={"color": _plot.CATEGORY_COLORS[cat], "width": 3}, hoverinfo="skip"))
        f.add_trace(go.Scatter(x=_f32(d["s"]), y=_f32(d["sdot"]), mode="markers", marker={"size": 2, "opacity": 0},
                               showlegend=False, text=d["binding"],
                               hovertemplate="s=%{x:.4f}<br>ṡ=%{y:.4f}<br>%{text}<extra></extra>"))
    ymax, clipped = _plot.phase_plane_ylim(d)
    if clipped is not None:
        f.add_annotation(text=_plot.clipped_note(d, ymax, clipped),
                         xref="paper", yref="paper", x=1, y=1, showarrow=False, xanchor="right", yanchor="top")
    f.update_layout(xaxis_title="s (path parameter)", yaxis_title="ṡ (1/s)", yaxis_range=[0, ymax])
    figs.append(("Phase plane: ṡ(s), coloured by the limit that binds", f))
    if not result.ok:
        return figs

    f = go.Figure()
    polys = _plot.polygons_data(spec, result)
    for i, p in enumerate(polys):
        v = p["vertices"]
        color = f"hsl({(i * 110) % 360}, 60%, 45%)"
        if len(v):
            closed = np.vstack([v, v[:1]])
            f.add_trace(go.Scatter(x=closed[:, 0], y=closed[:, 1], fill="toself", mode="lines", line={"color": color},
                                   name=f"s = {p['s']:.3g} (k = {p['k']})" + ("" if p["bounded"] else ", unbounded: cut off"),
                                   opacity=0.6))
        f.add_trace(go.Scatter(x=[p["x"]], y=[p["u"]], mode="markers", marker={"color": color, "size": 9},
                               showlegend=False))
    f.update_layout(xaxis_title="x = ṡ² (1/s²)", yaxis_title="u = s̈ (1/s²)")
    view = _plot.polygons_view(polys)
    if view is not None:  # unbounded polygons are cut at the solver's stand-in bound: show the rest
        f.update_layout(xaxis_range=list(view[0]), yaxis_range=list(view[1]))
        f.add_annotation(text="unbounded polygons extend beyond the view", xref="paper", yref="paper", x=1, y=0,
                         showarrow=False, xanchor="right", yanchor="bottom")
    figs.append(("Feasible polygons in (ṡ², s̈) and the solution (the paper's fig. 3)", f))

    td = _plot.torques_data(result, getattr(spec, "robot", None), samples=_SAMPLES)
    if td is not None:
        what = {"problem": "the problem's limits", "given": "the given limits",
                "urdf": "the URDF effort (the problem has no torque limits)"}[td["limits"]]
        figs.append((f"Torques against {what}",
                     _against_limits(td["t"], _plot.limit_ratios(td["tau"], td["tau_min"], td["tau_max"], td["joint_names"]),
                                     "torque / limit")))

    limits = _plot.problem_limits(spec)
    if "velocity" in limits:
        vd = _plot.velocities_data(result, *limits["velocity"], names, samples=_SAMPLES)
        figs.append(("Joint velocities against the limits",
                     _against_limits(vd["t"], _plot.limit_ratios(vd["qd"], vd["vmin"], vd["vmax"], vd["joint_names"]),
                                     "joint velocity / limit")))
    if "acceleration" in limits:
        ad = _plot.accelerations_data(result, *limits["acceleration"], names, samples=_SAMPLES)
        figs.append(("Joint accelerations against the limits",
                     _against_limits(ad["t"], _plot.limit_ratios(ad["qdd"], ad["amin"], ad["amax"], ad["joint_names"]),
                                     "joint acceleration / limit")))

    w = _plot.wrenches_data(result)
    if w is not None:
        # Per link, as plot.contacts draws by default: the normal force on each link (not a line per point),
        # and the margin of the same forces (one evaluation).
        f = go.Figure()
        for n, link in enumerate(w["links"]):
            f.add_trace(go.Scatter(x=_f32(w["t"]), y=_f32(w["normal_force"][:, n]), mode="lines",
                                   name=f"normal force on {link}"))
        f.add_trace(go.Scatter(x=_f32(w["t"]), y=_f32(w["margin"]), mode="lines", name="margin (weakest cone weight)",
                               line={"color": "black", "width": 3}))
        f.add_hline(y=0.0, line={"dash": "dash", "color": "red", "width": 1})
        f.update_layout(xaxis_title="t (s)", yaxis_title="force (N)")
        figs.append(("Contact forces and their margin", f))
        # Each link's centre of pressure in its support polygon (plot.centers_of_pressure).
        hulls = _plot.support_polygons(result, w["links"])
        f = go.Figure()
        for n, link in enumerate(w["links"]):
            if hulls[link] is not None:
                f.add_trace(go.Scatter(x=hulls[link][:, 0], y=hulls[link][:, 1], mode="lines", fill="toself",
                                       opacity=0.3, name=f"support of {link}"))
            f.add_trace(go.Scatter(x=_f32(w["cop"][:, n, 0]), y=_f32(w["cop"][:, n, 1]), mode="lines",
                                   name=f"centre of pressure of {link}"))
        f.update_layout(xaxis_title="x (m)", yaxis_title="y (m)", yaxis={"scaleanchor": "x", "scaleratio": 1})
        figs.append(("Centres of pressure in their support polygons", f))
    return figs


#: Samples per curve over t in the page (a plot is ~1000 px wide; the matplotlib plots take 1000).
_SAMPLES = 500


def summary(spec, result) -> dict[str, Any]:
    prob = spec.problem if hasattr(spec, "problem") else spec
    st = result.stats
    out = {
        "problem": getattr(spec, "name", ""),
        "status": result.status.name.lower(),
        "duration (s)": f"{result.duration:.6g}" if result.ok else None,
        "grid intervals N": int(prob.intervals),
        "constraints": ", ".join(c.name for c in prob.constraints),
        "boundary speeds ṡ (1/s)": f"{prob.sdot_begin:g}, {prob.sdot_end:g}",
    }
    if getattr(spec, "robot", None) is not None:
        out["robot"] = f"{spec.robot.name} ({spec.robot.nq} joints)"
    if result.message:
        out["message"] = result.message
    if not result.ok:
        out["binding constraints"] = ", ".join(result.binding_constraints)
    gap = st.get("gap")
    out["certified gap"] = f"{gap:.2g}" if gap is not None else None
    out["solve time (ms)"] = f"{1e3 * (st['time_feasible_sets'] + st['time_reachability'] + st['time_slp']):.3g}"
    return out


def _plotly_js_gzip_base64() -> str:
    """plotly.js, gzipped and base64-encoded: a third of its size; the page inflates it with the browser's
    DecompressionStream (Chrome 80, Firefox 113, Safari 16.4) and needs no network."""
    import base64
    import gzip

    from plotly.offline import get_plotlyjs

    return base64.b64encode(gzip.compress(get_plotlyjs().encode("utf-8"), compresslevel=9, mtime=0)).decode("ascii")


_LOADER = """
<script>
(async function () {
  const note = document.getElementById("pathpace-loading");
  try {
    const b64 = document.getElementById("pathpace-plotlyjs").textContent;
    const bytes = Uint8Array.from(atob(b64), c => c.charCodeAt(0));
    const js = await new Response(new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"))).text();
    const s = document.createElement("script");
    s.text = js;
    document.head.appendChild(s);
    for (const el of document.querySelectorAll("script.pathpace-figure")) {
      const fig = JSON.parse(el.textContent);
      Plotly.newPlot(el.dataset.div, fig.data, fig.layout, {responsive: true});
    }
    note.remove();
  } catch (e) {
    note.textContent = "The plots need a browser with DecompressionStream (Chrome 80+, Firefox 113+, Safari 16.4+): " + e;
  }
})();
</script>
"""


def write_report(spec, result, out: str | os.PathLike) -> Path:
    """Writes the page to `out` (plotly.js inline, compressed: it opens offline) and returns its path."""
    figs = figures(spec, result)
    parts = []
    for i, (title, fig) in enumerate(figs):
        fig.update_layout(height=430, margin={"l": 60, "r": 20, "t": 30, "b": 50}, template="plotly_white")
        data = fig.to_json().replace("</", "<\\/")  # no "</script>" inside the JSON
        parts.append(f"<h2>{html.escape(title)}</h2>\n<div id=\"fig{i}\" style=\"height:430px\"></div>\n"
                     f"<script type=\"application/json\" class=\"pathpace-figure\" data-div=\"fig{i}\">{data}</script>")
    info = summary(spec, result)
    rows = "\n".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>" for k, v in info.items())
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>pathpace report: {html.escape(getattr(spec, 'name', ''))}</title>
<style>body{{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}} table{{border-collapse:collapse}}
th,td{{border:1px solid #ccc;padding:4px 8px;text-align:left}} th{{background:#f4f4f4}}</style></head>
<body><h1>pathpace report: {html.escape(getattr(spec, 'name', ''))}</h1>
<table id="summary">{rows}</table>
<p id="pathpace-loading">Drawing the plots...</p>
{''.join(parts)}
<script type="application/json" id="pathpace-summary">{json.dumps(info)}</script>
<script type="text/plain" id="pathpace-plotlyjs">{_plotly_js_gzip_base64()}</script>
{_LOADER}
</body></html>
"""
    path = Path(out)
    path.write_text(page, encoding="utf-8")
    return path
