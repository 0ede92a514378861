"""Law synthesis figure: the wanted and the achieved law over one turn, and the error."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

__all__ = ["law_synthesis_figure"]


def law_synthesis_figure(result, fig=None):
    """Wanted and achieved output over the cycle (top) and the error (bottom), segments shaded; returns the Figure.

    Parameters
    ----------
    result : gearlever.synthesis.law.LawSynthesis
    fig : matplotlib Figure, optional
    """
    if fig is None:
        fig = plt.figure(figsize=(7.5, 5.5), layout="constrained")
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    t = result.law_target
    ang = t.output == "angle"
    conv = np.degrees if ang else (lambda x: x)
    unit = "deg" if ang else t.units
    th = np.degrees(result.theta)
    ax1.plot(th, conv(result.target), color="k", lw=1.5, label="wanted")
    ax1.plot(th, conv(result.achieved), color="tab:blue", lw=1.2, ls="--", label=f"{result.kind} (achieved)")
    ax2.plot(th, conv(result.error), color="tab:red", lw=1.0)
    for k, motion in enumerate(t.motions):
        a, b = np.degrees(t.breaks[k]), np.degrees(t.breaks[k + 1])
        for ax in (ax1, ax2):
            if motion == "dwell":
                ax.axvspan(a, b, color="0.9", zorder=0)
        ax1.annotate(
            motion, ((a + b) / 2, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom", fontsize=8
        )
    ax1.set_ylabel(f"output ({unit})")
    ax2.set_ylabel(f"error ({unit})")
    ax2.set_xlabel("law input (deg)")
    ax2.set_xlim(0, 360)
    ax1.legend(loc="best", fontsize=8)
    ax1.grid(True, alpha=0.3)
    ax2.grid(True, alpha=0.3)
    return fig
