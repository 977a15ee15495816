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
    assert titles == ["phase plane: ṡ(s), coloured by the limit that binds",
                      "feasible (ṡ², s̈) polygons and the solution (dots)", "joint velocities against the limits",
                      "joint accelerations against the limits", "torques against the problem's limits",
                      "contact forces"]
    assert fig.axes[5].texts[0].get_text() == "no contacts in this problem"
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
    assert "<script src=" not in text  # self-contained: plotly.js is inline (gzipped)
    assert len(text) < 2_500_000  # was 5.3 MB with plotly.js as text and 1000 float64 samples per curve
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
    assert plots == 5  # phase plane, polygons, torques, velocities, accelerations
    assert traces[0] >= 3 and min(traces) >= 1  # phase plane: curve, profile runs, hover layer
    assert "optimal" in summary and "pendulum" in summary


# ---- the plotted data read back from the matplotlib artists, against the result's numbers (issue 24) ----


def _agg():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _curves(ax):
    """label -> (x, y) of every labelled line of an axes (matplotlib's own data, as drawn)."""
    return {ln.get_label(): (np.asarray(ln.get_xdata(), float), np.asarray(ln.get_ydata(), float))
            for ln in ax.get_lines() if not ln.get_label().startswith("_")}


def pendulum_problem(torque_scale=0.7):
    """The pendulum swing of the CLI tests with the problem's torque limits at `torque_scale` x effort."""
    robot = pp.RobotModel.from_urdf(DATA / "pendulum.urdf")
    prob = kinematic_problem(pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]]), boundary="clamped"), 300, [-3.0],
                             [3.0], [-15.0], [20.0])
    prob.add_torque_limits(robot, scale=torque_scale)
    return robot, prob


def test_torques_plot_divides_by_the_problems_limits_not_the_urdf():
    plt = _agg()
    robot, prob = pendulum_problem(0.7)
    res = prob.solve()
    assert res.ok
    np.testing.assert_allclose(res.tau_max, 0.7 * robot.effort_limits)  # the limits the solve held (C++)
    np.testing.assert_allclose(res.tau_min, -0.7 * robot.effort_limits)
    ax = plot.torques(res, robot)
    assert ax.get_title() == "torques against the problem's limits"
    ((label, (t, y)),) = [(k, v) for k, v in _curves(ax).items()]
    tau = res.trajectory().torques(t, robot)[:, 0]
    np.testing.assert_allclose(y, tau / res.tau_max[0], rtol=1e-12)  # the curve is τ / τ_max of the problem
    # Torque binds somewhere on this swing at 0.7 x effort: the curve reaches ±1 (to the grid's O(Δs²)),
    # where the URDF effort would have put it at 0.7.
    assert 0.98 < np.max(np.abs(y)) < 1.02
    assert label == f"hinge (peak {100 * np.max(np.abs(y)):.0f} %)"
    # Given limits win; without torque limits in the problem the URDF effort is used and the title says so.
    assert plot.torques(res, robot, tau_min=[-10.0], tau_max=[10.0]).get_title() == "torques against the given limits"
    bare = kinematic_problem(pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]])), 100, [-3.0], [3.0], [-15.0], [20.0])
    r2 = bare.solve()
    assert r2.tau_max is None
    ax = plot.torques(r2, robot)
    assert ax.get_title() == "torques against the URDF effort (the problem has no torque limits)"
    _, (t, y) = next(iter(_curves(ax).items()))
    np.testing.assert_allclose(y, r2.trajectory().torques(t, robot)[:, 0] / robot.effort_limits[0], rtol=1e-12)
    assert plot.torques(r2).texts[0].get_text() == "no robot in this problem: no torques"
    plt.close("all")


