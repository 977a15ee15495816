"""pytest puts the folder of each conftest.py on sys.path (import mode "prepend"): this one makes the shared
modules of this folder (helpers.py, oracles.py, contact_corpus.py) importable from tests in subfolders
(fuzz/), also when those run alone (`pytest tests/python/fuzz`). It also gives the fixture that runs a test
once per SIMD width of the torque rows."""

import pytest


def _torque_widths():
    import pathpace

    widths, widest = [1], pathpace._core._torque_lanes_supported()
    while widths[-1] * 2 <= widest:
        widths.append(widths[-1] * 2)
    return widths


@pytest.fixture(params=_torque_widths(), ids=lambda w: f"lanes{w}")
def each_torque_width(request, monkeypatch):
    """Runs a test once per SIMD width of the torque rows that this CPU runs (PATHPACE_TORQUE_LANES): a machine
    with AVX-512 takes the 8-lane path, one with AVX2 the 4-lane one, so every width is exercised here."""
    monkeypatch.setenv("PATHPACE_TORQUE_LANES", str(request.param))
    return request.param
