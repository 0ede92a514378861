"""The floor under the newer commands (issue 33, part 5): one test per class of hostile input.

Each class is tested on every command the issue found it in: an output that is
also an input of the same command (refused naming both, the input untouched),
sizes the arithmetic cannot carry (refused, never a silent 0), input files
nested too deeply for the parser (one line, no RecursionError), a law read off
a crank that turns fully (no KeyError), messages that name internals or read
badly (overflow, a huge JSON integer, an open interval, articles, both ways of
giving a law, a CAM or LAW file given as a model), and a follower that cannot
be built (an oscillating roller's pivot inside the cam).  Every test runs
:func:`gearlever.cli.main` in-process and checks the exit status and the one
line on stderr.
"""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

from gearlever.cli import main
from gearlever.data import example_path

LIFT = example_path("law_lift.toml").read_text()
ROCK = """[law]
output = "angle"
units = "deg"
[[law.segment]]
to = 180
motion = "cycloidal"
rise = 30
[[law.segment]]
to = 360
motion = "cycloidal"
rise = -30
"""
ROLLER = ["--follower", "translating-roller", "--roller-radius", "5", "--base-radius", "40"]


def run(capsys, argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err: str) -> str:
    assert err.endswith("\n") and err.count("\n") == 1, err
    assert "Traceback" not in err
    return err


@pytest.fixture
def files(tmp_path):
    (tmp_path / "fourbar.toml").write_text(example_path("fourbar.toml").read_text())
    (tmp_path / "lift.toml").write_text(LIFT)
    x = np.arange(0, 360, 10)
    (tmp_path / "s.csv").write_text("input_deg,output\n" + "".join(f"{a},{5 - 5 * np.cos(np.radians(a))}\n" for a in x))
    (tmp_path / "s.toml").write_text('[law]\noutput = "displacement"\nunits = "mm"\nsamples = "s.csv"\n')
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    (tmp_path / "t.csv").write_text("x,y\n" + "".join(f"{np.cos(a) + 4},{np.sin(a)}\n" for a in t))
    (tmp_path / "d.links.json").write_text(
        json.dumps(
            {
                "x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
                "edges": [[0, 1], [1, 3], [2, 3]],
                "fixed_joints": [0, 2],
                "motor": [0, 1],
            }
        )
    )
    return tmp_path


OVER_INPUT = {
    "analyze --out MODEL": (["mechanism", "analyze", "{d}/fourbar.toml", "--out", "{d}/fourbar.toml"], "fourbar.toml"),
    "analyze --out ./MODEL": (
        ["mechanism", "analyze", "{d}/fourbar.toml", "--out", "{d}/./fourbar.toml"],
        "fourbar.toml",
    ),
    "forces --out MODEL": (["mechanism", "forces", "{d}/fourbar.toml", "--out", "{d}/fourbar.toml"], "fourbar.toml"),
    "cam design --out LAW": (["cam", "design", "{d}/lift.toml", *ROLLER, "--out", "{d}/lift.toml"], "lift.toml"),
    "cam design --report LAW": (
        ["cam", "design", "{d}/lift.toml", *ROLLER, "--out", "{d}/c.toml", "--report", "{d}/lift.toml"],
        "lift.toml",
    ),
    "cam design --profile SAMPLES": (
        ["cam", "design", "{d}/s.toml", *ROLLER, "--out", "{d}/c.toml", "--profile", "{d}/s.csv"],
        "s.csv",
    ),
    "synthesize law --out LAW": (
        ["synthesize", "law", "{d}/lift.toml", "--type", "slider-crank", "--out", "{d}/lift.toml"],
        "lift.toml",
    ),
    "curve score --out TARGET": (
        ["curve", "score", "{d}/d.links.json", "--target", "{d}/t.csv", "--out", "{d}/t.csv"],
        "t.csv",
    ),
}


