"""Six-bar dwell linkage for a law: a dyad driven by a coupler point, the rocker pivoted near an arc centre dwells.

Stephenson III: the crank-rocker of :mod:`~gearlever.synthesis.law.fourbar`
(ground 1) carries the coupler point ``C = A + cx e3 + cy n3`` (``e3`` along
A->B, ``n3`` its normal); the dyad ``C - D - O6`` (lengths ``l5 = |CD|``,
``l6 = |O6 D|``, branch ``branch2``) drives the output rocker ``O6 D``.
Where the coupler curve follows a circular arc of radius ``l5`` about ``D``,
``D`` stands still and the output dwells (the arc-dwell six-bar; Norton,
*Design of Machinery*, dwell mechanisms; Kota, Erdman and Riley, "Development
of knowledge base for designing linkage-type dwell mechanisms", J. Mech.
Trans. Automation 109 (1987) 308-315).

The global search works that way: each candidate four-bar and coupler point
fits a circle (Kasa's algebraic fit) to the coupler points over the law's
dwell samples and puts ``D`` at its centre, ``l5`` its radius and ``O6`` at
the searched distance ``l6`` and angle ``beta`` from ``D``
(:meth:`SixBarDwellLaw.to_full`); the polish then frees all twelve design
variables.

Constraints, exact: the four-bar's as in the four-bar kind; the dyad closes
at every sample with no dead point and its transmission angle (at ``D``)
stays within the bound over the turn (sampled), the output does not turn
through a full revolution (a rocker).

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import DWELL, LawKind, atan2c, register
from gearlever.synthesis.law.fourbar import LENGTHS, SIZE, crank_rocker, fourbar_angles, transmission_range

__all__ = ["SixBarDwellLaw"]

#: Bounds of the coupler point (coupler frame) and of the dyad's pivot, in ground lengths.
COUPLER = (-3.0, 3.0)
PIVOT = (-4.0, 5.0)
DYAD = (0.1, 6.0)


@register
class SixBarDwellLaw(LawKind):
    """Stephenson III arc-dwell six-bar, output the rocker O6-D (see the module docstring)."""

    name = "sixbar-dwell"
    order = 3
    example = {"output": "angle", "units": "deg", "segments": DWELL}
    outputs = ("angle",)
    names = ("b", "c", "u2", "alpha", "cx", "cy", "x6", "y6", "l5", "l6", "branch", "branch2")
    fixed = ("branch", "branch2")

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        L, C, P, D = LENGTHS, COUPLER, PIVOT, DYAD
        self.lo = np.array([L[0], L[0], 0.0, -math.pi, C[0], C[0], P[0], P[0], D[0], D[0], -1.0, -1.0])
        self.hi = np.array([L[1], L[1], 1.0, math.pi, C[1], C[1], P[1], P[1], D[1], D[1], 1.0, 1.0])

    def _coupler_point(self, Z, theta):
        b, c, u2 = Z[:, 0:1], Z[:, 1:2], Z[:, 2:3]
        a = crank_rocker(b, c, u2)
        sig = np.where(np.real(Z[:, 10:11]) >= 0, 1.0, -1.0)
        phi = Z[:, 3:4] + theta
        _, th3 = fourbar_angles(a, b, c, phi, sig)
        Ax, Ay = a * np.cos(phi), a * np.sin(phi)
        e, n = (np.cos(th3), np.sin(th3)), (-np.sin(th3), np.cos(th3))
        cx, cy = Z[:, 4:5], Z[:, 5:6]
        return Ax + cx * e[0] + cy * n[0], Ay + cx * e[1] + cy * n[1], a

    def _dyad(self, Z, theta):
        Cx, Cy, a = self._coupler_point(Z, theta)
        x6, y6, l5, l6 = Z[:, 6:7], Z[:, 7:8], Z[:, 8:9], Z[:, 9:10]
        Fx, Fy = Cx - x6, Cy - y6
        f2 = Fx * Fx + Fy * Fy
        f = np.sqrt(f2)
        cg = (l6 * l6 + f2 - l5 * l5) / (2.0 * l6 * f)
        cm = (l5 * l5 + l6 * l6 - f2) / (2.0 * l5 * l6)
        return Fx, Fy, f, cg, cm, a

    def generate(self, Z, theta):
        return self._generate(Z, theta)[:2]

    def evaluate(self, Z, theta):
        G, ok, cm = self._generate(Z, theta)
        a = np.real(crank_rocker(Z[:, 0], Z[:, 1], Z[:, 2]))
        m1, M1 = transmission_range(a, np.real(Z[:, 0]), np.real(Z[:, 1]))
        with np.errstate(invalid="ignore"):
            cr = np.real(cm)
            mu_lo, mu_hi = np.arccos(np.clip(cr.max(axis=1), -1, 1)), np.arccos(np.clip(cr.min(axis=1), -1, 1))
        return G, ok, np.minimum(m1, mu_lo), np.maximum(M1, mu_hi)

    def _generate(self, Z, theta):
        Fx, Fy, f, cg, cm, a = self._dyad(Z, theta)
        sig2 = np.where(np.real(Z[:, 11:12]) >= 0, 1.0, -1.0)
        ang = atan2c(Fy, Fx)
        ar = np.real(ang)
        un = np.unwrap(ar, axis=1)
        ang = ang + (un - ar)
        # winding of C about O6 over the turn (the closing step included): a rocker needs 0
        close = np.mod(ar[:, 0] - un[:, -1] + math.pi, 2 * math.pi) - math.pi
        winding = np.round((un[:, -1] + close - un[:, 0]) / (2 * math.pi))
        cgr = np.real(cg)
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(np.real(a[:, 0])) & (winding == 0) & np.all(np.abs(cgr) < 1.0 - 1e-9, axis=1)
            gam = np.arccos(np.where(np.abs(cgr) < 1.0, cg, 0.0))
        return ang + sig2 * gam, ok, cm

    def transmission(self, Z):
        _, _, mn, mx = self.evaluate(np.real(np.atleast_2d(Z)), self.target.theta)
        return mn, mx

    def _circle(self, Z):
        """Kasa's circle ``(p, q, R)`` through the coupler points over the law's dwell samples, batched.

        Also the coupler point at the dwell's first sample ``(Cx, Cy)``.
        """
        th = self.target.theta[self.target.dwell]
        Cx, Cy, _ = self._coupler_point(Z, th)
        # x^2 + y^2 = 2 p x + 2 q y + r by least squares (I. Kasa, IEEE Trans. Instrum. Meas. 25 (1976) 8-14)
        M = np.stack([2 * Cx, 2 * Cy, np.ones_like(Cx)], axis=-1)
        rhs = Cx * Cx + Cy * Cy
        with np.errstate(invalid="ignore"):
            A = np.einsum("nki,nkj->nij", M, M) + 1e-12 * np.eye(3)
            bvec = np.einsum("nki,nk->ni", M, rhs)
            ok = np.all(np.isfinite(A), axis=(1, 2)) & np.all(np.isfinite(bvec), axis=1)
            sol = np.full((Z.shape[0], 3), np.nan)
            sol[ok] = np.linalg.solve(A[ok], bvec[ok][..., None])[..., 0]
            p, q, r = sol[:, 0], sol[:, 1], sol[:, 2]
            R = np.sqrt(r + p * p + q * q)
        return p, q, R, Cx[:, 0], Cy[:, 0]

    def search_box(self):
        """The search's variables: the four-bar, the coupler point, ``l6`` and the angle ``beta`` of O6 about D.

        ``D`` (at the start of the dwell) and ``l5`` are the centre and the radius of the circle fitted to the
        coupler curve over the dwell (:meth:`to_full`): each candidate has its best arc dwell.  A law with no
        dwell searches the design variables themselves.
        """
        if not self.target.dwell.any():
            return self.lo, self.hi
        lo = np.concatenate([self.lo[:6], [DYAD[0], -math.pi, -1.0]])
        hi = np.concatenate([self.hi[:6], [DYAD[1], math.pi, 1.0]])
        return lo, hi

    def to_full(self, Zs):
        if not self.target.dwell.any():
            return Zs
        Zs = np.asarray(Zs, dtype=float)
        Zf = np.zeros((Zs.shape[0], self.d))
        Zf[:, :6], Zf[:, 10] = Zs[:, :6], Zs[:, 8]
        p, q, R, Cx, Cy = self._circle(Zf)
        l6, beta = Zs[:, 6], Zs[:, 7]
        x6, y6 = p + l6 * np.cos(beta), q + l6 * np.sin(beta)
        # the branch that puts D at the centre: D on the side of O6->C given by the sign of the cross product
        cross = (p - x6) * (Cy - y6) - (q - y6) * (Cx - x6)
        Z = np.column_stack([Zs[:, :6], x6, y6, R, l6, Zs[:, 8], np.where(cross < 0, 1.0, -1.0)])
        with np.errstate(invalid="ignore"):
            out = ~np.all((Z >= self.lo) & (Z <= self.hi), axis=1)
        Z[out] = np.nan
        return Z

    def search_sample(self, rng, m):
        lo, hi = self.search_box()
        return lo + rng.random((m, lo.size)) * (hi - lo)

    def details(self, z):
        z = np.asarray(z, dtype=float)
        a = float(crank_rocker(z[0], z[1], z[2]))
        S = SIZE
        return {
            "lengths": {
                "ground": S,
                "crank": a * S,
                "coupler": z[0] * S,
                "rocker": z[1] * S,
                "coupler_point": [z[4] * S, z[5] * S],
                "O6": [z[6] * S, z[7] * S],
                "link5": z[8] * S,
                "output": z[9] * S,
            },
            "branch": "+" if z[10] >= 0 else "-",
            "branch2": "+" if z[11] >= 0 else "-",
            "crank_deg_at_input_0": math.degrees(z[3]),
        }

    def model(self, z, k):
        z = np.asarray(z, dtype=float)
        th = np.zeros(1)
        Cx, Cy, a = self._coupler_point(z[None, :], th)
        a = float(a[0, 0])
        psi6 = float(self.generate(z[None, :], th)[0][0, 0])
        b, c, al = float(z[0]), float(z[1]), float(z[3])
        sig = 1.0 if z[10] >= 0 else -1.0
        psi, _ = fourbar_angles(np.array([[a]]), np.array([[b]]), np.array([[c]]), np.array([[al]]), sig)
        psi = float(psi[0, 0])
        S = SIZE
        pts = {
            "O2": (0.0, 0.0),
            "O4": (S, 0.0),
            "O6": (S * z[6], S * z[7]),
            "A": (S * a * math.cos(al), S * a * math.sin(al)),
            "B": (S + S * c * math.cos(psi), S * c * math.sin(psi)),
            "C": (S * float(Cx[0, 0]), S * float(Cy[0, 0])),
            "D": (S * (z[6] + z[9] * math.cos(psi6)), S * (z[7] + z[9] * math.sin(psi6))),
        }
        return {
            "mechanism": mechanism_table("law six-bar dwell (Stephenson III)", ""),
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": {
                "ground": ["O2", "O4", "O6"],
                "crank": ["O2", "A"],
                "coupler": ["A", "B", "C"],
                "rocker": ["O4", "B"],
                "link5": ["C", "D"],
                "output": ["O6", "D"],
            },
            "inputs": [{"link": "crank"}],
        }