def test_velocity_and_acceleration_plots_against_the_problems_limits():
    plt = _agg()
    prob = line_problem()
    res = prob.solve()
    for fn, kind, order in ((plot.velocities, "velocities", 1), (plot.accelerations, "accelerations", 2)):
        ax = fn(res, problem=prob)
        assert ax.get_title() == f"joint {kind} against the limits"
        (t, y), = _curves(ax).values()
        np.testing.assert_allclose(y, res.trajectory()(t, order)[:, 0] / 1.0, rtol=1e-12)  # both limits are ±1
        assert np.max(np.abs(y)) == pytest.approx(1.0, abs=1e-9)  # the bang-cruise-bang of T = 4 reaches both
    # Limits given explicitly divide instead; a problem without that kind of limit says so.
    (t, y), = _curves(plot.accelerations(res, [-2.0], [4.0])).values()
    np.testing.assert_allclose(y, res.trajectory().qdd(t)[:, 0] / 4.0, rtol=1e-12)
    only_v = kinematic_problem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), 50, [-1.0], [1.0],
                               [-1.0], [1.0])
    assert set(plot.problem_limits(only_v)) == {"velocity", "acceleration"}
    np.testing.assert_allclose(plot.problem_limits(only_v)["acceleration"][1], [1.0])
    v_only = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=50)
    v_only.add_velocity_limits([-1.0], [1.0])
    v_only.add_velocity_limits([-2.0], [0.5])  # the tightest of two
    np.testing.assert_allclose(plot.problem_limits(v_only)["velocity"][0], [-1.0])
    np.testing.assert_allclose(plot.problem_limits(v_only)["velocity"][1], [0.5])
    ax = plot.accelerations(v_only.solve(), problem=v_only)
    assert ax.texts[0].get_text() == "no acceleration limits in this problem"
    plt.close("all")


def test_many_joints_keep_distinct_colours_and_the_legend_outside():
    plt = _agg()
    t = np.linspace(0, 1, 50)
    ratios = [(f"j{i}", (i + 1) / 20 * np.sin(2 * np.pi * t)) for i in range(20)]
    fig, ax = plt.subplots()
    plot._against_limits(ax, t, ratios, "y", "title")
    coloured = [ln for ln in ax.get_lines() if ln.get_label().startswith("j")]
    assert [ln.get_label().split()[0] for ln in coloured] == [f"j{i}" for i in range(19, 19 - plot.HIGHLIGHT, -1)]
    assert len({ln.get_color() for ln in coloured}) == plot.HIGHLIGHT  # no colour twice
    assert "12 other joints (peak 60 %)" in [ln.get_label() for ln in ax.get_lines()]
    legend = ax.get_legend()
    assert legend.get_bbox_to_anchor().x0 >= ax.get_window_extent().x1  # right of the axes, not over them
    # Contacts: more than 10 force curves still get distinct colours.
    assert len({plot.plt_color(i, 24) for i in range(24)}) == 24
    assert len({plot.plt_color(i, 14) for i in range(14)}) == 14
    assert plot._against_limits(plt.subplots()[1], t, [], "y", "t").texts[0].get_text() == "no joint has a finite limit"
    plt.close("all")


def test_phase_plane_curves_are_the_results_and_infinite_stretches_are_shaded():
    plt = _agg()
    prob = line_problem()
    res = prob.solve()
    ax = plot.phase_plane(prob, res)
    lines = ax.get_lines()
    # The profile segments, joined, are the result's (s, ṡ) at every grid point.
    seg = [ln for ln in lines if ln.get_linestyle() == "-"]
    xs = np.concatenate([ln.get_xdata()[:1] for ln in seg] + [seg[-1].get_xdata()[1:]])
    ys = np.concatenate([ln.get_ydata()[:1] for ln in seg] + [seg[-1].get_ydata()[1:]])
    np.testing.assert_array_equal(xs, res.s)
    np.testing.assert_array_equal(ys, res.sdot)
    mvc = _curves(ax)["maximum-velocity curve"]
    np.testing.assert_allclose(mvc[1], 1.0 / 3.0)
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert labels == ["maximum-velocity curve", "bound by: acceleration limit", "bound by: velocity limit"]
    assert not any("infinite" in x for x in labels)
    # Only acceleration limits on one joint: nothing bounds ṡ alone anywhere; the whole axis is shaded and
    # the legend says what the shading is.
    acc = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=40)
    acc.add_acceleration_limits([-1.0], [1.0])
    r = acc.solve()
    ax = plot.phase_plane(acc, r)
    assert any(t.get_text().startswith("maximum-velocity curve infinite (shaded)") for t in ax.get_legend().get_texts())
    (span,) = ax.patches
    x0, x1 = span.get_bbox().x0, span.get_bbox().x1  # data coordinates in x
    np.testing.assert_allclose([x0, x1], [0.0, 1.0])
    assert ax.get_ylim()[1] == pytest.approx(1.1 * np.max(r.sdot))
    plt.close("all")


