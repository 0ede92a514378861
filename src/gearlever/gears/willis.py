"""The Willis (inverted-motion) equation of a two-gear differential with a carrier.

A leading gear (pitch radius ``r_lead``) and a driven gear (``r_driven``) mesh
while their centres are carried by a carrier (in the ZRDPM: a lever).  Seen
from the carrier, the pair is an ordinary fixed-axis mesh, so

    (omega_driven - omega_carrier) / (omega_lead - omega_carrier) = i

with the signed basic ratio ``i = -r_lead/r_driven`` for an external mesh and
``i = +r_lead/r_driven`` for an internal one.  Everything here is linear in
the speeds, so the same relation holds for accelerations and for the
analogues (speeds and accelerations divided by the leading link's ``omega``
and ``omega**2``).

Pure numpy: arrays in, arrays out, any shape (broadcast).
"""

from __future__ import annotations

import numpy as np

from gearlever._validate import positive
from gearlever.errors import GearleverError

#: The two kinds of mesh a differential pair can have.
MESHES = ("external", "internal")


def basic_ratio(r_lead, r_driven, mesh="external"):
    """Signed ratio of the pair seen from the carrier (the Willis ratio).

    Parameters
    ----------
    r_lead, r_driven : float
        Pitch radii (or tooth numbers) of the leading and the driven gear (> 0).
    mesh : {"external", "internal"}
        External mesh reverses the sense of rotation, internal keeps it.

    Returns
    -------
    float
        ``-r_lead/r_driven`` (external) or ``+r_lead/r_driven`` (internal).

    Notes
    -----
    Paper eq. 2 (contour 1, ``i = -r9/r8``) and eq. 21 (contour 2,
    ``i = -r6/r7``); both contours of the paper have an external mesh.

    Examples
    --------
    >>> basic_ratio(2.0, 4.0)
    -0.5
    >>> basic_ratio(2.0, 4.0, "internal")
    0.5
    """
    r_lead = positive("r_lead", r_lead)
    r_driven = positive("r_driven", r_driven)
    return signed_ratio(r_lead / r_driven, mesh)


def signed_ratio(ratio, mesh="external") -> float:
    """The Willis ratio ``i`` from the unsigned ``ratio = r_lead/r_driven`` and the mesh.

    The one place where the sign rule lives: :func:`basic_ratio`,
    :func:`driven_speed`, :func:`driven_analogues`, :mod:`gearlever.zrdpm` and
    :func:`gearlever.loops.closed.zrdpm_contour_system` all use it.

    Parameters
    ----------
    ratio : float
        ``r_lead / r_driven`` (> 0).
    mesh : {"external", "internal"}

    Returns
    -------
    float
        ``-ratio`` (external mesh: the pair turns in opposite senses) or
        ``+ratio`` (internal).

    Notes
    -----
    Paper eq. 2 (``(omega_8 - omega_1)/(omega_9 - omega_1) = -r9/r8``) and
    eq. 21 for contour 2.

    Examples
    --------
    >>> signed_ratio(0.5), signed_ratio(0.5, "internal")
    (-0.5, 0.5)
    """
    ratio = positive("ratio", ratio)
    if mesh not in MESHES:
        raise GearleverError(f"mesh must be 'external' or 'internal', got {mesh!r}")
    return -ratio if mesh == "external" else ratio


_signed = signed_ratio


def willis_row(z_a: int, z_b: int, sign: int = 1) -> tuple[int, int, int]:
    """Willis' equation in tooth form: coefficients of ``rot_a, rot_b, rot_c``.

    ``z_a (rot_a - rot_c) + sign z_b (rot_b - rot_c) = 0``, so the row is
    ``(z_a, sign z_b, -(z_a + sign z_b))``: ``sign = 1`` for an external
    mesh (or the two side gears of a bevel differential seen from opposite
    sides), ``-1`` for an internal one.  It is :func:`signed_ratio` with
    ``ratio = z_a / z_b`` written without division, so that gear networks
    keep exact integers.

    Notes
    -----
    R. Willis, *Principles of Mechanism*, 2nd ed. (1870): the train seen from
    the carrier is an ordinary train; ZRDPM paper eq. 2; the generic
    differential ``n_a rot_a + n_b rot_b - (n_a + n_b) rot_c = 0`` of the
    Nuttall chariot page is the case ``sign = 1``.

    Examples
    --------
    >>> willis_row(20, 40), willis_row(20, 80, sign=-1)
    ((20, 40, -60), (20, -80, 60))
    """
    if sign not in (1, -1):
        raise GearleverError(f"sign must be 1 or -1, got {sign!r}")
    return (z_a, sign * z_b, -(z_a + sign * z_b))


