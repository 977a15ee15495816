"""Problem files with contact phases (contacts.phases): the same problem as add_contact_phases, and every
new key's errors named."""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from pathpace.problem_file import ProblemFileError, load_problem

sys.path.insert(0, str(Path(__file__).parent))
from test_contact import rod_path  # noqa: E402

DATA = Path(__file__).resolve().parents[1] / "data"
ROD = {"link": "rod", "point": [0, 0, -1], "normal": [0, 0, 1], "friction": 0.5}


def rod_file(tmp_path, contacts, name="rod.json"):
    th = np.linspace(-0.15, 0.15, 61)
    path = rod_path(th)
    q, dq, ddq = path.evaluate(th)
    f = tmp_path / name
    f.write_text(json.dumps({
        "robot": {"urdf": str(DATA / "rod.urdf")},
        "path": {"samples": {"s": th.tolist(), "q": q.tolist(), "dq": dq.tolist(), "ddq": ddq.tolist()}},
        "grid": th.tolist(), "contacts": contacts}))
    return f, path, th


def test_contact_phases_in_a_file_are_add_contact_phases(tmp_path):
    contacts = {"cone_edges": 4, "phases": [{"s": [-0.15, 0.0], "points": [ROD]},
                                            {"s": [0.0, 0.15], "points": [ROD], "friction_margin": 0.5}]}
    f, path, th = rod_file(tmp_path, contacts)
    spec = load_problem(f)
    got = spec.solve()
    robot = pp.RobotModel.from_urdf(DATA / "rod.urdf")
    rod = [pp.Contact("rod", point=[0, 0, -1], normal=[0, 0, 1], friction=0.5)]
    prob = pp.TimeScalingProblem(path, grid=th)
    prob.add_contact_phases(robot, [(-0.15, 0.0, rod), (0.0, 0.15, rod, {"friction_margin": 0.5})], cone_edges=4)
    expected = prob.solve()
    assert expected.ok and got.ok
    # Built through the file (its own order of constraints): the same optimum far below the certified
    # tolerance (1e-7), not to the last bit (measured 2.5e-11).
    assert got.duration == pytest.approx(expected.duration, rel=1e-9)
    assert len(spec.contact_phases) == 2 and spec.contact_phases[1][3] == {"friction_margin": 0.5}
    assert len(got.trajectory().contact_phases) == 2
    # The friction margin of the second phase binds: slower than without it.
    plain = {"cone_edges": 4, "phases": [{"s": [-0.15, 0.0], "points": [ROD]}, {"s": [0.0, 0.15], "points": [ROD]}]}
    assert load_problem(rod_file(tmp_path, plain, "plain.json")[0]).solve().duration < got.duration


@pytest.mark.parametrize("contacts, match", [
    ({"points": [ROD], "phases": []}, "either 'points'"),
    ({}, "either 'points'"),
    ({"phases": []}, r"contacts.phases'.*non-empty list of phases"),
    ({"phases": [{"points": [ROD]}]}, r"contacts.phases\[0\].s'.*missing"),
    ({"phases": [{"s": [0.0], "points": [ROD]}]}, r"contacts.phases\[0\].s"),
    ({"phases": [{"s": [-0.15, 0.15], "points": []}]}, r"contacts.phases\[0\].points'.*non-empty list"),
    ({"phases": [{"s": [-0.15, 0.15], "points": [{"point": [0, 0, 0]}]}]}, r"contacts.phases\[0\].points\[0\].link"),
    ({"phases": [{"s": [-0.15, 0.15], "points": [ROD], "cone_edges": 4}]}, r"is one for all phases"),
    ({"phases": [{"s": [-0.15, 0.15], "points": [ROD], "mu": 1}]}, r"contacts.phases\[0\]"),
    ({"points": [ROD], "drift": "never"}, r"drift"),
])
def test_every_phase_key_error_is_named(tmp_path, contacts, match):
    f = rod_file(tmp_path, contacts)[0]
    with pytest.raises(ProblemFileError, match=match):
        load_problem(f)


def test_the_new_contact_options_reach_the_constraint(tmp_path):
    # The rod weighs 9.8 N: each point pushing 10 N beyond its cone (cone_offset) is impossible.
    f = rod_file(tmp_path, {"points": [ROD], "cone_edges": 4, "cone_offset": 10.0})[0]
    assert load_problem(f).solve().status == pp.Status.INFEASIBLE
    f = rod_file(tmp_path, {"points": [ROD], "cone_edges": 4, "cone_offset": 5.0}, "half.json")[0]
    assert load_problem(f).solve().status == pp.Status.OPTIMAL


def test_contact_phases_of_a_file_drive_find_executable_margin(tmp_path):
    # End to end: the phases a file gives (ProblemSpec.contact_phases) are find_executable_margin's phases;
    # at the search's lower bound (0 N, no margin) its problem is the file's, and each run gets the phases.
    from pathpace.sim import find_executable_margin
    contacts = {"cone_edges": 4, "phases": [{"s": [-0.15, 0.0], "points": [ROD]}, {"s": [0.0, 0.15], "points": [ROD]}]}
    f, path, th = rod_file(tmp_path, contacts)
    spec = load_problem(f)

    class Verdict:
        fell, executed, worst_criterion = False, True, ("stand-in", 0.0)

        def __init__(self, duration):
            self.duration = duration

        def summary(self):
            return "stand-in"

    class StandIn:
        robot, contacts, options = spec.robot, [], []

        def run(self, traj, **options):
            self.options.append(options)
            return Verdict(traj.duration)

    sim = StandIn()
    out = find_executable_margin(sim, path, phases=spec.contact_phases, grid=th, cone_edges=4, lower=0.0, upper=1.0)
    assert out.margin == 0.0 and out.trials[0].status == "OPTIMAL"
    assert out.trials[0].duration == pytest.approx(spec.solve().duration, rel=1e-9)
    assert sim.options and all(o == {"phases": spec.contact_phases} for o in sim.options)


def test_project_on_demand_in_a_file_reaches_the_constraint(tmp_path):
    """contacts.project_on_demand: the solve refines its polygons (stats['projection_rounds']) and gives the full
    projection's T; a value that is not a bool is named."""
    full = load_problem(rod_file(tmp_path, {"points": [ROD], "cone_edges": 4})[0])
    lazy = load_problem(rod_file(tmp_path, {"points": [ROD], "cone_edges": 4, "project_on_demand": True}, "od.json")[0])
    a, b = full.solve(), lazy.solve()
    assert a.status == b.status == pp.Status.OPTIMAL
    assert b.duration == pytest.approx(a.duration, rel=1e-9)
    assert b.stats["projection_rounds"] >= 1 and a.stats["projection_rounds"] == 0
    with pytest.raises(ProblemFileError, match="project_on_demand"):
        load_problem(rod_file(tmp_path, {"points": [ROD], "cone_edges": 4, "project_on_demand": "yes"}, "bad.json")[0])
