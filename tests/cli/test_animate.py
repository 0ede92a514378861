"""``gearlever animate --fourbar``: the four-bar shortcut of ``mechanism animate`` (same model, same animation)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from PIL import Image

from gearlever.cli import build_parser, main
from gearlever.loops import fourbar
from gearlever.plotting.animation import fourbar_mechanism

LINKS = (9.0, 5.0, 8.0, 8.0)


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_shortcut_model_has_the_link_lengths_and_the_branch_of_the_closed_form(branch):
    m = fourbar_mechanism(*LINKS, branch=branch).model
    P = {k: np.array(v) for k, v in m.points.items()}
    ground, crank, coupler, rocker = LINKS
    assert math.dist(P["O2"], P["O4"]) == pytest.approx(ground, rel=1e-12)
    assert math.dist(P["O2"], P["A"]) == pytest.approx(crank, rel=1e-12)
    assert math.dist(P["A"], P["B"]) == pytest.approx(coupler, rel=1e-12)
    assert math.dist(P["O4"], P["B"]) == pytest.approx(rocker, rel=1e-12)
    th2 = math.atan2(P["A"][1], P["A"][0])
    th3 = math.atan2(*(P["B"] - P["A"])[::-1])
    ref = fourbar(*LINKS, np.array([th2]), branch=branch).theta3[0]
    assert math.cos(th3 - ref) == pytest.approx(1.0, abs=1e-12)
    assert [s.name for s in m.inputs] == ["crank"]


def test_shortcut_sweep_follows_the_closed_form_rocker_angle():
    mech = fourbar_mechanism(*LINKS)
    th = mech.sketch_inputs[0] + np.linspace(0, 2 * np.pi, 24, endpoint=False)
    r = mech.solve(th[:, None])
    ref = fourbar(*LINKS, th).theta4
    got = np.arctan2(*(r.point["B"] - np.array([LINKS[0], 0.0])).T[::-1])
    assert np.allclose(np.cos(got - ref), 1.0, atol=1e-10)


def test_shortcut_writes_the_mechanism_animation(tmp_path, capsys):
    gif = tmp_path / "fb.gif"
    assert main(["animate", "--fourbar", *map(str, LINKS), "--out", str(gif), "--frames", "3", "--fps", "5"]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {gif}"
    with Image.open(gif) as im:
        assert im.size == (800, 600) and im.n_frames == 3 and im.info["duration"] == 200


def test_help_says_it_is_the_shortcut_of_mechanism_animate():
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    text = sub.choices["animate"].format_help()
    assert "mechanism animate" in text and "--size" in text and "--dpi" in text


def test_the_figure_options_do_not_import_matplotlib_when_the_parser_is_built():
    import subprocess
    import sys

    code = "import sys, gearlever.cli as c; c.build_parser(); print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "False"
