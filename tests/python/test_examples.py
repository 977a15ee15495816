"""Every example runs and says what it should."""

import runpy
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_demo_solves_the_panda_path_and_reports_the_locked_joint(capsys):
    runpy.run_path(str(EXAMPLES / "demo.py"), run_name="__main__")
    out = capsys.readouterr().out
    assert "N = 1000: OPTIMAL" in out
    assert "INFEASIBLE" in out and "binding: velocity joint 3" in out
    assert (EXAMPLES / "output" / "panda_trajectory.csv").is_file()
