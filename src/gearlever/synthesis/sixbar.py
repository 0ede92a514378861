"""Path generation by a Stephenson III six-bar: a crank-rocker four-bar and an RR dyad from its coupler to ground.

Linkage (Stephenson III, the six-bar path generator of R. L. Norton,
*Design of Machinery*, sec. 3.7 and fig. 3-26, "six-bar linkages"; the
synthesis formulation is that of the four-bar in
:mod:`gearlever.synthesis.path_fourbar`): the Grashof crank-rocker
``O2-A-B-O4`` (same exact parametrization of the crank) carries the point
``C`` at ``(cx, cy)`` in its coupler frame; the dyad ``C-D`` (length
``l5``), ``D-O6`` (``l6``) joins it to the ground pivot ``O6 = (x6, y6)``;
the traced point ``P`` rides on ``C-D`` at ``(px, py)`` in its frame.  The
dyad is the same closed form as the four-bar's
(:func:`gearlever.synthesis.path_fourbar._dyad` with ``A -> C``, ``D -> O6 - C``).

Search vector: the four-bar's (``x0, y0, theta0, r1, r3, r4, u2, cx, cy``,
``phi1``), then ``x6, y6, l5, l6, px, py`` and ``branch``, a discrete code
``k = floor(branch)`` in ``0..3`` (four-bar branch ``+1`` for even ``k``,
dyad branch ``+1`` for ``k < 2``), kept during the polish.

Constraints: the four-bar's (exact by construction), and the dyad closes
with margin at every crank angle (checked at :data:`CLOSURE_SAMPLES`
angles per turn with the relative margin :data:`CLOSURE_MARGIN`) before a
candidate is evaluated.  Lengths ``l5, l6`` in the length range, ``x6, y6,
px, py`` in the coordinate range.

The kind registers itself as ``sixbar``
(:mod:`gearlever.synthesis.path_kinds`), third in ``auto``.

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.synthesis.path_fourbar import FourBarPathProblem, _coupler, _dyad
from gearlever.synthesis.path_fourbar import fourbar_result as _result
from gearlever.synthesis.path_kinds import PathKind, PathSynthesis, register

__all__ = ["StephensonSixBarKind", "StephensonSixBarPathProblem", "sixbar_result"]

#: Crank angles per turn at which the dyad's closure is checked.
CLOSURE_SAMPLES = 360
#: Relative margin kept from the dyad's toggle positions.
CLOSURE_MARGIN = 1e-3

_FB = ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy")


class StephensonSixBarPathProblem(FourBarPathProblem):
    """A Stephenson III six-bar path-generation problem (same interface as :class:`FourBarPathProblem`).

    Examples
    --------
    >>> pb = StephensonSixBarPathProblem([[0, 0], [1, 0], [2, 1]], length_range=(0.5, 5), coord_range=(-5, 5))
    >>> pb.names[-7:]
    ('x6', 'y6', 'l5', 'l6', 'px', 'py', 'branch')
    """

    def __init__(self, targets, timing="none", angles=None, **kw):
        super().__init__(targets, timing, angles, **kw)
        lo, hi = self.length_range
        clo, chi = self.coord_range
        names = list(self.names[:-1])
        blo, bhi = list(self.lo[:-1]), list(self.hi[:-1])
        for n, a, b in (
            ("x6", clo, chi),
            ("y6", clo, chi),
            ("l5", lo, hi),
            ("l6", lo, hi),
            ("px", clo, chi),
            ("py", clo, chi),
            ("branch", 0.0, 4.0),
        ):
            names.append(n)
            blo.append(a)
            bhi.append(b)
        self.names = tuple(names)
        self.lo = np.array(blo, dtype=float)
        self.hi = np.array(bhi, dtype=float)
        self._col = {n: i for i, n in enumerate(names)}
        self.d = len(names)

    def mode_of(self, Z):
        """Discrete code ``k`` in 0..3 (four-bar branch +1 for even ``k``, dyad branch +1 for ``k < 2``), (n,)."""
        return np.clip(np.floor(np.asarray(Z)[..., self._col["branch"]]), 0, 3)

    @staticmethod
    def decode(mode):
        """Branch signs (four-bar, dyad) of discrete codes ``mode``."""
        k = np.asarray(mode, dtype=int)
        return np.where(k % 2 == 0, 1.0, -1.0), np.where(k < 2, 1.0, -1.0)

    def params(self, Z):
        p, ok = super().params(Z)
        for n in ("x6", "y6", "l5", "l6", "px", "py"):
            p[n] = np.asarray(Z, dtype=float)[..., self._col[n]]
        return p, ok

    def feasible(self, Z):
        """Mask (n,): a crank-rocker four-bar (by construction) whose dyad closes with margin all around."""
        Z = np.atleast_2d(np.asarray(Z, dtype=float))
        p, ok = self.params(Z)
        s1, _ = self.decode(self.mode_of(Z))
        grid = np.arange(CLOSURE_SAMPLES) * (2 * math.pi / CLOSURE_SAMPLES)
        C = _coupler(*(p[k][:, None] for k in _FB), grid[None, :], s1[:, None])
        f = np.hypot(p["x6"][:, None] - C[..., 0], p["y6"][:, None] - C[..., 1])
        l5, l6 = p["l5"], p["l6"]
        closes = (f.min(axis=1) > np.abs(l5 - l6) * (1 + CLOSURE_MARGIN)) & (
            f.max(axis=1) < (l5 + l6) * (1 - CLOSURE_MARGIN)
        )
        return ok & closes

    def _pts(self, Z, phi, mode, jac=False):
        p, _ = self.params(Z)
        s1, s2 = self.decode(mode)
        if not jac:
            C = super()._pts(Z, phi, s1)
        else:
            C, dC = super()._pts(Z, phi, s1, jac=True)
        Cx, Cy = C[..., 0], C[..., 1]
        x6, y6 = p["x6"][:, None], p["y6"][:, None]
        args = (Cx, Cy, x6 - Cx, y6 - Cy, p["l5"][:, None], p["l6"][:, None], p["px"][:, None], p["py"][:, None])
        if not jac:
            return _dyad(*args, s2[:, None])
        P, d, e, n = _dyad(*args, s2[:, None], jac=True)
        out = {}
        for name, v in dC.items():
            out[name] = d(v[..., 0], v[..., 1], -v[..., 0], -v[..., 1])
        out["x6"] = d(0.0, 0.0, 1.0, 0.0)
        out["y6"] = d(0.0, 0.0, 0.0, 1.0)
        out["l5"] = d(0.0, 0.0, 0.0, 0.0, 1.0, 0.0)
        out["l6"] = d(0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
        out["px"] = e
        out["py"] = n
        return P, out


def sixbar_result(pb: StephensonSixBarPathProblem, w, mode, evals, seed, starts, seconds) -> PathSynthesis:
    """The :class:`~gearlever.synthesis.path_kinds.PathSynthesis` of a polished Stephenson six-bar."""
    from dataclasses import replace

    s1, s2 = (float(v[0]) for v in pb.decode(np.array([int(mode)])))
    Z, phi = pb._split(np.asarray(w, dtype=float), mode)
    # the four-bar part (its coupler point is C) through the four-bar's result builder
    fb = FourBarPathProblem(
        pb.targets,
        pb.timing,
        pb.angles,
        pivot=pb.pivot,
        ground_angle=pb.ground_angle,
        length_range=pb.length_range,
        coord_range=pb.coord_range,
    )
    w4 = np.concatenate([Z[: fb.d - 1], phi if pb.timing == "none" else []])
    r4 = _result(fb, w4, s1, evals, seed, starts, seconds)
    p, _ = pb.params(Z[None, :])
    p = {k: float(v[0]) for k, v in p.items()}
    traced = pb._pts(Z[None, :], phi[None, :], np.array([mode]))[0]
    err = np.hypot(*(traced - pb.targets).T)
    C = np.array(r4.achieved[0])
    D = _dyad(C[0], C[1], p["x6"] - C[0], p["y6"] - C[1], p["l5"], p["l6"], p["l5"], 0.0, s2)
    pts = {k: r4.points[k] for k in ("O2", "O4", "A", "B")}
    pts.update({"O6": [p["x6"], p["y6"]], "C": C.tolist(), "D": D.tolist(), "P": traced[0].tolist()})
    path = pb._pts(Z[None, :], (r4.crank_angles[0] + np.linspace(0.0, 2 * math.pi, 721))[None, :], np.array([mode]))[0]
    return replace(
        r4,
        kind="sixbar",
        achieved=traced,
        error=err,
        objective=float(np.sum(err**2)),
        points=pts,
        links={**r4.links, "link5": p["l5"], "output": p["l6"]},
        branch=f"four-bar {r4.branch}, dyad {'+' if s2 > 0 else '-'}",
        feasible=bool(r4.feasible and pb.feasible_w(w, mode)),
        params={**r4.params, **{k: p[k] for k in ("x6", "y6", "l5", "l6", "px", "py")}, "sigma2": s2},
        path=path,
    )


@register
class StephensonSixBarKind(PathKind):
    """The ``sixbar`` kind: a Stephenson III six-bar, tried after the geared five-bar in ``auto``.

    Examples
    --------
    >>> from gearlever.synthesis.path_kinds import get
    >>> get("sixbar").make_problem(targets=[[0, 0], [1, 0], [2, 1]]).names[-3:]
    ('px', 'py', 'branch')
    """

    name = "sixbar"
    order = 30
    problem = StephensonSixBarPathProblem

    def result(self, pb, w, mode, evals, seed, starts, seconds):
        return sixbar_result(pb, w, mode, evals, seed, starts, seconds)

    def model(self, result, name, units):
        from gearlever.synthesis.model import stephenson_sixbar_model

        q = result.points
        return stephenson_sixbar_model(
            q["O2"], q["O4"], q["O6"], q["A"], q["B"], q["C"], q["D"], q["P"], name=name, units=units
        )
