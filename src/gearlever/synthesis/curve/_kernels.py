"""Compiled residuals of the curve refinement: one sketch's gaps to the target and their Jacobian.

The least-squares refinement (:func:`gearlever.synthesis.curve.search.refine`)
evaluates one sketch at a time, some hundred times a solve: the batched numpy
simulator (:mod:`gearlever.synthesis.curve.simulate`) spends most of such a
call in the overhead of its small array operations (0.9 ms for the gaps and
2.4 to 5.1 ms for their Jacobian of a five- to nine-joint linkage, measured on
a 2-core Intel Xeon at 2.50 GHz; compiled: 0.05 ms and 0.2 to 0.6 ms, a
refinement 3 to 4 times faster).  These kernels do the same arithmetic in
loops compiled by numba: the dyads' closed forms and their forward-mode
derivatives (:func:`~gearlever.synthesis.curve.simulate.simulate_jacobian`'s
Notes), the resampling by arc length and its derivative, the alignment's
gaps.  Tested against the numpy path and against finite differences.

Imported on first use by the refinement (never at ``import gearlever``);
compiled once a machine into numba's on-disk cache (:func:`gearlever.loops.compiled.jit`).
Only additions, multiplications, divisions and square roots, in a fixed
order and never fused: the same bits on every x86 CPU.

Imports numpy, :mod:`math` and :mod:`gearlever.loops.compiled` only.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.loops.compiled import jit

__all__ = ["gaps", "gaps_jacobian"]


@jit
def _crank(x0, pivot, tip):  # pragma: no cover - compiled
    """The crank's sketch vector and length."""
    vx = x0[tip, 0] - x0[pivot, 0]
    vy = x0[tip, 1] - x0[pivot, 1]
    return vx, vy, math.sqrt(vx * vx + vy * vy)


@jit
def _dyad(x0, k, i, j):  # pragma: no cover - compiled
    """A dyad's sketch vectors ``k - i``, ``k - j``, their squared lengths and the branch sign."""
    a0, a1 = x0[k, 0] - x0[i, 0], x0[k, 1] - x0[i, 1]
    b0, b1 = x0[k, 0] - x0[j, 0], x0[k, 1] - x0[j, 1]
    u0, u1 = x0[j, 0] - x0[i, 0], x0[j, 1] - x0[i, 1]
    s = -1.0 if u0 * a1 - u1 * a0 < 0.0 else 1.0
    return a0, a1, b0, b1, a0 * a0 + a1 * a1, b0 * b0 + b1 * b1, s


@jit
def _closure(X, i, j, t, A, B, s):  # pragma: no cover - compiled
    """A dyad at step ``t``: ``d = x_j - x_i``, ``L = |d|^2``, ``alpha`` and ``beta`` (the simulator's Notes)."""
    d0 = X[j, t, 0] - X[i, t, 0]
    d1 = X[j, t, 1] - X[i, t, 1]
    L = d0 * d0 + d1 * d1
    alpha = 0.5 + (A - B) / (2.0 * L)
    return d0, d1, L, alpha, s * math.sqrt(A / L - alpha * alpha)


@jit
def _mean(P):  # pragma: no cover - compiled
    """Mean of the rows of ``P`` (n, 2), summed in order."""
    m0 = 0.0
    m1 = 0.0
    for q in range(P.shape[0]):
        m0 += P[q, 0]
        m1 += P[q, 1]
    return m0 / P.shape[0], m1 / P.shape[0]


@jit
def _positions(x0, dyads, pivot, tip, cs, X):  # pragma: no cover - compiled (tested through gaps)
    """Every joint over the crank turn into ``X`` (N, T, 2): the closed forms of the simulator."""
    N = x0.shape[0]
    T = cs.shape[0]
    for q in range(N):
        for t in range(T):
            X[q, t, 0] = x0[q, 0]
            X[q, t, 1] = x0[q, 1]
    vx, vy, r = _crank(x0, pivot, tip)
    for t in range(T):
        X[tip, t, 0] = x0[pivot, 0] + r * cs[t, 0]
        X[tip, t, 1] = x0[pivot, 1] + r * cs[t, 1]
    for n in range(dyads.shape[0]):
        k, i, j = dyads[n, 0], dyads[n, 1], dyads[n, 2]
        a0, a1, b0, b1, A, B, s = _dyad(x0, k, i, j)
        for t in range(T):
            d0, d1, L, alpha, beta = _closure(X, i, j, t, A, B, s)
            X[k, t, 0] = X[i, t, 0] + alpha * d0 - beta * d1
            X[k, t, 1] = X[i, t, 1] + alpha * d1 + beta * d0


