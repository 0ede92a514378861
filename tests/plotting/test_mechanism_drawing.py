"""Mechanism drawings and GIFs: names, inputs, legend, loads from the model, sizes and their caps, CJK names."""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.colors import same_color  # noqa: E402
from PIL import Image  # noqa: E402

from gearlever.cli import main  # noqa: E402
from gearlever.errors import GearleverError  # noqa: E402
from gearlever.mechanism import Mechanism  # noqa: E402
from gearlever.plotting._common import plt, save  # noqa: E402
from gearlever.plotting.mechanism import (  # noqa: E402
    LOAD_COLOR,
    _fallback_label,
    animate_mechanism,
    draw_mechanism,
)

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
MODELS = sorted(p.stem for p in EXAMPLES.glob("*.toml") if "[law]" not in p.read_text(encoding="utf-8"))


def _texts(ax) -> list[str]:
    return [t.get_text() for t in ax.texts]


def _named(name: str, texts) -> bool:
    """``name`` appears as a whole word in one of ``texts``."""
    pat = re.compile(rf"(^|[\s(]){re.escape(name)}($|[\s):,])")
    return any(pat.search(t) for t in texts)


def _sweep(mech, n=13):
    return mech.solve(mech.sketch_inputs[0] + np.linspace(0, 2 * np.pi, n, endpoint=False)[:, None])


@pytest.mark.parametrize("stem", MODELS)
def test_every_link_point_and_input_is_named_and_the_legend_lists_the_links(stem):
    mech = Mechanism.load(EXAMPLES / f"{stem}.toml")
    m = mech.model
    ax = draw_mechanism(mech)
    texts = _texts(ax)
    try:
        for name in m.links:
            assert _named(name, texts), (name, texts)
        for p in m.points:
            assert p in texts, (p, texts)
        for spec in m.inputs:
            assert f"input: {spec.name if spec.kind == 'slider' else spec.label}" in texts
        legend = ax.get_legend()
        assert legend is not None
        entries = [t.get_text() for t in legend.get_texts()]
        assert all(k in entries for k in m.moving) and "input" in entries
        assert ax.get_title() == m.name
        assert ax.get_aspect() == 1.0
    finally:
        plt.close(ax.figure)


@pytest.mark.parametrize("stem", ["planetary", "ferguson", "compound_planetary", "geared_fivebar"])
def test_every_gear_shows_its_tooth_count(stem):
    mech = Mechanism.load(EXAMPLES / f"{stem}.toml")
    ax = draw_mechanism(mech)
    texts = _texts(ax)
    plt.close(ax.figure)
    for g in mech.model.gears.values():
        assert any(t.endswith(f"z = {g.teeth}") and g.name in t for t in texts), (g.name, texts)


def test_engine_load_arrow_ends_at_its_point_with_the_model_value_and_gravity_in_the_legend():
    mech = Mechanism.load(EXAMPLES / "engine.toml")
    raw = mech.model.extra["loads"][0]
    value = math.hypot(*raw["force"])  # 1000 N in the file
    ax = draw_mechanism(mech)
    texts = _texts(ax)
    arrows = [
        a
        for a in ax.texts
        if getattr(a, "arrow_patch", None) is not None and same_color(a.arrow_patch.get_ec(), LOAD_COLOR)
    ]
    entries = [t.get_text() for t in ax.get_legend().get_texts()]
    plt.close(ax.figure)
    assert f"{value:g} N" in texts
    # the arrow's head is the load's point B, its tail against the force direction
    heads = [np.array(a.xy) for a in arrows]
    tails = [np.array(a.xyann) for a in arrows]
    B = np.array(mech.model.points[raw["point"]])
    k = int(np.argmin([np.hypot(*(h - B)) for h in heads]))
    assert np.allclose(heads[k], B)
    d = heads[k] - tails[k]
    assert np.allclose(d / np.hypot(*d), np.array(raw["force"]) / value)
    assert "load (N)" in entries
    assert any(e.startswith("gravity (0, -9.81) m/s") for e in entries)


def test_a_row_of_a_sweep_is_drawn_where_the_solver_puts_it():
    mech = Mechanism.load(EXAMPLES / "fourbar.toml")
    r = _sweep(mech)
    ax = draw_mechanism(mech, r, row=4)
    pins = {tuple(np.round(line.get_xydata()[0], 9)) for line in ax.lines if line.get_marker() == "o"}
    plt.close(ax.figure)
    for p in ("A", "B"):
        assert tuple(np.round(r.point[p][4], 9)) in pins
    with pytest.raises(GearleverError, match="row"):
        draw_mechanism(mech, r, row=99)


