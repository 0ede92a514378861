"""CLI: gearlever synthesize function|motion; the written model reproduces the report under mechanism analyze."""

import csv
import io
import json

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.mechanism import Mechanism
from gearlever.synthesis.model import fourbar_model

LOG = ["--expr", "log10(x)", "--x-range", "1", "2", "--input-range", "45", "105", "--output-range", "135", "225"]


def _analyze(capsys, model, lo, hi, n):
    assert main(["mechanism", "analyze", str(model), "--points", str(n), "--input", str(lo), str(hi)]) == 0
    return list(csv.DictReader(io.StringIO(capsys.readouterr().out)))


@pytest.mark.parametrize("points", ["3", "5"])
def test_function_model_reproduces_reported_errors_under_mechanism_analyze(tmp_path, capsys, points):
    out, rep = tmp_path / "m.toml", tmp_path / "r.json"
    argv = ["synthesize", "function", *LOG, "--points", points, "--out", str(out), "--report", str(rep)]
    assert main(argv) == 0
    capsys.readouterr()
    r = json.loads(rep.read_text())
    assert r["objective"].startswith("exact" if points == "3" else "least squares")
    off = r["model_angle_offsets_deg"]
    for t in r["targets"]:
        rows = _analyze(capsys, out, t["input_deg"] + off["crank"], t["input_deg"] + off["crank"], 1)
        rocker = float(rows[0]["rocker_angle_deg"]) + off["rocker"]
        err = (rocker - t["output_deg"] + 180) % 360 - 180
        assert err == pytest.approx(t["error_deg"], abs=1e-6)
    if points == "3":
        assert max(abs(t["error_deg"]) for t in r["targets"]) < 1e-9
    assert 0 < r["structural_error_max_deg"] < 0.5
    assert r["grashof"] == "triple-rocker" and r["defect"] is None


def test_function_structural_error_covers_the_whole_input_range(tmp_path, capsys):
    # Chebyshev targets lie inside --input-range 45..105: the error at its ends (0.169 deg at x = 1) counts
    rep = tmp_path / "r.json"
    assert main(["synthesize", "function", *LOG, "--out", str(tmp_path / "m.toml"), "--report", str(rep)]) == 0
    capsys.readouterr()
    r = json.loads(rep.read_text())
    assert r["structural_error_max_deg"] == pytest.approx(0.16864, abs=1e-5)


