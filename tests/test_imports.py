"""No import circles, a layering per subpackage, and a library that never imports its command line.

The graph is read from the sources with :mod:`ast`, not by importing them:
every ``import`` and ``from ... import`` counts, at module level and inside
functions (a lazy import hides a circle at import time; the design still has
it), ``if TYPE_CHECKING:`` blocks included; relative imports are resolved.
``from gearlever.x import y`` is an edge to the module ``gearlever.x.y`` when
that is a module, else to ``gearlever.x``.  A module's edge to a package that
contains it (its own ``__init__``) is not counted: Python imports it first
anyway, and a package's ``__init__`` gathering its modules is not a circle.

The layering (:data:`MAY_IMPORT`) is printed in the guide's architecture page
(``docs/guide/architecture.rst``), and a test below keeps the page and the
data equal.
"""

from __future__ import annotations

import ast
import pathlib
import re

import pytest

import gearlever

SRC = pathlib.Path(gearlever.__file__).parent
ROOT = SRC.parents[1]

#: Circles other work owns; each entry is a set of modules (dotted) or of top-level units (subpackages and
#: top-level modules).  A circle found must lie inside one entry.  The integrator empties this list when the
#: branches that remove them are merged.
ALLOWED: list = []  # every circle the house had is gone (issue 30); keep it empty

#: Private helpers and the error family every subpackage may use.
_BASE = {"errors", "_io", "_validate", "_result", "_format", "_progress"}
#: The numeric core, in layers: arrays in, arrays out.
_CORE = {"gears", "trains", "laws", "loops", "zrdpm", "cams", "mechanism", "flywheels", "synthesis"}

#: What each top-level unit (subpackage, or module beside them) may import, besides itself.
MAY_IMPORT: dict[str, set[str]] = {
    "errors": set(),
    "_frame": set(),
    "_format": set(),
    "_progress": set(),
    "_io": {"errors", "_format"},
    "_validate": {"errors"},
    "_result": {"_frame", "_format"},
    "data": {"errors", "_io"},
    "gears": _BASE | {"data"},
    "trains": _BASE | {"data"},
    "laws": _BASE | {"data"},
    "loops": _BASE | {"gears"},
    "zrdpm": _BASE | {"data", "gears", "loops"},
    "cams": _BASE | {"data", "laws"},
    "mechanism": _BASE | {"data", "gears", "loops"},
    "flywheels": _BASE | {"data", "gears", "loops", "mechanism"},
    "synthesis": _BASE | {"data", "gears", "loops", "laws", "cams", "mechanism"},
    "export": _BASE | {"data", "gears", "cams", "mechanism"},
    "tables": _BASE | {"_frame", "data"} | _CORE,
    "plotting": _BASE | {"data"} | _CORE,
    "reproduce": _BASE | {"data", "tables", "plotting"} | _CORE,
    "workbench": _BASE | {"data", "tables", "plotting", "export"} | _CORE,
    "cli": _BASE | {"data", "tables", "plotting", "reproduce", "export", "workbench"} | _CORE,
    "__main__": {"cli"},
    "gearlever": _BASE | _CORE,
}


def _module_name(path: pathlib.Path) -> str:
    parts = list(path.relative_to(SRC.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {_module_name(p): p for p in sorted(SRC.rglob("*.py"))}


def _resolve(name: str) -> str | None:
    parts = name.split(".")
    while parts:
        if ".".join(parts) in MODULES:
            return ".".join(parts)
        parts.pop()
    return None


def _imports(module: str, path: pathlib.Path) -> set[str]:
    """The gearlever modules ``module`` imports anywhere in its body."""
    package = module.split(".") if path.name == "__init__.py" else module.split(".")[:-1]
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = package[: len(package) - node.level + 1] if node.level else []
            full = ".".join(base + ([node.module] if node.module else []))
            targets = [f"{full}.{alias.name}" for alias in node.names]
        else:
            continue
        for t in targets:
            if t.split(".")[0] != "gearlever":
                continue
            r = _resolve(t)
            if r is not None and r != module and not module.startswith(r + "."):
                out.add(r)
    return out


def build_graph() -> dict[str, set[str]]:
    """Module -> the gearlever modules it imports (module- and function-level)."""
    return {m: _imports(m, p) for m, p in MODULES.items()}


def unit(module: str) -> str:
    """The top-level unit of a module: its subpackage or top-level module (``gearlever`` for the root)."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "gearlever"


def unit_graph(graph: dict[str, set[str]]) -> dict[str, set[str]]:
    out: dict[str, set[str]] = {unit(m): set() for m in graph}
    for m, targets in graph.items():
        out[unit(m)] |= {unit(t) for t in targets if unit(t) != unit(m)}
    return out


def circles(graph: dict[str, set[str]]) -> list[set[str]]:
    """Strongly connected components of more than one node (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.get(w, ())))))
                elif w in on_stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = set()
                while True:
                    w = stack.pop()
                    on_stack.discard(w)
                    comp.add(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    found.append(comp)
    return found


def _allowed(nodes: set[str]) -> bool:
    return any(nodes <= entry for entry in ALLOWED)


GRAPH = build_graph()
UNITS = unit_graph(GRAPH)


def test_the_graph_sees_function_level_and_relative_imports():
    # a lazy import inside a function counts (cli/_shared.py imports gearlever.mechanism only when called)
    assert "gearlever.mechanism" in GRAPH["gearlever.cli._shared"]
    assert "gearlever.errors" in GRAPH["gearlever.cli._shared"]
    assert circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [{"a", "b", "c"}]


def test_no_circle_between_modules():
    bad = [sorted(c) for c in circles(GRAPH) if not _allowed(c)]
    assert bad == []


def test_no_circle_between_subpackages():
    bad = [sorted(c) for c in circles(UNITS) if not _allowed(c)]
    assert bad == []


def test_no_library_module_imports_the_command_line():
    users = [
        f"{m} -> {t}"
        for m, targets in GRAPH.items()
        for t in targets
        if unit(t) == "cli" and unit(m) not in ("cli", "__main__") and not _allowed({unit(m), "cli"})
    ]
    assert users == []


def test_the_layering_rules_are_themselves_free_of_circles_and_cover_every_unit():
    assert set(UNITS) <= set(MAY_IMPORT), sorted(set(UNITS) - set(MAY_IMPORT))
    assert circles(MAY_IMPORT) == []


@pytest.mark.parametrize("name", sorted(MAY_IMPORT))
def test_each_subpackage_imports_only_what_its_layer_may(name):
    extra = {t for t in UNITS.get(name, set()) - MAY_IMPORT[name] if not _allowed({name, t})}
    assert extra == set(), f"{name} imports {sorted(extra)}"


def test_the_architecture_page_prints_the_layering_rules():
    """The guide's table "what each subpackage may import" is this data, row for row."""
    page = (ROOT / "docs" / "guide" / "architecture.rst").read_text(encoding="utf-8")
    rows = {}
    for line in page.splitlines():
        m = re.match(r"^``(\w+)``\s{2,}(.*)$", line)
        if m:
            rows[m.group(1)] = set(re.findall(r"``(\w+)``", m.group(2)))
    assert rows == MAY_IMPORT
