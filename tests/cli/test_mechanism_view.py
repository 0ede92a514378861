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
    # 12 digits of the column's largest value (gearlever._format): zero up to rounding is written 0
    np.testing.assert_allclose(got, ic.xy[:, k, 0], rtol=0, atol=1e-11 * np.abs(ic.xy[:, k, 0]).max())
    assert rows[0]["ic_coupler/rocker_x_mm"] is None  # equal angular velocities at the sketch: at infinity


def test_analyze_centres_csv_leaves_a_centre_at_infinity_empty_as_the_viewer_guide_says(tmp_path):
    import csv

    out = tmp_path / "a.csv"
    args = ["mechanism", "analyze", str(EXAMPLES / "slider_crank.toml"), "--points", "3", "--centres"]
    assert main(args + ["--out", str(out)]) == 0
    rows = list(csv.DictReader(out.open()))
    assert "nan" not in out.read_text()
    assert rows[0]["ic_ground/piston_x_mm"] == "" and rows[0]["ic_ground/piston_y_mm"] == ""  # a slider's centre
    assert float(rows[0]["ic_crank/rod_x_mm"]) == pytest.approx(10.0)  # the pin A


def _chain_toml(path: Path, dyads: int) -> Path:
    """A crank driving ``dyads`` RR dyads, each on its own ground pivot (2 dyads + 1 moving links)."""
    lines = ['[mechanism]\nunits = "mm"\n[points]\nO = [0.0, 0.0]\nA = [10.0, 0.0]']
    links = ['crank = ["O", "A"]']
    ground = ['"O"']
    for i in range(dyads):
        t = 0.3 * np.sin(i)
        g = np.array([40 * np.cos(t), 40 * np.sin(t)])
        a = np.array([10.0, 0.0])
        d = g - a
        dist = float(np.hypot(*d))
        along = (35.0**2 - 30.0**2 + dist**2) / (2 * dist)
        c = a + along * d / dist + np.sqrt(35.0**2 - along**2) * np.array([-d[1], d[0]]) / dist
        lines.append(f"G{i} = [{float(g[0])!r}, {float(g[1])!r}]\nC{i} = [{float(c[0])!r}, {float(c[1])!r}]")
        ground.append(f'"G{i}"')
        links.append(f'cp{i} = ["A", "C{i}"]\nrk{i} = ["G{i}", "C{i}"]')
    text = "\n".join([*lines, "[links]", f"ground = [{', '.join(ground)}]", *links, '[[inputs]]\nlink = "crank"\n'])
    path.write_text(text, encoding="utf-8")
    return path


@pytest.mark.parametrize(
    "model, extra, needle",
    [
        ("fourbar", ["--input", "crank=1e10"], "--input: crank is 2.78e+07 turns from its sketch value"),
        ("fourbar", ["--input", "crank=1e308"], "--input: crank is"),
        ("chain101", ["--frames", "3600"], "--frames: 3600 frames x 101 moving links"),
        ("fivebar_two_inputs", ["--frames", "3600"], "--frames: 3600 frames x 24 values of right x 4 moving links"),
        ("chain999", ["--frames", "2"], "[links] has 999 moving links, more than the viewer's cap of 150"),
    ],
)
def test_view_work_caps_refuse_before_solving_in_one_line(tmp_path, capsys, monkeypatch, model, extra, needle):
    # refused before anything is solved (the solver is replaced by a failure): no time, no memory spent
    def boom(*a, **k):
        raise AssertionError("solved before the cap refused")

    monkeypatch.setattr(Mechanism, "solve", boom)
    if model.startswith("chain"):
        path = _chain_toml(tmp_path / f"{model}.toml", (int(model[5:]) - 1) // 2)
    else:
        path = EXAMPLES / f"{model}.toml"
    out = tmp_path / "v.html"
    rc = main(["mechanism", "view", str(path), "--out", str(out), *extra])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and needle in err, err
    assert "Traceback" not in err and not out.exists()
    if model == "chain999":
        assert str(path) in err


def test_view_of_a_rocking_input_sweeps_one_oscillation(tmp_path, capsys):
    out = tmp_path / "w.html"
    model = str(Path(__file__).resolve().parents[2] / "examples" / "watt_i.toml")
    assert main(["mechanism", "view", model, "--out", str(out), "--frames", "40", "--rpm", "10"]) == 0
    assert capsys.readouterr().err == "AB rocks between 67.284 and 78.254 deg: sweeping one oscillation\n"
    from gearlever.plotting.viewer import viewer_data

    d = viewer_data(Mechanism.load(model), frames=40, rpm=10)
    assert d["closed"] == "1" * 40 and set(d["osc"]["dir"]) == {1, -1}
    assert np.degrees(min(d["osc"]["q"])) > 67.2836 and np.degrees(max(d["osc"]["q"])) < 78.2542
    assert d["period"] == pytest.approx(2 * (d["osc"]["upper"] - d["osc"]["lower"]) / (10 * np.pi / 30))
    assert '"osc"' in out.read_text()
