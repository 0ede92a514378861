"""Oscillating (rocker) roller follower.

The pivot is at (D, 0), D the pivot distance; the arm of length L makes the
angle gamma with the line from the pivot to the cam centre, the roller centre
at q = (D - L cos gamma, L sin gamma).  At the law's lowest output the roller
sits on the prime circle Rb + Rr: cos gamma_0 = (D**2 + L**2 - (Rb + Rr)**2) / (2 D L)
(law of cosines); the law's output angle s turns the arm away from the cam,
gamma = gamma_0 + s.  Geometry as in J. J. Uicker, G. R. Pennock, J. E. Shigley,
*Theory of Machines and Mechanisms*, ch. 6 "Cam design" (oscillating roller follower).
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cams.followers._base import FollowerParams, RollerFollower, need
from gearlever.errors import GearleverError


def gamma0(p: FollowerParams, base_radius: float) -> float:
    """Arm angle at the law's lowest output (roller on the prime circle)."""
    D, L, rp = p.pivot_distance, p.arm, base_radius + p.roller_radius
    return math.acos((D * D + L * L - rp * rp) / (2 * D * L))


class OscillatingRoller(RollerFollower):
    """Oscillating roller follower (arm L about a pivot at distance D).

    Examples
    --------
    >>> import numpy as np
    >>> p = FollowerParams(roller_radius=1.0, arm=4.0, pivot_distance=5.0)
    >>> q, _, _ = OscillatingRoller().path(np.array([0.0]), p, 2.0)
    >>> round(float(np.hypot(*q[0])), 12)  # on the prime circle Rb + Rr
    3.0
    """

    name = "oscillating-roller"
    law_output = "angle"
    needs = ("roller_radius", "arm", "pivot_distance")
    bounded_by = ("pivot_distance", "arm")
    description = "roller on a rocker arm L pivoted at distance D"

    def check(self, p, base_radius, stroke):
        need(p, "roller_radius", "--roller-radius", self.name)
        D = need(p, "pivot_distance", "--pivot-distance", self.name)
        L = need(p, "arm", "--arm", self.name)
        rp = base_radius + p.roller_radius
        if not abs(D - L) < rp < D + L:
            raise GearleverError(
                f"--arm {L:g} and --pivot-distance {D:g} cannot reach the prime circle base + roller = {rp:g} "
                f"(it must lie between |D - L| = {abs(D - L):g} and D + L = {D + L:g})"
            )
        if gamma0(p, base_radius) + stroke >= math.pi:
            raise GearleverError(
                f"the law's stroke {math.degrees(stroke):g} deg swings the arm past the line through the cam "
                f"centre (start at {math.degrees(gamma0(p, base_radius)):g} deg from it): use a larger --pivot-distance"
            )

    def base_radius_bounds(self, p, stroke):
        D, L = p.pivot_distance, p.arm
        return max(0.0, abs(D - L) - p.roller_radius), D + L - p.roller_radius

    def path(self, s, p, base_radius):
        g = gamma0(p, base_radius) + s
        c, sn = np.cos(g), np.sin(g)
        L, D = p.arm, p.pivot_distance
        q = np.stack([D - L * c, L * sn], axis=-1)
        dq = np.stack([L * sn, L * c], axis=-1)
        d2q = np.stack([L * c, -L * sn], axis=-1)
        return q, dq, d2q
