"""Figures of motion laws and disc cams: SVAJ diagrams and the cam profile."""

from __future__ import annotations

import math

import matplotlib.pyplot as plt
import numpy as np

from gearlever.plotting._common import axes

__all__ = ["cam_design_figure", "cam_profile_plot", "svaj_plot"]

_NAMES = (("s", "displacement"), ("v", "velocity"), ("a", "acceleration"), ("j", "jerk"))


def svaj_plot(values, axs=None, label: str | None = None):
    """The four SVAJ diagrams of a :class:`~gearlever.laws.LawValues` over the input angle.

    Parameters
    ----------
    values : LawValues
        From :meth:`MotionLaw.evaluate` (per radian, or per second).
    axs : sequence of 4 Axes, optional
        Where to draw; a new figure of four stacked panels when None.
    label : str, optional
        Legend label of the curves.

    Returns
    -------
    list of Axes

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "345", "rise": -10}])
    >>> len(svaj_plot(law.evaluate(np.linspace(0, 2 * np.pi, 361))))
    4
    """
    if axs is None:
        _, axs = plt.subplots(4, 1, figsize=(6.0, 7.0), sharex=True, layout="constrained")
    angle = values.output == "angle"
    unit = "deg" if angle else values.units
    scale = 180 / math.pi if angle else 1.0
    per = "rad" if values.per == "rad" else "s"
    x = np.degrees(values.theta)
    order = np.argsort(x)
    for k, (ax, (field, name)) in enumerate(zip(axs, _NAMES, strict=True)):
        y = getattr(values, field) * scale
        ax.plot(x[order], y[order], lw=1.2, label=label)
        ax.axhline(0.0, color="0.6", lw=0.6)
        suffix = "" if k == 0 else f"/{per}" + ("" if k == 1 else f"^{k}")
        ax.set_ylabel(f"{field} ({unit}{suffix})")
        ax.set_title(name, fontsize=9, loc="left")
        ax.grid(True, lw=0.3)
    axs[-1].set_xlabel("input angle (deg)")
    axs[-1].set_xlim(0, 360)
    axs[-1].set_xticks(np.arange(0, 361, 60))
    return list(axs)


def cam_profile_plot(design, ax=None, at: float = 0.0):
    """The cam surface, pitch curve, base circle and the follower at cam angle ``at`` (rad).

    The cam is drawn turned by ``at`` (counterclockwise) in the fixed frame,
    so the follower sits where the law puts it.

    Examples
    --------
    >>> from gearlever.laws import law_from_segments
    >>> from gearlever.cams import design_cam
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "345", "rise": -10}])
    >>> ax = cam_profile_plot(design_cam(law, "translating-roller", base_radius=30, roller_radius=5, points=720))
    >>> ax.get_aspect()
    1.0
    """
    ax = axes(ax, figsize=(5.0, 5.0))
    c, s = math.cos(at), math.sin(at)
    rot = np.array([[c, s], [-s, c]])

    def closed(pts):
        pts = pts @ rot
        return np.vstack([pts, pts[:1]])

    surf = closed(design.surface)
    ax.fill(surf[:, 0], surf[:, 1], color="0.85", zorder=1)
    ax.plot(surf[:, 0], surf[:, 1], color="k", lw=1.2, label="cam surface", zorder=2)
    if np.all(np.isfinite(design.pitch)):
        pitch = closed(design.pitch)
        ax.plot(pitch[:, 0], pitch[:, 1], color="C0", lw=0.8, ls="--", label="pitch curve")
    t = np.linspace(0, 2 * math.pi, 361)
    rb = design.base_radius
    ax.plot(rb * np.cos(t), rb * np.sin(t), color="0.5", lw=0.6, ls=":", label="base circle")
    ax.plot([0], [0], marker="+", color="k")
    k = int(np.argmin(np.abs(np.angle(np.exp(1j * (design.theta - at))))))
    contact = design.contact[k]
    if np.all(np.isfinite(design.pitch)):
        centre = design.pitch[k] @ rot
        r = design.roller_radius
        ax.plot(centre[0] + r * np.cos(t), centre[1] + r * np.sin(t), color="C3", lw=1.0, label="roller")
        if math.isfinite(design.pivot_distance):
            ax.plot([design.pivot_distance, centre[0]], [0.0, centre[1]], color="C3", lw=1.5)
            ax.plot([design.pivot_distance], [0.0], marker="o", color="C3")
        else:
            ax.plot([centre[0], centre[0]], [centre[1], centre[1] + 1.5 * r + design.stroke], color="C3", lw=1.5)
    else:
        pos = np.array([design.face_contact_min, design.face_contact_max])
        if math.isfinite(design.pivot_distance):
            pivot = np.array([design.pivot_distance, 0.0])
            d = contact - pivot
            reach = max(float(pos.max()), float(np.hypot(*d))) * 1.1
            ends = pivot + np.outer([0.0, reach], d / max(float(np.hypot(*d)), 1e-300))
            ax.plot(ends[:, 0], ends[:, 1], color="C3", lw=2.0, label="face")
            ax.plot([pivot[0]], [pivot[1]], marker="o", color="C3")
        else:
            x = design.offset + pos
            ax.plot(x, [contact[1], contact[1]], color="C3", lw=2.0, label="face")
    ax.plot([contact[0]], [contact[1]], marker=".", color="C3")
    ax.set_aspect("equal")
    unit = "" if design.units == "length" else f" {design.units}"
    ax.set_title(f"{design.follower} cam, base radius {design.base_radius:.4g}{unit}", fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(True, lw=0.3)
    return ax


def cam_design_figure(design, values):
    """SVAJ diagrams (left) and the cam profile (right) on one Figure.

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.laws import law_from_segments
    >>> from gearlever.cams import design_cam
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...                                                 {"to": 360, "motion": "345", "rise": -10}])
    >>> cam = design_cam(law, "translating-flat", base_radius=30, points=720)
    >>> len(cam_design_figure(cam, law.evaluate(cam.theta)).axes)
    5
    """
    fig = plt.figure(figsize=(11.0, 7.0), layout="constrained")
    grid = fig.add_gridspec(4, 2, width_ratios=(1.0, 1.2))
    first = fig.add_subplot(grid[0, 0])
    axs = [first] + [fig.add_subplot(grid[k, 0], sharex=first) for k in range(1, 4)]
    svaj_plot(values, axs)
    cam_profile_plot(design, fig.add_subplot(grid[:, 1]))
    return fig
