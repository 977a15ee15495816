"""The Python surface: stubs match the module, exports, threads, io round trips."""

import ast
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
from pathpace import _core
from pathpace.io import load_waypoints_csv, result_to_dict, save_result_json, save_trajectory_csv


def test_type_stubs_name_only_what_the_module_has_and_everything_it_exports():
    stub = ast.parse((Path(pp.__file__).parent / "_core.pyi").read_text())
    classes = {n.name: n for n in stub.body if isinstance(n, ast.ClassDef)}
    for name, node in classes.items():
        assert hasattr(_core, name), name
        for item in node.body:
            if isinstance(item, ast.FunctionDef) and not item.name.startswith("__"):
                assert hasattr(getattr(_core, name), item.name), f"{name}.{item.name}"
    attributes = {n.target.id for n in stub.body if isinstance(n, ast.AnnAssign)}
    for name in attributes:
        assert hasattr(_core, name), name
    functions = {n.name for n in stub.body if isinstance(n, ast.FunctionDef)}
    for name in functions:
        assert callable(getattr(_core, name, None)), name
    public = {n for n in dir(_core) if not n.startswith("_")}
    known = set(classes) | attributes | functions
    assert public <= known, public - known


def test_package_exports_everything_in_all():
    for name in pp.__all__:
        assert hasattr(pp, name), name


def problem():
    rng = np.random.default_rng(4)
    return kinematic_problem(rng.uniform(-1, 1, (6, 4)), 400, -np.ones(4), np.ones(4), -2 * np.ones(4), 2 * np.ones(4))


@pytest.mark.parametrize("method", ["auto", "slp"])
def test_one_problem_solved_from_many_threads_gives_one_answer(method):
    prob = problem()
    reference = prob.solve(method=method)
    with ThreadPoolExecutor(4) as pool:
        results = list(pool.map(lambda _: prob.solve(method=method), range(16)))
    for r in results:
        assert r.status == reference.status
        np.testing.assert_array_equal(r.sdot, reference.sdot)


def test_result_and_trajectory_export(tmp_path):
    res = problem().solve()
    d = result_to_dict(res)
    assert d["status"] == "optimal" and d["duration"] == pytest.approx(res.duration)
    save_result_json(res, tmp_path / "r.json")
    back = json.loads((tmp_path / "r.json").read_text())
    np.testing.assert_allclose(back["sdot"], res.sdot)
    traj = res.trajectory()
    save_trajectory_csv(traj, tmp_path / "t.csv", dt=0.05, joint_names=["a", "b", "c", "d"])
    data = np.loadtxt(tmp_path / "t.csv", delimiter=",", skiprows=1)
    header = (tmp_path / "t.csv").read_text().splitlines()[0].split(",")
    assert header[:3] == ["t", "q_a", "q_b"] and len(header) == 13
    assert data[-1, 0] == pytest.approx(traj.duration)
    np.testing.assert_allclose(data[:, 1:5], traj.q(data[:, 0]), atol=1e-12)
    with pytest.raises(pp.InvalidInputError, match="joint_names has 2 entries, the trajectory has 4 coordinates"):
        save_trajectory_csv(traj, tmp_path / "x.csv", dt=0.05, joint_names=["a", "b"])


def test_infeasible_result_exports_with_location(tmp_path):
    path = pp.CubicSplinePath(np.array([[0.0], [1.0]]))
    prob = pp.TimeScalingProblem(path, grid=10)
    prob.add_velocity_limits([0.0], [0.0])
    d = result_to_dict(prob.solve())
    assert d["status"] == "infeasible" and d["duration"] is None
    assert d["binding_constraints"] == ["velocity joint 0"]
    json.dumps(d)


def test_waypoint_csv_with_header(tmp_path):
    f = tmp_path / "w.csv"
    f.write_text("j1,j2\n0,1\n0.5,2\n1,0\n")
    np.testing.assert_array_equal(load_waypoints_csv(f), [[0, 1], [0.5, 2], [1, 0]])


def test_cli_solves_a_waypoint_file(tmp_path, capsys):
    from pathpace.cli import main

    f = tmp_path / "w.csv"
    f.write_text("0,0\n1,0.5\n0.2,1.5\n")
    code = main(["solve", str(f), "--vmax", "1", "--amax", "2", "-N", "200", "--out", str(tmp_path / "t.csv"),
                 "--json", str(tmp_path / "r.json"), "--stats"])
    assert code == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "optimal" and out["duration"] > 0
    assert (tmp_path / "t.csv").is_file() and (tmp_path / "r.json").is_file()


def test_malloc_tuning_is_on_by_default_and_can_be_switched_off():
    import subprocess
    import sys

    code = "import pathpace._core as c; print(c.malloc_tuned)"
    on = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    env = dict(__import__("os").environ, PATHPACE_NO_MALLOC_TUNING="1")
    off = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env).stdout.strip()
    assert (on, off) == ("True", "False")
