"""``gearlever synthesize law`` and ``gearlever mechanism law``: model, report, figure, refusals (one line, exit 2),
the written model reproducing the reported law.

Run through :func:`gearlever.cli.main` (its error handling included).
"""

from __future__ import annotations

import json
import math
import tomllib

import numpy as np
import pytest

import gearlever.cli as cli
from gearlever.mechanism import Mechanism
from gearlever.synthesis.law.measure import mechanism_law

DWELL = """[law]
output = "angle"
units = "deg"
[[law.segment]]
to = 120
motion = "dwell"
[[law.segment]]
to = 240
motion = "cycloidal"
rise = 45
[[law.segment]]
to = 360
motion = "345"
rise = -45
"""

STROKE = """[law]
output = "displacement"
units = "mm"
[[law.segment]]
to = 180
motion = "harmonic"
rise = 40
[[law.segment]]
to = 360
motion = "harmonic"
rise = -40
"""


@pytest.fixture
def run(capsys):
    def go(*argv):
        code = cli.main([*map(str, argv)])
        out, err = capsys.readouterr()
        return code, out, err

    return go


def test_writes_model_report_and_figure_and_the_model_reproduces_the_law(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out, rep, fig = tmp_path / "m.toml", tmp_path / "r.json", tmp_path / "f.png"
    code, text, err = run(
        "synthesize", "law", law, "--type", "geared-fourbar", "--out", out, "--report", rep, "--figure", fig,
        "--budget", 2000, "--workers", 1,
    )  # fmt: skip
    assert code == 0, err
    assert "error            max" in text and "teeth" in text
    model = tomllib.loads(out.read_text())
    assert "output" in model["links"] and model["meshes"][0]["carrier"] == "rocker"
    r = json.loads(rep.read_text())
    assert r["kind"] == "geared-fourbar" and r["feasible"] and r["seed"] == 0
    assert [s["motion"] for s in r["segments"]] == ["dwell", "cycloidal", "345"]
    assert r["transmission_deg"][0] >= 20 - 1e-6
    assert r["cam"]["available"] and r["cam"]["follower"] == "oscillating-roller" and r["cam"]["error_max"] == 0.0
    assert r["cam"]["pressure_angle_max_deg"] == pytest.approx(30.0, abs=1e-6)
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the written model, turned by the engine, gives the achieved law: its error against the law is the report's
    ml = mechanism_law(Mechanism.load(out), "output", 3600)
    from gearlever.laws import load_law

    want = load_law(law).evaluate(ml.theta).s
    achieved = ml.s + math.radians(r["output_at_input_0_deg"])  # the model's rotation from its sketch, zeroed
    err_max = float(np.degrees(np.abs(achieved - want).max()))
    # the model is written at 10 digits of its size (gearlever._format): its law differs from the design's by less
    assert err_max == pytest.approx(r["error_max_deg"], abs=1e-5)


def test_slider_crank_for_a_stroke_law_and_mechanism_law_reads_it_back(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(STROKE)
    out = tmp_path / "m.toml"
    code, _, err = run("synthesize", "law", law, "--type", "slider-crank", "--out", out, "--budget", 2000)
    assert code == 0, err
    code, text, err = run("mechanism", "law", out, "--output", "output", "--format", "json")
    assert code == 0, err
    r = json.loads(text)
    assert r["kind"] == "displacement" and r["net_change"] == 0.0
    assert r["range"] == pytest.approx(40.0, rel=0.05)
    assert [s["motion"] for s in r["segments"]] in (["rise", "return"], ["return", "rise"])
    code, text, _ = run("mechanism", "law", out, "--output", "output")
    assert code == 0 and "segments         2" in text


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--type", "slider-crank"], "LAW"),
        (["--type", "fourbar", "--min-transmission", "95"], "--min-transmission"),
        (["--type", "geared-fourbar", "--teeth", "40", "20"], "--teeth"),
        (["--type", "cam"], "--type"),
        (["--type", "fourbar", "--budget", "5"], "--budget"),
    ],
)
def test_refusals_are_one_line_naming_the_flag_or_file(tmp_path, run, argv, words):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out = tmp_path / "m.toml"
    code, _, err = run("synthesize", "law", law, "--out", out, *argv)
    assert code == 2
    assert words in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not out.exists()


