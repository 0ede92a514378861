"""The README's examples run as printed: every console command, in order, in one empty folder,
with its output checked where the README shows it; every Python block; every link and picture."""

import os
import pathlib
import re
import shlex
import subprocess
import sys

import pytest

import gearlever
from tests._printed import numbers_agree

ROOT = pathlib.Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
TEXT = README.read_text(encoding="utf-8")
PYTHON_BLOCKS = re.findall(r"```python\n(.*?)```", TEXT, re.DOTALL)
CONSOLE_BLOCKS = re.findall(r"```console\n(.*?)```", TEXT, re.DOTALL)
ELLIPSIS = "..."
TRUNCATED = " ..."  # a shown line ending so is the start of the printed line


def console_steps(blocks):
    """(command, expected output lines) for every ``$ `` line of the console blocks, in order."""
    steps = []
    for block in blocks:
        for line in block.splitlines():
            if line.startswith("$ "):
                steps.append((line[2:], []))
            elif line.strip():
                assert steps, f"output shown before any command: {line!r}"
                steps[-1][1].append(line.rstrip())
    return steps


STEPS = console_steps(CONSOLE_BLOCKS)


def _matches(shown, printed):
    if shown.endswith(TRUNCATED):
        return printed.startswith(shown[: -len(TRUNCATED)])
    return numbers_agree(shown, printed)


def output_agrees(shown, printed):
    """Every shown line is a printed line, in order; ``...`` stands for any number of printed lines,
    and without ``...`` the shown lines are consecutive and start at the first printed line."""
    printed = [p.rstrip() for p in printed]
    pos, free = 0, False
    for s in shown:
        if s == ELLIPSIS:
            free = True
            continue
        if free:
            while pos < len(printed) and not _matches(s, printed[pos]):
                pos += 1
        if pos >= len(printed) or not _matches(s, printed[pos]):
            return False
        pos, free = pos + 1, False
    return free or pos == len(printed)


def test_the_output_check_can_fail():
    assert output_agrees(["a", "b ..."], ["a", "bc"])
    assert output_agrees(["...", "c"], ["a", "b", "c"])
    assert not output_agrees(["a"], ["a", "b"])
    assert not output_agrees(["b"], ["a", "b"])
    assert not output_agrees(["a", "x ..."], ["a", "bc"])
    assert not output_agrees(["...", "d"], ["a", "b", "c"])


def test_the_readme_is_short():
    assert len(TEXT.splitlines()) < 200


def test_the_quickstart_shows_the_main_commands():
    commands = [c for c, _ in STEPS]
    for sub in ("mechanism analyze", "mechanism draw", "mechanism view", "synthesize function", "reproduce"):
        assert any(c.startswith(f"gearlever {sub}") for c in commands), sub
    assert any(c.count("--rpm") >= 2 for c in commands), "a two-input example"


def test_every_console_command_runs_as_printed(tmp_path):
    """The commands depend on each other (a model is copied, then analysed), so they run in order."""
    assert len(STEPS) >= 5
    env = dict(os.environ, MPLBACKEND="Agg", PYTHONPATH=str(pathlib.Path(gearlever.__file__).parents[1]))
    for command, shown in STEPS:
        argv = shlex.split(command)
        assert argv[0] == "gearlever", command
        done = subprocess.run(
            [sys.executable, "-m", "gearlever", *argv[1:]],
            cwd=tmp_path,
            env=env,
            capture_output=True,
            text=True,
            timeout=600,
        )
        assert done.returncode == 0, f"{command}\n{done.stderr}"
        if shown:
            assert output_agrees(shown, done.stdout.splitlines()), f"{command}\nprinted:\n{done.stdout}"
        for flag in ("--out", "--tables", "--figures"):
            if flag in argv:
                written = tmp_path / argv[argv.index(flag) + 1]
                assert written.exists() and (written.is_dir() or written.stat().st_size > 0), (command, flag)
    assert (tmp_path / "fourbar.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "<html" in (tmp_path / "fourbar.html").read_text(encoding="utf-8").lower()
    assert (tmp_path / "tables" / "table1.csv").exists() and (tmp_path / "figures" / "zrdpm_fig3_u1.png").exists()


def test_the_readme_has_a_python_example():
    assert PYTHON_BLOCKS


@pytest.mark.parametrize("i", range(len(PYTHON_BLOCKS)))
def test_readme_python_example_runs(i, monkeypatch):
    monkeypatch.chdir(ROOT)
    exec(compile(PYTHON_BLOCKS[i], f"README.md python block {i + 1}", "exec"), {"__name__": "readme"})


def test_every_link_and_picture_exists():
    targets = re.findall(r"\]\(([^)#\s]+)\)", TEXT)
    assert targets
    missing = [t for t in targets if "://" not in t and not (ROOT / t).exists()]
    assert missing == []


def test_every_guide_page_is_linked():
    linked = set(re.findall(r"\(docs/guide/([\w-]+)\.rst\)", TEXT))
    pages = {p.stem for p in (ROOT / "docs" / "guide").glob("*.rst")}
    assert pages <= linked, sorted(pages - linked)


def test_every_benchmark_has_a_row_in_the_speed_table():
    table = TEXT.split("## Speed", 1)[1].split("\n## ", 1)[0]
    assert [b.name for b in sorted((ROOT / "benchmarks").glob("bench_*.py")) if f"`{b.name}`" not in table] == []
