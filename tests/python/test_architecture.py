"""The shape of cpp/src that docs/architecture.md describes, checked so that it stays true (issue 26).

- One layer per folder, dependencies one way: a file of cpp/src/<layer>/ includes public headers and the
  folders of earlier layers only.
- Nothing outside cpp/src/constraints asks a constraint for its concrete type: constraints tell the problem
  what it needs through Constraint's virtual hooks.
- Nothing outside cpp/src/paths asks a path for its concrete type: Path::polynomial() gives the polynomial
  pieces of a path that has them (issue 22).
- No function over ~150 lines and no file over ~700, unless the file says why: a comment containing
  "long file:" (the file) or "long function:" on the line before a function's definition.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "cpp" / "src"
LAYERS = ["base", "paths", "geometry", "lp", "robot", "constraints", "solve", "result", "problem"]
CONSTRAINT_TYPES = ("Constraint", "VelocityLimits", "AccelerationLimits", "LinearConstraint", "TorqueLimits",
                    "ContactConstraint")
PATH_TYPES = ("Path", "PiecewisePolynomialPath", "CubicSplinePath", "SampledPath", "FunctionPath", "SubPath")
MAX_FUNCTION, MAX_FILE = 150, 700
CAST = re.compile(r"dynamic(?:_pointer)?_cast\s*<\s*(?:const\s+)?(?:pathpace::)?(?:detail::)?(\w+)|typeid\s*\(")


def sources():
    return sorted(p for p in SRC.rglob("*") if p.suffix in (".cpp", ".hpp"))


def test_every_source_is_in_a_layer():
    stray = [str(p.relative_to(SRC)) for p in sources() if p.parent.parent != SRC or p.parent.name not in LAYERS]
    assert not stray, f"files outside the layer folders {LAYERS}: {stray}"


def test_dependencies_go_one_way():
    wrong = []
    for p in sources():
        rank = LAYERS.index(p.parent.name)
        for line_no, line in enumerate(p.read_text().splitlines(), 1):
            m = re.match(r'\s*#\s*include\s+"([a-z_]+)/', line)
            if m and m.group(1) != "pathpace":
                if m.group(1) not in LAYERS:
                    wrong.append(f"{p.relative_to(SRC)}:{line_no} includes unknown folder {m.group(1)}/")
                elif LAYERS.index(m.group(1)) > rank:
                    wrong.append(f"{p.relative_to(SRC)}:{line_no} ({p.parent.name}) includes {m.group(1)}/ (a later layer)")
    assert not wrong, "\n".join(wrong)


def casts_outside(folder: str, types: tuple[str, ...]) -> list[str]:
    """Lines outside cpp/src/<folder> that cast to one of `types` (or use typeid)."""
    found = []
    for p in list(sources()) + sorted((ROOT / "cpp" / "bindings").glob("*.[ch]pp")):
        if p.parent.name == folder and p.parent.parent == SRC:
            continue
        for line_no, line in enumerate(p.read_text().splitlines(), 1):
            if "get_type_info(typeid(" in line:
                continue  # pybind11's own lookup of a trampoline's Python object, not a dispatch on the type
            for m in CAST.finditer(line):
                if m.group(1) is None or m.group(1) in types:
                    found.append(f"{p.relative_to(ROOT)}:{line_no}: {line.strip()}")
    return found


def test_no_constraint_type_asked_outside_the_constraints():
    found = casts_outside("constraints", CONSTRAINT_TYPES)
    assert not found, "\n".join(found)


def test_no_path_type_asked_outside_the_paths():
    found = casts_outside("paths", PATH_TYPES)
    assert not found, "\n".join(found)


def test_cast_pattern_sees_path_casts():
    line = "if (auto pp = std::dynamic_pointer_cast<const PiecewisePolynomialPath>(path_)) x();"
    assert [m.group(1) for m in CAST.finditer(line)] == ["PiecewisePolynomialPath"]


def function_lengths(text: str):
    """(name, first line, length) of each function defined at namespace scope: a line at column 0 that
    opens a body ending in '{', closed by the next '}' at column 0. Good enough for this code's style."""
    lines = text.splitlines()
    out, i = [], 0
    head = re.compile(r"^[A-Za-z_][\w:<>,\s\*&~]*?\b([\w:~]+)\s*\(")
    while i < len(lines):
        line = lines[i]
        m = head.match(line)
        if m and not line.startswith(("namespace", "struct", "class", "enum", "union", "template", "#", "using")):
            j = i
            while j < len(lines) and not lines[j].rstrip().endswith("{") and not lines[j].rstrip().endswith(";"):
                j += 1
            if j < len(lines) and lines[j].rstrip().endswith("{"):
                k = j + 1
                while k < len(lines) and not lines[k].startswith("}"):
                    k += 1
                exempt = i > 0 and "long function:" in lines[i - 1]
                out.append((m.group(1), i + 1, k - i + 1, exempt))
                i = k + 1
                continue
        i += 1
    return out


def test_function_lengths_detected():
    text = "int f(int a,\n      int b) {\n  return a;\n}\n\nvoid g() {\n  x();\n  y();\n}\n"
    assert [(n, s, l) for n, s, l, _ in function_lengths(text)] == [("f", 1, 4), ("g", 6, 4)]


@pytest.mark.parametrize("path", sources(), ids=lambda p: str(p.relative_to(SRC)))
def test_no_long_functions_or_files(path):
    text = path.read_text()
    n = text.count("\n")
    assert n <= MAX_FILE or "long file:" in text, f"{n} lines (> {MAX_FILE}) and no 'long file:' comment saying why"
    long = [f"{name} at line {start}: {length} lines" for name, start, length, exempt in function_lengths(text)
            if length > MAX_FUNCTION and not exempt]
    assert not long, f"functions over {MAX_FUNCTION} lines without a 'long function:' comment: {long}"
