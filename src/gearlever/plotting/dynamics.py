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
    res : gearlever.flywheels.flywheel.Flywheel
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
    scale = float(max(np.max(np.abs(T)), np.max(np.abs(L))))
    mean = res.mean_torque if abs(res.mean_torque) > 1e-9 * scale else 0.0  # no round-off digits in the title
    ax.set_title(f"Turning-moment diagram, mean torque {mean:.4g}")
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


def plot_input_torque(d, ax=None, label=None):
    """Input torque (or force) of an inverse-dynamics result against the input angle.

    Parameters
    ----------
    d : gearlever.mechanism.dynamics.InverseDynamics
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax)
    th = np.degrees(d.q[:, 0])
    ax.plot(th, d.input_force[:, 0], color="C0", lw=1.5, label=label or "input torque")
    ax.axhline(float(np.nanmean(d.input_force[:, 0])), color="C3", lw=1.0, ls="--", label="mean")
    ax.set_xlabel("input angle (deg)")
    ax.set_ylabel("input torque (N m)")
    ax.set_title("Torque the driver must give")
    ax.legend(loc="best", fontsize=8)
    return ax


def plot_bearing_polar(d, key, ax=None):
    """Polar diagram of a pin force over the cycle: the tip of the force vector, angle and magnitude.

    Parameters
    ----------
    d : gearlever.mechanism.dynamics.InverseDynamics
    key : str
        A key of ``d.reaction`` (the force on the pin's second link from its first).
    ax : matplotlib polar Axes, optional (a new polar Axes when None)

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(5.0, 5.0), layout="constrained")
        ax = fig.add_subplot(projection="polar")
    f = d.reaction[key]
    ang = np.arctan2(f[:, 1], f[:, 0])
    mag = np.hypot(f[:, 0], f[:, 1])
    ang = np.append(ang, ang[:1])
    mag = np.append(mag, mag[:1])
    ax.plot(ang, mag, color="C0", lw=1.4, label=f"pin {key} (N)")
    ax.plot(ang[:1], mag[:1], "o", color="C3", label=f"input at {np.degrees(d.q[0, 0]):.0f} deg")
    a, b = d.pins[key]
    ax.set_title(f"Load on {b} from {a} at pin {key.split(':')[0]}")
    ax.legend(loc="lower left", fontsize=8, bbox_to_anchor=(-0.1, -0.12))
    return ax


def forces_figure(d, bearing: str, label=None):
    """Input torque beside the polar diagram of the load at pin ``bearing``; returns the Figure."""
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(11.0, 4.5), layout="constrained")
    plot_input_torque(d, ax=fig.add_subplot(1, 2, 1), label=label)
    plot_bearing_polar(d, bearing, ax=fig.add_subplot(1, 2, 2, projection="polar"))
    return fig
