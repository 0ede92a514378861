"""Four-bar curves over a crank turn: analogues and transmission angle."""

from __future__ import annotations

import numpy as np

from gearlever.loops import fourbar, grashof, limit_positions, transmission_angle
from gearlever.plotting._common import plt

__all__ = ["fourbar_curves"]


def fourbar_curves(ground, crank, coupler, rocker, branch="open", points=721):
    """Two panels: velocity/acceleration analogues and transmission angle; returns the Figure."""
    th = np.linspace(0.0, 2 * np.pi, points)
    r = fourbar(ground, crank, coupler, rocker, th, branch=branch)
    mu = np.degrees(transmission_angle(ground, crank, coupler, rocker, th))
    deg = np.degrees(th)
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7.0, 6.5), sharex=True, layout="constrained")
    a1.plot(deg, r.dtheta3_dphi, label=r"$d\theta_3/d\theta_2$")
    a1.plot(deg, r.dtheta4_dphi, label=r"$d\theta_4/d\theta_2$")
    a1.plot(deg, r.d2theta3_dphi2, "--", label=r"$d^2\theta_3/d\theta_2^2$")
    a1.plot(deg, r.d2theta4_dphi2, "--", label=r"$d^2\theta_4/d\theta_2^2$")
    lp = limit_positions(ground, crank, coupler, rocker, branch)
    for t in np.degrees(np.mod(lp.theta2_at_rocker_extremes, 2 * np.pi)):
        a1.axvline(t, color="0.6", lw=0.8, ls=":")
    a1.set_ylabel("analogue (rad/rad, rad/rad²)")
    a1.set_title(
        f"Four-bar {ground:g}/{crank:g}/{coupler:g}/{rocker:g} "
        f"({grashof(ground, crank, coupler, rocker).kind}, {branch}): analogues; "
        "dotted: rocker extremes"
    )
    a1.legend(fontsize=8, ncol=2)
    a1.grid(True, alpha=0.3)
    a2.plot(deg, mu, color="tab:purple", label=r"transmission angle $\mu$")
    a2.axhspan(40, 140, color="tab:green", alpha=0.1, label="40°..140° (usual design range)")
    a2.set_xlabel(r"crank angle $\theta_2$ (deg)")
    a2.set_ylabel(r"$\mu$ (deg)")
    a2.set_title("Transmission angle between coupler and rocker")
    a2.legend(fontsize=8)
    a2.grid(True, alpha=0.3)
    a2.set_xlim(0, 360)
    return fig
