"""Crank and slotted lever for a law: the quick-return lever, its angle the output or its end driving a ram.

The crank ``O2 A`` (length ``a``, the unit of the search) carries a block
that slides in the slot of the lever pivoted at ``O4``, at the distance
``d a`` below ``O2`` (``O4 = (0, -d a)``); ``d > 1``, so the lever
oscillates between the two positions where the crank stands square to the
slot.  Its forward swing takes the crank arc ``pi + 2 asin(1/d)``, its
return ``pi - 2 asin(1/d)``: the quick return of the shaper, time ratio
``(pi + 2 asin(1/d)) / (pi - 2 asin(1/d))`` (2 for ``d = 2``; J. E. Shigley
and J. J. Uicker, *Theory of Machines and Mechanisms*, quick-return
mechanisms; R. L. Norton, *Design of Machinery*, the crank-shaper).

- An angle law: the output is the lever (link ``output``), its angle
  ``psi = atan2(A - O4)``; variables ``d, alpha`` (the crank angle at law
  input 0).  The block drives the lever at right angles to the slot, so the
  transmission angle is 90 deg throughout.
- A displacement law: the lever's arm ``O4 B`` (length ``L``, at ``delta``
  from the slot) carries a block ``B`` sliding in a slot of the ram (link
  ``output``), which travels along x: the ram's travel is ``s = L cos(psi +
  delta)`` (a Scotch yoke on the lever); variables ``d, L, delta, alpha``.
  The transmission angle is the arm's angle to the ram's travel, ``arccos
  |cos(psi + delta)|``: an arm aligned with the travel moves the ram no more.

Lengths scale with the law's stroke (displacement) or the model's
:data:`~gearlever.synthesis.law.fourbar.SIZE` (angle).  Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import LawKind, atan2c, register
from gearlever.synthesis.law.fourbar import SIZE

__all__ = ["SlottedLeverLaw", "time_ratio"]

#: Range of the pivot distance ``d`` in crank lengths (the lever oscillates: ``d > 1``).
PIVOT = (1.02, 6.0)


def time_ratio(d):
    """Quick-return time ratio of a crank and slotted lever with pivot distance ``d > 1`` crank lengths.

    Notes
    -----
    The lever's extremes are where the crank stands square to the slot, at
    ``asin(1/d)`` either side of the perpendicular to ``O2 O4``; the forward
    swing spans ``pi + 2 asin(1/d)`` of crank, the return ``pi - 2 asin(1/d)``
    (Shigley and Uicker, *Theory of Machines and Mechanisms*, quick-return
    mechanisms).

    Examples
    --------
    >>> round(float(time_ratio(2.0)), 12)
    2.0
    """
    b = np.arcsin(1.0 / np.asarray(d, dtype=float))
    return (math.pi + 2 * b) / (math.pi - 2 * b)


@register
class SlottedLeverLaw(LawKind):
    """Crank and slotted lever (quick return): the lever, or a ram on its arm, follows the law."""

    name = "slotted-lever"
    order = 5
    example = {
        "output": "displacement",
        "units": "mm",
        "segments": ({"to": 240, "motion": "linear", "rise": 40}, {"to": 360, "motion": "cycloidal", "rise": -40}),
    }
    outputs = ("angle", "displacement")
    names = ("d", "L", "delta", "alpha")

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        self.ram = target.output == "displacement"
        self.unit = target.scale if self.ram else SIZE
        if self.ram:
            R = target.scale
            self.names = ("d", "L", "delta", "alpha")
            self.lo = np.array([PIVOT[0], 0.2 * R, -math.pi, -math.pi])
            self.hi = np.array([PIVOT[1], 4.0 * R, math.pi, math.pi])
        else:
            self.names = ("d", "alpha")
            self.lo = np.array([PIVOT[0], -math.pi])
            self.hi = np.array([PIVOT[1], math.pi])

    @staticmethod
    def _psi(d, phi):
        """Lever angle ``(n, N)`` of ``A - O4 = (cos phi, sin phi + d)``: within ``pi/2 +- asin(1/d)``, no wrap."""
        return atan2c(np.sin(phi) + d, np.cos(phi))

    def generate(self, Z, theta):
        d = Z[:, 0:1]
        phi = Z[:, -1:] + theta
        psi = self._psi(d, phi)
        ok = np.real(Z[:, 0]) > 1.0
        if not self.ram:
            return psi, ok
        L, delta = Z[:, 1:2], Z[:, 2:3]
        return L * np.cos(psi + delta), ok

    def transmission(self, Z):
        Z = np.real(np.atleast_2d(Z))
        if not self.ram:
            half = np.full(Z.shape[0], math.pi / 2)
            return half, half
        psi = self._psi(Z[:, 0:1], Z[:, -1:] + self.target.theta)
        mu = np.arccos(np.clip(np.abs(np.cos(psi + Z[:, 2:3])), 0.0, 1.0))
        return mu.min(axis=1), mu.max(axis=1)

    def details(self, z):
        z = np.asarray(z, dtype=float)
        U = self.unit
        lengths = {"crank": U, "pivot_distance": float(z[0]) * U}
        if self.ram:
            lengths["arm"] = float(z[1])
        out = {
            "lengths": lengths,
            "time_ratio": float(time_ratio(z[0])),
            "crank_deg_at_input_0": math.degrees(z[-1]),
        }
        if self.ram:
            out["arm_deg_from_slot"] = math.degrees(z[2])
        return out

    def model(self, z, k):
        z = np.asarray(z, dtype=float)
        U = self.unit
        d, al = float(z[0]), float(z[-1])
        psi = float(self._psi(np.array([[d]]), np.array([[al]]))[0, 0])
        A = (U * math.cos(al), U * math.sin(al))
        O4 = (0.0, -d * U)
        pts = {"O2": (0.0, 0.0), "O4": O4, "A": A}
        links = {"ground": ["O2", "O4"], "crank": ["O2", "A"], "block": ["A"]}
        slot = [A[0] - O4[0], A[1] - O4[1]]
        sliders = [{"name": "block", "link": "block", "on": "output" if not self.ram else "lever", "point": "A"}]
        sliders[0]["direction"] = slot
        if not self.ram:
            pts["E"] = (O4[0] + U * math.cos(psi), O4[1] + U * math.sin(psi))
            links["output"] = ["O4", "E"]
            title = "law crank and slotted lever"
            units = ""
        else:
            L, delta = float(z[1]), float(z[2])
            B = (O4[0] + L * math.cos(psi + delta), O4[1] + L * math.sin(psi + delta))
            R = (B[0], B[1] + 0.25 * U)
            pts.update({"B": B, "R": R})
            links.update({"lever": ["O4", "B"], "yoke": ["B"], "output": ["R"]})
            sliders += [
                {"name": "yoke", "link": "yoke", "on": "output", "point": "B", "direction": [0.0, 1.0]},
                {"name": "output", "link": "output", "on": "ground", "point": "R", "direction": [1.0, 0.0]},
            ]
            title = "law crank and slotted lever, ram on a yoke"
            units = self.target.units
        return {
            "mechanism": mechanism_table(title, units),
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": links,
            "sliders": sliders,
            "inputs": [{"link": "crank"}],
        }
