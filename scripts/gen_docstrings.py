#!/usr/bin/env python3
"""Generates pathpace's API documentation from its one source, cpp/bindings/docstrings.txt.

Outputs:
  docstrings.hpp                one `constexpr const char*` per entry, passed to each py::class_ / .def;
                                written by the build (cpp/bindings/CMakeLists.txt: --header PATH), never
                                checked in, so it cannot be stale
  python/pathpace/_core.pyi     the stubs' docstrings, rewritten in place (signatures stay hand-written)
  cpp/include/pathpace/**.hpp   the `///` block under each marker line "// docstrings.txt @@ Name", in
                                Doxygen form (@brief, @param, @return, @throws)
The stubs and headers are checked in (the C++ library builds without Python);
tests/python/test_docstrings.py fails when any of them is stale.

The source is a list of entries, each headed by a line "@@ Class", "@@ Class.member" or "@@ function".
A class's "Attributes" section also documents its properties: each "name : type" item there becomes
the docstring of property Class.name ("type: description"), so a property is described once, in its
class, and has its own __doc__ too. An explicit "@@ Class.name" entry for such a property is an error.

For C++, a class's Parameters go to the marker "Class.__init__" (above a constructor; only the
parameters that constructor declares), its Attributes to the marker "Class.name" above each member, and
a "C++" section appears only in the headers (its "@param x ..." / "@return ..." / "@throws X ..."
lines replace the generated ones of the same name, its other lines are description). A "Python" section
appears only in help() and the stubs (its heading dropped). "#! python-only A B" lists entries that have
no C++ counterpart although a header declares the same name.

Usage: scripts/gen_docstrings.py [--check]      rewrite the stubs and headers (--check: exit 1 if stale)
       scripts/gen_docstrings.py --header PATH    write the bindings' header (only if its text changes)
"""

from __future__ import annotations

import ast
import re
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCE = ROOT / "cpp/bindings/docstrings.txt"
STUB = ROOT / "python/pathpace/_core.pyi"
HEADERS = ROOT / "cpp/include/pathpace"
MARKER = re.compile(r"(\s*)// docstrings\.txt @@ ([A-Za-z_][\w.]*(?: [A-Za-z_][\w.]*)*)\s*")
CPP, PYTHON = "C++", "Python"  # sections for one side only
EXCEPTIONS = {"InvalidInputError": "InvalidInput", "Error": "Error"}  # Python name -> C++ name


def parse_entries(text: str) -> dict[str, str]:
    """{name: text} in source order; lines before the first entry and lines starting with '#!' are comments."""
    entries: dict[str, str] = {}
    name = None
    body: list[str] = []
    for line in text.splitlines():
        if line.startswith("#!"):
            continue
        m = re.fullmatch(r"@@ ([A-Za-z_][\w.]*)\s*", line)
        if m:
            if name is not None:
                entries[name] = "\n".join(body).strip("\n")
            name = m.group(1)
            if name in entries:
                raise SystemExit(f"{SOURCE.name}: '{name}' is documented twice")
            body = []
        elif name is not None:
            body.append(line.rstrip())
    if name is not None:
        entries[name] = "\n".join(body).strip("\n")
    for k, v in entries.items():
        if not v:
            raise SystemExit(f"{SOURCE.name}: '{k}' has no text")
    return entries


def section(doc: str, title: str) -> list[str]:
    """The lines of a numpy-style section ("Title" over a dashed line) up to the next section."""
    lines = doc.splitlines()
    for i in range(len(lines) - 1):
        if lines[i] == title and re.fullmatch(r"-{3,}", lines[i + 1]):
            out = []
            for j in range(i + 2, len(lines)):
                if j + 1 < len(lines) and lines[j] and re.fullmatch(r"-{3,}", lines[j + 1]):
                    break
                out.append(lines[j])
            return out
    return []


NAMES = r"[A-Za-z_]\w*(?:, ?[A-Za-z_]\w*)*"


def items(lines: list[str], returns: bool = False) -> tuple[list[tuple[str, str, str]], list[str]]:
    """The (names, type, description) items of a numpy section, and the prose lines after them. In
    Returns, each unindented line is a type (names empty); elsewhere "name, name : type" (names may
    continue on the next line after a trailing comma)."""
    out: list[list] = []  # [names, type, description lines, names continue]
    for i, line in enumerate(lines):
        if not line or line.startswith(" "):
            if out:
                out[-1][2].append(line)
            continue
        if returns:
            out.append(["", line, [], False])
            continue
        m = re.fullmatch(rf"({NAMES})(,?)(?: :(?: (.*))?)?", line)
        if not m:
            return [(n, t, textwrap.dedent("\n".join(d)).strip()) for n, t, d, _ in out], lines[i:]
        if out and out[-1][3] and not out[-1][2]:
            out[-1] = [f"{out[-1][0]}, {m.group(1)}", m.group(3) or "", [], bool(m.group(2))]
        else:
            out.append([m.group(1), m.group(3) or "", [], bool(m.group(2))])
    return [(n, t, textwrap.dedent("\n".join(d)).strip()) for n, t, d, _ in out], []


