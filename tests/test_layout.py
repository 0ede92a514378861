"""The house rules of the package layout: subpackages by concept, each saying what it holds
and what it may import; provenance cited as a reader can find it.  (The 0.1 module paths
are gone: see CHANGELOG.md.)"""

import importlib
import pathlib
import re

import pytest

import gearlever

SRC = pathlib.Path(gearlever.__file__).parent

#: Subpackages of the numeric core: arrays in, arrays out, never pandas or pyplot.
CORE = ["gears", "trains", "zrdpm", "loops", "mechanism", "flywheels", "synthesis", "laws", "cams"]
#: Every subpackage of gearlever.
SUBPACKAGES = sorted(p.parent.name for p in SRC.glob("*/__init__.py"))


def test_the_subpackages_by_concept_exist():
    assert set(CORE + ["data", "plotting", "tables", "reproduce", "cli"]) <= set(SUBPACKAGES)


@pytest.mark.parametrize("name", SUBPACKAGES)
def test_each_subpackage_docstring_says_what_lives_there_and_what_it_may_import(name):
    doc = importlib.import_module(f"gearlever.{name}").__doc__ or ""
    assert len(doc.split()) >= 15, f"gearlever.{name} has no real docstring"
    assert re.search(r"import", doc), f"gearlever.{name}'s docstring does not say what it may import"


@pytest.mark.parametrize("name", CORE)
def test_the_numeric_core_imports_neither_pandas_nor_matplotlib(name):
    rx = re.compile(r"^\s*(import|from)\s+(pandas|matplotlib)\b", re.MULTILINE)
    users = [str(p.relative_to(SRC)) for p in (SRC / name).rglob("*.py") if rx.search(p.read_text(encoding="utf-8"))]
    assert users == []


def test_no_top_level_module_holds_a_concept_of_its_own():
    """Only private helpers and the error family sit beside the subpackages."""
    top = sorted(p.stem for p in SRC.glob("*.py"))
    assert all(t.startswith("_") or t == "errors" for t in top), top


def test_py_typed_marker_ships_with_the_package():
    assert (SRC / "py.typed").is_file()


def test_every_data_file_is_declared_as_package_data():
    import tomllib

    patterns = tomllib.loads((SRC.parents[1] / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    globs = patterns["gearlever"]
    files = [p for p in (SRC / "data").iterdir() if p.is_file() and p.suffix != ".py"]
    assert files and all(any(p.match(g) for g in globs) for p in files), [p.name for p in files]


def test_the_package_never_calls_matplotlib_use():
    rx = re.compile(r"matplotlib\.use\(")
    assert [p for p in SRC.rglob("*.py") if rx.search(p.read_text(encoding="utf-8"))] == []


def test_sources_are_cited_as_a_reader_can_find_them_not_by_file_or_work_item():
    """No docstring or data header names a seed file, the team's folders or an issue number."""
    rx = re.compile(r"\bseeds?\s*0\d\d|seeds/|reference README|\(issue \d+\)|\bissue \d+\b", re.IGNORECASE)
    hits = []
    for p in list(SRC.rglob("*.py")) + list((SRC / "data").glob("*.csv")):
        for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
            if rx.search(line):
                hits.append(f"{p.relative_to(SRC)}:{i}")
    assert hits == []


def test_every_error_is_a_gearlever_error_and_a_value_error():
    assert issubclass(gearlever.GearleverError, ValueError)
    assert issubclass(gearlever.ClosureError, gearlever.GearleverError)
