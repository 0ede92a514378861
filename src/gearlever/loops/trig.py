"""Sine and cosine of an array together, from one tangent of the half angle.

Used where both are needed for every element (the ZRDPM fast path, the
input links of :mod:`gearlever.mechanism.assur`); speed is measured in
``benchmarks/bench_zrdpm.py`` and ``benchmarks/bench_mechanism.py``.
"""

from __future__ import annotations

import numpy as np

__all__ = ["sincos_half_angle"]


def sincos_half_angle(phi: np.ndarray, sin_out: np.ndarray, cos_out: np.ndarray) -> None:
    """Write ``sin(phi)`` and ``cos(phi)`` into the given arrays, from one tangent of the half angle.

    With ``t = tan(phi / 2)``: ``cos(phi) = 2 / (1 + t**2) - 1`` and
    ``sin(phi) = t (2 / (1 + t**2))``: one transcendental call instead of two,
    then four multiply-adds.  ``sin_out`` serves as scratch for ``t``.  Within
    3.4e-16 (absolute) of ``np.sin`` and ``np.cos`` for any finite angle
    (measured on 10^6 angles per decade up to 1e300; tested).

    Notes
    -----
    The tangent half-angle substitution (Weierstrass).  Why: numpy evaluates
    float64 ``sin`` and ``cos`` one element at a time through the C library
    (its SIMD versions are disabled for accuracy), but ``tan`` by a SIMD
    kernel where the CPU has AVX-512 (numpy's SVML dispatch): on the 2-core
    Intel Xeon (AVX-512) measured 4 ns a tangent against 11-19 ns a sine or
    cosine.  Near ``phi = pi`` (``t`` large) both forms stay exact to rounding:
    ``2 / (1 + t**2)`` tends to 0, never to an overflow for a finite float
    angle (the closest a float comes to an odd multiple of pi gives ``|t|``
    below 1e17).

    Examples
    --------
    >>> s, c = np.empty(3), np.empty(3)
    >>> sincos_half_angle(np.array([0.0, np.pi / 2, np.pi]), s, c)
    >>> np.round(s, 15).tolist(), np.round(c, 15).tolist()
    ([0.0, 1.0, 0.0], [1.0, 0.0, -1.0])
    """
    t = sin_out
    np.multiply(phi, 0.5, out=t)
    np.tan(t, out=t)
    np.multiply(t, t, out=cos_out)
    cos_out += 1.0
    np.divide(2.0, cos_out, out=cos_out)
    t *= cos_out  # sin = t * 2 / (1 + t^2)
    cos_out -= 1.0
