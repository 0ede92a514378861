"""The fast path of the ZRDPM models: blocked, in place, one pass over the angles.

Same results as :func:`gearlever.zrdpm.analogues` and
:func:`gearlever.zrdpm.tables_outputs` to rounding (1e-12, tested); speed is
measured in ``benchmarks/bench_zrdpm.py``.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._validate import finite_array, positive_int
from gearlever.errors import GearleverError
from gearlever.loops.trig import sincos_half_angle
from gearlever.zrdpm.parameters import ContourKinematics, TablesConstants, ZrdpmContour

#: Columns of one 6 x 3 matrix product: 6 * 3 * 8192 = 147 456 multiply-adds stays below the
#: 262 144 at which OpenBLAS starts threads for a product (its GEMM_MULTITHREAD_THRESHOLD 4
#: times 65 536); a threaded product this small costs, on a busy machine, up to ten times a
#: single-threaded one (measured with its Haswell and Zen kernels, those of an AMD EPYC).
PRODUCT_COLUMNS = 8192

__all__ = ["PRODUCT_COLUMNS", "fast_outputs"]


def _check_out(out, shape):
    want = (6, *shape)
    if (
        not isinstance(out, np.ndarray)
        or out.dtype != np.float64
        or out.shape != want
        or not out.flags.c_contiguous
        or not out.flags.writeable
    ):
        got = f"{out.dtype} array of shape {out.shape}" if isinstance(out, np.ndarray) else type(out).__name__
        raise GearleverError(f"out must be a writeable C-contiguous float64 array of shape {want}, got {got}")
    return out


def fast_outputs(
    params: ZrdpmContour, phi, constants: TablesConstants | None, block: int, out=None
) -> ContourKinematics:
    """Fast evaluation of :func:`~gearlever.zrdpm.analogues` (``constants`` None) or
    :func:`~gearlever.zrdpm.tables_outputs`, same results to rounding (1e-12).

    Tables model: one pass over the angles, block by block (``block``
    angles, at most :data:`PRODUCT_COLUMNS`; the (3, block) buffer stays in
    cache): ``sin``
    and ``cos`` of the block into the buffer (whose third row is ones), both
    from one tangent of the half angle
    (:func:`~gearlever.loops.trig.sincos_half_angle`), then the six outputs as
    one 6 x 3 matrix product (small enough that OpenBLAS does not thread it),
    every output being ``alpha sin + beta cos + gamma`` with the coefficients of eqs. 9, 11, 14 and 16.  Self-consistent
    model: per block, in-place ufuncs, with a second sin/cos pair for the lever
    angle (both pairs from half-angle tangents).  The six outputs are rows of
    one ``(6, *phi.shape)`` array, which
    may be given as ``out`` to reuse memory.

    Notes
    -----
    The formulas of paper eqs. 9, 11, 14 and 16 (contour 2: 28, 30, 33, 35),
    as in :mod:`gearlever.zrdpm.model`.

    Examples
    --------
    >>> k = fast_outputs(ZrdpmContour(), np.array([0.0]), None, block=8)
    >>> float(k.u_carrier[0]), float(k.u_gear[0])
    (1.0, 1.0)
    """
    block = positive_int("block", block)
    phi = finite_array("phi", phi)
    shape = phi.shape
    flat = np.ascontiguousarray(phi).reshape(-1)
    n = flat.size
    out = np.empty((6, *shape)) if out is None else _check_out(out, shape)
    rows = out.reshape(6, n)
    c = params.lever_gain
    i = params.signed_ratio  # Willis, gears/willis.py
    g = 1.0 - i
    sgn = params.x_sign
    bs = min(block, max(n, 1))
    if constants is not None:
        th0 = constants.lever_angle0
        c0, s0 = math.cos(th0), math.sin(th0)
        L, E = constants.l_u2, constants.l_e
        # every output is alpha sin(phi) + beta cos(phi) + gamma; cos(theta) = C c0 - S s0,
        # sin(theta) = S c0 + C s0.  Columns: coefficient of sin, of cos, constant.
        coef = np.array(
            [
                [c, c, 0.0],  # u_c = c (S + C)                     eq. 9
                [g * c, g * c, i],  # u_g = (1 - i) u_c + i         eq. 11
                [-c, c, 0.0],  # e_c = c (C - S)
                [-g * c, g * c, 0.0],  # e_g = (1 - i) e_c          eq. 14
                [-sgn * (E * c0 - L * s0), -sgn * (L * c0 + E * s0), 0.0],  # a_x   eq. 16
                [-(L * c0 + E * s0), E * c0 - L * s0, 0.0],  # a_y
            ]
        )
        # one pass over the angles: per block, sin and cos go into a cache-resident
        # (3, block) buffer whose third row is ones, and one 6 x 3 matrix product writes
        # the block of all six outputs (nothing is written twice, no full-size scratch)
        bs = min(bs, PRODUCT_COLUMNS)
        x = np.ones((3, bs))
        for start in range(0, n, bs):
            stop = min(start + bs, n)
            xb = x[:, : stop - start]
            sincos_half_angle(flat[start:stop], xb[0], xb[1])
            np.matmul(coef, xb, out=rows[:, start:stop])
        return ContourKinematics(*out)
    u_c, u_g, e_c, e_g, a_x, a_y = rows
    th0 = params.lever_angle0
    ell = params.l
    s, co, t1, t2 = (np.empty(bs) for _ in range(4))
    for start in range(0, n, bs):
        stop = min(start + bs, n)
        m = stop - start
        S, C, T1, T2 = s[:m], co[:m], t1[:m], t2[:m]
        sincos_half_angle(flat[start:stop], S, C)
        uc, ug, ec, eg, ax, ay = (
            u_c[start:stop],
            u_g[start:stop],
            e_c[start:stop],
            e_g[start:stop],
            a_x[start:stop],
            a_y[start:stop],
        )
        np.add(S, C, out=uc)
        uc *= c
        np.subtract(C, S, out=ec)
        ec *= c
        np.multiply(uc, g, out=ug)
        ug += i
        np.multiply(ec, g, out=eg)
        # theta = th0 + c (S - C + 1); then S, C are reused for sin/cos(theta)
        np.subtract(S, C, out=T1)
        T1 += 1.0
        T1 *= c
        T1 += th0
        sincos_half_angle(T1, S, C)
        np.multiply(uc, uc, out=T2)  # u**2
        # eq. 16: a_x = -l (cos u2 + sin e), a_y = l (cos e - sin u2)
        np.multiply(C, T2, out=ax)
        np.multiply(S, ec, out=T1)
        ax += T1
        ax *= -ell * sgn
        np.multiply(C, ec, out=ay)
        np.multiply(S, T2, out=T1)
        ay -= T1
        ay *= ell
    return ContourKinematics(*out)
