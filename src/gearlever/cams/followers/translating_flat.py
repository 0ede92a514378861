"""Translating flat-faced follower.

The face is the line y = Rb + s, perpendicular to the follower's travel; it
touches the cam at x = ds/dtheta and the cam's radius of curvature there is
rho = Rb + s + s'' (R. L. Norton, *Design of Machinery*, sec. 8.6, flat-faced
follower: undercut where rho < 0); the pressure angle is zero.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cams.followers._base import FlatFollower


class TranslatingFlat(FlatFollower):
    """Translating flat-faced follower, face perpendicular to its travel along +y.

    Examples
    --------
    >>> import numpy as np
    >>> from gearlever.cams import FollowerParams
    >>> beta, *_, h, dh, d2h = TranslatingFlat().face(np.array([0.0, 2.0]), FollowerParams(), 20.0)
    >>> h.tolist()
    [20.0, 22.0]
    """

    name = "translating-flat"
    law_output = "displacement"
    needs = ("offset",)
    description = "flat face perpendicular to a straight-line follower"

    def base_radius_bounds(self, p, stroke):
        return 0.0, 1e4 * max(stroke, 1e-300)

    def face(self, s, p, base_radius):
        z = np.zeros_like(s)
        return z + math.pi / 2, z, z, base_radius + s, np.ones_like(s), z

    def velocity_direction(self, c, p):
        return np.broadcast_to(np.array([0.0, 1.0]), c.shape)

    def face_position(self, c, beta, p):
        return c[:, 0] - p.offset
