"""The gear-lever differential mechanism (ZRDPM) of Alimukhamedov et al. (2020).

Two mirror-image contours, each a double-slider vector contour driving a lever
(the carrier of a two-gear differential):

* contour 1: leading gear 9 (angle ``phi``), carrier (lever) 1, driven gear 8,
  sliders B (on x) and A (on a y guide); analogues ``u_1, u_8, e_1, e_8`` and
  point accelerations ``a_B, a_A`` (paper eqs. 2-20, Table I);
* contour 2: leading gear 6, carrier (lever) 2, driven gear 7, points D (x)
  and E (y); ``u_2, u_7, e_2, e_7`` and ``a_D, a_E`` (eqs. 21-39, Table II).

Two models are provided, because the paper's own tables do not follow its
section-2 formulas (Tables I and II are eq. 16 with constant analogues):

* the **self-consistent model** (:func:`analogues`): the lever's analogues
  vary with ``phi`` (eq. 9 and its derivative), the lever angle is their
  integral, and eq. 16/35 gives the point accelerations from them;
* the **tables model** (:func:`tables_outputs`): eq. 16/35 evaluated with
  *constant* ``l u**2`` and ``l e`` and the lever at ``phi + theta0``; this is
  what Tables I and II were computed with.  Its constants are identified from
  the published values by least squares
  (:func:`~gearlever.zrdpm.published.identify_tables_constants`).

Angles are radians (``_deg`` only at the command line and in table
columns; ``lever_angle0_deg`` is kept as an alias keyword).  Lengths in cm.  All
kinematic functions take an array of angles and return arrays of its shape.
Contour 1 is drawn (and tabulated in the paper) with its x axis reversed
with respect to contour 2, the two contours being mirror images; this is the
``x_sign`` of :class:`ZrdpmContour` (-1 for contour 1, +1 for contour 2).

Modules: :mod:`~gearlever.zrdpm.parameters` (parameters and names), this
module (the two models), :mod:`~gearlever.zrdpm.fast` (their fast path),
:mod:`~gearlever.zrdpm.published` (the published tables, the identification
of their constants, the recovery of analogues).
"""

from __future__ import annotations

import math  # noqa: F401  (used by the doctests)

import numpy as np

from gearlever._validate import finite_array
from gearlever.errors import GearleverError
from gearlever.gears import willis
from gearlever.loops import closed
from gearlever.zrdpm.fast import fast_outputs
from gearlever.zrdpm.parameters import (
    ContourKinematics,
    TablesConstants,
    ZrdpmContour,
    x_sign,
)

# --------------------------------------------------------------------------
# the self-consistent model (paper section 2 as written)


def lever_angle(params: ZrdpmContour, phi) -> np.ndarray:
    """Angle of the lever (carrier 1 or 2) over the leading link's angle.

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Leading link angle(s), radians.

    Returns
    -------
    ndarray
        ``theta(phi) = theta0 + c (sin(phi) - cos(phi) + 1)``, radians.

    Notes
    -----
    The integral of eq. 9 (eq. 28-29 for lever 2), see
    :func:`gearlever.loops.closed.slider_lever`.

    Examples
    --------
    >>> float(lever_angle(ZrdpmContour(lever_angle0=0.0), 0.0))
    0.0
    """
    dtheta, _, _ = closed.slider_lever(params.l, params.r_a, params.r_b, phi)
    return params.lever_angle0 + dtheta


def analogues(params: ZrdpmContour, phi, *, block: int | None = None, out=None) -> ContourKinematics:
    """All six outputs of a contour by the self-consistent model.

    Parameters
    ----------
    params : ZrdpmContour
    phi : array_like
        Leading link angle(s) (``phi_9`` or ``phi_6``), radians.
    block : int, optional
        If given, use the fast path, a compiled kernel taking this many
        angles at a time (same results to rounding; see
        :func:`gearlever.zrdpm.fast.fast_outputs`).
    out : ndarray, optional
        Fast path only: a C-contiguous float64 array of shape
        ``(6, *phi.shape)`` to write the six outputs into (its rows are
        returned).

    Returns
    -------
    ContourKinematics

    Notes
    -----
    ``u_c = c (sin + cos)``, ``e_c = du_c/dphi`` (eqs. 9, 28-29); driven gear
    by Willis (eqs. 4, 14; 23, 33) with a uniformly turning leading link;
    point accelerations by eq. 16 / 35 at the lever angle of
    :func:`lever_angle`, x axis signed by :attr:`ZrdpmContour.x_sign`.

    Examples
    --------
    >>> k = analogues(ZrdpmContour(), [0.0])
    >>> float(k.u_carrier[0]), float(k.e_carrier[0]), float(k.u_gear[0])
    (1.0, 1.0, 1.0)
    """
    if not isinstance(params, ZrdpmContour):
        raise GearleverError(f"params must be a ZrdpmContour, got {type(params).__name__}")
    if block is not None:
        return fast_outputs(params, phi, None, block, out)
    if out is not None:
        raise GearleverError("out must be None unless block is given (the fast path)")
    dtheta, u_c, e_c = closed.slider_lever(params.l, params.r_a, params.r_b, phi)
    theta = params.lever_angle0 + dtheta
    u_g, e_g = willis.driven_analogues(u_c, e_c, params.ratio, params.mesh)
    a_x, a_y = closed.point_acceleration(params.l, theta, u_c, e_c)
    return ContourKinematics(u_c, u_g, e_c, e_g, params.x_sign * a_x, a_y)


def _named_contour(contour: int, params: ZrdpmContour | None, phi) -> dict:
    """The self-consistent model of ``contour`` (default parameters when None), by paper names."""
    params = ZrdpmContour(contour=contour) if params is None else params
    if params.contour != contour:
        raise GearleverError(f"params.contour must be {contour} for contour{contour}, got {params.contour}")
    return analogues(params, phi).named(contour)


