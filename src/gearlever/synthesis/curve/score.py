"""The challenge's scores: curve distance, material, feasibility and the 2-D hypervolume.

Notes
-----
Definitions of the MIT 2.156 linkage synthesis challenge (A. H. Nobari,
F. Ahmed et al., repository ``ahnobari/2155-Optimization-Challenge-Problem``,
``LINKS.Geometry`` and ``LINKS.Optimization``), implemented from their
description:

* both curves are resampled by arc length to 200 points along the polyline
  of their points in order (the first point kept; a traced curve runs over
  the whole turn, 0 to 2 pi inclusive), then centred on their mean;
* both are divided by the target's RMS radius ``sqrt(mean |t_k|^2)`` (so the
  design's size counts);
* over every cyclic shift of the design's points, in both directions, the
  rotation that best maps them onto the target (least squares,
  ``theta = arg sum t_k conj(c_k)`` in complex notation) is applied and the
  distance is ``2 pi`` times the mean point gap ``|t_k - R c_k|``; the
  smallest over the 400 alignments is the distance; a design that locks
  scores infinity;
* material is twice the total length of the links (the challenge sums the
  symmetric matrix of link lengths);
* feasible: distance < 0.75, material < 10 and at most 20 joints;
* the hypervolume of a set of designs is the area dominated by its feasible
  points and bounded by the reference point (0.75, 10).

Two scorings (:data:`SCORINGS`) differ only in what the target's polyline
and the material mean:

* ``"challenge"``: the definitions above, exactly (the target is the open
  polyline of its points, the material is absolute): for the challenge's own
  targets, so that its published values come out;
* ``"relative"`` (for a user's curve, the default of ``synthesize curve`` and
  ``curve score``): the target is *closed* (:func:`closed`: the segment from
  its last point back to the first counts, so a repeated first point changes
  nothing and a sparse target is not read as missing a piece), a closed curve
  has no first point (the distance is the least over :data:`RESTARTS` starts
  of the target's resampling spread over one sample spacing:
  :func:`score_distance`), and the material is measured at the size of the challenge's targets,
  ``material x REFERENCE_RMS / r`` with ``r`` the RMS radius of the target
  (:func:`material_scale`): the same design drawn ten times larger scores the
  same, and the bound 10 means ``10 r / REFERENCE_RMS`` in the target's units.

>>> import numpy as np
>>> t = np.linspace(0, 2 * np.pi, 200)
>>> circle = np.stack([np.cos(t), np.sin(t)], -1)
>>> round(float(distance(circle[None] * 1.0, circle)[0]), 6)
0.0
>>> hypervolume([[0.25, 5.0]])
2.5
"""

from __future__ import annotations

import functools

import numpy as np

from gearlever.errors import GearleverError

__all__ = [
    "MAX_DISTANCE",
    "MAX_JOINTS",
    "MAX_MATERIAL",
    "REFERENCE",
    "REFERENCE_RMS",
    "RESOLUTION",
    "SCORINGS",
    "check_scoring",
    "closed",
    "distance",
    "feasible",
    "hypervolume",
    "material",
    "material_scale",
    "normalise",
    "resample",
    "rms_radius",
    "score_distance",
    "scoring_target",
]

#: Points of the resampled curves.
RESOLUTION = 200
#: Feasibility bounds and hypervolume reference point of the challenge.
MAX_DISTANCE = 0.75
MAX_MATERIAL = 10.0
MAX_JOINTS = 20
REFERENCE = (MAX_DISTANCE, MAX_MATERIAL)
#: The scorings: the size-free one for a user's curve, the challenge's absolute one.
SCORINGS = ("relative", "challenge")
#: RMS radius at which the relative scoring measures material: that of the challenge's six targets (0.191).
REFERENCE_RMS = 0.191
#: Starts of a closed target's resampling (spread over one sample spacing) of the relative scoring.
RESTARTS = 4