def driven_speed(omega_lead, omega_carrier, ratio, mesh="external"):
    """Angular speed of the driven gear from the leading gear's and the carrier's.

    Parameters
    ----------
    omega_lead, omega_carrier : array_like
        Angular speeds (or accelerations, or their analogues) of the leading
        gear and of the carrier, in any consistent unit.
    ratio : float
        ``r_lead / r_driven`` (> 0): in the paper ``r9/r8`` or ``r6/r7``.
    mesh : {"external", "internal"}

    Returns
    -------
    ndarray
        ``omega_driven = (1 - i) omega_carrier + i omega_lead`` with the signed
        ratio ``i`` of :func:`basic_ratio`.

    Notes
    -----
    Paper eq. 3 (``omega_8 = (1 + r9/r8) omega_1 - (r9/r8) omega_9``), eq. 22
    for contour 2; by differentiation in time the same form gives the
    accelerations, eqs. 12-13 and 31-32.

    Examples
    --------
    >>> float(driven_speed(1.0, 0.0, 0.5))        # carrier at rest: plain ratio
    -0.5
    >>> float(driven_speed(3.0, 3.0, 0.5))        # all turning together
    3.0
    """
    i = _signed(ratio, mesh)
    omega_lead = np.asarray(omega_lead, dtype=float)
    omega_carrier = np.asarray(omega_carrier, dtype=float)
    return (1.0 - i) * omega_carrier + i * omega_lead


def willis_ratio(omega_driven, omega_lead, omega_carrier):
    """The ratio of the speeds relative to the carrier (the left side of eq. 2).

    Parameters
    ----------
    omega_driven, omega_lead, omega_carrier : array_like
        Angular speeds; ``omega_lead`` must differ from ``omega_carrier``.

    Returns
    -------
    ndarray
        ``(omega_driven - omega_carrier) / (omega_lead - omega_carrier)``.

    Notes
    -----
    Paper eq. 2 (and 21).  The ratio is undefined when the lead turns with the
    carrier; that is reported as an error instead of a division by zero.

    Examples
    --------
    >>> float(willis_ratio(-0.5, 1.0, 0.0))
    -0.5
    """
    omega_driven = np.asarray(omega_driven, dtype=float)
    omega_lead = np.asarray(omega_lead, dtype=float)
    omega_carrier = np.asarray(omega_carrier, dtype=float)
    rel = omega_lead - omega_carrier
    if np.any(rel == 0):
        raise GearleverError("omega_lead must differ from omega_carrier (the Willis ratio is undefined)")
    return (omega_driven - omega_carrier) / rel


def driven_analogues(u_carrier, e_carrier, ratio, mesh="external", e_lead=0.0):
    """Velocity and acceleration analogues of the driven gear.

    The generalized coordinate is the leading gear's angle, so its own
    analogues are ``u_lead = 1`` and ``e_lead`` (0 when it turns uniformly).

    Parameters
    ----------
    u_carrier, e_carrier : array_like
        Carrier's ``omega_c/omega_lead`` and ``epsilon_c/omega_lead**2``.
    ratio : float
        ``r_lead / r_driven`` (> 0).
    mesh : {"external", "internal"}
    e_lead : array_like, optional
        ``epsilon_lead/omega_lead**2`` (default 0, uniform leading link).

    Returns
    -------
    u_driven, e_driven : ndarray

    Notes
    -----
    Paper eq. 4 / 11 (``u_8 = (1 + r9/r8) u_1 - r9/r8``) and eq. 14
    (``e_8 = (1 + r9/r8) e_1 - (r9/r8) e_9``); eqs. 23, 30 and 33 for gear 7.

    Examples
    --------
    >>> u8, e8 = driven_analogues(1.0, 0.5, 0.5)
    >>> float(u8), float(e8)
    (1.0, 0.75)
    """
    i = _signed(ratio, mesh)
    u_carrier = np.asarray(u_carrier, dtype=float)
    e_carrier = np.asarray(e_carrier, dtype=float)
    e_lead = np.asarray(e_lead, dtype=float)
    return (1.0 - i) * u_carrier + i, (1.0 - i) * e_carrier + i * e_lead
