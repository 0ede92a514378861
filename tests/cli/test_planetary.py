"""CLI runs: gearlever planetary design (table, JSON, limits, bad input)."""

import json
from fractions import Fraction

import pytest

from gearlever.cli import main
from gearlever.gears.planetary import design_planetary


def test_planetary_design_json_equals_the_python_api(capsys):
    args = ["planetary", "design", "--ratio", "9/2", "--planets", "3", "--max-teeth", "100", "--format", "json"]
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    api = design_planetary(Fraction(9, 2), 3, max_teeth=100, limit=20)
    assert data["candidates"] == api.candidates and data["count"] == api.count
    assert [(s["sun"], s["planet"], s["ring"], s["ratio"]) for s in data["solutions"]] == [
        (s.sun, s.planet, s.ring, f"{s.ratio.numerator}/{s.ratio.denominator}") for s in api.solutions
    ]
    assert all(s["error"] == 0.0 for s in data["solutions"])


def test_planetary_compound_json_keys_and_limit(capsys):
    args = ["planetary", "design", "--ratio", "9", "--planets", "3", "--kind", "compound", "--max-teeth", "60"]
    assert main([*args, "--format", "json", "--limit", "1"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["solutions"]) == 1 and data["count"] > 1
    assert {"sun", "planet1", "planet2", "ring", "ratio", "error"} <= set(data["solutions"][0])
    assert main([*args, "--limit", "2"]) == 0
    out = capsys.readouterr().out
    assert f"{data['count']} set(s), first 2 shown" in out


def test_planetary_unreachable_target_prints_a_note(capsys):
    assert main(["planetary", "design", "--ratio", "1.5", "--planets", "3", "--max-teeth", "80"]) == 0
    assert "note: the target 3/2 is outside the ratios" in capsys.readouterr().out


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--planets", "1"], "--planets must be an integer in [2, 64]"),
        (["--planets", "3", "--min-teeth", "0"], "--min-teeth must be an integer >= 1"),
        (["--planets", "3", "--min-teeth", "-4"], "--min-teeth must be an integer >= 1"),
        (["--planets", "3", "--min-teeth", "60", "--max-teeth", "50"], "tooth range is empty"),
        (["--planets", "3", "--max-teeth", "2001"], "--max-teeth must be at most 2000"),
        (["--planets", "3", "--kind", "compound", "--max-teeth", "400"], "--max-teeth must be at most 300"),
        (["--planets", "3", "--fixed", "sun", "--input", "sun"], "different members"),
        (["--planets", "3", "--limit", "0"], "--limit"),
        (["--planets", "x"], "--planets"),
    ],
)
def test_planetary_bad_input_exit_2_one_line(capsys, extra, needle):
    assert main(["planetary", "design", "--ratio", "4", *extra]) == 2
    err = capsys.readouterr().err
    assert needle in err and len(err.strip().splitlines()) == 1
