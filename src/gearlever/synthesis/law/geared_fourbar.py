"""Geared four-bar for a law: a gear fixed to the coupler drives an output gear about a ground pivot.

The crank-rocker of :mod:`~gearlever.synthesis.law.fourbar` (ground 1)
carries gear ``g3`` on its coupler; the output gear ``g5`` (link ``output``)
turns about a ground pivot and meshes with it, the mesh carried by the link
that holds both centres:

- ``"rocker"`` variant (a returning law): ``g3`` centred at the rocker pin
  ``B``, ``g5`` about ``O4``, carrier the rocker: ``theta5 = (1 + rho) psi -
  rho theta3``, ``rho = z3 / z5``.  The output's velocity is the rocker's
  plus ``rho`` times the rocker's relative to the coupler: the classic source
  of dwell and reversal (Norton, *Design of Machinery*, geared linkages;
  Willis' equation seen from the carrier);
- ``"crank"`` variant (a law whose output turns on by ``net`` every cycle):
  ``g3`` centred at the crank pin ``A``, ``g5`` about ``O2``, carrier the
  crank: ``theta5 = (1 + rho) phi - rho theta3``, so the output turns
  ``2 pi (1 + rho)`` per cycle and ``rho = net / (2 pi) - 1`` must be a
  ratio of whole teeth within the bounds.

Teeth are integers in ``teeth = (zmin, zmax)``: the search rounds its two
tooth variables, the polish holds them.  Pitch radii follow from the centre
distance (the rocker or the crank length) and the teeth.

Pure numpy.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import DWELL, LawKind, register
from gearlever.synthesis.law.fourbar import LENGTHS, SIZE, FourBarLaw, crank_rocker, fourbar_angles, transmission_range

__all__ = ["GearedFourBarLaw", "teeth_for_ratio"]


def teeth_for_ratio(rho: float, teeth) -> tuple | None:
    """Smallest whole teeth ``(z3, z5)`` within ``teeth`` with ``z3 / z5 = rho`` exactly (to 1e-12), or None.

    Examples
    --------
    >>> teeth_for_ratio(1.5, (17, 120)), teeth_for_ratio(math.pi, (17, 120))
    ((27, 18), None)
    """
    zmin, zmax = teeth
    fr = Fraction(rho).limit_denominator(zmax)
    if fr <= 0 or abs(float(fr) - rho) > 1e-12 * max(1.0, rho):
        return None
    for mult in range(1, zmax + 1):
        z3, z5 = fr.numerator * mult, fr.denominator * mult
        if z3 > zmax or z5 > zmax:
            return None
        if z3 >= zmin and z5 >= zmin:
            return (z3, z5)
    return None


@register
class GearedFourBarLaw(LawKind):
    """Geared four-bar, output the gear on the ground pivot (see the module docstring)."""

    name = "geared-fourbar"
    order = 1
    example = {"output": "angle", "units": "deg", "segments": DWELL}
    outputs = ("angle",)
    names = ("b", "c", "u2", "alpha", "z3", "z5", "branch")
    fixed = ("z3", "z5", "branch")

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        zl, zh = self.teeth
        if not 1 <= zl <= zh:
            raise GearleverError(f"teeth must be 1 <= zmin <= zmax, got {teeth!r}")
        self.variant = "rocker" if abs(target.net) <= 1e-9 * max(target.scale, 1.0) else "crank"
        self.lo = np.array([LENGTHS[0], LENGTHS[0], 0.0, -math.pi, zl - 0.499, zl - 0.499, -1.0])
        self.hi = np.array([LENGTHS[1], LENGTHS[1], 1.0, math.pi, zh + 0.499, zh + 0.499, 1.0])
        if self.variant == "crank":
            tz = teeth_for_ratio(target.net / (2 * math.pi) - 1.0, self.teeth)
            if tz is None:
                raise GearleverError(
                    f"the law's output turns {math.degrees(target.net):.6g} deg per cycle: a geared four-bar's "
                    f"output gear turns 360 (1 + z3/z5) deg, whole teeth {zl}..{zh}; no such teeth give it"
                )
            self.lo[4:6] = self.hi[4:6] = tz

    def check(self):
        if self.target.output != "angle":
            raise GearleverError(f"a {self.name} gives an output angle, the law is {self.target.output}")

    def _teeth(self, Z):
        return np.round(np.real(Z[:, 4:5])), np.round(np.real(Z[:, 5:6]))

    def generate(self, Z, theta):
        b, c, u2 = Z[:, 0:1], Z[:, 1:2], Z[:, 2:3]
        a = crank_rocker(b, c, u2)
        sig = np.where(np.real(Z[:, -1:]) >= 0, 1.0, -1.0)
        phi = Z[:, 3:4] + theta
        psi, th3 = fourbar_angles(a, b, c, phi, sig)
        z3, z5 = self._teeth(Z)
        rho = z3 / z5
        carrier = psi if self.variant == "rocker" else phi
        return (1.0 + rho) * carrier - rho * th3, np.isfinite(np.real(a[:, 0]))

    def transmission(self, Z):
        a = np.real(crank_rocker(Z[:, 0], Z[:, 1], Z[:, 2]))
        return transmission_range(a, np.real(Z[:, 0]), np.real(Z[:, 1]))

    def details(self, z):
        out = FourBarLaw(self.target).details(np.concatenate([z[:4], z[-1:]]))
        z3, z5 = (int(v[0, 0]) for v in self._teeth(np.asarray(z)[None, :]))
        out["lengths"]["rocker"] = out["lengths"].pop("output")
        out["teeth"] = {"g3 (coupler)": z3, "g5 (output)": z5}
        out["variant"] = self.variant
        return out

    def model(self, z, k):
        z = np.asarray(z, dtype=float)
        pts, (a, b, c, al, psi, th3) = FourBarLaw(self.target).pose(np.concatenate([z[:4], z[-1:]]))
        z3, z5 = (int(v[0, 0]) for v in self._teeth(z[None, :]))
        centre = "B" if self.variant == "rocker" else "A"
        pivot, carrier = ("O4", "rocker") if self.variant == "rocker" else ("O2", "crank")
        dist = (c if self.variant == "rocker" else a) * SIZE
        r5 = dist * z5 / (z3 + z5)
        # the output link's second point on the output gear's pitch circle, in the direction of
        # the output angle at law input 0 (the generated output there)
        th5 = (1.0 + z3 / z5) * (psi if self.variant == "rocker" else al) - z3 / z5 * th3
        P = pts[pivot]
        pts["E"] = (P[0] + r5 * math.cos(th5), P[1] + r5 * math.sin(th5))
        return {
            "mechanism": mechanism_table("law geared four-bar", ""),
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": {
                "ground": ["O2", "O4"],
                "crank": ["O2", "A"],
                "coupler": ["A", "B"],
                "rocker": ["O4", "B"],
                "output": [pivot, "E"],
            },
            "gears": {
                "g3": {"link": "coupler", "centre": centre, "teeth": z3},
                "g5": {"link": "output", "centre": pivot, "teeth": z5},
            },
            "meshes": [{"gears": ["g3", "g5"], "carrier": carrier}],
            "inputs": [{"link": "crank"}],
        }
