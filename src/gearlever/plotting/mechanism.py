"""Drawings of mechanism models: links, joints, sliders, gears as pitch circles, point paths; GIF animation."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearlever._io import atomic_path
from gearlever._validate import positive_int
from gearlever.plotting._common import axes, plt

__all__ = ["draw_mechanism", "animate_mechanism"]

_COLORS = plt.rcParams["axes.prop_cycle"].by_key()["color"]


def _configuration(mech, result, row):
    """Point positions (dict) and link angles at ``row`` of ``result`` (the sketch when None)."""
    m = mech.model
    if result is None:
        return dict(m.points), {k: 0.0 for k in m.links}
    pts = {p: tuple(result.point[p][row]) for p in result.point}
    rot = {k: (result.angle[k][row] - m.links[k].angle0) for k in m.links}
    return pts, rot


def _draw_frame(ax, mech, pts, rot):
    m = mech.model
    artists = []
    for i, (name, link) in enumerate(m.links.items()):
        xy = np.array([pts[p] for p in link.points])
        if not np.all(np.isfinite(xy)):
            continue
        if name == "ground":
            artists += ax.plot(xy[:, 0], xy[:, 1], "k^", ms=8, zorder=3)
            continue
        color = _COLORS[i % len(_COLORS)]
        if len(xy) >= 3:
            artists += ax.fill(xy[:, 0], xy[:, 1], color=color, alpha=0.25, zorder=1)
            closed = np.vstack([xy, xy[:1]])
            artists += ax.plot(closed[:, 0], closed[:, 1], "-", color=color, lw=2, zorder=2)
        elif len(xy) == 2:
            artists += ax.plot(xy[:, 0], xy[:, 1], "-", color=color, lw=2.5, zorder=2, label=name)
    joints = {p for p, _, _ in m.joints}
    for p in joints:
        x, y = pts[p]
        if np.isfinite(x):
            artists += ax.plot([x], [y], "o", mfc="white", mec="k", ms=5, zorder=4)
    for s in m.sliders:
        x, y = pts[s.point]
        if not np.isfinite(x):
            continue
        th = rot[s.on]
        u = np.array(
            [
                np.cos(th) * s.direction[0] - np.sin(th) * s.direction[1],
                np.sin(th) * s.direction[0] + np.cos(th) * s.direction[1],
            ]
        )
        L = 0.25 * m.length_scale
        artists += ax.plot([x - L * u[0], x + L * u[0]], [y - L * u[1], y + L * u[1]], "k--", lw=0.8, zorder=1)
        artists += ax.plot([x], [y], "s", mfc="0.8", mec="k", ms=9, zorder=3)
    t = np.linspace(0, 2 * np.pi, 73)
    for g in m.gears.values():
        r = m.pitch_radius(g.name)
        x, y = pts[g.centre]
        if r is None or not np.isfinite(x):
            continue
        ls = "-." if g.internal else "-"
        artists += ax.plot(x + r * np.cos(t), y + r * np.sin(t), ls, color="0.35", lw=1, zorder=1)
        th = rot[g.link]
        artists += ax.plot([x, x + r * np.cos(th)], [y, y + r * np.sin(th)], "-", color="0.35", lw=0.8)
    return artists


def draw_mechanism(mech, result=None, row=None, ax=None):
    """Draw a mechanism at the sketch (or at ``row`` of ``result``) with the point paths of ``result``.

    Parameters
    ----------
    mech : gearlever.Mechanism
    result : MechanismResult, optional
        A sweep; the path of every point not on ground is drawn dotted.
    row : int, optional
        Row of ``result`` to draw; the sketch when None.
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib.axes.Axes
    """
    ax = axes(ax, figsize=(5.5, 4.5))
    m = mech.model
    if result is not None:
        ground_pts = set(m.links["ground"].points)
        for p, xy in result.point.items():
            if p not in ground_pts:
                ax.plot(xy[:, 0], xy[:, 1], ":", lw=1, color="0.45", zorder=0)
    pts, rot = _configuration(mech, result if row is not None else None, row)
    _draw_frame(ax, mech, pts, rot)
    for p, (x, y) in pts.items():
        if np.isfinite(x):
            ax.annotate(p, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_aspect("equal", adjustable="datalim")
    unit = f" ({m.units})" if m.units else ""
    ax.set_xlabel(f"x{unit}")
    ax.set_ylabel(f"y{unit}")
    ax.set_title(m.name, fontsize=10)
    return ax


def animate_mechanism(mech, result, path, fps: int = 12, dpi: int = 60) -> Path:
    """Write a GIF with one frame per row of ``result`` to ``path`` (atomically); return the path."""
    from matplotlib.animation import PillowWriter

    frames = positive_int("frames", len(result.closed))
    fig = plt.figure(figsize=(4.5, 3.8))
    ax = fig.add_axes((0.14, 0.12, 0.82, 0.8))
    allxy = np.concatenate([v for v in result.point.values()] + [np.array(list(mech.model.points.values()))])
    allxy = allxy[np.all(np.isfinite(allxy), axis=1)]
    pad = (
        0.1 * mech.model.length_scale + max((mech.model.pitch_radius(g) or 0.0) for g in mech.model.gears)
        if mech.model.gears
        else 0.1 * mech.model.length_scale
    )
    ax.set_xlim(allxy[:, 0].min() - pad, allxy[:, 0].max() + pad)
    ax.set_ylim(allxy[:, 1].min() - pad, allxy[:, 1].max() + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_title(mech.model.name, fontsize=9)
    for xy in result.point.values():
        ax.plot(xy[:, 0], xy[:, 1], ":", lw=1, color="0.6")
    path = Path(path)
    with atomic_path(path, suffix=".gif") as tmp:
        writer = PillowWriter(fps=fps)
        with writer.saving(fig, str(tmp), dpi):
            current: list = []
            for i in range(frames):
                for a in current:
                    a.remove()
                pts, rot = _configuration(mech, result, i)
                current = _draw_frame(ax, mech, pts, rot)
                writer.grab_frame()
    plt.close(fig)
    return path
