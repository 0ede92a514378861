"""Figures of linkage synthesis: function-generator curves, poses, Burmester curves, the linkage drawn."""

from __future__ import annotations

import numpy as np

from gearlever.plotting._common import axes, plt

__all__ = ["draw_linkage", "function_curves", "function_figure", "burmester_plot", "motion_figure"]


def draw_linkage(model: dict, ax=None, color="k", label=None):
    """Draw a synthesized model's links at its sketch pose (ground pivots as triangles); returns the Axes."""
    ax = axes(ax)
    pts = {k: np.asarray(v, dtype=float) for k, v in model["points"].items()}
    first = True
    for link, names in model["links"].items():
        xy = np.array([pts[n] for n in names])
        if link == "ground":
            ax.plot(xy[:, 0], xy[:, 1], "^", color="0.3", ms=9, zorder=3)
            continue
        if len(names) > 2:
            xy = np.vstack([xy, xy[:1]])
            ax.fill(xy[:, 0], xy[:, 1], color=color, alpha=0.12)
        ax.plot(xy[:, 0], xy[:, 1], "-o", color=color, lw=2, ms=4, label=label if first else None)
        first = False
    for s in model.get("sliders", []):
        p = pts[s["point"]]
        u = np.asarray(s["direction"], dtype=float)
        u = u / np.hypot(*u)
        span = max(np.ptp([q[0] for q in pts.values()]), np.ptp([q[1] for q in pts.values()]), 1e-9)
        line = np.array([p - span * u, p + 0.3 * span * u])
        ax.plot(line[:, 0], line[:, 1], ":", color="0.4", lw=1)
        ax.plot(*p, "s", color=color, ms=10, mfc="none")
    for k, p in pts.items():
        ax.annotate(k, p, textcoords="offset points", xytext=(4, 4), fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    return ax


def function_curves(result, ax=None):
    """Wanted and generated output over the input range, and the targets; returns the Axes."""
    ax = axes(ax)
    deg = result.kind == "fourbar"
    conv = np.degrees if deg else (lambda v: np.asarray(v))
    x = np.degrees(result.dense_input)
    ax.plot(x, conv(result.dense_target), color="tab:blue", lw=2, label="wanted")
    ax.plot(x, conv(result.dense_achieved), "--", color="tab:red", lw=1.5, label="generated (engine)")
    ax.plot(np.degrees(result.input_angle), conv(result.target), "ko", ms=5, label="targets")
    ax.set_xlabel("crank angle (deg)")
    ax.set_ylabel("rocker angle (deg)" if deg else "slider travel")
    err = conv(result.structural_error_max)
    ax.set_title(f"Function generator: max structural error {float(err):.4g}{' deg' if deg else ''}")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    return ax


def function_figure(result):
    """Two panels: :func:`function_curves` and the linkage at the first target; returns the Figure."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11.0, 4.5), layout="constrained")
    function_curves(result, a1)
    draw_linkage(result.model, a2)
    lens = ", ".join(f"{k} {v:.4g}" for k, v in result.lengths.items())
    a2.set_title(f"At the first target: {lens}", fontsize=9)
    a2.grid(True, alpha=0.3)
    return fig


def burmester_plot(curves, ax=None):
    """Centre-point and circle-point curves of four poses (:class:`~gearlever.synthesis.motion.BurmesterCurves`)."""
    ax = axes(ax)
    c, m = curves.center, curves.circle
    allxy = np.concatenate([c.reshape(-1, 2), m.reshape(-1, 2)])
    ok = np.all(np.isfinite(allxy), axis=1)
    if ok.any():
        lo, hi = np.percentile(allxy[ok], [10, 90], axis=0)
        pad = 1.5 * (hi - lo).max() + 1e-9
        mid = (lo + hi) / 2
    for b in range(2):
        for arr, col, lab in ((c, "tab:blue", "centre points"), (m, "tab:orange", "circle points")):
            xy = arr[:, b, :].copy()
            if ok.any():
                far = np.any(np.abs(xy - mid) > pad, axis=1)
                xy[far] = np.nan
            ax.plot(xy[:, 0], xy[:, 1], ".", ms=2, color=col, label=lab if b == 0 else None)
    if ok.any():
        ax.set_xlim(mid[0] - pad, mid[0] + pad)
        ax.set_ylim(mid[1] - pad, mid[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_title("Burmester curves (four poses)")
    ax.legend(fontsize=8, markerscale=4)
    return ax


def _poses(ax, points, angles, scale):
    for (x, y), a in zip(points, angles):
        ax.annotate(
            "", (x + scale * np.cos(a), y + scale * np.sin(a)), (x, y), arrowprops={"arrowstyle": "->", "color": "g"}
        )
    ax.plot(points[:, 0], points[:, 1], "gs", ms=6, label="poses")


def motion_figure(result, curves=None, coupler_path=None):
    """Poses, the best linkage at the first pose, its coupler path; Burmester curves beside when given."""
    ncol = 2 if curves is not None else 1
    fig, axs = plt.subplots(1, ncol, figsize=(6.5 * ncol, 5.5), layout="constrained", squeeze=False)
    ax = axs[0, 0]
    best = result.best
    span = float(np.ptp(result.points, axis=0).max()) or 1.0
    if coupler_path is not None:
        ax.plot(coupler_path[:, 0], coupler_path[:, 1], "-", color="tab:purple", lw=1, label="coupler point path")
    draw_linkage(best.model, ax, label="linkage at pose 1")
    _poses(ax, result.points, result.angles, 0.3 * span)
    ax.set_title(
        f"Motion generation ({result.method}): residual {best.residual:.2g}, "
        f"{best.grashof}{', ' + best.defect if best.defect else ''}",
        fontsize=9,
    )
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    if curves is not None:
        burmester_plot(curves, axs[0, 1])
        _poses(axs[0, 1], result.points, result.angles, 0.3 * span)
        for d in (best.crank, best.rocker):
            axs[0, 1].plot(*d.ground_pivot, "k^", ms=9)
            axs[0, 1].plot(*d.moving_pivot, "ko", ms=6, mfc="none")
    return fig
