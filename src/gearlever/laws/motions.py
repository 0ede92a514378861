"""Normalised segment motions: y(u) on u in [0, 1], y(0) = 0, y(1) = 1.

Each motion of the registry :data:`MOTIONS` gives the displacement y and its
derivatives y', y'', y''' with respect to the normalised input u = (theta -
theta_0) / beta of a segment of width beta.  A segment rising by h then has
s = h y, v = h y' / beta, a = h y'' / beta**2, j = h y''' / beta**3 per radian
of input.  ``dwell`` is y = 0 (it carries no rise).

The motions are the standard cam laws of R. L. Norton, *Design of Machinery*
(chapter 8, "Cam design": simple harmonic, cycloidal, modified trapezoid,
modified sine, 3-4-5 and 4-5-6-7 polynomials) and of H. A. Rothbart, *Cam
Design Handbook* (chapter 3, "Cam motions").  Their peak factors (the maxima of
abs(y'), abs(y''), abs(y'''), tabulated in both texts as C_v, C_a, C_j) are checked in the
tests: cycloidal 2, 2 pi, 4 pi**2; harmonic pi/2, pi**2/2; 3-4-5 1.875, 5.7735,
60; 4-5-6-7 2.1875, 7.5132, 52.5; modified trapezoid 2.0, 4.8881, 61.4; modified
sine 1.7596, 5.5280, 69.5.

>>> from gearlever.laws.motions import MOTIONS
>>> float(MOTIONS["cycloidal"].y(0.5))
0.5
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["MOTIONS", "Motion"]

_PI = math.pi


@dataclass(frozen=True)
class Motion:
    """One normalised motion: ``derivs(u)`` gives (y, y', y'', y''') on u in [0, 1].

    Attributes
    ----------
    name : str
        Registry name.
    derivs : callable
        ``u -> (y, dy, d2y, d3y)``, vectorised over arrays of u in [0, 1].
    rises : bool
        False for the dwell (y = 0), True for motions going from 0 to 1.
    description : str
        One line for listings.

    Examples
    --------
    >>> from gearlever.laws.motions import MOTIONS
    >>> y, dy, d2y, d3y = MOTIONS["345"].derivs(1.0)
    >>> float(y), float(dy), float(d2y)
    (1.0, 0.0, 0.0)
    """

    name: str
    derivs: Callable
    rises: bool
    description: str

    def y(self, u):
        """The displacement y(u)."""
        return self.derivs(u)[0]


def _u(u) -> np.ndarray:
    return np.asarray(u, dtype=float)


def _dwell(u):
    u = _u(u)
    z = np.zeros_like(u)
    return z, z.copy(), z.copy(), z.copy()


def _linear(u):
    u = _u(u)
    z = np.zeros_like(u)
    return u.copy(), np.ones_like(u), z, z.copy()


def _harmonic(u):
    """Simple harmonic motion: y = (1 - cos pi u) / 2 (Norton, Design of Machinery, sec. 8.3)."""
    u = _u(u)
    c, s = np.cos(_PI * u), np.sin(_PI * u)
    return (1 - c) / 2, _PI / 2 * s, _PI**2 / 2 * c, -(_PI**3) / 2 * s


def _cycloidal(u):
    """Cycloidal motion: y = u - sin(2 pi u) / (2 pi) (Norton, Design of Machinery, sec. 8.3)."""
    u = _u(u)
    c, s = np.cos(2 * _PI * u), np.sin(2 * _PI * u)
    return u - s / (2 * _PI), 1 - c, 2 * _PI * s, 4 * _PI**2 * c


def _poly(coeffs: dict[int, float]):
    """A polynomial y = sum c_k u**k and its first three derivatives."""

    def derivs(u):
        u = _u(u)
        out = [np.zeros_like(u) for _ in range(4)]
        for k, c in coeffs.items():
            for d in range(4):
                if k - d < 0:
                    break
                fac = math.perm(k, d)
                out[d] = out[d] + c * fac * u ** (k - d)
        return tuple(out)

    return derivs


#: 3-4-5 polynomial: y = 10 u^3 - 15 u^4 + 6 u^5 (Norton, Design of Machinery, sec. 8.3, "polynomial functions").
_p345 = _poly({3: 10.0, 4: -15.0, 5: 6.0})
#: 4-5-6-7 polynomial: y = 35 u^4 - 84 u^5 + 70 u^6 - 20 u^7 (same section).
_p4567 = _poly({4: 35.0, 5: -84.0, 6: 70.0, 7: -20.0})


def _piecewise_sinusoid(pieces):
    """Build y, y', y'', y''' from an acceleration made of pieces.

    ``pieces`` lists (u0, u1, k0, k1, k2, w): on [u0, u1] the acceleration is
    k0 + k1 sin(w t) + k2 cos(w t) with t = u - u0, for unit peak; it is
    integrated in closed form from y(0) = y'(0) = 0 and scaled so y(1) = 1.
    """
    starts = []
    v0 = s0 = 0.0
    for u0, u1, k0, k1, k2, w in pieces:
        starts.append((v0, s0))
        t = u1 - u0
        v1, s1 = _piece_vs(t, v0, s0, k0, k1, k2, w)
        v0, s0 = v1, s1
    scale = 1.0 / s0

    def derivs(u):
        u = _u(u)
        out = [np.zeros_like(u) for _ in range(4)]
        for (u0, u1, k0, k1, k2, w), (v0, s0) in zip(pieces, starts, strict=True):
            m = (u >= u0) & (u <= u1) if u1 == 1.0 else (u >= u0) & (u < u1)
            if not np.any(m):
                continue
            t = u[m] - u0
            v, s = _piece_vs(t, v0, s0, k0, k1, k2, w)
            a = k0 + k1 * np.sin(w * t) + k2 * np.cos(w * t)
            j = k1 * w * np.cos(w * t) - k2 * w * np.sin(w * t)
            for d, val in enumerate((s, v, a, j)):
                out[d][m] = scale * val
        return tuple(out)

    return derivs


def _piece_vs(t, v0, s0, k0, k1, k2, w):
    """Velocity and displacement of one acceleration piece after t."""
    if w == 0.0:
        a = k0 + k2
        return v0 + a * t, s0 + v0 * t + a * t * t / 2
    v = v0 + k0 * t + k1 * (1 - np.cos(w * t)) / w + k2 * np.sin(w * t) / w
    s = s0 + v0 * t + k0 * t * t / 2 + k1 * (t - np.sin(w * t) / w) / w + k2 * (1 - np.cos(w * t)) / w**2
    return v, s


#: Modified trapezoid: sine quarter-waves of period 1/2 joining constant-acceleration
#: pieces, each eighth of the segment (Norton, Design of Machinery, sec. 8.3, "modified trapezoidal").
_modtrap = _piecewise_sinusoid(
    [
        (0.0, 1 / 8, 0.0, 1.0, 0.0, 4 * _PI),
        (1 / 8, 3 / 8, 1.0, 0.0, 0.0, 0.0),
        (3 / 8, 5 / 8, 0.0, 0.0, 1.0, 4 * _PI),
        (5 / 8, 7 / 8, -1.0, 0.0, 0.0, 0.0),
        (7 / 8, 1.0, 0.0, 0.0, -1.0, 4 * _PI),
    ]
)
#: Modified sine: a sine quarter-wave of period 1/2 over the first and last eighths,
#: a sine of period 3/2 between (Norton, Design of Machinery, sec. 8.3, "modified sine").
_modsine = _piecewise_sinusoid(
    [
        (0.0, 1 / 8, 0.0, 1.0, 0.0, 4 * _PI),
        (1 / 8, 7 / 8, 0.0, 0.0, 1.0, 4 * _PI / 3),
        (7 / 8, 1.0, 0.0, 0.0, -1.0, 4 * _PI),
    ]
)

#: The registry of segment motions, by name.
MOTIONS: dict[str, Motion] = {
    m.name: m
    for m in (
        Motion("dwell", _dwell, False, "output at rest"),
        Motion("linear", _linear, True, "constant speed (velocity jumps at its ends)"),
        Motion("harmonic", _harmonic, True, "simple harmonic (acceleration jumps at its ends)"),
        Motion("cycloidal", _cycloidal, True, "cycloidal (zero acceleration at its ends)"),
        Motion("345", _p345, True, "3-4-5 polynomial"),
        Motion("4567", _p4567, True, "4-5-6-7 polynomial (zero jerk at its ends)"),
        Motion("modified-trapezoid", _modtrap, True, "modified trapezoidal acceleration"),
        Motion("modified-sine", _modsine, True, "modified sine acceleration"),
    )
}
