"""CLI: gearlever curve score; the model written for a linkage traces the simulated curve under mechanism analyze."""

import csv
import io
import json

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve.model import linkage_toml
from gearlever.synthesis.curve.score import hypervolume
from gearlever.synthesis.curve.simulate import simulate
from tests.synthesis.curve import _designs
from tests.synthesis.curve._designs import SIXBAR

small = _designs.small  # fixture


def _circle_csv(path, r=0.36055512754639896):
    t = np.linspace(0, 2 * np.pi, 120, endpoint=False)
    path.write_text("x,y\n" + "".join(f"{r * np.cos(a) + 4},{r * np.sin(a)}\n" for a in t))


def test_score_rows_and_hypervolume(tmp_path, capsys):
    a, b = tmp_path / "a.links.json", tmp_path / "b.links.json"
    a.write_text(json.dumps({**SIXBAR, "target_joint": 1}))  # crank tip: a circle of the crank's radius
    b.write_text(json.dumps(SIXBAR))
    tgt = tmp_path / "t.csv"
    _circle_csv(tgt)
    argv = ["curve", "score", str(a), str(b), "--target", str(tgt), "--format", "json"]
    assert main([*argv, "--scoring", "challenge"]) == 0
    r = json.loads(capsys.readouterr().out)
    rows = r["rows"]
    assert rows[0]["distance"] == pytest.approx(0.0, abs=0.05)  # target sampled differently: resampling only
    lk = linkage_from_dict(SIXBAR)
    mat = 2 * sum(np.hypot(*(lk.x0[i] - lk.x0[j])) for i, j in lk.edges)
    assert rows[1]["material"] == pytest.approx(mat, rel=1e-9)
    assert r["scoring"] == "challenge" and r["material_scale"] == 1.0
    # the default, relative: material at the size of the challenge's targets (RMS radius 0.191; this one's is r)
    assert main(argv) == 0
    rel = json.loads(capsys.readouterr().out)
    assert rel["scoring"] == "relative"
    assert rel["rows"][1]["material"] == pytest.approx(mat * 0.191 / 0.36055512754639896, rel=1e-3)
    assert rel["rows"][0]["distance"] < rows[0]["distance"]  # the closing segment of the 120-point target counts
    assert rows[1]["joints"] == 7 and rows[1]["links"] == 8
    feas = [x for x in rows if x["feasible"]]
    expect = hypervolume([[x["distance"], x["material"]] for x in feas])
    assert r["hypervolume"] == pytest.approx(expect)