@pytest.mark.parametrize("argv, name", OVER_INPUT.values(), ids=OVER_INPUT.keys())
def test_an_output_that_is_also_an_input_is_refused_naming_both(files, capsys, argv, name):
    before = {p.name: p.read_bytes() for p in files.iterdir()}
    code, _, err = run(capsys, [a.format(d=files) for a in argv])
    assert code == 2
    line = one_line(err)
    assert "an output may not replace an input" in line and line.count(name) >= 2, line
    assert {p.name: p.read_bytes() for p in files.iterdir()} == before  # nothing written, nothing left


def test_an_output_that_is_a_link_to_the_input_is_refused(files, capsys):
    os.symlink(files / "fourbar.toml", files / "out.csv")
    before = (files / "fourbar.toml").read_bytes()
    code, _, err = run(capsys, ["mechanism", "analyze", files / "fourbar.toml", "--out", files / "out.csv"])
    assert code == 2 and "may not replace an input" in one_line(err)
    assert (files / "fourbar.toml").read_bytes() == before


@pytest.mark.parametrize("scale", [1e300, 1e160, 1e12])
def test_curve_score_refuses_a_target_the_arithmetic_cannot_carry(files, capsys, scale):
    t = np.linspace(0, 2 * np.pi, 60, endpoint=False)
    (files / "big.csv").write_text("x,y\n" + "".join(f"{scale * np.cos(a)},{scale * np.sin(a)}\n" for a in t))
    code, out, err = run(capsys, ["curve", "score", files / "d.links.json", "--target", files / "big.csv"])
    assert code == 2 and out == ""
    assert "row 1 has a coordinate larger than" in one_line(err)


@pytest.mark.parametrize(
    "argv",
    [
        ["cam", "design", "{d}/deep.toml", *ROLLER, "--out", "{d}/c.toml"],
        ["cam", "view", "{d}/deep.toml", "--out", "{d}/c.html"],
        ["synthesize", "law", "{d}/deep.toml", "--type", "fourbar", "--out", "{d}/m.toml"],
    ],
    ids=["cam design LAW", "cam view CAM", "synthesize law LAW"],
)
def test_a_law_or_cam_file_nested_5000_deep_is_one_line(files, capsys, argv):
    (files / "deep.toml").write_text(
        "[law]\noutput = " + "[" * 5000 + "]" * 5000 + "\n[cam]\nx = " + "[" * 5000 + "]" * 5000
    )
    code, _, err = run(capsys, [a.format(d=files) for a in argv])
    assert code == 2
    assert "RecursionError" not in one_line(err) and "internal error" not in err


@pytest.mark.parametrize("example, output", [("fourbar", "crank"), ("whitworth", "lever")])
def test_mechanism_law_of_an_output_that_turns_fully(tmp_path, capsys, example, output):
    """A crank's output is one rise over the whole turn: its rise is the net change, 360 deg."""
    code, out, err = run(
        capsys, ["mechanism", "law", example_path(f"{example}.toml"), "--output", output, "--format", "json"]
    )
    assert code == 0, err
    rep = json.loads(out)
    (seg,) = rep["segments"]
    assert seg["motion"] == "rise" and seg["rise"] == pytest.approx(360.0, abs=1e-6)
    assert seg["excursion"] == pytest.approx(rep["range_deg"], abs=1e-6)


@pytest.mark.parametrize(
    "argv, flag",
    [
        (
            [
                "cam",
                "design",
                "{d}/lift.toml",
                "--follower",
                "translating-roller",
                "--roller-radius",
                "5",
                "--base-radius",
                "1e308",
                "--out",
                "{d}/c.toml",
            ],
            "--base-radius",
        ),
        (["cam", "design", "{d}/lift.toml", *ROLLER, "--rpm", "1e200", "--out", "{d}/c.toml"], "--rpm"),
    ],
    ids=["--base-radius 1e308", "--rpm 1e200"],
)
def test_an_overflow_names_the_flag_never_python(files, capsys, argv, flag):
    code, _, err = run(capsys, [a.format(d=files) for a in argv])
    line = one_line(err)
    assert code == 2 and "Numerical result out of range" not in line and "(34," not in line
    assert flag in line, line


