"""CLI tests: gearlever cam design (outputs written whole, report keys, one-line refusals naming file,
segment or flag)."""

import json
import math

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.laws import load_law

LAW = """[law]
output = "displacement"
units = "mm"
[[law.segment]]
to = 60
motion = "dwell"
[[law.segment]]
to = 150
motion = "cycloidal"
rise = 20
[[law.segment]]
to = 200
motion = "dwell"
[[law.segment]]
to = 320
motion = "345"
rise = -20
[[law.segment]]
to = 360
motion = "dwell"
"""

ANGLE_LAW = LAW.replace('output = "displacement"\nunits = "mm"', 'output = "angle"\nunits = "deg"')


@pytest.fixture
def law(tmp_path):
    p = tmp_path / "law.toml"
    p.write_text(LAW)
    return p


def _err(capsys):
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    return err


def test_design_writes_cam_profile_report_and_figure(tmp_path, law, capsys):
    out, rep, prof, fig = (tmp_path / n for n in ("cam.toml", "r.json", "p.csv", "f.png"))
    argv = ["cam", "design", str(law), "--follower", "translating-roller", "--base-radius", "40"]
    argv += ["--roller-radius", "8", "--out", str(out), "--report", str(rep), "--profile", str(prof)]
    assert main(argv + ["--figure", str(fig), "--rpm", "100"]) == 0
    text = capsys.readouterr().out
    assert "pressure angle    max" in text and "undercut          no" in text
    r = json.loads(rep.read_text())
    for key in ("pressure_angle_max_deg", "curvature_radius_min", "undercut", "base_radius", "a_max_mm_per_s2"):
        assert key in r
    assert r["base_radius"] == 40.0 and r["undercut"] is False and r["law_continuous"] is True
    # cycloidal 20 mm over 90 deg: peak velocity 2 h / beta per rad, times omega at 100 rpm
    assert r["v_max_mm_per_s"] == pytest.approx(2 * 20 / (math.pi / 2) * (100 * 2 * math.pi / 60), rel=1e-6)
    xy = np.loadtxt(prof, delimiter=",", skiprows=1)
    assert xy.shape == (3600, 2)
    np.testing.assert_allclose(np.hypot(*xy[:600].T), 40.0, atol=1e-9)  # the first dwell: on the base circle
    assert fig.read_bytes()[:4] == b"\x89PNG"
    # CAM.toml reads back as the same law
    again = load_law(out)
    np.testing.assert_allclose(again.breaks, load_law(law).breaks)
    np.testing.assert_allclose(again.rises, load_law(law).rises)


def test_design_svg_and_dxf_profiles(tmp_path, law, capsys):
    import ezdxf

    base = ["cam", "design", str(law), "--follower", "translating-flat", "--base-radius", "45", "--out"]
    assert main(base + [str(tmp_path / "c.toml"), "--profile", str(tmp_path / "p.svg")]) == 0
    assert "<polygon points=" in (tmp_path / "p.svg").read_text()
    assert main(base + [str(tmp_path / "c.toml"), "--profile", str(tmp_path / "p.dxf")]) == 0
    assert main(base + [str(tmp_path / "c.toml"), "--profile", str(tmp_path / "q.dxf")]) == 0
    assert (tmp_path / "p.dxf").read_bytes() == (tmp_path / "q.dxf").read_bytes()
    poly = [e for e in ezdxf.readfile(tmp_path / "p.dxf").modelspace() if e.dxftype() == "LWPOLYLINE"]
    assert len(poly) == 1 and len(poly[0]) == 3600 and poly[0].closed
    assert "face width" in capsys.readouterr().out


def test_design_sizes_the_base_radius_from_a_pressure_angle(tmp_path, law, capsys):
    rep = tmp_path / "r.json"
    argv = ["cam", "design", str(law), "--follower", "translating-roller", "--roller-radius", "8"]
    argv += ["--max-pressure-angle", "30", "--out", str(tmp_path / "c.toml"), "--report", str(rep)]
    assert main(argv) == 0
    r = json.loads(rep.read_text())
    assert r["base_radius_from"] == "sized" and r["pressure_angle_max_deg"] == pytest.approx(30, abs=1e-6)


