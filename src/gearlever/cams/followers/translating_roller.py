"""Translating roller follower, offset allowed.

The roller centre moves along the line x = e (the offset), its height
y = d + s with d = sqrt((Rb + Rr)**2 - e**2) so that at s = 0 it sits on the
prime circle of radius Rb + Rr (R. L. Norton, *Design of Machinery*, sec. 8.6
"Sizing the cam": pressure angle phi = arctan((v - e) / (s + d))).
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cams.followers._base import RollerFollower, need
from gearlever.errors import GearleverError


class TranslatingRoller(RollerFollower):
    """Translating roller follower (offset e along x, moving along +y).

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.cams import FollowerParams
    >>> q, dq, d2q = TranslatingRoller().path(np.array([0.0, 2.0]), FollowerParams(roller_radius=5.0), 20.0)
    >>> q.tolist()
    [[0.0, 25.0], [0.0, 27.0]]
    """

    name = "translating-roller"
    law_output = "displacement"
    needs = ("roller_radius", "offset")
    description = "roller on a straight-line follower, offset allowed"

    def check(self, p, base_radius, stroke):
        need(p, "roller_radius", "--roller-radius", self.name)
        if base_radius + p.roller_radius <= abs(p.offset):
            raise GearleverError(
                f"--offset {p.offset:g} must be smaller than the prime-circle radius base + roller = "
                f"{base_radius + p.roller_radius:g}"
            )

    def base_radius_bounds(self, p, stroke):
        lo = max(0.0, abs(p.offset) - p.roller_radius)
        return lo, lo + 1e4 * max(stroke, p.roller_radius, abs(p.offset), 1e-300)

    def path(self, s, p, base_radius):
        d = math.sqrt((base_radius + p.roller_radius) ** 2 - p.offset**2)
        q = np.stack([np.full_like(s, p.offset), d + s], axis=-1)
        dq = np.stack([np.zeros_like(s), np.ones_like(s)], axis=-1)
        return q, dq, np.zeros_like(q)
