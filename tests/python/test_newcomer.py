"""What a newcomer trips on (issue 24), through the Python API: reprs from C++ facts, the progress bar,
the time limit of a problem proven without SLP, sliding contacts (drift=), their pickling and problem files."""

import io
import json
import pickle
import re
import warnings

import numpy as np
import pytest

import pathpace as pp
from helpers import kinematic_problem
from test_contact_objects import box_corners, lifter_with_box


def readme_problem(N=1000):
    path = pp.CubicSplinePath(np.array([[0.0, 0.0], [1.0, 0.5], [0.2, 1.5]]))
    return kinematic_problem(path, N, [-1, -1], [1, 1], [-2, -2], [2, 2])


def sliding_box(slip, N=20):
    """The platform slides by s (q[0]); the box (q[2], its x) by (1 + slip) s: its corners slide by slip m."""
    s = np.linspace(0.0, 1.0, N + 1)
    q = np.zeros((N + 1, 8))
    dq = np.zeros_like(q)
    q[:, 0], dq[:, 0] = s, 1.0
    q[:, 2], dq[:, 2] = (1.0 + slip) * s, 1.0 + slip
    return pp.SampledPath(s, q, dq, np.zeros_like(q)), s


def test_reprs_say_what_the_objects_hold():
    prob = readme_problem(200)
    assert repr(prob) == ("<TimeScalingProblem dof=2 intervals=200 s=[0, 1] constraints=[velocity limits, "
                          "acceleration limits] sdot=(0, 0)>")
    res = prob.solve()
    traj = res.trajectory()
    assert repr(traj) == f"<Trajectory duration={res.duration:.6g} s dof=2 grid_points=201>"
    assert repr(res) == f"<Result status=optimal duration={res.duration:.6g}>"
    model = lifter_with_box()
    path, grid = sliding_box(0.0)
    p = pp.TimeScalingProblem(path, grid=grid)
    p.add_contacts(model, box_corners(), cone_edges=4)
    r = p.solve()
    assert re.fullmatch(r"<Trajectory duration=\S+ s dof=8 grid_points=21 robot='lifter\+box' contacts=4>",
                        repr(r.trajectory())), repr(r.trajectory())


def test_progress_bar_has_no_nan_estimate():
    from pathpace.progress import ProgressBar

    out = io.StringIO()
    with ProgressBar(3, "solving", file=out) as bar:
        first = out.getvalue()
        bar.update()
        bar._draw(bar.start + 1.0)
    assert "nan" not in out.getvalue()
    assert first.endswith("0/3 0.0 s elapsed ")  # nothing done: no estimate yet
    assert "1/3 1.0 s elapsed, 2.0 s left" in out.getvalue()
    done = io.StringIO()
    with ProgressBar(1, "x", file=done) as bar:
        bar.update()
    assert done.getvalue().rstrip().endswith("1/1 ") or "left" not in done.getvalue().split("\r")[-1]


def test_time_limit_is_reported_when_spent_before_the_slp():
    prob = readme_problem()
    best = prob.solve()
    assert best.status == pp.Status.OPTIMAL and best.stats["slp_iterations"] == 0
    r = prob.solve(time_limit=1e-9)
    assert r.status == pp.Status.TIME_LIMIT and r.ok
    assert r.duration == best.duration and "reached before the SLP" in r.message
    doc = pp.Result.__doc__
    assert "TIME_LIMIT (``time_limit`` reached" in doc and "True for OPTIMAL, ITERATION_LIMIT and TIME_LIMIT" in doc


