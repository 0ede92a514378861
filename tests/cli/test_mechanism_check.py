"""``gearlever mechanism check``: text and strict JSON for every shipped example with gears; bad input exits 2."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from gearlever.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
GEARED = ["geared_fivebar", "planetary", "compound_planetary", "ferguson", "zrdpm_gear_contour"]


@pytest.mark.parametrize("name", GEARED)
def test_check_every_shipped_example_with_gears(name, capsys):
    assert main(["mechanism", "check", str(EXAMPLES / f"{name}.toml"), "--points", "24", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["meshes"] and all(m["sketch"]["contact_ratio_total"] > 1 for m in d["meshes"])
    assert main(["mechanism", "check", str(EXAMPLES / f"{name}.toml"), "--points", "24"]) == 0
    text = capsys.readouterr().out
    assert text.count("\nmesh ") == len(d["meshes"]) and "contact ratio" in text


def test_check_zrdpm_over_the_adjusting_slide(capsys):
    model = str(EXAMPLES / "zrdpm_gear_contour.toml")
    assert main(["mechanism", "check", model, "--center-distance", "z9-z8=44:49", "--points", "51", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    (m,) = d["meshes"]
    assert m["over"] == "adjustment" and m["range"]["center_distance"] == [44, 49]
    assert m["range"]["least_backlash"]["center_distance"] == 44 and m["range"]["backlash"][0] < 0
    assert not d["ok"] and any(f.startswith("jams") for f in m["flags"])


@pytest.mark.parametrize(
    "args, words",
    [
        (["--center-distance", "z8-z9=44:49"], "--center-distance: unknown mesh 'z8-z9'"),
        (["--center-distance", "z9-z8=44"], "--center-distance must be MESH=START:STOP"),
        (["--center-distance", "z9-z8=-1:49"], "must be positive"),
        (["--points", "1"], "--points"),
        (["--points", "1e9"], "--points"),
    ],
)
def test_bad_input_exits_2_with_one_line(args, words, capsys):
    assert main(["mechanism", "check", str(EXAMPLES / "zrdpm_gear_contour.toml"), *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err