def test_phase_plane_categories_know_friction_and_phases():
    assert plot._category("friction at link 'rod' point (0, 0, -1)") == "friction"
    assert plot._category("phases[1]: friction at link 'foot' point (0.1, 0, 0)") == "friction"
    assert plot._category("phases[0]: torque knee upper") == "torque"
    assert plot._category("minimum normal force on link 'foot'") == "normal force"
    assert plot._category("phases[2]: no impact: contact 0 (link 'foot') is made at s = 1") == "contact"
    assert plot._category("contact forces cannot balance the robot") == "contact"
    assert plot._category("sdot^2 >= 0") == "boundary"
    assert plot._category("sddot = 0 at s_begin") == "boundary"
    assert plot._category("my own rows") == "other"
    assert plot._category("") == "free"
    assert set(plot.CATEGORY_NAMES) == set(plot.CATEGORY_COLORS)


def test_phase_plane_of_the_rod_shows_friction_and_the_clipped_curve():
    """The rod of sec. IV.E on its end leaning to 0.3 rad: friction binds somewhere (its own colour), and the
    y range is the profile's when the maximum-velocity curve towers over it."""
    plt = _agg()
    import sys as _sys

    _sys.path.insert(0, str(pathlib.Path(__file__).parent))
    from test_contact import rod_path

    th = np.linspace(-0.15, 0.15, 61)
    robot = pp.RobotModel.from_urdf(DATA / "rod.urdf")
    prob = pp.TimeScalingProblem(rod_path(th), grid=th)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)], cone_edges=4)
    res = prob.solve()
    d = plot.phase_plane_data(prob, res)
    for label, cat in zip(d["binding"], d["category"]):
        assert cat == plot._category(label)
    ax = plot.contacts(res, per_point=True)
    forces = {k: v for k, v in _curves(ax).items() if k.startswith("|f|")}
    (t, f), = forces.values()
    cf = res.trajectory().contact_forces(t)
    np.testing.assert_allclose(f, np.linalg.norm(cf.forces[:, 0, :], axis=1), rtol=1e-9)
    np.testing.assert_allclose(_curves(ax)["margin (weakest cone weight)"][1], cf.margin, rtol=1e-9, atol=1e-9)
    ymax, clipped = plot.phase_plane_ylim({"s": np.array([0.0, 0.5, 1.0]), "sdot": np.array([0.0, 1.0, 0.0]),
                                          "sdot_max": np.array([2.0, 50.0, 2.0])})
    assert ymax == 3.0 and clipped == (50.0, 0.5)
    assert plot.phase_plane_ylim({"s": np.array([0.0, 1.0]), "sdot": np.array([0.0, 1.0]),
                                  "sdot_max": np.array([2.0, 2.0])}) == (pytest.approx(2.2), None)
    plt.close("all")


def test_contacts_and_failed_results_say_why_a_panel_is_empty():
    plt = _agg()
    res = line_problem().solve()
    ax = plot.contacts(res)
    assert ax.texts[0].get_text() == "no contacts in this problem" and ax.get_title() == "contact forces"
    weak = kinematic_problem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), 20, [-1.0], [1.0],
                             [-1.0], [1.0])
    weak.set_boundary_speeds(5.0, 0.0)  # faster than the velocity limit allows at s = 0: infeasible
    bad = weak.solve()
    assert not bad.ok
    assert plot.contacts(bad).texts[0].get_text() == "no timing"
    fig = plot.summary_figure(weak, bad)
    assert fig.axes[1].texts[0].get_text() == "no timing: infeasible"
    assert fig._suptitle.get_text().startswith("infeasible (")
    plt.close("all")


def test_unbounded_polygons_are_drawn_dashed_and_say_so():
    plt = _agg()
    acc = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=40)
    acc.add_acceleration_limits([-1.0], [1.0])
    r = acc.solve()
    ax = plot.polygons(acc, r, s_values=[0.5])
    (edge,) = [ln for ln in ax.get_lines() if not ln.get_label().startswith("_")]
    assert edge.get_label().endswith(", unbounded: cut off") and edge.get_linestyle() == "--"
    bounded = plot.polygons(line_problem(), line_problem().solve(), s_values=[0.5])
    (edge,) = [ln for ln in bounded.get_lines() if not ln.get_label().startswith("_")]
    assert edge.get_linestyle() == "-" and "unbounded" not in edge.get_label()
    plt.close("all")


