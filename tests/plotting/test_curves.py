"""Figure of a curve synthesis: the legend never covers a curve; the curves are drawn where the designs run."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402

from gearlever.mechanism.linkage import linkage_from_dict, solve_plan  # noqa: E402
from gearlever.plotting.curves import curve_synthesis_plot  # noqa: E402
from gearlever.synthesis.curve.search import CurveSynthesis  # noqa: E402
from gearlever.synthesis.curve.simulate import simulate  # noqa: E402
from tests.synthesis.curve._designs import SIXBAR  # noqa: E402


def _result(designs, target):
    n = len(designs)
    return CurveSynthesis(
        tuple(designs),
        np.linspace(0.01, 0.3, n),
        np.linspace(9.0, 2.0, n),
        3.0 if n else 0.0,
        1000,
        0,
        2,
        100,
        scoring="relative",
        transforms=np.tile([0.0, 1.0, 0.0, 0.0], (n, 1)),
    )


def test_the_legend_of_the_curves_panel_covers_no_curve():
    lk = linkage_from_dict(SIXBAR)
    designs = []
    for s in (1.0, 1.02, 0.98):
        d = dict(SIXBAR, x0=(np.array(SIXBAR["x0"]) * s).tolist())
        designs.append(linkage_from_dict(d))
    target = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint][:-1]
    fig = curve_synthesis_plot(_result(designs, target), target)
    fig.canvas.draw()
    a2 = fig.axes[1]
    box = a2.get_legend().get_window_extent()
    lines = [ln for ln in a2.get_lines() if len(ln.get_xydata())]
    assert len(lines) == 4  # the target and three designs
    for ln in lines:
        xy = a2.transData.transform(ln.get_xydata())
        inside = (xy[:, 0] > box.x0) & (xy[:, 0] < box.x1) & (xy[:, 1] > box.y0) & (xy[:, 1] < box.y1)
        assert not inside.any(), ln.get_label()
    # drawn as written, on the target (the target is not moved or scaled for the figure)
    np.testing.assert_allclose(lines[1].get_xydata(), simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint])


def test_an_empty_front_draws_the_target_and_says_there_is_no_design():
    t = np.linspace(0, 2 * np.pi, 50)
    target = np.stack([np.cos(t), np.sin(t)], -1)
    fig = curve_synthesis_plot(_result([], target), target)
    fig.canvas.draw()
    assert fig.axes[2].get_title() == "no design on the front"
