"""Motion generation (rigid-body guidance) of a four-bar through 3, 4 or 5 poses of its coupler.

A pose is a coupler point ``(x, y)`` and the coupler's angle; only angle
differences matter.  Each side of the four-bar is a dyad: a ground pivot
(centre point) ``G``, a moving pivot (circle point) ``M`` on the coupler.
With ``delta_j = P_j - P_1``, ``alpha_j = angle_j - angle_1`` and the crank
rotation ``beta_j``, a dyad ``W = M_1 - G``, ``Z = P_1 - M_1`` (complex)
satisfies the standard-form dyad equations (A. G. Erdman and G. N. Sandor,
*Advanced Mechanism Design: Analysis and Synthesis*, vol. 2, Prentice-Hall, 1984)::

    W (e^{i beta_j} - 1) + Z (e^{i alpha_j} - 1) = delta_j,   j = 2..n.

- 3 poses: given the ground pivots, the moving pivots are linear unknowns;
  given the moving pivots, each ground pivot is the centre of the circle
  through the pivot's three positions.
- 4 poses: the centre-point and circle-point (Burmester) curves, sampled
  along the crank rotation ``beta_2``.
- 5 poses: every real Burmester point pair, from the roots of one
  polynomial (a resultant, :func:`numpy.roots`), at most four.

Numeric core: numpy, :mod:`gearlever.loops`, :mod:`gearlever.mechanism`.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as npoly

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.loops.fourbar import fourbar, grashof, transmission_angle
from gearlever.synthesis.model import fourbar_model
from gearlever.synthesis.registry import Kind, register

__all__ = [
    "Dyad",
    "BurmesterCurves",
    "MotionSolution",
    "MotionSynthesis",
    "moving_pivot",
    "fixed_pivot",
    "burmester_curves",
    "burmester_points",
    "synthesize_motion",
    "MAX_POSES",
]

#: Rigid-body guidance of a four-bar is exact for at most five poses.
MAX_POSES = 5
#: Dyads taken along each branch of the centre-point curve for four poses.
CURVE_DYADS = 48


def _poses(points, angles):
    try:
        P = np.asarray(points, dtype=float)
        th = np.asarray(angles, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise GearleverError("poses must be numbers: points (N, 2) and angles (N,)") from None
    if P.ndim != 2 or P.shape[1] != 2 or P.shape[0] != th.size:
        raise GearleverError(f"points must be (N, 2) and angles (N,), got {P.shape} and {th.shape}")
    if not (np.all(np.isfinite(P)) and np.all(np.isfinite(th))):
        raise GearleverError("poses must be finite (found NaN or inf)")
    n = th.size
    if n < 3:
        raise GearleverError(f"motion generation needs at least 3 poses, got {n}")
    if n > MAX_POSES:
        raise GearleverError(f"a four-bar can be guided exactly through at most {MAX_POSES} poses, got {n}")
    z = P[:, 0] + 1j * P[:, 1]
    for i, j in itertools.combinations(range(n), 2):
        if abs(z[i] - z[j]) == 0 and math.isclose(math.remainder(th[i] - th[j], 2 * math.pi), 0.0, abs_tol=1e-12):
            raise GearleverError(f"poses {i + 1} and {j + 1} are the same pose")
    return z, th


def _xy(z) -> tuple:
    return (float(np.real(z)), float(np.imag(z)))


@dataclass(frozen=True)
class Dyad(Result):
    """One side of a four-bar: ground pivot and moving pivot (at the first pose).

    Attributes
    ----------
    ground_pivot, moving_pivot : tuple of float
        Centre point ``G`` and circle point ``M_1``.
    beta : ndarray
        Rotation of the link G-M from the first pose to each pose, radians.

    Examples
    --------
    >>> d = moving_pivot([(0, 0), (1, 0.5), (2, 0.5)], np.radians([0, 20, 45]), (0.0, -2.0))
    >>> [round(v, 4) for v in d.ground_pivot], [round(v, 4) for v in d.moving_pivot]
    ([0.0, -2.0], [-0.906, 0.147])
    """

    ground_pivot: tuple
    moving_pivot: tuple
    beta: np.ndarray


def _dyad(z, th, G, M1) -> Dyad:
    Mj = z + np.exp(1j * (th - th[0])) * (M1 - z[0])
    beta = np.angle((Mj - G) / (M1 - G))
    return Dyad(_xy(G), _xy(M1), beta)


def moving_pivot(points, angles, ground_pivot) -> Dyad:
    """Three poses and a ground pivot: the moving pivot on the coupler (circle point), linear.

    Notes
    -----
    With ``u = M_1 - P_1``, ``|P_j + e^{i alpha_j} u - G| = |P_1 + u - G|``
    for ``j = 2, 3``; ``|u|^2`` cancels, leaving two linear equations
    ``2 Re([conj(P_j - G) e^{i alpha_j} - conj(P_1 - G)] u) = |P_1 - G|^2 -
    |P_j - G|^2`` (the inversion of Erdman & Sandor, *Advanced Mechanism
    Design* vol. 2, the specified ground-pivot case of three-position synthesis).

    Examples
    --------
    >>> d = moving_pivot([(0, 0), (1, 0.5), (2, 0.5)], np.radians([0, 20, 45]), (0.0, -2.0))
    >>> [round(v, 6) for v in d.moving_pivot]
    [-0.906013, 0.147035]
    """
    z, th = _poses(points, angles)
    if z.size != 3:
        raise GearleverError(f"moving_pivot takes exactly 3 poses, got {z.size}")
    G = complex(*_pair("ground_pivot", ground_pivot))
    rows, rhs = [], []
    for j in (1, 2):
        c = np.conj(z[j] - G) * np.exp(1j * (th[j] - th[0])) - np.conj(z[0] - G)
        rows.append([2 * c.real, -2 * c.imag])
        rhs.append(abs(z[0] - G) ** 2 - abs(z[j] - G) ** 2)
    A = np.array(rows)
    scale = max(1.0, float(np.abs(A).max()))
    if abs(np.linalg.det(A)) <= 1e-12 * scale * scale:
        raise GearleverError("ground_pivot: no unique moving pivot for these poses (the equations are degenerate)")
    u = np.linalg.solve(A, np.array(rhs))
    return _dyad(z, th, G, z[0] + complex(u[0], u[1]))


def fixed_pivot(points, angles, moving_pivot) -> Dyad:
    """Three poses and a moving pivot (at the first pose): the ground pivot, centre of the circle through its positions.

    Notes
    -----
    The centre-point construction of three-position synthesis (Norton,
    *Design of Machinery*, chapter on graphical linkage synthesis; Erdman & Sandor
    vol. 2, three-position synthesis): the
    circumcentre of ``M_1, M_2, M_3``.

    Examples
    --------
    >>> d = fixed_pivot([(0, 0), (1, 0.5), (2, 0.5)], np.radians([0, 20, 45]), (-0.906013, 0.147035))
    >>> [round(v, 4) + 0.0 for v in d.ground_pivot]
    [0.0, -2.0]
    """
    z, th = _poses(points, angles)
    if z.size != 3:
        raise GearleverError(f"fixed_pivot takes exactly 3 poses, got {z.size}")
    M1 = complex(*_pair("moving_pivot", moving_pivot))
    M = z + np.exp(1j * (th - th[0])) * (M1 - z[0])
    a, b, c = M
    d = 2 * ((b - a).real * (c - a).imag - (b - a).imag * (c - a).real)
    span = max(abs(b - a), abs(c - a), abs(c - b))
    if abs(d) <= 1e-12 * max(span, 1e-300) ** 2:
        raise GearleverError("moving_pivot: its three positions are on a line (no finite ground pivot)")
    ba, ca = b - a, c - a
    G = a + 1j * (ba * abs(ca) ** 2 - ca * abs(ba) ** 2) / d
    return _dyad(z, th, G, M1)


def _pair(name, p):
    try:
        x, y = (float(v) for v in p)
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be a pair of numbers (x, y), got {p!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise GearleverError(f"{name} must be finite, got {p!r}")
    return x, y


def _cofactors(z, th, idx):
    """Cofactors C_j of the first column of the compatibility matrix of poses 1, *idx*, and S = sum C_j."""
    d = z[list(idx)] - z[0]
    A = np.exp(1j * (th[list(idx)] - th[0])) - 1
    C = np.array(
        [A[1] * d[2] - A[2] * d[1], -(A[0] * d[2] - A[2] * d[0]), A[0] * d[1] - A[1] * d[0]],
        dtype=complex,
    )
    return C, complex(C.sum())


def _wz(z, th, j, k, bj, bk):
    """W, Z from poses j and k (indices) with crank rotations bj, bk."""
    M = np.array(
        [
            [np.exp(1j * bj) - 1, np.exp(1j * (th[j] - th[0])) - 1],
            [np.exp(1j * bk) - 1, np.exp(1j * (th[k] - th[0])) - 1],
        ]
    )
    rhs = np.array([z[j] - z[0], z[k] - z[0]])
    if abs(np.linalg.det(M)) < 1e-13:
        return None
    W, Z = np.linalg.solve(M, rhs)
    return W, Z


@dataclass(frozen=True)
class BurmesterCurves(Result):
    """Centre-point and circle-point curves of four poses, sampled along the crank rotation ``beta_2``.

    Attributes
    ----------
    beta2 : ndarray
        ``(N,)`` parameter, radians.
    center : ndarray
        ``(N, 2, 2)``: for each sample, the two branches (``+``/``-`` of the
        triangle closure), ``x, y`` of the centre point (ground pivot); NaN
        where the branch is not real.
    circle : ndarray
        ``(N, 2, 2)``: the matching circle points (moving pivots at pose 1).

    Examples
    --------
    >>> c = burmester_curves([(0, 0), (1, 0.5), (2, 0.4), (2.8, -0.2)], np.radians([0, 15, 35, 60]), samples=8)
    >>> c.beta2.shape, c.center.shape == c.circle.shape
    ((8,), True)
    """

    beta2: np.ndarray
    center: np.ndarray
    circle: np.ndarray

    def _frame_columns(self) -> dict:
        cols = {"beta2_rad": self.beta2}
        for b, s in enumerate("pm"):
            cols[f"center_{s}_x"], cols[f"center_{s}_y"] = self.center[:, b, 0], self.center[:, b, 1]
            cols[f"circle_{s}_x"], cols[f"circle_{s}_y"] = self.circle[:, b, 0], self.circle[:, b, 1]
        return cols


def burmester_curves(points, angles, samples: int = 720) -> BurmesterCurves:
    """Centre-point and circle-point curves of four poses (every dyad that guides the coupler through them).

    Notes
    -----
    The compatibility of the dyad equations for poses 1-4 (Erdman & Sandor,
    *Advanced Mechanism Design* vol. 2, four-position Burmester theory): the determinant of
    ``[e^{i beta_j} - 1, e^{i alpha_j} - 1, delta_j]`` (j = 2, 3, 4) vanishes,
    ``C_2 e^{i beta_2} + C_3 e^{i beta_3} + C_4 e^{i beta_4} = C_2 + C_3 + C_4``
    with ``C_j`` its cofactors: for each ``beta_2`` a triangle with sides
    ``|C_3|, |C_4|`` closes in two ways (or none), giving ``beta_3``; then
    ``W, Z`` from poses 2, 3, the centre point ``P_1 - Z - W`` and the
    circle point ``P_1 - Z``.

    Examples
    --------
    >>> pts = [(0, 0), (1, 0.5), (2, 0.4), (2.8, -0.2)]
    >>> c = burmester_curves(pts, np.radians([0, 15, 35, 60]), samples=8)
    >>> c.center.shape
    (8, 2, 2)
    """
    z, th = _poses(points, angles)
    if z.size != 4:
        raise GearleverError(f"burmester_curves takes exactly 4 poses, got {z.size}")
    if isinstance(samples, bool) or not isinstance(samples, (int, np.integer)) or not 2 <= samples <= 100_000:
        raise GearleverError(f"samples must be an integer from 2 to 100000, got {samples!r}")
    C, S = _cofactors(z, th, (1, 2, 3))
    beta2 = np.linspace(-np.pi, np.pi, int(samples), endpoint=False) + np.pi / samples
    center = np.full((beta2.size, 2, 2), np.nan)
    circle = np.full((beta2.size, 2, 2), np.nan)
    for i, b2 in enumerate(beta2):
        for k, b3 in enumerate(_beta3(C, S, b2)):
            if b3 is None:
                continue
            wz = _wz(z, th, 1, 2, b2, b3)
            if wz is None:
                continue
            W, Z = wz
            M1 = z[0] - Z
            G = M1 - W
            center[i, k] = _xy(G)
            circle[i, k] = _xy(M1)
    return BurmesterCurves(beta2, center, circle)


def _beta3(C, S, b2):
    T = S - C[0] * np.exp(1j * b2)
    t, r3, r4 = abs(T), abs(C[1]), abs(C[2])
    if t == 0 or r3 == 0:
        return [None, None]
    cg = (t * t + r3 * r3 - r4 * r4) / (2 * t * r3)
    if abs(cg) > 1:
        return [None, None]
    g = math.acos(cg)
    out = []
    for s in (1, -1):
        v = T / t * r3 * np.exp(1j * s * g) / C[1]
        out.append(float(np.angle(v)))
    return out


def burmester_points(points, angles) -> tuple:
    """Every dyad that guides the coupler through five poses (the Burmester point pairs, at most four).

    Returns
    -------
    tuple of Dyad
        Real solutions, in order of ``beta_2``.

    Notes
    -----
    Two compatibility equations (poses 1,2,3,4 and 1,2,3,5, see
    :func:`burmester_curves`) share ``u = e^{i beta_2}``, ``v = e^{i beta_3}``.
    Eliminating ``beta_4`` (``beta_5``) by ``|S - C_2 u - C_3 v| = |C_4|``
    and writing ``conj(u) = 1/u`` turns each into a polynomial quadratic in
    ``v`` with coefficients quadratic in ``u``; the resultant in ``v`` of the
    two is a polynomial of degree at most 8 in ``u`` whose roots on the unit
    circle, other than the trivial ``u = 1`` and the spurious ``u = 0``,
    are the Burmester solutions (Erdman & Sandor, *Advanced Mechanism Design*
    vol. 2, five-position Burmester theory: at most four real).  All its roots are found
    (:func:`numpy.roots`), the matching ``v`` from the quadratic, and each
    pair is polished by Newton steps on the two real equations.

    Examples
    --------
    >>> import numpy as np
    >>> pts = [(0.0, 0.0), (1.0, 0.6), (2.0, 0.9), (3.0, 0.7), (3.6, 0.1)]
    >>> len(burmester_points(pts, np.radians([0, 12, 30, 50, 75]))) in (0, 2, 4)
    True
    """
    z, th = _poses(points, angles)
    if z.size != 5:
        raise GearleverError(f"burmester_points takes exactly 5 poses, got {z.size}")
    Ca, Sa = _cofactors(z, th, (1, 2, 3))
    Cb, Sb = _cofactors(z, th, (1, 2, 4))

    def coeffs(C, S):
        c2, c3, ck = C
        a2 = np.array([c3 * np.conj(c2), -c3 * np.conj(S), 0])
        a1 = np.array([-S * np.conj(c2), abs(S) ** 2 + abs(c2) ** 2 + abs(c3) ** 2 - abs(ck) ** 2, -c2 * np.conj(S)])
        a0 = np.array([0, -S * np.conj(c3), c2 * np.conj(c3)])
        return a2, a1, a0

    a2, a1, a0 = coeffs(Ca, Sa)
    b2, b1, b0 = coeffs(Cb, Sb)
    m = npoly.polymul
    res = npoly.polysub(
        m(npoly.polysub(m(a2, b0), m(a0, b2)), npoly.polysub(m(a2, b0), m(a0, b2))),
        m(npoly.polysub(m(a2, b1), m(a1, b2)), npoly.polysub(m(a1, b0), m(a0, b1))),
    )
    res = np.trim_zeros(res, "b")
    scale = np.abs(res).max() if res.size else 0.0
    if res.size < 2 or scale == 0:
        raise GearleverError("points/angles: the five poses are degenerate (the compatibility equations vanish)")
    res = res / scale
    roots = npoly.polyroots(res)
    sols = []
    for u in roots:
        if not abs(abs(u) - 1) < 1e-4 or abs(u - 1) < 1e-7:
            continue
        fa = [npoly.polyval(u, c) for c in (a0, a1, a2)]
        gb = [npoly.polyval(u, c) for c in (b0, b1, b2)]
        best = None
        for v in npoly.polyroots(fa) if abs(fa[2]) > 0 else []:
            r = abs(npoly.polyval(v, gb))
            if best is None or r < best[0]:
                best = (r, v)
        if best is None or not abs(abs(best[1]) - 1) < 1e-4:
            continue
        b = _polish(Ca, Sa, Cb, Sb, float(np.angle(u)), float(np.angle(best[1])))
        if b is None:
            continue
        wz = _wz(z, th, 1, 2, b[0], b[1])
        if wz is None:
            continue
        W, Z = wz
        M1 = z[0] - Z
        G = M1 - W
        if not (np.isfinite(G) and np.isfinite(M1)):
            continue
        d = _dyad(z, th, G, M1)
        if any(abs(d.beta[1] - e.beta[1]) < 1e-7 and abs(d.beta[2] - e.beta[2]) < 1e-7 for e in sols):
            continue
        sols.append(d)
    sols.sort(key=lambda d: float(d.beta[1]))
    return tuple(sols)


def _polish(Ca, Sa, Cb, Sb, b2, b3, steps: int = 30):
    """Newton steps on |S - C2 u - C3 v|^2 - |Ck|^2 = 0 for both pose sets (real unknowns beta2, beta3)."""
    x = np.array([b2, b3])
    for _ in range(steps):
        u, v = np.exp(1j * x[0]), np.exp(1j * x[1])
        F, J = np.empty(2), np.empty((2, 2))
        for r, (C, S) in enumerate(((Ca, Sa), (Cb, Sb))):
            E = S - C[0] * u - C[1] * v
            F[r] = abs(E) ** 2 - abs(C[2]) ** 2
            J[r, 0] = 2 * np.real(np.conj(E) * (-1j * C[0] * u))
            J[r, 1] = 2 * np.real(np.conj(E) * (-1j * C[1] * v))
        scale = max(abs(Ca[2]) ** 2, abs(Cb[2]) ** 2, 1e-300)
        if np.abs(F).max() <= 1e-15 * scale:
            break
        try:
            dx = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            return None
        x = x + dx
    if np.abs(F).max() > 1e-9 * scale:
        return None
    return float(x[0]), float(x[1])


@dataclass(frozen=True)
class MotionSolution(Result):
    """A four-bar (crank dyad + rocker dyad) that guides the coupler through the poses, checked by the engine.

    Attributes
    ----------
    crank, rocker : Dyad
    model : dict
        Model assembled at the first pose (``O2, A`` crank dyad; ``O4, B``
        rocker dyad; ``P`` the coupler point).
    input_angle : ndarray
        Crank angle ``O2->A`` at each pose, radians from +x.
    point_error, angle_error : ndarray
        Engine coupler point distance (length) and coupler angle error (rad) at each pose.
    residual : float
        ``max(point_error, angle_error * size) / size``.
    size : float
        Largest link length.
    lengths : dict
        ``ground, crank, coupler, rocker``.
    grashof : str
    crank_turns : bool
    transmission_range : tuple
        Smallest and largest transmission angle over the crank motion through
        the poses, radians (NaN where none assembles).
    defect : str
        Empty, or the branch, order or circuit defect found.

    Examples
    --------
    >>> m = synthesize_motion([(0, 0), (1, 0.5), (2, 0.5)], np.radians([0, 20, 45]), fixed_pivots=[(0, -2), (2.5, -2)])
    >>> bool(m.best.residual < 1e-9), m.best.grashof
    (True, 'double-rocker')
    """

    crank: Dyad
    rocker: Dyad
    model: dict
    input_angle: np.ndarray
    point_error: np.ndarray
    angle_error: np.ndarray
    residual: float
    size: float
    lengths: dict
    grashof: str
    crank_turns: bool
    transmission_range: tuple
    defect: str

    def _frame_columns(self) -> dict:
        return {
            "input_angle_rad": self.input_angle,
            "point_error": self.point_error,
            "angle_error_rad": self.angle_error,
        }


@dataclass(frozen=True)
class MotionSynthesis(Result):
    """Ranked four-bars through the poses (defect-free first, full-turn crank, transmission angle, size).

    Attributes
    ----------
    points : ndarray
        ``(N, 2)`` coupler points of the poses.
    angles : ndarray
        ``(N,)`` coupler angles, radians.
    method : str
        ``"fixed pivots"``, ``"moving pivots"``, ``"burmester curves"`` or ``"burmester points"``.
    dyads : tuple of Dyad
        Every dyad found (for five poses: the Burmester pairs).
    solutions : tuple of MotionSolution
        Best first.
    evaluations : int
        Input rows solved by the mechanism engine.

    Examples
    --------
    >>> m = synthesize_motion([(0, 0), (1, 0.5), (2, 0.5)], np.radians([0, 20, 45]), fixed_pivots=[(0, -2), (2.5, -2)])
    >>> m.method, len(m.solutions)
    ('fixed pivots', 1)
    """

    points: np.ndarray
    angles: np.ndarray
    method: str
    dyads: tuple
    solutions: tuple
    evaluations: int

    @property
    def best(self) -> MotionSolution:
        return self.solutions[0]

    def _frame_columns(self) -> dict:
        s = self.solutions
        return {
            "ground_x": np.array([x.crank.ground_pivot[0] for x in s]),
            "ground_y": np.array([x.crank.ground_pivot[1] for x in s]),
            "residual": np.array([x.residual for x in s]),
            "transmission_angle_min_rad": np.array([x.transmission_range[0] for x in s]),
            "defect": np.array([x.defect for x in s], dtype=object),
        }


def _check_pair(z, th, d1: Dyad, d2: Dyad, engine: bool = True):
    """A four-bar from two dyads: defects by the closed form, residuals by the engine; None if degenerate."""
    G1, M1 = complex(*d1.ground_pivot), complex(*d1.moving_pivot)
    G2, M2 = complex(*d2.ground_pivot), complex(*d2.moving_pivot)
    d, a, b, c = abs(G2 - G1), abs(M1 - G1), abs(M2 - M1), abs(M2 - G2)
    size = max(d, a, b, c)
    if not np.isfinite(size) or min(d, a, b, c) <= 1e-9 * size:
        return None
    if size >= (d + a + b + c - size) * (1 - 1e-12):
        return None
    gam = np.angle(G2 - G1)
    alpha = th - th[0]
    Mj1 = z + np.exp(1j * alpha) * (M1 - z[0])
    Mj2 = z + np.exp(1j * alpha) * (M2 - z[0])
    phi = np.angle(Mj1 - G1) - gam  # local crank angles
    psi = np.angle(Mj2 - G2) - gam
    defect = ""
    branch = None
    for br in ("open", "crossed"):
        r = fourbar(d, a, b, c, phi, branch=br)
        ok = np.abs(np.angle(np.exp(1j * (r.theta4 - psi)))) < 1e-6
        if ok[0]:
            branch = br
            if not ok.all():
                defect = f"branch defect: pose {int(np.flatnonzero(~ok)[0]) + 1} is on the other assembly"
            break
    if branch is None:
        return None
    # order: the crank must reach the poses in order turning one way (within its arc when it rocks)
    g = grashof(d, a, b, c)
    if g.crank_rotates:
        fwd, bwd = np.mod(phi - phi[0], 2 * np.pi), np.mod(phi[0] - phi, 2 * np.pi)
    else:
        fwd = np.angle(np.exp(1j * (phi - phi[0])))
        bwd = -fwd
    if np.all(np.diff(fwd) > 0):
        sense, rel = 1.0, fwd
    elif np.all(np.diff(bwd) > 0):
        sense, rel = -1.0, bwd
    else:
        sense, rel = 0.0, fwd
        defect = defect or "order defect: the crank does not reach the poses in order turning one way"
    sweep = phi[0] + (sense or 1.0) * np.linspace(0.0, float(rel[-1]) if sense else 0.0, 181)
    rs = fourbar(d, a, b, c, sweep, branch=branch)
    if not defect and not rs.valid.all():
        bad = float(np.degrees(np.angle(np.exp(1j * (sweep[int(np.flatnonzero(~rs.valid)[0])] + gam)))))
        defect = f"circuit defect: a dead point between the poses (crank angle {bad:.6g} deg)"
    mu = transmission_angle(d, a, b, c, sweep)
    sol = dict(
        d=d, a=a, b=b, c=c, size=size, branch=branch, defect=defect, grashof=g, mu=mu, phi=phi + gam, sense=sense
    )
    return sol


def _solution(z, th, d1, d2, info, name):
    G1, M1 = complex(*d1.ground_pivot), complex(*d1.moving_pivot)
    G2, M2 = complex(*d2.ground_pivot), complex(*d2.moving_pivot)
    model = fourbar_model(_xy(G1), _xy(G2), _xy(M1), _xy(M2), _xy(z[0]), name=name)
    from gearlever.mechanism import Mechanism

    q = np.unwrap(info["phi"])
    res = Mechanism.from_dict(model).solve(q[:, None])
    P = res.point["P"]
    perr = np.abs(P[:, 0] + 1j * P[:, 1] - z)
    cang = res.angle["coupler"]
    aerr = np.abs(np.angle(np.exp(1j * ((cang - cang[0]) - (th - th[0])))))
    perr = np.where(res.closed, perr, np.inf)
    aerr = np.where(res.closed, aerr, np.inf)
    size = info["size"]
    resid = float(max(perr.max(), (aerr * size).max()) / size)
    mu = info["mu"]
    return (
        MotionSolution(
            d1,
            d2,
            model,
            q,
            perr,
            aerr,
            resid,
            size,
            {"ground": info["d"], "crank": info["a"], "coupler": info["b"], "rocker": info["c"]},
            info["grashof"].kind,
            bool(info["grashof"].crank_rotates),
            (float(np.nanmin(mu)), float(np.nanmax(mu))) if np.isfinite(mu).any() else (math.nan, math.nan),
            info["defect"],
        ),
        int(q.size),
    )


def _rank_key(s: MotionSolution, spread: float):
    mu = s.transmission_range
    worst = min(mu[0], math.pi - mu[1]) if all(map(math.isfinite, mu)) else 0.0
    return (
        bool(s.defect),
        s.residual > 1e-6,
        not s.crank_turns,
        -round(worst, 6),
        s.size / max(spread, 1e-300),
    )


def synthesize_motion(
    points,
    angles,
    *,
    fixed_pivots=None,
    moving_pivots=None,
    keep: int = 20,
    name: str = "synthesized four-bar (motion generation)",
) -> MotionSynthesis:
    """Four-bars that guide a coupler through 3, 4 or 5 poses, ranked.

    Parameters
    ----------
    points : array_like
        ``(N, 2)`` coupler point of each pose.
    angles : array_like
        ``(N,)`` coupler angle of each pose, radians (only differences matter).
    fixed_pivots, moving_pivots : pair of (x, y), optional
        Three poses only: the two ground pivots (crank first), or the two
        moving pivots at the first pose; exactly one is required.
    keep : int
        Solutions kept (best first).
    name : str
        Model name.

    Returns
    -------
    MotionSynthesis

    Notes
    -----
    Dyads by :func:`moving_pivot` / :func:`fixed_pivot` (3 poses), along the
    centre-point curve (:func:`burmester_curves`, 4 poses: :data:`CURVE_DYADS`
    per branch, every pair tried) or the Burmester points
    (:func:`burmester_points`, 5 poses, every pair).  Each pair is a four-bar
    (the dyad listed first is the crank); branch, order and circuit defects
    are found with the closed form of :mod:`gearlever.loops.fourbar` (the
    poses must lie on one assembly, in order while the crank turns one way,
    with no dead point between them); the residuals come from the mechanism
    engine solving the written model at the poses.  Ranking: defect-free
    first, then a crank that turns fully, then the larger worst transmission
    angle, then the smaller size.

    Examples
    --------
    >>> pts = [(0, 0), (1, 0.5), (2, 0.5)]
    >>> r = synthesize_motion(pts, np.radians([0, 20, 45]), fixed_pivots=[(0, -2), (2.5, -2)])
    >>> r.method, r.best.residual < 1e-9
    ('fixed pivots', True)
    """
    z, th = _poses(points, angles)
    n = z.size
    if isinstance(keep, bool) or not isinstance(keep, (int, np.integer)) or not 1 <= keep <= 1000:
        raise GearleverError(f"keep must be an integer from 1 to 1000, got {keep!r}")
    if n == 3:
        if (fixed_pivots is None) == (moving_pivots is None):
            raise GearleverError("three poses need exactly one of fixed_pivots or moving_pivots (two pivots each)")
        given = fixed_pivots if fixed_pivots is not None else moving_pivots
        what = "fixed_pivots" if fixed_pivots is not None else "moving_pivots"
        try:
            p1, p2 = (_pair(what, p) for p in given)
        except (TypeError, ValueError):
            raise GearleverError(f"{what} must be two pivots ((x, y), (x, y))") from None
        if fixed_pivots is not None:
            dyads = (moving_pivot(z_pts(z), th, p1), moving_pivot(z_pts(z), th, p2))
            method = "fixed pivots"
        else:
            dyads = (fixed_pivot(z_pts(z), th, p1), fixed_pivot(z_pts(z), th, p2))
            method = "moving pivots"
        pairs = [(0, 1)]
    else:
        if fixed_pivots is not None or moving_pivots is not None:
            raise GearleverError(f"fixed_pivots/moving_pivots are for three poses; {n} poses fix the dyads")
        if n == 4:
            curves = burmester_curves(z_pts(z), th, samples=CURVE_DYADS)
            dyads = []
            for i in range(curves.beta2.size):
                for k in range(2):
                    if np.all(np.isfinite(curves.center[i, k])):
                        dyads.append(_dyad(z, th, complex(*curves.center[i, k]), complex(*curves.circle[i, k])))
            dyads = tuple(dyads)
            method = "burmester curves"
        else:
            dyads = burmester_points(z_pts(z), th)
            method = "burmester points"
        pairs = [(i, j) for i in range(len(dyads)) for j in range(len(dyads)) if i != j]
    spread = float(max(abs(a - b) for a, b in itertools.combinations(z, 2)))
    cands = []
    for i, j in pairs:
        info = _check_pair(z, th, dyads[i], dyads[j])
        if info is not None:
            cands.append((i, j, info))
    if not cands:
        raise GearleverError(
            f"no four-bar found through these {n} poses ({len(dyads)} dyad(s)); "
            + ("choose other pivots" if n == 3 else "the poses admit no real pair of dyads that assembles")
        )

    def pre(c):
        info = c[2]
        mu = info["mu"]
        worst = float(np.nanmin(np.minimum(mu, np.pi - mu))) if np.isfinite(mu).any() else 0.0
        return (bool(info["defect"]), not info["grashof"].crank_rotates, -worst, info["size"] / max(spread, 1e-300))

    cands.sort(key=pre)
    sols, evals = [], 0
    for i, j, info in cands[: max(keep, 1) * 2]:
        s, e = _solution(z, th, dyads[i], dyads[j], info, name)
        sols.append(s)
        evals += e
    sols.sort(key=lambda s: _rank_key(s, spread))
    return MotionSynthesis(np.column_stack([z.real, z.imag]), th, method, tuple(dyads), tuple(sols[:keep]), evals)


def z_pts(z):
    """Complex points as an ``(N, 2)`` array."""
    return np.column_stack([np.real(z), np.imag(z)])


def _example_poses(n: int) -> tuple:
    """``(points, angles)`` of ``n`` coupler poses of a known four-bar (O2 (0, 0), O4 (4, 0), A (1, 0.3),
    B (4.5, 2.8), coupler point (2, 3)) over 1.6 rad of crank turn."""
    o4, a, b, p = np.array([4.0, 0.0]), np.array([1.0, 0.3]), np.array([4.5, 2.8]), np.array([2.0, 3.0])
    phi = math.atan2(a[1], a[0]) + np.linspace(0.0, 1.6, n)
    lengths = (4.0, float(np.hypot(*a)), float(np.hypot(*(b - a))), float(np.hypot(*(b - o4))))
    th3 = fourbar(*lengths, phi, branch="open").theta3
    gamma = math.atan2(*(p - a)[::-1]) - math.atan2(*(b - a)[::-1])
    r = float(np.hypot(*(p - a)))
    pts = np.column_stack([lengths[1] * np.cos(phi), lengths[1] * np.sin(phi)])
    pts += r * np.column_stack([np.cos(th3 + gamma), np.sin(th3 + gamma)])
    return pts, th3


def _example(n: int):
    def example() -> tuple:
        pts, ang = _example_poses(n)
        return (pts, ang), ({"fixed_pivots": [(0.0, 0.0), (4.0, 0.0)]} if n == 3 else {})

    return example


for _n, _how in [
    (3, "given the two fixed (or moving) pivots: the other two in closed form"),
    (4, "along the centre-point curve (Burmester curves)"),
    (5, "on the Burmester points"),
]:
    register(
        Kind(
            "motion",
            f"{_n}-poses",
            f"four-bar guiding a coupler through {_n} poses, {_how}",
            "gearlever.synthesis.motion:synthesize_motion",
            kind_arg=None,
            searched=False,
            order=_n,
            example=_example(_n),
        )
    )
