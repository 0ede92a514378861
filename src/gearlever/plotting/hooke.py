"""Figures of Hooke's coupling: velocity ratio over a turn."""

from __future__ import annotations

import math

import numpy as np

from gearlever.plotting._common import axes
from gearlever.trains import hooke


def _finish_turn_axes(ax, xlabel: str, ylabel: str, title: str):
    """Label an Axes whose x axis is one turn in degrees; leave room for the legend on top."""
    ax.set_xlim(0.0, 360.0)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, hi + 0.35 * (hi - lo))  # room for the legend above the curves
    ax.legend(fontsize=7, ncol=2, loc="upper center")
    return ax


def plot_single_ratio(shaft_angles_deg=(10.0, 20.0, 30.0, 45.0), ax=None, n: int = 361):
    """Velocity ratio of a single joint over a turn, one curve per shaft angle; returns the Axes."""
    ax = axes(ax)
    phi_deg = np.linspace(0.0, 360.0, n)
    for b in shaft_angles_deg:
        ratio = hooke.velocity_ratio(np.radians(phi_deg), math.radians(b))
        ax.plot(
            phi_deg,
            ratio,
            label=f"shaft angle {b:g} deg (cos {math.cos(math.radians(b)):.3f} .. "
            f"1/cos {1 / math.cos(math.radians(b)):.3f})",
        )
    ax.axhline(1.0, color="0.5", lw=0.8, ls=":")
    return _finish_turn_axes(
        ax,
        "input angle phi (deg; 0 = input fork in the plane of the shafts)",
        "velocity ratio omega_out / omega_in (-)",
        "Single Hooke's joint: velocity ratio over a turn",
    )


def plot_double_ratio(
    cases_deg=((30.0, 30.0, 0.0), (30.0, 20.0, 0.0), (30.0, 30.0, 30.0), (30.0, 30.0, 90.0)),
    ax=None,
    n: int = 361,
):
    """Velocity ratio of double couplings (beta1, beta2, phase in deg) over a turn; returns the Axes."""
    ax = axes(ax)
    phi_deg = np.linspace(0.0, 360.0, n)
    for b1, b2, p in cases_deg:
        ratio = hooke.double_velocity_ratio(np.radians(phi_deg), math.radians(b1), math.radians(b2), math.radians(p))
        ax.plot(phi_deg, ratio, label=f"{b1:g} and {b2:g} deg, forks {p:g} deg apart")
    single = hooke.velocity_ratio(np.radians(phi_deg), math.radians(cases_deg[0][0]))
    ax.plot(phi_deg, single, color="0.6", ls="--", lw=1.0, label=f"single joint {cases_deg[0][0]:g} deg")
    return _finish_turn_axes(
        ax,
        "first-shaft angle phi (deg)",
        "velocity ratio omega_last / omega_first (-)",
        "Double Hooke's coupling: velocity ratio over a turn",
    )
