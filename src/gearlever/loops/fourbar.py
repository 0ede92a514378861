"""The four-bar linkage: closed-form positions and analogues, Grashof, limits, transmission.

Conventions: ground pivot O2 at the origin, ground pivot O4 at ``(ground, 0)``;
crank O2-A at angle ``phi`` (the input), coupler A-B at ``theta3``, rocker
O4-B at ``theta4``; angles in radians, counter-clockwise from +x, returned in
``(-pi, pi]``.  The loop is ``crank e^{i phi} + coupler e^{i theta3} -
rocker e^{i theta4} - ground = 0``.

Branches: ``"open"`` puts B on the left of the diagonal A->O4 (the convex
quadrilateral of textbook drawings when ``0 < phi < pi``), ``"crossed"``
on its right.  The branch is a fixed sign in the closed form, so it is kept
along the whole motion and never jumps.

Pure numpy.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever._validate import finite_array, positive
from gearlever.errors import ClosureError, GearleverError
from gearlever.loops.engine import INPUT, LoopSystem, Vector

__all__ = [
    "FourBar",
    "FourBarResult",
    "fourbar",
    "fourbar_system",
    "GrashofClass",
    "grashof",
    "LimitPositions",
    "limit_positions",
    "transmission_angle",
    "change_points",
]

_BRANCH = {"open": 1.0, "crossed": -1.0}


def _branch(branch) -> float:
    try:
        return _BRANCH[branch]
    except (KeyError, TypeError):
        raise GearleverError(f"branch must be 'open' or 'crossed', got {branch!r}") from None


def _lengths(ground, crank, coupler, rocker):
    d = positive("ground", ground)
    a = positive("crank", crank)
    b = positive("coupler", coupler)
    c = positive("rocker", rocker)
    links = {"ground": d, "crank": a, "coupler": b, "rocker": c}
    name, longest = max(links.items(), key=lambda kv: kv[1])
    # the sum of the three others, added directly (not total - longest, which
    # loses them entirely beside a huge link: 1e308 + 3 - 1e308 = 0)
    others = sum(sorted(v for k, v in links.items() if k != name))  # inf beside huge links: still >
    if longest >= others:
        raise GearleverError(
            f"{name} must be shorter than the sum of the other three links "
            f"({others:.6g}) for the linkage to assemble, got {longest:.6g}"
        )
    return d, a, b, c


@dataclass(frozen=True)
class FourBarResult(Result):
    """Positions and analogues of a four-bar over an array of crank angles.

    Attributes
    ----------
    phi : ndarray
        Input (crank) angles, radians (also readable as ``theta2``, its old
        name).
    theta3, theta4 : ndarray
        Coupler and rocker angles, radians in ``(-pi, pi]``; NaN where the
        loop cannot close.
    dtheta3_dphi, dtheta4_dphi : ndarray
        Velocity analogues ``omega3/omega2``, ``omega4/omega2``.
    d2theta3_dphi2, d2theta4_dphi2 : ndarray
        Acceleration analogues (``alpha/omega2**2`` at constant crank speed).
    valid : ndarray of bool
        Closes and is not at a dead point (all six arrays finite).
    closed : ndarray of bool
        Closes (positions finite).
    change_point : ndarray of bool
        The linkage is folded flat here (all four joints on the ground line,
        within ``singular_tol``): a change point of a Grashof change-point
        linkage (``s + l = p + q``), where it can switch assembly.  The
        closed form's branch sign is kept, so past such a point the same
        ``branch`` names a different assembly (the parallelogram 4/2/4/2
        becomes the antiparallelogram); see :func:`change_points`.

    Examples
    --------
    >>> r = fourbar(9, 5, 8, 8, [0.0, 1.0])
    >>> r.theta4.shape, bool(r.valid.all())
    ((2,), True)
    """

    phi: np.ndarray
    theta3: np.ndarray
    theta4: np.ndarray
    dtheta3_dphi: np.ndarray
    dtheta4_dphi: np.ndarray
    d2theta3_dphi2: np.ndarray
    d2theta4_dphi2: np.ndarray
    valid: np.ndarray
    closed: np.ndarray
    change_point: np.ndarray

    @property
    def theta2(self) -> np.ndarray:
        """:attr:`phi` under its old name (the crank angle)."""
        return self.phi


def _scaled(ground, crank, coupler, rocker):
    """Checked lengths divided by the longest: angles and analogues are scale-free, and
    huge (1e308) or tiny lengths then neither overflow nor underflow."""
    d, a, b, c = _lengths(ground, crank, coupler, rocker)
    m = max(d, a, b, c)
    return d / m, a / m, b / m, c / m


def fourbar(ground, crank, coupler, rocker, phi, branch="open", *, strict=False, singular_tol=1e-7) -> FourBarResult:
    """Coupler and rocker angles of a four-bar and their analogues, closed form.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths (> 0, the longest shorter than the sum of the others).
    phi : array_like
        Crank angles, radians, any shape.
    branch : {"open", "crossed"}
        Assembly branch, kept for every point.
    strict : bool
        Raise :class:`~gearlever.errors.ClosureError` if any point cannot close or is at a dead point,
        instead of returning NaN there with ``valid`` False.
    singular_tol : float
        A point is a dead point where ``|sin(theta3 - theta4)|`` is below this.

    Returns
    -------
    FourBarResult

    Notes
    -----
    Position: with the diagonal ``D = O4 - A`` of length ``f``, the triangle
    A-B-O4 gives ``cos(gamma) = (coupler^2 + f^2 - rocker^2) / (2 coupler f)``
    and ``theta3 = arg(D) + sigma gamma`` (``sigma = +1`` open, ``-1``
    crossed); B follows and ``theta4 = arg(B - O4)``.  The loop closes iff
    ``|cos(gamma)| <= 1``.  Analogues: the differentiated loop (Norton,
    *Design of Machinery*, eqs. 6.18 and 7.12, as analogues) solved by
    Cramer's rule::

        dtheta3/dphi = a sin(theta4 - phi) / (b sin(theta3 - theta4))
        dtheta4/dphi = a sin(theta3 - phi) / (c sin(theta3 - theta4))

    and the same 2x2 matrix for the acceleration analogues.

    Examples
    --------
    >>> r = fourbar(9.0, 5.0, 8.0, 8.0, [0.0, np.pi / 2])
    >>> np.round(np.degrees(r.theta4), 6).tolist()
    [104.477512, 100.996969]
    >>> bool(r.valid.all())
    True
    """
    d, a, b, c = _scaled(ground, crank, coupler, rocker)
    sigma = _branch(branch)
    th2 = finite_array("phi", phi)
    c2, s2 = np.cos(th2), np.sin(th2)
    dx, dy = d - a * c2, -a * s2
    f2 = dx * dx + dy * dy
    f = np.sqrt(f2)
    with np.errstate(divide="ignore", invalid="ignore"):
        cg = (b * b + f2 - c * c) / (2.0 * b * f)
        closed = (f > 0) & (np.abs(cg) <= 1.0 + 1e-13)
        cg = np.clip(np.where(closed, cg, np.nan), -1.0, 1.0)
        sg = sigma * np.sqrt(1.0 - cg * cg)
        c3 = (dx * cg - dy * sg) / f
        s3 = (dy * cg + dx * sg) / f
        bx, by = a * c2 + b * c3 - d, a * s2 + b * s3
        theta3 = np.arctan2(s3, c3)
        theta4 = np.arctan2(by, bx)
        # (c3, s3) is a unit vector by construction; normalize (c4, s4) against rounding
        h4 = np.hypot(bx, by)
        c4, s4 = bx / h4, by / h4
        S = s3 * c4 - c3 * s4  # sin(theta3 - theta4)
        dead = ~(np.abs(S) > singular_tol)
        valid = closed & ~dead
        S = np.where(valid, S, np.nan)
        w3 = a * (s4 * c2 - c4 * s2) / (b * S)
        w4 = a * (s3 * c2 - c3 * s2) / (c * S)
        kx = a * c2 + b * w3 * w3 * c3 - c * w4 * w4 * c4
        ky = a * s2 + b * w3 * w3 * s3 - c * w4 * w4 * s4
        e3 = -(kx * c4 + ky * s4) / (b * S)
        e4 = -(kx * c3 + ky * s3) / (c * S)
        # folded flat: A and B on the ground line (the change point of s + l = p + q)
        change_point = closed & (np.abs(s2) <= singular_tol) & (np.abs(a * s2 + b * s3) <= singular_tol)
    if strict and not valid.all():
        first = th2.reshape(-1)[int(np.flatnonzero(~valid.reshape(-1))[0])]
        raise ClosureError(
            f"phi: the four-bar cannot close or is at a dead point at phi = {first!r} rad "
            f"({int((~valid).sum())} of {valid.size} points)"
        )
    return FourBarResult(th2, theta3, theta4, w3, w4, e3, e4, valid, closed, change_point)


def fourbar_system(ground, crank, coupler, rocker) -> LoopSystem:
    """The four-bar as a general :class:`~gearlever.loops.engine.LoopSystem`.

    Vectors: ``A`` (crank, input angle), ``BA`` (coupler, unknown
    ``theta3``), ``B`` (rocker, unknown ``theta4``, sign -1), ``O4``
    (ground, sign -1), so that ``r_A + r_BA = r_B + r_O4``.

    Examples
    --------
    >>> fourbar_system(9, 5, 8, 8).unknowns
    ('theta3', 'theta4')
    """
    d, a, b, c = _lengths(ground, crank, coupler, rocker)
    return LoopSystem(
        [
            [
                Vector("A", a, INPUT),
                Vector("BA", b, "theta3"),
                Vector("B", c, "theta4", -1),
                Vector("O4", d, 0.0, -1),
            ]
        ]
    )


@dataclass(frozen=True)
class GrashofClass:
    """Grashof classification of a four-bar.

    Attributes
    ----------
    condition : str
        ``"grashof"`` (s + l < p + q), ``"change point"`` (=) or ``"non-grashof"``.
    kind : str
        ``"crank-rocker"``, ``"rocker-crank"``, ``"double-crank"``,
        ``"double-rocker"``, ``"change point"`` or ``"triple-rocker"``.
    s_plus_l, p_plus_q : float
        Shortest plus longest, and the sum of the other two.
    crank_rotates : bool
        Whether the input link can make full turns.

    Examples
    --------
    >>> grashof(9, 5, 8, 8).kind
    'crank-rocker'
    """

    condition: str
    kind: str
    s_plus_l: float
    p_plus_q: float
    crank_rotates: bool


def grashof(ground, crank, coupler, rocker) -> GrashofClass:
    """Classify a four-bar by Grashof's condition and the position of its shortest link.

    Notes
    -----
    Grashof's law (Norton, *Design of Machinery*, sec. 2.12): with s the
    shortest, l the longest and p, q the others, if ``s + l < p + q`` some
    link turns fully; the shortest link as the crank gives a crank-rocker, as
    the ground a double-crank, as the coupler a double-rocker.  If
    ``s + l > p + q`` no link turns fully (triple rocker); equality is a
    change-point linkage.

    Examples
    --------
    >>> grashof(9, 5, 8, 8).kind
    'crank-rocker'
    >>> grashof(4, 5, 8, 8).kind
    'double-crank'
    >>> grashof(9, 7, 8, 7).condition
    'non-grashof'
    """
    d, a, b, c = _lengths(ground, crank, coupler, rocker)
    ls = sorted([d, a, b, c])
    sl, pq = ls[0] + ls[3], ls[1] + ls[2]
    tol = 1e-12 * ls[3]
    if abs(sl - pq) <= tol:
        return GrashofClass("change point", "change point", sl, pq, True)
    if sl > pq:
        return GrashofClass("non-grashof", "triple-rocker", sl, pq, False)
    s = ls[0]
    if d == s:
        kind, rot = "double-crank", True
    elif a == s:
        kind, rot = "crank-rocker", True
    elif c == s:
        kind, rot = "rocker-crank", False
    else:
        kind, rot = "double-rocker", False
    return GrashofClass("grashof", kind, sl, pq, rot)


@dataclass(frozen=True)
class LimitPositions(Result):
    """Limit positions of a four-bar on one branch.

    Attributes
    ----------
    input_limits : ndarray
        Crank angles (radians) where the coupler and rocker are collinear:
        the input cannot pass them (empty when the crank turns fully).
    theta2_at_rocker_extremes, theta4_extremes : ndarray
        Crank angles where the crank and coupler are collinear (the rocker
        stops, dtheta4/dphi = 0) and the rocker angles there.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(np.degrees(limit_positions(9, 5, 8, 8).theta4_extremes), 2)
    array([ 80.41, 160.81])
    """

    input_limits: np.ndarray
    theta2_at_rocker_extremes: np.ndarray
    theta4_extremes: np.ndarray


def _wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def limit_positions(ground, crank, coupler, rocker, branch="open") -> LimitPositions:
    """Input limits (toggle positions) and rocker extremes of a four-bar.

    Notes
    -----
    Toggle of the input: coupler and rocker collinear, ``|O4 A| = b +- c``,
    so ``cos(phi) = (a^2 + d^2 - (b +- c)^2) / (2 a d)``.  Rocker
    extremes: crank and coupler collinear, ``|O2 B| = a + b`` (extended) or
    ``|a - b|`` (folded), and the triangle O2-O4-B gives B (Norton, sec. 3.3).
    Only the positions that lie on ``branch`` are kept.

    Examples
    --------
    >>> lp = limit_positions(9, 5, 8, 8)
    >>> lp.input_limits.size, np.round(np.degrees(lp.theta4_extremes), 4).tolist()
    (0, [80.4059, 160.8119])
    """
    d, a, b, c = _lengths(ground, crank, coupler, rocker)
    _branch(branch)
    lims = []
    for bc in (b + c, abs(b - c)):
        cos2 = (a * a + d * d - bc * bc) / (2 * a * d)
        if abs(cos2) <= 1.0:
            t = float(np.arccos(cos2))
            lims.extend([t, -t] if t not in (0.0, float(np.pi)) else [t])
    cands = []
    for ob, shift in ((a + b, 0.0), (abs(a - b), 0.0 if a > b else np.pi)):
        if ob == 0:
            continue
        cb = (d * d + ob * ob - c * c) / (2 * d * ob)
        if abs(cb) <= 1.0:
            beta = float(np.arccos(cb))
            cands.extend([beta + shift, -beta + shift])
    cands = _wrap(np.array(cands, dtype=float))
    t2, t4 = [], []
    if cands.size:
        r = fourbar(d, a, b, c, cands, branch=branch)
        for th2, th3, th4, ok in zip(cands, r.theta3, r.theta4, r.closed):
            if not ok:
                continue
            # on this branch if the coupler is collinear with the crank
            if abs(np.sin(th3 - th2)) < 1e-7:
                t2.append(float(th2))
                t4.append(float(th4))
    order = np.argsort(t4)
    return LimitPositions(
        np.sort(np.array(lims, dtype=float)),
        np.array(t2, dtype=float)[order],
        np.array(t4, dtype=float)[order],
    )


def change_points(ground, crank, coupler, rocker) -> np.ndarray:
    """Crank angles where a four-bar folds flat (all joints on the ground line), radians.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths (> 0, the longest shorter than the sum of the others).

    Returns
    -------
    ndarray
        Sorted angles in ``[0, pi]`` (of 0 and pi) where the linkage is flat;
        empty unless the linkage is a Grashof change-point linkage
        (``s + l = p + q``).

    Notes
    -----
    Flat means the crank lies on the ground line (``phi = 0`` or ``pi``)
    and the triangle A-B-O4 is degenerate: ``|O4 - A| = |d - a cos(phi)|``
    equals ``b + c`` or ``|b - c|``.  That happens only when
    ``s + l = p + q`` (Norton, *Design of Machinery*, sec. 2.12, the
    change-point or "special Grashof" case): there the linkage can switch
    between two assemblies (parallelogram and antiparallelogram for
    ``d = b``, ``a = c``).  :func:`fourbar` keeps its branch sign through
    the point, so it follows the switch; ``FourBarResult.change_point``
    marks the samples at the fold.

    Examples
    --------
    >>> np.degrees(change_points(4, 2, 4, 2)).tolist()
    [0.0, 180.0]
    >>> change_points(9, 5, 8, 8).size
    0
    """
    d, a, b, c = _scaled(ground, crank, coupler, rocker)
    out = []
    for th in (0.0, math.pi):
        f = abs(d - a * math.cos(th))
        if min(abs(f - (b + c)), abs(f - abs(b - c))) <= 1e-12:
            out.append(th)
    return np.array(out, dtype=float)


def transmission_angle(ground, crank, coupler, rocker, phi) -> np.ndarray:
    """Transmission angle (between coupler and rocker), radians in ``[0, pi]``.

    Notes
    -----
    Law of cosines in triangle A-B-O4 (Norton, eq. 3.3a):
    ``cos(mu) = (b^2 + c^2 - f^2) / (2 b c)``, ``f = |O4 - A|``; the same on
    both branches.  NaN where the loop cannot close.  Good practice keeps
    ``mu`` within 40..140 degrees.

    Examples
    --------
    >>> float(np.degrees(transmission_angle(9, 5, 8, 8, 0.0)).round(6))
    28.955024
    """
    d, a, b, c = _scaled(ground, crank, coupler, rocker)
    th2 = finite_array("phi", phi)
    f2 = a * a + d * d - 2 * a * d * np.cos(th2)
    cm = (b * b + c * c - f2) / (2 * b * c)
    with np.errstate(invalid="ignore"):
        return np.where(np.abs(cm) <= 1.0 + 1e-13, np.arccos(np.clip(cm, -1.0, 1.0)), np.nan)


@dataclass(frozen=True)
class FourBar:
    """A four-bar linkage as a frozen parameter object over the functions of this module.

    Parameters
    ----------
    ground, crank, coupler, rocker : float
        Link lengths (> 0, the longest shorter than the sum of the others).
    branch : {"open", "crossed"}

    Examples
    --------
    >>> fb = FourBar(9, 5, 8, 8)
    >>> fb.grashof().kind, bool(fb.solve([0.0]).valid[0])
    ('crank-rocker', True)
    """

    ground: float
    crank: float
    coupler: float
    rocker: float
    branch: str = "open"

    def __post_init__(self):
        d, a, b, c = _lengths(self.ground, self.crank, self.coupler, self.rocker)
        _branch(self.branch)
        for name, v in zip(("ground", "crank", "coupler", "rocker"), (d, a, b, c)):
            object.__setattr__(self, name, v)

    @property
    def links(self) -> tuple:
        """``(ground, crank, coupler, rocker)``."""
        return (self.ground, self.crank, self.coupler, self.rocker)

    def solve(self, phi, *, strict=False) -> FourBarResult:
        """:func:`fourbar` on this linkage and branch."""
        return fourbar(*self.links, phi, branch=self.branch, strict=strict)

    def system(self) -> LoopSystem:
        """:func:`fourbar_system` of this linkage."""
        return fourbar_system(*self.links)

    def grashof(self) -> GrashofClass:
        """:func:`grashof` of this linkage."""
        return grashof(*self.links)

    def limit_positions(self) -> LimitPositions:
        """:func:`limit_positions` on this branch."""
        return limit_positions(*self.links, branch=self.branch)

    def transmission_angle(self, phi) -> np.ndarray:
        """:func:`transmission_angle` of this linkage."""
        return transmission_angle(*self.links, phi)

    def change_points(self) -> np.ndarray:
        """:func:`change_points` of this linkage."""
        return change_points(*self.links)