def check_scoring(scoring: str) -> str:
    """``scoring`` if it is one of :data:`SCORINGS`, else a :class:`~gearlever.errors.GearleverError` naming it.

    >>> check_scoring("tight")
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: scoring must be one of relative, challenge, got 'tight'
    """
    if scoring not in SCORINGS:
        raise GearleverError(f"scoring must be one of {', '.join(SCORINGS)}, got {scoring!r}")
    return scoring


def closed(target) -> np.ndarray:
    """The target's points with its first point repeated at the end (unless it is there already): a closed polyline.

    Examples
    --------
    >>> closed([[0, 0], [1, 0], [0, 1]]).tolist()
    [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]
    >>> closed([[0, 0], [1, 0], [0, 1], [0, 0]]).shape
    (4, 2)
    """
    t = np.asarray(target, dtype=float)
    if t.shape[0] and np.array_equal(t[0], t[-1]):
        return t
    return np.concatenate([t, t[:1]])


def scoring_target(target, scoring: str = "relative") -> np.ndarray:
    """The polyline the distance is measured to: :func:`closed` in the relative scoring, as given in the challenge's."""
    return closed(target) if check_scoring(scoring) == "relative" else np.asarray(target, dtype=float)


def _restart(poly, s0: float) -> np.ndarray:
    """The closed polyline ``poly`` (first point repeated last) started at arc length ``s0`` from its first point."""
    seg = np.hypot(*np.diff(poly, axis=0).T)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    i = int(np.clip(np.searchsorted(cum, s0, side="right") - 1, 0, len(seg) - 1))
    w = (s0 - cum[i]) / seg[i] if seg[i] > 0 else 0.0
    p = poly[i] + w * (poly[i + 1] - poly[i])
    return np.concatenate([[p], poly[i + 1 : -1], poly[: i + 1], [p]])


def score_distance(curves, target, scoring: str = "relative") -> np.ndarray:
    """The scoring's distance of traced curves to a target, shape (B,).

    The challenge's scoring: :func:`distance` to the target as given.  The
    relative scoring: the target is :func:`closed` and has no first point:
    the least :func:`distance` over :data:`RESTARTS` starts of its
    resampling, evenly over the first sample spacing (the challenge's
    distance compares the samples of both curves one to one, so where a
    closed target happens to start would otherwise count).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 200)
    >>> circle = np.stack([np.cos(t), np.sin(t)], -1)
    >>> float(score_distance(circle[None], circle)[0]) < 1e-9
    True
    """
    t = scoring_target(target, scoring)
    if scoring == "challenge":
        return distance(curves, t)
    total = float(np.hypot(*np.diff(t, axis=0).T).sum())
    best = None
    for j in range(RESTARTS):
        d = distance(curves, _restart(t, total * j / (RESTARTS * (RESOLUTION - 1))))
        best = d if best is None else np.minimum(best, d)
    return best


def rms_radius(curve, n: int = RESOLUTION) -> float:
    """RMS radius of a polyline resampled by arc length to ``n`` points about their mean (the distance's scale)."""
    t = resample(np.asarray(curve, dtype=float)[None], n)[0]
    t = t - t.mean(0)
    return float(np.sqrt((t**2).sum(-1).mean()))


def material_scale(target, scoring: str = "relative") -> float:
    """Factor from material in the target's units to the scoring's material: ``REFERENCE_RMS / r`` or 1.

    ``r`` is the RMS radius of the scoring's target polyline
    (:func:`scoring_target`, :func:`rms_radius`); the challenge's scoring
    counts material as it is (1).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 200)
    >>> circle = np.stack([np.cos(t), np.sin(t)], -1)
    >>> round(material_scale(50 * circle) * 50, 4), material_scale(circle, "challenge")
    (0.191, 1.0)
    """
    if check_scoring(scoring) == "challenge":
        return 1.0
    return REFERENCE_RMS / rms_radius(scoring_target(target, scoring))


