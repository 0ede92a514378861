"""Shared figure helpers: new axes, deterministic atomic saving; the size caps of :mod:`._limits`."""

from __future__ import annotations

from pathlib import Path

import matplotlib.pyplot as plt

from gearlever._io import atomic_path
from gearlever.plotting._limits import (  # noqa: F401 - the figure sizes and caps, shared
    ANIMATION_DPI,
    ANIMATION_SIZE,
    DRAWING_SIZE,
    MAX_ANIMATION_PIXELS,
    MAX_DPI,
    MAX_PIXELS,
    MAX_SIZE_IN,
    MIN_SIZE_IN,
    check_figure,
    check_frames,
    pixels,
)

#: PNG metadata left out so that re-running writes the same bytes.
_PNG_METADATA = {"Software": None}


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
    with atomic_path(path) as tmp:
        fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
    plt.close(fig)
    return path
