"""Velocity ratio and sense of rotation of a train of wheels.

A simple or compound train is a chain of meshes.  Mesh ``i`` (counted from 1)
joins a driver of ``drivers[i-1]`` teeth to a follower of ``followers[i-1]``
teeth; the follower of one mesh turns on the same axis as the driver of the
next.  The velocity ratio of the last axis to the first is the product of the
drivers' teeth over the product of the followers' teeth (the classic text on
trains of wheelwork, page marked (41)).  An external mesh reverses the sense of rotation, an internal one (a
pinion inside an annulus) keeps it.

An idler is a single wheel that is the follower of one mesh and the driver of
the next: its teeth appear once above and once below the fraction and cancel,
and it adds one external mesh.  It can be given either way: inside
``drivers``/``followers`` (the cancellation then happens in the product), or
through ``idlers`` (tooth numbers of idlers placed in external meshes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

from gearlever import _validate
from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = ["TrainRatio", "train_ratio"]


@dataclass(frozen=True)
class TrainRatio(Result):
    """Result of :func:`train_ratio`.

    Attributes
    ----------
    drivers, followers : tuple of int
        Teeth of the drivers and followers, mesh by mesh (idlers not included).
    idlers : tuple of int
        Teeth of the idlers given separately.
    internal_meshes : tuple of int
        Mesh numbers (from 1) that are internal.
    magnitude : Fraction
        ``|omega_last / omega_first|`` = prod(drivers) / prod(followers), exact.
    sense : int
        +1 if the last axis turns the same way as the first, -1 if reversed.
    external_meshes : int
        Number of external meshes, idlers' meshes included.

    Examples
    --------
    >>> t = train_ratio([20, 30], [60, 45])
    >>> t.magnitude, t.sense
    (Fraction(2, 9), 1)
    """

    drivers: tuple[int, ...]
    followers: tuple[int, ...]
    idlers: tuple[int, ...]
    internal_meshes: tuple[int, ...]
    magnitude: Fraction
    sense: int
    external_meshes: int

    @property
    def ratio(self) -> Fraction:
        """Signed exact ratio omega_last / omega_first."""
        return self.sense * self.magnitude

    @property
    def value(self) -> float:
        """Signed ratio as a float."""
        return float(self.ratio)

    def summary(self) -> dict:
        """JSON-ready record (the command line's json): exact ratio ``"p/q"``, its float and sense."""
        return {
            "drivers": list(self.drivers),
            "followers": list(self.followers),
            "idlers": list(self.idlers),
            "internal_meshes": list(self.internal_meshes),
            "ratio": f"{self.magnitude.numerator}/{self.magnitude.denominator}",
            "ratio_float": float(self.magnitude),
            "sense": "same" if self.sense > 0 else "reversed",
            "signed_ratio_float": self.value,
            "external_meshes": self.external_meshes,
        }


def _teeth(name: str, values) -> tuple[int, ...]:
    try:
        seq = list(values)
    except TypeError:
        raise GearleverError(f"{name} must be a sequence of positive integers, got {values!r}") from None
    return tuple(_validate.positive_int(name, v) for v in seq)


def train_ratio(drivers, followers, internal=(), idlers=()) -> TrainRatio:
    """Exact velocity ratio and sense of rotation of a train of wheels.

    Parameters
    ----------
    drivers, followers : sequence of int
        Teeth of the driver and of the follower of each mesh, in order; the
        two sequences have the same length (at least one mesh).
    internal : sequence of int, optional
        Numbers (counted from 1) of the meshes that are internal.
    idlers : sequence of int, optional
        Teeth of idlers, each placed in an external mesh: each cancels out of
        the ratio and adds one external mesh.

    Returns
    -------
    TrainRatio

    Notes
    -----
    omega_last / omega_first = (-1)**e * prod(N_drivers) / prod(n_followers),
    with e the number of external meshes (the classic text on trains of
    wheelwork, page marked (41): the
    ratio is the product of the drivers' teeth over that of the followers';
    with all gearing outside, each mesh reverses the sense, so m axes keep it
    when m is odd).

    Examples
    --------
    >>> r = train_ratio([20, 30], [60, 45])
    >>> r.magnitude, r.sense
    (Fraction(2, 9), 1)
    >>> train_ratio([20, 30], [60, 45], internal=[2]).sense
    -1
    >>> train_ratio([20], [60], idlers=[37]).sense
    1
    """
    drivers = _teeth("drivers", drivers)
    followers = _teeth("followers", followers)
    if not drivers:
        raise GearleverError("drivers must hold at least one tooth number, got none")
    if len(drivers) != len(followers):
        raise GearleverError(f"followers must have as many entries as drivers ({len(drivers)}), got {len(followers)}")
    idlers = _teeth("idlers", idlers)
    internal_list = _teeth("internal", internal)
    for i in internal_list:
        if i > len(drivers):
            raise GearleverError(f"internal must hold mesh numbers from 1 to {len(drivers)}, got {i}")
    if len(set(internal_list)) != len(internal_list):
        raise GearleverError(f"internal must not repeat a mesh number, got {list(internal_list)}")
    internal_set = tuple(sorted(internal_list))
    magnitude = Fraction(math.prod(drivers), math.prod(followers))
    external = len(drivers) - len(internal_set) + len(idlers)
    sense = -1 if external % 2 else 1
    return TrainRatio(
        drivers=drivers,
        followers=followers,
        idlers=idlers,
        internal_meshes=internal_set,
        magnitude=magnitude,
        sense=sense,
        external_meshes=external,
    )