def test_oscillating_roller_design(tmp_path, capsys):
    p = tmp_path / "a.toml"
    p.write_text(ANGLE_LAW)
    argv = ["cam", "design", str(p), "--follower", "oscillating-roller", "--base-radius", "30"]
    argv += ["--roller-radius", "6", "--arm", "50", "--pivot-distance", "70", "--out", str(tmp_path / "c.toml")]
    assert main(argv) == 0


@pytest.mark.parametrize(
    ("law_text", "extra", "words"),
    [
        (LAW.replace("to = 150", "to = 40"), [], "segment 2: to = 40 deg does not pass the end of segment 1"),
        (
            LAW.replace('to = 200\nmotion = "dwell"', 'to = 200\nmotion = "dwell"\nrise = 3'),
            [],
            "segment 3: rise = 3 on a dwell",
        ),
        (LAW.replace("cycloidal", "cycloid"), [], "did you mean 'cycloidal'"),
        (LAW.replace("to = 360", "to = 350"), [], "the last segment must end at 360"),
        (LAW.replace("rise = -20", "rise = -10"), [], "does not return to its start"),
        (LAW, ["--base-radius", "5", "--roller-radius", "30"], "--base-radius 5 with --roller-radius 30: undercut"),
        (LAW, ["--roller-radius", "8"], "--base-radius is required"),
        (LAW, ["--base-radius", "40"], "--roller-radius is required"),
        (LAW, ["--base-radius", "10", "--roller-radius", "8", "--max-pressure-angle", "30"], "--max-pressure-angle 30"),
        (LAW, ["--base-radius", "40", "--roller-radius", "8", "--arm", "3"], "--arm does not apply"),
        (LAW, ["--base-radius", "40", "--roller-radius", "8", "--profile", "x.pdf"], "--profile must end with"),
        (ANGLE_LAW, ["--base-radius", "40", "--roller-radius", "8"], "needs a displacement law"),
    ],
)
def test_bad_input_exits_2_with_one_line_naming_file_segment_or_flag(tmp_path, capsys, law_text, extra, words):
    p = tmp_path / "bad.toml"
    p.write_text(law_text)
    out = tmp_path / "cam.toml"
    argv = ["cam", "design", str(p), "--follower", "translating-roller", "--out", str(out)]
    extra = extra or ["--base-radius", "40", "--roller-radius", "8"]
    assert main(argv + extra) == 2
    err = _err(capsys)
    assert words in err, err
    assert not out.exists()


def test_undercut_line_gives_the_smallest_base_radius_that_avoids_it(tmp_path, law, capsys):
    argv = ["cam", "design", str(law), "--follower", "translating-roller", "--base-radius", "5"]
    assert main(argv + ["--roller-radius", "30", "--out", str(tmp_path / "c.toml")]) == 2
    err = _err(capsys)
    least = float(err.rstrip().rsplit(" ", 1)[1])
    argv = ["cam", "design", str(law), "--follower", "translating-roller", "--base-radius", f"{least * 1.001}"]
    assert main(argv + ["--roller-radius", "30", "--out", str(tmp_path / "c.toml")]) == 0


def test_samples_with_nan_are_refused_naming_the_row(tmp_path, capsys):
    (tmp_path / "s.csv").write_text("input_deg,output\n0,0\n90,5\n180,nan\n270,5\n")
    (tmp_path / "l.toml").write_text('[law]\noutput = "displacement"\nunits = "mm"\nsamples = "s.csv"\n')
    argv = ["cam", "design", str(tmp_path / "l.toml"), "--follower", "translating-flat", "--base-radius", "40"]
    assert main(argv + ["--out", str(tmp_path / "c.toml")]) == 2
    assert "row 3: output is nan" in _err(capsys)


@pytest.mark.parametrize("flag", ["--out", "--profile", "--report", "--figure"])
@pytest.mark.parametrize("target", ["/proc/x.csv", "/dev/null", "{tmp}/missing/x.csv", "{tmp}"])
def test_unwritable_outputs_are_refused_before_any_file_is_written(tmp_path, law, capsys, flag, target):
    target = target.replace("{tmp}", str(tmp_path))
    outs = {"--out": str(tmp_path / "c.toml"), "--profile": None, "--report": None, "--figure": None}
    outs[flag] = target
    argv = ["cam", "design", str(law), "--follower", "translating-flat", "--base-radius", "40"]
    for f, v in outs.items():
        if v is not None:
            argv += [f, v]
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main(argv) == 2
    err = _err(capsys)
    assert flag in err and repr(target) in err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


