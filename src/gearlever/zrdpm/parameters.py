"""Parameters of the ZRDPM contours and the names of their outputs.

:class:`ZrdpmContour` (lengths, radii, gears, initial lever angle),
:class:`TablesConstants` (the constant analogues of the published tables),
:class:`ContourKinematics` (the six outputs), the paper's names
(:data:`PAPER_NAMES`) and :func:`x_sign`.  Radians and cm throughout; the
old keyword ``lever_angle0_deg`` is kept as an alias of ``lever_angle0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from gearlever._validate import finite, positive, positive_int
from gearlever.errors import GearleverError
from gearlever.gears import willis

__all__ = [
    "CONTOUR_OF_TABLE",
    "PAPER_NAMES",
    "TABLE_OF_CONTOUR",
    "ContourKinematics",
    "TablesConstants",
    "ZrdpmContour",
    "x_sign",
]

#: Paper names of the outputs per contour: (u carrier, u gear, e carrier,
#: e gear, point on x, point on y), and the published table of the contour.
PAPER_NAMES = {
    1: ("u_1", "u_8", "e_1", "e_8", "a_B", "a_A"),
    2: ("u_2", "u_7", "e_2", "e_7", "a_D", "a_E"),
}
TABLE_OF_CONTOUR = {1: "I", 2: "II"}
CONTOUR_OF_TABLE = {"I": 1, "II": 2}


def _check_contour(contour) -> int:
    if isinstance(contour, bool) or contour not in (1, 2):
        raise GearleverError(f"contour must be 1 or 2, got {contour!r}")
    return int(contour)


def x_sign(contour) -> float:
    """Direction of the x axis the contour is tabulated in: -1 for contour 1, +1 for 2.

    Notes
    -----
    Alimukhamedov et al. (2020), Tables I and II: Table I equals Table II with the x axis reversed
    (``a_B = -a_D``, ``a_A = a_E``), the two contours being mirror images.

    Examples
    --------
    >>> x_sign(1), x_sign(2)
    (-1.0, 1.0)
    """
    return -1.0 if _check_contour(contour) == 1 else 1.0


@dataclass(frozen=True)
class ZrdpmContour:
    """Parameters of one ZRDPM contour (lengths in cm).

    Parameters
    ----------
    contour : {1, 2}
        1: gears 9 (leading) and 8, lever 1, points B, A.  2: gears 6
        (leading) and 7, lever 2, points D, E.
    l : float
        Contour link length ``l1`` (or ``l2``), > 0.  The paper states none;
        the default 10 cm is ours.
    r : float
        Offset ``r1`` (``r2``) of the y guide (positions only).
    r_a, r_b : float or None
        Radii at which the two sliders act on the lever (``rA``, ``rB``;
        ``rE``, ``rD``), > 0.  None (the default) means ``l/2``, so that
        ``l = rA + rB`` and eq. 9 holds as printed (``u_1 = sin + cos``).
        The default is resolved at construction: ``dataclasses.replace(p,
        l=...)`` keeps the radii of ``p``.
    r_lead, r_driven : float
        Pitch radii of the leading and the driven gear (``r9, r8`` or
        ``r6, r7``), > 0.  Stated default: 2 and 4 cm, ratio 0.5.
    mesh : {"external", "internal"}
        Mesh of the gear pair (the paper's is external).
    lever_angle0 : float
        Lever angle at ``phi = 0``, radians (default ``-pi/2``, the tables'
        phase).  The keyword ``lever_angle0_deg`` (degrees) is accepted as an
        alias, and read back as a property.

    Notes
    -----
    Paper section 2 (contour 1, eqs. 2-20) and section 3 (contour 2,
    eqs. 21-39); lengths in cm, angles in radians.

    Examples
    --------
    >>> p = ZrdpmContour(contour=2)
    >>> p.ratio, p.x_sign
    (0.5, 1.0)
    >>> ZrdpmContour(l=20.0).r_a, ZrdpmContour(l=20.0).lever_gain
    (10.0, 1.0)
    """

    contour: int = 1
    l: float = 10.0
    r: float = 0.0
    r_a: float | None = None
    r_b: float | None = None
    r_lead: float = 2.0
    r_driven: float = 4.0
    mesh: str = "external"
    lever_angle0: float = -math.pi / 2

    def __post_init__(self):
        object.__setattr__(self, "contour", _check_contour(self.contour))
        ell = positive("l", self.l)
        for name in ("r_a", "r_b"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, ell / 2)
        for name in ("l", "r_a", "r_b", "r_lead", "r_driven"):
            object.__setattr__(self, name, positive(name, getattr(self, name)))
        for name in ("r", "lever_angle0"):
            object.__setattr__(self, name, finite(name, getattr(self, name)))
        if self.mesh not in willis.MESHES:
            raise GearleverError(f"mesh must be 'external' or 'internal', got {self.mesh!r}")

    @classmethod
    def from_teeth(cls, contour, z_lead, z_driven, module=1.0, **kwargs):
        """Build from tooth numbers: pitch radius = module * z / 2.

        >>> ZrdpmContour.from_teeth(1, 20, 40).ratio
        0.5
        """
        z_lead = positive_int("z_lead", z_lead)
        z_driven = positive_int("z_driven", z_driven)
        module = positive("module", module)
        return cls(contour=contour, r_lead=module * z_lead / 2, r_driven=module * z_driven / 2, **kwargs)

    def with_ratio(self, ratio):
        """A copy whose leading gear is resized to give ``r_lead/r_driven = ratio``.

        >>> ZrdpmContour().with_ratio(2.0).r_lead
        8.0
        """
        ratio = positive("ratio", ratio)
        return replace(self, r_lead=ratio * self.r_driven)

    @property
    def ratio(self) -> float:
        """``r_lead / r_driven`` (``r9/r8`` or ``r6/r7``)."""
        return self.r_lead / self.r_driven

    @property
    def signed_ratio(self) -> float:
        """Willis ratio ``i`` of the pair (:func:`gearlever.gears.willis.signed_ratio`)."""
        return willis.signed_ratio(self.ratio, self.mesh)

    @property
    def lever_angle0_deg(self) -> float:
        """:attr:`lever_angle0` in degrees (the old name, kept as an alias)."""
        return math.degrees(self.lever_angle0)

    @property
    def x_sign(self) -> float:
        """See :func:`x_sign`."""
        return x_sign(self.contour)

    @property
    def lever_gain(self) -> float:
        """``c = l / (r_a + r_b)``, the amplitude factor of eq. 9."""
        return self.l / (self.r_a + self.r_b)

    @property
    def names(self) -> tuple:
        """Paper names of the six outputs, see :data:`PAPER_NAMES`."""
        return PAPER_NAMES[self.contour]


@dataclass(frozen=True)
class TablesConstants:
    """Constant analogues with which the paper's tables were computed.

    Parameters
    ----------
    contour : {1, 2}
    l_u2 : float
        ``l * u**2`` of the lever, cm (>= 0).
    l_e : float
        ``l * e`` of the lever, cm.
    lever_angle0 : float
        The lever's angle is ``phi + lever_angle0``, radians (default
        ``-pi/2``).  The keyword ``lever_angle0_deg`` (degrees) is accepted as
        an alias, and read back as a property.

    Notes
    -----
    Alimukhamedov et al. (2020), Tables I and II (eq. 16 / 35 with constant
    analogues); identified by :func:`identify_tables_constants`.
    In the form ``a_x = A sin(phi) + B cos(phi)`` (Table I) the constants are
    ``A = l_u2`` and ``B = -l_e`` (see :attr:`A`, :attr:`B`).

    Examples
    --------
    >>> k = TablesConstants(1, 21.0, -2.24)
    >>> k.A, k.B, k.lever_angle0_deg
    (21.0, 2.24, -90.0)
    >>> TablesConstants(1, 21.0, -2.24, lever_angle0_deg=-90.0) == k
    True
    """

    contour: int
    l_u2: float
    l_e: float
    lever_angle0: float = -math.pi / 2

    def __post_init__(self):
        object.__setattr__(self, "contour", _check_contour(self.contour))
        if not isinstance(self.l_u2, (int, float)) or not math.isfinite(self.l_u2) or self.l_u2 < 0:
            raise GearleverError(f"l_u2 must be a non-negative finite number, got {self.l_u2!r}")
        object.__setattr__(self, "l_u2", float(self.l_u2))
        object.__setattr__(self, "l_e", finite("l_e", self.l_e))
        object.__setattr__(self, "lever_angle0", finite("lever_angle0", self.lever_angle0))

    @property
    def lever_angle0_deg(self) -> float:
        """:attr:`lever_angle0` in degrees (the old name, kept as an alias)."""
        return math.degrees(self.lever_angle0)

    @property
    def A(self) -> float:
        """Amplitude of the sine term of Table I's a_B (= ``l_u2``)."""
        return self.l_u2

    @property
    def B(self) -> float:
        """Amplitude of the cosine term of Table I's a_B (= ``-l_e``)."""
        return -self.l_e


