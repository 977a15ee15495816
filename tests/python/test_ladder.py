"""examples/humanoid_ladder.py (issue 21, Deliver 3): Talos climbs two rungs on hands and feet.

What holds with room is asserted: the contact data (16 changes, every held point on its rung's top), the
IK path (held points fixed to within the drift tolerance, joints inside their limits), the timing at N = 100
(optimal, ṡ = 0 at each make by the no-impact rule), and what MuJoCo does with it (the example's scene:
contacts with a 2 ms time constant, the feed-forward in the plan's friction margin): the N = 400 timing with
30 N per point executes with room (every criterion at most half its threshold; measured 2026-12-07: slip 0.35,
the rest <= 0.1), while the N = 100 timing and the velocity and acceleration optimum fall, and the uniform
timing at the executed one's T does not execute (a criterion at least twice its threshold). Its run time
against N = 50..800 is plotted and about linear (fig. 5). The IK takes ~10-20 s, each simulation ~5-15 s.
"""

import runpy
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


@pytest.fixture(scope="module")
def ladder():
    ns = runpy.run_path(str(EXAMPLES / "humanoid_ladder.py"))
    robot = ns["talos_sway"].load_talos()
    return {"ns": ns, "robot": robot, "path": ns["climb_path"](robot)}


def test_contact_data_has_16_changes_and_every_hold_on_a_rung_top(ladder):
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    phases = ns["phases"]()
    assert ns["contact_changes"]() == 16 and len(phases) == 17
    # Makes and breaks between consecutive phases, counted from the contact sets themselves.
    keys = [{(c.link, tuple(c.point)) for c in p[2]} for p in phases]
    changes = sum(len(a - b) > 0 for a, b in zip(keys, keys[1:])) + sum(len(b - a) > 0 for a, b in zip(keys, keys[1:]))
    assert changes == 16
    # Each held point, at both ends of each phase, is on the top of a rung (sole points on it, a hand's ball
    # centre BALL above it), within the rung's depth and width.
    boxes = ns["rung_boxes"]()
    for s0, s1, contacts in phases:
        for s in (s0, s1):
            q = path.q(s)
            for c in contacts:
                p = (robot.frame_placement(q, c.link) @ np.append(c.point, 1.0))[:3]
                if c.link in ns["HANDS"]:
                    p = p - [0.0, 0.0, ns["BALL"]]
                on = [b for b in boxes if abs(p[2] - (b["centre"][2] + b["half_size"][2])) < 1e-6
                      and np.all(np.abs(p[:2] - b["centre"][:2]) <= b["half_size"][:2])]
                assert len(on) == 1, (s, c.link, p)
    # The feet climb from rung 1 to rung 3, the hands from rung 6 to the top rung (8).
    q_end = path.q(path.s_end)
    assert np.isclose(robot.frame_placement(q_end, "left_sole_link")[2, 3], 3 * ns["RISE"], atol=1e-6)
    hand_z = robot.frame_placement(q_end, "gripper_left_base_link")[2, 3]
    assert np.isclose(hand_z, ns["RUNGS"] * ns["RISE"] + ns["BALL"], atol=1e-6)


def test_ik_path_keeps_held_points_fixed_and_joints_inside_limits(ladder):
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    for s0, s1, contacts in ns["phases"]():
        drift, _ = pp.ContactConstraint(robot, contacts, cone_edges=8).max_drift(path, np.linspace(s0, s1, 201))
        assert drift < ns["DRIFT"]
    q = np.array([path.q(s) for s in np.linspace(path.s_begin, path.s_end, 1701)])
    lo, hi = robot.position_limits
    assert np.all(q >= lo) and np.all(q <= hi)


def test_timing_at_n100_is_optimal_and_rests_at_every_make(ladder):
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    prob, res, _, _ = ns["timing"](robot, path, 100, **ns["MARGINS"])
    assert res.status == pp.Status.OPTIMAL and prob.grid.size == 101
    makes = [s1 for s0, s1, limb in ns["schedule"]() if limb is not None]  # a swing ends with its limb's make
    breaks = [s0 for s0, s1, limb in ns["schedule"]() if limb is not None]
    for s in makes:
        k = int(np.argmin(np.abs(prob.grid - s)))
        assert prob.grid[k] == s and res.sdot[k] == 0.0  # the no-impact rule
    # Breaks need no rest: the timing moves through each lift-off.
    assert all(res.sdot[int(np.argmin(np.abs(prob.grid - s)))] > 1e-3 for s in breaks)
    rest = [c for c in prob.constraints if isinstance(c, pp.ContactConstraint) and c.rest_at_begin]
    assert len(rest) == 8
    # Torque limits bind somewhere (the wrists' 8 N·m), friction elsewhere: both shape the timing.
    assert any(": torque " in b for b in res.binding) and any(": friction at link" in b for b in res.binding)


