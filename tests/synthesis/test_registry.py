"""The registry of path-generation kinds: every kind complete, each module importable alone, no import circle,
and a kind added by ``register`` reaches the driver without touching it."""

from __future__ import annotations

import ast
import pathlib
import subprocess
import sys
import tomllib

import numpy as np
import pytest

import gearlever.synthesis
from gearlever.errors import GearleverError
from gearlever.mechanism.modelfile import model_toml
from gearlever.synthesis import path, path_kinds, registry
from gearlever.synthesis.path_fourbar import FourBarPathProblem, fourbar_result
from gearlever.synthesis.path_kinds import PathKind, PathSynthesis

SYN = pathlib.Path(gearlever.synthesis.__file__).parent
SRC = SYN.parents[1]
T5 = [[1.0, 2.0], [1.5, 2.4], [1.8, 3.0], [1.2, 3.5], [0.8, 2.8]]


def test_the_builtin_kinds_are_registered_in_auto_order():
    assert path_kinds.names() == ("fourbar", "geared-fivebar", "sixbar")
    assert path.KINDS == ("fourbar", "geared-fivebar", "sixbar", "auto")


@pytest.mark.parametrize("name", ["fourbar", "geared-fivebar", "sixbar"])
def test_every_kind_has_a_search_space_a_result_builder_and_a_model_writer(name):
    kind = path_kinds.get(name)
    assert kind.name == name and isinstance(kind, PathKind)
    for method in ("result", "model"):  # overridden, not the base's NotImplementedError
        assert getattr(type(kind), method) is not getattr(PathKind, method), (name, method)
    pb = kind.make_problem(targets=T5, length_range=(0.2, 5), coord_range=(-5, 5))
    assert issubclass(kind.problem, FourBarPathProblem) and isinstance(pb, kind.problem)
    assert pb.names[-1] == "branch" and pb.lo.shape == pb.hi.shape == (pb.d,)
    assert np.all(pb.lo < pb.hi)
    Z = pb.sample(np.random.default_rng(0), 64)
    f = pb.objective(Z)
    assert f.shape == (64,) and np.all((f >= 0) | np.isinf(f))


@pytest.mark.parametrize("name", ["fourbar", "geared-fivebar", "sixbar"])
def test_the_result_and_model_of_each_kind_come_from_its_registered_builders(name):
    r = path.synthesize_path(T5, length_range=(0.2, 5), coord_range=(-5, 5), kind=name, budget=6000, seed=1, workers=1)
    assert r.kind == name and r.feasible
    m = tomllib.loads(model_toml(r.model()))
    assert m == tomllib.loads(model_toml(path_kinds.get(name).model(r, name="synthesized path generator", units="")))
    assert m["inputs"] == [{"link": "crank"}]


@pytest.mark.parametrize(
    "module",
    [
        "gearlever.synthesis.sixbar",
        "gearlever.synthesis.fivebar",
        "gearlever.synthesis.path_fourbar",
        "gearlever.synthesis.path_kinds",
        "gearlever.synthesis.path",
        "gearlever.synthesis.model",
        "gearlever.synthesis._dask",
    ],
)
def test_each_module_imports_alone_in_a_fresh_interpreter(module):
    code = f"import {module}; from gearlever.synthesis import path_kinds; print(path_kinds.names())"
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        env={"PYTHONPATH": str(SRC), "PATH": "/usr/bin:/bin"},
        timeout=120,
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "('fourbar', 'geared-fivebar', 'sixbar')"


def _module_name(path_: pathlib.Path) -> str:
    rel = path_.relative_to(SRC).with_suffix("")
    parts = rel.parts[:-1] if rel.name == "__init__" else rel.parts
    return ".".join(parts)


def _module_level_imports(path_: pathlib.Path, name: str, package: bool, modules=()) -> set:
    """Modules of gearlever.synthesis a module imports when it is imported (not inside functions).

    ``from P import m`` of a module ``m`` (one of ``modules``) counts as an import of ``P.m``, else of ``P``.
    """
    tree = ast.parse(path_.read_text(encoding="utf-8"))
    out = set()
    pkg = name if package else name.rpartition(".")[0]

    def visit(nodes):
        for node in nodes:
            if isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = pkg.split(".")[: len(pkg.split(".")) - (node.level - 1)]
                    base = ".".join(up + ([base] if base else []))
                subs = {f"{base}.{a.name}" for a in node.names} & set(modules)
                out.update(subs or {base})
            elif isinstance(node, (ast.If, ast.Try, ast.With)):
                for field in ("body", "orelse", "finalbody", "handlers"):
                    visit(getattr(node, field, []) or [])
            elif isinstance(node, ast.ExceptHandler):
                visit(node.body)

    visit(tree.body)
    return {m for m in out if m.startswith("gearlever.synthesis")}


