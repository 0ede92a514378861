"""Four-bar for a law: a Grashof crank-rocker whose rocker (the link ``output``) follows the law.

Ground ``O2 = (0, 0)``, ``O4 = (1, 0)`` in the search (the model is scaled
by :data:`SIZE`); crank ``a``, coupler ``b``, rocker ``c``; the crank angle
at law input 0 is ``alpha`` and the crank turns counter-clockwise with the
law's input; ``branch`` picks the assembly (its sign).

Exact constraints by construction: ``b, c`` in :data:`LENGTHS` and the crank
a fraction ``u2`` of the room Grashof leaves
(``a < min(1, b, c, 1 + b + c - 2 max(1, b, c))``, the parametrization of
:mod:`gearlever.synthesis.path`), so the crank turns fully on one branch
with no dead point; the transmission angle's extremes are at the crank
angles 0 and pi (closed form).

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.mechanism.modelfile import mechanism_table, xy_pair
from gearlever.synthesis.law._core import LawKind, atan2c, register

__all__ = ["FourBarLaw", "crank_rocker", "fourbar_angles", "SIZE", "LENGTHS"]

#: Ground link of a written angle-law model (model length units).
SIZE = 100.0
#: Range of the coupler and rocker lengths, in ground lengths.
LENGTHS = (0.2, 5.0)
#: Smallest crank, in ground lengths, and the relative room kept below Grashof's limit.
CRANK_MIN = 0.02
MARGIN = 1e-6


def crank_rocker(b, c, u2):
    """Crank length ``a`` of a crank-rocker with ground 1 from the fraction ``u2`` of the room; NaN if none.

    Examples
    --------
    >>> round(float(crank_rocker(np.array(2.0), np.array(2.0), np.array(0.5))), 6)
    0.509999
    """
    br, cr = np.real(b), np.real(c)
    room = np.minimum(np.minimum(1.0, np.minimum(br, cr)), 1.0 + br + cr - 2.0 * np.maximum(1.0, np.maximum(br, cr)))
    top = room * (1.0 - MARGIN)
    ok = top > CRANK_MIN
    a = CRANK_MIN + u2 * (np.where(ok, top, np.nan) - CRANK_MIN)
    # derivatives of ``top`` in b, c carried by the complex step
    if np.iscomplexobj(b) or np.iscomplexobj(c):
        bi, ci = np.imag(b), np.imag(c)
        which = np.argmin(
            np.stack([np.ones_like(br), br, cr, 1.0 + br + cr - 2.0 * np.maximum(1.0, np.maximum(br, cr))]), axis=0
        )
        dtop = np.select(
            [which == 1, which == 2, which == 3],
            [bi, ci, bi + ci - 2.0 * np.where((br >= cr) & (br >= 1), bi, np.where(cr >= 1, ci, 0.0))],
            0.0,
        ) * (1.0 - MARGIN)
        a = a + 1j * np.real(u2) * dtop
    return a


def fourbar_angles(a, b, c, phi, sigma):
    """Rocker angle ``psi`` and coupler angle ``theta3`` (radians, continuous) of four-bars with ground (0,0)-(1,0).

    ``a, b, c`` (n, 1), ``phi`` crank angles (n, N), ``sigma`` +-1 (n, 1).

    Notes
    -----
    ``psi = pi + atan2(-Dy, -Dx) + sigma gamma`` with ``D = A - O4`` (never
    wraps: ``|A| < |O4|`` for a crank-rocker), ``cos gamma = (c^2 + f^2 -
    b^2) / (2 c f)``, ``f = |D|``; the coupler angle ``theta3 = psi + sigma
    mu`` with the transmission angle ``cos mu = (b^2 + c^2 - f^2) / (2 b c)``
    (the triangle O4 A B; Norton, *Design of Machinery*, the four-bar
    position analysis).

    Examples
    --------
    >>> psi, th3 = fourbar_angles(np.array([[0.3]]), np.array([[1.0]]), np.array([[0.8]]),
    ...                           np.array([[0.0]]), np.array([[1.0]]))
    >>> round(float(np.degrees(psi[0, 0])), 4), round(float(np.degrees(th3[0, 0])), 4)
    (263.3346, 307.3832)
    """
    Dx = a * np.cos(phi) - 1.0
    Dy = a * np.sin(phi)
    f2 = Dx * Dx + Dy * Dy
    f = np.sqrt(f2)
    gamma = np.arccos((c * c + f2 - b * b) / (2.0 * c * f))
    mu = np.arccos((b * b + c * c - f2) / (2.0 * b * c))
    psi = math.pi + atan2c(-Dy, -Dx) + sigma * gamma
    return psi, psi + sigma * mu


def transmission_range(a, b, c):
    """Smallest and largest transmission angle of crank-rockers (ground 1): at crank angles 0 and pi."""
    with np.errstate(invalid="ignore"):
        m0 = np.arccos(np.clip((b * b + c * c - (1.0 - a) ** 2) / (2.0 * b * c), -1.0, 1.0))
        m1 = np.arccos(np.clip((b * b + c * c - (1.0 + a) ** 2) / (2.0 * b * c), -1.0, 1.0))
    return np.minimum(m0, m1), np.maximum(m0, m1)


@register
class FourBarLaw(LawKind):
    """Crank-rocker four-bar, output the rocker (see the module docstring)."""

    name = "fourbar"
    order = 0
    outputs = ("angle",)
    names = ("b", "c", "u2", "alpha", "branch")
    fixed = ("branch",)

    def __init__(self, target, teeth=(17, 120)):
        super().__init__(target, teeth)
        self.lo = np.array([LENGTHS[0], LENGTHS[0], 0.0, -math.pi, -1.0])
        self.hi = np.array([LENGTHS[1], LENGTHS[1], 1.0, math.pi, 1.0])

    @staticmethod
    def _sigma(Z):
        return np.where(np.real(Z[:, -1:]) >= 0, 1.0, -1.0)

    def _links(self, Z):
        b, c, u2 = Z[:, 0:1], Z[:, 1:2], Z[:, 2:3]
        return crank_rocker(b, c, u2), b, c

    def generate(self, Z, theta):
        a, b, c = self._links(Z)
        psi, _ = fourbar_angles(a, b, c, Z[:, 3:4] + theta, self._sigma(Z))
        return psi, np.isfinite(np.real(a[:, 0]))

    def transmission(self, Z):
        a, b, c = (np.real(v[:, 0]) for v in self._links(Z))
        return transmission_range(a, b, c)

    def details(self, z):
        a, b, c = (float(np.real(v[0, 0])) for v in self._links(np.asarray(z)[None, :]))
        return {
            "lengths": {"ground": SIZE, "crank": a * SIZE, "coupler": b * SIZE, "output": c * SIZE},
            "branch": "+" if z[-1] >= 0 else "-",
            "crank_deg_at_input_0": math.degrees(z[3]),
        }

    def pose(self, z):
        """Points ``O2, O4, A, B`` at law input 0 (model units) and the angles there."""
        z = np.asarray(z, dtype=float)
        a, b, c = (float(v[0, 0]) for v in self._links(z[None, :]))
        al = float(z[3])
        sig = 1.0 if z[-1] >= 0 else -1.0
        psi, th3 = fourbar_angles(np.array([[a]]), np.array([[b]]), np.array([[c]]), np.array([[al]]), sig)
        psi, th3 = float(psi[0, 0]), float(th3[0, 0])
        S = SIZE
        pts = {
            "O2": (0.0, 0.0),
            "O4": (S, 0.0),
            "A": (S * a * math.cos(al), S * a * math.sin(al)),
            "B": (S + S * c * math.cos(psi), S * c * math.sin(psi)),
        }
        return pts, (a, b, c, al, psi, th3)

    def model(self, z, k):
        pts, _ = self.pose(z)
        return {
            "mechanism": mechanism_table("law four-bar", ""),
            "points": {n: xy_pair(n, p) for n, p in pts.items()},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "output": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
