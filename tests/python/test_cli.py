"""The `pathpace` command, driven as a user would: a subprocess per call."""

import csv
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
import pathpace.robots

DATA = pathlib.Path(__file__).resolve().parents[1] / "data"


def run(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "pathpace.cli", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, timeout=300)


PENDULUM = f"""\
name: swing
robot:
  urdf: {DATA / 'pendulum.urdf'}
path:
  waypoints: [[0.0], [-0.3], [0.4]]
  boundary: clamped
grid: 400
limits:
  velocity: [3.0]
  acceleration: {{max: [20.0], min: [-15.0]}}
  torque: {{from: urdf, scale: 0.9, margin: 0.1}}
boundary: {{sdot: [0, 0]}}
solver: {{tolerance: 1e-6}}
"""


@pytest.fixture
def problem(tmp_path):
    f = tmp_path / "swing.yaml"
    f.write_text(PENDULUM)
    return f


def api_result():
    robot = pp.RobotModel.from_urdf(DATA / "pendulum.urdf")
    prob = kinematic_problem(pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]]), boundary="clamped"), 400, [-3.0], [3.0],
                             [-15.0], [20.0])
    prob.add_torque_limits(robot, scale=0.9, margin=0.1)
    return prob.solve(tolerance=1e-6)


def test_solve_writes_named_columns_and_the_result(problem, tmp_path):
    out, js, jt = tmp_path / "t.csv", tmp_path / "r.json", tmp_path / "jt.json"
    p = run("solve", problem, "--out", out, "--json", js, "--joint-trajectory", jt, "--dt", 0.005, "--stats")
    assert p.returncode == 0, p.stderr
    summary = json.loads(p.stdout)
    assert summary["status"] == "optimal" and summary["problem"] == "swing"
    assert summary["duration"] == pytest.approx(api_result().duration, rel=1e-12)  # same problem as the API's
    header = next(csv.reader(out.open()))
    assert header == ["t", "q_hinge", "qd_hinge", "qdd_hinge"]
    assert json.loads(js.read_text())["ok"] is True
    msg = json.loads(jt.read_text())
    assert msg["joint_names"] == ["hinge"] and len(msg["points"][0]["effort"]) == 1


def test_check_passes_its_own_timing_and_flags_a_faster_one(problem, tmp_path):
    out = tmp_path / "t.csv"
    assert run("solve", problem, "--out", out).returncode == 0
    p = run("check", problem, out, "--json", tmp_path / "audit.json")
    assert p.returncode == 0, p.stdout + p.stderr
    lines = p.stdout.splitlines()
    assert [ln.split()[0] for ln in lines] == ["velocity", "acceleration", "torque"]  # a continuous joint: no position row
    assert all(ln.endswith("ok") for ln in lines)
    # The same motion 20 % faster: t -> t / 1.2 scales q̇ by 1.2 and q̈ by 1.44 (positions only in this CSV).
    rows = list(csv.reader(out.open()))
    fast = tmp_path / "fast.csv"
    with fast.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "hinge"])
        for r in rows[1:]:
            w.writerow([float(r[0]) / 1.2, r[1]])
    p = run("check", problem, fast)
    assert p.returncode == 1
    bad = [ln for ln in p.stdout.splitlines() if ln.endswith("VIOLATED")]
    assert any(ln.startswith("torque") and "hinge" in ln for ln in bad), p.stdout
    audit = json.loads((tmp_path / "audit.json").read_text())
    assert {r["constraint"] for r in audit} == {"velocity", "acceleration", "torque"}


def one_line_error(p, *needles):
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith("pathpace: error: ")
    for n in needles:
        assert n in lines[0], (n, lines[0])
    return lines[0]


@pytest.mark.parametrize(
    "edit, needles",
    [
        (lambda t: t.replace("grid: 400", "grid: 400\nspeed: 3"), ["swing.yaml", "key 'speed'", "unknown key"]),
        (lambda t: t.replace("velocity: [3.0]", "velocity: [3.0, 2.0]"), ["key 'limits.velocity'", "2 entries", "expected 1"]),
        (lambda t: t.replace("velocity: [3.0]", "velocity: [-3.0]"), ["key 'limits.velocity'", "vmax[0] (hinge) = -3"]),
        (lambda t: t.replace("pendulum.urdf", "nothere.urdf"), ["key 'robot.urdf'", "nothere.urdf", "does not exist"]),
        (lambda t: t.replace("boundary: clamped", "boundary: tight"), ["key 'path'", "boundary = 'tight'"]),
        (lambda t: t.replace("sdot: [0, 0]", "sdot: [0]"), ["key 'boundary.sdot'"]),
        (lambda t: t.replace("tolerance: 1e-6", "tolerance: fast"), ["key 'solver.tolerance'", "'fast'"]),
        (lambda t: t + "contacts: {points: [{link: nowhere}]}\n", ["key 'limits.torque'", "contacts include the torque"]),
        (lambda t: "[1, 2", ["swing.yaml", "not valid YAML"]),
    ],
)
def test_problem_file_errors_are_one_line_naming_the_key(tmp_path, edit, needles):
    f = tmp_path / "swing.yaml"
    f.write_text(edit(PENDULUM))
    one_line_error(run("solve", f), *needles)


