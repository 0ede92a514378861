"""Path generation by a four-bar: the coupler point of a Grashof crank-rocker passes through target points.

The problem (the formulation of Cabrera, Simon and Prado, "Optimal synthesis
of mechanisms with genetic algorithms", Mech. Mach. Theory 37 (2002)
1165-1177, eqs. 1-9): find the crank pivot ``O2 = (x0, y0)``, the ground
line angle ``theta0``, the link lengths ground ``r1``, crank ``r2``, coupler
``r3``, rocker ``r4``, the coupler point ``(cx, cy)`` in the coupler frame
(along A->B and its normal) and the assembly branch that minimize
``f = sum_i |P(phi_i) - T_i|^2``
over the targets ``T_i``, with ``phi_i`` the crank angle from the ground
line at target ``i``:

- timing ``"absolute"``: ``phi_i`` given;
- timing ``"relative"``: ``phi_i = phi_1 + (given_i - given_1)``, ``phi_1`` free;
- timing ``"none"``: ``phi_i`` free; in the global search they are the
  best-matching samples of the coupler curve in counter-clockwise order
  (an exact dynamic program over the sampled curve, every cyclic start),
  then free variables of the polish; a polish that breaks the order is
  discarded.

Constraints are exact, by construction (never penalties):

- full rotation of the crank (Grashof crank-rocker, the crank the shortest
  link): the search samples ``r1, r3, r4`` in the length range and the crank
  as a fraction ``u2`` of the room left,
  ``r2 = lo + u2 (r2max (1 - margin) - lo)``,
  ``r2max = min(r1, r3, r4, r1 + r3 + r4 - 2 max(r1, r3, r4))``,
  so that ``r2 < min`` and ``s + l < p + q`` hold for every ``u2`` in
  ``[0, 1]``; a candidate whose room is empty (``r2max <= lo``) is
  rejected before evaluation;
- the loop then closes at every crank angle on the one branch chosen
  (the closed form of :mod:`gearlever.loops.fourbar`, branch sign fixed);
- the targets are reached in their order as the crank turns
  counter-clockwise (timing given as increasing angles; without timing,
  the order is enforced by the matching);
- the length range bounds all four links, the coordinate range bounds
  ``x0, y0, cx, cy`` (the sets of the published benchmarks).

This module holds the four-bar kind of the registry
(:mod:`gearlever.synthesis.path_kinds`): its problem
(:class:`FourBarPathProblem`, also the base of the other kinds' problems,
with the closed forms :func:`_dyad` and :func:`_coupler` they share), its
result builder and its model writer; the search is the driver's,
:func:`gearlever.synthesis.path.synthesize_path`.

Pure numpy and scipy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis.path_kinds import PathKind, PathSynthesis, register

__all__ = ["FourBarPathProblem", "FourBarKind", "fourbar_result"]

#: Relative room kept below Grashof's limit ``s + l = p + q`` (a change point).
GRASHOF_MARGIN = 1e-6
#: Samples of the coupler curve per crank turn in the matching without timing.
CURVE_SAMPLES = 72
#: Most target points.
MAX_TARGETS = 1000
#: Largest target coordinate (and range bound) in size: the written model's coordinates stay within
#: the model file's cap (:data:`gearlever.mechanism.model.MAX_COORDINATE`, 1e12) with room for the
#: default ranges (3 times the targets' extent around them).
MAX_TARGET_COORDINATE = 1e11
#: A lower length bound of 0 (``length_range=(0, hi)``: any positive length) is this fraction of the
#: problem's size (the larger of ``hi`` and the coordinate span): ten times above the shortest link a
#: model file accepts (1e-6 of the model's size, :data:`gearlever.mechanism.model.MAX_SCALE_RATIO`).
ZERO_LENGTH_FRACTION = 1e-5

TIMINGS = ("none", "relative", "absolute")


def _dyad(Ax, Ay, Dx, Dy, r3, r4, cx, cy, sigma, jac=False):
    """Point ``P`` (..., 2) of the link A-C of an RR dyad closing ``A`` to ``A + D`` (links r3 at A, r4 at A + D).

    ``P = A + cx e3 + cy e3_perp`` with ``e3`` the unit vector A->C on branch
    ``sigma``.  With ``jac`` also a function ``d(dAx, dAy, dDx, dDy, dr3, dr4)``
    giving ``dP`` (..., 2) for a change of A, D and the lengths (``cx, cy``
    fixed), and ``e3``, ``e3_perp`` (the derivatives in ``cx``, ``cy``).
    """
    f2 = Dx * Dx + Dy * Dy
    f = np.sqrt(f2)
    cg = np.clip((r3 * r3 + f2 - r4 * r4) / (2.0 * r3 * f), -1.0, 1.0)
    sga = np.sqrt(1.0 - cg * cg)
    sg = sigma * sga
    c3 = (Dx * cg - Dy * sg) / f
    s3 = (Dy * cg + Dx * sg) / f
    Px = Ax + cx * c3 - cy * s3
    Py = Ay + cx * s3 + cy * c3
    P = np.stack(np.broadcast_arrays(Px, Py), axis=-1)
    if not jac:
        return P
    Qx, Qy = -(Py - Ay), Px - Ax  # dP/dtheta3 = J (P - A)
    cg_f = 1.0 / (2.0 * r3) - (r3 * r3 - r4 * r4) / (2.0 * r3 * f2)
    cg_r3 = 1.0 / (2.0 * f) - (f2 - r4 * r4) / (2.0 * r3 * r3 * f)
    cg_r4 = -r4 / (r3 * f)

    def d(dAx, dAy, dDx, dDy, dr3=0.0, dr4=0.0):
        dpsi = (Dx * dDy - Dy * dDx) / f2
        df = (Dx * dDx + Dy * dDy) / f
        dcg = cg_f * df + cg_r3 * dr3 + cg_r4 * dr4
        # at a toggle (sin(gamma) = 0, only at the limit of closure) the derivative is taken as 0
        dth3 = dpsi - sigma * np.where(sga > 0, dcg / np.where(sga > 0, sga, 1.0), 0.0)
        return np.stack(np.broadcast_arrays(dAx + Qx * dth3, dAy + Qy * dth3), axis=-1)

    e3 = np.stack(np.broadcast_arrays(c3, s3), axis=-1)
    n3 = np.stack(np.broadcast_arrays(-s3, c3), axis=-1)
    return P, d, e3, n3


def _coupler(x0, y0, th0, r1, r2, r3, r4, cx, cy, phi, sigma, jac=False):
    """Coupler point P (..., 2) of four-bars at crank angles ``phi`` from the ground line (broadcast).

    With ``jac`` also the derivatives ``dP/dv`` for v in
    ``x0, y0, th0, r1, r2, r3, r4, cx, cy, phi`` (a dict of (..., 2)).
    """
    al = th0 + phi
    ca, sa = np.cos(al), np.sin(al)
    c0, s0 = np.cos(th0), np.sin(th0)
    Ax, Ay = x0 + r2 * ca, y0 + r2 * sa
    Dx, Dy = r1 * c0 - r2 * ca, r1 * s0 - r2 * sa
    if not jac:
        return _dyad(Ax, Ay, Dx, Dy, r3, r4, cx, cy, sigma)
    P, d, e3, n3 = _dyad(Ax, Ay, Dx, Dy, r3, r4, cx, cy, sigma, jac=True)
    out = {
        "x0": d(1.0, 0.0, 0.0, 0.0),
        "y0": d(0.0, 1.0, 0.0, 0.0),
        "th0": d(-r2 * sa, r2 * ca, -Dy, Dx),
        "r1": d(0.0, 0.0, c0, s0),
        "r2": d(ca, sa, -ca, -sa),
        "r3": d(0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
        "r4": d(0.0, 0.0, 0.0, 0.0, 0.0, 1.0),
        "cx": e3,
        "cy": n3,
        "phi": d(-r2 * sa, r2 * ca, r2 * sa, -r2 * ca),
    }
    return P, out


def _monotone_match(D, window=None):
    """Cheapest counter-clockwise matching of targets to curve samples, every cyclic start.

    ``D`` (n, N, L): squared distance of target i to sample m of a closed
    curve of L samples.  Returns the cost (n,) of the best assignment
    ``m_1 <= m_2 <= ... <= m_N`` within ``window`` consecutive samples (one
    crank turn; default L) and, per candidate, the start of the window.
    Windows start at every ``window // N``-th sample: the widest gap of an
    assignment within a turn is at least that long, so a start falls in it.
    """
    n, N, L = D.shape
    M = L if window is None else window
    step = max(1, M // N)
    cuts = np.arange(0, L, step)
    best = np.full(n, np.inf)
    best_cut = np.zeros(n, dtype=int)
    ar = np.arange(M)
    for s in cuts:
        Dw = D[:, :, (s + ar) % L]
        g = Dw[:, 0, :]
        for i in range(1, N):
            g = Dw[:, i, :] + np.minimum.accumulate(g, axis=1)
        c = g.min(axis=1)
        better = c < best
        best = np.where(better, c, best)
        best_cut = np.where(better, s, best_cut)
    return best, best_cut


def _backtrack(Dw):
    """Sample indices (N,) of the cheapest monotone matching in one window ``Dw`` (N, M)."""
    N, M = Dw.shape
    G = np.empty((N, M))
    G[0] = Dw[0]
    for i in range(1, N):
        G[i] = Dw[i] + np.minimum.accumulate(G[i - 1])
    idx = np.empty(N, dtype=int)
    idx[-1] = int(np.argmin(G[-1]))
    for i in range(N - 2, -1, -1):
        idx[i] = int(np.argmin(G[i, : idx[i + 1] + 1]))
    return idx


class FourBarPathProblem:
    """A four-bar path-generation problem: design vector, exact constraints, batched objective.

    Parameters
    ----------
    targets : array_like (N, 2)
        Target points, in the order the coupler point must reach them.
    timing : {"none", "relative", "absolute"}
    angles : array_like (N,), optional
        Crank angles at the targets, radians (needed with timing):
        increments for ``"relative"``, angles from the ground line for
        ``"absolute"``; strictly increasing, spanning less than a turn.
    pivot : pair of float, optional
        Fixed crank pivot ``O2``.
    ground_angle : float, optional
        Fixed ground line angle ``theta0`` (radians).
    length_range, coord_range : pair of float
        Bounds of every link length, and of ``x0, y0, cx, cy``.  A lower
        length bound of 0 (published constraint sets write it) means any
        positive length: it becomes :data:`ZERO_LENGTH_FRACTION` of the
        problem's size, the shortest link a model file can hold with margin.
    weights : array_like (N,), optional
        Positive weight of each target's squared distance in the objective
        (default 1 each); a closed path's first target, met again one crank
        turn later, counts twice.
    min_transmission : float, optional
        Smallest transmission angle allowed over the whole crank turn,
        radians in ``[0, pi/2)``: every candidate whose angle between
        coupler and rocker leaves ``[mu, pi - mu]`` is infeasible (an exact
        constraint, like buildability).

    Notes
    -----
    Search vector ``z`` (:attr:`names`): ``x0, y0`` (unless the pivot is
    fixed), ``theta0`` (unless fixed), ``r1, r3, r4, u2, cx, cy``,
    ``phi1`` (relative timing), ``branch`` (its sign; search only).  The
    polish vector ``w`` drops ``branch`` and, without timing, appends the N
    crank angles.  See the module docstring for the equations.

    Examples
    --------
    >>> pb = FourBarPathProblem([[0, 0], [1, 0], [2, 1]], "none", length_range=(0.5, 5), coord_range=(-5, 5))
    >>> pb.names
    ('x0', 'y0', 'theta0', 'r1', 'r3', 'r4', 'u2', 'cx', 'cy', 'branch')
    """

    def __init__(
        self,
        targets,
        timing="none",
        angles=None,
        *,
        pivot=None,
        ground_angle=None,
        length_range=(1.0, 10.0),
        coord_range=(-10.0, 10.0),
        weights=None,
        min_transmission=None,
    ):
        T = _targets(targets)
        if timing not in TIMINGS:
            raise GearleverError(f"timing must be one of {', '.join(TIMINGS)}, got {timing!r}")
        self.targets = T
        self.N = T.shape[0]
        self.weights = np.ones(self.N)
        if weights is not None:
            wt = np.asarray(weights, dtype=float).reshape(-1)
            if wt.size != self.N or not np.all(np.isfinite(wt)) or np.any(wt <= 0):
                raise GearleverError(f"weights must be {self.N} finite positive numbers, one per target")
            self.weights = wt
        self._sqrt_w = np.repeat(np.sqrt(self.weights), 2)
        mt = 0.0 if min_transmission is None else float(min_transmission)
        if not (math.isfinite(mt) and 0.0 <= mt < math.pi / 2):
            raise GearleverError(f"min_transmission must be in [0, pi/2) radians, got {min_transmission!r}")
        self.min_transmission = mt
        self.timing = timing
        self.angles = None
        if timing != "none":
            if angles is None:
                raise GearleverError(f"angles must be given with timing {timing!r} (one crank angle per target)")
            a = np.asarray(angles, dtype=float).reshape(-1)
            if a.size != self.N or not np.all(np.isfinite(a)):
                raise GearleverError(f"angles must be {self.N} finite crank angles, one per target")
            if np.any(np.diff(a) <= 0):
                i = int(np.argmax(np.diff(a) <= 0)) + 1
                raise GearleverError(
                    f"angles must increase strictly (counter-clockwise crank): angle {i + 1} "
                    f"({math.degrees(a[i]):.6g} deg) is not greater than angle {i} ({math.degrees(a[i - 1]):.6g} deg)"
                )
            if a[-1] - a[0] >= 2 * math.pi:
                raise GearleverError(
                    "angles must span less than one turn (360 deg) from the first target to the last, "
                    f"got {math.degrees(a[-1] - a[0]):.6g} deg"
                )
            self.angles = a
        lo, hi = (float(v) for v in length_range)
        if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi):
            raise GearleverError(f"length_range must be 0 <= LO < HI, got {length_range!r}")
        clo, chi = (float(v) for v in coord_range)
        if not (math.isfinite(clo) and math.isfinite(chi) and clo < chi):
            raise GearleverError(f"coord_range must be LO < HI, got {coord_range!r}")
        for name, v in (("length_range", hi), ("coord_range", max(abs(clo), abs(chi)))):
            if v > 10 * MAX_TARGET_COORDINATE:
                raise GearleverError(
                    f"{name} must stay within {10 * MAX_TARGET_COORDINATE:g} in size (the model file's cap on "
                    f"coordinates), got {v:g}"
                )
        if lo == 0.0:  # no lower bound: any positive length the model file can hold
            lo = ZERO_LENGTH_FRACTION * max(hi, chi - clo)
            if not lo < hi:  # pragma: no cover - hi is then below 1e-5 of the coordinate span
                raise GearleverError(f"length_range: HI {hi:g} is too small for the coordinate range {coord_range!r}")
        self.length_range = (lo, hi)
        self.coord_range = (clo, chi)
        self.pivot = None
        if pivot is not None:
            p = np.asarray(pivot, dtype=float).reshape(-1)
            if p.size != 2 or not np.all(np.isfinite(p)):
                raise GearleverError(f"pivot must be a pair of finite numbers, got {pivot!r}")
            if np.any(p < clo) or np.any(p > chi):
                raise GearleverError(f"pivot {p.tolist()} must lie within coord_range [{clo:g}, {chi:g}]")
            self.pivot = p
        self.ground_angle = None
        if ground_angle is not None:
            g = float(ground_angle)
            if not math.isfinite(g):
                raise GearleverError(f"ground_angle must be finite, got {ground_angle!r}")
            self.ground_angle = g
        names, blo, bhi = [], [], []

        def add(n, a, b):
            names.append(n)
            blo.append(a)
            bhi.append(b)

        if self.pivot is None:
            add("x0", clo, chi)
            add("y0", clo, chi)
        if self.ground_angle is None:
            add("theta0", 0.0, 2 * math.pi)
        for n in ("r1", "r3", "r4"):
            add(n, lo, hi)
        add("u2", 0.0, 1.0)
        add("cx", clo, chi)
        add("cy", clo, chi)
        if timing == "relative":
            add("phi1", 0.0, 2 * math.pi)
        add("branch", -1.0, 1.0)
        self.names = tuple(names)
        self.lo = np.array(blo)
        self.hi = np.array(bhi)
        self._col = {n: i for i, n in enumerate(names)}
        self.d = len(names)
        self.evaluations = 0

    # ---------------------------------------------------------------- parameters
    def _get(self, Z, name, fixed):
        i = self._col.get(name)
        return Z[..., i] if i is not None else np.full(Z.shape[:-1], fixed)

    def params(self, Z):
        """Physical parameters of candidates ``Z`` (n, d or d-1): a dict of (n,) and the feasibility mask.

        Keys ``x0, y0, th0, r1, r2, r3, r4, cx, cy`` and ``sigma`` (+1 open, -1 crossed, when
        ``branch`` is in ``Z``); ``ok`` is False where no crank fits (``r2max <= lo``).
        """
        Z = np.asarray(Z, dtype=float)
        px, py = self.pivot if self.pivot is not None else (0.0, 0.0)
        p = {
            "x0": self._get(Z, "x0", px),
            "y0": self._get(Z, "y0", py),
            "th0": self._get(Z, "theta0", self.ground_angle if self.ground_angle is not None else 0.0),
            "r1": Z[..., self._col["r1"]],
            "r3": Z[..., self._col["r3"]],
            "r4": Z[..., self._col["r4"]],
            "cx": Z[..., self._col["cx"]],
            "cy": Z[..., self._col["cy"]],
        }
        r2, ok = self._crank(p["r1"], p["r3"], p["r4"], Z[..., self._col["u2"]])
        p["r2"] = r2
        if Z.shape[-1] > self._col["branch"]:
            p["sigma"] = np.where(Z[..., self._col["branch"]] >= 0, 1.0, -1.0)
        return p, ok

    def _crank(self, r1, r3, r4, u2, grad=False):
        lo = self.length_range[0]
        R = np.stack([r1, r3, r4], axis=-1)
        mn = R.min(axis=-1)
        mx = R.max(axis=-1)
        g = r1 + r3 + r4 - 2.0 * mx
        room = np.minimum(mn, g) * (1.0 - GRASHOF_MARGIN)
        ok = room > lo
        r2 = lo + u2 * (room - lo)
        if not grad:
            return r2, ok
        # d room / d(r1, r3, r4): the active branch of the min (ties: first)
        use_mn = mn <= g
        dmn = np.eye(3)[np.argmin(R, axis=-1)]
        dg = 1.0 - 2.0 * np.eye(3)[np.argmax(R, axis=-1)]
        droom = np.where(use_mn[..., None], dmn, dg) * (1.0 - GRASHOF_MARGIN)
        return r2, ok, u2[..., None] * droom, room - lo

    def phis(self, Z):
        """Crank angles from the ground line at the targets (n, N) for timed problems."""
        if self.timing == "absolute":
            return np.broadcast_to(self.angles, Z.shape[:-1] + (self.N,))
        rel = self.angles - self.angles[0]
        return Z[..., self._col["phi1"], None] + rel

    # ---------------------------------------------------------------- kinematics hooks
    def mode_of(self, Z):
        """Discrete part of candidates ``Z`` (the branch sign, +1 open, -1 crossed), (n,)."""
        return np.where(np.asarray(Z)[..., self._col["branch"]] >= 0, 1.0, -1.0)

    def feasible(self, Z):
        """Mask (n,) of candidates that are buildable (the crank fits: ``r2max > lo``) and transmit.

        Notes
        -----
        With :attr:`min_transmission` ``mu_min``, the transmission angle
        ``mu`` (``cos mu = (r3^2 + r4^2 - f^2) / (2 r3 r4)``, ``f = |O4 - A|``,
        Norton, *Design of Machinery*, eq. 3.3a) of a crank-rocker is
        monotone in the crank angle between its extremes at the crank angles
        0 and pi (``f = r1 - r2`` and ``r1 + r2``), so the whole turn keeps
        ``mu_min <= mu <= pi - mu_min`` exactly when both extremes do.
        """
        p, ok = self.params(Z)
        if self.min_transmission > 0.0:
            c = math.cos(self.min_transmission)
            r1, r2, r3, r4 = p["r1"], p["r2"], p["r3"], p["r4"]
            s2, den = r3 * r3 + r4 * r4, 2.0 * r3 * r4
            for f in (r1 - r2, r1 + r2):
                ok = ok & (np.abs((s2 - f * f) / den) <= c)
        return ok

    def _pts(self, Z, phi, mode, jac=False):
        """Coupler points (n, m, 2) of candidates ``Z`` (n, d) at crank angles ``phi`` (n, m).

        With ``jac`` also ``dP/dv`` (n, m, 2) for every search name but ``branch``
        (``phi1`` and the angles as ``"phi"``).
        """
        p, _ = self.params(Z)
        args = [p[k][:, None] for k in ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy")]
        sig = np.asarray(mode, dtype=float).reshape(-1, 1)
        if not jac:
            return _coupler(*args, phi, sig)
        P, dP = _coupler(*args, phi, sig, jac=True)
        _, _, droom, span = self._crank(p["r1"], p["r3"], p["r4"], Z[:, self._col["u2"]], grad=True)
        out = {"phi": dP["phi"]}
        for n in self.names:
            if n in ("x0", "y0", "cx", "cy"):
                out[n] = dP[n]
            elif n == "theta0":
                out[n] = dP["th0"]
            elif n in ("r1", "r3", "r4"):
                j = ("r1", "r3", "r4").index(n)
                out[n] = dP[n] + dP["r2"] * droom[:, None, j, None]
            elif n == "u2":
                out[n] = dP["r2"] * span[:, None, None]
        return P, out

    #: Crank turns after which every candidate's motion repeats (the sampled closed curve).
    turns = 1

    def _grid(self):
        """Crank angles sampling the closed curve: CURVE_SAMPLES per turn over :attr:`turns` turns."""
        return np.arange(CURVE_SAMPLES * self.turns) * (2 * math.pi / CURVE_SAMPLES)

    # ---------------------------------------------------------------- objective
    def objective(self, Z):
        """Sum of squared target distances of candidates ``Z`` (n, d); ``inf`` where infeasible."""
        Z = np.atleast_2d(np.asarray(Z, dtype=float))
        self.evaluations += Z.shape[0]
        ok = self.feasible(Z)
        out = np.full(Z.shape[0], np.inf)
        if not ok.any():
            return out
        Zk = Z[ok]
        mode = self.mode_of(Zk)
        if self.timing == "none":
            grid = self._grid()
            P = self._pts(Zk, np.broadcast_to(grid, (Zk.shape[0], grid.size)), mode)
            diff = self.targets[None, :, None, :] - P[:, None, :, :]
            D = np.einsum("nimk,nimk->nim", diff, diff) * self.weights[None, :, None]
            cost, _ = _monotone_match(D, CURVE_SAMPLES)
        else:
            P = self._pts(Zk, self.phis(Zk), mode)
            diff = P - self.targets
            cost = np.einsum("nik,nik,i->n", diff, diff, self.weights)
        out[ok] = cost
        return out

    def sample(self, rng, m):
        """``m`` uniform candidates in the search box."""
        return self.lo + rng.random((m, self.d)) * (self.hi - self.lo)

    # ---------------------------------------------------------------- polish
    def start_angles(self, z):
        """Crank angles (N,) at the targets of search vector ``z`` (the matching without timing)."""
        z = np.asarray(z, dtype=float)
        if self.timing != "none":
            return np.asarray(self.phis(z[None, :])[0], dtype=float)
        grid = self._grid()
        P = self._pts(z[None, :], grid[None, :], self.mode_of(z[None, :]))
        diff = self.targets[None, :, None, :] - P[:, None, :, :]
        D = np.einsum("nimk,nimk->nim", diff, diff) * self.weights[None, :, None]
        M, L = CURVE_SAMPLES, grid.size
        _, cut = _monotone_match(D, M)
        win = (cut[0] + np.arange(M)) % L
        idx = _backtrack(D[0][:, win])
        return grid[0] + (cut[0] + idx) * (2 * math.pi / M)

    def to_w(self, z):
        """Polish vector of search vector ``z``: ``z`` without ``branch`` (+ the N angles without timing)."""
        z = np.asarray(z, dtype=float)
        w = np.delete(z, self._col["branch"])
        if self.timing == "none":
            w = np.concatenate([w, self.start_angles(z)])
        return w

    def _split(self, w, mode=1.0):
        nb = self.d - 1
        Z = np.concatenate([w[:nb], [mode]])  # branch column: the discrete mode, kept out of the polish
        if self.timing == "none":
            return Z, w[nb:]
        return Z, np.asarray(self.phis(Z[None, :])[0], dtype=float)

    def points(self, w, mode):
        """Coupler point (N, 2) at the targets' crank angles for polish vector ``w`` and discrete ``mode``."""
        Z, phi = self._split(np.asarray(w, dtype=float), mode)
        return self._pts(Z[None, :], phi[None, :], np.array([mode]))[0]

    def residual(self, w, mode):
        """Weighted residual ``sqrt(w_i) (P_i - T_i)`` flattened (2N,) of polish vector ``w``."""
        self.evaluations += 1
        return (self.points(w, mode) - self.targets).reshape(-1) * self._sqrt_w

    def jacobian(self, w, mode):
        """Analytic Jacobian (2N, len(w)) of :meth:`residual` (chain rule through ``r2(r1, r3, r4, u2)``).

        Notes
        -----
        The coupler angle ``theta3 = arg(D) + sigma gamma`` with ``D = O4 - A``
        and ``cos(gamma) = (r3^2 + |D|^2 - r4^2) / (2 r3 |D|)`` (the closed
        form of :func:`gearlever.loops.fourbar`); its differential
        ``d theta3 = (Dx dDy - Dy dDx)/|D|^2 - sigma d cos(gamma) / sin(gamma)``
        and ``dP = dA + J (P - A) d theta3 + e3 d cx + e3_perp d cy`` give every
        column.
        """
        Z, phi = self._split(np.asarray(w, dtype=float), mode)
        _, dP = self._pts(Z[None, :], phi[None, :], np.array([mode]), jac=True)
        cols = [(dP["phi"] if n == "phi1" else dP[n])[0].reshape(-1) for n in self.names[:-1]]
        J = np.stack(cols, axis=1)
        if self.timing == "none":
            Jphi = np.zeros((self.N, 2, self.N))
            Jphi[np.arange(self.N), :, np.arange(self.N)] = dP["phi"][0]
            J = np.concatenate([J, Jphi.reshape(2 * self.N, self.N)], axis=1)
        return J * self._sqrt_w[:, None]

    def polish_bounds(self):
        nb = self.d - 1
        lo, hi = self.lo[:nb].copy(), self.hi[:nb].copy()
        if self.timing == "relative":
            i = self._col["phi1"]
            lo[i], hi[i] = -np.inf, np.inf
        if self.timing == "none":
            lo = np.concatenate([lo, np.full(self.N, -np.inf)])
            hi = np.concatenate([hi, np.full(self.N, np.inf)])
        return lo, hi

    def in_order(self, w):
        """True if the crank angles of ``w`` reach the targets counter-clockwise within one turn."""
        _, phi = self._split(np.asarray(w, dtype=float))
        inc = np.mod(np.diff(phi), 2 * math.pi)
        return bool(inc.sum() < 2 * math.pi * (1 - 1e-12))

    def feasible_w(self, w, mode=1.0):
        """The polish vector meets every constraint (bounds, buildability, order)."""
        w = np.asarray(w, dtype=float)
        lo, hi = self.polish_bounds()
        if np.any(w < lo) or np.any(w > hi) or not np.all(np.isfinite(w)):
            return False
        Z, _ = self._split(w, mode)
        return bool(self.feasible(Z[None, :])[0]) and self.in_order(w)

    def polish(self, w, sigma):
        """Local least squares from ``w`` (analytic Jacobian, trust region in the box); returns ``(w, f)``.

        A polished point that leaves the feasible set (an active transmission
        or Grashof constraint) is pulled back along the step by bisection to
        the last feasible point that still improves.
        """
        from scipy.optimize import least_squares

        lo, hi = self.polish_bounds()
        w0 = np.clip(np.asarray(w, dtype=float), lo, hi)
        f0 = float(np.sum(self.residual(w0, sigma) ** 2))
        try:
            sol = least_squares(
                self.residual,
                w0,
                jac=self.jacobian,
                bounds=(lo, hi),
                args=(sigma,),
                method="trf",
                x_scale="jac",
                xtol=1e-15,
                ftol=1e-15,
                gtol=1e-15,
                max_nfev=1000,
            )
            w1 = sol.x
            f1 = float(np.sum(self.residual(w1, sigma) ** 2))
        except (ValueError, np.linalg.LinAlgError):
            return w0, f0
        if not f1 < f0:
            return w0, f0
        if self.feasible_w(w1, sigma):
            return w1, f1
        best, fb, t_in, t_out = w0, f0, 0.0, 1.0
        for _ in range(40):  # bisection on the segment w0 -> w1 for the constraint boundary
            t = 0.5 * (t_in + t_out)
            wt = w0 + t * (w1 - w0)
            if self.feasible_w(wt, sigma):
                t_in = t
                ft = float(np.sum(self.residual(wt, sigma) ** 2))
                if ft < fb:
                    best, fb = wt, ft
            else:
                t_out = t
        return best, fb


