"""pathpace.plot (matplotlib) and the HTML report, rendered in headless Chromium (Debian's chromium driven
by playwright); the rendering test is skipped cleanly when either is missing."""

import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
from pathpace import plot

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"


def line_problem(N=200):
    """q = 3 s under |q̇| <= 1, |q̈| <= 1: accelerate (acceleration binds), cruise at the velocity limit,
    brake — T = 4 analytically."""
    return kinematic_problem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), N, [-1.0], [1.0], [-1.0],
                             [1.0])


def test_phase_plane_colours_the_binding_limit():
    prob = line_problem()
    res = prob.solve()
    d = plot.phase_plane_data(prob, res, joint_names=["slide"])
    s, cat = d["s"], d["category"]
    np.testing.assert_allclose(d["sdot_max"], 1.0 / 3.0)  # |p'| ṡ <= 1
    # Accelerating on s < 1/6 (q from 0 to 0.5), cruising in the middle, braking after s = 5/6.
    assert all(c == "acceleration" for c, x in zip(cat, s) if 0 < x < 0.16)
    assert all(c == "velocity" for c, x in zip(cat, s) if 0.18 < x < 0.82)
    assert all(c == "acceleration" for c, x in zip(cat, s) if 0.84 < x < 1)
    assert "slide" in d["binding"][100]  # joint names replace indices in the labels


def test_polygons_contain_the_solution():
    prob = line_problem()
    res = prob.solve()
    for p in plot.polygons_data(prob, res, count=5):
        fs = prob.feasible_set(p["k"])
        assert fs.contains(p["x"], p["u"], 1e-9)
        assert p["vertices"].shape[1] == 2 and len(p["vertices"]) >= 3


def test_matplotlib_figure_has_the_four_panels(tmp_path):
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    from pathpace.problem_file import load_problem

    f = tmp_path / "swing.yaml"
    f.write_text(f"robot: {{urdf: {DATA / 'pendulum.urdf'}}}\npath: {{waypoints: [[0.0], [-0.3], [0.4]]}}\ngrid: 300\n"
                 "limits: {velocity: [3.0], acceleration: [20.0], torque: {scale: 0.9}}\n")
    spec = load_problem(f)
    res = spec.solve()
    fig = plot.summary_figure(spec, res, polygons_at=[0.3, 0.6])
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["phase plane: profile coloured by the binding limit", "feasible polygons and the solution",
                      "torques against the limits", "joint velocities against the limits"]
    fig.savefig(tmp_path / "f.svg")
    assert (tmp_path / "f.svg").stat().st_size > 10_000


def chromium_executable():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def test_report_renders_in_headless_chromium_without_console_errors(tmp_path):
    pytest.importorskip("plotly")
    sync_api = pytest.importorskip("playwright.sync_api")
    exe = chromium_executable()
    if exe is None:
        pytest.skip("no chromium executable (apt-get install chromium)")
    problem = tmp_path / "swing.yaml"
    problem.write_text(f"name: swing\nrobot: {{urdf: {DATA / 'pendulum.urdf'}}}\n"
                       "path: {waypoints: [[0.0], [-0.3], [0.4]]}\ngrid: 300\n"
                       "limits: {velocity: [3.0], acceleration: [20.0], torque: {scale: 0.9}}\n")
    page_file = tmp_path / "report.html"
    p = subprocess.run([sys.executable, "-m", "pathpace.cli", "report", str(problem), "--out", str(page_file)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stderr
    text = page_file.read_text()
    assert "<script src=" not in text  # self-contained: plotly.js is inline
    errors = []
    with sync_api.sync_playwright() as pw:
        try:
            browser = pw.chromium.launch(executable_path=exe, args=["--no-sandbox", "--disable-gpu"])
        except Exception as e:  # noqa: BLE001 - a browser that cannot start is an environment problem
            pytest.skip(f"chromium does not start under playwright: {str(e).splitlines()[0]}")
        page = browser.new_page()
        page.on("console", lambda m: errors.append(m.text) if m.type == "error" else None)
        page.on("pageerror", lambda e: errors.append(str(e)))
        page.goto(page_file.as_uri())
        page.wait_for_function("document.querySelectorAll('.js-plotly-plot .main-svg').length >= 4", timeout=30000)
        plots = page.eval_on_selector_all(".js-plotly-plot", "els => els.length")
        traces = page.evaluate("Array.from(document.querySelectorAll('.js-plotly-plot')).map(d => d.data.length)")
        summary = page.inner_text("#summary")
        browser.close()
    assert errors == []
    assert plots == 4  # phase plane, polygons, torques, velocities
    assert traces[0] >= 3 and min(traces) >= 1  # phase plane: curve, profile runs, hover layer
    assert "optimal" in summary and "pendulum" in summary