def test_argument_and_file_errors_are_one_line(problem, tmp_path):
    one_line_error(run("solve", tmp_path / "missing.yaml"), "missing.yaml", "cannot be read")
    one_line_error(run("solve"), "the following arguments are required: problems")
    one_line_error(run("solve", problem, "--dt", "fast"), "argument --dt", "'fast'")
    one_line_error(run("solve", problem, "--vmax", "1"), "argument --vmax")
    one_line_error(run("solve", problem, "--out", tmp_path / "t.csv", "--dt", "-1"), "--dt = -1.0 must be > 0")
    one_line_error(run("check", problem, tmp_path / "nothing.csv"), "nothing.csv", "cannot be read")
    bad = tmp_path / "bad.csv"
    bad.write_text("t,elbow\n0,1\n1,2\n")
    one_line_error(run("check", problem, bad), "bad.csv", "no column 'q_hinge'")
    one_line_error(run("frobnicate"), "invalid choice: 'frobnicate'")


def test_progress_on_a_single_solve(problem):
    p = run("solve", problem, "--progress", "-v")
    assert p.returncode == 0, p.stderr
    assert "solving swing done in" in p.stderr
    assert json.loads(p.stdout)["status"] == "optimal"


def test_infeasible_exits_1_with_where_and_why(problem, tmp_path):
    f = tmp_path / "weak.yaml"
    f.write_text(PENDULUM.replace("torque: {from: urdf, scale: 0.9, margin: 0.1}", "torque: {min: [-0.1], max: [0.1]}")
                 .replace("[[0.0], [-0.3], [0.4]]", "[[1.0], [2.0]]"))
    p = run("solve", f, "--stats")
    assert p.returncode == 1
    out = json.loads(p.stdout)
    assert out["status"] == "infeasible" and out["binding_constraints"] and out["infeasible_index"] >= 0
    assert "torque hinge upper" in out["binding_constraints"]  # joints named, not numbered


def test_batch_with_progress_bar(problem, tmp_path):
    files = []
    for i, g in enumerate((100, 200, 300)):
        f = tmp_path / f"p{i}.json"  # JSON problem files, grid overridden per file
        import yaml

        d = yaml.safe_load(PENDULUM)
        d["grid"] = g
        f.write_text(json.dumps(d))
        files.append(f)
    p = run("solve", *files, "--out-dir", tmp_path / "out", "--progress", "--workers", 2, "--stats")
    assert p.returncode == 0, p.stderr
    assert "solving [" in p.stderr and "3/3" in p.stderr
    assert [json.loads(ln)["status"] for ln in p.stdout.splitlines()] == ["optimal"] * 3
    assert sorted(x.name for x in (tmp_path / "out").iterdir()) == sorted(
        [f"p{i}.{e}" for i in range(3) for e in ("csv", "json")])


