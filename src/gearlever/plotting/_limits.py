"""Sizes of figures and animations and their caps (no matplotlib: the CLI reads them at start-up)."""

from __future__ import annotations

import math

from gearlever.errors import GearleverError

#: Largest resolution (dots per inch) of a saved figure or animation.
MAX_DPI = 600
#: Largest figure width or height (inches).
MAX_SIZE_IN = 40.0
#: Smallest figure width or height (inches): room for the axes and the legend.
MIN_SIZE_IN = 1.0
#: Most pixels of one image or frame (an RGBA buffer of 100 MB while drawing).
MAX_PIXELS = 25e6
#: Most pixels of all the frames of an animation (kept as one byte a pixel until written: 200 MB).
MAX_ANIMATION_PIXELS = 2e8
#: Default still drawing of a mechanism (inches).
DRAWING_SIZE = (8.0, 5.6)
#: Default animation: 8 x 6 in at 100 dpi, 800 x 600 pixels.
ANIMATION_SIZE = (8.0, 6.0)
ANIMATION_DPI = 100


def pixels(width_in: float, height_in: float, dpi: float) -> tuple[int, int]:
    """Image size in pixels of a figure of ``width_in`` x ``height_in`` inches at ``dpi``.

    >>> pixels(8, 6, 100)
    (800, 600)
    """
    return int(round(width_in * dpi)), int(round(height_in * dpi))


def check_figure(what: str, width_in: float, height_in: float, dpi: float | None = None) -> None:
    """Refuse a figure size (inches) or resolution outside the caps, naming ``what`` (and ``dpi``).

    >>> check_figure("figsize", 8, 6, 100)
    >>> check_figure("figsize", 40, 40, 600)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: figsize 40 x 40 in at dpi 600 is 24000 x 24000 = 5.76e+08 pixels, more...
    """
    for v in (width_in, height_in):
        if not (math.isfinite(v) and MIN_SIZE_IN <= v <= MAX_SIZE_IN):
            raise GearleverError(
                f"{what} must be between {MIN_SIZE_IN:g} and {MAX_SIZE_IN:g} inches each, "
                f"got {width_in:g} x {height_in:g}"
            )
    if dpi is None:
        return
    if not (isinstance(dpi, (int, float)) and 1 <= dpi <= MAX_DPI):
        raise GearleverError(f"dpi must be between 1 and {MAX_DPI}, got {dpi!r}")
    w, h = pixels(width_in, height_in, dpi)
    if w * h > MAX_PIXELS:
        raise GearleverError(
            f"{what} {width_in:g} x {height_in:g} in at dpi {dpi:g} is {w} x {h} = {w * h:.3g} pixels, "
            f"more than the cap {MAX_PIXELS:.3g} pixels"
        )


def check_frames(what: str, frames: int, width_in: float, height_in: float, dpi: float) -> None:
    """Refuse an animation whose frames hold more than :data:`MAX_ANIMATION_PIXELS` pixels in all.

    >>> check_frames("frames", 360, 8, 6, 100)
    >>> check_frames("frames", 360, 20, 15, 100)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: frames 360 of 2000 x 1500 pixels are 1.08e+09 pixels, more than the cap 2e+08...
    """
    w, h = pixels(width_in, height_in, dpi)
    total = frames * w * h
    if total > MAX_ANIMATION_PIXELS:
        raise GearleverError(
            f"{what} {frames} of {w} x {h} pixels are {total:.3g} pixels, "
            f"more than the cap {MAX_ANIMATION_PIXELS:.3g} pixels"
        )
