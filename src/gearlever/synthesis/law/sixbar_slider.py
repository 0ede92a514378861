"""Six-bar with a slider for a displacement law: the shaper, a slotted lever driving a ram through a rod.

As the shipped ``examples/whitworth.toml``: the crank ``O2 A`` (length
``a``, the unit of the search, which scales with the law's stroke) carries
a block sliding in the slot of the lever pivoted at ``O4 = d a (cos gamma,
sin gamma)``; the lever's arm ``O4 B`` (length ``L``, at ``delta`` from the
slot) drives the rod ``B C`` (length ``r``), whose end ``C`` is the ram
(link ``output``) sliding along the line ``y = e``.  For ``d < 1`` the lever
turns fully (Whitworth's quick return), for ``d > 1`` it oscillates (the
crank-shaper); either way the lever turns slowly while the crank is far from
``O4`` and fast while it is near, so the ram's stroke one way takes longer
than the other (Shigley and Uicker, *Theory of Machines and Mechanisms*,
quick-return mechanisms; Norton, *Design of Machinery*, the Whitworth and
crank-shaper mechanisms).

Closed form: the lever's direction ``u = (A - O4) / |A - O4|``, ``B = O4 +
L R(delta) u``, and the ram ``s = B_x + sigma sqrt(r^2 - (e - B_y)^2)``
(the slider-crank's position with the lever's arm as its crank).  The rod is
``r = L + |e - O4_y| + m`` (``m > 0``), so it reaches the ram's line at every
lever angle.  The transmission angle at the ram ``arccos(|e - B_y| / r)``
(the rod against the ram's normal) stays within the bound over the turn
(sampled); the block drives the lever square to its slot throughout.

Variables ``d, gamma, L, delta, m, e, alpha, branch`` (``alpha`` the crank
angle at law input 0, ``branch`` the sign ``sigma``).  Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import LawKind, register

__all__ = ["SixBarSliderLaw"]

#: Range of the pivot distance ``d`` in crank lengths, and the band about 1 refused (O4 on the crank's circle).
PIVOT = (0.1, 4.0)
NEAR_ONE = 0.02


@register
class SixBarSliderLaw(LawKind):
    """Six-bar with a slider (the shaper: slotted lever, rod and ram), output the ram."""

    name = "sixbar-slider"
    order = 6
    example = {
        "output": "displacement",
        "units": "mm",
        "segments": ({"to": 240, "motion": "linear", "rise": 40}, {"to": 360, "motion": "cycloidal", "rise": -40}),
    }
    outputs = ("displacement",)
    names = ("d", "gamma", "L", "delta", "m", "e", "alpha", "branch")
    fixed = ("branch",)

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        R = target.scale
        self.unit = R
        self.lo = np.array([PIVOT[0], -math.pi, 0.2 * R, -math.pi, 0.02 * R, -4.0 * R, -math.pi, -1.0])
        self.hi = np.array([PIVOT[1], math.pi, 4.0 * R, math.pi, 6.0 * R, 4.0 * R, math.pi, 1.0])

    @staticmethod
    def _abs(x):
        return np.where(np.real(x) >= 0, x, -x)

    def _points(self, Z, theta):
        """``O4, B, r, e``: the lever pivot ``(n, 1)``, the arm's end ``(n, N)``, the rod and the ram line."""
        U = self.unit
        d, g, L, de, m, e = (Z[:, i : i + 1] for i in range(6))
        phi = Z[:, 6:7] + theta
        x4, y4 = U * d * np.cos(g), U * d * np.sin(g)
        wx, wy = U * np.cos(phi) - x4, U * np.sin(phi) - y4
        n = np.sqrt(wx * wx + wy * wy)
        ux, uy = wx / n, wy / n
        c, s = np.cos(de), np.sin(de)
        Bx, By = x4 + L * (c * ux - s * uy), y4 + L * (s * ux + c * uy)
        r = L + self._abs(e - y4) + m
        return (x4, y4), (Bx, By), r, e

    def generate(self, Z, theta):
        _, (Bx, By), r, e = self._points(Z, theta)
        sig = np.where(np.real(Z[:, 7:8]) >= 0, 1.0, -1.0)
        h = e - By
        s = Bx + sig * np.sqrt(r * r - h * h)
        ok = np.abs(np.real(Z[:, 0]) - 1.0) > NEAR_ONE
        return s, ok

    def transmission(self, Z):
        Z = np.real(np.atleast_2d(Z))
        _, (_, By), r, e = self._points(Z, self.target.theta)
        mu = np.arccos(np.clip(np.abs(e - By) / r, 0.0, 1.0))
        return mu.min(axis=1), mu.max(axis=1)

    def _pose(self, z):
        z = np.asarray(z, dtype=float)
        th = np.zeros(1)
        (x4, y4), (Bx, By), r, e = self._points(z[None, :], th)
        s = float(self.generate(z[None, :], th)[0][0, 0])
        al = float(z[6])
        U = self.unit
        return {
            "O2": (0.0, 0.0),
            "O4": (float(x4[0, 0]), float(y4[0, 0])),
            "A": (U * math.cos(al), U * math.sin(al)),
            "B": (float(Bx[0, 0]), float(By[0, 0])),
            "C": (s, float(e[0, 0])),
        }, float(r[0, 0])

    def details(self, z):
        z = np.asarray(z, dtype=float)
        pts, r = self._pose(z)
        U = self.unit
        return {
            "lengths": {
                "crank": U,
                "pivot_distance": float(z[0]) * U,
                "arm": float(z[2]),
                "rod": r,
                "ram_line_offset": float(z[5]),
            },
            "O4": list(pts["O4"]),
            "lever": "turns fully (Whitworth)" if z[0] < 1 else "oscillates (crank-shaper)",
            "arm_deg_from_slot": math.degrees(z[3]),
            "branch": "+" if z[7] >= 0 else "-",
            "crank_deg_at_input_0": math.degrees(z[6]),
        }

    def model(self, z, k):
        pts, _ = self._pose(z)
        A, O4 = pts["A"], pts["O4"]
        slot = [A[0] - O4[0], A[1] - O4[1]]
        return {
            "mechanism": mechanism_table("law six-bar with a slider (shaper)", self.target.units),
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": {
                "ground": ["O2", "O4"],
                "crank": ["O2", "A"],
                "block": ["A"],
                "lever": ["O4", "B"],
                "rod": ["B", "C"],
                "output": ["C"],
            },
            "sliders": [
                {
                    "name": "block",
                    "link": "block",
                    "on": "lever",
                    "point": "A",
                    "direction": slot,
                },
                {"name": "output", "link": "output", "on": "ground", "point": "C", "direction": [1.0, 0.0]},
            ],
            "inputs": [{"link": "crank"}],
        }
