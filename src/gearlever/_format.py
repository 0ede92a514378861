"""The one rule for the digits of printed and written numbers.

A number is written with the digits its computation determines.  A
coordinate of a synthesized design is counted from the *size* of its
mechanism (:func:`quantize`); a value of a table keeps its own significant
digits but is never written finer than two digits below its column's largest
value (:func:`quantize_in_column`).  The last digits of a
linear solve differ between machines (OpenBLAS picks its kernels by CPU), and
a coordinate that is zero up to rounding (``4.5e-08`` of a link of 4) or a
residual at machine precision would otherwise print its noise; quantized to
the scale, it prints as what it is.

================================  ======  ====================================
what                              digits  why
================================  ======  ====================================
kinematics (positions, rates)     12      closed forms and Newton to 1e-13 of
                                          the size, linear solves with the
                                          analytic Jacobian
forces, dynamics                  10      a linear solve whose condition
                                          number reaches 1e3 on ordinary models
simulate (integrated motion)      9       the integrator's relative tolerance
                                          is 1e-10 per step
synthesized designs and reports   10      exact solutions and polished optima
                                          are met to 1e-10 of the size
================================  ======  ====================================

Quantizing is plain IEEE arithmetic (no BLAS), so the same inputs give the
same bytes on every machine; two machines can still differ in a last written
digit when a value lies within their few-ulp difference of a rounding
boundary (a chance of about 1e-4 per number at 12 digits, less at fewer).
Tests therefore compare numbers with tolerances, never printed last digits.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "DIGITS_KINEMATICS",
    "DIGITS_FORCES",
    "DIGITS_SIMULATE",
    "DIGITS_DESIGN",
    "decade_unit",
    "quantize",
    "quantized",
    "rounded",
]

DIGITS_KINEMATICS = 12
DIGITS_FORCES = 10
DIGITS_SIMULATE = 9
DIGITS_DESIGN = 10


def decade_unit(scale: float, digits: int) -> float:
    """The last written decade of ``digits`` significant digits of ``scale``.

    >>> decade_unit(84.0, 10), decade_unit(4.5, 12)
    (1e-08, 1e-11)
    """
    return float(f"{10.0 ** (math.floor(math.log10(abs(scale))) - digits + 1):.1g}")


def quantize(v: float, scale: float, digits: int) -> float:
    """``v`` rounded to ``digits`` significant digits of ``scale`` (to ``digits`` of ``v`` when scale is 0).

    Returns a float whose shortest text has at most ``digits`` significant
    digits; NaN and infinities are returned as they are, ``-0.0`` as ``0.0``.

    Examples
    --------
    >>> quantize(4.544146903207036e-08, 4.5, 10), quantize(3.9999999175257566, 4.5, 10)
    (4.5e-08, 3.999999918)
    >>> quantize(-1.27e-14, 270.0, 12), quantize(2 / 3, 0.0, 4)
    (0.0, 0.6667)
    """
    v = float(v)
    if not math.isfinite(v):
        return v
    scale = abs(float(scale))
    if not math.isfinite(scale) or scale == 0.0:
        return float(f"{v + 0.0:.{digits}g}") + 0.0
    unit = decade_unit(scale, digits)
    q = round(v / unit) * unit
    return float(f"{q + 0.0:.{digits}g}") + 0.0


#: Digits beyond a column's own at which its scale sets a floor (see :func:`quantize_in_column`).
FLOOR_EXTRA = 2


def quantize_in_column(v: float, scale: float, digits: int) -> float:
    """``v`` at ``digits`` significant digits of itself, and never finer than ``digits + 2`` of ``scale``.

    The rule of tabular output: a value keeps its own digits (an
    acceleration of -3.93 at the start of a run that reaches 43966), and a
    value that is zero up to rounding against its column (an instant centre
    at -7e-14 in a column reaching 54) is written 0.

    Examples
    --------
    >>> quantize_in_column(-3.93359925149, 43966.4, 9), quantize_in_column(-6.97e-14, 53.6, 12)
    (-3.933599, 0.0)
    """
    v = float(v)
    if not math.isfinite(v) or v == 0.0:
        return v + 0.0
    unit = decade_unit(v, digits)
    scale = abs(float(scale))
    if math.isfinite(scale) and scale > 0.0:
        unit = max(unit, decade_unit(scale, digits + FLOOR_EXTRA))
    q = round(v / unit) * unit
    return float(f"{q + 0.0:.{digits}g}") + 0.0


def quantized(a, digits: int, scale: float | None = None) -> np.ndarray:
    """An array rounded by :func:`quantize` to ``digits`` of ``scale`` (default: its largest finite magnitude).

    Examples
    --------
    >>> quantized([90.0, -1.27e-14, 32.09436719354], 10).tolist()
    [90.0, 0.0, 32.09436719]
    """
    a = np.asarray(a, dtype=float)
    if scale is None:
        fin = np.abs(a[np.isfinite(a)])
        scale = float(fin.max()) if fin.size else 0.0
    if scale == 0.0 or not math.isfinite(scale):
        return a + 0.0
    unit = decade_unit(scale, digits)
    with np.errstate(invalid="ignore"):
        q = np.where(np.isfinite(a), np.round(a / unit) * unit, a)
    # the shortest text of each value: digits of the scale, no binary tail
    out = np.array([float(f"{v + 0.0:.{digits}g}") if math.isfinite(v) else v for v in q.reshape(-1)])
    return out.reshape(a.shape) + 0.0


def rounded(obj, digits: int, scale: float | None = None):
    """A report (nested dicts, lists, floats) with every float quantized; NaN and infinities as None.

    With ``scale`` every float is quantized to ``digits`` of it (coordinates of
    one mechanism); without, each to its own ``digits`` significant digits.

    Examples
    --------
    >>> rounded({"x": [1 / 3, float("nan")], "n": 2}, 4)
    {'x': [0.3333, None], 'n': 2}
    >>> rounded({"O2": [4.544146903e-08, 1.0]}, 10, scale=4.0)
    {'O2': [4.5e-08, 1.0]}
    """
    if isinstance(obj, dict):
        return {k: rounded(v, digits, scale) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [rounded(v, digits, scale) for v in obj]
    if isinstance(obj, (float, np.floating)):
        v = float(obj)
        if not math.isfinite(v):
            return None
        return quantize(v, 0.0 if scale is None else scale, digits)
    return obj
