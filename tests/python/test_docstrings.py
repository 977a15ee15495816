"""The docstrings of pathpace._core have one source, cpp/bindings/docstrings.txt. The build turns it
into the header the bindings pass to each class and .def; the stubs' docstrings (_core.pyi, checked in)
must be up to date with it, every public class, method and property must have an entry, and each
entry's text must be what help() shows."""

import importlib.util
import inspect
import pathlib

import pytest

import pathpace as pp
from pathpace import _core

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "gen_docstrings.py"

pytestmark = pytest.mark.skipif(not SCRIPT.exists(), reason="needs the source tree")


def generator():
    spec = importlib.util.spec_from_file_location("gen_docstrings", SCRIPT)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_stubs_docstrings_are_up_to_date():
    gen = generator()
    stale = [str(path.relative_to(ROOT)) for path, text in gen.outputs().items() if path.read_text(encoding="utf-8") != text]
    assert stale == [], f"run scripts/gen_docstrings.py: {stale} differ from cpp/bindings/docstrings.txt"


def public_names():
    """Every public class, method, property and function of _core, as "Class.member" (and the dunders
    that are part of the API)."""
    names = []
    for name, obj in vars(_core).items():
        if name.startswith("_") or not (inspect.isclass(obj) or callable(obj)):
            continue
        names.append(name)
        if not inspect.isclass(obj):
            continue
        members = getattr(obj, "__members__", {})  # an enum's values are documented by the enum
        for attr in vars(obj):
            if attr in members or (members and attr in ("name", "value")):
                continue
            if not attr.startswith("_") or attr in ("__call__", "__bool__"):
                names.append(f"{name}.{attr}")
    return names


def runtime_doc(qualname):
    cls, _, member = qualname.partition(".")
    obj = getattr(_core, cls)
    if member:
        raw = vars(obj)[member]
        obj = raw if isinstance(raw, property) else getattr(obj, member)
    return obj.__doc__ or ""


def test_every_public_name_has_its_one_doc_and_help_shows_it():
    docs = generator().documented()
    missing = [n for n in public_names() if n not in docs]
    assert missing == [], f"no entry in cpp/bindings/docstrings.txt for {missing}"
    unknown = [n for n in docs if n.lstrip("_").split(".")[0] not in vars(_core) and n.split(".")[0] not in vars(_core)]
    assert unknown == [], f"entries for names _core does not have: {unknown}"
    wrong = [n for n, text in docs.items() if text not in runtime_doc(n)]
    assert wrong == [], f"__doc__ does not show the entry of {wrong}"


def test_help_shows_the_full_text_after_the_signature():
    doc = pp.TimeScalingProblem.solve.__doc__
    signature, _, text = doc.partition("\n")
    assert signature.startswith("solve(self: pathpace._core.TimeScalingProblem, method: object = 'auto'")
    assert "Never raises for an infeasible problem" in text and "guarantee : {'grid', 'continuous'}" in text
    assert pp.Trajectory.duration.__doc__ == "float: T in s."
    assert "m/s² in the world frame" in pp.RobotModel.gravity_vector.__doc__
    assert pp.InvalidInputError.__doc__.startswith("Bad input (also a ValueError)")
