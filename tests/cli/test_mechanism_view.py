"""``gearlever mechanism view`` and ``analyze --centres``: files written, refusals in one line (exit 2)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.mechanism import Mechanism
from gearlever.mechanism.centres import instant_centres

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def test_view_writes_one_self_contained_page(tmp_path):
    out = tmp_path / "w.html"
    assert main(["mechanism", "view", str(EXAMPLES / "watt_sixbar.toml"), "--out", str(out), "--frames", "24"]) == 0
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>") and '"N":24' in page.replace(" ", "")
    assert "http" not in page


def test_view_two_inputs_with_rpm_and_held_input(tmp_path):
    out = tmp_path / "z.html"
    args = ["mechanism", "view", str(EXAMPLES / "zrdpm_gear_contour.toml"), "--out", str(out), "--frames", "12"]
    assert main(args + ["--rpm", "gear9=100", "--rpm", "lever1=-30", "--input", "lever1=90"]) == 0
    text = out.read_text(encoding="utf-8")
    data = json.loads(text.split('type="application/json">', 1)[1].split("</script>", 1)[0])
    assert data["grid"]["values"][0] == pytest.approx(np.pi / 2)
    assert data["period"] == pytest.approx(0.6)


@pytest.mark.parametrize(
    "extra, flag",
    [
        (["--out", "x.png"], "--out"),
        (["--out", "x.html", "--frames", "100000"], "--frames"),
        (["--out", "x.html", "--frames", "1"], "--frames"),
        (["--out", "x.html", "--input", "crnk=3"], "--input"),
        (["--out", "x.html", "--rpm", "a=1", "--rpm", "b=2"], "--rpm"),
    ],
)
def test_view_refusals_are_one_line_naming_the_flag(tmp_path, capsys, extra, flag, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(SystemExit) as e:
        rc = main(["mechanism", "view", str(EXAMPLES / "fourbar.toml"), *extra])
        raise SystemExit(rc)
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and flag in err
    assert not list(tmp_path.iterdir())


def test_view_rpm_must_give_the_first_input(tmp_path, capsys):
    out = tmp_path / "z.html"
    rc = main(["mechanism", "view", str(EXAMPLES / "zrdpm_gear_contour.toml"), "--out", str(out), "--rpm", "lever1=3"])
    assert rc == 2 and "gear9" in capsys.readouterr().err and not out.exists()


def test_analyze_centres_adds_the_instant_centre_columns(tmp_path):
    out = tmp_path / "a.json"
    model = str(EXAMPLES / "fourbar.toml")
    args = ["mechanism", "analyze", model, "--points", "8", "--centres", "--format", "json"]
    assert main(args + ["--out", str(out)]) == 0
    rows = json.loads(out.read_text())["rows"]
    mech = Mechanism.load(EXAMPLES / "fourbar.toml")
    ic = instant_centres(mech.solve(mech.sketch_inputs[0] + np.linspace(0, 2 * np.pi, 8, endpoint=False)))
    k = ic.pairs.index("ground/coupler")
    got = [r["ic_ground/coupler_x_mm"] for r in rows]
    np.testing.assert_allclose(got, ic.xy[:, k, 0], rtol=1e-11)
    assert rows[0]["ic_coupler/rocker_x_mm"] is None  # equal angular velocities at the sketch: at infinity
