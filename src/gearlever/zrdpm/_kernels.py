"""Compiled kernels of the ZRDPM fast path (:mod:`gearlever.zrdpm.fast`), one pass over the angles.

Imported on first use only (numba).  Each kernel works block by block, on
slices (a loop over a stretch of the whole arrays is not vectorized): the
vectorized loop takes every angle of a block through the polynomial sine and
cosine of :mod:`gearlever.loops.compiled`; a block holding an angle (or, in
the self-consistent model, a lever angle) beyond ``SINCOS_LIMIT`` is done
again through the C library.  Outputs are six rows ``o0`` to ``o5``.
"""

from __future__ import annotations

import numba

from gearlever.loops.compiled import SINCOS_LIMIT, jit, sincos


@numba.njit(inline="always", error_model="numpy")
def _tables_angle(x, k, o0, o1, o2, o3, o4, o5, j, libm):
    # every output is alpha sin(phi) + beta cos(phi) + gamma (coefficients k, row by row)
    s, c = sincos(x, libm)
    o0[j] = k[0] * s + k[1] * c + k[2]
    o1[j] = k[3] * s + k[4] * c + k[5]
    o2[j] = k[6] * s + k[7] * c + k[8]
    o3[j] = k[9] * s + k[10] * c + k[11]
    o4[j] = k[12] * s + k[13] * c + k[14]
    o5[j] = k[15] * s + k[16] * c + k[17]


@jit
def _tables_poly(phi, k, o0, o1, o2, o3, o4, o5):
    far = 0
    for j in range(phi.size):
        far += abs(phi[j]) > SINCOS_LIMIT
        _tables_angle(phi[j], k, o0, o1, o2, o3, o4, o5, j, False)
    return far


@jit
def _tables_libm(phi, k, o0, o1, o2, o3, o4, o5):
    for j in range(phi.size):
        _tables_angle(phi[j], k, o0, o1, o2, o3, o4, o5, j, True)


@jit
def tables(phi, k, out, block):
    """Tables model: ``out[r] = k[3r] sin(phi) + k[3r+1] cos(phi) + k[3r+2]``, r = 0..5."""
    for start in range(0, phi.size, block):
        stop = min(start + block, phi.size)
        x = phi[start:stop]
        o0, o1, o2 = out[0, start:stop], out[1, start:stop], out[2, start:stop]
        o3, o4, o5 = out[3, start:stop], out[4, start:stop], out[5, start:stop]
        if _tables_poly(x, k, o0, o1, o2, o3, o4, o5):
            _tables_libm(x, k, o0, o1, o2, o3, o4, o5)


@numba.njit(inline="always", error_model="numpy")
def _self_consistent_angle(x, p, o0, o1, o2, o3, o4, o5, j, libm):
    # p = (c, 1 - i, i, lever_angle0, -l x_sign, l); the formulas of zrdpm.model (eqs. 9, 11, 14, 16)
    s, c = sincos(x, libm)
    uc = p[0] * (s + c)
    ec = p[0] * (c - s)
    theta = p[3] + p[0] * (s - c + 1.0)
    s2, c2 = sincos(theta, libm)
    u2 = uc * uc
    o0[j] = uc
    o1[j] = uc * p[1] + p[2]
    o2[j] = ec
    o3[j] = ec * p[1]
    o4[j] = (c2 * u2 + s2 * ec) * p[4]
    o5[j] = (c2 * ec - s2 * u2) * p[5]
    return abs(theta) > SINCOS_LIMIT


@jit
def _self_consistent_poly(phi, p, o0, o1, o2, o3, o4, o5):
    far = 0
    for j in range(phi.size):
        far += abs(phi[j]) > SINCOS_LIMIT
        far += _self_consistent_angle(phi[j], p, o0, o1, o2, o3, o4, o5, j, False)
    return far


@jit
def _self_consistent_libm(phi, p, o0, o1, o2, o3, o4, o5):
    for j in range(phi.size):
        _self_consistent_angle(phi[j], p, o0, o1, o2, o3, o4, o5, j, True)


@jit
def self_consistent(phi, p, out, block):
    """Self-consistent model: a second sine and cosine per angle, of the lever angle."""
    for start in range(0, phi.size, block):
        stop = min(start + block, phi.size)
        x = phi[start:stop]
        o0, o1, o2 = out[0, start:stop], out[1, start:stop], out[2, start:stop]
        o3, o4, o5 = out[3, start:stop], out[4, start:stop], out[5, start:stop]
        if _self_consistent_poly(x, p, o0, o1, o2, o3, o4, o5):
            _self_consistent_libm(x, p, o0, o1, o2, o3, o4, o5)
