"""CLI tests: gearlever hooke (degrees at the command line, strict JSON, flags in errors)."""

import json
import math

import pytest

from gearlever.cli import main


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_hooke_json_single_and_double(capsys):
    recs = _json(capsys, ["hooke", "--shaft-angle", "60", "--input-angle", "0", "90", "--format", "json"])
    assert [r["input_deg"] for r in recs] == [0.0, 90.0]
    # extremes 1/cos 60 = 2 and cos 60 = 0.5 (the classic text, section 70)
    assert recs[0]["ratio"] == pytest.approx(2.0) and recs[1]["ratio"] == pytest.approx(0.5)
    recs = _json(capsys, ["hooke", "--shaft-angle", "30", "--second-angle", "30", "--format", "json"])
    assert len(recs) == 25 and all(r["ratio"] == pytest.approx(1.0) for r in recs)
    assert all(r["output_deg"] == pytest.approx(r["input_deg"], abs=1e-9) for r in recs)


def test_hooke_json_is_strict_and_in_degrees(capsys):
    assert main(["hooke", "--shaft-angle", "45", "--input-angle", "30", "--format", "json"]) == 0
    out_text = capsys.readouterr().out
    assert "NaN" not in out_text and "Infinity" not in out_text
    rec = json.loads(out_text)[0]
    psi = math.degrees(math.atan(math.tan(math.radians(30)) / math.cos(math.radians(45))))
    assert rec["output_deg"] == pytest.approx(psi, rel=1e-12)


def test_hooke_table(capsys):
    assert main(["hooke", "--shaft-angle", "30", "--second-angle", "20", "--phase", "90", "--input-angle", "0"]) == 0
    assert "double coupling" in capsys.readouterr().out


@pytest.mark.parametrize(
    "argv, word",
    [
        (["hooke", "--shaft-angle", "90"], "--shaft-angle"),
        (["hooke", "--shaft-angle", "-1"], "--shaft-angle"),
        (["hooke", "--shaft-angle", "30", "--second-angle", "120"], "--second-angle"),
        (["hooke", "--shaft-angle", "nan"], "--shaft-angle"),
        (["hooke", "--shaft-angle", "30", "--phase", "10"], "--phase"),
        (["hooke", "--shaft-angle", "30", "--phase", "inf", "--second-angle", "10"], "--phase"),
        (["hooke", "--shaft-angle", "30", "--input-angle", "x"], "--input-angle"),
        (["hooke", "--shaft-angle", "30", "--input-angle"] + ["1"] * 10_001, "--input-angle takes at most 10,000"),
    ],
)
def test_bad_input_exits_2_with_one_line_naming_the_flag(capsys, argv, word):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and word in err and "Traceback" not in err
    assert "shaft_angle" not in err and "second_angle" not in err