def contour1(params: ZrdpmContour | None, phi) -> dict:
    """Contour 1 (gears 9, 8; lever 1) by the self-consistent model, by paper names.

    ``params`` None means the default ``ZrdpmContour(contour=1)``.  Returns a
    dict with ``u_1, u_8, e_1, e_8, a_B, a_A``, arrays shaped like ``phi``.

    Examples
    --------
    >>> sorted(contour1(None, [0.0]))
    ['a_A', 'a_B', 'e_1', 'e_8', 'u_1', 'u_8']
    """
    return _named_contour(1, params, phi)


def contour2(params: ZrdpmContour | None, phi) -> dict:
    """Contour 2 (gears 6, 7; lever 2) by the self-consistent model, by paper names.

    ``params`` None means the default ``ZrdpmContour(contour=2)``.  Returns a
    dict with ``u_2, u_7, e_2, e_7, a_D, a_E``, arrays shaped like ``phi``.

    Examples
    --------
    >>> sorted(contour2(None, [0.0]))
    ['a_D', 'a_E', 'e_2', 'e_7', 'u_2', 'u_7']
    """
    return _named_contour(2, params, phi)


# --------------------------------------------------------------------------
# the tables model (what Tables I and II were computed with)


def tables_point_accelerations(constants: TablesConstants, phi) -> tuple[np.ndarray, np.ndarray]:
    """Point accelerations of the tables model: eq. 16/35 with constant analogues.

    Parameters
    ----------
    constants : TablesConstants
    phi : array_like
        Leading link angle(s), radians.

    Returns
    -------
    a_x, a_y : ndarray
        ``a_B, a_A`` (contour 1) or ``a_D, a_E`` (contour 2), cm.

    Notes
    -----
    Paper eq. 16 (35) with ``l u**2`` and ``l e`` held constant and the lever
    at ``theta = phi + theta0`` (Tables I and II of the paper)::

        a_x = x_sign * (-(l u**2) cos(theta) - (l e) sin(theta))
        a_y = -(l u**2) sin(theta) + (l e) cos(theta)

    Evaluated with :func:`gearlever.loops.closed.point_acceleration` at unit
    length and ``u = sqrt(l u**2)``.

    Examples
    --------
    >>> ax, ay = tables_point_accelerations(TablesConstants(2, 1.0, 0.0), [math.pi / 2])
    >>> round(float(ax[0]), 12), round(float(ay[0]), 12)
    (-1.0, 0.0)
    """
    if not isinstance(constants, TablesConstants):
        raise GearleverError(f"constants must be TablesConstants, got {type(constants).__name__}")
    phi = finite_array("phi", phi)
    theta = phi + constants.lever_angle0
    a_x, a_y = closed.point_acceleration(1.0, theta, math.sqrt(constants.l_u2), constants.l_e)
    return x_sign(constants.contour) * a_x, a_y


def tables_outputs(
    params: ZrdpmContour, constants: TablesConstants, phi, *, block: int | None = None, out=None
) -> ContourKinematics:
    """All six outputs of a contour as the paper computed them for its tables.

    The carrier's and the gear's analogues follow eqs. 9-14 (they vary with
    ``phi``); the point accelerations use the constant analogues of
    :func:`tables_point_accelerations`.

    Parameters
    ----------
    params : ZrdpmContour
    constants : TablesConstants
        Same contour as ``params``.
    phi : array_like
        Radians.
    block : int, optional
        If given, use the fast path: a compiled kernel taking this many angles
        at a time, one sine and one cosine per angle, then the six outputs
        written in place; the results equal the plain path's to rounding
        (:func:`gearlever.zrdpm.fast.fast_outputs`).
    out : ndarray, optional
        Fast path only: a C-contiguous float64 array of shape
        ``(6, *phi.shape)`` to write the six outputs into (saves the
        allocation when called repeatedly).

    Returns
    -------
    ContourKinematics

    Notes
    -----
    Eqs. 9, 11, 14 (contour 1) / 29, 30, 33 (contour 2) and eq. 16 / 35 with
    constants.

    Examples
    --------
    >>> k = tables_outputs(ZrdpmContour(2), TablesConstants(2, 1.0, 0.0), [0.0, 1.0])
    >>> k2 = tables_outputs(ZrdpmContour(2), TablesConstants(2, 1.0, 0.0), [0.0, 1.0], block=1)
    >>> all(np.allclose(a, b, rtol=1e-12, atol=1e-12) for a, b in zip(k, k2))
    True
    """
    if not isinstance(params, ZrdpmContour):
        raise GearleverError(f"params must be a ZrdpmContour, got {type(params).__name__}")
    if not isinstance(constants, TablesConstants):
        raise GearleverError(f"constants must be TablesConstants, got {type(constants).__name__}")
    if constants.contour != params.contour:
        raise GearleverError(f"constants.contour must equal params.contour ({params.contour}), got {constants.contour}")
    if block is not None:
        return fast_outputs(params, phi, constants, block, out)
    if out is not None:
        raise GearleverError("out must be None unless block is given (the fast path)")
    _, u_c, e_c = closed.slider_lever(params.l, params.r_a, params.r_b, phi)
    u_g, e_g = willis.driven_analogues(u_c, e_c, params.ratio, params.mesh)
    a_x, a_y = tables_point_accelerations(constants, phi)
    return ContourKinematics(u_c, u_g, e_c, e_g, a_x, a_y)


__all__ = [
    "analogues",
    "contour1",
    "contour2",
    "lever_angle",
    "tables_outputs",
    "tables_point_accelerations",
]