def test_a_links_json_integer_too_large_names_the_file_and_key(files, capsys):
    (files / "h.links.json").write_text(
        '{"x0": [[0, 0], [0, 1], [3, 0], [2, 2]], "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], '
        '"motor": [0, ' + "9" * 400 + "]}"
    )
    code, _, err = run(capsys, ["curve", "score", files / "h.links.json", "--target", files / "t.csv"])
    line = one_line(err)
    assert code == 2 and "h.links.json" in line and "motor" in line and "int too large" not in line
    (files / "x.links.json").write_text(
        '{"x0": [[0, 0], [0, ' + "9" * 400 + "]], " + '"edges": [[0, 1]], "fixed_joints": [0], "motor": [0, 1]}'
    )
    code, _, err = run(capsys, ["curve", "score", files / "x.links.json", "--target", files / "t.csv"])
    line = one_line(err)
    assert code == 2 and "x.links.json" in line and "x0" in line


def test_an_open_interval_is_said_as_one(capsys):
    code, _, err = run(
        capsys, ["mechanism", "law", example_path("fourbar.toml"), "--output", "rocker", "--threshold", "0"]
    )
    assert code == 2 and "greater than 0 and less than 1" in one_line(err)


def test_articles_read_right(files, capsys):
    code, _, err = run(
        capsys,
        ["cam", "design", files / "lift.toml", "--follower", "oscillating-roller", "--roller-radius", "5",
         "--base-radius", "30", "--arm", "40", "--pivot-distance", "60", "--out", files / "c.toml"],
    )  # fmt: skip
    assert code == 2 and "an oscillating-roller follower" in one_line(err)
    (files / "u.toml").write_text('[law]\noutput = "displacement"\nunits = "deg"\nsamples = "s.csv"\n')
    code, _, err = run(capsys, ["cam", "design", files / "u.toml", *ROLLER, "--out", files / "c.toml"])
    assert code == 2 and "a displacement law" in one_line(err) and "an displacement" not in err


def test_a_law_with_both_segments_and_samples_is_told_so(files, capsys):
    (files / "both.toml").write_text(LIFT.replace("[law]\n", '[law]\nsamples = "s.csv"\n', 1))
    code, _, err = run(capsys, ["cam", "design", files / "both.toml", *ROLLER, "--out", files / "c.toml"])
    line = one_line(err)
    assert code == 2 and "has both" in line and "needs either" not in line


@pytest.mark.parametrize("table, command", [("cam", "cam view"), ("law", "cam design")])
def test_a_cam_or_law_file_given_as_a_model_points_to_its_command(files, capsys, table, command):
    (files / "x.toml").write_text(f"[{table}]\nx = 1\n")
    code, _, err = run(capsys, ["mechanism", "analyze", files / "x.toml"])
    assert code == 2 and f"unknown table [{table}]" in one_line(err) and command in err


def test_a_stroke_of_a_degree_law_is_said_in_degrees(files, capsys):
    (files / "rock.toml").write_text(ROCK)
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-roller", "--roller-radius", "5"]
    code, _, err = run(
        capsys, [*argv, "--arm", "40", "--pivot-distance", "60", "--base-radius", "3", "--out", files / "c.toml"]
    )
    assert code == 2 and "stroke 30 deg" in one_line(err)


# -- Say what you accept: one rule for the columns of every CSV a user gives ------------------------------------