def test_net_rotation_is_refused_for_a_rocker_and_met_by_gears_as_a_whole_multiple(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text('[law]\noutput = "angle"\nunits = "deg"\n[[law.segment]]\nto = 360\nmotion = "linear"\nrise = 720\n')
    out = tmp_path / "m.toml"
    code, _, err = run("synthesize", "law", law, "--type", "fourbar", "--out", out, "--budget", 200)
    assert code == 2 and "LAW" in err and "returns to its start" in err and not out.exists()
    code, _, err = run("synthesize", "law", law, "--type", "geared-fourbar", "--out", out, "--budget", 2000)
    assert code == 0, err
    ml = mechanism_law(Mechanism.load(out), "output", 720)
    assert ml.net == pytest.approx(4 * math.pi, rel=1e-12)
    law.write_text(
        '[law]\noutput = "angle"\nunits = "deg"\n[[law.segment]]\nto = 360\nmotion = "linear"\nrise = 500.5\n'
    )
    code, _, err = run("synthesize", "law", law, "--type", "geared-fourbar", "--out", out, "--budget", 200)
    assert code == 2 and "no such teeth" in err


def test_mechanism_law_refuses_an_unknown_output(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out = tmp_path / "m.toml"
    assert run("synthesize", "law", law, "--type", "fourbar", "--out", out, "--budget", 500)[0] == 0
    code, _, err = run("mechanism", "law", out, "--output", "rockr")
    assert code == 2 and "--output" in err and "rockr" in err


@pytest.mark.parametrize("kind", ["fourbar", "geared-fourbar", "sixbar-dwell", "gear-lever"])
def test_the_written_model_opens_in_analyze_draw_view_and_forces(tmp_path, run, kind):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out = tmp_path / "m.toml"
    assert run("synthesize", "law", law, "--type", kind, "--out", out, "--budget", 600)[0] == 0
    code, text, err = run("mechanism", "analyze", out, "--points", 36)
    assert code == 0, err
    assert "output_angle_deg" in text.splitlines()[0]
    assert run("mechanism", "draw", out, "--out", tmp_path / "d.png")[0] == 0
    assert run("mechanism", "view", out, "--out", tmp_path / "v.html")[0] == 0
    code, _, err = run("mechanism", "forces", out, "--points", 36)
    assert code == 0, err


def test_auto_tries_every_angle_kind_and_ranks_them(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    code, text, err = run("synthesize", "law", law, "--type", "auto", "--out", out, "--report", rep, "--budget", 600)
    assert code == 0, err
    r = json.loads(rep.read_text())
    tried = r["types_tried"]
    assert set(tried) == {
        "fourbar",
        "slider-crank",
        "geared-fourbar",
        "sixbar-dwell",
        "gear-lever",
        "slotted-lever",
        "sixbar-slider",
    }
    assert tried["slider-crank"] is None and tried["sixbar-slider"] is None  # an angle law: no slider
    best = min(v for v in tried.values() if v is not None)
    assert tried[r["kind"]] == best and "tried" in text
    # why a kind was not tried: one reason per kind, in the report and the table (never "-")
    why = r["types_not_tried"]
    assert set(why) == {k for k, v in tried.items() if v is None}
    for k in why:
        assert why[k] == "a " + k + " gives an output displacement, the law is angle"
        assert f"not tried        {k}: {why[k]}" in text
    assert " -" not in text.splitlines()[0]


def test_the_same_model_bytes_for_one_or_two_workers(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    a, b = tmp_path / "a.toml", tmp_path / "b.toml"
    assert run("synthesize", "law", law, "--type", "fourbar", "--out", a, "--budget", 800, "--workers", 1)[0] == 0
    assert run("synthesize", "law", law, "--type", "fourbar", "--out", b, "--budget", 800, "--workers", 2)[0] == 0
    assert a.read_bytes() == b.read_bytes()


def test_an_unreachable_scheduler_is_refused_naming_the_flag(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out = tmp_path / "m.toml"
    code, _, err = run(
        "synthesize", "law", law, "--type", "fourbar", "--out", out, "--budget", 200, "--scheduler", "tcp://127.0.0.1:9"
    )
    assert code == 2 and "--scheduler" in err and len(err.strip().splitlines()) == 1 and not out.exists()


def test_gear_lever_report_has_teeth_module_and_the_slide_sweep(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text(DWELL)
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    code, text, err = run(
        "synthesize", "law", law, "--type", "gear-lever", "--out", out, "--report", rep, "--budget", 600
    )
    assert code == 0, err
    r = json.loads(rep.read_text())
    d = r["design"]
    assert d["variant"] == "held" and all(17 <= z <= 120 for z in d["teeth"].values())
    rows = d["slide_range"]
    assert [x["centre_distance"] for x in rows] == pytest.approx(np.linspace(90, 110, 9).tolist())
    mid = rows[4]
    assert mid["feasible"] and mid["error_max_deg"] == pytest.approx(r["error_max_deg"], rel=0.05)
    assert "slide (err max)" in text and "teeth" in text
    m = tomllib.loads(out.read_text())
    assert m["gears"]["g9"]["link"] == "ground" and m["meshes"][0]["carrier"] == "lever"


def test_gear_lever_refuses_a_net_rotation_no_teeth_give(tmp_path, run):
    law = tmp_path / "law.toml"
    law.write_text('[law]\noutput = "angle"\nunits = "deg"\n[[law.segment]]\nto = 360\nmotion = "linear"\nrise = 360\n')
    code, _, err = run("synthesize", "law", law, "--type", "gear-lever", "--out", tmp_path / "m.toml")
    assert code == 2 and "LAW" in err and "z9/z8" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "m.toml").exists()