def resample(curves, n: int = RESOLUTION) -> np.ndarray:
    """Resample polylines by arc length to ``n`` points from the first point to the last.

    Parameters
    ----------
    curves : array_like, shape (B, M, 2)

    Returns
    -------
    ndarray, shape (B, n, 2)
        NaN for a curve of zero length or with NaN points.

    Examples
    --------
    >>> resample([[[0, 0], [1, 0], [3, 0]]], 5)[0, :, 0].tolist()
    [0.0, 0.75, 1.5, 2.25, 3.0]
    """
    c = np.asarray(curves, dtype=float)
    B, M, _ = c.shape
    seg = np.hypot(*np.diff(c, axis=1).transpose(2, 0, 1))
    cum = np.concatenate([np.zeros((B, 1)), np.cumsum(seg, 1)], 1)
    total = cum[:, -1:]
    ok = np.isfinite(cum).all(1) & (total[:, 0] > 0)
    out = np.full((B, n, 2), np.nan)
    if not ok.any():
        return out
    c, cum, total = c[ok], cum[ok], total[ok]
    f = cum / total  # (b, M) from 0 to 1, non-decreasing
    b = f.shape[0]
    s = np.linspace(0.0, 1.0, n)
    # one searchsorted over all rows at once: row r is shifted by 2 r (its fractions stay in [2 r, 2 r + 1])
    off = 2.0 * np.arange(b)[:, None]
    hi = np.searchsorted((f + off).ravel(), (s[None, :] + off).ravel(), side="right").reshape(b, n)
    hi -= (np.arange(b) * M)[:, None]
    hi = np.clip(hi, 1, M - 1)
    lo = hi - 1
    f_lo, f_hi = np.take_along_axis(f, lo, 1), np.take_along_axis(f, hi, 1)
    span = f_hi - f_lo
    w = np.clip(np.divide(s[None, :] - f_lo, span, out=np.zeros_like(span), where=span > 0), 0.0, 1.0)
    p_lo = np.take_along_axis(c, lo[..., None], 1)
    p_hi = np.take_along_axis(c, hi[..., None], 1)
    out[ok] = p_lo + w[..., None] * (p_hi - p_lo)
    return out


def normalise(curves, target, n: int = RESOLUTION):
    """Resampled, centred designs and target, divided by the target's RMS radius: complex arrays (B, n), (n,)."""
    t = resample(np.asarray(target, dtype=float)[None], n)[0]
    t = t - t.mean(0)
    scale = np.sqrt((t**2).sum(-1).mean())
    c = resample(curves, n)
    c = c - c.mean(1, keepdims=True)
    return (c[..., 0] + 1j * c[..., 1]) / scale, (t[:, 0] + 1j * t[:, 1]) / scale


@functools.lru_cache(maxsize=8)
def _alignment_indices(n: int) -> np.ndarray:
    """Sample indices of the ``2 n`` alignments (cyclic shifts, both directions), ``(2 n, n)``, read-only, cached."""
    k = np.arange(n)
    fwd = (k[None, :] + k[:, None]) % n
    rev = (k[:, None] - k[None, :]) % n
    out = np.concatenate([fwd, rev])  # (2n, n)
    out.setflags(write=False)
    return out


def _exact(c, t, chunk: int = 16) -> np.ndarray:
    n = t.shape[0]
    idx = _alignment_indices(n)
    out = np.empty(c.shape[0])
    for a in range(0, c.shape[0], chunk):
        C = c[a : a + chunk][:, idx]  # (b, 2n, n)
        z = (t * np.conj(C)).sum(-1)
        rot = np.exp(1j * np.angle(z))
        gap = np.abs(t - rot[..., None] * C).mean(-1)
        out[a : a + chunk] = gap.min(-1)
    return out