def fourbar_result(pb: FourBarPathProblem, w, sigma, evals, seed, starts, seconds) -> PathSynthesis:
    """The :class:`~gearlever.synthesis.path_kinds.PathSynthesis` of a polished four-bar (branch ``sigma``)."""
    from gearlever.loops import grashof, transmission_angle

    Z, phi = pb._split(np.asarray(w, dtype=float))
    p, ok = pb.params(Z[None, :])
    p = {k: float(v[0]) for k, v in p.items() if k != "sigma"}
    p["sigma"] = float(sigma)
    args = [p[k] for k in ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy")]
    traced = _coupler(*args, phi, sigma)
    err = np.hypot(*(traced - pb.targets).T)
    # unwrap the crank angles counter-clockwise from the first target
    inc = np.concatenate([[0.0], np.cumsum(np.mod(np.diff(phi), 2 * math.pi))])
    crank = phi[0] + inc
    th0 = p["th0"]
    a1 = math.atan2(math.sin(th0 + phi[0]), math.cos(th0 + phi[0]))
    O2 = np.array([p["x0"], p["y0"]])
    O4 = O2 + p["r1"] * np.array([math.cos(th0), math.sin(th0)])
    A = O2 + p["r2"] * np.array([math.cos(a1), math.sin(a1)])
    # B from the coupler direction at the first target
    al = th0 + phi[0]
    Dx, Dy = p["r1"] * math.cos(th0) - p["r2"] * math.cos(al), p["r1"] * math.sin(th0) - p["r2"] * math.sin(al)
    f = math.hypot(Dx, Dy)
    cg = max(-1.0, min(1.0, (p["r3"] ** 2 + f * f - p["r4"] ** 2) / (2 * p["r3"] * f)))
    sg = sigma * math.sqrt(1 - cg * cg)
    c3, s3 = (Dx * cg - Dy * sg) / f, (Dy * cg + Dx * sg) / f
    B = A + p["r3"] * np.array([c3, s3])
    P = traced[0]
    links = {"ground": p["r1"], "crank": p["r2"], "coupler": p["r3"], "rocker": p["r4"]}
    lk = (p["r1"], p["r2"], p["r3"], p["r4"])
    gk = grashof(*lk).kind
    mu = transmission_angle(*lk, np.linspace(0.0, 2 * math.pi, 721))
    feasible = bool(ok[0]) and pb.feasible_w(w, sigma) and gk == "crank-rocker"
    return PathSynthesis(
        kind="fourbar",
        target=pb.targets.copy(),
        achieved=traced,
        error=err,
        objective=float(np.sum(err**2)),
        crank_angles=crank,
        input_angles=a1 + inc,
        points={"O2": O2.tolist(), "O4": O4.tolist(), "A": A.tolist(), "B": B.tolist(), "P": P.tolist()},
        links=links,
        branch="open" if sigma > 0 else "crossed",
        grashof=gk,
        transmission_range=(float(np.nanmin(mu)), float(np.nanmax(mu))),
        feasible=feasible,
        evaluations=int(evals),
        seed=int(seed),
        starts=int(starts),
        timing=pb.timing,
        seconds=float(seconds),
        params=p,
        path=_coupler(*args, crank[0] + np.linspace(0.0, 2 * math.pi, 721), sigma),
    )


def _targets(targets) -> np.ndarray:
    """The targets as an (N, 2) float array, refused naming the first bad one."""
    try:
        T = np.asarray(targets, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise GearleverError("targets must be an (N, 2) array of numbers") from None
    if T.ndim != 2 or T.shape[1] != 2 or T.shape[0] < 2:
        raise GearleverError(f"targets must be an (N, 2) array of N >= 2 points, got shape {T.shape}")
    if T.shape[0] > MAX_TARGETS:
        raise GearleverError(f"targets must be at most {MAX_TARGETS} points, got {T.shape[0]}")
    bad = ~np.isfinite(T) | (np.abs(np.nan_to_num(T, nan=0.0, posinf=np.inf)) > MAX_TARGET_COORDINATE)
    if bad.any():
        i, j = (int(v) for v in np.argwhere(bad)[0])
        raise GearleverError(
            f"targets[{i}] must be finite and at most {MAX_TARGET_COORDINATE:g} in size "
            f"(the model's coordinates are capped), got {'xy'[j]} = {float(T[i, j])!r}"
        )
    return T


@register
class FourBarKind(PathKind):
    """The ``fourbar`` kind: a Grashof crank-rocker, first in ``auto``.

    Examples
    --------
    >>> from gearlever.synthesis.path_kinds import get
    >>> get("fourbar").make_problem(targets=[[0, 0], [1, 0], [2, 1]]).names[-1]
    'branch'
    """

    name = "fourbar"
    order = 10
    problem = FourBarPathProblem
    options = frozenset({"min_transmission"})
    closed_path = True

    def result(self, pb, w, mode, evals, seed, starts, seconds):
        return fourbar_result(pb, w, mode, evals, seed, starts, seconds)

    def model(self, result, name, units):
        from gearlever.synthesis.model import fourbar_model

        q = result.points
        return fourbar_model(q["O2"], q["O4"], q["A"], q["B"], q["P"], name=name, units=units)
