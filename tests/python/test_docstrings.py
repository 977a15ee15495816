"""The docstrings of pathpace._core and of the public C++ headers have one source,
cpp/bindings/docstrings.txt. The build turns it into the header the bindings pass to each class and
.def; the stubs' docstrings (_core.pyi) and the headers' `///` blocks under "// docstrings.txt @@ Name"
markers (both checked in) must be up to date with it, every public class, method and property must have
an entry, each entry's text must be what help() shows, and every declaration a header shares with an
entry must carry its marker."""

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


def test_the_stubs_and_headers_are_up_to_date():
    gen = generator()
    outputs = gen.outputs()
    assert gen.STUB in outputs and len(outputs) > 20  # the stubs and the headers with markers
    stale = [str(path.relative_to(ROOT)) for path, text in outputs.items() if path.read_text(encoding="utf-8") != text]
    assert stale == [], f"run scripts/gen_docstrings.py: {stale} differ from cpp/bindings/docstrings.txt"


def entries():
    gen = generator()
    return gen, gen.parse_entries(gen.SOURCE.read_text(encoding="utf-8"))


def test_a_stale_header_block_is_rewritten():
    gen, source = entries()
    path = ROOT / "cpp/include/pathpace/path.hpp"
    text = path.read_text(encoding="utf-8")
    edited = text.replace("/// @param s (m,): Path parameter", "/// @param s The path parameter")
    assert edited != text
    assert gen.rewrite_header(edited, source)[0] == text  # so --check and the test above see it
    # A hand-written block under a marker is replaced, a trailing ///< comment dropped.
    new, used = gen.rewrite_header("  // docstrings.txt @@ Path.dof\n  /// old\n  int dof() const;  ///< old\n", source)
    assert new == "  // docstrings.txt @@ Path.dof\n  /// Number of coordinates n of q.\n  int dof() const;\n"
    assert used == ["Path.dof"]


def test_a_marker_naming_no_entry_fails():
    gen, source = entries()
    with pytest.raises(SystemExit, match="Path.nope"):
        gen.rewrite_header("// docstrings.txt @@ Path.nope\nint x;\n", source, "x.hpp")
    with pytest.raises(SystemExit, match="only a type"):  # an attribute without a description
        gen.rewrite_header("// docstrings.txt @@ PiecewisePolynomialPath.breakpoints\nint breakpoints();\n", source)


def test_every_declaration_shared_with_an_entry_has_its_marker(monkeypatch):
    gen = generator()
    assert gen.missing_markers() == [], "add '// docstrings.txt @@ Name' above these declarations, or list " \
        "them on a '#! python-only' line of cpp/bindings/docstrings.txt"
    # The check finds them: without any marker, the obvious counterparts are all missing.
    monkeypatch.setattr(gen, "header_outputs", lambda _: ({}, []))
    missing = gen.missing_markers()
    assert {"Path", "Path.q", "Path.dof", "TimeScalingProblem.solve", "TimeScalingProblem.__init__", "auto_grid",
            "Result.sdot", "FeasibleSet.contains"} <= set(missing)
    assert "RobotModel.from_urdf_file" not in missing  # python-only: the C++ doc is from_urdf's
    assert "PiecewisePolynomialPath.breakpoints" not in missing  # a type alone: nothing for C++


def test_the_headers_read_as_doxygen_and_each_side_keeps_its_own_sections():
    headers = {p.name: p.read_text(encoding="utf-8") for p in (ROOT / "cpp/include/pathpace").rglob("*.hpp")}
    text = "\n".join(headers.values())
    assert "/// @brief p(s).\n  ///\n  /// @param s (m,): Path parameter, clamped to [s_begin, s_end].\n" \
           "  /// @return (len(s), dof()): row i is p(s[i]).\n" in headers["path.hpp"]
    assert "/// @throws InvalidInput Unreadable file, invalid URDF, unknown locked joint." in headers["robot_model.hpp"]
    # numpy headings and Python type lines stay out of the C++ docs
    assert "/// Parameters" not in text and "/// ----" not in text and "array_like" not in text
    # a C++ section only in the headers, a Python section only in help() and the stubs
    assert "Python sees it as pathpace.InvalidInputError" in headers["errors.hpp"]
    assert "Python sees it as" not in pp.InvalidInputError.__doc__ and "Also a ValueError." in pp.InvalidInputError.__doc__
    assert "Also a ValueError." not in headers["errors.hpp"]
    assert "The GIL is released meanwhile." in pp.TimeScalingProblem.solve.__doc__
    assert "GIL" not in headers["time_scaling_problem.hpp"]
    docs = generator().documented()
    assert not [n for n, t in docs.items() if "@param" in t or "@return" in t or "\nC++\n---" in t]
    # a class's parameters go to its constructors, only those each declares
    spline = headers["cubic_spline_path.hpp"]
    first, second = spline.split("// docstrings.txt @@ CubicSplinePath.__init__")[1:3]
    assert "@param spacing" in first and "@param knots" not in first and "@param s_begin,s_end" in first
    assert "@param knots K strictly increasing" in second and "@param spacing" not in second


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
    assert pp.InvalidInputError.__doc__.startswith("Bad input: the message names") and "Also a ValueError." in pp.InvalidInputError.__doc__
