"""ZRDPM figures: drawn, titled, labelled, with a legend, and saved (Agg)."""

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402

from gearlever import zrdpm  # noqa: E402
from gearlever.plotting import zrdpm as plots  # noqa: E402
from gearlever.plotting._common import axes, save  # noqa: E402
from gearlever.tables import zrdpm as tabs  # noqa: E402


def _check_axes(ax):
    assert ax.get_title() or ax.figure._suptitle is not None
    assert "(deg)" in ax.get_xlabel()
    assert "(" in ax.get_ylabel() and ")" in ax.get_ylabel()
    assert ax.get_legend() is not None


def test_fig3_u1_over_a_turn(tmp_path):
    ax = plots.plot_u1_turn()
    _check_axes(ax)
    y = ax.lines[0].get_ydata()
    assert max(y) == pytest.approx(2**0.5, abs=1e-4) and min(y) == pytest.approx(-(2**0.5), abs=1e-4)
    path = save(ax.figure, tmp_path / "fig3.png")
    assert path.stat().st_size > 5000


def test_fig3_draws_on_given_axes():
    ax = axes()
    assert plots.plot_u1_turn(zrdpm.ZrdpmContour(l=2.0, r_a=1.0, r_b=3.0), ax=ax) is ax


def test_analogue_curves_of_both_contours(tmp_path):
    fig = plots.plot_analogues()
    assert len(fig.axes) == 2
    for ax in fig.axes:
        assert len(ax.lines) == 4
        _check_axes(ax)
    assert "0.5" in fig.axes[0].get_title() and "2" in fig.axes[1].get_title()
    assert save(fig, tmp_path / "a.png").stat().st_size > 5000


def test_table_comparison_figure(tmp_path):
    fig = plots.plot_table_comparison([tabs.reproduce("II")])
    assert len(fig.axes) == 2
    for ax in fig.axes:
        _check_axes(ax)
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        assert any("published" in s for s in labels) and any("self-consistent" in s for s in labels)
    assert save(fig, tmp_path / "c.png").stat().st_size > 5000
