"""Contracts of code that several callers share: the SolverStats table behind Result.stats and Result's pickle
state, the constraint-evaluation timing of TimeScalingProblem (set_joint_names re-evaluates rows), and the
limit curves that pathpace.plot (matplotlib) and pathpace.report (plotly) both draw."""

import os
import pickle
import sys
import types
from pathlib import Path

import numpy as np
import pytest

import pathpace as pp
from helpers import two_joint_problem
from pathpace import plot

# Result's pickle state keeps SolverStats as a tuple of these 40 entries, in this order (the format pickles
# written so far have): a new field may only be appended, with a new entry count. The first pickles had
# the first 18, the next ones the first 23, then 26 (before the jerk statistics), then 29 (before the
# projection's ranging, dense simplex and pivot counts), then 33 (before the dense simplex's fallbacks by cause),
# then 38 (before the audit's GLPK slice LPs), then 39 (before the projection's refinement rounds).
STATS_STATE = ("slp_iterations", "lp_solves", "greatest_element", "gap", "average_halfplanes", "time_constraints",
               "time_feasible_sets", "time_reachability", "time_slp", "audit_rounds", "audit_cuts", "audit_worst",
               "windows", "window_points", "time_projection", "projection_lp_solves", "inexact_points", "newton_steps",
               "projection_lps_initial", "projection_lps_vertex", "projection_lps_certificate",
               "projection_lps_cap_growth", "projection_lps_cold_retry", "audit_lps", "audit_projections",
               "audit_reused", "jerk_iterations", "jerk_linearised_gap", "second_order_duration",
               "projection_ranged_certificates", "projection_lps_dense", "projection_lps_dense_fallback",
               "projection_pivots", "projection_fallback_cap", "projection_fallback_small_pivot",
               "projection_fallback_unbounded", "projection_fallback_singular", "projection_fallback_certificate",
               "audit_lps_glpk", "projection_rounds")


def test_set_joint_names_keeps_the_time_of_the_rows_it_relabels():
    """Limits added before the names get the names' labels (their rows are kept: they do not depend on the
    names); their rows' time is still what stats['time_constraints'] sums. It was left at 0 when the rows
    were replaced by untimed ones."""
    prob = two_joint_problem(N=50)
    assert prob.solve().stats["time_constraints"] > 0.0
    prob.set_joint_names(["shoulder", "elbow"])
    labels = [lab for k in (0, 25) for lab in prob.feasible_set(k).labels]
    assert any("shoulder" in lab for lab in labels) and not any("joint 0" in lab for lab in labels)
    assert prob.solve().stats["time_constraints"] > 0.0


def test_result_stats_are_the_40_fields_and_a_pickle_round_trip_keeps_them():
    res = two_joint_problem(N=50).solve()
    assert set(res.stats) == set(STATS_STATE)
    back = pickle.loads(pickle.dumps(res))
    assert back.stats == res.stats and back.duration == res.duration


def test_result_reads_a_stats_state_in_the_40_39_38_33_29_26_23_and_18_entry_layouts():
    """A state written in the layout pickles have (each value distinct, of its field's type) is read into
    the fields of that name; one in the earlier 18-, 23-, 26-, 29-, 33-, 38- and 39-entry layouts too, the fields they lack at
    0; a state of another length is refused, named."""
    res = two_joint_problem(N=50).solve()
    state = list(res.__getstate__())
    assert state[8] == tuple(res.stats[name] for name in STATS_STATE)
    values = []
    for i, name in enumerate(STATS_STATE):
        kind = type(res.stats[name])
        values.append(True if kind is bool else (i + 1 if kind is int else i + 0.25))
    state[8] = tuple(values)
    r = pp.Result.__new__(pp.Result)
    r.__setstate__(tuple(state))
    assert r.stats == dict(zip(STATS_STATE, values))
    assert all(type(r.stats[n]) is type(v) for n, v in zip(STATS_STATE, values))
    for first in (18, 23, 26, 29, 33, 38, 39):
        state[8] = tuple(values[:first])
        r = pp.Result.__new__(pp.Result)
        r.__setstate__(tuple(state))
        assert r.stats == dict(zip(STATS_STATE, values[:first] + [0] * (40 - first)))
    state[8] = tuple(values[:-3])  # 37: no layout's length
    with pytest.raises(pp.InvalidInputError, match=r"Result stats pickle state has 37 entries, expected 40"):
        pp.Result.__new__(pp.Result).__setstate__(tuple(state))


