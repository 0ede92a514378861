"""Velocity and acceleration plans (vector polygons) drawn from the loop engine's numbers.

The arrows come from :mod:`gearlever.loops.plan`: each side of the loop
equation is drawn head to tail from the pole ``p``; both sides end at the same
point, which is the graphical method's check that the loop is closed.  The
values drawn are rounded to about 1e-9 of the plan's size (:data:`PLOT_BITS`),
so that a figure is byte-identical on machines whose arithmetic differs in the
last bit.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from matplotlib.lines import Line2D

from gearlever._format import binary_grid
from gearlever.loops import (
    acceleration_plan,
    double_slider,
    double_slider_system,
    fourbar,
    fourbar_system,
    velocity_plan,
)
from gearlever.plotting._common import axes

__all__ = [
    "draw_plan",
    "velocity_plan_axes",
    "acceleration_plan_axes",
    "zrdpm_acceleration_plan",
    "zrdpm_plans_figure",
    "fourbar_plans",
]

_SIDE_COLOR = {1: "tab:blue", -1: "tab:red"}


def _label(prefix, term, labels):
    if labels and (term.vector, term.kind) in labels:
        return labels[(term.vector, term.kind)]
    sup = {"r": "", "s": "" if prefix == "v" else "s", "n": "n", "t": "t", "c": "c"}[term.kind]
    return f"${prefix}_{{{term.vector}}}" + (f"^{{{sup}}}$" if sup else "$")


#: Plotted values are rounded to ``2**-PLOT_BITS`` of the plan's size (about 1e-9):
#: last-bit differences between CPUs (fused multiply-add, libm) then vanish and the
#: figure's bytes are the same on every machine.
PLOT_BITS = 30


def _rounded(terms) -> list:
    """``terms`` on the grid ``2**-PLOT_BITS`` of the largest value (:func:`gearlever._format.binary_grid`)."""
    terms = list(terms)
    values = binary_grid([t.value for t in terms], PLOT_BITS)
    return [dataclasses.replace(t, value=v) for t, v in zip(terms, values)]


def draw_plan(terms, ax=None, *, prefix="a", unit="", labels=None, title=None):
    """Draw plan arrows (from :func:`~gearlever.loops.plan.velocity_plan` or
    :func:`~gearlever.loops.plan.acceleration_plan`) head to tail from the pole.

    Parameters
    ----------
    terms : list of PlanTerm
    ax : matplotlib Axes, optional
    prefix : str
        ``"v"`` or ``"a"`` for the labels.
    unit : str
        Unit for the axis labels, e.g. ``"cm/s^2"``.
    labels : dict, optional
        ``{(vector, kind): label}`` overriding the automatic labels.
    title : str, optional

    Returns
    -------
    matplotlib Axes
    """
    ax = axes(ax, figsize=(5.5, 5.0))
    terms = _rounded(terms)
    scale = max([abs(t.value) for t in terms] + [1e-300])
    pts = [0j]
    handles = []
    for side in (1, -1):
        chain = [t for t in terms if t.side == side]
        if not chain:
            continue
        names = []
        for t in chain:
            if t.vector not in names:
                names.append(t.vector)
        z = 0j
        for t in chain:
            start, end = z, z + t.value
            lab = _label(prefix, t, labels)
            if abs(t.value) > 1e-9 * scale:
                ax.annotate(
                    "",
                    xy=(end.real, end.imag),
                    xytext=(start.real, start.imag),
                    arrowprops=dict(arrowstyle="-|>", color=_SIDE_COLOR[side], lw=1.6, shrinkA=0, shrinkB=0),
                )
                mid = 0.5 * (start + end)
                nrm = 1j * t.value / abs(t.value) * 0.04 * scale * side
                ax.text(
                    (mid + nrm).real,
                    (mid + nrm).imag,
                    lab,
                    color=_SIDE_COLOR[side],
                    ha="center",
                    va="center",
                    fontsize=11,
                )
            else:
                ax.text(
                    end.real,
                    end.imag,
                    f"  {lab[:-1]} = 0$",
                    color=_SIDE_COLOR[side],
                    ha="left",
                    va="bottom",
                    fontsize=10,
                )
            z = end
            pts.append(end)
        handles.append(
            Line2D(
                [],
                [],
                color=_SIDE_COLOR[side],
                lw=1.6,
                label=" + ".join(f"${prefix}_{{{n}}}$" for n in names),
            )
        )
    xs, ys = [p.real for p in pts], [p.imag for p in pts]
    ax.plot(xs, ys, linestyle="none", marker=".", color="0.3")
    ax.plot([0], [0], "ko", ms=5)
    ax.annotate("p", (0, 0), textcoords="offset points", xytext=(5, 5))
    pad = 0.12 * scale
    # data limits, not fixed limits: with adjustable="datalim" the aspect may widen them
    ax.update_datalim([(min(xs) - pad, min(ys) - pad), (max(xs) + pad, max(ys) + pad)])
    ax.margins(0.0)
    ax.autoscale_view()
    # "datalim": the axes keep the box constrained layout gives them and the
    # limits grow to keep the aspect (a "box" aspect made the right plan taller
    # than its slot, its title ran into the suptitle and its x label was cut)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, alpha=0.3)
    what = "velocity" if prefix == "v" else "acceleration"
    ax.set_xlabel(f"x component of {what} ({unit})" if unit else f"x component of {what}")
    ax.set_ylabel(f"y component of {what} ({unit})" if unit else f"y component of {what}")
    ax.legend(handles=handles, loc="best", fontsize=9, title="each side of the loop")
    if title:
        ax.set_title(title)
    return ax


def velocity_plan_axes(system, sol, index=0, omega=1.0, ax=None, *, unit="", labels=None, title=None):
    """Velocity plan of any loop system at point ``index`` of ``sol``; returns the Axes."""
    return draw_plan(velocity_plan(system, sol, index, omega), ax, prefix="v", unit=unit, labels=labels, title=title)


def acceleration_plan_axes(system, sol, index=0, omega=1.0, alpha=0.0, ax=None, *, unit="", labels=None, title=None):
    """Acceleration plan of any loop system at point ``index`` of ``sol``; returns the Axes."""
    return draw_plan(
        acceleration_plan(system, sol, index, omega, alpha),
        ax,
        prefix="a",
        unit=unit,
        labels=labels,
        title=title,
    )


#: labels of paper eqs. 19-20 for the double-slider contour
ZRDPM_LABELS = {
    ("B", "s"): "$a_B$",
    ("A", "s"): "$a_A$",
    ("BA", "n"): "$a_{BA}^n$",
    ("BA", "t"): "$a_{BA}^t$",
}


def zrdpm_acceleration_plan(l=21.0, r=0.0, phi_deg=30.0, omega=1.0, alpha=0.0, ax=None):
    """Acceleration plan of the ZRDPM contour-1 double slider, labelled as paper eqs. 19-20.

    ``a_B = a_A + a_BA^n + a_BA^t`` with ``a_B`` along the x guide and ``a_A``
    along the y guide, for link length ``l`` (cm), input angle ``phi_deg``,
    input speed ``omega`` (rad/s) and acceleration ``alpha`` (rad/s^2).
    Returns the Axes.
    """
    system = double_slider_system(l, r)
    sol = double_slider(l, r, [math.radians(phi_deg)])
    title = (
        f"ZRDPM contour 1 acceleration plan (eqs. 19-20)\n"
        f"$l_1$ = {l:g} cm, $\\varphi$ = {phi_deg:g}°, $\\omega_9$ = {omega:g} rad/s, "
        f"$\\varepsilon_9$ = {alpha:g} rad/s²"
    )
    ax = acceleration_plan_axes(system, sol, 0, omega, alpha, ax, unit="cm/s²", labels=ZRDPM_LABELS, title=title)
    ax.text(0.02, 0.03, r"$a_B = a_A + a_{BA}^n + a_{BA}^t$", transform=ax.transAxes, fontsize=10)
    return ax


def zrdpm_plans_figure(l=21.0, r=0.0, phi_deg=30.0, omega=1.0, alpha=0.5):
    """Two ZRDPM plans side by side: constant input speed, and input acceleration ``alpha``."""
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.0, 5.0), layout="constrained")
    zrdpm_acceleration_plan(l, r, phi_deg, omega, 0.0, ax=a1)
    zrdpm_acceleration_plan(l, r, phi_deg, omega, alpha, ax=a2)
    return fig


def fourbar_plans(ground, crank, coupler, rocker, theta2_deg, omega=1.0, alpha=0.0, branch="open", unit="cm"):
    """Velocity and acceleration plans of a four-bar at one crank angle; returns the Figure."""
    import matplotlib.pyplot as plt

    th = np.array([math.radians(theta2_deg)])
    r = fourbar(ground, crank, coupler, rocker, th, branch=branch, strict=True)
    system = fourbar_system(ground, crank, coupler, rocker)
    sol = system.solve(th, {"theta3": float(r.theta3[0]), "theta4": float(r.theta4[0])}, strict=True)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10.5, 5.0), layout="constrained")
    velocity_plan_axes(
        system,
        sol,
        0,
        omega,
        ax=a1,
        unit=f"{unit}/s",
        title=f"Velocity plan, $\\theta_2$ = {theta2_deg:g}°, $\\omega_2$ = {omega:g} rad/s",
    )
    acceleration_plan_axes(
        system,
        sol,
        0,
        omega,
        alpha,
        ax=a2,
        unit=f"{unit}/s²",
        title=f"Acceleration plan, $\\alpha_2$ = {alpha:g} rad/s²",
    )
    fig.suptitle(
        f"Four-bar {ground:g}/{crank:g}/{coupler:g}/{rocker:g} {unit} (ground/crank/coupler/rocker), {branch} branch"
    )
    return fig