@pytest.mark.parametrize(
    ("kind", "good_header", "extra_header", "extra_row"),
    [
        ("curve target", "x,y", "x,y,z", "5,0,7"),
        ("law samples", "input_deg,output", "input_deg,output,speed", "350,0.1,3"),
        ("path targets", "x,y", "x,y,weight", "5,0,7"),
    ],
)
def test_every_user_csv_refuses_an_extra_column_by_header_or_by_row(
    files, capsys, kind, good_header, extra_header, extra_row
):
    """Before: path CSVs refused extra columns while law samples and curve targets dropped them silently."""
    t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    if kind == "law samples":
        body = "".join(f"{a},{5 - 5 * np.cos(np.radians(a))}\n" for a in np.arange(0, 360, 10))
    else:
        body = "".join(f"{np.cos(a) + 4},{np.sin(a)}\n" for a in t)

    def argv(name):
        if kind == "curve target":
            return ["curve", "score", files / "d.links.json", "--target", files / name]
        if kind == "law samples":
            (files / "l.toml").write_text(f'[law]\noutput = "displacement"\nunits = "mm"\nsamples = "{name}"\n')
            return ["cam", "design", files / "l.toml", *ROLLER, "--out", files / "c.toml"]
        return ["synthesize", "path", files / name, "--budget", "2000", "--out", files / "p.toml"]

    (files / "h.csv").write_text(f"{extra_header}\n" + body.replace("\n", ",1\n"))
    code, _, err = run(capsys, argv("h.csv"))
    line = one_line(err)
    assert code == 2 and "unknown column" in line and extra_header.split(",")[-1] in line and "h.csv" in line
    (files / "r.csv").write_text(f"{good_header}\n" + body + extra_row + "\n")
    code, _, err = run(capsys, argv("r.csv"))
    line = one_line(err)
    assert code == 2 and "3 values" in line and "r.csv" in line


def test_law_samples_like_targets_need_no_header(files, capsys):
    """Before: law samples needed a header while curve and path targets did not; now each may have one or not."""
    from gearlever.laws import load_law

    body = "".join(f"{a},{5 - 5 * np.cos(np.radians(a))}\n" for a in np.arange(0, 360, 10))
    (files / "n.csv").write_text("# a comment line\n" + body)
    (files / "h.csv").write_text("input_deg,output\n" + body)
    for name in ("n", "h"):
        (files / f"{name}.toml").write_text(f'[law]\noutput = "displacement"\nunits = "mm"\nsamples = "{name}.csv"\n')
    a, b = load_law(files / "n.toml"), load_law(files / "h.toml")
    th = np.linspace(0, 2 * np.pi, 7)
    np.testing.assert_array_equal(a.evaluate(th).s, b.evaluate(th).s)


def test_a_cam_file_carries_only_its_followers_dimensions_in_its_laws_units(files, capsys):
    code, _, _ = run(capsys, ["cam", "design", files / "lift.toml", *ROLLER, "--out", files / "c.toml"])
    assert code == 0
    text = (files / "c.toml").read_text()
    (files / "arm.toml").write_text(text.replace("[cam]\n", "[cam]\narm = 40.0\n", 1))
    code, _, err = run(capsys, ["cam", "view", files / "arm.toml", "--out", files / "v.html"])
    line = one_line(err)
    assert code == 2 and "arm" in line and "translating-roller" in line and "arm.toml" in line
    assert 'units = "mm"' in text
    (files / "in.toml").write_text(text.replace('units = "mm"', 'units = "in"', 1))
    code, _, err = run(capsys, ["cam", "view", files / "in.toml", "--out", files / "v.html"])
    line = one_line(err)
    assert code == 2 and "units" in line and "'in'" in line and "'mm'" in line


def test_an_oscillating_cam_file_names_the_units_of_its_lengths(files, capsys):
    from gearlever.cams.camfile import load_cam

    (files / "rock.toml").write_text(ROCK)
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-roller", "--roller-radius", "5"]
    argv += ["--arm", "40", "--pivot-distance", "60", "--base-radius", "30", "--out", files / "o.toml"]
    code, _, err = run(capsys, argv)
    assert code == 0, err
    text = (files / "o.toml").read_text()
    (files / "o_mm.toml").write_text(
        text.replace("[cam]\n", '[cam]\nunits = "mm"\n', 1)
        if "units" not in text
        else text.replace('units = "length"', 'units = "mm"')
    )
    assert load_cam(files / "o_mm.toml").units == "mm"
    (files / "o_bad.toml").write_text((files / "o_mm.toml").read_text().replace('units = "mm"', 'units = "parsec"'))
    code, _, err = run(capsys, ["cam", "view", files / "o_bad.toml", "--out", files / "v.html"])
    line = one_line(err)
    assert code == 2 and "parsec" in line and "mm" in line