def test_report_summary_rounds_and_labels():
    pytest.importorskip("plotly")
    from pathpace import report

    prob = line_problem()
    res = prob.solve()
    s = report.summary(prob, res)
    assert s["duration (s)"] == f"{res.duration:.6g}" and len(s["duration (s)"]) <= 8
    figs = dict(report.figures(prob, res))
    assert figs["Joint velocities against the limits"].layout.yaxis.title.text == "joint velocity / limit"
    assert figs["Joint accelerations against the limits"].layout.yaxis.title.text == "joint acceleration / limit"
    assert figs["Joint velocities against the limits"].layout.showlegend  # one joint: its name and peak still shown
    # The data in the page is the result's, to float32.
    phase = figs["Phase plane: ṡ(s), coloured by the limit that binds"]
    hover = [tr for tr in phase.data if tr.mode == "markers"][0]
    np.testing.assert_allclose(np.asarray(hover.y, float), res.sdot, rtol=1e-6)
    vel = figs["Joint velocities against the limits"].data[0]
    np.testing.assert_allclose(np.asarray(vel.y, float), res.trajectory().qd(np.asarray(vel.x, float))[:, 0],
                               rtol=1e-5, atol=1e-6)


def test_views_that_would_hide_the_data_are_narrowed_and_say_so():
    bounded = {"bounded": True, "x": 1.0, "u": 0.5, "vertices": np.array([[0.0, -1.0], [2.0, 0.0], [0.0, 1.0]])}
    assert plot.polygons_view([bounded]) is None
    cut = {"bounded": False, "x": 0.2, "u": -3.0, "vertices": np.array([[0.0, -1e14], [1e14, 0.0], [0.0, 1e14]])}
    (x0, x1), (y0, y1) = plot.polygons_view([bounded, cut])
    assert x0 <= 0.0 and 2.0 < x1 < 10.0 and y0 < -3.0 and 1.0 < y1 < 10.0  # the bounded one and both points
    only = plot.polygons_view([cut])
    assert only[0][0] <= 0.2 <= only[0][1] and only[1][0] <= -3.0 <= only[1][1]
    d = {"s": np.array([0.0, 0.5, 1.0]), "sdot": np.array([0.0, 1.0, 0.0]), "sdot_max": np.array([5.0, 50.0, 5.0])}
    ymax, clipped = plot.phase_plane_ylim(d)
    assert plot.clipped_note(d, ymax, clipped) == "maximum-velocity curve above this range everywhere (min 5, peak 50)"
    d["sdot_max"] = np.array([2.0, 50.0, 2.0])
    ymax, clipped = plot.phase_plane_ylim(d)
    assert plot.clipped_note(d, ymax, clipped) == "maximum-velocity curve clipped (peak 50 at s = 0.5)"
    pytest.importorskip("plotly")
    from pathpace import report

    shaded = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=40)
    shaded.add_acceleration_limits([-1.0], [1.0])
    phase = report.figures(shaded, shaded.solve())[0][1]
    assert "ṡ_max = ∞ (shaded): nothing bounds ṡ alone" in [tr.name for tr in phase.data]
    assert len(phase.layout.shapes) == 1 and phase.layout.shapes[0].x0 == 0.0 and phase.layout.shapes[0].x1 == 1.0
    # Drawn: the polygons' axes take that view, with the note.
    plt = _agg()
    acc = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=40)
    acc.add_acceleration_limits([-1.0], [1.0])
    r = acc.solve()
    ax = plot.polygons(acc, r, s_values=[0.5])
    assert ax.get_xlim()[1] < 1e3 and "unbounded polygons extend beyond the view" in [t.get_text() for t in ax.texts]
    plt.close("all")


def test_clipped_curve_and_narrowed_view_are_noted_on_both_backends():
    """A parabola that reverses at s = 0.544 (p' = 0): the maximum-velocity curve peaks far above the
    profile, and a 1-joint polygon under acceleration limits alone is unbounded."""
    plt = _agg()
    pytest.importorskip("plotly")
    from pathpace import report

    prob = pp.TimeScalingProblem(pp.CubicSplinePath(np.array([[0.0], [1.0], [0.3]])), grid=200)
    prob.add_acceleration_limits([-2.0], [2.0])
    prob.add_velocity_limits([-1.5], [1.5])
    res = prob.solve()
    ax = plot.phase_plane(prob, res)
    assert any(t.get_text().startswith("maximum-velocity curve clipped (peak ") for t in ax.texts)
    assert ax.get_ylim()[1] == pytest.approx(3.0 * np.max(res.sdot))
    figs = report.figures(prob, res)
    assert any(a.text.startswith("maximum-velocity curve clipped") for a in figs[0][1].layout.annotations)
    acc = pp.TimeScalingProblem(pp.PiecewisePolynomialPath([0.0, 1.0], np.array([[[0.0], [3.0]]])), grid=40)
    acc.add_acceleration_limits([-1.0], [1.0])
    poly = dict(report.figures(acc, acc.solve()))["Feasible polygons in (ṡ², s̈) and the solution (the paper's fig. 3)"]
    assert [a.text for a in poly.layout.annotations] == ["unbounded polygons extend beyond the view"]
    assert poly.layout.xaxis.range[1] < 1e3
    assert plot.velocities(res).texts[0].get_text() == "no velocity limits given (pass problem=, or the limits)"
    plt.close("all")