def attribute_items(cls: str, doc: str) -> list[tuple[str, str, str]]:
    found, _ = items(section(doc, "Attributes"))
    for names, typ, desc in found:
        if not typ and not desc:
            raise SystemExit(f"{SOURCE.name}: {cls}'s attribute {names} has neither a type nor a description")
    return found


def attribute_docs(cls: str, doc: str) -> dict[str, str]:
    """Class.name -> "type: description" for each item of the class's Attributes section."""
    out: dict[str, str] = {}
    for names, typ, desc in attribute_items(cls, doc):
        full = f"{typ.strip()}: {desc}" if desc else typ.strip()
        for n in names.split(","):
            out[f"{cls}.{n.strip()}"] = full
    return out


def headings(lines: list[str]) -> list[int]:
    """Indices of the section headings (a line over a dashed line)."""
    return [i for i in range(len(lines) - 1)
            if lines[i] and not lines[i].startswith(" ") and re.fullmatch(r"-{3,}", lines[i + 1])]


def one_side(doc: str, keep: str, drop: str) -> str:
    """The entry without its `drop` sections, and with the headings of its `keep` sections removed."""
    lines = doc.splitlines()
    marks = headings(lines) + [len(lines)]
    out: list[str] = []
    out += lines[: marks[0]]
    for start, end in zip(marks, marks[1:]):
        if lines[start] == drop:
            continue
        out += lines[start + 2: end] if lines[start] == keep else lines[start:end]
    return re.sub(r"\n{3,}", "\n\n", "\n".join(out)).strip("\n")


def python_text(doc: str) -> str:
    return one_side(doc, PYTHON, CPP)


def all_docs(entries: dict[str, str]) -> dict[str, str]:
    docs = {k: python_text(v) for k, v in entries.items()}
    for name, text in entries.items():
        if "." in name:
            continue
        for key, value in attribute_docs(name, python_text(text)).items():
            if key in entries:
                raise SystemExit(f"{SOURCE.name}: '{key}' is in {name}'s Attributes and has its own entry")
            docs[key] = value
    return docs


def identifier(name: str) -> str:
    """Trajectory.__call__ -> Trajectory_call_ (C++ reserves names with a double underscore)."""
    parts = []
    for p in name.split("."):
        parts.append(p.strip("_") + "_" if p.startswith("__") else p.lstrip("_") if p.startswith("_") else p)
    return "_".join(parts)


def header(docs: dict[str, str]) -> str:
    out = [
        "// Generated by scripts/gen_docstrings.py from cpp/bindings/docstrings.txt (by the build): edit that.",
        "#pragma once",
        "",
        "namespace pathpace::python::doc {",
        "",
    ]
    seen = set()
    for name, text in docs.items():
        ident = identifier(name)
        if ident in seen:
            raise SystemExit(f"two entries map to the C++ name {ident}")
        seen.add(ident)
        if ")doc\"" in text:
            raise SystemExit(f"'{name}' contains the raw-string delimiter )doc\"")
        out.append(f'constexpr const char* {ident} = R"doc({text})doc";')
    out += ["", "}  // namespace pathpace::python::doc", ""]
    return "\n".join(out)


def render_docstring(text: str, indent: str) -> list[str]:
    if '"""' in text:
        raise SystemExit(f'a docstring contains """: {text[:40]}')
    prefix = "r" if "\\" in text else ""
    lines = text.splitlines()
    if len(lines) == 1:
        return [f'{indent}{prefix}"""{lines[0]}"""']
    out = [f'{indent}{prefix}"""{lines[0]}']
    out += [f"{indent}{line}" if line else "" for line in lines[1:]]
    out.append(f'{indent}"""')
    return out


