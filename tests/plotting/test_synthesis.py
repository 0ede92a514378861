"""Synthesis figures: Axes/Figure returned, drawn from the results (function generator, Burmester curves, motion)."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

from gearlever.plotting.synthesis import (  # noqa: E402
    burmester_plot,
    draw_linkage,
    function_curves,
    function_figure,
    motion_figure,
)
from gearlever.synthesis import burmester_curves, function_targets, synthesize_function, synthesize_motion  # noqa: E402


def test_function_figures_draw_targets_and_engine_curve():
    t = function_targets("log10(x)", (1, 2), np.radians([45, 105]), np.radians([135, 225]))
    r = synthesize_function(t.input_angle, t.target, target_at=t.target_at)
    ax = function_curves(r)
    assert len(ax.lines) == 3
    np.testing.assert_allclose(ax.lines[2].get_xdata(), np.degrees(t.input_angle))
    fig = function_figure(r)
    assert len(fig.axes) == 2


def test_burmester_and_motion_figures():
    pts = [(0, 0), (1, 0.5), (2, 0.4), (2.8, -0.2)]
    ang = np.radians([0, 15, 35, 60])
    c = burmester_curves(pts, ang, samples=90)
    ax = burmester_plot(c)
    assert len(ax.lines) == 4
    res = synthesize_motion(pts, ang)
    fig = motion_figure(res, c)
    assert len(fig.axes) == 2
    ax2 = draw_linkage(res.best.model)
    assert len(ax2.lines) >= 3
