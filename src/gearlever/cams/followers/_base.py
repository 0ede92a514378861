"""The two contact families of followers: a roller (its centre's path) and a flat face (its line).

A follower kind module defines one subclass of :class:`RollerFollower` or
:class:`FlatFollower`; :mod:`gearlever.cams.design` drives every kind through
these interfaces, never by name.

Frames: the cam turns counterclockwise by the input angle theta about the
origin of the fixed frame; the cam's own frame coincides with it at theta = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearlever.errors import GearleverError, a


class Unbuildable(GearleverError):
    """A follower layout that cannot be built (an oscillating roller's pivot inside the cam it follows).

    The message names the dimensions by their parameter names (``pivot_distance``); :meth:`named` says it with
    the names of another face: the command line's flags or a CAM file's ``[cam]`` keys.

    Examples
    --------
    >>> e = Unbuildable("{pivot_distance} 30 lies inside the cam", ["pivot_distance"])
    >>> str(e), e.named({"pivot_distance": "--pivot-distance"})
    ('pivot_distance 30 lies inside the cam', '--pivot-distance 30 lies inside the cam')
    """

    def __init__(self, template: str, names) -> None:
        self.template = template
        self.names = tuple(names)
        super().__init__(self.named({}))

    def named(self, names: dict) -> str:
        """The message with each dimension called ``names[dimension]`` (its parameter name when absent)."""
        return self.template.format(**{n: names.get(n, n) for n in self.names})


@dataclass(frozen=True)
class FollowerParams:
    """Follower dimensions (lengths in the cam's units).

    Attributes
    ----------
    roller_radius : float
        Roller radius (roller followers; 0 for flat ones).
    offset : float
        Translating followers: x of the follower axis (the cam centre at the
        origin, the follower moving along +y).  Oscillating flat: distance of
        the face line from the pivot, towards the cam.  Oscillating roller: unused (0).
    arm : float or None
        Oscillating roller: pivot to roller-centre length L.
    pivot_distance : float or None
        Oscillating followers: cam centre to pivot distance D (pivot at (D, 0)).

    Examples
    --------
    >>> FollowerParams(roller_radius=5.0).offset
    0.0
    """

    roller_radius: float = 0.0
    offset: float = 0.0
    arm: float | None = None
    pivot_distance: float | None = None


class FollowerKind:
    """A follower kind: its name, the law output it follows and the flags it needs.

    Examples
    --------
    >>> from gearlever.cams import FOLLOWERS
    >>> FOLLOWERS["oscillating-roller"].law_output
    'angle'
    """

    #: Registry name (the CLI's ``--follower``).
    name: str = ""
    #: Law output it follows: "displacement" (translating) or "angle" (oscillating).
    law_output: str = ""
    #: "roller" or "flat".
    contact: str = ""
    #: Parameters it needs besides the base radius (FollowerParams field names).
    needs: tuple = ()
    #: One line for listings.
    description: str = ""
    #: The dimensions that set the largest base radius it can assemble with (``base_radius_bounds``'s
    #: upper end), named when sizing finds no radius below that bound.
    bounded_by: tuple = ()

    def check(self, p: FollowerParams, base_radius: float, stroke: float) -> None:
        """Raise :class:`GearleverError` if the dimensions cannot assemble over the stroke."""

    def base_radius_bounds(self, p: FollowerParams, stroke: float) -> tuple[float, float]:
        """The open interval of base radii the kind can assemble with."""
        raise NotImplementedError

    def bound_note(self, p: FollowerParams, stroke: float, hi: float) -> str:
        """Why the base radius must stay below ``hi`` when it is not plain assembly (text after the number)."""
        return ""


class RollerFollower(FollowerKind):
    """A roller follower: the kind gives the roller centre's path q(s) in the fixed frame.

    Examples
    --------
    >>> from gearlever.cams import FOLLOWERS
    >>> [k for k, v in FOLLOWERS.items() if isinstance(v, RollerFollower)]
    ['translating-roller', 'oscillating-roller']
    """

    contact = "roller"

    def path(self, s: np.ndarray, p: FollowerParams, base_radius: float):
        """(q, dq/ds, d2q/ds2), each of shape (N, 2), at follower displacements s."""
        raise NotImplementedError


class FlatFollower(FollowerKind):
    """A flat-faced follower: the kind gives its face line n_f(s) . x = h(s) in the fixed frame.

    n_f = (cos beta, sin beta) is the face normal pointing away from the cam.

    Examples
    --------
    >>> from gearlever.cams import FOLLOWERS
    >>> [k for k, v in FOLLOWERS.items() if isinstance(v, FlatFollower)]
    ['translating-flat', 'oscillating-flat']
    """

    contact = "flat"

    def face(self, s: np.ndarray, p: FollowerParams, base_radius: float):
        """(beta, dbeta/ds, d2beta/ds2, h, dh/ds, d2h/ds2) at follower displacements s."""
        raise NotImplementedError

    def velocity_direction(self, c: np.ndarray, p: FollowerParams) -> np.ndarray:
        """Unit direction (N, 2) of the velocity of the follower's point at the contact c."""
        raise NotImplementedError

    def face_position(self, c: np.ndarray, beta: np.ndarray, p: FollowerParams) -> np.ndarray:
        """Where along the face the contact c lies (from the follower axis or the pivot)."""
        raise NotImplementedError


def need(p: FollowerParams, name: str, flag: str, kind: str) -> float:
    """The positive dimension ``name`` of ``p``, or a refusal naming ``flag``."""
    value = getattr(p, name)
    if value is None or not np.isfinite(value) or value <= 0:
        raise GearleverError(f"{flag} must be a positive length for {a(kind)} follower, got {value!r}")
    return float(value)
