"""Oscillating (rocker) roller follower.

The pivot is at (D, 0), D the pivot distance; the arm of length L makes the
angle gamma with the line from the pivot to the cam centre, the roller centre
at q = (D - L cos gamma, L sin gamma).  At the law's lowest output the roller
sits on the prime circle Rb + Rr: cos gamma_0 = (D**2 + L**2 - (Rb + Rr)**2) / (2 D L)
(law of cosines); the law's output angle s turns the arm away from the cam,
gamma = gamma_0 + s.  Geometry as in J. J. Uicker, G. R. Pennock, J. E. Shigley,
*Theory of Machines and Mechanisms*, ch. 6 "Cam design" (oscillating roller follower).

What can be built: the pivot is the arm's shaft, fixed in the frame, and the
turning cam sweeps the whole disc of its largest radius R_max, so the pivot
must lie outside that disc over the whole cycle: D > R_max
(:func:`cam_radius_max`).  This is the bare geometric condition: no clearance
for the shaft's own radius is added, since the follower has no such dimension
here and we found no rule for one that we could check in R. L. Norton
(*Design of Machinery*, ch. 8) or H. A. Rothbart (*Cam Design Handbook*); a
designer adds the shaft's radius and a running clearance to D.  Sizing keeps to the base radii
below the one at which the cam reaches the pivot
(:meth:`OscillatingRoller.base_radius_bounds`).
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cams.followers._base import FollowerParams, RollerFollower, Unbuildable, need
from gearlever.errors import GearleverError

#: Pivot distances tried between the arm's assembly limits when a refusal says which one would clear the cam.
SUGGEST_GRID = 4000


def gamma0(p: FollowerParams, base_radius: float) -> float:
    """Arm angle at the law's lowest output (roller on the prime circle)."""
    D, L, rp = p.pivot_distance, p.arm, base_radius + p.roller_radius
    return math.acos((D * D + L * L - rp * rp) / (2 * D * L))


def _reach(D: float, L: float, g: float) -> float:
    """Distance from the cam centre to the roller centre with the arm at gamma (law of cosines)."""
    return math.sqrt(max(D * D + L * L - 2 * D * L * math.cos(g), 0.0))


def cam_radius_max(p: FollowerParams, base_radius: float, stroke: float) -> float:
    """The cam's largest radius: the roller centre's largest distance from the cam centre, less the roller.

    Notes
    -----
    The roller centre lies at sqrt(D**2 + L**2 - 2 D L cos gamma) from the cam
    centre (law of cosines in the triangle cam centre, pivot, roller centre),
    which grows with gamma on (0, pi): it is largest at the arm's farthest
    swing gamma_0 + stroke.  The cam is the pitch region shrunk by the roller
    radius Rr, so its largest radius is that distance less Rr (reached where
    the pitch curve's tangent is square to the radius).  The arm's pivot can
    be built only outside the disc the turning cam sweeps: D > R_max.

    Examples
    --------
    >>> p = FollowerParams(roller_radius=1.0, arm=4.0, pivot_distance=5.0)
    >>> round(cam_radius_max(p, 2.0, 0.0), 12)  # no stroke: the base circle
    2.0
    """
    return _reach(p.pivot_distance, p.arm, gamma0(p, base_radius) + stroke) - p.roller_radius


def _swing_limit(p: FollowerParams) -> float | None:
    """The largest arm angle gamma at which the cam still clears the pivot (None: any angle in (0, pi))."""
    D, L, rr = p.pivot_distance, p.arm, p.roller_radius
    c = (D * D + L * L - (D + rr) ** 2) / (2 * D * L)  # roller centre at D + Rr: the cam's radius is D
    if c <= -1.0:
        return None
    return math.acos(min(c, 1.0))


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
        r_cam = cam_radius_max(p, base_radius, stroke)
        if not D > r_cam:
            raise Unbuildable(
                f"{{pivot_distance}} {D:g}: the follower's pivot lies inside the cam, whose largest radius is "
                f"{r_cam:.6g} (base radius {base_radius:.6g}, {{arm}} {L:g}, {{roller_radius}} {p.roller_radius:g}, "
                f"stroke {math.degrees(stroke):.6g} deg): the turning cam would strike the pivot's shaft; "
                + self._what_would_do(p, base_radius, stroke),
                ("pivot_distance", "arm", "roller_radius"),
            )

    def _what_would_do(self, p, base_radius, stroke) -> str:
        """Which pivot distances clear the cam with the arm, roller and base radius given (message text)."""
        L, rp = p.arm, base_radius + p.roller_radius
        lo, hi = abs(rp - L), rp + L  # the arm reaches the prime circle in between

        def ok(d: float) -> bool:
            q = FollowerParams(p.roller_radius, p.offset, L, d)
            return gamma0(q, base_radius) + stroke < math.pi and d > cam_radius_max(q, base_radius, stroke)

        grid = np.linspace(lo, hi, SUGGEST_GRID + 2)[1:-1]
        k = next((k for k, d in enumerate(grid) if ok(float(d))), None)
        if k is None:
            return (
                f"no {{pivot_distance}} clears it with {{arm}} {L:g} (the arm reaches the base circle from "
                f"{lo:.6g} to {hi:.6g}): give a shorter {{arm}} or a smaller base radius"
            )
        a, b = (float(grid[k - 1]) if k else lo), float(grid[k])
        for _ in range(200):  # bisection to the smallest pivot distance that clears
            m = 0.5 * (a + b)
            if m in (a, b):
                break
            a, b = (a, m) if ok(m) else (m, b)
        return (
            f"a {{pivot_distance}} above {b:.6g} would clear it (up to {hi:.6g}, where the arm still reaches "
            f"the base circle), or give a shorter {{arm}} or a smaller base radius"
        )

    def base_radius_bounds(self, p, stroke):
        """Base radii the arm assembles with, below the one at which the cam reaches the pivot.

        Raises :class:`~gearlever.cams.followers._base.Unbuildable` when no base radius keeps the pivot
        outside the cam (the stroke swings the arm too far out for this pivot distance and arm).
        """
        D, L, rr = p.pivot_distance, p.arm, p.roller_radius
        lo, hi = max(0.0, abs(D - L) - rr), D + L - rr
        g_lim = _swing_limit(p)
        if g_lim is None:
            return lo, hi
        g0 = g_lim - stroke  # the arm's start angle must stay below it; gamma_0 grows with the base radius
        top = _reach(D, L, g0) - rr if g0 > 0 else -math.inf
        if not top > lo:
            raise Unbuildable(
                f"no base radius keeps the follower's pivot outside the cam: a stroke of {math.degrees(stroke):.6g} "
                f"deg swings the arm ({{arm}} {L:g}) so far out that the cam reaches the pivot at "
                f"{{pivot_distance}} {D:g} whatever its base radius; give a larger {{pivot_distance}} or a "
                "shorter {arm}",
                ("pivot_distance", "arm"),
            )
        return lo, min(hi, top)

    def bound_note(self, p, stroke, hi):
        D, L, rr = p.pivot_distance, p.arm, p.roller_radius
        return " (above it the cam reaches the follower's pivot)" if hi < D + L - rr else ""

    def path(self, s, p, base_radius):
        g = gamma0(p, base_radius) + s
        c, sn = np.cos(g), np.sin(g)
        L, D = p.arm, p.pivot_distance
        q = np.stack([D - L * c, L * sn], axis=-1)
        dq = np.stack([L * sn, L * c], axis=-1)
        d2q = np.stack([L * c, -L * sn], axis=-1)
        return q, dq, d2q