def stub(source: str, docs: dict[str, str]) -> str:
    """The stub with each class's and member's docstring replaced by docs (removed where it has none)."""
    tree = ast.parse(source)
    lines = source.splitlines()
    edits = []  # (line index, action...) applied bottom-up

    def visit(node, qualname: str, indent: str):
        doc = docs.get(qualname)
        body = node.body
        first = body[0]
        has_doc = isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str)
        inner = indent + "    "
        if has_doc:
            new = render_docstring(doc, inner) if doc else []
            if not new and len(body) == 1:
                new = [inner + "..."]
            edits.append((first.lineno - 1, first.end_lineno, new))
        elif doc:
            if len(body) == 1 and isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) \
                    and first.value.value is Ellipsis and first.lineno == node.body[0].lineno \
                    and lines[first.lineno - 1].rstrip().endswith("..."):
                line = lines[first.lineno - 1]
                head = line[: first.col_offset].rstrip()
                if head.endswith(":"):  # "def f(...) -> T: ..." on one line
                    edits.append((first.lineno - 1, first.lineno, [head] + render_docstring(doc, inner)))
                    return
            start = min([first.lineno] + [d.lineno for d in getattr(first, "decorator_list", [])])
            edits.append((start - 1, start - 1, render_docstring(doc, inner)))
        if isinstance(node, ast.ClassDef):
            for child in body:
                if isinstance(child, (ast.FunctionDef, ast.ClassDef)):
                    visit(child, f"{qualname}.{child.name}", inner)

    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            visit(node, node.name, "")
    for start, end, new in sorted(edits, key=lambda e: e[0], reverse=True):
        lines[start:end] = new
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------------ C++ headers

def rst_to_doxygen(text: str) -> str:
    """rst's ``code`` as Markdown's `code`, and Python's exception names as C++'s."""
    text = text.replace("``", "`")
    return re.sub(r"(?<!\.)\b(" + "|".join(EXCEPTIONS) + r")\b", lambda m: EXCEPTIONS[m.group(1)], text)


def paragraphs(lines: list[str]) -> list[str]:
    """The lines with runs of blank lines made one, none at either end."""
    return re.sub(r"\n{3,}", "\n\n", "\n".join(lines)).strip("\n").splitlines()


def command(cmd: str, desc: str) -> list[str]:
    first, *rest = desc.splitlines()
    return [f"{cmd} {first}"] + ["  " + line if line else "" for line in rest]


def cpp_commands(lines: list[str]) -> tuple[dict[str, list[str]], list[str]]:
    """A C++ section: its "@param x ..." / "@return ..." / "@throws X ..." commands (keyed "@param x",
    continuation lines attached) and its other lines."""
    commands: dict[str, list[str]] = {}
    prose: list[str] = []
    key = None
    for line in lines:
        m = re.match(r"(@param \S+|@return|@throws \S+)\b", line)
        if m:
            key = m.group(1)
            commands[key] = [line]
        elif key and line.strip():
            commands[key].append("  " + line.strip())
        else:
            key = None
            prose.append(line)
    return commands, prose


def with_shape(typ: str, desc: str) -> str:
    """The description, after the array shape of its Python type ("array_like (K, n)" -> "(K, n): ...")."""
    m = re.search(r"(?:array_like|ndarray)s? (\([^()]*\))", typ)
    return f"{m.group(1)}: {desc}" if m and desc else desc


def identifiers(declaration: str) -> set[str]:
    return set(re.findall(r"[A-Za-z_]\w*", declaration))


def attribute_block(name: str, entries: dict[str, str]) -> list[str]:
    """The C++ doc of member Class.name: its item's description in the class's Attributes."""
    cls, _, member = name.partition(".")
    for names, typ, desc in attribute_items(cls, one_side(entries[cls], "", PYTHON)):
        if member in [n.strip() for n in names.split(",")]:
            if not desc:
                raise SystemExit(f"{SOURCE.name}: {cls}'s attribute {member} has only a type: nothing for C++")
            return rst_to_doxygen(with_shape(typ, desc)).splitlines()
    raise SystemExit(f"marker '{name}': no entry of that name in {SOURCE.name}")


def read_sections(doc: str, is_type: bool, declared: set[str]):
    """An entry's C++ view: (description lines, [(names, @param text)], [@return texts],
    [(exception, text)], the C++ section's commands)."""
    lines = doc.splitlines()
    marks = headings(lines) + [len(lines)]
    text, params, returns, throws = list(lines[: marks[0]]), [], [], []
    commands: dict[str, list[str]] = {}
    for start, end in zip(marks, marks[1:]):
        title, body = lines[start], lines[start + 2: end]
        if title == CPP:
            commands, prose = cpp_commands(body)
            text += [""] + prose
            if is_type:  # a class's parameters are its constructors'
                commands = {k: v for k, v in commands.items() if not k.startswith("@param")}
        elif title in ("Parameters", "Attributes"):
            found, prose = items(body)
            text += [""] + prose
            if title == "Parameters" and not is_type:
                for names, typ, desc in found:
                    kept = [n.strip() for n in names.split(",") if n.strip() in declared]
                    if kept and desc:
                        params.append((kept, with_shape(typ, desc)))
        elif title == "Returns":
            returns += [desc or typ for _, typ, desc in items(body, returns=True)[0]]
        elif title == "Raises":
            throws += [(EXCEPTIONS.get(exc, exc), desc) for exc, _, desc in items(body)[0]]
        else:
            text += ["", f"{title}:"] + body
    return text, params, returns, throws, commands