@jit
def _derivatives(x0, dyads, pivot, tip, cs, X, J):  # pragma: no cover - compiled (tested through gaps_jacobian)
    """Forward-mode derivatives of ``X`` with respect to the sketch into ``J`` (N, T, 2, 2N)."""
    N = x0.shape[0]
    T = cs.shape[0]
    P = 2 * N
    J[:] = 0.0
    for q in range(N):
        for t in range(T):
            J[q, t, 0, 2 * q] = 1.0
            J[q, t, 1, 2 * q + 1] = 1.0
    vx, vy, r = _crank(x0, pivot, tip)
    dr = np.zeros(P)
    dr[2 * tip] += vx / r
    dr[2 * tip + 1] += vy / r
    dr[2 * pivot] -= vx / r
    dr[2 * pivot + 1] -= vy / r
    for t in range(T):
        for c in range(2):
            for p in range(P):
                J[tip, t, c, p] = J[pivot, t, c, p] + cs[t, c] * dr[p]
    dA = np.empty(P)
    dB = np.empty(P)
    dL = np.empty(P)
    dal = np.empty(P)
    for n in range(dyads.shape[0]):
        k, i, j = dyads[n, 0], dyads[n, 1], dyads[n, 2]
        a0, a1, b0, b1, A, B, s = _dyad(x0, k, i, j)
        dA[:] = 0.0
        dB[:] = 0.0
        dA[2 * k] += 2.0 * a0
        dA[2 * k + 1] += 2.0 * a1
        dA[2 * i] -= 2.0 * a0
        dA[2 * i + 1] -= 2.0 * a1
        dB[2 * k] += 2.0 * b0
        dB[2 * k + 1] += 2.0 * b1
        dB[2 * j] -= 2.0 * b0
        dB[2 * j + 1] -= 2.0 * b1
        for t in range(T):
            d0, d1, L, alpha, beta = _closure(X, i, j, t, A, B, s)
            for p in range(P):
                dL[p] = 2.0 * (d0 * (J[j, t, 0, p] - J[i, t, 0, p]) + d1 * (J[j, t, 1, p] - J[i, t, 1, p]))
            for p in range(P):
                dal[p] = (dA[p] - dB[p]) / (2.0 * L) - (A - B) / (2.0 * L * L) * dL[p]
            for p in range(P):
                dd0 = J[j, t, 0, p] - J[i, t, 0, p]
                dd1 = J[j, t, 1, p] - J[i, t, 1, p]
                dbeta = (dA[p] / L - A / (L * L) * dL[p] - 2.0 * alpha * dal[p]) / (2.0 * beta)
                J[k, t, 0, p] = J[i, t, 0, p] + dal[p] * d0 + alpha * dd0 - dbeta * d1 - beta * dd1
                J[k, t, 1, p] = J[i, t, 1, p] + dal[p] * d1 + alpha * dd1 + dbeta * d0 + beta * dd0


@jit
def _lengths(c, cum, seg):  # pragma: no cover - compiled
    """Segment lengths and cumulative length of a polyline; False where it has no length or a NaN."""
    M = c.shape[0]
    cum[0] = 0.0
    for m in range(M - 1):
        e0 = c[m + 1, 0] - c[m, 0]
        e1 = c[m + 1, 1] - c[m, 1]
        seg[m] = math.sqrt(e0 * e0 + e1 * e1)
        cum[m + 1] = cum[m] + seg[m]
    total = cum[M - 1]
    return math.isfinite(total) and total > 0.0


@jit
def _resample(c, cum, seg, s, P, lo_out, w_out):  # pragma: no cover - compiled
    """Resampled points ``P`` (n, 2) at fractions ``s`` of the length, with each sample's segment and weight."""
    M = c.shape[0]
    total = cum[M - 1]
    hi = 1
    for q in range(s.shape[0]):
        while hi < M - 1 and cum[hi] / total <= s[q]:
            hi += 1
        lo = hi - 1
        w = 0.0
        if seg[lo] > 0.0:
            w = min(max((s[q] * total - cum[lo]) / seg[lo], 0.0), 1.0)
        lo_out[q] = lo
        w_out[q] = w
        P[q, 0] = c[lo, 0] + w * (c[hi, 0] - c[lo, 0])
        P[q, 1] = c[lo, 1] + w * (c[hi, 1] - c[lo, 1])


@jit
def _gaps(x0, dyads, pivot, tip, target, cs, s, perm, tz, scale, rot, norm, out):  # pragma: no cover - compiled
    N = x0.shape[0]
    T = cs.shape[0]
    n = s.shape[0]
    X = np.empty((N, T, 2))
    _positions(x0, dyads, pivot, tip, cs, X)
    c = X[target]
    cum = np.empty(T)
    seg = np.empty(T - 1)
    if not _lengths(c, cum, seg):
        return False
    Pz = np.empty((n, 2))
    lo = np.empty(n, dtype=np.int64)
    w = np.empty(n)
    _resample(c, cum, seg, s, Pz, lo, w)
    m0, m1 = _mean(Pz)
    for q in range(n):
        zr = (Pz[perm[q], 0] - m0) / scale
        zi = (Pz[perm[q], 1] - m1) / scale
        out[q] = norm[q] * (rot[0] * zr - rot[1] * zi - tz[q, 0])
        out[n + q] = norm[q] * (rot[0] * zi + rot[1] * zr - tz[q, 1])
    for q in range(2 * n):
        if not math.isfinite(out[q]):
            return False
    return True