def test_an_oscillating_sizing_failure_names_its_flag_and_says_undercut(files, capsys):
    """Before: 'no base radius up to 50 meets ...': no flag, no reason; the translating-flat one says both."""
    (files / "rock.toml").write_text(
        ROCK.replace("to = 180", "to = 60").replace("to = 360", "to = 120")
        + '[[law.segment]]\nto = 360\nmotion = "dwell"\n'
    )
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-flat", "--pivot-distance", "50"]
    code, _, err = run(capsys, [*argv, "--min-curvature-radius", "0", "--out", files / "o.toml"])
    line = one_line(err)
    assert code == 2 and "--pivot-distance 50" in line and "undercut" in line
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-roller", "--roller-radius", "5"]
    argv += ["--arm", "40", "--pivot-distance", "50", "--max-pressure-angle", "10", "--out", files / "o.toml"]
    code, _, err = run(capsys, argv)
    line = one_line(err)
    assert code == 2 and "--pivot-distance 50" in line and "pressure angle reached" in line


def test_an_oscillating_roller_whose_pivot_lies_inside_the_cam_is_refused(files, capsys):
    """Before: --pivot-distance 30 with --arm 40 wrote a cam with an 83.6 deg pressure angle that cuts the pivot."""
    (files / "rock.toml").write_text(ROCK)
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-roller", "--roller-radius", "5"]
    argv += ["--arm", "40", "--base-radius", "30", "--out", files / "c.toml"]
    code, _, err = run(capsys, [*argv, "--pivot-distance", "30"])
    line = one_line(err)
    assert code == 2 and line.startswith(
        "gearlever: error: --pivot-distance 30: the follower's pivot lies inside the cam"
    )
    assert "a --pivot-distance above" in line and "--arm 40" in line and "pivot_distance" not in line
    assert not (files / "c.toml").exists()
    least = float(line.split("a --pivot-distance above ")[1].split()[0])
    code, _, err = run(capsys, [*argv, "--pivot-distance", f"{least * 1.001:.6g}"])
    assert code == 0, err
    # cam view of a CAM file edited so that its pivot lies inside: the [cam] key is named
    (files / "in.toml").write_text(
        (files / "c.toml").read_text().replace(f"pivot_distance = {least * 1.001:.6g}", "pivot_distance = 30", 1)
    )
    code, _, err = run(capsys, ["cam", "view", files / "in.toml", "--out", files / "v.html"])
    line = one_line(err)
    assert code == 2 and "in.toml: [cam] pivot_distance 30: the follower's pivot lies inside the cam" in line
    assert not (files / "v.html").exists()


def test_sizing_an_oscillating_roller_keeps_its_pivot_outside_the_cam(files, capsys):
    """Sizing returns only a base radius whose cam clears the pivot, or refuses saying why, naming the flags."""
    (files / "rock.toml").write_text(ROCK)
    argv = ["cam", "design", files / "rock.toml", "--follower", "oscillating-roller", "--roller-radius", "10"]
    argv += ["--arm", "100", "--max-pressure-angle", "30", "--report", files / "r.json", "--out", files / "c.toml"]
    code, _, err = run(capsys, [*argv, "--pivot-distance", "200"])
    assert code == 0, err
    rep = json.loads((files / "r.json").read_text())
    from gearlever.cams.followers import FollowerParams
    from gearlever.cams.followers.oscillating_roller import cam_radius_max

    r_max = cam_radius_max(FollowerParams(10.0, 0.0, 100.0, 200.0), rep["base_radius"], np.radians(rep["stroke"]))
    assert rep["pressure_angle_max_deg"] <= 30 + 1e-9 and r_max < 200
    wide = ROCK.replace("rise = 30", "rise = 120").replace("rise = -30", "rise = -120")
    (files / "wide.toml").write_text(wide)
    argv[2] = files / "wide.toml"
    argv[argv.index("--report") + 1] = files / "r2.json"
    code, _, err = run(capsys, [*argv, "--pivot-distance", "200"])
    line = one_line(err)
    assert code == 2 and "no base radius keeps the follower's pivot outside the cam" in line
    assert "--pivot-distance 200" in line and "--arm 100" in line and not (files / "r2.json").exists()