def test_sliding_contacts_error_warn_and_say_so_in_the_result():
    model = lifter_with_box()
    path, grid = sliding_box(0.05)  # the box slides 5 cm on the platform
    prob = pp.TimeScalingProblem(path, grid=grid)
    with pytest.raises(pp.InvalidInputError,
                       match=r"^contact \d \(link 'box'\) moves by 0\.05 m \(farthest at s = 1; drift_tolerance 1e-06 m\)"):
        prob.add_contacts(model, box_corners(), cone_edges=4)  # default: drift="auto", 1e-6 m
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        prob.add_contacts(model, box_corners(), cone_edges=4, drift_tolerance=0.06, drift="error")  # within
    prob = pp.TimeScalingProblem(path, grid=grid)
    with pytest.warns(UserWarning, match=r"moves by 0\.05 m"):
        prob.add_contacts(model, box_corners(), cone_edges=4, drift_tolerance=0.01)  # auto: 5x the tolerance
    assert "moving_contacts=1" in repr(prob)
    res = prob.solve()
    assert res.ok and "the path moves its contacts" in res.message
    (d,) = res.contact_drift
    assert d["contact"] in range(4) and d["link"] == "box" and d["s"] == 1.0 and d["constraint"] == ""
    assert d["drift"] == pytest.approx(0.05, rel=1e-12) and d["tolerance"] == 0.01
    assert "moving_contacts=1" in repr(res)
    # Results and problems pickle with it (Dask, solve_many on processes); so does the JSON of a result.
    again = pickle.loads(pickle.dumps(res))
    assert again.contact_drift == res.contact_drift and again.message == res.message
    np.testing.assert_array_equal(again.tau_max, res.tau_max)
    p2 = pickle.loads(pickle.dumps(prob))
    assert p2.solve().contact_drift == res.contact_drift
    from pathpace.io import result_to_dict

    assert result_to_dict(res)["contact_drift"][0]["link"] == "box"
    json.dumps(result_to_dict(res))
    with pytest.raises(pp.InvalidInputError, match=r"^drift_tolerance = -1 must be >= 0 \(metres\)$"):
        prob.add_contacts(model, box_corners(), drift_tolerance=-1.0)


def test_pickles_written_before_contact_drift_still_load():
    prob = readme_problem(50)
    res = prob.solve()
    state = res.__getstate__()
    assert len(state) == 19  # 18 before sddot_points (jerk limits); that layout still loads
    mid = pp.Result.__new__(pp.Result)
    mid.__setstate__(state[:18])
    assert mid.duration == res.duration and mid.sddot_points is None
    old = pp.Result.__new__(pp.Result)
    old.__setstate__(state[:15])
    assert old.duration == res.duration and old.contact_drift == [] and old.tau_max is None
    pstate = prob.__getstate__()
    assert len(pstate) == 6  # 5 before the jerk limits; that layout and the 4-entry one still load
    for n in (4, 5):
        p = pp.TimeScalingProblem.__new__(pp.TimeScalingProblem)
        p.__setstate__(pstate[:n])
        assert p.solve().duration == res.duration
    with pytest.raises(pp.InvalidInputError, match="Result"):
        pp.Result.__new__(pp.Result).__setstate__(state[:16])


def test_problem_file_contacts_check_the_drift(tmp_path):
    from pathpace.problem_file import ProblemFileError, load_problem

    path, grid = sliding_box(0.05)
    q, dq, ddq = path.evaluate(grid)
    lifter = tmp_path / "lifter.urdf"
    import test_contact_objects as tco

    lifter.write_text(tco.LIFTER)

    def write(extra):
        d = {"path": {"samples": {"s": grid.tolist(), "q": q[:, :2].tolist(), "dq": dq[:, :2].tolist(),
                                  "ddq": ddq[:, :2].tolist()}},
             "robot": {"urdf": str(lifter)}, "grid": grid.tolist(),
             "contacts": {"points": [{"link": "platform", "point": [0, 0, 0]}], **extra}}
        f = tmp_path / "p.json"
        f.write_text(json.dumps(d))
        return f

    # The platform's point moves with the platform: 1 m.
    with pytest.raises(ProblemFileError, match=r"key 'contacts': contact 0 \(link 'platform'\) moves by 1 m"):
        load_problem(write({}))
    with pytest.warns(UserWarning, match="moves by 1 m"):
        spec = load_problem(write({"drift": "warn"}))
    assert isinstance(spec.contacts, pp.ContactConstraint)
    with pytest.raises(ProblemFileError, match=r"key 'contacts': drift = 'sometimes', expected"):
        load_problem(write({"drift": "sometimes"}))
    spec = load_problem(write({"drift_tolerance": 2.0}))  # within
    assert spec.problem.constraints[-1] is not None