def _graph() -> dict:
    files = {_module_name(p): p for p in SYN.rglob("*.py")}
    return {
        name: {m for m in _module_level_imports(p, name, p.name == "__init__.py", files) if m in files and m != name}
        for name, p in files.items()
    }


def _cycles(graph: dict) -> list:
    """Every cycle of ``graph`` found by a depth-first search (each as the list of its modules)."""
    found, state = [], {}

    def dfs(u, stack):
        state[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, ())):
            if state.get(v) == 1:
                found.append(stack[stack.index(v) :] + [v])
            elif v not in state:
                dfs(v, stack)
        stack.pop()
        state[u] = 2

    for u in sorted(graph):
        if u not in state:
            dfs(u, [])
    return found


def test_no_module_of_synthesis_imports_another_in_a_circle_at_module_level():
    graph = _graph()
    # the scan sees the imports it should: the kinds import the four-bar and the registry, not the driver
    assert {"gearlever.synthesis.path_fourbar", "gearlever.synthesis.path_kinds"} <= graph["gearlever.synthesis.sixbar"]
    for kind in ("sixbar", "fivebar", "path_fourbar", "path_kinds", "_dask"):
        assert "gearlever.synthesis.path" not in graph[f"gearlever.synthesis.{kind}"], kind
    assert _cycles(graph) == []


def test_the_cycle_finder_finds_a_circle():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c", "a"]]
    assert _cycles({"a": {"b"}, "b": set()}) == []


class DummyKind(PathKind):
    """A four-bar under another name, last in ``auto``, writing its own model name."""

    name = "dummy"
    order = 99
    problem = FourBarPathProblem

    def result(self, pb, w, mode, evals, seed, starts, seconds):
        from dataclasses import replace

        return replace(fourbar_result(pb, w, mode, evals, seed, starts, seconds), kind=self.name)

    def model(self, result, name, units):
        return path_kinds.get("fourbar").model(result, name=f"dummy: {name}", units=units)


@pytest.fixture
def dummy(monkeypatch):
    registry.kinds()  # every family loaded first: the copy holds them all
    monkeypatch.setattr(registry, "_KINDS", {**registry._KINDS})
    path_kinds.register(DummyKind)
    return path_kinds.get("dummy")


def test_a_registered_kind_reaches_the_driver_without_touching_it(dummy):
    assert path_kinds.names()[-1] == "dummy" and path.KINDS[-2:] == ("dummy", "auto")
    assert isinstance(path.make_problem({"kind": "dummy", "targets": T5}), FourBarPathProblem)
    r = path.synthesize_path(T5, length_range=(0.2, 5), coord_range=(-5, 5), kind="dummy", budget=4000, workers=1)
    assert isinstance(r, PathSynthesis) and r.kind == "dummy" and r.feasible
    assert r.model()["mechanism"]["name"] == "dummy: synthesized path generator"
    assert r.summary()["type"] == "dummy"


def test_auto_tries_a_registered_kind_in_the_registry_order(dummy, monkeypatch):
    monkeypatch.setattr(path, "AUTO_GOOD", -1.0)  # never good enough: auto tries every kind
    r = path.synthesize_path(T5, length_range=(0.2, 5), coord_range=(-5, 5), kind="auto", budget=6000, workers=1)
    assert list(r.tried) == ["fourbar", "geared-fivebar", "sixbar", "dummy"]


def test_an_unknown_kind_is_refused_naming_the_registered_ones(dummy):
    with pytest.raises(GearleverError, match="kind must be one of fourbar, geared-fivebar, sixbar, dummy, auto"):
        path.synthesize_path(T5, kind="nonsense")
    with pytest.raises(GearleverError, match="kind must be one of"):
        path.make_problem({"kind": "nonsense", "targets": T5})


def test_register_refuses_what_is_not_a_named_kind():
    with pytest.raises(GearleverError, match="PathKind with a name"):
        path_kinds.register(object)
    with pytest.raises(GearleverError, match="PathKind with a name"):
        path_kinds.register(PathKind)  # no name
    with pytest.raises(GearleverError, match="'auto'"):
        path_kinds.register(type("Auto", (PathKind,), {"name": "auto"}))