def test_function_figure_and_slider_crank_pairs(tmp_path, capsys):
    a, b, e = 2.0, 5.0, 1.0
    phi = np.radians([10.0, 50.0, 90.0, 130.0])
    s = a * np.cos(phi) + np.sqrt(b * b - (e - a * np.sin(phi)) ** 2)
    pairs = tmp_path / "p.csv"
    pairs.write_text("input_deg,output\n" + "".join(f"{float(np.degrees(p))!r},{float(v)!r}\n" for p, v in zip(phi, s)))
    out, rep, fig = tmp_path / "s.toml", tmp_path / "s.json", tmp_path / "s.png"
    argv = ["synthesize", "function", str(pairs), "--type", "slider-crank", "--out", str(out)]
    assert main([*argv, "--report", str(rep), "--figure", str(fig)]) == 0
    capsys.readouterr()
    r = json.loads(rep.read_text())
    assert r["lengths"] == pytest.approx({"crank": a, "rod": b, "offset": e}, abs=1e-8)
    assert fig.read_bytes()[:4] == b"\x89PNG"
    m = Mechanism.load(out)
    res = m.solve(np.radians([10.0, 130.0])[:, None])
    np.testing.assert_allclose(res.point["B"][:, 0], s[[0, 3]], atol=1e-9)


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return str(p)


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--expr", "__import__('os')", *LOG[2:]], "--expr"),
        (["--expr", "log10(x)", "--x-range", "1", "1", *LOG[5:]], "--x-range"),
        (["--expr", "log10(x)", "--x-range", "1", "2", "--input-range", "45", "45", *LOG[8:]], "--input-range"),
        ([*LOG, "--points", "2"], "--points"),
        ([*LOG[:3]], "--x-range"),
        ([], "PAIRS.csv or --expr"),
    ],
)
def test_function_bad_input_exit_2_one_line(tmp_path, capsys, args, needle):
    out = tmp_path / "m.toml"
    assert main(["synthesize", "function", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and "\n" not in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("input_deg,output_deg\n10,20\n20,30\n", "at least 3"),
        ("input_deg,out\n10,20\n20,30\n30,40\n", "missing column(s) output_deg"),
        ("input_deg,output_deg\n10,20\n20,abc\n30,40\n", "row 3 column output_deg"),
        ("input_deg,output_deg\n10,20\n20,nan\n30,40\n", "row 3 column output_deg: must be finite"),
        ("input_deg,output_deg\n10,20\n20,30\n10,40\n", "row 4 column input_deg: repeats row 2"),
    ],
)
def test_function_bad_pairs_file_exit_2_naming_row_and_column(tmp_path, capsys, text, needle):
    pairs = _write(tmp_path, "p.csv", text)
    assert main(["synthesize", "function", pairs, "--out", str(tmp_path / "m.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and "\n" not in err


def _poses_csv(tmp_path, n):
    m = Mechanism.from_dict(fourbar_model((0, 0), (4, 0), (1, 0.3), (4.5, 2.8), (2, 3)))
    q = m.sketch_inputs[0] + np.linspace(0.0, 1.6, n)
    r = m.solve(q[:, None])
    P, th = r.point["P"], np.degrees(r.angle["coupler"])
    rows = "".join(f"{float(x)!r},{float(y)!r},{float(a)!r}\n" for (x, y), a in zip(P, th))
    return _write(tmp_path, f"poses{n}.csv", "x,y,angle_deg\n" + rows), P, th


def test_motion_five_poses_all_solutions_and_model_reproduces_poses(tmp_path, capsys):
    poses, P, th = _poses_csv(tmp_path, 5)
    out, rep, fig, folder = tmp_path / "m.toml", tmp_path / "r.json", tmp_path / "f.png", tmp_path / "all"
    argv = ["synthesize", "motion", poses, "--out", str(out), "--report", str(rep), "--figure", str(fig)]
    assert main([*argv, "--all", str(folder)]) == 0
    capsys.readouterr()
    r = json.loads(rep.read_text())
    assert len(list(folder.glob("solution_*.toml"))) == len(r["solutions"]) >= 2
    best = r["solutions"][0]
    assert best["defect"] is None and best["residual_relative"] < 1e-9
    rows = _analyze(capsys, out, best["input_deg"][0], best["input_deg"][0], 1)
    assert float(rows[0]["A_x_len"]) == pytest.approx(best["moving_pivots"][0][0], abs=1e-9)
    m = Mechanism.load(out)
    res = m.solve(np.radians(best["input_deg"])[:, None])
    np.testing.assert_allclose(res.point["P"], P, atol=1e-8)
    assert fig.read_bytes()[:4] == b"\x89PNG"


def test_motion_three_poses_with_fixed_pivots(tmp_path, capsys):
    poses, P, th = _poses_csv(tmp_path, 3)
    out = tmp_path / "m.toml"
    assert main(["synthesize", "motion", poses, "--fixed-pivots", "0", "0", "4", "0", "--out", str(out)]) == 0
    assert "A (1, 0.3), B (4.5, 2.8)" in capsys.readouterr().out


@pytest.mark.parametrize(
    ("n", "extra", "needle"),
    [(6, [], "at most 5"), (3, [], "--fixed-pivots"), (4, ["--fixed-pivots", "0", "0", "4", "0"], "for 3 poses")],
)
def test_motion_bad_input_exit_2(tmp_path, capsys, n, extra, needle):
    poses, _, _ = _poses_csv(tmp_path, n)
    assert main(["synthesize", "motion", poses, *extra, "--out", str(tmp_path / "m.toml")]) == 2
    err = capsys.readouterr().err.strip()
    assert needle in err and "\n" not in err


def test_motion_duplicate_and_missing_column(tmp_path, capsys):
    p = _write(tmp_path, "d.csv", "x,y,angle_deg\n0,0,0\n1,1,10\n0,0,0\n")
    assert main(["synthesize", "motion", p, "--out", str(tmp_path / "m.toml")]) == 2
    assert "row 4: repeats row 2" in capsys.readouterr().err
    p = _write(tmp_path, "c.csv", "x,y\n0,0\n1,1\n2,0\n")
    assert main(["synthesize", "motion", p, "--out", str(tmp_path / "m.toml")]) == 2
    assert "missing column(s) angle_deg" in capsys.readouterr().err


def test_function_branch_defect_refused_exit_2(tmp_path, capsys):
    from gearlever.loops.fourbar import fourbar

    phi = np.radians([20.0, 60.0, 100.0])
    psi = fourbar(1.0, 0.4, 1.1, 0.9, phi).theta4
    psi[2] = fourbar(1.0, 0.4, 1.1, 0.9, phi[2:], branch="crossed").theta4[0]
    rows = "".join(f"{float(np.degrees(p))!r},{float(np.degrees(v))!r}\n" for p, v in zip(phi, psi))
    pairs = _write(tmp_path, "p.csv", "input_deg,output_deg\n" + rows)
    out = tmp_path / "m.toml"
    assert main(["synthesize", "function", pairs, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert "branch defect" in err and "\n" not in err
    assert not out.exists()