def test_cjk_names_draw_and_save_without_a_warning(tmp_path):
    mech = Mechanism.from_dict(
        {
            "mechanism": {"name": "曲柄摇杆机构", "units": "毫米"},
            "points": {"原点": [0, 0], "O4": [40, 0], "甲": [10, 0], "乙": [45.1, 28.3]},
            "links": {"ground": ["原点", "O4"], "曲柄": ["原点", "甲"], "连杆": ["甲", "乙"], "摇杆": ["O4", "乙"]},
            "inputs": [{"link": "曲柄"}],
        }
    )
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ax = draw_mechanism(mech, _sweep(mech, 7))
        save(ax.figure, tmp_path / "cjk.png")
        animate_mechanism(mech, _sweep(mech, 2), tmp_path / "cjk.gif", figsize=(4, 3), dpi=40)
    assert (tmp_path / "cjk.png").read_bytes()[:4] == b"\x89PNG"


def test_fallback_label_keeps_what_the_font_draws_and_escapes_the_rest():
    assert _fallback_label("crank_2") == "crank_2"
    assert _fallback_label("$x$") == r"\$x\$"  # no mathtext from a name
    assert _fallback_label("a\nb") == r"a\nb"


def test_drawing_bytes_are_the_same_run_to_run(tmp_path):
    mech = Mechanism.load(EXAMPLES / "whitworth.toml")
    r = _sweep(mech, 19)
    for name in ("a.png", "b.png"):
        save(draw_mechanism(mech, r).figure, tmp_path / name, dpi=60)
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()


# --------------------------------------------------------------------------- CLI sizes
def test_gif_is_800_pixels_wide_by_default_one_frame_a_row(tmp_path):
    gif = tmp_path / "m.gif"
    assert main(["mechanism", "animate", str(EXAMPLES / "engine.toml"), "--out", str(gif), "--frames", "3"]) == 0
    with Image.open(gif) as im:
        assert im.format == "GIF" and im.size[0] >= 800 and im.size == (800, 600) and im.n_frames == 3
    fb = tmp_path / "fb.gif"
    assert main(["animate", "--fourbar", "9", "5", "8", "8", "--out", str(fb), "--frames", "2"]) == 0
    with Image.open(fb) as im:
        assert im.size == (800, 600) and im.n_frames == 2


def test_size_and_dpi_set_the_pixels(tmp_path):
    png, gif = tmp_path / "m.png", tmp_path / "m.gif"
    model = str(EXAMPLES / "slider_crank.toml")
    assert main(["mechanism", "draw", model, "--out", str(png), "--size", "6", "4", "--dpi", "50"]) == 0
    small = ["--frames", "2", "--size", "5", "4", "--dpi", "30"]
    assert main(["mechanism", "animate", model, "--out", str(gif), *small]) == 0
    with Image.open(png) as a, Image.open(gif) as b:
        assert a.size == (300, 200) and b.size == (150, 120)


@pytest.mark.parametrize(
    "extra, needle",
    [
        (["--dpi", "601"], "--dpi: must be at most 600"),
        (["--dpi", "0"], "--dpi"),
        (["--size", "41", "5"], "--size: must be at most 40"),
        (["--size", "0.5", "5"], "--size must be at least 1"),
        (["--size", "40", "40", "--dpi", "600"], "--size 40 40 with --dpi 600"),
        (["--size", "x", "5"], "--size"),
    ],
)
@pytest.mark.parametrize("command", ["draw", "animate", "fourbar"])
def test_figure_size_caps_exit_2_with_one_line_naming_the_flag(command, extra, needle, tmp_path, capsys):
    if command == "fourbar":
        argv = ["animate", "--fourbar", "9", "5", "8", "8", "--out", str(tmp_path / "x.gif")]
    else:
        suffix = "png" if command == "draw" else "gif"
        argv = ["mechanism", command, str(EXAMPLES / "fourbar.toml"), "--out", str(tmp_path / f"x.{suffix}")]
    assert main(argv + extra) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err and "Traceback" not in err
    assert not list(tmp_path.iterdir())


def test_all_the_frames_together_are_capped(tmp_path, capsys):
    argv = ["mechanism", "animate", str(EXAMPLES / "fourbar.toml"), "--out", str(tmp_path / "x.gif")]
    assert main(argv + ["--frames", "360", "--size", "20", "15"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--frames 360 of --size 20 15 with --dpi 100" in err and "2e+08" in err
    assert not list(tmp_path.iterdir())


def test_a_row_that_cannot_close_shows_the_frame_and_says_so():
    from gearlever.plotting.animation import fourbar_mechanism

    mech = fourbar_mechanism(9, 7, 3, 4)  # triple rocker: the crank cannot turn fully
    r = _sweep(mech, 24)
    row = int(np.flatnonzero(~r.closed)[0])
    ax = draw_mechanism(mech, r, row=row)
    texts, title = _texts(ax), ax.get_title()
    plt.close(ax.figure)
    assert title.endswith("(does not close)")
    assert {"O2", "O4", "ground", "input: crank"} <= set(texts)
    assert not {"A", "B", "crank", "coupler", "rocker"} & set(texts)
