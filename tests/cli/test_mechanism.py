"""``gearlever mechanism``: outputs, strict JSON, exit 2 with one stderr line, no partial files."""

from __future__ import annotations

import json
import math
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
    assert len(lines) == 13 and lines[0].startswith("input_crank_deg,qdot_crank_per_crank,")
    assert "omega_coupler_per_crank" in lines[0] and "v_P_x_mm_per_crank" in lines[0]
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
    assert len(d["rows"]) == 5 and d["rows"][-1]["input_gear9_deg"] == 90.0


def test_a_rocking_input_sweeps_one_oscillation_and_a_range_past_its_limits_is_refused(tmp_path, capsys):
    model = tmp_path / "tr.toml"
    model.write_text(
        "[points]\nO2 = [0, 0]\nO4 = [10, 0]\nA = [0, 8]\nB = [3, 12]\n"
        '[links]\nground = ["O2", "O4"]\ncrank = ["O2", "A"]\ncoupler = ["A", "B"]\nrocker = ["O4", "B"]\n'
        '[[inputs]]\nlink = "crank"\n'
    )
    assert main(["mechanism", "analyze", str(model), "--points", "36", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    rows = json.loads(out)["rows"]
    assert len(rows) == 36 and all(r["closed"] for r in rows)
    # crank 8, ground 10, coupler 5, rocker |O4 B| = sqrt(193): dead points where coupler and rocker fold onto
    # each other, |A O4| = c - b (law of cosines), symmetric about 180 deg (b + c > 18 never binds)
    b, c = 5.0, math.sqrt(193.0)
    lo = math.degrees(math.acos((64 + 100 - (c - b) ** 2) / 160))
    hi = 360.0 - lo
    assert err.strip() == f"crank rocks between {lo:.3f} and {hi:.3f} deg: sweeping one oscillation"
    angles = [r["input_crank_deg"] for r in rows]
    assert lo - 1e-9 < min(angles) and max(angles) < hi + 1e-9
    d = [r["direction"] for r in rows]
    assert d[0] == 1 and set(d) == {1, -1} and [r["qdot_crank_per_crank"] for r in rows] == d
    # direction flips twice (at each limit): +1 ... -1 ... +1
    assert sum(1 for x, y in zip(d, d[1:]) if x != y) == 2
    assert main(["mechanism", "analyze", str(model), "--input", "30", "200"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"between {lo:.3f} and {hi:.3f} deg" in err and "--input 30 200" in err


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


def _rows(capsys):
    return json.loads(capsys.readouterr().out)["rows"]


def test_sweep_rule_full_turn_excludes_the_end_and_a_range_includes_it(capsys):
    model = str(EXAMPLES / "fourbar.toml")
    assert main(["mechanism", "analyze", model, "--format", "json"]) == 0
    rows = _rows(capsys)
    assert len(rows) == 360 and rows[0]["input_crank_deg"] == 0.0 and rows[-1]["input_crank_deg"] == 359.0
    assert main(["mechanism", "analyze", model, "--points", "5", "--input", "10", "50", "--format", "json"]) == 0
    assert [r["input_crank_deg"] for r in _rows(capsys)] == pytest.approx([10.0, 20.0, 30.0, 40.0, 50.0], abs=1e-12)


def test_draw_uses_the_same_default_count_as_analyze():
    from gearlever.cli import build_parser

    p = build_parser()
    d = p.parse_args(["mechanism", "draw", "m.toml", "--out", "m.png"])
    a = p.parse_args(["mechanism", "analyze", "m.toml"])
    assert d.points == a.points == 360


def test_two_input_model_sweeps_the_first_input_and_holds_the_other_without_input(capsys):
    # gear 9 turns a full turn, lever 1 stays at the sketch: gear 8 turns at -z9/z8 = -20/25 (Willis, carrier still)
    assert (
        main(["mechanism", "analyze", str(EXAMPLES / "zrdpm_gear_contour.toml"), "--points", "8", "--format", "json"])
        == 0
    )
    rows = _rows(capsys)
    assert len(rows) == 8 and all(r["closed"] for r in rows)
    assert all(r["input_lever1_deg"] == 0.0 and r["qdot_lever1_per_gear9"] == 0.0 for r in rows)
    assert all(abs(r["omega_gear8_per_gear9"] + 20 / 25) < 1e-12 for r in rows)
    assert abs(rows[1]["gear8_angle_deg"] + 45.0 * 20 / 25) < 1e-9


def test_draw_of_a_two_input_model_with_one_range_names_what_is_missing(tmp_path, capsys):
    png = tmp_path / "z.png"
    model = str(EXAMPLES / "zrdpm_gear_contour.toml")
    assert main(["mechanism", "draw", model, "--out", str(png), "--input", "0", "90"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and not png.exists()
    assert "--input: model 'ZRDPM gear contour 9-8 on lever 1' has 2 inputs (gear9, lever1); " in err
    assert "give --input [NAME=]START STOP once per input" in err
    assert main(["mechanism", "draw", model, "--out", str(png), "--points", "24"]) == 0
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_input_ranges_named_after_the_inputs_in_any_order_equal_the_ordered_ones(capsys):
    model = str(EXAMPLES / "zrdpm_gear_contour.toml")
    base = ["mechanism", "analyze", model, "--points", "5", "--format", "csv"]
    outs = []
    for extra in (
        ["--input", "0", "360", "--input", "0", "60"],
        ["--input", "gear9=0", "360", "--input", "lever1=0", "60"],
        ["--input", "lever1=0", "60", "--input", "gear9=0", "360"],
    ):
        assert main([*base, *extra]) == 0
        outs.append(capsys.readouterr().out)
    assert outs[0] == outs[1] == outs[2]
    assert "input_lever1_deg" in outs[0]
    rows = [ln.split(",") for ln in outs[0].splitlines()]
    col = rows[0].index("input_lever1_deg")
    assert [float(r[col]) for r in rows[1:]] == pytest.approx([0, 15, 30, 45, 60], abs=1e-12)


@pytest.mark.parametrize(
    "extra, words",
    [
        (["--input", "gear9=0", "360"], ["missing: lever1"]),
        (["--input", "gear9=0", "360", "--input", "0", "60"], ["name every input"]),
        (["--input", "gear9=0", "360", "--input", "lever=0", "60"], ["unknown input 'lever'", "did you mean 'lever1'"]),
        (["--input", "gear9=0", "360", "--input", "gear9=0", "60"], ["'gear9' given twice"]),
        (["--input", "=0", "360", "--input", "0", "60"], ["--input", "name must come before '='"]),
        (["--input", "gear9=x", "360", "--input", "lever1=0", "60"], ["--input", "number"]),
    ],
)
def test_named_input_ranges_refused_in_one_line(capsys, extra, words):
    model = str(EXAMPLES / "zrdpm_gear_contour.toml")
    assert main(["mechanism", "analyze", model, "--points", "3", *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    for w in words:
        assert w in err, err


def test_rpm_gives_velocities_in_time_named_as_such(capsys):
    model = str(EXAMPLES / "fourbar.toml")
    assert main(["mechanism", "analyze", model, "--points", "6", "--format", "json"]) == 0
    ana = _rows(capsys)
    assert main(["mechanism", "analyze", model, "--points", "6", "--rpm", "120", "--format", "json"]) == 0
    vel = _rows(capsys)
    w = 120 * 2 * 3.141592653589793 / 60
    assert "omega_coupler_per_crank" in ana[0] and "omega_coupler_rad_s" not in ana[0]
    for a, v in zip(ana, vel):
        assert abs(v["qdot_crank_rad_s"] - w) < 1e-10
        assert abs(v["omega_coupler_rad_s"] - w * a["omega_coupler_per_crank"]) < 1e-9
        assert abs(v["v_P_x_mm_s"] - w * a["v_P_x_mm_per_crank"]) < 1e-9
        assert abs(v["a_P_y_mm_s2"] - w * w * a["a_P_y_mm_per_crank_sq"]) < 1e-6


def test_rpm_per_input_of_a_two_input_model(capsys):
    model = str(EXAMPLES / "zrdpm_gear_contour.toml")
    argv = ["mechanism", "analyze", model, "--points", "3", "--rpm", "gear9=100", "--rpm", "lever1=-30"]
    assert main(argv + ["--format", "json"]) == 0
    rows = _rows(capsys)
    w9, w1 = 100 * 3.141592653589793 / 30, -30 * 3.141592653589793 / 30
    # Willis: (w8 - w1) / (w9 - w1) = -z9 / z8
    for r in rows:
        assert abs(r["omega_gear8_rad_s"] - (w1 - 20 / 25 * (w9 - w1))) < 1e-9
    assert main(argv[:-2] + ["--rpm", "lever2=1"]) == 2
    assert "--rpm: unknown input 'lever2' (inputs: gear9, lever1)" in capsys.readouterr().err


def test_slider_input_oscillates_between_its_dead_points_or_takes_a_range(tmp_path, capsys):
    """A piston driving a slider-crank stops at the crank's dead centres: one oscillation, as PMKS+ sweeps it."""
    text = (EXAMPLES / "slider_crank.toml").read_text()
    text = text.replace('[[inputs]]\nlink = "crank"', '[[inputs]]\nslider = "piston"')
    model = tmp_path / "sc.toml"
    model.write_text(text)
    assert main(["mechanism", "analyze", str(model), "--points", "40", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    assert err.count("\n") == 1 and "piston rocks between" in err and "one oscillation" in err
    rows = json.loads(out)["rows"]
    x = [r["input_piston_mm"] for r in rows]
    # closed form of the offset slider-crank (crank 10, rod 35, offset 5): x_B = sqrt((L +- r)^2 - e^2)
    x0 = math.sqrt(35**2 - 5**2) + 10  # the sketch: crank along +x, B at x = 10 + sqrt(35^2 - 5^2)
    lo, hi = math.sqrt(25**2 - 5**2) - x0, math.sqrt(45**2 - 5**2) - x0
    assert min(x) >= lo - 1e-9 and max(x) <= hi + 1e-9 and min(x) < lo + 2 and max(x) > hi - 2
    assert {r["direction"] for r in rows} == {1, -1}
    assert main(["mechanism", "analyze", str(model), "--points", "3", "--input", "0", "-10", "--format", "json"]) == 0
    rows = _rows(capsys)
    assert [r["input_piston_mm"] for r in rows] == [0.0, -5.0, -10.0]
    assert all(r["qdot_piston_mm_per_piston"] == 1.0 for r in rows) and "omega_rod_per_piston" in rows[0]


ROCKS = "AB rocks between 67.284 and 78.254 deg: sweeping one oscillation\n"


def test_watt_i_oscillates_in_analyze_with_a_direction_column_and_the_rpm_as_a_speed(capsys):
    model = str(EXAMPLES / "watt_i.toml")
    assert main(["mechanism", "analyze", model, "--points", "24", "--rpm", "10", "--format", "json"]) == 0
    out, err = capsys.readouterr()
    assert err == ROCKS
    rows = json.loads(out)["rows"]
    assert all(r["closed"] for r in rows) and len(rows) == 24
    w = 10 * math.pi / 30
    assert [r["qdot_AB_rad_s"] for r in rows] == [pytest.approx(w * r["direction"], rel=1e-11) for r in rows]
    assert {r["direction"] for r in rows} == {1, -1}
    assert min(r["input_AB_deg"] for r in rows) > 67.2836 and max(r["input_AB_deg"] for r in rows) < 78.2542


@pytest.mark.parametrize(
    "extra",
    [["--input", "AB=67.2815", "67.2815", "--points", "1"], ["--input", "60", "75"], ["--input", "AB=70", "80"]],
)
def test_a_range_past_the_limits_is_refused_in_one_line_naming_them(extra, capsys):
    assert main(["mechanism", "analyze", str(EXAMPLES / "watt_i.toml"), *extra]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and "moves only between 67.284 and 78.254 deg" in err
    assert "NaN" not in err and "nan" not in err


def test_a_model_locked_at_its_sketch_is_refused_naming_the_binding_links(tmp_path, capsys):
    model = tmp_path / "locked.toml"
    model.write_text(
        '[points]\nO2 = [0, 0]\nO4 = [4, 0]\nA = [-1, 0]\nB = [5, 0]\n[links]\nground = ["O2", "O4"]\n'
        'crank = ["O2", "A"]\ncoupler = ["A", "B"]\nrocker = ["O4", "B"]\n[[inputs]]\nlink = "crank"\n'
    )
    for cmd in (["analyze"], ["draw", "--out", str(tmp_path / "x.png")], ["forces"]):
        assert main(["mechanism", cmd[0], str(model), *cmd[1:]]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and "dead point of the links coupler, rocker" in err
    assert not (tmp_path / "x.png").exists()


def test_watt_i_draws_and_animates_one_oscillation(tmp_path, capsys):
    png, gif = tmp_path / "w.png", tmp_path / "w.gif"
    assert main(["mechanism", "draw", str(EXAMPLES / "watt_i.toml"), "--out", str(png), "--points", "60"]) == 0
    assert main(["mechanism", "animate", str(EXAMPLES / "watt_i.toml"), "--out", str(gif), "--frames", "6"]) == 0
    assert capsys.readouterr().err == ROCKS * 2
    assert png.stat().st_size > 0 and gif.stat().st_size > 0
