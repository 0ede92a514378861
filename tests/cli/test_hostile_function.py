"""Hostile pass over ``gearlever synthesize function`` (issue 25): every combination of signs and ranges.

Each run either writes a model, report and figure whose structural error is the written model's
(recomputed here from the file by circle intersection, not by the engine), or exits 2 with one line
and writes nothing; never exit 1, never null or NaN in a report.
"""

import json
import tempfile
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from gearlever.cli import main
from gearlever.synthesis.function import DENSE_POINTS, function_targets
from tests.synthesis._function_check import recompute

ISSUE = ["--expr", "x**1.5", "--x-range", "1", "4", "--input-range", "30", "90", "--output-range", "90", "180"]


def _run(capsys, folder: Path, argv, figure=True):
    outputs = (("out", "toml"), ("report", "json"), ("figure", "png"))[: 3 if figure else 2]
    files = {k: folder / f"m.{ext}" for k, ext in outputs}
    args = ["synthesize", "function", *argv] + [x for k, p in files.items() for x in (f"--{k}", str(p))]
    rc = main(args)
    cap = capsys.readouterr()
    return rc, cap, files


def _numbers(obj, where="report"):
    """Every number in the report, failing on null outside the fields that may be null."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            if v is None:
                assert k in ("x", "expression", "defect"), f"{where}.{k} is null"
            else:
                _numbers(v, f"{where}.{k}")
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            _numbers(v, f"{where}[{i}]")
    elif isinstance(obj, float):
        assert np.isfinite(obj), where


def _check_written(files, rep, expr, x_range, input_deg, output, slider=False):
    """The report's structural error is the written model's, recomputed from the file."""
    _numbers(rep)
    if "figure" in files:
        assert files["figure"].read_bytes()[:4] == b"\x89PNG"
    conv = (lambda v: np.asarray(v, dtype=float)) if slider else np.radians
    t = function_targets(expr, x_range, np.radians(input_deg), conv(output), len(rep["targets"]))
    dense = np.linspace(min(np.radians(input_deg)), max(np.radians(input_deg)), DENSE_POINTS)
    err_t, sem, margin = recompute(files["out"], t.input_angle, t.target, dense, t.target_at(dense))
    unit = "" if slider else "_deg"
    reported = rep[f"structural_error_max{unit}"]
    mine = float(sem) if slider else float(np.degrees(sem))
    # the report carries 6 significant digits; the recomputation agrees to 1e-8 of a radian or of the size
    assert reported == pytest.approx(mine, rel=1e-5, abs=1e-7)
    got = [t_[f"error{unit}"] for t_ in rep["targets"]]
    np.testing.assert_allclose(got, err_t if slider else np.degrees(err_t), atol=1e-6)
    assert margin.min() > 0


def test_issue_command_reports_the_structural_error_of_the_written_model(tmp_path, capsys):
    # before: exit 1 "TypeError: unsupported format string passed to NoneType.__format__", null errors,
    # a figure titled "max structural error nan deg"
    rc, cap, files = _run(capsys, tmp_path, ISSUE)
    assert rc == 0, cap.err
    rep = json.loads(files["report"].read_text())
    assert rep["lengths"] == pytest.approx(
        {"ground": 1, "crank": 2.24544, "coupler": 2.94696, "rocker": 0.89714}, abs=5e-6
    )
    assert rep["structural_error_max_deg"] == pytest.approx(0.619, abs=5e-4)
    assert rep["model_angle_offsets_deg"] == {"crank": -180, "rocker": 180}
    _check_written(files, rep, "x**1.5", (1, 4), (30, 90), (90, 180))
    # the written model under mechanism analyze, at the report's model inputs, gives the generated outputs
    for t in rep["targets"]:
        q = t["model_input_deg"]
        assert main(["mechanism", "analyze", str(files["out"]), "--points", "1", "--input", str(q), str(q)]) == 0
        line = capsys.readouterr().out.splitlines()
        row = dict(zip(line[0].split(","), line[1].split(",")))
        rocker = float(row["rocker_angle_deg"]) - rep["model_angle_offsets_deg"]["rocker"]
        assert (rocker - t["output_deg"] + 180) % 360 - 180 == pytest.approx(0, abs=1e-6)


@pytest.mark.parametrize(
    ("extra", "input_deg"),
    [
        (["--points", "5"], (30, 90)),
        (["--input-range", "10", "70"], (10, 70)),
        (["--input-range", "60", "120"], (60, 120)),
        (["--input-range", "200", "260"], (200, 260)),
    ],
)
def test_issue_variants_report_the_written_models_error(tmp_path, capsys, extra, input_deg):
    argv = list(ISSUE)
    if extra[0] == "--input-range":
        argv[5:8] = extra
    else:
        argv += extra
    rc, cap, files = _run(capsys, tmp_path, argv)
    assert rc == 0, cap.err
    _check_written(files, json.loads(files["report"].read_text()), "x**1.5", (1, 4), input_deg, (90, 180))


@pytest.mark.parametrize("deg", [[200.0, 240.0, 280.0, 320.0], [10.0, 50.0, 90.0]])
@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_slider_crank_pairs_of_either_crank_sign_are_checked_on_the_written_model(tmp_path, capsys, deg, sign):
    a, b, e = 2.0 * sign, 5.0, 1.0
    phi = np.radians(deg)
    s = a * np.cos(phi) + np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    pairs = tmp_path / "p.csv"
    pairs.write_text("input_deg,output\n" + "".join(f"{d!r},{float(v)!r}\n" for d, v in zip(deg, s)))
    rc, cap, files = _run(capsys, tmp_path, [str(pairs), "--type", "slider-crank"])
    assert rc == 0, cap.err
    rep = json.loads(files["report"].read_text())
    _numbers(rep)
    assert rep["lengths"] == pytest.approx({"crank": 2.0, "rod": b, "offset": e}, abs=1e-8)
    dense = np.linspace(phi.min(), phi.max(), DENSE_POINTS)
    err_t, sem, _ = recompute(files["out"], phi, s, dense, np.interp(dense, phi, s))
    assert rep["structural_error_max"] == pytest.approx(float(sem), rel=1e-5, abs=1e-9)
    assert np.abs(err_t).max() < 1e-8
    assert rep["model_angle_offsets_deg"]["crank"] % 180 == 0


@given(
    start=st.integers(0, 359),
    span=st.integers(10, 300) | st.integers(-300, -10),
    out_start=st.integers(0, 359),
    out_span=st.integers(10, 270) | st.integers(-270, -10),
    points=st.integers(3, 5),
    expr=st.sampled_from([("x**1.5", 1, 4), ("log10(x)", 1, 2), ("sin(x)", 0, 1.5), ("exp(x)", 0, 1)]),
)
@settings(max_examples=30, suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow])
def test_any_ranges_exit_0_with_the_written_models_error_or_2_writing_nothing(
    capsys, start, span, out_start, out_span, points, expr
):
    f, x0, x1 = expr
    ir, orng = (start, start + span), (out_start, out_start + out_span)
    argv = ["--expr", f, "--x-range", str(x0), str(x1), "--input-range", *map(str, ir), "--output-range"]
    argv += [*map(str, orng), "--points", str(points)]
    with tempfile.TemporaryDirectory() as d:
        rc, cap, files = _run(capsys, Path(d), argv, figure=False)  # figures: drawn by the tests above
        assert rc in (0, 2), cap.err
        if rc == 2:
            assert cap.err.count("\n") == 1 and cap.err.startswith("gearlever: error: ")
            assert not any(p.exists() for p in files.values())
            assert list(Path(d).iterdir()) == []
            return
        _check_written(files, json.loads(files["report"].read_text()), f, (x0, x1), ir, orng)


def test_dead_point_in_the_range_exit_2_naming_where_and_nothing_written(tmp_path, capsys):
    argv = [*ISSUE[:8], "--output-range", "10", "70"]
    rc, cap, files = _run(capsys, tmp_path, argv)
    assert rc == 2
    assert "dead point between the input angles 89.1" in cap.err and cap.err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_impractical_proportions_warn_with_the_ratio_and_offer_the_scale(tmp_path, capsys):
    argv = [*ISSUE[:5], "--input-range", "300", "400", "--output-range", "90", "180"]
    rc, cap, files = _run(capsys, tmp_path, argv)
    assert rc == 0
    warn = [ln for ln in cap.err.splitlines() if "warning" in ln]
    assert len(warn) == 1 and cap.err.count("\n") == 1
    assert "impractical proportions: the coupler is 27.7 times the ground" in warn[0]
    assert "--ground 0.03608 makes the coupler 1 long" in warn[0]
    rep = json.loads(files["report"].read_text())
    assert rep["link_ratio"] == pytest.approx(27.7164, abs=1e-4) and len(rep["warnings"]) == 1
    # the scale offered does what it says
    rc, cap, files = _run(capsys, tmp_path, [*argv, "--ground", "0.03608"])
    assert rc == 0 and json.loads(files["report"].read_text())["lengths"]["coupler"] == pytest.approx(1, abs=1e-4)


def test_practical_proportions_do_not_warn(tmp_path, capsys):
    rc, cap, _ = _run(capsys, tmp_path, ISSUE)
    assert rc == 0 and cap.err == ""


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["--expr", "9" * 499, *ISSUE[2:]], "--expr '999"),
        (["--expr", "x+" + "9" * 497, *ISSUE[2:]], "a number of 497 digits is too large"),
        (["--expr", "x*1e999", *ISSUE[2:]], "--expr 'x*1e999': a number is beyond 1.8e308"),
        ([*ISSUE, "--ground", "0"], "--ground"),
        ([*ISSUE[:5], "--input-range", "0", "360", *ISSUE[8:]], "--input-range must span less than a full turn"),
    ],
)
def test_bad_input_exit_2_one_line_naming_the_flag(tmp_path, capsys, argv, needle):
    rc, cap, _ = _run(capsys, tmp_path, argv)
    assert rc == 2
    assert needle in cap.err and cap.err.count("\n") == 1 and len(cap.err) < 300
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize(
    ("rows", "kind", "needle"),
    [
        ("input_deg,output_deg\n0,10\n200,20\n400,30\n", "fourbar", "column input_deg: the targets span 400 deg"),
        ("input_deg,output_deg\n0,10\n1e300,20\n40,30\n", "fourbar", "row 3 column input_deg: must be at most"),
        ("input_deg,output\n0,10\n10,1e300\n40,30\n", "slider-crank", "row 3 column output: must be at most 1e+12"),
    ],
)
def test_pairs_beyond_a_turn_or_the_caps_exit_2_naming_row_and_column(tmp_path, capsys, rows, kind, needle):
    pairs = tmp_path / "p.csv"
    pairs.write_text(rows)
    out = tmp_path / "m.toml"
    assert main(["synthesize", "function", str(pairs), "--type", kind, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1
    assert not out.exists()


def test_slider_crank_that_rocks_with_target_1_past_180_deg(tmp_path, capsys):
    # before: exit 1 (the engine was asked for the crank a full turn from its sketch at -170 deg, through the
    # limits of a crank that rocks); crank 2, rod 2.5, offset 1: the crank reaches -48.6 .. 228.6 deg only
    a, b, e = 2.0, 2.5, 1.0
    deg = [190.0, 200.0, 210.0, 220.0]
    phi = np.radians(deg)
    s = a * np.cos(phi) + np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    pairs = tmp_path / "p.csv"
    pairs.write_text("input_deg,output\n" + "".join(f"{d!r},{float(v)!r}\n" for d, v in zip(deg, s)))
    rc, cap, files = _run(capsys, tmp_path, [str(pairs), "--type", "slider-crank"])
    assert rc == 0, cap.err
    rep = json.loads(files["report"].read_text())
    _numbers(rep)
    assert rep["grashof"] == "crank rocks" and rep["model_angle_offsets_deg"]["crank"] == -360
    dense = np.linspace(phi.min(), phi.max(), DENSE_POINTS)
    err_t, sem, _ = recompute(files["out"], phi, s, dense, np.interp(dense, phi, s))
    assert rep["structural_error_max"] == pytest.approx(float(sem), rel=1e-5, abs=1e-9)
    assert np.abs(err_t).max() < 1e-8
