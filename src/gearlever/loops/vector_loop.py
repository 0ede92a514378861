"""Closed-form vector contours and the kinematics of a point on a turning link.

Pure numpy: every function takes arrays of angles (radians, any shape) and
returns arrays of the same shape.  Derivatives are *analogues*: derivatives
with respect to the generalized coordinate ``phi`` (the angle of the leading
link), so that a time derivative is the analogue times ``omega`` (velocity)
or times ``omega**2`` (acceleration, at constant ``omega``).

Conventions
-----------
``x`` to the right, ``y`` up, angles counter-clockwise from ``+x``.
"""

from __future__ import annotations

import numpy as np

from gearlever._validate import finite, finite_array, positive


def double_slider(l, r, phi):
    """Projections of the double-slider contour O-A-B and their analogues.

    A link of length ``l`` at angle ``phi`` has its end B on the x axis and its
    end A on a guide parallel to y, offset by ``r``.

    Parameters
    ----------
    l : float
        Link length (> 0).
    r : float
        Offset of the y-guide's origin.
    phi : array_like
        Link angle(s), radians.

    Returns
    -------
    x_B, y_A, dx_B_dphi, dy_A_dphi, d2x_B_dphi2, d2y_A_dphi2 : ndarray
        Positions and their first and second analogues, each shaped like ``phi``.

    Notes
    -----
    Paper eq. 6 (contour 1) and eq. 25 (contour 2)::

        x_B = l cos(phi),          y_A = l sin(phi) + r
        dx_B/dphi = -l sin(phi),   dy_A/dphi = l cos(phi)          (eq. 7, 26)
        d2x_B/dphi2 = -l cos(phi), d2y_A/dphi2 = -l sin(phi)

    Examples
    --------
    >>> x, y, dx, dy, d2x, d2y = double_slider(2.0, 1.0, [0.0])
    >>> float(x[0]), float(y[0]), float(dx[0]), float(dy[0])
    (2.0, 1.0, -0.0, 2.0)
    """
    l = positive("l", l)
    r = finite("r", r)
    phi = finite_array("phi", phi)
    c, s = np.cos(phi), np.sin(phi)
    return l * c, l * s + r, -l * s, l * c, -l * c, -l * s


def point_acceleration(l, theta, u, e):
    """Acceleration analogues of the end of a link turning about its other end.

    Parameters
    ----------
    l : float
        Distance from the pivot to the point (> 0).
    theta : array_like
        Link angle, radians.
    u, e : array_like
        Velocity analogue ``dtheta/dphi`` and acceleration analogue
        ``d2theta/dphi2`` of the link (broadcast against ``theta``).

    Returns
    -------
    a_x, a_y : ndarray
        ``d2x/dphi2`` and ``d2y/dphi2`` of the point (accelerations over
        ``omega**2``, in the units of ``l``).

    Notes
    -----
    Paper eq. 16 (points B, A) and eq. 35 (points D, E)::

        a_x = -l cos(theta) u**2 - l sin(theta) e
        a_y = -l sin(theta) u**2 + l cos(theta) e

    Examples
    --------
    >>> ax, ay = point_acceleration(1.0, 0.0, 1.0, 0.0)   # centripetal only
    >>> float(ax), float(ay)
    (-1.0, 0.0)
    """
    l = positive("l", l)
    theta = finite_array("theta", theta)
    u = np.asarray(u, dtype=float)
    e = np.asarray(e, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    u2 = u * u
    return -l * (c * u2 + s * e), l * (c * e - s * u2)


def recover_analogues(l, theta, a_x, a_y):
    """Recover ``u**2`` and ``e`` of a link from both acceleration projections.

    Parameters
    ----------
    l : float
        Distance from the pivot to the point (> 0).
    theta : array_like
        Link angle, radians.
    a_x, a_y : array_like
        Acceleration analogues of the point (as from :func:`point_acceleration`).

    Returns
    -------
    u_squared, e : ndarray
        The squared velocity analogue and the acceleration analogue.

    Notes
    -----
    Paper eq. 17 (and 36) solves only the x line of eq. 16 for ``e`` and
    divides by ``sin(theta)``, which fails at 0 and 180 degrees.  Projecting
    eq. 16 on the link's normal and on the link itself instead::

        e    = ( cos(theta) a_y - sin(theta) a_x) / l
        u**2 = -(cos(theta) a_x + sin(theta) a_y) / l

    is the exact inverse, finite for every angle when ``l > 0``.

    Examples
    --------
    >>> u2, e = recover_analogues(1.0, 0.0, *point_acceleration(1.0, 0.0, 2.0, 0.5))
    >>> float(u2), float(e)
    (4.0, 0.5)
    """
    l = positive("l", l)
    theta = finite_array("theta", theta)
    a_x = np.asarray(a_x, dtype=float)
    a_y = np.asarray(a_y, dtype=float)
    c, s = np.cos(theta), np.sin(theta)
    return -(c * a_x + s * a_y) / l, (c * a_y - s * a_x) / l


def slider_lever(l, r_a, r_b, phi):
    """Turn and analogues of a lever driven by the two sliders of the double-slider contour.

    The slider A (speed ``dy_A/dphi``) and the slider B (``dx_B/dphi``) push a
    lever on opposite sides at radii ``r_a`` and ``r_b`` from its pivot.

    Parameters
    ----------
    l : float
        Contour link length (> 0).
    r_a, r_b : float
        Radii at which the sliders act on the lever (> 0).
    phi : array_like
        Angle(s) of the leading link, radians.

    Returns
    -------
    dtheta, dtheta_dphi, d2theta_dphi2 : ndarray
        The lever's turn since ``phi = 0``, its velocity analogue and its
        acceleration analogue, each shaped like ``phi``.

    Notes
    -----
    Paper eq. 8 (``omega_1 = (V_A - V_B)/(r_A + r_B)``) with eq. 7 gives eq. 9
    for ``l = r_A + r_B``; in general, with ``c = l/(r_A + r_B)``::

        dtheta/dphi   = c (sin(phi) + cos(phi))
        d2theta/dphi2 = c (cos(phi) - sin(phi))
        theta - theta(0) = c (sin(phi) - cos(phi) + 1)

    The paper's eqs. 10-11 print ``sin - cos``; eq. 9 and the mirror
    eqs. 28-30 print ``sin + cos``, which is what eqs. 7-8 give.  Contour 2's
    eq. 27 takes ``|V_E - V_D|``; the signed difference is used here, as in
    eq. 28.

    Examples
    --------
    >>> d, u, e = slider_lever(2.0, 1.0, 1.0, [0.0])
    >>> float(d[0]), float(u[0]), float(e[0])
    (0.0, 1.0, 1.0)
    """
    l = positive("l", l)
    r_a = positive("r_a", r_a)
    r_b = positive("r_b", r_b)
    phi = finite_array("phi", phi)
    c = l / (r_a + r_b)
    s, co = np.sin(phi), np.cos(phi)
    return c * (s - co + 1.0), c * (s + co), c * (co - s)