def _fast(c, t, keep: int) -> np.ndarray:
    """Exact gap over the ``keep`` alignments of least squared gap (found by FFT correlation)."""
    n = t.shape[0]
    Fc, Ft = np.fft.fft(c, axis=-1), np.fft.fft(t)
    fwd = np.abs(np.fft.ifft(Fc * np.conj(Ft), axis=-1))  # |sum_k c_{k+s} conj(t_k)|
    rev = np.abs(np.fft.ifft(Ft * np.fft.fft(np.conj(c), axis=-1), axis=-1))  # |sum_k t_k conj(c_{s-k})|
    score = np.concatenate([fwd, rev], -1)
    best = np.argsort(-score, axis=-1, kind="stable")[:, :keep]  # (B, keep)
    idx = _alignment_indices(n)[best]  # (B, keep, n)
    C = np.take_along_axis(c[:, None, :], idx, axis=-1)
    z = (t * np.conj(C)).sum(-1)
    rot = np.exp(1j * np.angle(z))
    return np.abs(t - rot[..., None] * C).mean(-1).min(-1)


def distance(curves, target, *, keep: int | None = None) -> np.ndarray:
    """The challenge's distance of traced curves to a target curve (see the module Notes).

    Parameters
    ----------
    curves : array_like, shape (B, M, 2)
        Traced curves (NaN where a design locks: distance infinity).
    target : array_like, shape (K, 2)
    keep : int, optional
        Search only the ``keep`` alignments of least squared gap (found by FFT
        correlation) instead of all 400: the search's fast mode, an upper
        bound of the exact distance, equal to it when the best alignment is
        among them.

    Returns
    -------
    ndarray, shape (B,)

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0, 2 * np.pi, 200)
    >>> circle = np.stack([np.cos(t), np.sin(t)], -1)
    >>> float(distance(2 * circle[None], circle)[0]) > 6  # twice as large: gap 1 everywhere, times 2 pi
    True
    """
    c, tn = normalise(curves, target)
    if not np.all(np.isfinite(tn)):
        raise GearleverError("target must be a curve of non-zero length and size")
    ok = np.isfinite(c).all(-1)
    out = np.full(c.shape[0], np.inf)
    if ok.any():
        cc = c[ok]
        d = _exact(cc, tn) if keep is None else _fast(cc, tn, keep)
        out[ok] = 2.0 * np.pi * d
    return out


def material(x0s, edges) -> np.ndarray:
    """Twice the total link length of each sketch (the challenge's material), shape (B,).

    Examples
    --------
    >>> float(material([[[0, 0], [3, 0], [3, 4]]], [[0, 1], [1, 2], [0, 2]])[0])
    24.0
    """
    x = np.asarray(x0s, dtype=float)
    e = np.asarray(edges, dtype=int).reshape(-1, 2)
    return 2.0 * np.hypot(*(x[:, e[:, 0]] - x[:, e[:, 1]]).transpose(2, 0, 1)).sum(-1)


def feasible(distances, materials, joints) -> np.ndarray:
    """The challenge's feasibility: distance < 0.75, material < 10, at most 20 joints.

    Examples
    --------
    >>> feasible([0.5, 0.5, 0.8], [9.0, 10.0, 1.0], [20, 5, 5]).tolist()
    [True, False, False]
    """
    d, m, j = (np.asarray(v) for v in (distances, materials, joints))
    return (d < MAX_DISTANCE) & (m < MAX_MATERIAL) & (j <= MAX_JOINTS)


def hypervolume(points, reference=REFERENCE) -> float:
    """Exact area dominated by 2-D points (both minimised) and bounded by ``reference``.

    Points not strictly better than the reference in both objectives add
    nothing.  A sorted sweep: O(n log n).

    Examples
    --------
    >>> hypervolume([[0.5, 5.0], [0.25, 8.0], [0.6, 9.0]], reference=(1.0, 10.0))
    3.0
    """
    F = np.asarray(points, dtype=float).reshape(-1, 2)
    r1, r2 = (float(v) for v in reference)
    F = F[np.isfinite(F).all(1) & (F[:, 0] < r1) & (F[:, 1] < r2)]
    if F.size == 0:
        return 0.0
    F = F[np.lexsort((F[:, 1], F[:, 0]))]
    area, level = 0.0, r2
    for f1, f2 in F:
        if f2 < level:
            area += (r1 - f1) * (level - f2)
            level = f2
    return float(area)
