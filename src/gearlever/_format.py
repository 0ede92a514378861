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
    "rounded_report",
    "format_number",
    "below",
    "page_numbers",
    "binary_grid",
    "toml_value",
    "toml_key",
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


def rounded_report(rep: dict, digits: int, scales: dict) -> dict:
    """A report rounded by :func:`rounded`: each key of ``scales`` at ``digits`` of its scale, the rest of itself.

    The digits of a synthesis report: distances at the targets' size ``S``,
    objectives (sums of squares) at ``S**2``, angles of 360 deg, so that an
    exact fit is written 0, not its rounding noise.

    >>> rounded_report({"error": 3e-13, "angle": 90.00000000001, "n": 2}, 10, {"error": 4.0})
    {'error': 0.0, 'angle': 90.0, 'n': 2}
    """
    out = rounded(rep, digits)
    for key, scale in scales.items():
        if key in rep:
            out[key] = rounded(rep[key], digits, scale)
    return out


def format_number(v, digits: int = 12) -> str:
    """One number as CSV text: ``digits`` significant digits, ``nan``/``inf`` spelt out, never ``-0``.

    >>> format_number(-0.0), format_number(float("nan")), format_number(1 / 3, 6)
    ('0', 'nan', '0.333333')
    """
    v = float(v)
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    return f"{v + 0.0:.{digits}g}"  # + 0.0: no "-0"


def below(v, scale: float, digits: int = DIGITS_DESIGN, fmt: str = ".6g") -> str:
    """A quantized error as printed: ``below`` the last decade of ``scale`` when it is 0, else ``v`` in ``fmt``.

    >>> below(0.0, 4.0), below(2.5e-6, 4.0, fmt=".3g"), below(None, 1.0)
    ('below 1e-09', '2.5e-06', 'none')
    """
    if v is None:
        return "none"
    return f"below {decade_unit(scale, digits):g}" if v == 0 else f"{v:{fmt}}"


def page_numbers(a, digits: int, scale: float | None = None, *, integers: bool = False) -> list:
    """An array as a JSON-ready list for a page: ``digits`` significant digits, None for NaN, no ``-0``.

    Values below ``1e-12 scale`` are rounding noise: written as 0 (no floor
    when ``scale`` is None).  With ``integers``, whole values below 1e15 are
    written as ints (``5`` rather than ``5.0``, shorter pages).

    >>> page_numbers([1 / 3, -1e-15, float("nan"), 2.0], 4, scale=1.0, integers=True)
    [0.3333, 0, None, 2]
    """
    a = np.asarray(a, dtype=float).ravel()
    if scale is not None:
        a = np.where(np.abs(a) < 1e-12 * scale, 0.0, a)
    out = [float(f"{v:.{digits}g}") if math.isfinite(v) else None for v in a.tolist()]
    if integers:
        out = [int(v) if v is not None and v.is_integer() and abs(v) < 1e15 else v for v in out]
    return [0 if v == 0 else v for v in out]


def binary_grid(values, bits: int) -> list:
    """Complex ``values`` rounded to the power-of-two grid ``2**-bits`` of the largest magnitude of a part.

    A power of two keeps the rounding exact; the grid is chosen from the largest
    value's binary exponent, which last-bit differences between machines do not
    change (except at an exact power of two, where both sides then round alike
    anyway).  Values are returned unchanged when all are 0 or one is not finite.

    >>> binary_grid([complex(1.0, 1e-12), complex(0.5, 0.25)], 30)
    [(1+0j), (0.5+0.25j)]
    """
    values = [complex(v) for v in values]
    big = max([abs(v) for v in values] + [0.0])
    if not big > 0 or not math.isfinite(big):
        return values
    grid = 2.0 ** (math.frexp(big)[1] - bits)

    def r(x: float) -> float:
        return round(x / grid) * grid + 0.0

    return [complex(r(v.real), r(v.imag)) for v in values]


def toml_value(v, digits: int = 12) -> str:
    """One TOML value: floats at ``digits`` significant digits (``.0`` kept), ``nan``/``inf`` spelt as TOML does.

    Strings are basic strings (JSON's escapes, which TOML shares), lists are
    arrays and dicts inline tables.

    >>> toml_value(90.0), toml_value(1 / 3, 6), toml_value(float("nan")), toml_value(["a", 2, True])
    ('90.0', '0.333333', 'nan', '["a", 2, true]')
    """
    import json

    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, (float, np.floating)):
        text = format_number(v, digits)
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(toml_value(x, digits) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{toml_key(k)} = {toml_value(x, digits)}" for k, x in v.items()) + " }"
    raise TypeError(f"cannot write {type(v).__name__} as a TOML value")


def toml_key(k) -> str:
    """A TOML key: bare when it is ASCII letters, digits, ``_`` and ``-``, else quoted.

    >>> toml_key("base_radius"), toml_key("a b")
    ('base_radius', '"a b"')
    """
    k = str(k)
    return k if k and k.isascii() and all(c.isalnum() or c in "_-" for c in k) else toml_value(k)