def param_lines(params, commands: dict[str, list[str]], declaration: str) -> list[str]:
    """@param lines in the declaration's order: the C++ section's where it has one for a name (it
    replaces the generated one), then its own for other parameters the declaration has."""
    declared = identifiers(declaration)
    by_name = {n: k for k in commands if k.startswith("@param ") for n in k.split()[1].split(",")}
    documented: list[tuple[str, list[str]]] = []  # (first name, lines)
    for names, desc in params:
        key = next((by_name[n] for n in names if by_name.get(n) in commands), None)
        if key:
            documented.append((names[0], commands.pop(key)))
        elif not any(n in by_name for n in names):
            documented.append((names[0], command(f"@param {','.join(names)}", desc)))
    for key in [k for k in commands if k.startswith("@param")]:
        lines_of = commands.pop(key)
        names = [n for n in key.split()[1].split(",") if n in declared]
        if names:
            documented.append((names[0], lines_of))
    position = {n: i for i, n in reversed(list(enumerate(re.findall(r"[A-Za-z_]\w*", declaration))))}
    return [line for _, lines_of in sorted(documented, key=lambda d: position.get(d[0], len(position)))
            for line in lines_of]


def doxygen(name: str, entries: dict[str, str], declaration: str) -> list[str]:
    """The `///` lines (without the slashes) for the declaration under marker `name`."""
    cls, _, member = name.partition(".")
    if member and member != "__init__" and name not in entries:
        return attribute_block(name, entries)
    is_type = re.match(r"\s*(class|struct|enum)\b", declaration) is not None
    text, params, returns, throws, commands = read_sections(
        one_side(entries[cls if member == "__init__" else name], "", PYTHON), is_type, identifiers(declaration))
    out = [] if member == "__init__" else paragraphs(text)  # a constructor: its parameters only
    if out:
        out[0] = "@brief " + out[0]
    tail = param_lines(params, commands, declaration)
    if member == "__init__":
        commands = {}
    if re.search(r"\bvoid\s+\w+\s*\(", declaration):
        returns = []
    for desc in returns:
        tail += commands.pop("@return") if "@return" in commands else command("@return", desc)
    for exc, desc in throws:
        tail += commands.pop(f"@throws {exc}") if f"@throws {exc}" in commands else command(f"@throws {exc}", desc)
    tail += [line for k in list(commands) for line in commands.pop(k)]  # the C++ section's other commands
    if out and tail:
        out.append("")
    out += tail
    if not out:
        raise SystemExit(f"marker '{name}': the entry has nothing for this C++ declaration")
    return rst_to_doxygen("\n".join(out)).splitlines()


WIDTH = 120  # of a header line


def wrap(block: list[str], width: int) -> list[str]:
    """Lines longer than width broken at a space, the rest carried into the paragraph's next line (a
    command's continuation indented)."""
    out = list(block)
    i = 0
    while i < len(out):
        line = out[i]
        cut = line.rfind(" ", 0, width + 1)
        if len(line) <= width or cut <= len(line) - len(line.lstrip()):
            i += 1
            continue
        head, rest = line[:cut], line[cut + 1:]
        lead = " " * (len(line) - len(line.lstrip()))
        more = lead + ("  " if line.lstrip().startswith("@") else "")
        follows = i + 1 < len(out) and out[i + 1].strip() and not out[i + 1].lstrip().startswith("@") \
            and out[i + 1].startswith(more) and not out[i + 1].startswith(more + " ")
        out[i] = head
        if follows:
            out[i + 1] = more + rest + " " + out[i + 1][len(more):]
        else:
            out.insert(i + 1, more + rest)
        i += 1
    return out


def declaration_after(lines: list[str], i: int) -> str:
    """The declaration that starts at line i: up to its first ';' or '{'."""
    out = []
    for line in lines[i:]:
        out.append(line)
        if ";" in line or "{" in line:
            break
    return "\n".join(out)


