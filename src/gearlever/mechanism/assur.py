"""Closed-form fast path: a mechanism decomposed into drivers and class-II Assur groups (dyads).

A mechanism whose links are all found, one group at a time, as

- a *driver*: an input link pinned to ground (its angle is the input), or
- an *RRR dyad*: two unknown links joined by a pin, each pinned to an
  already known link (circle-circle intersection), or
- an *RRP dyad*: an unknown link pinned to a known link and, at its other
  pin, to a block that slides on a known link (circle-line intersection),

with every pin and slider of the model used exactly once, is solved here in
closed form, batched over all input rows: positions by the intersections,
velocities and accelerations by 2x2 linear solves (Cramer's rule) on the
analytic Jacobian of each dyad.  Anything else (gear meshes, slider inputs,
higher Assur groups, redundant joints) returns no plan and is solved by the
general reduced-coordinate Newton of :mod:`gearlever.mechanism.solve`.

The fast path only answers when every row is safely away from a dead point
(see :data:`DYAD_MARGIN`) and the inputs move in steps of at most
:data:`~gearlever.mechanism.solve.COARSE_STEP`; otherwise it declines and the
general path answers, with its NaN rows, ``closed`` flags and reasons.

Pure numpy; no solver call per point.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever.loops.trig import sincos_half_angle
from gearlever.mechanism._constants import COARSE_STEP
from gearlever.mechanism.model import GROUND, MechanismModel

__all__ = ["DYAD_MARGIN", "DyadPlan", "plan_dyads"]

#: Smallest ``|sin|`` of the angle between the two members of a dyad (RRR), or between
#: the link and the guide normal (RRP), for which the closed form answers; below it the
#: general continuation decides (dead points, branch changes).
DYAD_MARGIN = 0.1

#: Rows evaluated together by :meth:`DyadPlan.solve`: the temporaries of one block
#: (some 40 arrays of BLOCK floats) stay in a core's cache instead of going to memory.
BLOCK = 8192

TAU = 2.0 * math.pi


@dataclass(frozen=True)
class _Driver:
    w: int  # input column
    link: str
    pivot: str  # pin with ground


@dataclass(frozen=True)
class _RRR:
    l1: str
    l2: str
    p: str  # pin joining l1 and l2
    p1: str  # pin of l1 with a known link k1
    k1: str
    p2: str  # pin of l2 with a known link k2
    k2: str
    r1: float
    r2: float
    sigma: float  # assembly branch: sign of cross(P2 - P1, P - P1) in the sketch
    e1: tuple  # sketch unit vectors P - P1, P - P2
    e2: tuple


@dataclass(frozen=True)
class _RRP:
    l1: str  # link pinned to known k1 at p1 and to the block l2 at p
    l2: str  # block: slides on the known link k2 (same rotation as k2)
    p: str
    p1: str
    k1: str
    k2: str
    slider: int  # index into model.sliders
    sgn_s: float  # slider coordinate = sgn_s * t (t: travel of p along the guide)
    u: tuple  # unit guide direction (sketch)
    r1: float
    sigma: float  # branch: sign of u . (P - P1) in the sketch
    e1: tuple


class DyadPlan:
    """The order in which drivers and dyads determine a mechanism (see :func:`plan_dyads`).

    Attributes
    ----------
    steps : tuple
        Drivers, then dyads, in solving order.
    """

    def __init__(self, model: MechanismModel, ks, steps: tuple):
        self.model = model
        self.ks = ks
        self.steps = steps
        P = model.points
        self._ground_points = {n: (*P[n], 0.0, 0.0, 0.0, 0.0) for n in P if GROUND in model.carriers(n)}

    # ---------------------------------------------------------------- evaluation
    def _point(self, st, pts, link, name, keep=True, dest=None):
        """Kinematics ``(X, Y, VX, VY, AX, AY)`` of the sketch location ``name`` carried by the known ``link``.

        ``dest``: where :meth:`run` writes its results (see there); the point's
        values go into its arrays when it has some.
        """
        got = pts.get(name) if keep else None
        if got is not None:
            return got
        C, S, w, al, ref = st[link]
        P = self.model.points
        vx, vy = P[name][0] - P[ref][0], P[name][1] - P[ref][1]
        OX, OY, OVX, OVY, OAX, OAY = pts[ref]
        o = dest[1].get(name, _NO_POINT) if dest is not None and keep and link != GROUND else _NO_POINT
        if o[0] is not None and w is not None:
            out = _point_in_place(C, S, w, al, vx, vy, pts[ref], o, dest[3])
            pts[name] = out
            return out
        rx = C * vx - S * vy
        ry = S * vx + C * vy
        if o[0] is None:
            X, Y = OX + rx, OY + ry
        else:
            X, Y = np.add(OX, rx, out=o[0]), np.add(OY, ry, out=o[1])
        if w is None:
            out = (X, Y, None, None, None, None)
        else:
            w2 = w * w
            if o[0] is None:
                VX, VY = OVX - w * ry, OVY + w * rx
                AX = OAX - al * ry - w2 * rx
                AY = OAY + al * rx - w2 * ry
            else:
                VX, VY = np.subtract(OVX, w * ry, out=o[2]), np.add(OVY, w * rx, out=o[3])
                AX = np.subtract(OAX - al * ry, w2 * rx, out=o[4])
                AY = np.subtract(OAY + al * rx, w2 * ry, out=o[5])
            out = (X, Y, VX, VY, AX, AY)
        if keep and link != GROUND:
            pts[name] = out
        return out

    def run(self, dq, qd=None, qdd=None, dest=None):
        """Closed-form kinematics at the input offsets ``dq`` (W, N) from the sketch.

        Returns ``(phi, state, slider, pts, margin)``: per moving link its
        wrapped rotation; per link ``(cos, sin, omega, alpha, reference point)``
        of its rotation; per slider index ``(s, sd, sdd)``; the point
        kinematics ``(X, Y, VX, VY, AX, AY)`` computed on the way; and the
        smallest dyad margin of each row (``(N,)``, NaN where a dyad does not
        assemble).  Without ``qd`` only positions are computed.

        ``dest``, with ``qd``: three dicts of ``(N,)`` arrays to write the
        results into (link -> ``(phi, cos, sin, omega, alpha)``, point ->
        ``(X, Y, VX, VY, AX, AY)``, slider -> ``(s, sd, sdd)``): the last
        operation of each value writes it there (``out=``) instead of into a
        new array, so that no copy is needed.  Values it does not write (an
        input's angle and rates) are returned as usual; the caller copies them.
        """
        rates = qd is not None
        st = {GROUND: (1.0, 0.0, 0.0 if rates else None, 0.0, None)}
        pts = dict(self._ground_points)
        phi, slider = {}, {}
        margin = None
        for step in self.steps:
            if isinstance(step, _Driver):
                a = dq[step.w]
                o = dest[0].get(step.link, _NO_LINK) if dest is not None else _NO_LINK
                C = np.empty_like(a) if o[1] is None else o[1]
                S = np.empty_like(a) if o[2] is None else o[2]
                sincos_half_angle(a, S, C)  # one tangent instead of a sine and a cosine
                w = qd[step.w] if rates else None
                al = qdd[step.w] if rates else None
                phi[step.link] = a
                st[step.link] = (C, S, w, al, step.pivot)
                continue
            if isinstance(step, _RRR):
                m = self._rrr(step, st, pts, phi, rates, dest)
            else:
                m = self._rrp(step, st, pts, phi, slider, rates, dest)
            margin = m if margin is None else np.minimum(margin, m)  # NaN (no assembly) propagates
        return phi, st, slider, pts, margin

    def _rrr(self, s: _RRR, st, pts, phi, rates, dest=None):
        P1 = self._point(st, pts, s.k1, s.p1, dest=dest)
        P2 = self._point(st, pts, s.k2, s.p2, dest=dest)
        if dest is not None and rates:
            return _rrr_in_place(s, st, pts, phi, P1, P2, dest)
        X1, Y1, VX1, VY1, AX1, AY1 = P1
        X2, Y2, VX2, VY2, AX2, AY2 = P2
        o1 = o2 = _NO_LINK
        op = _NO_POINT
        dx, dy = X2 - X1, Y2 - Y1
        d2 = dx * dx + dy * dy
        a = 0.5 + (s.r1 * s.r1 - s.r2 * s.r2) * 0.5 / d2
        h2 = (s.r1 * s.r1) / d2 - a * a
        with np.errstate(invalid="ignore"):
            h = np.sqrt(h2)
        margin = h * d2 * (1.0 / (s.r1 * s.r2))  # |sin| of the angle between the members
        sh = s.sigma * h
        r1x = a * dx - sh * dy  # P - P1
        r1y = a * dy + sh * dx
        X, Y = np.add(X1, r1x, out=op[0]), np.add(Y1, r1y, out=op[1])
        r2x, r2y = X - X2, Y - Y2
        # rotations from the sketch: cos = e . e0, sin = e0 x e  (e = r / |r|, |r| = r_i)
        i1, i2 = 1.0 / s.r1, 1.0 / s.r2
        C1 = np.multiply(r1x * s.e1[0] + r1y * s.e1[1], i1, out=o1[1])
        S1 = np.multiply(r1y * s.e1[0] - r1x * s.e1[1], i1, out=o1[2])
        C2 = np.multiply(r2x * s.e2[0] + r2y * s.e2[1], i2, out=o2[1])
        S2 = np.multiply(r2y * s.e2[0] - r2x * s.e2[1], i2, out=o2[2])
        phi[s.l1] = np.arctan2(S1, C1, out=o1[0])
        phi[s.l2] = np.arctan2(S2, C2, out=o2[0])
        if not rates:
            st[s.l1] = (C1, S1, None, None, s.p)
            st[s.l2] = (C2, S2, None, None, s.p)
            pts[s.p] = (X, Y, None, None, None, None)
            return margin
        # w1 perp(r1) - w2 perp(r2) = vP2 - vP1 =: b;  w1 = b.r2 / (r1 x r2), w2 = b.r1 / (r1 x r2)
        icr = 1.0 / (r1x * r2y - r1y * r2x)
        bx, by = VX2 - VX1, VY2 - VY1
        w1 = np.multiply(bx * r2x + by * r2y, icr, out=o1[3])
        w2 = np.multiply(bx * r1x + by * r1y, icr, out=o2[3])
        VX, VY = np.subtract(VX1, w1 * r1y, out=op[2]), np.add(VY1, w1 * r1x, out=op[3])
        q1, q2 = w1 * w1, w2 * w2
        cx = AX2 - AX1 + q1 * r1x - q2 * r2x
        cy = AY2 - AY1 + q1 * r1y - q2 * r2y
        al1 = np.multiply(cx * r2x + cy * r2y, icr, out=o1[4])
        al2 = np.multiply(cx * r1x + cy * r1y, icr, out=o2[4])
        AX = np.subtract(AX1 - al1 * r1y, q1 * r1x, out=op[4])
        AY = np.subtract(AY1 + al1 * r1x, q1 * r1y, out=op[5])
        st[s.l1] = (C1, S1, w1, al1, s.p)
        st[s.l2] = (C2, S2, w2, al2, s.p)
        pts[s.p] = (X, Y, VX, VY, AX, AY)
        return margin

    def _rrp(self, s: _RRP, st, pts, phi, slider, rates, dest=None):
        X1, Y1, VX1, VY1, AX1, AY1 = self._point(st, pts, s.k1, s.p1, dest=dest)
        CK, SK, wK, alK, _ = st[s.k2]
        ground = s.k2 == GROUND
        # Q: the sketch location of P carried by k2; the guide through Q turns with k2
        if ground:
            QX, QY = self.model.points[s.p]
            QVX = QVY = QAX = QAY = 0.0
            ux, uy = s.u
        else:
            QX, QY, QVX, QVY, QAX, QAY = self._point(st, pts, s.k2, s.p, keep=False)
            ux, uy = CK * s.u[0] - SK * s.u[1], SK * s.u[0] + CK * s.u[1]
        if dest is not None and rates:
            o1, op, osl = dest[0][s.l1], dest[1][s.p], dest[2][s.slider]
        else:
            o1, op, osl = _NO_LINK, _NO_POINT, _NO_LINK
        wx, wy = QX - X1, QY - Y1
        uw = ux * wx + uy * wy
        disc = uw * uw - (wx * wx + wy * wy - s.r1 * s.r1)
        with np.errstate(invalid="ignore"):
            root = np.sqrt(disc)
        margin = root * (1.0 / s.r1)  # |u . e1|: the link is not normal to the guide
        t = s.sigma * root - uw
        X, Y = np.add(QX, t * ux, out=op[0]), np.add(QY, t * uy, out=op[1])
        r1x, r1y = X - X1, Y - Y1
        i1 = 1.0 / s.r1
        C1 = np.multiply(r1x * s.e1[0] + r1y * s.e1[1], i1, out=o1[1])
        S1 = np.multiply(r1y * s.e1[0] - r1x * s.e1[1], i1, out=o1[2])
        phi[s.l1] = np.arctan2(S1, C1, out=o1[0])
        phi[s.l2] = phi[s.k2] if not ground else np.zeros_like(t)
        if not rates:
            st[s.l1] = (C1, S1, None, None, s.p)
            st[s.l2] = (CK, SK, None, None, s.p)
            pts[s.p] = (X, Y, None, None, None, None)
            slider[s.slider] = (s.sgn_s * t, None, None)
            return margin
        # w1 perp(r1) - td u = vQ + t wK perp(u) - vP1 =: b
        iru = 1.0 / (r1x * ux + r1y * uy)
        bx, by = QVX - VX1, QVY - VY1
        if not ground:
            bx = bx - t * wK * uy
            by = by + t * wK * ux
        w1 = np.multiply(by * ux - bx * uy, iru, out=o1[3])  # b . perp(u) / (r1 . u)
        td = -(bx * r1x + by * r1y) * iru
        VX, VY = np.subtract(VX1, w1 * r1y, out=op[2]), np.add(VY1, w1 * r1x, out=op[3])
        q1 = w1 * w1
        # al1 perp(r1) - tdd u = aQ + 2 td wK perp(u) + t (alK perp(u) - wK^2 u) - aP1 + w1^2 r1 =: c
        cx = QAX - AX1 + q1 * r1x
        cy = QAY - AY1 + q1 * r1y
        if not ground:
            k = 2.0 * td * wK + t * alK
            wk2t = t * wK * wK
            cx = cx - k * uy - wk2t * ux
            cy = cy + k * ux - wk2t * uy
        al1 = np.multiply(cy * ux - cx * uy, iru, out=o1[4])
        tdd = -(cx * r1x + cy * r1y) * iru
        AX = np.subtract(AX1 - al1 * r1y, q1 * r1x, out=op[4])
        AY = np.subtract(AY1 + al1 * r1x, q1 * r1y, out=op[5])
        st[s.l1] = (C1, S1, w1, al1, s.p)
        st[s.l2] = (CK, SK, wK if not ground else np.zeros_like(t), alK if not ground else np.zeros_like(t), s.p)
        pts[s.p] = (X, Y, VX, VY, AX, AY)
        slider[s.slider] = tuple(np.multiply(s.sgn_s, v, out=o) for v, o in zip((t, td, tdd), osl))
        return margin

    # ---------------------------------------------------------------- solve
    def solve(self, q, qd, qdd):
        """Reduced coordinates and rates ``x, xd, xdd`` (nx, N), ``(C, S)`` and point kinematics, or None.

        ``None`` (the general path must answer) when an input step exceeds
        :data:`~gearlever.mechanism.solve.COARSE_STEP`, or a dyad comes within
        :data:`DYAD_MARGIN` of a dead point at some row or on the way from the
        sketch to the first row.  The point kinematics: point -> ``(position,
        velocity, acceleration)``, each ``(N, 2)``, for the points the dyads
        compute on the way.

        Notes
        -----
        The rotations are unwrapped along the input rows, starting from the
        sketch (rotation 0) through the straight path to the first row in
        steps of at most ``COARSE_STEP``, so that they equal the ones found
        by continuation.

        The rows are evaluated :data:`BLOCK` at a time, each result written
        by its last operation into its place in the returned arrays; every
        value is the result of the same operations as in one pass over all
        rows (the same bits).  The returned arrays are views of one
        allocation (a large one gets huge pages: some 1 300 page faults
        instead of 5 900 for the four-bar at 10^5 rows, 1.4x faster in
        ``benchmarks/bench_mechanism.py``), so keeping any one of them keeps
        the memory of all.
        """
        ks = self.ks
        Nn = q.shape[1]
        q0 = ks.q0[:, None]
        # lead-in from the sketch to the first row
        d0 = q[:, 0] - ks.q0
        m = max(1, math.ceil(float(np.max(np.abs(d0))) / COARSE_STEP))
        lead = d0[:, None] * (np.arange(m + 1) / m)[None, :]
        lphi, _, _, lpts, lmargin = self.run(lead)
        if lmargin is not None and not np.all(lmargin >= DYAD_MARGIN):
            return None
        n, model, idx = ks.n, self.model, ks.idx
        names = [name for name in lpts if name not in self._ground_points]
        # every result in one allocation: one large mapping, whose pages the kernel can give as huge
        # pages (numpy advises it for arrays of 4 MB and more), instead of some 30 arrays faulted
        # in 4 kB at a time (each solve returns fresh memory)
        mem = np.empty(Nn * (3 * ks.nx + 2 * n + 6 * len(names)))
        parts = np.split(mem, np.cumsum([Nn * ks.nx] * 3 + [Nn * n] * 2 + [2 * Nn] * (3 * len(names)))[:-1])
        x, xd, xdd = (a.reshape(ks.nx, Nn) for a in parts[:3])
        C, S = (a.reshape(n, Nn) for a in parts[3:5])
        pts = {name: tuple(a.reshape(Nn, 2) for a in parts[5 + 3 * i : 8 + 3 * i]) for i, name in enumerate(names)}
        drivers = {s.link for s in self.steps if isinstance(s, _Driver)}
        dyad_links = [k for k in model.moving if k not in drivers]
        jumps = dict.fromkeys(dyad_links, False)  # a step of the wrapped rotation beyond pi
        scratch = np.empty((_SCRATCH_ROWS, min(BLOCK, Nn)))  # the temporaries, reused block after block
        for start in range(0, Nn, BLOCK):
            stop = min(start + BLOCK, Nn)
            b = slice(start, stop)
            # input steps: the rows must follow each other closely (the continuation's coarse step)
            lo = max(start - 1, 0)
            dqb = q[:, lo:stop] - q0
            if dqb.shape[1] > 1 and not np.abs(np.diff(dqb, axis=1)).max() <= COARSE_STEP:
                return None
            dq = dqb[:, start - lo :]
            dest = (
                {k: (x[idx[k], b], C[idx[k], b], S[idx[k], b], xd[idx[k], b], xdd[idx[k], b]) for k in model.moving},
                {p: (P[b, 0], P[b, 1], V[b, 0], V[b, 1], A[b, 0], A[b, 1]) for p, (P, V, A) in pts.items()},
                {j: (x[n + j, b], xd[n + j, b], xdd[n + j, b]) for j in range(ks.S)},
                scratch[:, : stop - start],
            )
            phi, st, slider, bpts, margin = self.run(dq, qd[:, b], qdd[:, b], dest)
            if margin is not None and not np.all(margin >= DYAD_MARGIN):
                return None
            # what the last operations did not write in place: the inputs' angles and rates
            for k, o in dest[0].items():
                _fill(o, (phi[k], *st[k][:4]))
            for p, o in dest[1].items():
                _fill(o, bpts[p])
            for j, o in dest[2].items():
                _fill(o, slider[j])
            for k in dyad_links:
                if jumps[k]:
                    continue
                p = x[idx[k], b]
                if start and abs(float(p[0]) - float(x[idx[k], start - 1])) > math.pi:
                    jumps[k] = True
                elif p.size > 1 and float(p.max()) - float(p.min()) > math.pi:
                    jumps[k] = bool(np.abs(np.diff(p)).max() > math.pi)
        for k in dyad_links:
            lp = np.unwrap(lphi[k])
            _unwrap_in_place(x[idx[k]], float(lp[-1]), jumps[k])
        return x, xd, xdd, (C, S), pts


_NO_LINK = (None,) * 5
_NO_POINT = (None,) * 6
_SCRATCH_ROWS = 11

# The in-place forms below do the operations of the expressions in DyadPlan._point and
# DyadPlan._rrr, in the same order, into scratch rows (no temporary array is allocated: a
# block's temporaries neither go through malloc nor fault their pages in again), so their
# results are the same bits (tests/mechanism/test_assur.py checks it).


def _point_in_place(C, S, w, al, vx, vy, ref, o, t):
    """:meth:`DyadPlan._point` with rates, its six results written into ``o``, scratch rows ``t``."""
    OX, OY, OVX, OVY, OAX, OAY = ref
    np.multiply(C, vx, out=t[0])
    np.multiply(S, vy, out=t[1])
    rx = np.subtract(t[0], t[1], out=t[0])
    np.multiply(S, vx, out=t[1])
    np.multiply(C, vy, out=t[2])
    ry = np.add(t[1], t[2], out=t[1])
    X, Y = np.add(OX, rx, out=o[0]), np.add(OY, ry, out=o[1])
    np.multiply(w, ry, out=t[2])
    VX = np.subtract(OVX, t[2], out=o[2])
    np.multiply(w, rx, out=t[2])
    VY = np.add(OVY, t[2], out=o[3])
    w2 = np.multiply(w, w, out=t[2])
    np.multiply(al, ry, out=t[3])
    np.subtract(OAX, t[3], out=t[3])
    np.multiply(w2, rx, out=t[4])
    AX = np.subtract(t[3], t[4], out=o[4])
    np.multiply(al, rx, out=t[3])
    np.add(OAY, t[3], out=t[3])
    np.multiply(w2, ry, out=t[4])
    AY = np.subtract(t[3], t[4], out=o[5])
    return X, Y, VX, VY, AX, AY


def _rrr_in_place(s: _RRR, st, pts, phi, P1, P2, dest):
    """:meth:`DyadPlan._rrr` with rates, every result written into ``dest``, its scratch rows for the rest."""
    X1, Y1, VX1, VY1, AX1, AY1 = P1
    X2, Y2, VX2, VY2, AX2, AY2 = P2
    o1, o2, op, t = dest[0][s.l1], dest[0][s.l2], dest[1][s.p], dest[3]
    dx, dy = np.subtract(X2, X1, out=t[0]), np.subtract(Y2, Y1, out=t[1])
    np.multiply(dx, dx, out=t[2])
    np.multiply(dy, dy, out=t[3])
    d2 = np.add(t[2], t[3], out=t[2])
    a = np.divide((s.r1 * s.r1 - s.r2 * s.r2) * 0.5, d2, out=t[3])
    np.add(0.5, a, out=a)
    np.divide(s.r1 * s.r1, d2, out=t[4])
    np.multiply(a, a, out=t[5])
    np.subtract(t[4], t[5], out=t[4])
    with np.errstate(invalid="ignore"):
        h = np.sqrt(t[4], out=t[4])
    margin = np.multiply(h, d2)
    margin *= 1.0 / (s.r1 * s.r2)
    sh = np.multiply(s.sigma, h, out=t[5])
    np.multiply(a, dx, out=t[6])
    np.multiply(sh, dy, out=t[7])
    r1x = np.subtract(t[6], t[7], out=t[6])
    np.multiply(a, dy, out=t[7])
    np.multiply(sh, dx, out=t[8])
    r1y = np.add(t[7], t[8], out=t[7])
    X, Y = np.add(X1, r1x, out=op[0]), np.add(Y1, r1y, out=op[1])
    r2x, r2y = np.subtract(X, X2, out=t[8]), np.subtract(Y, Y2, out=t[9])
    # rotations from the sketch (t[0] to t[5] are free from here)
    for (ux, uy), e, i, o, k in ((r1x, r1y), s.e1, 1.0 / s.r1, o1, s.l1), ((r2x, r2y), s.e2, 1.0 / s.r2, o2, s.l2):
        np.multiply(ux, e[0], out=t[0])
        np.multiply(uy, e[1], out=t[1])
        np.add(t[0], t[1], out=t[0])
        C = np.multiply(t[0], i, out=o[1])
        np.multiply(uy, e[0], out=t[0])
        np.multiply(ux, e[1], out=t[1])
        np.subtract(t[0], t[1], out=t[0])
        S = np.multiply(t[0], i, out=o[2])
        phi[k] = np.arctan2(S, C, out=o[0])
    # rates: w1 = b.r2 / (r1 x r2), w2 = b.r1 / (r1 x r2), b = vP2 - vP1
    np.multiply(r1x, r2y, out=t[0])
    np.multiply(r1y, r2x, out=t[1])
    np.subtract(t[0], t[1], out=t[0])
    icr = np.divide(1.0, t[0], out=t[0])
    bx, by = np.subtract(VX2, VX1, out=t[1]), np.subtract(VY2, VY1, out=t[2])
    ws = []
    for ux, uy, o in ((r2x, r2y, o1), (r1x, r1y, o2)):
        np.multiply(bx, ux, out=t[3])
        np.multiply(by, uy, out=t[4])
        np.add(t[3], t[4], out=t[3])
        ws.append(np.multiply(t[3], icr, out=o[3]))
    w1, w2 = ws
    np.multiply(w1, r1y, out=t[3])
    VX = np.subtract(VX1, t[3], out=op[2])
    np.multiply(w1, r1x, out=t[3])
    VY = np.add(VY1, t[3], out=op[3])
    q1, q2 = np.multiply(w1, w1, out=t[1]), np.multiply(w2, w2, out=t[2])
    # c = aP2 - aP1 + q1 r1 - q2 r2
    np.subtract(AX2, AX1, out=t[3])
    np.multiply(q1, r1x, out=t[4])
    np.add(t[3], t[4], out=t[3])
    np.multiply(q2, r2x, out=t[4])
    cx = np.subtract(t[3], t[4], out=t[3])
    np.subtract(AY2, AY1, out=t[4])
    np.multiply(q1, r1y, out=t[5])
    np.add(t[4], t[5], out=t[4])
    np.multiply(q2, r2y, out=t[5])
    cy = np.subtract(t[4], t[5], out=t[4])
    als = []
    for ux, uy, o in ((r2x, r2y, o1), (r1x, r1y, o2)):
        np.multiply(cx, ux, out=t[5])
        np.multiply(cy, uy, out=t[10])
        np.add(t[5], t[10], out=t[5])
        als.append(np.multiply(t[5], icr, out=o[4]))
    al1, al2 = als
    np.multiply(al1, r1y, out=t[5])
    np.subtract(AX1, t[5], out=t[5])
    np.multiply(q1, r1x, out=t[10])
    AX = np.subtract(t[5], t[10], out=op[4])
    np.multiply(al1, r1x, out=t[5])
    np.add(AY1, t[5], out=t[5])
    np.multiply(q1, r1y, out=t[10])
    AY = np.subtract(t[5], t[10], out=op[5])
    st[s.l1] = (o1[1], o1[2], w1, al1, s.p)
    st[s.l2] = (o2[1], o2[2], w2, al2, s.p)
    pts[s.p] = (X, Y, VX, VY, AX, AY)
    return margin


def _fill(dest, values) -> None:
    """Copy each value into its array of ``dest`` unless it already is that array."""
    for d, v in zip(dest, values):
        if v is not d:
            d[...] = v


def _unwrap_in_place(p: np.ndarray, start: float, jumps: bool) -> None:
    """``p`` (wrapped angles along the rows) made continuous, its first value the one nearest ``start``.

    ``jumps``: some step between two rows exceeds pi (else the rows only get the whole turns of the start).
    """
    k0 = round((start - float(p[0])) / TAU)
    if jumps and p.size > 1:
        d = np.diff(p)
        p[1:] -= TAU * np.cumsum(np.round(d / TAU))
    if k0:
        p += TAU * k0


def plan_dyads(ks) -> DyadPlan | None:
    """Decompose a compiled mechanism into drivers and dyads; None if it does not decompose.

    Parameters
    ----------
    ks : KinematicSystem
        The compiled model (its inputs, sketch values and coordinate order).

    Returns
    -------
    DyadPlan or None
        None for gear meshes, slider inputs, inputs not pinned to ground or
        relative to a moving link, groups other than RRR and RRP dyads, and
        joints left over (redundant constraints).

    Notes
    -----
    Structural decomposition into Assur groups (L. V. Assur, 1914): starting
    from the frame and the driving links, repeatedly find two unknown links
    that form a class-II group with known links; the position of each group
    is the intersection of two circles (RRR) or of a circle and a line (RRP),
    its velocities and accelerations the solution of a 2x2 linear system
    (J. J. Uicker, G. R. Pennock and J. E. Shigley, *Theory of Machines and
    Mechanisms*, Oxford University Press, ch. 3-4).  The assembly branch is
    the one of the sketch: the sign of the cross product (RRR) or of the
    projection on the guide (RRP) there.
    """
    model = ks.model
    P = model.points
    if model.meshes:
        return None
    pins = list(model.joints)  # (point, a, b)
    used_pin = [False] * len(pins)
    used_sl = [False] * len(model.sliders)
    known = {GROUND}
    steps = []
    for w, spec in enumerate(model.inputs):
        if spec.kind != "link" or spec.relative_to not in (None, GROUND) or spec.name in known:
            return None
        piv = None
        for e, (p, a, b) in enumerate(pins):
            if not used_pin[e] and {a, b} == {spec.name, GROUND}:
                piv = (e, p)
                break
        if piv is None:
            return None
        used_pin[piv[0]] = True
        known.add(spec.name)
        steps.append(_Driver(w, spec.name, piv[1]))

    def free_pins(link):
        return [(e, p, b if a == link else a) for e, (p, a, b) in enumerate(pins) if not used_pin[e] and link in (a, b)]

    def arr(name):
        return np.array(P[name], dtype=float)

    unknown = [k for k in model.moving if k not in known]
    while unknown:
        found = None
        for e, (p, a, b) in enumerate(pins):
            if used_pin[e] or a in known or b in known or a == b:
                continue
            for l1, l2 in ((a, b), (b, a)):
                g1 = [(e1, p1, k1) for e1, p1, k1 in free_pins(l1) if k1 in known and e1 != e and p1 != p]
                if not g1:
                    continue
                e1, p1, k1 = g1[0]
                g2 = [(e2, p2, k2) for e2, p2, k2 in free_pins(l2) if k2 in known and e2 != e and p2 != p]
                if g2:
                    e2, p2, k2 = g2[0]
                    v1, v2 = arr(p) - arr(p1), arr(p) - arr(p2)
                    r1, r2 = float(np.hypot(*v1)), float(np.hypot(*v2))
                    dd = arr(p2) - arr(p1)
                    cr = float(dd[0] * v1[1] - dd[1] * v1[0])
                    if r1 == 0.0 or r2 == 0.0 or cr == 0.0:
                        continue
                    found = _RRR(
                        l1, l2, p, p1, k1, p2, k2, r1, r2, math.copysign(1.0, cr), tuple(v1 / r1), tuple(v2 / r2)
                    )
                    marks = ([e, e1, e2], [])
                    break
                for j, sl in enumerate(model.sliders):
                    if used_sl[j] or l2 not in (sl.link, sl.on):
                        continue
                    k2 = sl.on if sl.link == l2 else sl.link
                    if k2 not in known:
                        continue
                    u = np.array(sl.direction, dtype=float)
                    u /= np.hypot(*u)
                    v1 = arr(p) - arr(p1)
                    r1 = float(np.hypot(*v1))
                    proj = float(u @ v1)
                    if r1 == 0.0 or proj == 0.0:
                        continue
                    found = _RRP(
                        l1, l2, p, p1, k1, k2, j, 1.0 if sl.link == l2 else -1.0, tuple(u), r1,
                        math.copysign(1.0, proj), tuple(v1 / r1),
                    )  # fmt: skip
                    marks = ([e, e1], [j])
                    break
                if found is not None:
                    break
            if found is not None:
                break
        if found is None:
            return None
        for e in marks[0]:
            used_pin[e] = True
        for j in marks[1]:
            used_sl[j] = True
        known.update((found.l1, found.l2))
        steps.append(found)
        unknown = [k for k in model.moving if k not in known]
    if not all(used_pin) or not all(used_sl):
        return None
    return DyadPlan(model, ks, tuple(steps))
