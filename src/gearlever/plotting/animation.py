"""Animated GIF of a four-bar over a crank turn (matplotlib's Pillow writer)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from gearlever._io import atomic_path
from gearlever._validate import positive_int
from gearlever.loops import fourbar, grashof
from gearlever.plotting._common import plt

__all__ = ["fourbar_frames", "animate_fourbar"]


def fourbar_frames(ground, crank, coupler, rocker, frames=36, branch="open"):
    """Joint positions O2, A, B, O4 per frame: complex array (frames, 4) (NaN where open)."""
    frames = positive_int("frames", frames)
    th = np.linspace(0.0, 2 * np.pi, frames, endpoint=False)
    r = fourbar(ground, crank, coupler, rocker, th, branch=branch)
    a = crank * np.exp(1j * th)
    b = a + coupler * np.exp(1j * r.theta3)
    return th, np.stack([np.zeros_like(a), a, b, np.full_like(a, ground)], axis=-1)


def animate_fourbar(ground, crank, coupler, rocker, path, frames=36, branch="open", fps=12, dpi=60):
    """Write a GIF of the four-bar over one crank turn to ``path`` (atomically); return the path.

    Frames where the linkage cannot close show the ground only.
    """
    from matplotlib.animation import PillowWriter

    th, P = fourbar_frames(ground, crank, coupler, rocker, frames, branch)
    kind = grashof(ground, crank, coupler, rocker).kind
    # fixed axes position (no layout engine): each frame is drawn exactly once
    fig = plt.figure(figsize=(4.0, 3.4))
    ax = fig.add_axes((0.16, 0.14, 0.8, 0.74))
    finite = P[np.isfinite(P)]
    xs, ys = finite.real, finite.imag
    pad = 0.1 * max(ground, crank, coupler, rocker)
    ax.set_xlim(xs.min() - pad, xs.max() + pad)
    ax.set_ylim(ys.min() - pad, ys.max() + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (length units)")
    ax.set_ylabel("y (length units)")
    ax.plot([0, ground], [0, 0], "k--", lw=1, label="ground")
    (crank_line,) = ax.plot([], [], "-o", color="tab:blue", lw=2, ms=4, label="crank")
    (coupler_line,) = ax.plot([], [], "-o", color="tab:orange", lw=2, ms=4, label="coupler")
    (rocker_line,) = ax.plot([], [], "-o", color="tab:green", lw=2, ms=4, label="rocker")
    (path_line,) = ax.plot(P[:, 2].real, P[:, 2].imag, ":", color="0.5", lw=1, label="path of B")
    ax.legend(loc="upper left", fontsize=7)
    title = ax.set_title("")

    def draw(i):
        o2, a, b, o4 = P[i]
        if np.isfinite(b):
            crank_line.set_data([o2.real, a.real], [o2.imag, a.imag])
            coupler_line.set_data([a.real, b.real], [a.imag, b.imag])
            rocker_line.set_data([o4.real, b.real], [o4.imag, b.imag])
        else:
            for ln in (crank_line, coupler_line, rocker_line):
                ln.set_data([], [])
        title.set_text(f"{kind}, {branch}: θ2 = {np.degrees(th[i]):.0f}°")
        return crank_line, coupler_line, rocker_line, title

    path = Path(path)
    writer = PillowWriter(fps=fps)
    try:
        with atomic_path(path, suffix=".tmp.gif") as tmp:
            with writer.saving(fig, tmp, dpi):
                for i in range(len(th)):
                    draw(i)
                    writer.grab_frame()
    finally:
        plt.close(fig)
    return path