@pytest.mark.parametrize(
    "edit, needle",
    [
        ({"motor": [1, 0]}, "motor"),
        ({"edges": [[0, 1], [1, 9]]}, "edges[1]"),
        ({"fixed_joints": [0]}, "edges"),
    ],
)
def test_score_refuses_a_malformed_design_in_one_line(tmp_path, capsys, edit, needle):
    p = tmp_path / "bad.links.json"
    p.write_text(json.dumps({**SIXBAR, **edit}))
    tgt = tmp_path / "t.csv"
    _circle_csv(tgt)
    assert main(["curve", "score", str(p), "--target", str(tgt)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "bad.links.json" in err and needle in err


@pytest.mark.parametrize(
    "text, needle",
    [
        ("x,y\n" + "1,2\n" * 30, "distinct"),
        ("x,y\n" + "".join(f"{i},{2 * i}\n" for i in range(30)), "line"),
        ("x,y\n" + "".join(f"{i},{i * i}\n" for i in range(30)) + "nan,1\n", "must be finite, got 'nan'"),
        ("a,b\n1,2\n", "header"),
    ],
)
def test_score_refuses_a_bad_target(tmp_path, capsys, text, needle):
    p = tmp_path / "d.links.json"
    p.write_text(json.dumps(SIXBAR))
    tgt = tmp_path / "t.csv"
    tgt.write_text(text)
    assert main(["curve", "score", str(p), "--target", str(tgt)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--target" in err and needle in err


def test_written_model_traces_the_simulated_curve_under_mechanism_analyze(tmp_path, capsys):
    lk = linkage_from_dict(SIXBAR)
    m = tmp_path / "m.toml"
    m.write_text(linkage_toml(lk))
    assert main(["mechanism", "analyze", str(m), "--points", "4", "--input", "0", "270"]) == 0
    rows = list(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    x = simulate(lk.x0[None], solve_plan(lk), thetas=np.radians([0, 90, 180, 270]))[0, 6]
    got = np.array([[float(r["P_x_len"]), float(r["P_y_len"])] for r in rows])
    np.testing.assert_allclose(got, x, atol=1e-8)


def _egg_csv(path):
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    path.write_text("x,y\n" + "".join(f"{0.3 * np.cos(a) * (1 + 0.2 * np.sin(a))},{0.24 * np.sin(a)}\n" for a in t))


def test_synthesize_curve_writes_models_links_and_front_that_score_the_same(tmp_path, capsys, small):
    tgt, out, rep = tmp_path / "egg.csv", tmp_path / "designs", tmp_path / "r.json"
    _egg_csv(tgt)
    argv = ["synthesize", "curve", str(tgt), "--out", str(out), "--budget", "1000", "--designs", "4"]
    assert main([*argv, "--report", str(rep), "--seed", "2"]) == 0
    assert "designs on the front" in capsys.readouterr().out
    rows = list(csv.DictReader(io.StringIO((out / "pareto.csv").read_text())))
    assert 1 <= len(rows) <= 4
    r = json.loads(rep.read_text())
    assert r["designs"] == len(rows) and r["budget"] == 1000
    # the low-material end: a crank whose tip is traced (a circle is within distance 0.75 of the egg)
    assert r["front"][-1]["joints"] == 2 and r["front"][-1]["links"] == 1
    links = [str(out / f"{row['design']}.links.json") for row in rows]
    assert main(["curve", "score", *links, "--target", str(tgt), "--format", "json"]) == 0
    scored = json.loads(capsys.readouterr().out)
    for row, s in zip(rows, scored["rows"]):
        assert s["distance"] == pytest.approx(float(row["distance"]), rel=1e-9)
        assert s["material"] == pytest.approx(float(row["material"]), rel=1e-9)
        assert s["feasible"]
    assert scored["hypervolume"] == pytest.approx(r["hypervolume"], rel=1e-9)
    assert main(["mechanism", "analyze", str(out / "0001.toml"), "--points", "3"]) == 0
    assert "P_x_len" in capsys.readouterr().out.splitlines()[0]


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--max-joints", "3"], "--max-joints"),
        (["--max-joints", "21"], "--max-joints"),
        (["--budget", "10"], "--budget"),
        (["--budget", "100000000"], "--budget"),
        (["--time", "0.1"], "--time"),
        (["--budget", "2000", "--time", "5"], "--time"),
        (["--figure", "f.svg"], "--figure"),
    ],
)
def test_synthesize_curve_refuses_bad_flags_in_one_line(tmp_path, capsys, extra, needle):
    tgt = tmp_path / "egg.csv"
    _egg_csv(tgt)
    assert main(["synthesize", "curve", str(tgt), "--out", str(tmp_path / "o"), *extra]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and needle in err
    assert not (tmp_path / "o").exists()


def test_synthesize_curve_refuses_a_single_repeated_point(tmp_path, capsys):
    tgt = tmp_path / "p.csv"
    tgt.write_text("x,y\n" + "1,1\n" * 50)
    assert main(["synthesize", "curve", str(tgt), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "TARGET" in err and "distinct" in err


def test_synthesize_curve_with_time_stops_on_the_clock(tmp_path, capsys, small):
    tgt, out, rep = tmp_path / "egg.csv", tmp_path / "designs", tmp_path / "r.json"
    _egg_csv(tgt)
    assert main(["synthesize", "curve", str(tgt), "--out", str(out), "--time", "3", "--report", str(rep)]) == 0
    r = json.loads(rep.read_text())
    assert r["budget"] is None and r["designs"] >= 1
    assert (out / "pareto.csv").exists()


def _d_mm_csv(path, n=60):
    """A 50 mm D drawn in millimetres (issue 33), without a repeated first point."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    x = np.where(np.cos(t) > 0.3, 0.3, np.cos(t)) * 25 + 706
    path.write_text("x,y\n" + "".join(f"{a},{b}\n" for a, b in zip(x, np.sin(t) * 25 + 400)))


def test_synthesize_curve_writes_into_an_existing_empty_folder_and_says_time_and_real_evaluations(
    tmp_path, capsys, small
):
    tgt, out, rep = tmp_path / "d.csv", tmp_path / "designs", tmp_path / "r.json"
    _d_mm_csv(tgt)
    out.mkdir()
    argv = ["synthesize", "curve", str(tgt), "--out", str(out), "--time", "4", "--report", str(rep)]
    assert main(argv) == 0
    r = json.loads(rep.read_text())
    assert r["scoring"] == "relative" and r["designs"] >= 1 and not r["empty"]
    assert r["budget"] is None and r["time_limit"] == 4
    # the real count of NSGA-II's evaluations (not a placeholder), and the refinements' beside it
    assert 0 < r["evaluations"] < 10**6 and r["polish_evaluations"] > 0
    header = (out / "0001.toml").read_text().splitlines()[0]
    assert "time limit 4 s" in header and "budget" not in header and "relative scoring" in header
    # the design is drawn where the target is (millimetres near (706, 400)), with its transform in the report
    lk = json.loads((out / "0001.links.json").read_text())
    x = simulate(np.array(lk["x0"])[None], solve_plan(linkage_from_dict(lk)))[0, lk["target_joint"]]
    assert np.hypot(*(x.mean(0) - [701.4, 400])) < 5
    tf = r["front"][0]["transform"]
    assert set(tf) == {"rotation_deg", "scale", "translation"} and tf["scale"] > 50
    # a folder that holds anything is refused, naming it, before any work
    capsys.readouterr()
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--out" in err and "not empty" in err and str(out) in err


def test_synthesize_curve_says_when_the_front_is_empty(tmp_path, capsys, small):
    tgt, out, rep, fig = tmp_path / "d.csv", tmp_path / "o", tmp_path / "r.json", tmp_path / "f.png"
    _d_mm_csv(tgt)
    argv = ["synthesize", "curve", str(tgt), "--out", str(out), "--budget", "1000", "--scoring", "challenge"]
    assert main([*argv, "--report", str(rep), "--figure", str(fig)]) == 0
    cap = capsys.readouterr()
    assert "0 designs on the front" in cap.out
    err = cap.err.strip()
    assert "\n" not in err and "warning: no design on the front" in err and "--scoring relative" in err
    r = json.loads(rep.read_text())
    assert r["empty"] and r["designs"] == 0 and r["scoring"] == "challenge" and fig.stat().st_size > 0