def rewrite_header(text: str, entries: dict[str, str], where: str = "") -> tuple[str, list[str]]:
    """The header with each marker's `///` block regenerated, and the names its markers use."""
    known = set(all_docs(entries)) | {f"{k}.__init__" for k in entries if "." not in k}
    lines = text.splitlines()
    out: list[str] = []
    used: list[str] = []
    i = 0
    while i < len(lines):
        out.append(lines[i])
        m = MARKER.fullmatch(lines[i])
        i += 1
        if not m:
            continue
        indent, names = m.groups()
        name = names.split()[0]  # more names: one declaration of several members ("double a, b;")
        for n in names.split():
            if n not in known:
                raise SystemExit(f"{where}: marker '{n}' names no entry of {SOURCE.name}")
            used.append(n)
        while i < len(lines) and lines[i].startswith(indent + "///"):
            i += 1
        if i < len(lines):  # a trailing "///<" comment of the declaration is the marker's to write
            lines[i] = re.sub(r"\s*///<.*", "", lines[i])
        block = doxygen(name, entries, declaration_after(lines, i))
        out += [f"{indent}/// {line}".rstrip() for line in wrap(block, WIDTH - len(indent) - 4)]
    return "\n".join(out) + "\n", used


def headers() -> list[Path]:
    return sorted(HEADERS.rglob("*.hpp"))


def header_outputs(entries: dict[str, str]) -> tuple[dict[Path, str], list[str]]:
    out, used = {}, []
    for path in headers():
        text = path.read_text(encoding="utf-8")
        if "// docstrings.txt @@ " in text:
            out[path], names = rewrite_header(text, entries, str(path.relative_to(ROOT)))
            used += names
    return out, used


def python_only(text: str) -> set[str]:
    """The names listed on "#! python-only A B" lines."""
    return {n for line in text.splitlines() if line.startswith("#! python-only ") for n in line.split()[2:]}


def class_body(headers_text: str, cls: str) -> str | None:
    m = re.search(rf"^\s*(?:class|struct|enum class) {cls}\b[^;]*?\{{(.*?)^}};", headers_text, re.M | re.S)
    return m.group(1) if m else None


def missing_markers() -> list[str]:
    """Entries (and class attributes with a description, and constructors) whose name a public header
    obviously declares (the class; a member function or field of that name in its class; a free
    function) but with no marker naming them, less the python-only ones."""
    source = SOURCE.read_text(encoding="utf-8")
    entries = parse_entries(source)
    text = "\n".join(re.sub(r"//.*", "", p.read_text(encoding="utf-8")) for p in headers())
    _, used = header_outputs(entries)
    wanted = []
    for name in all_docs(entries):
        cls, _, member = name.partition(".")
        body = class_body(text, cls)
        if not member:
            if body is not None or re.search(rf"^\S.*\b{cls}\(", text, re.M):
                wanted.append(name)
                if "Parameters" in [entries[name].splitlines()[i] for i in headings(entries[name].splitlines())] and body is not None \
                        and re.search(rf"^\s+(?:explicit )?{cls}\(", body, re.M):
                    wanted.append(f"{cls}.__init__")
            continue
        if body is None or not re.search(rf"\b{re.escape(member)}\s*(\(|;|=|{{)", body):
            continue
        if name not in entries and not next((d for names, _, d in attribute_items(cls, python_text(entries[cls]))
                                             if member in [n.strip() for n in names.split(",")]), ""):
            continue  # an attribute with only a type: nothing to say in C++
        wanted.append(name)
    return [n for n in wanted if n not in used and n not in python_only(source)]


def outputs() -> dict[Path, str]:
    """The checked-in outputs and their text."""
    out = {STUB: stub(STUB.read_text(encoding="utf-8"), documented())}
    out.update(header_outputs(parse_entries(SOURCE.read_text(encoding="utf-8")))[0])
    return out


def documented() -> dict[str, str]:
    """Every documented name (entries and class attributes) and its text: what the test compares with __doc__."""
    return all_docs(parse_entries(SOURCE.read_text(encoding="utf-8")))


def main(argv: list[str]) -> int:
    if "--header" in argv:
        path = Path(argv[argv.index("--header") + 1])
        text = header(documented())
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text, encoding="utf-8")
        return 0
    check = "--check" in argv
    stale = []
    for path, text in outputs().items():
        if path.exists() and path.read_text(encoding="utf-8") == text:
            continue
        if check:
            stale.append(str(path.relative_to(ROOT)))
        else:
            path.write_text(text, encoding="utf-8")
            print("wrote", path.relative_to(ROOT))
    if stale:
        print("stale (run scripts/gen_docstrings.py):", ", ".join(stale))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
