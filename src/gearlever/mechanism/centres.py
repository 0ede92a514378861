"""Instant centres of velocity of every pair of links, from the solved velocities.

For two links ``i`` and ``j`` moving in the plane, the instant centre
``P_ij`` is the point where a point carried by ``i`` and a point carried by
``j`` have the same velocity.  With ``a_k = v_k(O_k) - w_k k x O_k`` the
velocity of the point of link ``k`` at the origin (``O_k`` its frame origin,
``w_k`` its angular velocity),

    v_k(P) = a_k + w_k k x P,   so   (w_i - w_j) k x P_ij = a_j - a_i,

one 2x2 solve per pair and frame (``k x (x, y) = (-y, x)``).  Pins, sliders
and gear meshes enter only through the solved velocities, so the same
formula gives a pin's centre (the pin), a slider's centre (at infinity,
normal to the guide) and a gear pair's centre (the pitch point).  Pairs
whose angular velocities are equal are in relative translation: their
centre is at infinity, reported as NaN with :attr:`InstantCentres.at_infinity`
set and the direction of the centre (normal to the relative velocity) in
:attr:`InstantCentres.direction`.

Numeric core: numpy only.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from gearlever._result import Result
from gearlever.mechanism.model import GROUND

__all__ = ["InstantCentres", "instant_centres", "kennedy_defect", "centre_columns", "EQUAL_OMEGA_TOL"]

#: Two angular velocities are equal (the centre is at infinity) when they differ by at most this
#: fraction of the largest angular velocity of the frame.
EQUAL_OMEGA_TOL = 1e-6


@dataclass(frozen=True)
class InstantCentres(Result):
    """Instant centres of every pair of links over the frames of a mechanism result.

    Attributes
    ----------
    links : tuple of str
        Ground first, then the moving links in model order.
    pairs : tuple of str
        ``"a/b"`` for every pair of :attr:`links` (``a`` before ``b`` in that order).
    xy : ndarray
        ``(N, P, 2)``: the centre of each pair at each frame; NaN at infinity
        and where the mechanism is not assembled or its rates are undefined.
    at_infinity : ndarray of bool
        ``(N, P)``: the two angular velocities are equal (relative translation).
    direction : ndarray
        ``(N, P, 2)``: unit vector towards a centre at infinity (normal to the
        relative velocity); NaN for finite centres and for pairs without
        relative motion.
    closed : ndarray of bool
        ``(N,)``: the mechanism is assembled with finite rates at this frame.
    """

    links: tuple
    pairs: tuple
    xy: np.ndarray
    at_infinity: np.ndarray
    direction: np.ndarray
    closed: np.ndarray

    def centre(self, a: str, b: str) -> np.ndarray:
        """``(N, 2)`` centre of links ``a`` and ``b`` (either order)."""
        return self.xy[:, self._index(a, b)]

    def _index(self, a: str, b: str) -> int:
        for key in (f"{a}/{b}", f"{b}/{a}"):
            if key in self.pairs:
                return self.pairs.index(key)
        from gearlever.errors import GearleverError

        raise GearleverError(f"links: no pair {a!r}/{b!r} (links: {', '.join(self.links)})")

    def _frame_columns(self) -> dict:
        cols = {}
        for p, key in enumerate(self.pairs):
            cols[f"ic_{key}_x"], cols[f"ic_{key}_y"] = self.xy[:, p, 0], self.xy[:, p, 1]
        return cols


def instant_centres(result) -> InstantCentres:
    """Instant centres of all pairs of links of a solved mechanism, at every frame.

    Parameters
    ----------
    result : MechanismResult
        A solve (:meth:`gearlever.mechanism.Mechanism.solve`).  For one
        degree of freedom the centres do not depend on the input speed; for
        several they are those of the motion at the result's input rates
        ``qdot``.

    Returns
    -------
    InstantCentres

    Notes
    -----
    The velocity of the point ``P`` of link ``k`` is
    ``v_k(P) = v_k(O_k) + w_k k x (P - O_k)``; equating it for links ``i``
    and ``j`` gives ``(w_i - w_j) k x P = a_j - a_i`` with
    ``a_k = v_k(O_k) - w_k k x O_k``: the instant centre (J. J. Uicker,
    G. R. Pennock and J. E. Shigley, *Theory of Machines and Mechanisms*,
    5th ed., Oxford University Press, 2017, ch. 3, the instant centre of
    velocity as the point of equal velocity of two bodies).  When
    ``|w_i - w_j| <= EQUAL_OMEGA_TOL * max_k |w_k|`` the pair is in
    relative translation and its centre is at infinity, in the direction
    normal to ``a_j - a_i``.

    Examples
    --------
    The coupler/ground centre of a four-bar is where the crank and rocker lines meet:

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({
    ...     "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 1], "B": [4, 3]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"],
    ...               "coupler": ["A", "B"], "rocker": ["O4", "B"]},
    ...     "inputs": [{"link": "crank"}]})
    >>> ic = instant_centres(m.solve(m.sketch_inputs[0]))
    >>> np.round(ic.centre("ground", "coupler")[0], 9).tolist()
    [4.0, 4.0]
    """
    m = result.model
    links = (GROUND,) + tuple(m.moving)
    N = result.closed.shape[0]
    pose, vel = result.pose, result.pose_velocity  # (N, n, 3)
    n1 = len(links)
    w = np.zeros((N, n1))
    a = np.zeros((N, n1, 2))
    w[:, 1:] = vel[:, :, 2]
    ox, oy = pose[:, :, 0], pose[:, :, 1]
    a[:, 1:, 0] = vel[:, :, 0] + w[:, 1:] * oy  # v - w k x O, k x O = (-oy, ox)
    a[:, 1:, 1] = vel[:, :, 1] - w[:, 1:] * ox
    ok = result.closed & np.all(np.isfinite(vel), axis=(1, 2)) & np.all(np.isfinite(pose), axis=(1, 2))
    pairs = list(combinations(range(n1), 2))
    I = np.array([p[0] for p in pairs], dtype=int)
    J = np.array([p[1] for p in pairs], dtype=int)
    dw = w[:, I] - w[:, J]  # (N, P)
    d = a[:, J] - a[:, I]  # (N, P, 2)
    wmax = np.max(np.abs(w), axis=1, where=np.isfinite(w), initial=0.0)
    inf = (np.abs(dw) <= EQUAL_OMEGA_TOL * wmax[:, None]) & ok[:, None]
    good = ok[:, None] & ~inf
    safe = np.where(good, dw, 1.0)
    xy = np.full((N, len(pairs), 2), np.nan)
    xy[..., 0] = np.where(good, d[..., 1] / safe, np.nan)
    xy[..., 1] = np.where(good, -d[..., 0] / safe, np.nan)
    # a centre at infinity lies along the normal to the relative (translational) velocity
    nrm = np.hypot(d[..., 0], d[..., 1])
    dscale = np.max(np.abs(a), axis=(1, 2), where=np.isfinite(a), initial=0.0)
    moving = inf & (nrm > 1e-12 * np.maximum(dscale, 1e-300)[:, None])
    nsafe = np.where(moving, nrm, 1.0)
    direction = np.full_like(xy, np.nan)
    direction[..., 0] = np.where(moving, -d[..., 1] / nsafe, np.nan)
    direction[..., 1] = np.where(moving, d[..., 0] / nsafe, np.nan)
    names = tuple(f"{links[i]}/{links[j]}" for i, j in pairs)
    return InstantCentres(links, names, xy, inf, direction, ok)


def kennedy_defect(ic: InstantCentres) -> tuple:
    """How far the three centres of every triple of links are from a line (Kennedy's theorem).

    Returns
    -------
    triples : tuple of tuple of str
        Every triple of :attr:`InstantCentres.links`, in order.
    defect : ndarray
        ``(N, T)``: ``|cross(P_jk - P_ij, P_ik - P_ij)|`` divided by the
        product of the two lengths (the sine of the angle between them),
        with a centre at infinity replaced by its direction; NaN where two
        centres are at infinity, or coincide, or the frame is not assembled.

    Notes
    -----
    Aronhold-Kennedy theorem: the three instant centres of three bodies in
    plane motion lie on one straight line (Uicker, Pennock and Shigley,
    *Theory of Machines and Mechanisms*, 5th ed., ch. 3, the theorem of
    three centres).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({
    ...     "points": {"O2": [0, 0], "O4": [4, 0], "A": [1, 1], "B": [4, 3]},
    ...     "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"],
    ...               "coupler": ["A", "B"], "rocker": ["O4", "B"]},
    ...     "inputs": [{"link": "crank"}]})
    >>> triples, dev = kennedy_defect(instant_centres(m.solve([0.3, 1.2])))
    >>> len(triples), bool(np.nanmax(dev) < 1e-12)
    (4, True)
    """
    n1 = len(ic.links)
    triples = tuple(combinations(range(n1), 3))
    out = np.full((ic.xy.shape[0], len(triples)), np.nan)

    def idx(i, j):
        return ic.pairs.index(f"{ic.links[i]}/{ic.links[j]}")

    for t, (i, j, k) in enumerate(triples):
        cs = [idx(i, j), idx(i, k), idx(j, k)]
        P = ic.xy[:, cs]  # (N, 3, 2)
        D = ic.direction[:, cs]
        fin = np.all(np.isfinite(P), axis=2)  # (N, 3)
        for base in range(3):
            others = [c for c in range(3) if c != base]
            vecs = []
            for c in others:
                v = np.where(fin[:, c, None], P[:, c] - P[:, base], D[:, c])
                vecs.append(v)
            u, v = vecs
            cross = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
            lu, lv = np.hypot(u[:, 0], u[:, 1]), np.hypot(v[:, 0], v[:, 1])
            with np.errstate(invalid="ignore", divide="ignore"):
                s = np.abs(cross) / (lu * lv)
            use = fin[:, base] & np.isnan(out[:, t]) & (lu > 0) & (lv > 0) & np.isfinite(s)
            out[use, t] = s[use]
    names = tuple(tuple(ic.links[c] for c in tr) for tr in triples)
    return names, out


def centre_columns(result) -> dict:
    """Command-line columns of the instant centres of ``result``: ``ic_ground/coupler_x_mm`` ...

    Lengths carry the model's ``units`` label (``len`` when none); a centre
    at infinity is NaN (``gearlever mechanism analyze --centres`` writes it
    empty in CSV and null in JSON).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"mechanism": {"units": "mm"}, "points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> list(centre_columns(m.solve([0.0, 1.0])))
    ['ic_ground/crank_x_mm', 'ic_ground/crank_y_mm']
    """
    ic = instant_centres(result)
    u = result.model.units or "len"
    cols = {}
    for p, key in enumerate(ic.pairs):
        cols[f"ic_{key}_x_{u}"], cols[f"ic_{key}_y_{u}"] = ic.xy[:, p, 0], ic.xy[:, p, 1]
    return cols
