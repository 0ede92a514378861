"""Oscillating flat-faced follower.

The face is a straight line swinging about the pivot (D, 0): its normal
n_f = (sin gamma, cos gamma), the line n_f . x = D sin gamma - e, e the face's
distance from the pivot towards the cam.  At the law's lowest output it
touches the base circle: sin gamma_0 = (Rb + e) / D; the law's output angle
turns it away from the cam, gamma = gamma_0 + s.  Geometry as in J. J. Uicker,
G. R. Pennock, J. E. Shigley, *Theory of Machines and Mechanisms*, ch. 6
"Cam design" (oscillating flat-face follower).
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cams.followers._base import FlatFollower, FollowerParams, need
from gearlever.errors import GearleverError


def gamma0(p: FollowerParams, base_radius: float) -> float:
    """Face angle at the law's lowest output (touching the base circle)."""
    return math.asin((base_radius + p.offset) / p.pivot_distance)


class OscillatingFlat(FlatFollower):
    """Oscillating flat-faced follower pivoted at distance D.

    Examples
    --------
    >>> import numpy as np
    >>> p = FollowerParams(pivot_distance=10.0)
    >>> *_, h, dh, d2h = OscillatingFlat().face(np.array([0.0]), p, 5.0)
    >>> round(float(h[0]), 12)  # tangent to the base circle
    5.0
    """

    name = "oscillating-flat"
    law_output = "angle"
    needs = ("pivot_distance", "offset")
    bounded_by = ("pivot_distance", "offset")
    description = "flat face on a rocker pivoted at distance D (face offset e from the pivot)"

    def check(self, p, base_radius, stroke):
        D = need(p, "pivot_distance", "--pivot-distance", self.name)
        if not 0 < base_radius + p.offset < D:
            raise GearleverError(
                f"--pivot-distance {D:g} must exceed base radius + face offset = {base_radius + p.offset:g} "
                "(the pivot lies outside the base circle)"
            )
        if gamma0(p, base_radius) + stroke >= math.pi / 2:
            raise GearleverError(
                f"the law's stroke {math.degrees(stroke):g} deg turns the face past the perpendicular to the "
                f"pivot line (start at {math.degrees(gamma0(p, base_radius)):g} deg): use a larger --pivot-distance"
            )

    def base_radius_bounds(self, p, stroke):
        return max(0.0, -p.offset), p.pivot_distance - p.offset

    def face(self, s, p, base_radius):
        g = gamma0(p, base_radius) + s
        D = p.pivot_distance
        beta = math.pi / 2 - g
        one = np.ones_like(s)
        return beta, -one, 0 * one, D * np.sin(g) - p.offset, D * np.cos(g), -D * np.sin(g)

    def velocity_direction(self, c, p):
        r = c - np.array([p.pivot_distance, 0.0])
        u = np.stack([-r[:, 1], r[:, 0]], axis=-1)
        return u / np.linalg.norm(u, axis=-1, keepdims=True)

    def face_position(self, c, beta, p):
        # signed distance along the face from the pivot's foot, positive towards the cam centre's side
        r = c - np.array([p.pivot_distance, 0.0])
        return -r[:, 0] * np.sin(beta) + r[:, 1] * np.cos(beta)
