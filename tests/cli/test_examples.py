"""``gearlever examples``: the shipped example files listed and copied out; refusals are one line, exit 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gearlever.cli import main
from gearlever.data import example_path, list_examples

REPO_EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_the_repository_examples_folder_is_the_package_data_folder():
    # examples/ at the repository root is a link to the shipped files, so old paths keep working
    assert REPO_EXAMPLES.resolve() == example_path("fourbar.toml").parent.resolve()
    assert sorted(p.name for p in REPO_EXAMPLES.iterdir() if p.suffix in (".toml", ".csv")) == list_examples()


def test_list_names_every_example_with_its_kind_and_description(capsys):
    assert main(["examples", "list", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert [r["name"] for r in rows] == list_examples()
    kinds = {r["name"]: r["kind"] for r in rows}
    assert kinds["fourbar.toml"] == "mechanism model" and kinds["car_differential.csv"] == "gear network"
    assert kinds["law_lift.toml"] == "motion law (cam design)"
    four = next(r for r in rows if r["name"] == "fourbar.toml")
    assert four["description"] == "Crank-rocker four-bar with a coupler point P (lengths in mm)."


def test_list_csv_has_a_header_and_one_row_per_example(capsys):
    assert main(["examples", "list"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "name,kind,description" and len(lines) == 1 + len(list_examples())


def test_copy_writes_identical_files_and_prints_their_paths(tmp_path, capsys):
    dest = tmp_path / "new" / "folder"
    assert main(["examples", "copy", "fourbar", "car_differential.csv", "--to", str(dest)]) == 0
    printed = capsys.readouterr().out.split()
    assert printed == [str(dest / "fourbar.toml"), str(dest / "car_differential.csv")]
    for name in ("fourbar.toml", "car_differential.csv"):
        assert (dest / name).read_bytes() == example_path(name).read_bytes()


def test_a_copied_model_analyses(tmp_path, capsys):
    assert main(["examples", "copy", "fourbar.toml", "--to", str(tmp_path)]) == 0
    path = capsys.readouterr().out.strip()
    assert main(["mechanism", "analyze", path, "--points", "4"]) == 0
    assert len(capsys.readouterr().out.splitlines()) == 5


def test_copy_refuses_to_overwrite_without_force_and_writes_nothing(tmp_path, capsys):
    (tmp_path / "fourbar.toml").write_text("mine")
    assert main(["examples", "copy", "slider_crank", "fourbar", "--to", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "--force" in err and "fourbar.toml" in err
    assert (tmp_path / "fourbar.toml").read_text() == "mine"
    assert not (tmp_path / "slider_crank.toml").exists()  # checked before anything is written
    assert main(["examples", "copy", "fourbar", "--to", str(tmp_path), "--force"]) == 0
    assert (tmp_path / "fourbar.toml").read_bytes() == example_path("fourbar.toml").read_bytes()


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["examples", "copy", "nosuch"], ["no example 'nosuch'", "fourbar.toml", "car_differential.csv"]),
        (["examples", "copy", "compound_planetary"], ["ambiguous", "compound_planetary.csv"]),
        (["examples", "copy", "fourbar", "--to", "/proc/x"], ["--to", "/proc/x"]),
        (["examples", "copy", "fourbar", "--to", "{tmp}/file.txt"], ["--to", "not a directory"]),
    ],
    ids=["unknown", "ambiguous", "proc", "to-a-file"],
)
def test_bad_names_and_folders_are_one_line_exit_2(argv, words, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "file.txt").write_text("x")
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1
    for w in words:
        assert w in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.txt"]


def test_copy_refuses_a_directory_in_the_way(tmp_path, capsys):
    (tmp_path / "fourbar.toml").mkdir()
    assert main(["examples", "copy", "fourbar", "--to", str(tmp_path), "--force"]) == 2
    assert "is a directory" in capsys.readouterr().err
