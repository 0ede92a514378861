"""Compiled kernels: a sine and cosine of float64 that vectorize on any x86 CPU.

Imported on first use by the fast paths only (never at ``import gearlever``):
importing numba takes about 0.4 s, and the first call of a kernel compiles it
once per machine into numba's on-disk cache (about 1.5 s), after which a call
loads it from there.

Why a kernel of our own: numpy evaluates float64 ``sin``, ``cos`` and (without
AVX-512) ``tan`` one element at a time through the C library, 11 to 14 ns an
element on the 2-core Intel Xeon these were measured on; a loop of
multiply-adds that LLVM vectorizes gives both in about 3 ns, with AVX2 or
AVX-512 alike.  The same code gives the same bits on every x86 CPU: only
additions, multiplications and a rounding to an integer, in a fixed order,
never fused into multiply-adds (numba does not contract without ``fastmath``),
so the vector width does not change a result (tested across numba's target
CPUs).

Within the layering of ``loops`` it imports numpy and numba only.
"""

from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["SINCOS_LIMIT", "jit", "sincos", "sincos_into"]

#: Largest ``|x|`` the polynomial path reduces exactly: ``k * _PIO2_1`` is exact for ``|k| < 2**20``.
#: Beyond it a kernel recomputes its block through the C library's ``sin`` and ``cos``.
SINCOS_LIMIT = 2.0**19

# Cody and Waite's reduction x - k pi/2 with pi/2 split in three parts, the first two of 33 bits, so
# that k * part is exact (the split of fdlibm's e_rem_pio2.c, Sun Microsystems 1993).
_INV_PIO2 = 6.36619772367581382433e-01
_PIO2_1 = 1.57079632673412561417e00
_PIO2_2 = 6.07710050630396597660e-11
_PIO2_3 = 2.02226624871116645580e-21
# Minimax polynomials of sin and cos on [-pi/4, pi/4], error below 2**-58 (fdlibm's __kernel_sin.c and
# __kernel_cos.c, Sun Microsystems 1993).
_S1 = -1.66666666666666324348e-01
_S2 = 8.33333333332248946124e-03
_S3 = -1.98412698298579493134e-04
_S4 = 2.75573137070700676789e-06
_S5 = -2.50507602534068634195e-08
_S6 = 1.58969099521155010221e-10
_C1 = 4.16666666666666019037e-02
_C2 = -1.38888888888741095749e-03
_C3 = 2.48015872894767294178e-05
_C4 = -2.75573143513906633035e-07
_C5 = 2.08757232129817482790e-09
_C6 = -1.13596475577881948265e-11


def jit(fn):
    """``numba.njit`` with the on-disk cache, numpy's error model and no bounds checks.

    Where no cache directory can be written (a read-only install without a
    writable home), the kernel compiles at each first call instead.
    """
    try:
        return numba.njit(cache=True, error_model="numpy", boundscheck=False)(fn)
    except RuntimeError:  # numba: "cannot cache function ...: no locator available"
        return numba.njit(error_model="numpy", boundscheck=False)(fn)


@numba.njit(inline="always", error_model="numpy")
def sincos(x, libm):
    """``(sin x, cos x)``: the polynomial path, or the C library's where ``libm`` is true.

    Inlined into the kernels, which call it with ``libm`` False in their
    vectorized loop (valid for ``|x| <= SINCOS_LIMIT``) and True in the
    fix-up of a block holding a larger angle.

    Notes
    -----
    ``k = rint(2x / pi)``, ``r = x - k pi/2`` (Cody and Waite, *Software
    Manual for the Elementary Functions*, 1980, ch. 8), ``sin r`` and
    ``cos r`` by fdlibm's minimax polynomials, then the quadrant ``k mod 4``
    swaps and signs them.
    """
    if libm:
        return math.sin(x), math.cos(x)
    k = np.rint(x * _INV_PIO2)
    r = x - k * _PIO2_1
    r = r - k * _PIO2_2
    r = r - k * _PIO2_3
    z = r * r
    s = r + r * z * (_S1 + z * (_S2 + z * (_S3 + z * (_S4 + z * (_S5 + z * _S6)))))
    c = (1.0 - 0.5 * z) + z * z * (_C1 + z * (_C2 + z * (_C3 + z * (_C4 + z * (_C5 + z * _C6)))))
    q = np.int64(k) & 3
    odd = (q & 1) == 1
    sn = c if odd else s
    cs = s if odd else c
    return (-sn if q & 2 else sn), (-cs if (q + 1) & 2 else cs)


@jit
def _sincos_poly(phi, sin_out, cos_out):
    far = 0
    for j in range(phi.size):
        far += abs(phi[j]) > SINCOS_LIMIT
        sin_out[j], cos_out[j] = sincos(phi[j], False)
    return far


@jit
def _sincos_libm(phi, sin_out, cos_out):
    for j in range(phi.size):
        sin_out[j], cos_out[j] = sincos(phi[j], True)


@jit
def _sincos_into(phi, sin_out, cos_out, block):
    # the loops run on slices of a block: a loop over start..stop of the whole arrays is not vectorized
    for start in range(0, phi.size, block):
        stop = min(start + block, phi.size)
        x, s, c = phi[start:stop], sin_out[start:stop], cos_out[start:stop]
        if _sincos_poly(x, s, c):
            _sincos_libm(x, s, c)


def sincos_into(phi: np.ndarray, sin_out: np.ndarray, cos_out: np.ndarray, block: int = 32768) -> None:
    """Write ``sin(phi)`` and ``cos(phi)`` of a 1-D float64 array into the given arrays.

    Within 2.3e-16 (absolute) of ``np.sin`` and ``np.cos`` for any finite
    angle (tested on 10^5 angles per range up to 1e300); a block of
    ``block`` angles holding one beyond :data:`SINCOS_LIMIT` goes through the
    C library instead.

    Examples
    --------
    >>> s, c = np.empty(3), np.empty(3)
    >>> sincos_into(np.array([0.0, np.pi / 2, np.pi]), s, c)
    >>> np.round(s, 15).tolist(), np.round(c, 15).tolist()
    ([0.0, 1.0, 0.0], [1.0, 0.0, -1.0])
    """
    _sincos_into(phi, sin_out, cos_out, block)
