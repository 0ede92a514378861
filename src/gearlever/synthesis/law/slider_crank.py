"""Offset slider-crank for a displacement law: the slider (link ``output``) travels as the law says.

Crank pivot ``O2 = (0, 0)``, slider line ``y = e`` along +x; crank ``a``,
rod ``b = a + |e| + m`` (so the crank turns fully: ``b > a + |e|``), crank
angle ``alpha`` at law input 0, ``branch`` the sign of the root (slider
ahead of or behind the crank pin).  Lengths scale with the law's stroke.

Notes: the slider's position ``s = a cos(phi) + sigma sqrt(b^2 - (e - a
sin(phi))^2)`` (Norton, *Design of Machinery*, the slider-crank position
analysis); the transmission angle ``arccos(|e - a sin(phi)| / b)`` is least
where ``|e - a sin phi|`` is largest, ``|e| + a``.

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import LIFT, LawKind, register

__all__ = ["SliderCrankLaw"]


@register
class SliderCrankLaw(LawKind):
    """Offset slider-crank, output the slider (see the module docstring)."""

    name = "slider-crank"
    order = 4
    example = {"output": "displacement", "units": "mm", "segments": LIFT}
    outputs = ("displacement",)
    names = ("a", "e", "m", "alpha", "branch")
    fixed = ("branch",)

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        R = target.scale
        self.lo = np.array([0.2 * R, -2.0 * R, 0.02 * R, -math.pi, -1.0])
        self.hi = np.array([1.5 * R, 2.0 * R, 6.0 * R, math.pi, 1.0])

    @staticmethod
    def _abs(e):
        return np.where(np.real(e) >= 0, e, -e)

    def generate(self, Z, theta):
        a, e, m = Z[:, 0:1], Z[:, 1:2], Z[:, 2:3]
        b = a + self._abs(e) + m
        sig = np.where(np.real(Z[:, 4:5]) >= 0, 1.0, -1.0)
        phi = Z[:, 3:4] + theta
        h = e - a * np.sin(phi)
        s = a * np.cos(phi) + sig * np.sqrt(b * b - h * h)
        return s, np.ones(Z.shape[0], dtype=bool)

    def transmission(self, Z):
        a, e, m = (np.real(Z[:, i]) for i in range(3))
        b = a + np.abs(e) + m
        return np.arccos(np.clip((np.abs(e) + a) / b, 0, 1)), np.arccos(np.clip(np.maximum(np.abs(e) - a, 0) / b, 0, 1))

    def details(self, z):
        a, e, m = (float(v) for v in z[:3])
        return {
            "lengths": {"crank": a, "rod": a + abs(e) + m, "offset": e},
            "branch": "+" if z[-1] >= 0 else "-",
            "crank_deg_at_input_0": math.degrees(z[3]),
        }

    def model(self, z, k):
        a, e, m, al = (float(v) for v in z[:4])
        b = a + abs(e) + m
        sig = 1.0 if z[4] >= 0 else -1.0
        h = e - a * math.sin(al)
        s0 = a * math.cos(al) + sig * math.sqrt(b * b - h * h)
        units = self.target.units if self.target.output == "displacement" else ""
        return {
            "mechanism": mechanism_table("law slider-crank", units),
            "points": {
                "O2": xy_pair("O2", (0, 0)),
                "A": xy_pair("A", (a * math.cos(al), a * math.sin(al))),
                "B": [s0, e],
            },
            "links": {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "output": ["B"]},
            "sliders": [{"link": "output", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
            "inputs": [{"link": "crank"}],
        }
