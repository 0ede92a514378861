"""Path synthesis figure: targets, the generated coupler curve and the linkage at the first target."""

from __future__ import annotations

import numpy as np

from gearlever.plotting._common import axes

__all__ = ["path_synthesis_plot"]


def path_synthesis_plot(result, ax=None):
    """Targets, coupler curve over a crank turn and the linkage at the first target; returns the Axes.

    Parameters
    ----------
    result : gearlever.synthesis.path.PathSynthesis
    ax : matplotlib Axes, optional
    """
    ax = axes(ax, figsize=(6.5, 6.0))
    curve = result.curve()
    ax.plot(curve[:, 0], curve[:, 1], color="tab:blue", lw=1.2, label="coupler curve")
    T = result.target
    ax.plot(T[:, 0], T[:, 1], "o", mfc="none", mec="tab:red", ms=8, label="targets")
    ax.plot(result.achieved[:, 0], result.achieved[:, 1], "x", color="tab:blue", ms=6, label="coupler point at targets")
    for i, (x, y) in enumerate(T):
        ax.annotate(str(i + 1), (x, y), textcoords="offset points", xytext=(5, 5), fontsize=8, color="tab:red")
    q = {k: np.asarray(v) for k, v in result.points.items()}
    ax.plot(*np.array([q["O2"], q["A"]]).T, "-", color="k", lw=2.5, label="crank")
    if "D" in q:  # Stephenson six-bar: four-bar with C on its coupler, dyad C-D-O6, P on C-D
        ax.fill(*np.array([q["A"], q["B"], q["C"]]).T, color="0.6", alpha=0.4, ec="k", lw=1.5, label="coupler")
        ax.plot(*np.array([q["O4"], q["B"]]).T, "-", color="0.3", lw=2.5, label="rocker")
        ax.fill(*np.array([q["C"], q["D"], q["P"]]).T, color="tab:orange", alpha=0.3, ec="k", lw=1.5, label="link5")
        ax.plot(*np.array([q["O6"], q["D"]]).T, "-", color="0.45", lw=2.5, label="output")
    elif "C" in q:  # geared five-bar: second crank O4-B, couplers A-C(-P) and B-C
        ax.fill(*np.array([q["A"], q["C"], q["P"]]).T, color="0.6", alpha=0.4, ec="k", lw=1.5, label="coupler")
        ax.plot(*np.array([q["O4"], q["B"]]).T, "-", color="0.3", lw=2.5, label="geared crank")
        ax.plot(*np.array([q["B"], q["C"]]).T, "-", color="0.45", lw=2.0, label="link5")
        for name, teeth in zip(("O2", "O4"), result.teeth):
            ax.annotate(f"z={teeth}", q[name], textcoords="offset points", xytext=(6, 6), fontsize=8)
    else:
        ax.fill(*np.array([q["A"], q["B"], q["P"]]).T, color="0.6", alpha=0.4, ec="k", lw=1.5, label="coupler")
        ax.plot(*np.array([q["O4"], q["B"]]).T, "-", color="0.3", lw=2.5, label="rocker")
    ax.plot(*np.array([q["O2"], q["O4"]]).T, ":", color="0.3", lw=1.0)
    for name in [n for n in ("O2", "O4", "O6") if n in q]:
        ax.plot(*q[name], "^", color="k", ms=10)
        ax.annotate(name, q[name], textcoords="offset points", xytext=(6, -12), fontsize=9)
    for name in [n for n in ("A", "B", "C", "D", "P") if n in q]:
        ax.plot(*q[name], "o", color="k", ms=4)
        ax.annotate(name, q[name], textcoords="offset points", xytext=(5, 4), fontsize=9)
    ax.set_aspect("equal", adjustable="datalim")
    what = f"{result.kind}, gears {result.teeth[0]}:{result.teeth[1]}" if result.teeth else result.kind
    if result.kind == "fourbar":
        what += f", {result.grashof}"
    ax.set_title(f"Path synthesis ({what}, timing {result.timing}): objective {result.objective:.3g}", fontsize=10)
    ax.legend(fontsize=8, loc="best")
    ax.grid(True, alpha=0.3)
    return ax
