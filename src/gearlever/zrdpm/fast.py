"""The fast path of the ZRDPM models: one compiled pass over the angles.

Same results as :func:`gearlever.zrdpm.analogues` and
:func:`gearlever.zrdpm.tables_outputs` to rounding (1e-12, tested); the
kernels (numba, in :mod:`gearlever.zrdpm._kernels`) are imported and compiled
on first use.  Speed is measured in ``benchmarks/bench_zrdpm.py``.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._validate import finite_array, positive_int
from gearlever.errors import GearleverError
from gearlever.zrdpm.parameters import ContourKinematics, TablesConstants, ZrdpmContour

__all__ = ["fast_outputs"]


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

    One pass over the angles by a compiled kernel, ``block`` angles at a
    time, writing the six outputs as rows of one ``(6, *phi.shape)`` array,
    which may be given as ``out`` to reuse memory.  Each angle's sine and
    cosine come from ``gearlever.loops.compiled.sincos``, the same bits
    on any x86 CPU; a block holding an angle beyond
    :data:`~gearlever.loops.compiled.SINCOS_LIMIT` (about 5e5 rad) is done
    again through the C library's ``sin`` and ``cos``.

    Notes
    -----
    The formulas of paper eqs. 9, 11, 14 and 16 (contour 2: 28, 30, 33, 35),
    as in :mod:`gearlever.zrdpm.model`.  Tables model: every output is
    ``alpha sin(phi) + beta cos(phi) + gamma``.  Self-consistent model: a
    second sine and cosine per angle, of the lever angle.

    Examples
    --------
    >>> k = fast_outputs(ZrdpmContour(), np.array([0.0]), None, block=8)
    >>> float(k.u_carrier[0]), float(k.u_gear[0])
    (1.0, 1.0)
    """
    from gearlever.zrdpm import _kernels  # numba: imported and compiled on first use

    block = positive_int("block", block)
    phi = finite_array("phi", phi)
    shape = phi.shape
    flat = np.ascontiguousarray(phi, dtype=np.float64).reshape(-1)
    out = np.empty((6, *shape)) if out is None else _check_out(out, shape)
    rows = out.reshape(6, flat.size)
    c = params.lever_gain
    i = params.signed_ratio  # Willis, gears/willis.py
    g = 1.0 - i
    sgn = params.x_sign
    if constants is not None:
        th0 = constants.lever_angle0
        c0, s0 = math.cos(th0), math.sin(th0)
        L, E = constants.l_u2, constants.l_e
        # every output is alpha sin(phi) + beta cos(phi) + gamma; cos(theta) = C c0 - S s0,
        # sin(theta) = S c0 + C s0.  Per output: coefficient of sin, of cos, constant.
        coef = (
            *(c, c, 0.0),  # u_c = c (S + C)                     eq. 9
            *(g * c, g * c, i),  # u_g = (1 - i) u_c + i         eq. 11
            *(-c, c, 0.0),  # e_c = c (C - S)
            *(-g * c, g * c, 0.0),  # e_g = (1 - i) e_c          eq. 14
            *(-sgn * (E * c0 - L * s0), -sgn * (L * c0 + E * s0), 0.0),  # a_x   eq. 16
            *(-(L * c0 + E * s0), E * c0 - L * s0, 0.0),  # a_y
        )
        _kernels.tables(flat, tuple(float(v) for v in coef), rows, block)
    else:
        ell = params.l
        p = (c, g, i, params.lever_angle0, -ell * sgn, ell)
        _kernels.self_consistent(flat, tuple(float(v) for v in p), rows, block)
    return ContourKinematics(*out)
