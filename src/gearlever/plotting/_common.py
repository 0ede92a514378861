"""Shared figure helpers: new axes, deterministic atomic saving (the size caps live in :mod:`._limits`)."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from gearlever._io import atomic_path

#: PNG metadata left out so that re-running writes the same bytes.
_PNG_METADATA = {"Software": None}

#: Axis limits are rounded to this fraction of their span before a figure is
#: written (see :func:`settle`).
SETTLE = 1e-9


def _settled(lo: float, hi: float) -> tuple[float, float]:
    span = abs(hi - lo)
    if not (np.isfinite(lo) and np.isfinite(hi)) or span == 0:
        return lo, hi
    unit = 10.0 ** np.floor(np.log10(span * SETTLE))
    return float(np.round(lo / unit) * unit), float(np.round(hi / unit) * unit)


def settle(fig) -> None:
    """Round the limits of every linear axis of ``fig`` to :data:`SETTLE` of its span.

    A figure drawn from a computation carries its last digits, and those
    differ between machines (OpenBLAS picks its kernels by CPU): a data
    limit that moves by 1e-14 moves every grid line and label through Agg's
    pixel snapping.  The limits are the one quantity every artist of an Axes
    depends on; rounded to a decade of 1e-9 of their span they are the same on
    every machine unless a limit lies within 1e-14 of a rounding boundary, and
    the data drawn inside them differ by far less than Agg's 1/256 pixel.

    Examples
    --------
    >>> fig, ax = plt.subplots()
    >>> _ = ax.plot([0.0, 1.0 + 3e-15], [0.0, 2.0])
    >>> _ = ax.set_xlim(0.0, 1.0 + 3e-15)
    >>> settle(fig)
    >>> [float(v) for v in ax.get_xlim()]
    [0.0, 1.0]
    >>> plt.close(fig)
    """
    fig.canvas.draw()  # autoscale and aspect applied: the limits as drawn
    for ax in fig.axes:
        if ax.name != "rectilinear":
            continue
        if ax.get_xscale() == "linear":
            ax.set_xlim(*_settled(*ax.get_xlim()))
        if ax.get_yscale() == "linear":
            ax.set_ylim(*_settled(*ax.get_ylim()))


def axes(ax=None, figsize=(7.0, 4.5)):
    """Return ``ax``, or a new Axes on a new Figure when ``ax`` is None."""
    if ax is None:
        _, ax = plt.subplots(figsize=figsize, layout="constrained")
    return ax


def save(fig, path, dpi: int = 120) -> Path:
    """Save ``fig`` to ``path`` (format from the suffix) atomically, close it, return the path."""
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    metadata = _PNG_METADATA if fmt == "png" else None
    settle(fig)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
    plt.close(fig)
    return path