@pytest.mark.parametrize("extra", [["--base-radius", "40"], ["--min-curvature-radius", "4"]])
def test_a_rise_too_narrow_for_the_profile_names_the_points_flag(tmp_path, capsys, extra):
    p = tmp_path / "n.toml"
    p.write_text(LAW.replace("to = 60", "to = 149.8"))
    argv = ["cam", "design", str(p), "--follower", "translating-flat", "--out", str(tmp_path / "c.toml"), *extra]
    assert main(argv) == 2
    assert "segment 2 spans 0.2 deg, less than 4 profile steps of 0.1 deg: give more --points than" in _err(capsys)


def _cam_file(tmp_path, law, capsys):
    out = tmp_path / "cam.toml"
    argv = ["cam", "design", str(law), "--follower", "translating-roller", "--base-radius", "40"]
    assert main(argv + ["--roller-radius", "8", "--out", str(out)]) == 0
    capsys.readouterr()
    return out


def _page_data(path):
    import re

    text = path.read_text(encoding="utf-8")
    return json.loads(re.search(r'<script id="gl-data" type="application/json">(.*?)</script>', text, re.S).group(1))


def test_cam_view_writes_the_page_and_mechanism_view_writes_the_same(tmp_path, law, capsys):
    from gearlever.cams import load_cam

    cam = _cam_file(tmp_path, law, capsys)
    a, b = tmp_path / "a.html", tmp_path / "b.html"
    assert main(["cam", "view", str(cam), "--out", str(a), "--frames", "120"]) == 0
    assert main(["mechanism", "view", str(cam), "--out", str(b), "--frames", "120"]) == 0
    assert a.read_text(encoding="utf-8") == b.read_text(encoding="utf-8")
    d = _page_data(a)
    assert d["N"] == 120 and d["follower"] == "translating-roller" and d["name"] == "cam"
    ref = load_cam(cam, points=3600)
    np.testing.assert_allclose(d["F"]["s"], ref.s[::30], atol=1e-8)
    np.testing.assert_allclose(d["F"]["phi"], np.degrees(ref.pressure_angle[::30]), atol=1e-8)
    # frames not dividing the file's points: the page is designed at the next multiple of the frames
    assert main(["cam", "view", str(cam), "--out", str(a), "--frames", "7"]) == 0
    d = _page_data(a)
    assert d["theta"][1] == pytest.approx(2 * math.pi / 7, abs=1e-9)


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["cam", "view", "{cam}", "--out", "{tmp}/p.png"], "--out must end with .html"),
        (["cam", "view", "{cam}", "--out", "{tmp}/p.html", "--frames", "1"], "--frames"),
        (["cam", "view", "{law}", "--out", "{tmp}/p.html"], "a [cam] table is missing"),
        (["mechanism", "view", "{cam}", "--out", "{tmp}/p.html", "--input", "x=1"], "--input does not apply"),
        (["mechanism", "view", "{cam}", "--out", "{tmp}/p.html", "--rpm", "60"], "--rpm does not apply"),
    ],
)
def test_cam_view_refusals_are_one_line(tmp_path, law, capsys, argv, words):
    cam = _cam_file(tmp_path, law, capsys)
    argv = [a.format(cam=cam, law=law, tmp=tmp_path) for a in argv]
    assert main(argv) == 2
    assert words in _err(capsys)
    assert not (tmp_path / "p.html").exists()


def test_dxf_profile_is_the_same_bytes_under_any_hash_seed(tmp_path):
    """ezdxf lists the classes of the entity types in use from a set; the writer fixes their order."""
    import os
    import subprocess
    import sys

    law = tmp_path / "law.toml"
    law.write_text(LAW)
    out = []
    for seed in ("1", "2", "3", "4", "5"):
        dxf = tmp_path / f"p{seed}.dxf"
        cmd = [sys.executable, "-m", "gearlever", "cam", "design", str(law), "--follower", "translating-roller"]
        cmd += ["--base-radius", "40", "--roller-radius", "10", "--out", str(tmp_path / f"c{seed}.toml")]
        env = {**os.environ, "PYTHONHASHSEED": seed}
        subprocess.run(cmd + ["--profile", str(dxf)], check=True, env=env, capture_output=True)
        out.append(dxf.read_bytes())
    assert all(o == out[0] for o in out)
