"""Path generation by a geared five-bar: two cranks coupled by a gear pair, closed by two couplers.

Linkage (the geared five-bar of W.-Y. Lin, "Optimum path synthesis of a
geared five-bar mechanism", Advances in Mechanical Engineering 2013,
article 757935): crank ``O2-A`` (length ``a``, the input, angle ``phi``
from the ground line), second crank ``O4-B`` (length ``b``) driven through
an external gear pair of teeth ``z1, z2`` at the angle
``beta = theta0 + psi + rho phi``, ``rho = -z1 / z2`` (``psi`` the phase),
couplers ``A-C`` (``c``) and ``B-C`` (``d``) meeting at ``C``; the traced
point ``P`` rides on ``A-C`` at ``(cx, cy)`` in its frame.  ``C`` is the
circle intersection on the branch ``sigma``, the same closed form as the
four-bar's with the moving ``B`` in place of the fixed pivot
(:func:`gearlever.synthesis.path_fourbar._dyad`).

Search vector: ``x0, y0, theta0`` (unless fixed), ``r1, a, b, c, d, cx, cy,
psi``, ``phi1`` (relative timing), and ``branch``, a discrete code
``k = floor(branch)`` choosing the gear pair ``RATIOS[k // 2]`` and the
branch sign (``+1`` for even ``k``).  The gear pair and branch are kept
during the polish.

Constraints, exact by rejection before evaluation: every length in the
length range, coordinates in the coordinate range, and the loop closes with
margin at every crank angle of the period (:data:`TURNS` crank turns, checked
at :data:`CLOSURE_SAMPLES` angles per turn with the relative margin
:data:`CLOSURE_MARGIN`), so the motion runs on one branch without a toggle.

The kind registers itself as ``geared-fivebar``
(:mod:`gearlever.synthesis.path_kinds`), second in ``auto``.

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.synthesis.path_fourbar import FourBarPathProblem, _dyad
from gearlever.synthesis.path_kinds import PathKind, PathSynthesis, register

__all__ = ["GearedFiveBarKind", "GearedFiveBarPathProblem", "RATIOS", "fivebar_result"]

#: Gear pairs (teeth of the input crank's gear, of the second crank's gear): ratios 1, 2, 1/2, 3.
RATIOS = ((30, 30), (40, 20), (20, 40), (60, 20))
#: Crank turns after which every gear pair of :data:`RATIOS` repeats its motion.
TURNS = 2
#: Crank angles per turn at which closure is checked.
CLOSURE_SAMPLES = 360
#: Relative margin kept from the toggle positions ``|AB| = c + d`` and ``|AB| = |c - d|``.
CLOSURE_MARGIN = 1e-3


class GearedFiveBarPathProblem(FourBarPathProblem):
    """A geared five-bar path-generation problem (same interface as :class:`FourBarPathProblem`).

    Examples
    --------
    >>> pb = GearedFiveBarPathProblem([[0, 0], [1, 0], [2, 1]], "none", length_range=(0.5, 5), coord_range=(-5, 5))
    >>> pb.names
    ('x0', 'y0', 'theta0', 'r1', 'a', 'b', 'c', 'd', 'cx', 'cy', 'psi', 'branch')
    """

    turns = TURNS

    def __init__(self, targets, timing="none", angles=None, **kw):
        super().__init__(targets, timing, angles, **kw)
        lo, hi = self.length_range
        clo, chi = self.coord_range
        names, blo, bhi = [], [], []
        for n, a, b in zip(self.names, self.lo, self.hi):
            if n in ("x0", "y0", "theta0"):
                names.append(n)
                blo.append(a)
                bhi.append(b)
        for n in ("r1", "a", "b", "c", "d"):
            names.append(n)
            blo.append(lo)
            bhi.append(hi)
        for n in ("cx", "cy"):
            names.append(n)
            blo.append(clo)
            bhi.append(chi)
        names.append("psi")
        blo.append(0.0)
        bhi.append(2 * math.pi)
        if self.timing == "relative":
            names.append("phi1")
            blo.append(0.0)
            bhi.append(2 * math.pi)
        names.append("branch")
        blo.append(0.0)
        bhi.append(2 * len(RATIOS))
        self.names = tuple(names)
        self.lo = np.array(blo, dtype=float)
        self.hi = np.array(bhi, dtype=float)
        self._col = {n: i for i, n in enumerate(names)}
        self.d = len(names)

    # ---------------------------------------------------------------- hooks
    def mode_of(self, Z):
        """Discrete code ``k`` (gear pair ``k // 2``, branch sign ``+1`` for even ``k``), (n,)."""
        k = np.floor(np.asarray(Z)[..., self._col["branch"]])
        return np.clip(k, 0, 2 * len(RATIOS) - 1)

    @staticmethod
    def decode(mode):
        """Gear ratios ``rho = -z1/z2`` and branch signs of discrete codes ``mode``."""
        k = np.asarray(mode, dtype=int)
        rho = np.array([-z1 / z2 for z1, z2 in RATIOS])[k // 2]
        sigma = np.where(k % 2 == 0, 1.0, -1.0)
        return rho, sigma

    def params(self, Z):
        """Physical parameters of candidates ``Z``: dict of (n,) (``x0, y0, th0, r1, a, b, c, d, cx, cy, psi``)."""
        Z = np.asarray(Z, dtype=float)
        px, py = self.pivot if self.pivot is not None else (0.0, 0.0)
        p = {
            "x0": self._get(Z, "x0", px),
            "y0": self._get(Z, "y0", py),
            "th0": self._get(Z, "theta0", self.ground_angle if self.ground_angle is not None else 0.0),
        }
        for n in ("r1", "a", "b", "c", "d", "cx", "cy", "psi"):
            p[n] = Z[..., self._col[n]]
        return p, np.ones(Z.shape[:-1], dtype=bool)

    def _AD(self, p, phi, rho):
        """Crank pin A, the vector D = B - A and the pieces of their derivatives, at angles ``phi`` (n, m)."""
        th0 = p["th0"][:, None]
        al = th0 + phi
        be = th0 + p["psi"][:, None] + rho[:, None] * phi
        a, b, r1 = p["a"][:, None], p["b"][:, None], p["r1"][:, None]
        ca, sa, cb, sb = np.cos(al), np.sin(al), np.cos(be), np.sin(be)
        c0, s0 = np.cos(th0), np.sin(th0)
        Ax, Ay = p["x0"][:, None] + a * ca, p["y0"][:, None] + a * sa
        Dx = r1 * c0 + b * cb - a * ca
        Dy = r1 * s0 + b * sb - a * sa
        return Ax, Ay, Dx, Dy, (ca, sa, cb, sb, c0, s0, a, b)

    def feasible(self, Z):
        """Mask (n,): the loop closes with margin at every sampled crank angle of the period."""
        Z = np.atleast_2d(np.asarray(Z, dtype=float))
        p, _ = self.params(Z)
        rho, _ = self.decode(self.mode_of(Z))
        grid = np.arange(CLOSURE_SAMPLES * TURNS) * (2 * math.pi / CLOSURE_SAMPLES)
        phi = np.broadcast_to(grid, (Z.shape[0], grid.size))
        _, _, Dx, Dy, _ = self._AD(p, phi, rho)
        f = np.hypot(Dx, Dy)
        c, d = p["c"], p["d"]
        return (f.min(axis=1) > np.abs(c - d) * (1 + CLOSURE_MARGIN) + 1e-300) & (
            f.max(axis=1) < (c + d) * (1 - CLOSURE_MARGIN)
        )

    def _pts(self, Z, phi, mode, jac=False):
        p, _ = self.params(Z)
        rho, sigma = self.decode(mode)
        sig = sigma[:, None]
        Ax, Ay, Dx, Dy, (ca, sa, cb, sb, c0, s0, a, b) = self._AD(p, phi, rho)
        c, d = p["c"][:, None], p["d"][:, None]
        cx, cy = p["cx"][:, None], p["cy"][:, None]
        if not jac:
            return _dyad(Ax, Ay, Dx, Dy, c, d, cx, cy, sig)
        P, dd, e3, n3 = _dyad(Ax, Ay, Dx, Dy, c, d, cx, cy, sig, jac=True)
        r = rho[:, None]
        out = {
            "x0": dd(1.0, 0.0, 0.0, 0.0),
            "y0": dd(0.0, 1.0, 0.0, 0.0),
            "theta0": dd(-a * sa, a * ca, -Dy, Dx),
            "r1": dd(0.0, 0.0, c0, s0),
            "a": dd(ca, sa, -ca, -sa),
            "b": dd(0.0, 0.0, cb, sb),
            "c": dd(0.0, 0.0, 0.0, 0.0, 1.0, 0.0),
            "d": dd(0.0, 0.0, 0.0, 0.0, 0.0, 1.0),
            "cx": e3,
            "cy": n3,
            "psi": dd(0.0, 0.0, -b * sb, b * cb),
            "phi": dd(-a * sa, a * ca, -r * b * sb + a * sa, r * b * cb - a * ca),
        }
        return P, out


def fivebar_result(pb: GearedFiveBarPathProblem, w, mode, evals, seed, starts, seconds) -> PathSynthesis:
    """The :class:`~gearlever.synthesis.path_kinds.PathSynthesis` of a polished geared five-bar."""
    Z, phi = pb._split(np.asarray(w, dtype=float), mode)
    p, _ = pb.params(Z[None, :])
    p = {k: float(v[0]) for k, v in p.items()}
    k = int(mode)
    rho, sigma = pb.decode(np.array([k]))
    rho, sigma = float(rho[0]), float(sigma[0])
    traced = pb._pts(Z[None, :], phi[None, :], np.array([k]))[0]
    err = np.hypot(*(traced - pb.targets).T)
    inc = np.concatenate([[0.0], np.cumsum(np.mod(np.diff(phi), 2 * math.pi))])
    crank = phi[0] + inc
    th0 = p["th0"]
    a1 = math.atan2(math.sin(th0 + phi[0]), math.cos(th0 + phi[0]))
    Ax, Ay, Dx, Dy, _ = pb._AD({n: np.array([v]) for n, v in p.items()}, np.array([[phi[0]]]), np.array([rho]))
    Ax, Ay, Dx, Dy = (float(v[0, 0]) for v in (Ax, Ay, Dx, Dy))
    O2 = np.array([p["x0"], p["y0"]])
    O4 = O2 + p["r1"] * np.array([math.cos(th0), math.sin(th0)])
    A = np.array([Ax, Ay])
    B = A + np.array([Dx, Dy])
    C = _dyad(Ax, Ay, Dx, Dy, p["c"], p["d"], p["c"], 0.0, sigma)
    # transmission angle at C (between the couplers) over the period
    grid = crank[0] + np.arange(CLOSURE_SAMPLES * TURNS) * (2 * math.pi / CLOSURE_SAMPLES)
    _, _, gx, gy, _ = pb._AD({n: np.array([v]) for n, v in p.items()}, grid[None, :], np.array([rho]))
    f2 = gx[0] ** 2 + gy[0] ** 2
    cmu = (p["c"] ** 2 + p["d"] ** 2 - f2) / (2 * p["c"] * p["d"])
    mu = np.arccos(np.clip(cmu, -1.0, 1.0))
    path = pb._pts(Z[None, :], crank[0] + np.linspace(0.0, 2 * math.pi * TURNS, 721 * TURNS)[None, :], np.array([k]))[0]
    feasible = pb.feasible_w(w, mode)
    z1, z2 = RATIOS[k // 2]
    return PathSynthesis(
        kind="geared-fivebar",
        target=pb.targets.copy(),
        achieved=traced,
        error=err,
        objective=float(np.sum(err**2)),
        crank_angles=crank,
        input_angles=a1 + inc,
        points={
            "O2": O2.tolist(),
            "O4": O4.tolist(),
            "A": A.tolist(),
            "B": B.tolist(),
            "C": C.tolist(),
            "P": traced[0].tolist(),
        },
        links={"ground": p["r1"], "crank": p["a"], "crank2": p["b"], "coupler": p["c"], "link5": p["d"]},
        branch="open" if sigma > 0 else "crossed",
        grashof="n/a (geared five-bar: closure checked over the period)",
        transmission_range=(float(mu.min()), float(mu.max())),
        feasible=bool(feasible),
        evaluations=int(evals),
        seed=int(seed),
        starts=int(starts),
        timing=pb.timing,
        seconds=float(seconds),
        params={**p, "rho": rho, "sigma": sigma},
        path=path,
        teeth=(z1, z2),
    )


@register
class GearedFiveBarKind(PathKind):
    """The ``geared-fivebar`` kind: two cranks coupled by a gear pair, tried after the four-bar in ``auto``.

    Examples
    --------
    >>> from gearlever.synthesis.path_kinds import get
    >>> get("geared-fivebar").make_problem(targets=[[0, 0], [1, 0], [2, 1]]).names[-2:]
    ('psi', 'branch')
    """

    name = "geared-fivebar"
    order = 20
    problem = GearedFiveBarPathProblem

    def result(self, pb, w, mode, evals, seed, starts, seconds):
        return fivebar_result(pb, w, mode, evals, seed, starts, seconds)

    def model(self, result, name, units):
        from gearlever.synthesis.model import geared_fivebar_model

        q = result.points
        return geared_fivebar_model(
            q["O2"], q["O4"], q["A"], q["B"], q["C"], q["P"], result.teeth, name=name, units=units
        )