def test_limit_ratios_divide_by_the_larger_limit_and_leave_out_joints_without_one():
    values = np.array([[1.0, 5.0, 3.0, -2.0], [-4.0, 1.0, 0.0, 1.0]])
    lo, hi = np.array([-2.0, -np.inf, 0.0, -8.0]), np.array([4.0, np.inf, 0.0, 2.0])
    ratios = plot.limit_ratios(values, lo, hi, ["a", "b", "c", "d"])
    assert [name for name, _ in ratios] == ["a", "d"]
    np.testing.assert_array_equal(ratios[0][1], [0.25, -1.0])
    np.testing.assert_array_equal(ratios[1][1], [-0.25, 0.125])


def test_matplotlib_and_plotly_draw_the_same_velocity_curves():
    matplotlib = pytest.importorskip("matplotlib")
    pytest.importorskip("plotly")
    matplotlib.use("Agg")
    from pathpace import report

    prob = two_joint_problem(50, vmin=(-1.0, -np.inf), vmax=(1.0, np.inf))  # joint b unlimited: no curve
    res = prob.solve()
    d = plot.velocities_data(res, [-1.0, -np.inf], [1.0, np.inf], ["a", "b"])
    expected = plot.limit_ratios(d["qd"], d["vmin"], d["vmax"], d["joint_names"])
    assert [name for name, _ in expected] == ["a"]
    np.testing.assert_allclose(expected[0][1], d["qd"][:, 0])

    ax = plot.velocities(res, [-1.0, -np.inf], [1.0, np.inf], joint_names=["a", "b"])
    peak = 100 * np.max(np.abs(expected[0][1]))
    drawn = [line for line in ax.get_lines() if line.get_label() == f"a (peak {peak:.0f} %)"]
    assert len(drawn) == 1 and len(ax.get_lines()) == 3  # the curve and the two limits
    np.testing.assert_array_equal(drawn[0].get_ydata(), expected[0][1])

    spec = types.SimpleNamespace(problem=prob, name="two joints", joint_names=["a", "b"],
                                 velocity_limits=([-1.0, -np.inf], [1.0, np.inf]))
    figs = dict(report.figures(spec, res))
    traces = figs["Joint velocities against the limits"].data
    # The page samples fewer points and stores them as float32 (report._SAMPLES, report._f32).
    d = plot.velocities_data(res, [-1.0, -np.inf], [1.0, np.inf], ["a", "b"], samples=report._SAMPLES)
    expected = plot.limit_ratios(d["qd"], d["vmin"], d["vmax"], d["joint_names"])
    assert [t.name for t in traces] == [f"a (peak {100 * np.max(np.abs(expected[0][1])):.0f} %)"]
    np.testing.assert_array_equal(np.asarray(traces[0].y), expected[0][1].astype(np.float32))
    np.testing.assert_array_equal(np.asarray(traces[0].x), d["t"].astype(np.float32))


def test_a_generated_bench_section_replaces_its_block_and_never_repeats_its_heading(tmp_path):
    """bench/common.write_generated_section (the sweep's and the contact bench's tables in bench/README.md):
    between its markers it replaces the block and keeps the rest; without the markers it goes right under
    its heading when the README has that line (it used to append the heading a second time), else under a
    new heading at the end."""
    environ = dict(os.environ)  # common pins BLAS threads in os.environ on import
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
    try:
        import common
    finally:
        sys.path.pop(0)
        os.environ.clear()
        os.environ.update(environ)
    begin, end, heading = "<!-- BEGIN x -->", "<!-- END x -->", "## Table x"
    readme = tmp_path / "README.md"

    def write(text, section):
        readme.write_text(text)
        common.write_generated_section(section, begin, end, heading, path=readme)
        return readme.read_text()

    new = f"{begin}\nnew table\n{end}"
    assert write(f"# B\n\n{heading}\n\n{begin}\nold\n{end}\n\nReading it: kept.\n", new) == \
        f"# B\n\n{heading}\n\n{new}\n\nReading it: kept.\n"
    # The markers removed by hand: under the existing heading, once, with what follows it kept.
    out = write(f"# B\n\n{heading}\n\nReading it: kept.\n\n## Next\n", new)
    assert out.count(heading) == 1 and out.index(heading) < out.index(new) < out.index("Reading it") < out.index("## Next")
    # A heading that only starts like ours is not ours; no heading at all: appended under a new one.
    for text in (f"# B\n\n{heading} (old)\n", "# B\n"):
        out = write(text, new)
        assert out.endswith(f"\n\n{heading}\n\n{new}\n") and out.startswith(text.rstrip("\n"))
