"""The car (bevel) differential: ring and pinion, carrier speed, torque split, power.

Members, numbered as in the source's model: pinion 1 (teeth ``Z1``), ring
gear and carrier 2 (teeth ``Z2``), planets 3 and 6, left side gear 4 and
right side gear 5 (equal teeth, driving the left and right wheels).

* Right-angle drive: ``w1*Z1 = w2*Z2`` and ``G1/G2 = Z1/Z2``.
* Differential: ``w2 = (w4 + w5)/2`` (Willis with equal side gears).
* Torques: ``G4 = G5 = G2/2`` (an open, loss-free differential).
* Power: ``G1*w1 = G2*w2 = G4*w4 + G5*w5``.

Speeds are in one unit throughout (rad/s, or rpm) and torques in one unit
(N m); power is torque times speed (W when speeds are in rad/s).  A turn's
radius is that of the axle mid-point, positive when turning left (centre of
the turn on the left, as the chariot's headings), so the left wheel is the
inner one; the track is the distance between the wheels' contact points.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from gearlever import _validate as V
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.networks import Differential, Gear, Mesh, Network


@dataclass(frozen=True)
class CarState(Result):
    """Speeds, torques and power of every loaded member (floats or arrays, broadcast)."""

    pinion_speed: np.ndarray | float
    carrier_speed: np.ndarray | float
    left_speed: np.ndarray | float
    right_speed: np.ndarray | float
    pinion_torque: np.ndarray | float
    ring_torque: np.ndarray | float
    left_torque: np.ndarray | float
    right_torque: np.ndarray | float

    @property
    def power_in(self):
        """Power fed in at the pinion, ``G1*w1``."""
        return self.pinion_torque * self.pinion_speed

    @property
    def power_out(self):
        """Power taken out at the wheels, ``G4*w4 + G5*w5``."""
        return self.left_torque * self.left_speed + self.right_torque * self.right_speed

    def summary(self) -> dict[str, float]:
        """Scalar results as plain floats (the CLI's json keys)."""
        keys = (
            "carrier_speed",
            "left_speed",
            "right_speed",
            "ring_torque",
            "left_torque",
            "right_torque",
            "power_in",
            "power_out",
        )
        return {k: float(getattr(self, k)) for k in keys}


def _arr(name, value):
    a = V.finite_array(name, value)
    return a if a.ndim else float(a)


def car_differential(
    pinion_teeth: int,
    ring_teeth: int,
    pinion_speed,
    pinion_torque,
    *,
    left_speed=None,
    turn_radius=None,
    track=None,
) -> CarState:
    """Speeds, torques and power of a car differential driven at the pinion.

    Parameters
    ----------
    pinion_teeth, ring_teeth : int
        ``Z1`` and ``Z2``.
    pinion_speed, pinion_torque : float or array_like
        ``w1`` and ``G1`` (arrays broadcast).
    left_speed : float or array_like, optional
        Left wheel speed ``w4`` (e.g. 0 for a wheel held); the right one follows.
    turn_radius, track : float, optional
        Give both for a turn of the axle mid-point (radius > 0 turns left,
        < 0 turns right; ``|radius| < track/2`` makes the inner wheel run
        backwards).  With neither ``left_speed`` nor a turn: a straight run.

    Returns
    -------
    CarState

    Examples
    --------
    One wheel held: the other runs at twice the carrier speed.

    >>> s = car_differential(10, 40, 100.0, 2.0, left_speed=0.0)
    >>> s.carrier_speed, s.right_speed, s.ring_torque, s.left_torque
    (25.0, 50.0, 8.0, 4.0)
    >>> s.power_in == s.power_out == 200.0
    True

    Notes
    -----
    Source (car differential model): ``w1 Z1 = w2 Z2``, ``G1/G2 = Z1/Z2``,
    ``w2 = (w4 + w5)/2``, ``G4 = G5 = G2/2``, ``P_in = P_out``.  In a turn of
    radius ``R`` the wheels' contact points run on radii ``R -/+ T/2`` at one
    yaw rate, so ``w4 = w2 (1 - T/(2R))`` and ``w5 = w2 (1 + T/(2R))``.
    """
    z1 = V.positive_int("pinion_teeth", pinion_teeth)
    z2 = V.positive_int("ring_teeth", ring_teeth)
    w1 = _arr("pinion_speed", pinion_speed)
    g1 = _arr("pinion_torque", pinion_torque)
    w2 = w1 * (z1 / z2)
    g2 = g1 * (z2 / z1)
    turning = turn_radius is not None or track is not None
    if left_speed is not None and turning:
        raise GearleverError("left_speed: give either left_speed or turn_radius with track, not both")
    if turning:
        if turn_radius is None or track is None:
            raise GearleverError("turn_radius and track must be given together")
        r = _arr("turn_radius", turn_radius)
        if np.any(np.asarray(r) == 0):
            raise GearleverError("turn_radius must be non-zero (a car cannot turn about its own mid-point)")
        t = V.positive("track", track)
        w4 = w2 * (1 - t / (2 * r))
    elif left_speed is not None:
        w4 = _arr("left_speed", left_speed) + 0 * w2
    else:
        w4 = w2
    w5 = 2 * w2 - w4
    return CarState(
        pinion_speed=w1 + 0 * w4,
        carrier_speed=w2 + 0 * w4,
        left_speed=w4,
        right_speed=w5,
        pinion_torque=g1,
        ring_torque=g2,
        left_torque=g2 / 2,
        right_torque=g2 / 2,
    )


def car_network(pinion_teeth: int, ring_teeth: int, side_teeth: int = 16) -> Network:
    """The car differential as a gear network (for the exact solver).

    Members ``pinion``, ``carrier`` (ring gear and carrier, teeth ``Z2``),
    ``left`` and ``right`` side gears (``side_teeth`` each).  The right-angle
    pair is a mesh with ``sign=-1`` because the source counts the pinion's and
    ring's rotations about axes chosen so that ``w1 Z1 = w2 Z2``.

    >>> sol = car_network(10, 40).solve(["pinion", "left"])
    >>> sol.relation("carrier"), sol.relation("right")
    ('rot_carrier = 1/4*rot_pinion', 'rot_right = 1/2*rot_pinion - rot_left')
    """
    z1 = V.positive_int("pinion_teeth", pinion_teeth)
    z2 = V.positive_int("ring_teeth", ring_teeth)
    zs = V.positive_int("side_teeth", side_teeth)
    gears = [Gear("pinion", z1), Gear("carrier", z2), Gear("left", zs), Gear("right", zs)]
    return Network(
        gears,
        [
            Mesh("ring_and_pinion", "pinion", "carrier", sign=-1),
            Differential("differential", "left", "right", "carrier"),
        ],
    )


def speed_ratio(pinion_teeth: int, ring_teeth: int) -> Fraction:
    """Exact carrier speed per pinion speed, ``Z1/Z2``.

    >>> speed_ratio(11, 41)
    Fraction(11, 41)
    """
    return Fraction(V.positive_int("pinion_teeth", pinion_teeth), V.positive_int("ring_teeth", ring_teeth))