class ContourKinematics(NamedTuple):
    """The six outputs of a contour, each an array shaped like ``phi``.

    ``u_carrier, u_gear, e_carrier, e_gear`` are ``u_1, u_8, e_1, e_8``
    (contour 1) or ``u_2, u_7, e_2, e_7`` (contour 2); ``a_x, a_y`` are
    ``a_B, a_A`` or ``a_D, a_E`` (cm, over the leading link's ``omega**2``).

    Examples
    --------
    >>> from gearlever.zrdpm import ZrdpmContour, analogues
    >>> k = analogues(ZrdpmContour(), [0.0])
    >>> float(k.u_carrier[0]), float(k.e_gear[0]), round(float(k.a_x[0]), 12)
    (1.0, 1.5, -10.0)
    """

    u_carrier: np.ndarray
    u_gear: np.ndarray
    e_carrier: np.ndarray
    e_gear: np.ndarray
    a_x: np.ndarray
    a_y: np.ndarray

    def named(self, contour) -> dict:
        """The outputs keyed by their paper names (``u_1``, ..., ``a_A``)."""
        return dict(zip(PAPER_NAMES[_check_contour(contour)], self))


def _accept_degrees_alias(cls):
    """Let ``cls(..., lever_angle0_deg=D)`` mean ``lever_angle0 = radians(D)`` (the old keyword)."""
    init = cls.__init__

    def __init__(self, *args, lever_angle0_deg=None, **kwargs):
        if lever_angle0_deg is not None:
            if "lever_angle0" in kwargs:
                raise GearleverError("give lever_angle0 (radians) or lever_angle0_deg (degrees), not both")
            kwargs["lever_angle0"] = math.radians(finite("lever_angle0_deg", lever_angle0_deg))
        init(self, *args, **kwargs)

    __init__.__doc__ = init.__doc__
    __init__.__wrapped__ = init
    cls.__init__ = __init__
    return cls


_accept_degrees_alias(ZrdpmContour)
_accept_degrees_alias(TablesConstants)
