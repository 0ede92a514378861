"""Turning-moment diagram and the energy-fluctuation band of a flywheel result."""

from __future__ import annotations

import numpy as np

from gearlever.plotting._common import axes


def _closed(res, values):
    """Samples of one full cycle (the wrap segment appended when the cycle was given by a period)."""
    th = np.degrees(res.theta)
    span = res.theta[-1] - res.theta[0]
    if res.period > span * (1 + 1e-12):
        return np.append(th, np.degrees(res.theta[0] + res.period)), np.append(values, values[0])
    return th, np.asarray(values)


def plot_turning_moment(res, ax=None):
    """Driving and resisting torque against crank angle, the excess and deficit areas shaded.

    Parameters
    ----------
    res : gearlever.dynamics.flywheel.Flywheel
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax)
    th, T = _closed(res, res.torque)
    _, L = _closed(res, res.load)
    ax.plot(th, T, color="C0", lw=1.5, label="driving torque")
    ax.plot(th, L, color="C3", lw=1.2, ls="--", label="resisting torque")
    ax.fill_between(th, T, L, where=T >= L, interpolate=True, color="C2", alpha=0.3, label="excess (speeds up)")
    ax.fill_between(th, T, L, where=T < L, interpolate=True, color="C1", alpha=0.3, label="deficit (slows down)")
    for t, name, c in ((res.theta_max_speed_deg, "max speed", "C2"), (res.theta_min_speed_deg, "min speed", "C1")):
        ax.axvline(t, color=c, lw=1.0, ls=":")
        ax.annotate(name, (t, ax.get_ylim()[1]), xytext=(3, -12), textcoords="offset points", color=c, fontsize=8)
    ax.set_xlabel("crank angle (deg)")
    ax.set_ylabel("torque")
    ax.set_title(f"Turning-moment diagram, mean torque {res.mean_torque:.4g}")
    ax.legend(loc="lower right", fontsize=8)
    return ax


def plot_energy(res, ax=None):
    """Energy ``E(theta) = integral (T - L)`` over the cycle with the band ``dE`` between its extremes.

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax)
    th, E = _closed(res, res.energy)
    if th.size > res.theta.size:
        E = E.copy()
        E[-1] = 0.0  # one full cycle brings the energy back
    ax.axhspan(res.energy_min, res.energy_max, color="C4", alpha=0.15, label=f"dE = {res.energy_fluctuation:.4g}")
    ax.plot(th, E, color="C4", lw=1.5, label="E(theta) - E(theta_0)")
    ax.plot([res.theta_max_speed_deg], [res.energy_max], "o", color="C2", label="max speed")
    ax.plot([res.theta_min_speed_deg], [res.energy_min], "o", color="C1", label="min speed")
    ax.set_xlabel("crank angle (deg)")
    ax.set_ylabel("energy")
    title = "Fluctuation of energy"
    if res.inertia is not None and res.fluctuation is not None:
        title += f": I = {res.inertia:.4g}, Cs = {res.fluctuation:.4g}"
    ax.set_title(title)
    ax.legend(loc="best", fontsize=8)
    return ax


def turning_moment_figure(res):
    """Both panels, the turning-moment diagram above the energy curve; returns the Figure."""
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.0, 7.0), sharex=True, layout="constrained")
    plot_turning_moment(res, ax=a1)
    plot_energy(res, ax=a2)
    return fig