def test_plot_and_demo(problem, tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "fig.png"
    p = run("plot", problem, "--out", png, "--polygons-at", 0.2, 0.5)
    assert p.returncode == 0, p.stderr
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    p = run("demo", "--out-dir", tmp_path / "demo")
    assert p.returncode == 0, p.stdout + p.stderr
    assert "optimal" in p.stdout and "VIOLATED" not in p.stdout
    assert {"panda_demo.yaml", "panda_demo.csv", "panda_demo.json", "panda_demo.png"} <= {
        x.name for x in (tmp_path / "demo").iterdir()}


def test_quick_waypoint_form_with_locked_joints(tmp_path):
    urdf = pp.robots.example_robot_urdf("panda_description/urdf/panda.urdf")
    w = tmp_path / "w.csv"
    rng = np.random.default_rng(1)
    np.savetxt(w, rng.uniform(-0.5, 0.5, (4, 7)), delimiter=",")
    p = run("solve", w, "--urdf", urdf, "--locked-joints", "panda_finger_joint1", "panda_finger_joint2=0",
            "--torque", "--out", tmp_path / "t.csv")
    assert p.returncode == 0, p.stderr
    assert next(csv.reader((tmp_path / "t.csv").open()))[1] == "q_panda_joint1"


def test_contact_problem_file_solves_and_checks(tmp_path):
    """The rod of sec. IV.E standing on its end (tests/python/test_contact.py), |θ| <= 0.15 so that it can
    rest at both ends: the CLI gives the API's timing, and the audit has a contact row."""
    import sys as _sys

    _sys.path.insert(0, str(pathlib.Path(__file__).parent))
    from test_contact import rod_path

    th = np.linspace(-0.15, 0.15, 101)
    path = rod_path(th)
    q, dq, ddq = path.evaluate(th)
    problem = tmp_path / "rod.json"
    problem.write_text(json.dumps({
        "robot": {"urdf": str(DATA / "rod.urdf")},
        "path": {"samples": {"s": th.tolist(), "q": q.tolist(), "dq": dq.tolist(), "ddq": ddq.tolist()}},
        "grid": th.tolist(),
        "contacts": {"points": [{"link": "rod", "point": [0, 0, -1], "normal": [0, 0, 1], "friction": 0.5}],
                     "cone_edges": 4},
    }))
    robot = pp.RobotModel.from_urdf(DATA / "rod.urdf")
    prob = pp.TimeScalingProblem(path, grid=th)
    prob.add_contacts(robot, [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)], cone_edges=4)
    expected = prob.solve()
    assert expected.ok
    out = tmp_path / "t.csv"
    p = run("solve", problem, "--out", out, "--stats")
    assert p.returncode == 0, p.stderr
    # The same problem, built through the file (its constraints in the file's order): the same optimum to
    # far below the certified tolerance (1e-7), not necessarily to the last bit (measured 4e-11).
    assert json.loads(p.stdout)["duration"] == pytest.approx(expected.duration, rel=1e-9)
    p = run("check", problem, out)
    assert p.returncode == 0, p.stdout + p.stderr
    contact = [ln for ln in p.stdout.splitlines() if ln.startswith("contact")]
    assert len(contact) == 1 and contact[0].endswith("ok") and "force-distribution margin" in contact[0]


# ---- papercuts of issue 24 ----


def test_version_and_single_prefix_errors(problem):
    p = run("--version")
    assert p.returncode == 0 and p.stdout.strip() == f"pathpace {pp.__version__}"
    line = one_line_error(run("solve", problem, "--grid", "many"), "argument -N/--grid")
    assert line.startswith("pathpace: error: solve: argument") and "pathpace: error: pathpace" not in line
    line = one_line_error(run("frobnicate"))
    assert line.startswith("pathpace: error: argument command: invalid choice")


def test_solve_prints_one_line_unless_asked_for_stats(problem, tmp_path):
    p = run("solve", problem)
    assert p.returncode == 0, p.stderr
    (line,) = p.stdout.splitlines()
    T = api_result().duration
    assert line.startswith(f"swing: optimal, T = {T:.6g} s (N = 400, solved in ")
    for flag in ("--stats", "-v"):
        assert json.loads(run("solve", problem, flag).stdout)["duration"] == pytest.approx(T, rel=1e-12)
    f = tmp_path / "weak.yaml"
    f.write_text(PENDULUM.replace("torque: {from: urdf, scale: 0.9, margin: 0.1}", "torque: {min: [-0.1], max: [0.1]}"))
    p = run("solve", f)
    assert p.returncode == 1
    (line,) = p.stdout.splitlines()
    assert line.startswith("swing: infeasible: ") and "torque hinge" in line
    p = run("plot", f, "--out", tmp_path / "weak.png")  # a failed solve still plots (the phase plane), exit 1
    assert p.returncode == 1 and p.stdout.splitlines()[0].startswith("swing: infeasible: ")


def test_one_line_names_a_time_limit_and_moving_contacts():
    from types import SimpleNamespace

    from pathpace.cli import _one_line

    prob = kinematic_problem(pp.CubicSplinePath(np.array([[0.0], [-0.3], [0.4]])), 100, [-3.0], [3.0], [-15.0], [20.0])
    res = prob.solve(time_limit=1e-9)
    assert res.status == pp.Status.TIME_LIMIT
    line = _one_line(res, "p")
    assert line.startswith("p: time_limit, T = ") and "time_limit = 1e-09 s reached" in line
    fake = SimpleNamespace(ok=True, status=pp.Status.OPTIMAL, duration=1.0, s=[0, 1], message="the path moves its contacts",
                           contact_drift=[{}], stats={"time_feasible_sets": 0, "time_reachability": 0, "time_slp": 0})
    assert _one_line(fake).endswith(": the path moves its contacts")


def test_dt_is_checked_before_the_solve(problem, tmp_path, monkeypatch):
    from pathpace import cli, problem_file

    def no_load(*a, **k):
        raise AssertionError("the problem was loaded before --dt was checked")

    monkeypatch.setattr(problem_file, "load_problem", no_load)
    for dt in ("0", "nan", "-0.5"):
        with pytest.raises(SystemExit) as e:
            cli.main(["solve", str(problem), "--dt", dt])
        assert e.value.code == 2


