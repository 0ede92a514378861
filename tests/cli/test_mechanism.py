"""``gearlever mechanism``: outputs, strict JSON, exit 2 with one stderr line, no partial files."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gearlever.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_structure_json_has_the_paper_numbers(capsys):
    assert main(["mechanism", "structure", str(EXAMPLES / "parallel_levers.toml"), "--format", "json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert {k: d[k] for k in ("n", "P5", "P4", "W_formula", "dof", "redundant")} == {
        "n": 5,
        "P5": 8,
        "P4": 0,
        "W_formula": -1,
        "dof": 1,
        "redundant": 2,
    }


def test_analyze_csv_and_json(tmp_path, capsys):
    out = tmp_path / "a.csv"
    assert main(["mechanism", "analyze", str(EXAMPLES / "fourbar.toml"), "--points", "12", "--out", str(out)]) == 0
    lines = out.read_text().splitlines()
    assert len(lines) == 13 and lines[0].startswith("in_crank_deg,crank_deg")
    assert (
        main(
            [
                "mechanism",
                "analyze",
                str(EXAMPLES / "zrdpm_gear_contour.toml"),
                "--points",
                "5",
                "--input",
                "0",
                "90",
                "--input",
                "0",
                "30",
                "--format",
                "json",
            ]
        )
        == 0
    )
    d = json.loads(capsys.readouterr().out)
    assert len(d["rows"]) == 5 and d["rows"][-1]["in_gear9_deg"] == 90.0


def test_rows_that_do_not_close_stay_with_nulls(tmp_path, capsys):
    model = tmp_path / "tr.toml"
    model.write_text(
        "[points]\nO2 = [0, 0]\nO4 = [10, 0]\nA = [0, 8]\nB = [3, 12]\n"
        '[links]\nground = ["O2", "O4"]\ncrank = ["O2", "A"]\ncoupler = ["A", "B"]\nrocker = ["O4", "B"]\n'
        '[[inputs]]\nlink = "crank"\n'
    )
    assert main(["mechanism", "analyze", str(model), "--points", "36", "--format", "json"]) == 0
    rows = json.loads(capsys.readouterr().out)["rows"]
    assert len(rows) == 36
    bad = [r for r in rows if not r["closed"]]
    assert bad and bad[0]["rocker_deg"] is None and bad[0]["reason"]


@pytest.mark.parametrize(
    "text, words",
    [
        (
            '[points]\nO = [0, 0]\n[links]\nground = ["O"]\ncrank = ["O", "Q"]\n[[inputs]]\nlink = "crank"\n',
            "unknown point",
        ),
        ('[points]\nO = [0, 0]\n[links]\nground = ["O"]\ncrank = []\n', "at least one point"),
        ("[points]\nO = [0, 0\n", "TOML syntax error"),
        (
            '[points]\nO = [0, 0]\nA = [1, 0]\n[links]\nground = ["O"]\ncrank = ["O", "A"]\n'
            '[[inputs]]\nlink = "ground"\n',
            "inputs[0].link",
        ),
    ],
)
def test_bad_model_exits_2_with_one_line_and_no_file(tmp_path, capsys, text, words):
    model = tmp_path / "bad.toml"
    model.write_text(text)
    out = tmp_path / "o.csv"
    assert main(["mechanism", "analyze", str(model), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err
    assert not out.exists()


def test_caps_are_enforced(tmp_path, capsys):
    assert main(["mechanism", "analyze", str(EXAMPLES / "fourbar.toml"), "--points", "100001"]) == 2
    assert (
        main(
            [
                "mechanism",
                "animate",
                str(EXAMPLES / "fourbar.toml"),
                "--out",
                str(tmp_path / "a.gif"),
                "--frames",
                "361",
            ]
        )
        == 2
    )
    err = capsys.readouterr().err.splitlines()
    assert "at most 100000" in err[0] and "at most 360" in err[1]
    assert not (tmp_path / "a.gif").exists()


def test_draw_and_animate_write_files(tmp_path):
    png, gif = tmp_path / "m.png", tmp_path / "m.gif"
    assert main(["mechanism", "draw", str(EXAMPLES / "geared_fivebar.toml"), "--out", str(png), "--points", "40"]) == 0
    assert main(["mechanism", "animate", str(EXAMPLES / "slider_crank.toml"), "--out", str(gif), "--frames", "4"]) == 0
    assert png.read_bytes()[:4] == b"\x89PNG" and gif.read_bytes()[:3] == b"GIF"
