"""No import circle among the modules of gearlever.synthesis (its curve package included), lazy imports counted.

A lazy import (inside a function) hides a circle at import time, but the design still has it: the scan
reads every ``import`` statement of a module, at any depth.  The registry reaches the families' modules by
name (:data:`gearlever.synthesis.registry.FAMILIES`, imported with :mod:`importlib`), as plug-ins.
"""

from __future__ import annotations

import ast
import pathlib

import gearlever

SRC = pathlib.Path(gearlever.__file__).parents[1]
SCOPE = ("gearlever.synthesis", "gearlever.synthesis.curve")


def _name(p: pathlib.Path) -> str:
    rel = p.relative_to(SRC).with_suffix("")
    return ".".join(rel.parts[:-1] if rel.name == "__init__" else rel.parts)


def _graph() -> dict:
    files = {_name(p): p for p in (SRC / "gearlever").rglob("*.py")}
    graph = {}
    for name, p in files.items():
        pkg = name if p.name == "__init__.py" else name.rpartition(".")[0]
        out = set()
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)]
                    base = ".".join(up + ([base] if base else []))
                subs = {f"{base}.{a.name}" for a in node.names} & set(files)
                out.update(subs or {base})
        graph[name] = {m for m in out if m in files and m != name}
    return graph


def _circles(graph: dict) -> list:
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_circle_finder_finds_a_circle_through_a_lazy_import():
    assert _circles({"a": {"b"}, "b": {"a"}, "c": {"a"}}) == [["a", "b"]]
    assert _circles({"a": {"b"}, "b": set()}) == []


def test_the_scan_sees_imports_inside_functions():
    graph = _graph()
    assert (
        "gearlever.synthesis.curve.topology" in graph["gearlever.synthesis.curve.targets"]
    )  # imported inside known_mechanism
    assert "gearlever.synthesis.driver" in graph["gearlever.synthesis.curve.search"]


def test_no_module_of_synthesis_or_curves_is_in_an_import_circle():
    circles = [c for c in _circles(_graph()) if any(m.startswith(SCOPE) for m in c)]
    assert circles == []


def test_the_dask_backend_and_the_curves_leaves_import_no_driver():
    graph = _graph()
    assert not {m for m in graph["gearlever.synthesis._dask"] if m.startswith("gearlever.synthesis.")} - {
        "gearlever.synthesis._search"
    }
    assert graph["gearlever.synthesis.curve.topology"] <= {"gearlever.mechanism.linkage", "gearlever.errors"}
    assert (
        "gearlever.synthesis.curve.search"
        not in graph["gearlever.synthesis.curve.library"] | graph["gearlever.synthesis.curve.targets"]
    )