def test_contacts_default_to_per_link_normal_forces_and_centres_of_pressure_sit_in_their_soles(monkeypatch):
    """The Talos sway on 9 points per sole: one line per sole (not 18), equal to contact_wrenches'
    normal force; the centre-of-pressure plot draws each sole's support hull and its CoP trace inside."""
    plt = _agg()
    import sys as _sys

    _sys.path.insert(0, str(pathlib.Path(__file__).parent))
    import contact_corpus as cc

    h = cc.load("talos")
    cons = cc.contacts(h, "sway", grid=(3, 3))
    prob = pp.TimeScalingProblem(cc.make_path(h, "sway"), grid=60)
    prob.add_contacts(h.robot, cons, cone_edges=8, min_normal_force=5.0, drift_tolerance=1e-4)
    res = prob.solve()

    def second_evaluation(*_args, **_kwargs):
        raise AssertionError("contact_forces called: the margin comes with contact_wrenches' forces")

    # The per-link plots evaluate the forces once: the margin is ContactWrenches.margin.
    monkeypatch.setattr(pp.Trajectory, "contact_forces", second_evaluation)
    ax = plot.contacts(res)
    lines = {k: v for k, v in _curves(ax).items() if k.startswith("normal force on")}
    assert sorted(lines) == ["normal force on left_sole_link", "normal force on right_sole_link"]
    t, f = lines["normal force on left_sole_link"]
    w = res.trajectory().contact_wrenches(t)
    np.testing.assert_allclose(f, w.normal_force[:, w.links.index("left_sole_link")], rtol=1e-12)
    ax = plot.centers_of_pressure(res)
    curves = _curves(ax)
    for link in ("left_sole_link", "right_sole_link"):
        x, y = curves[f"centre of pressure of {link}"]
        hull = [p for p in ax.patches if p.get_label() == f"support of {link}"][0].get_xy()
        assert (x.min() >= hull[:, 0].min() - 1e-6 and x.max() <= hull[:, 0].max() + 1e-6
                and y.min() >= hull[:, 1].min() - 1e-6 and y.max() <= hull[:, 1].max() + 1e-6)
        assert len(hull) == 5  # the sole's 4 corners, closed: interior points are not on the hull
    assert plot.centers_of_pressure(pp.TimeScalingProblem(cc.make_path(h, "sway"), grid=4).solve()).texts
    plt.close("all")
    # The HTML report draws the same: a line per link, not per point, and each CoP in its sole's polygon.
    from pathpace import report

    figs = dict(report.figures(prob, res))
    monkeypatch.undo()
    # ... and it is the margin of those forces: contact_forces' at the same times.
    t, margin = _curves(plot.contacts(res))["margin (weakest cone weight)"]
    np.testing.assert_array_equal(margin, res.trajectory().contact_forces(t).margin)
    traces = {tr.name: tr for tr in figs["Contact forces and their margin"].data}
    page_t = plot.wrenches_data(res)["t"]  # the page's times, before float32
    np.testing.assert_array_equal(traces["margin (weakest cone weight)"].y,  # the page stores float32
                                  res.trajectory().contact_forces(page_t).margin.astype(np.float32))
    assert sorted(traces) == ["margin (weakest cone weight)", "normal force on left_sole_link",
                              "normal force on right_sole_link"]
    wd = plot.wrenches_data(res)  # what the matplotlib plot draws (its t, contact_wrenches' normal force)
    np.testing.assert_allclose(traces["normal force on left_sole_link"].y,  # the page stores float32
                               wd["normal_force"][:, wd["links"].index("left_sole_link")], rtol=1e-6)
    cop = {tr.name: tr for tr in figs["Centres of pressure in their support polygons"].data}
    for link in ("left_sole_link", "right_sole_link"):
        hx, hy = np.asarray(cop[f"support of {link}"].x), np.asarray(cop[f"support of {link}"].y)
        x, y = np.asarray(cop[f"centre of pressure of {link}"].x), np.asarray(cop[f"centre of pressure of {link}"].y)
        assert len(hx) == 5
        assert x.min() >= hx.min() - 1e-6 and x.max() <= hx.max() + 1e-6
        assert y.min() >= hy.min() - 1e-6 and y.max() <= hy.max() + 1e-6