def test_plot_out_suffix_is_checked_before_the_solve(problem, tmp_path):
    pytest.importorskip("matplotlib")
    line = one_line_error(run("plot", problem, "--out", tmp_path / "f.xyz"), "argument --out", "suffix 'xyz'",
                          ".png", ".pdf", ".svg")
    assert not (tmp_path / "f.xyz").exists()
    assert "solving" not in line


def test_urdf_erd_on_the_command_line_and_its_errors(tmp_path):
    w = tmp_path / "w.csv"
    np.savetxt(w, np.random.default_rng(2).uniform(-0.5, 0.5, (3, 7)), delimiter=",")
    p = run("solve", w, "--urdf", "erd:panda_description/urdf/panda.urdf", "--locked-joints", "panda_finger_joint1",
            "panda_finger_joint2", "--torque", "--torque-scale", "0.9")
    assert p.returncode == 0, p.stderr
    assert p.stdout.startswith("w: optimal, T = ")
    one_line_error(run("solve", w, "--urdf", "erd:nothing/here.urdf"), "argument --urdf", "nothing/here.urdf")
    one_line_error(run("solve", w, "--urdf", tmp_path / "absent.urdf"), "argument --urdf", "absent.urdf", "does not exist")


def test_locked_mimic_against_its_joint_is_an_error_naming_both(tmp_path):
    w = tmp_path / "w.csv"
    np.savetxt(w, np.zeros((3, 7)), delimiter=",")
    one_line_error(run("solve", w, "--urdf", "erd:panda_description/urdf/panda.urdf", "--locked-joints",
                       "panda_finger_joint1=0.01", "panda_finger_joint2=0.03"),
                   "'panda_finger_joint2' = 0.03 breaks its mimic relation", "'panda_finger_joint1' = 0.01 gives 0.01")


def test_ragged_waypoints_name_the_row(tmp_path):
    f = tmp_path / "ragged.yaml"
    f.write_text(PENDULUM.replace("[[0.0], [-0.3], [0.4]]", "[[0.0], [-0.3, 1.0], [0.4]]"))
    one_line_error(run("solve", f), "key 'path.waypoints[1]'", "has 2 entries, row 0 has 1")


def test_yaml_without_pyyaml_says_what_to_install(problem, tmp_path):
    code = ("import sys; sys.modules['yaml'] = None\n"
            "from pathpace.cli import main\n"
            f"main(['solve', {str(problem)!r}])\n")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert p.returncode == 2
    assert "reading a YAML problem file needs pyyaml: pip install pyyaml (or pathpace[cli])" in p.stderr


def test_help_texts_and_units(problem, tmp_path):
    h = run("solve", "--help").stdout
    for needle in ("--knots {uniform,chord}", "chord length", "--torque-scale", "URDF effort",
                   "SDOT_BEGIN SDOT_END", "rest to rest", "erd:<path>", "--stats, -v"):
        assert needle in " ".join(h.split()), needle
    assert "O(Δs²)" in run("check", "--help").stdout
    out = tmp_path / "t.csv"
    assert run("solve", problem, "--out", out).returncode == 0
    p = run("check", problem, out)
    assert "rad|m" not in p.stdout and "N·m|N" not in p.stdout
    units = {ln.split()[0]: ln.split()[4] for ln in p.stdout.splitlines()}
    assert units == {"velocity": "rad/s", "acceleration": "rad/s²", "torque": "N·m"}


def test_audit_units_per_joint_kind():
    from types import SimpleNamespace

    from pathpace.audit import _units

    robot = pp.RobotModel.from_urdf(DATA / "pendulum.urdf", floating_base=True)
    assert robot.joint_units == ["m", "m", "m", "rad", "rad", "rad", "rad"]
    spec = SimpleNamespace(robot=robot)
    assert _units(spec, 7, "/s") == ["m/s", "m/s", "m/s", "rad/s", "rad/s", "rad/s", "rad/s"]
    assert _units(spec, 7, "", torque=True)[:4] == ["N", "N", "N", "N·m"]
    none = SimpleNamespace(robot=None)
    assert _units(none, 2, "/s²") == ["rad/s² or m/s²"] * 2
    assert _units(none, 1, "", torque=True) == ["N·m or N"]


def test_a_missing_optional_package_names_its_extra(problem, tmp_path):
    for module, extra in (("matplotlib", "plot"), ("plotly", "plot")):
        command = "plot" if module == "matplotlib" else "report"
        code = (f"import sys; sys.modules[{module!r}] = None\n"
                "from pathpace.cli import main\n"
                f"main([{command!r}, {str(problem)!r}, '--out', {str(tmp_path / ('x.png' if command == 'plot' else 'x.html'))!r}])\n")
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
        assert p.returncode == 2, p.stderr
        assert f"needs the Python package '{module}' (pip install {module}, or pathpace[{extra}])" in p.stderr, p.stderr
