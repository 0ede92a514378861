"""Figures of a simulated chariot drive: the path with pointer arrows, and the drift."""

from __future__ import annotations

import numpy as np

from gearlever.plotting._common import axes


def plot_chariot_path(runs, ax=None, arrows: int = 16):
    """Draw the axle mid-point's path and, at ``arrows`` places, the pointer's ground heading.

    Parameters
    ----------
    runs : dict[str, ChariotRun]
        Label -> run; every run is drawn (the first one's path as a line).
    ax : matplotlib Axes, optional
    arrows : int
        Number of pointer arrows along each path.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax, figsize=(6.5, 6.0))
    colors = ("tab:blue", "tab:red", "tab:green", "tab:purple")
    first = True
    for (label, run), color in zip(runs.items(), colors):
        x, y = run.positions()
        if first:
            ax.plot(x, y, color="0.55", lw=1.0, label="path of the axle mid-point")
            ax.plot(x[0], y[0], "o", color="0.3", label="start")
            first = False
        idx = np.linspace(0, x.size - 1, arrows).round().astype(int)
        h = run.pointer_heading[idx]
        scale = 0.06 * max(np.ptp(x), np.ptp(y), run.track)
        ax.quiver(
            x[idx],
            y[idx],
            np.cos(h) * scale,
            np.sin(h) * scale,
            color=color,
            angles="xy",
            scale_units="xy",
            scale=1,
            width=0.005,
            label=f"pointer, {label}",
        )
    ax.margins(0.1)  # room for the arrows at the edges (quiver does not widen the limits)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (units of track t)")
    ax.set_ylabel("y (units of track t)")
    ax.set_title("Nuttall chariot: path and pointer heading in the ground frame")
    ax.legend(loc="best", fontsize=8)
    return ax


def plot_drift(runs, ax=None):
    """Pointer drift (rad) against the distance driven by the axle mid-point, one line per run.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax)
    for label, run in runs.items():
        ax.plot(run.mid_distance(), run.drift, lw=1.2, label=f"{label} (max |drift| {run.max_drift:.2e} rad)")
    ax.axhline(0.0, color="0.6", lw=0.6)
    ax.set_xlabel("distance driven by the axle mid-point (units of track t)")
    ax.set_ylabel("pointer drift (rad)")
    ax.set_title("Nuttall chariot: pointer drift along a random path")
    ax.legend(loc="best", fontsize=8)
    return ax