@jit
def _gaps_jacobian(x0, dyads, pivot, tip, target, cs, s, perm, scale, rot, norm, out):  # pragma: no cover
    N = x0.shape[0]
    T = cs.shape[0]
    n = s.shape[0]
    P = 2 * N
    X = np.empty((N, T, 2))
    J = np.empty((N, T, 2, P))
    _positions(x0, dyads, pivot, tip, cs, X)
    _derivatives(x0, dyads, pivot, tip, cs, X, J)
    c = X[target]
    Jc = J[target]
    cum = np.empty(T)
    seg = np.empty(T - 1)
    if not _lengths(c, cum, seg):
        return False
    for t in range(T):
        for e in range(2):
            for p in range(P):
                if not math.isfinite(Jc[t, e, p]):
                    return False
    # d seg_m and the cumulative length's derivative
    dseg = np.zeros((T - 1, P))
    dcum = np.zeros((T, P))
    for m in range(T - 1):
        if seg[m] > 0.0:
            u0 = (c[m + 1, 0] - c[m, 0]) / seg[m]
            u1 = (c[m + 1, 1] - c[m, 1]) / seg[m]
            for p in range(P):
                dseg[m, p] = u0 * (Jc[m + 1, 0, p] - Jc[m, 0, p]) + u1 * (Jc[m + 1, 1, p] - Jc[m, 1, p])
        for p in range(P):
            dcum[m + 1, p] = dcum[m, p] + dseg[m, p]
    Pz = np.empty((n, 2))
    lo = np.empty(n, dtype=np.int64)
    w = np.empty(n)
    _resample(c, cum, seg, s, Pz, lo, w)
    dP = np.empty((n, 2, P))
    mean = np.zeros((2, P))
    for q in range(n):
        a = lo[q]
        b = a + 1
        wq = w[q]
        for p in range(P):
            dw = 0.0
            if seg[a] > 0.0:
                dw = (s[q] * dcum[T - 1, p] - dcum[a, p] - wq * dseg[a, p]) / seg[a]
            for e in range(2):
                v = (1.0 - wq) * Jc[a, e, p] + wq * Jc[b, e, p] + (c[b, e] - c[a, e]) * dw
                dP[q, e, p] = v
                mean[e, p] += v
    for e in range(2):
        for p in range(P):
            mean[e, p] /= n
    m0, m1 = _mean(Pz)
    for q in range(n):
        g = perm[q]
        for p in range(P):
            dzr = (dP[g, 0, p] - mean[0, p]) / scale
            dzi = (dP[g, 1, p] - mean[1, p]) / scale
            out[q, p] = norm[q] * (rot[0] * dzr - rot[1] * dzi)
            out[n + q, p] = norm[q] * (rot[0] * dzi + rot[1] * dzr)
        zr = (Pz[g, 0] - m0) / scale
        zi = (Pz[g, 1] - m1) / scale
        out[q, P] = -norm[q] * (rot[0] * zi + rot[1] * zr)
        out[n + q, P] = norm[q] * (rot[0] * zr - rot[1] * zi)
    return True


def gaps(x0, dyads, pivot, tip, target, cs, s, perm, tz, scale, angle, norm) -> np.ndarray | None:
    """Weighted gaps ``norm_k (e^(i angle) z_perm(k) - t_k)`` as (real parts, imaginary parts), or None.

    ``z`` is the traced joint's curve resampled by arc length at the
    fractions ``s``, centred and divided by ``scale``; ``tz`` (n, 2) the
    target's normalised points; ``cs`` (T, 2) the cosines and sines of the
    crank angles; ``dyads`` the solve plan's ``(k, i, j, ...)`` rows.  None
    where the linkage locks or its curve has no length.

    Examples
    --------
    >>> import numpy as np
    >>> x0 = np.array([[0.0, 0.0], [1.0, 0.0], [4.0, 0.0], [3.0, 3.0]])
    >>> cs = np.stack([np.cos(np.linspace(0, 2 * np.pi, 50)), np.sin(np.linspace(0, 2 * np.pi, 50))], -1)
    >>> s = np.linspace(0.0, 1.0, 50)
    >>> g = gaps(x0, np.array([[3, 1, 2, 0]]), 0, 1, 1, cs, s, np.arange(50), np.zeros((50, 2)), 1.0, 0.0,
    ...     np.ones(50))
    >>> round(float(np.hypot(g[:50], g[50:]).mean()), 3)  # the crank tip's circle about its centre: radius 1
    1.0
    """
    out = np.empty(2 * s.shape[0])
    rot = np.array([math.cos(angle), math.sin(angle)])
    ok = _gaps(x0, dyads, pivot, tip, target, cs, s, perm, tz, float(scale), rot, norm, out)
    return out if ok else None


def gaps_jacobian(x0, dyads, pivot, tip, target, cs, s, perm, scale, angle, norm) -> np.ndarray | None:
    """Jacobian of :func:`gaps` with respect to the sketch (``2 N`` columns) and the angle (last), or None."""
    out = np.empty((2 * s.shape[0], 2 * x0.shape[0] + 1))
    rot = np.array([math.cos(angle), math.sin(angle)])
    ok = _gaps_jacobian(x0, dyads, pivot, tip, target, cs, s, perm, float(scale), rot, norm, out)
    return out if ok else None
