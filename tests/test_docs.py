"""Every example of the user guide (docs/guide/*.rst) runs as printed.

* ``.. code-block:: console``: each line ``$ gearlever ...`` is run through
  :func:`gearlever.cli.main` in a temporary folder holding a copy of the
  examples (so ``examples/fourbar.toml`` and written files resolve there); it
  must exit 0.  The commands of one block run in order in one folder.  The
  lines printed after a command, up to the next ``$`` line, must be exactly
  its output (``...`` on a line of its own skips any number of output lines).
* ``.. code-block:: pycon``: doctests (``>>>``), output compared.
* ``.. code-block:: python``: executed.
* ``.. code-block:: toml``: parsed (TOML syntax); the examples of the model
  file's tables are fragments, so only their syntax and keys are checked
  (a fragment's tables and keys must be ones the model loader knows).

The Python blocks of one page run in order in one namespace, like a session.
"""

from __future__ import annotations

import doctest
import pathlib
import re
import shlex
import shutil
import tomllib

import pytest

from gearlever.cli import main
from gearlever.data import example_path, list_examples
from tests._printed import numbers_agree

GUIDE = pathlib.Path(__file__).resolve().parents[1] / "docs" / "guide"
PAGES = sorted(GUIDE.glob("*.rst"))
BLOCK = re.compile(
    r"^\.\. code-block:: (console|pycon|python|toml)[ \t]*\n"  # the directive
    r"((?:[ \t]+:[^\n]*\n)*)\n"  # its options
    r"((?:(?:[ \t]+[^\n]*)?\n)+)",  # the indented body (blank lines inside)
    re.M,
)


def _blocks(page: pathlib.Path):
    """``[(kind, text, line)]`` of the page's console, pycon and python blocks, dedented."""
    text = page.read_text(encoding="utf-8")
    out = []
    for m in BLOCK.finditer(text + "\n"):
        body = m.group(3).rstrip("\n").splitlines()
        indent = min(len(ln) - len(ln.lstrip()) for ln in body if ln.strip())
        out.append((m.group(1), "\n".join(ln[indent:] for ln in body) + "\n", text[: m.start()].count("\n") + 1))
    return out


def _console_blocks():
    """One pytest case per console block: ``[(command, expected output lines)]``."""
    cases = []
    for page in PAGES:
        for kind, body, line in _blocks(page):
            if kind != "console":
                continue
            commands = []
            for ln in body.splitlines():
                if ln.startswith("$ "):
                    commands.append((ln[2:], []))
                elif commands and ln.strip():
                    commands[-1][1].append(ln)
            commands = [c for c in commands if c[0].startswith("gearlever ")]
            if commands:
                cases.append(pytest.param(commands, id=f"{page.stem}:{line}"))
    return cases


CONSOLE = _console_blocks()
COMMANDS = [c for case in CONSOLE for c in case.values[0]]


@pytest.fixture
def workdir(tmp_path, monkeypatch):
    folder = tmp_path / "examples"
    folder.mkdir()
    for name in list_examples():
        shutil.copyfile(example_path(name), folder / name)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")  # what the command line sets; figures are files here
    monkeypatch.setenv("GEARLEVER_CACHE", str(tmp_path / "cache"))  # curve library build: an empty cache of its own
    return tmp_path


def test_the_guide_has_pages_and_examples_of_each_kind():
    kinds = {kind for page in PAGES for kind, _, _ in _blocks(page)}
    assert len(PAGES) >= 10 and kinds == {"console", "pycon", "python", "toml"}
    assert len(COMMANDS) >= 20


def _matches(expected: list[str], got: list[str]) -> bool:
    """``expected`` equals ``got`` line for line, a line ``...`` standing for any run of lines."""
    if not expected:
        return not got
    if expected[0].strip() == "...":
        return any(_matches(expected[1:], got[k:]) for k in range(len(got) + 1))
    if not got:
        return False
    head = expected[0].rstrip()
    if head.endswith(" ...") and head != "...":  # a line shown up to " ...": the printed line starts so
        same = numbers_agree(head[:-4], got[0][: len(head) - 4])
    else:
        same = numbers_agree(head, got[0])
    return same and _matches(expected[1:], got[1:])


@pytest.mark.parametrize("commands", CONSOLE)
def test_guide_commands_run_as_printed(commands, workdir, capsys):
    for command, expected in commands:
        try:
            status = main(shlex.split(command)[1:])
        except SystemExit as exc:  # --version, --help: argparse exits itself
            status = exc.code
        out, err = capsys.readouterr()
        assert status == 0, f"{command}: exit {status}: {err}"
        if expected:
            assert _matches(expected, out.splitlines()), f"{command} printed:\n{out}"


PYTHON_PAGES = [p for p in PAGES if any(k in ("pycon", "python") for k, _, _ in _blocks(p))]
TOML_BLOCKS = [
    pytest.param(body, id=f"{page.stem}:{line}")
    for page in PAGES
    for kind, body, line in _blocks(page)
    if kind == "toml"
]


@pytest.mark.parametrize("body", TOML_BLOCKS)
def test_guide_toml_fragments_parse_and_use_known_tables_and_keys(body):
    from gearlever.mechanism import schema

    data = tomllib.loads(body)
    known = {t.name: set(schema.allowed_keys(t.name)) for t in schema.TABLES if t.form in ("table", "array")}
    entries = {t.name: set(schema.allowed_keys(t.name)) for t in schema.TABLES if t.form == "map of tables"}
    for table, value in data.items():
        assert table in schema.allowed_tables(), table
        rows = value if isinstance(value, list) else [value]
        for row in rows:
            if table in known:
                assert set(row) <= known[table], (table, set(row) - known[table])
            elif table in entries:
                for name, entry in row.items():
                    assert set(entry) <= entries[table], (table, name, set(entry) - entries[table])
            elif table == "lengths":  # LINK or "LINK.P-Q" = a positive length
                assert all(isinstance(v, int | float) and v > 0 for v in row.values()), row


@pytest.mark.parametrize("page", PYTHON_PAGES, ids=lambda p: p.stem)
def test_guide_python_examples_run_as_printed(page, workdir):
    namespace: dict = {"__name__": f"guide_{page.stem}"}
    parser = doctest.DocTestParser()
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    for kind, body, line in _blocks(page):
        where = f"{page.name}, block at line {line}"
        if kind == "python":
            exec(compile(body, where, "exec"), namespace)
        elif kind == "pycon":
            test = parser.get_doctest(body, namespace, where, str(page), line)
            runner = doctest.DocTestRunner(optionflags=flags)
            runner.run(test, clear_globs=False)
            namespace.update(test.globs)  # DocTest works on a copy of the namespace
            assert runner.failures == 0, f"{where}: {runner.failures} example(s) failed (output above)"