def test_mujoco_execution_verdicts_with_room(ladder):
    pytest.importorskip("mujoco")
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    sim = ns["simulator"](robot, path)
    assert sim.contact_surfaces[:8] == ["rung_1"] * 8 and sim.contact_surfaces[8:] == ["rung_6"] * 2
    assert sim.model.geom("pathpace_contact_0").solref[0] == ns["CONTACT_TIMECONST"] == 0.002
    phases = ns["phases"]()
    # The timings that fall are fed forward with the physical cones' centre (the simulator's default): they fall
    # with the narrowed one too (examples/humanoid_ladder.py --sim), whose centre costs 3-6 x as much where the
    # motion asks for forces near the edge of the set (N = 100: 132 s against 43 s; the executed timing: 16 s).
    # Both falls below have room, measured once and not run here (30-45 s each): 10 % slower with the fall
    # thresholds doubled they fall again (bench/README.md, "Issue 21: the room of the simulator's verdicts").
    res100 = ns["timing"](robot, path, 100, **ns["MARGINS"])[1]
    assert sim.run(res100.trajectory(), phases=phases).fell
    run = dict(phases=phases, feedforward_friction_margin=ns["FEEDFORWARD_FRICTION_MARGIN"])
    options = dict(ns["MARGINS"], min_normal_force=ns["SIM_MIN_NORMAL_FORCE"], torque_scale=ns["TORQUE_SCALE"])
    res = ns["timing"](robot, path, ns["SIM_GRID"], **options)[1]
    out = sim.run(res.trajectory(), **run)
    # Executed with room, as the project defines it: every criterion (slip, lift, tilt, tracking, landing) at
    # most half its threshold. Measured: slip 0.35 (1.75 mm, the stance sole at the other foot's lift-off),
    # landing 0.08, lift, tilt and tracking <= 0.05; 0.34-0.43 over N = 300-600, 20-50 N per point, impratio 10
    # and 2.5 ms contacts (3 ms: 0.50), 0.39-0.44 with 1 N·m of torque noise (bench/README.md).
    assert not out.fell and max(out.criterion_ratios.values()) <= 0.5, out.criterion_ratios
    # The contact-unaware optimum (URDF velocity limits, 10 rad/s²) is slower here (T ~ 11.0 s) and falls in
    # the first foot's swing (s ~ 3.5).
    kinematic = ns["talos_sway"].kinematic_timing(robot, path, ns["phase_grid"](ns["SIM_GRID"]))
    assert kinematic.ok and sim.run(kinematic.trajectory(), phases=phases).fell
    # The path at a constant rate in the executed timing's T (fed forward with each phase's contacts, the
    # physical cones): not executed, with room (a criterion at least twice its threshold).
    uniform = ns["talos_sway"].uniform_timing(path, ns["SIM_GRID"], res.duration)
    out = sim.run(uniform, phases=phases)
    assert out.worst_criterion[1] >= 2.0, out.summary()


def test_grip_holds_each_hand_on_the_rung_top_and_the_ridge_behind_it(ladder):
    # The grip option (off by default: it does not execute, bench/README.md): per hand a ball on the rung top
    # and against the ridge behind it (normals +z and +x through its centre, no opposite pair), one sphere.
    pytest.importorskip("mujoco")
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    hand = ns["limb_contacts"](ns["HANDS"][0], grip=True)
    assert [tuple(c.normal) for c in hand] == [(0.0, 0.0, 1.0), (1.0, 0.0, 0.0)]
    assert all(np.allclose(c.point, ns["HAND_POINT"]) for c in hand)
    sim = ns["simulator"](robot, path, grip=True)
    assert sim.contact_surfaces[8:] == ["rung_6", "rung_6_ridge_behind_left", "rung_6", "rung_6_ridge_behind_right"]
    spheres = [sim.model.geom(i).name for i in range(sim.model.ngeom) if sim.model.geom(i).name.startswith("pathpace_contact_")]
    assert len(spheres) == 8 + 2  # one per sole point, one per hand


def test_run_time_against_n_is_plotted_and_about_linear(ladder, tmp_path):
    # The paper's fig. 5: add_contact_phases + solve at N = 50..800, plotted. How its time grows with N is a
    # measurement (bench/README.md), not a test's: the test proves the sweep runs and plots.
    ns, robot, path = ladder["ns"], ladder["robot"], ladder["path"]
    rows = ns["run_time_sweep"](robot, path, repeat=1)
    assert [r["N"] for r in rows] == [50, 100, 200, 400, 800] and all(r["status"] == "OPTIMAL" for r in rows)
    assert all(r["cpu"] > 0.0 for r in rows)
    # A finer grid is a closer approximation of the same optimum: T falls with N.
    assert all(a["T"] > b["T"] for a, b in zip(rows, rows[1:]))
    png = tmp_path / "ladder.png"
    ns["plot_sweep"](rows, png)
    assert png.stat().st_size > 10_000
