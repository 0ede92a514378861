"""Closed-form loops: slider-crank, inverted slider-crank, the ZRDPM double slider.

The one home of the ZRDPM contour's closed forms (paper eqs. 6-9, 16-17):
:func:`double_slider_projections`, :func:`slider_lever`,
:func:`point_acceleration`, :func:`recover_analogues`; :func:`double_slider`,
:func:`zrdpm_contour` and :mod:`gearlever.zrdpm` use them.  Derivatives are
*analogues*: derivatives with respect to the input angle ``phi``.

Each mechanism comes as a :class:`~gearlever.loops.engine.LoopSystem` (the
general form, used for plans and for checking) and as a solver that finds the
positions in closed form and the analogues by the batched linear solves of
the same system (or in closed form, for the double slider).

Pure numpy.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._validate import finite, finite_array, positive
from gearlever.errors import ClosureError, GearleverError
from gearlever.gears.willis import signed_ratio
from gearlever.loops.engine import INPUT, Input, LoopSolution, LoopSystem, Unknown, Vector

__all__ = [
    "slider_crank_system",
    "slider_crank",
    "inverted_slider_crank_system",
    "inverted_slider_crank",
    "double_slider_system",
    "double_slider",
    "zrdpm_contour_system",
    "zrdpm_contour",
    "double_slider_projections",
    "slider_lever",
    "point_acceleration",
    "recover_analogues",
]

_SIGN = {"open": 1.0, "crossed": -1.0}


def _sigma(branch):
    try:
        return _SIGN[branch]
    except (KeyError, TypeError):
        raise GearleverError(f"branch must be 'open' or 'crossed', got {branch!r}") from None


def _finish(system, phi, x, closed, strict, singular_tol, what):
    x = np.where(closed[..., None], x, np.nan)
    dx, d2x, bad = system.analogues(phi, x, singular_tol)
    valid = closed & ~bad
    if strict and not valid.all():
        first = phi.reshape(-1)[int(np.flatnonzero(~valid.reshape(-1))[0])]
        raise ClosureError(
            f"phi: the {what} cannot close or is at a dead point at {first!r} "
            f"({int((~valid).sum())} of {valid.size} points)"
        )
    return LoopSolution(system.unknowns, phi, x, dx, d2x, valid, closed)


def slider_crank_system(crank, rod, offset=0.0) -> LoopSystem:
    """Offset slider-crank as a loop: ``r_A + r_BA = offset*j + x_B``.

    Vectors ``A`` (crank, input angle), ``BA`` (rod, unknown ``theta3``),
    ``e`` (offset, fixed at 90 degrees, sign -1), ``B`` (slider, unknown
    length ``x_B`` along x, sign -1).

    Examples
    --------
    >>> slider_crank_system(1.0, 3.0).unknowns
    ('theta3', 'x_B')
    """
    a, b = positive("crank", crank), positive("rod", rod)
    e = finite("offset", offset)
    return LoopSystem(
        [
            [
                Vector("A", a, INPUT),
                Vector("BA", b, "theta3"),
                Vector("e", e, math.pi / 2, -1),
                Vector("B", "x_B", 0.0, -1),
            ]
        ]
    )


def slider_crank(crank, rod, phi, offset=0.0, branch="open", *, strict=False, singular_tol=1e-7) -> LoopSolution:
    """Slider-crank positions (closed form) and analogues (linear solves).

    Parameters
    ----------
    crank, rod : float
        Crank and connecting-rod lengths (> 0).
    phi : array_like
        Crank angles, radians.
    offset : float
        Height of the slider's line above the crank pivot.
    branch : {"open", "crossed"}
        ``"open"``: slider to the right of the rod's pin A (``cos theta3 > 0``).

    Returns
    -------
    LoopSolution
        Unknowns ``theta3`` (rad) and ``x_B`` (length).

    Notes
    -----
    ``a sin(phi) + b sin(theta3) = offset`` gives ``theta3``, and
    ``x_B = a cos(phi) + b cos(theta3)`` (Norton, eq. 4.16).  Dead points
    where ``cos(theta3) = 0``.

    Examples
    --------
    >>> s = slider_crank(1.0, 3.0, [0.0, np.pi])
    >>> s["x_B"].tolist()
    [4.0, 2.0]
    """
    system = slider_crank_system(crank, rod, offset)
    a, b, e = float(crank), float(rod), float(offset)
    sigma = _sigma(branch)
    th2 = finite_array("phi", phi)
    s3 = (e - a * np.sin(th2)) / b
    closed = np.abs(s3) <= 1.0
    s3c = np.clip(s3, -1.0, 1.0)
    c3 = sigma * np.sqrt(1.0 - s3c * s3c)
    theta3 = np.arctan2(s3c, c3)
    xb = a * np.cos(th2) + b * c3
    return _finish(system, th2, np.stack([theta3, xb], axis=-1), closed, strict, singular_tol, "slider-crank")


def inverted_slider_crank_system(ground, crank, offset=0.0) -> LoopSystem:
    """Inverted slider-crank as a loop: ``r_A = r_O4 + b e^{i theta4} + offset e^{i(theta4 + pi/2)}``.

    The crank pin A slides along link 4 (through O4, at ``(ground, 0)``);
    ``b`` is the slide distance, ``offset`` the perpendicular offset of the
    slide from O4.  Unknowns ``theta4`` and ``b``.

    Examples
    --------
    >>> inverted_slider_crank_system(2.0, 1.0).unknowns
    ('b', 'theta4')
    """
    d, a = positive("ground", ground), positive("crank", crank)
    e = finite("offset", offset)
    return LoopSystem(
        [
            [
                Vector("A", a, INPUT),
                Vector("O4", d, 0.0, -1),
                Vector("AO4", "b", "theta4", -1),
                Vector("e", e, Unknown("theta4", math.pi / 2), -1),
            ]
        ]
    )


def inverted_slider_crank(
    ground, crank, phi, offset=0.0, branch="open", *, strict=False, singular_tol=1e-7
) -> LoopSolution:
    """Inverted slider-crank positions (closed form) and analogues (linear solves).

    Returns
    -------
    LoopSolution
        Unknowns ``b`` (slide distance, > 0 on the open branch) and ``theta4``.

    Notes
    -----
    With ``P = r_A - r_O4``: ``(b + i offset) e^{i theta4} = P``, so
    ``b = sigma sqrt(|P|^2 - offset^2)`` and
    ``theta4 = arg(P) - arg(b + i offset)`` (Norton, sec. 4.9).  Dead point
    where ``b = 0``.

    Examples
    --------
    >>> s = inverted_slider_crank(2.0, 1.0, [0.0])
    >>> s["b"].tolist(), s["theta4"].round(12).tolist()
    ([1.0], [3.14159265359])
    """
    system = inverted_slider_crank_system(ground, crank, offset)
    d, a, e = float(ground), float(crank), float(offset)
    sigma = _sigma(branch)
    th2 = finite_array("phi", phi)
    px, py = a * np.cos(th2) - d, a * np.sin(th2)
    q = px * px + py * py - e * e
    closed = q >= 0
    b = sigma * np.sqrt(np.where(closed, q, 0.0))
    theta4 = np.arctan2(py, px) - np.arctan2(e, b)
    theta4 = np.arctan2(np.sin(theta4), np.cos(theta4))
    return _finish(system, th2, np.stack([b, theta4], axis=-1), closed, strict, singular_tol, "inverted slider-crank")


def double_slider_system(l, r) -> LoopSystem:
    """The ZRDPM double-slider contour O-A-B (paper eq. 5) as a loop.

    B slides on the x axis (unknown ``x_B``), A on a guide parallel to y
    (unknown ``y_A``, measured from a point offset by ``r``), and the link
    ``BA`` (``r_B - r_A``) of length ``l`` is at angle ``-phi``::

        x_B e^{i0} + r e^{i pi/2} - y_A e^{i pi/2} - l e^{-i phi} = 0

    so that ``r_B = r_A + r_BA`` (eq. 19's form) and ``x_B = l cos(phi)``,
    ``y_A = l sin(phi) + r`` (eq. 6).

    Examples
    --------
    >>> double_slider_system(21.0, 0.0).unknowns
    ('x_B', 'y_A')
    """
    l = positive("l", l)
    r = finite("r", r)
    return LoopSystem(
        [
            [
                Vector("B", "x_B", 0.0),
                Vector("r", r, math.pi / 2),
                Vector("A", "y_A", math.pi / 2, -1),
                Vector("BA", l, Input(-1.0, 0.0), -1),
            ]
        ]
    )


def double_slider(l, r, phi) -> LoopSolution:
    """Double-slider contour in closed form (:func:`double_slider_projections`) as a LoopSolution.

    Returns
    -------
    LoopSolution
        Unknowns ``x_B`` and ``y_A`` with their analogues; always valid.

    Notes
    -----
    Paper eqs. 6-7 (contour 1) and 25-26 (contour 2), via
    :func:`double_slider_projections`.

    Examples
    --------
    >>> s = double_slider(2.0, 1.0, [0.0])
    >>> s["x_B"].tolist(), s["y_A"].tolist(), s.d1("y_A").tolist()
    ([2.0], [1.0], [2.0])
    """
    system = double_slider_system(l, r)
    phi = finite_array("phi", phi)
    xb, ya, dxb, dya, d2xb, d2ya = double_slider_projections(l, r, phi)
    x = np.stack([xb, ya], axis=-1)
    dx = np.stack([dxb, dya], axis=-1)
    d2x = np.stack([d2xb, d2ya], axis=-1)
    ok = np.ones(phi.shape, dtype=bool)
    return LoopSolution(system.unknowns, phi, x, dx, d2x, ok, ok.copy())


def zrdpm_contour_system(
    l, r=0.0, r_a=None, r_b=None, ratio=0.5, mesh="external", lever_angle0=-math.pi / 2
) -> LoopSystem:
    """A whole ZRDPM contour (paper section 2) as four vector loops.

    Parameters
    ----------
    l, r : float
        Contour link length (> 0) and y-guide offset (paper ``l1, r1``).
    r_a, r_b : float, optional
        Radii at which the sliders act on the lever (default ``l/2`` each).
    ratio : float
        Gear ratio ``r9/r8`` (> 0).
    mesh : {"external", "internal"}
    lever_angle0 : float
        Lever angle at ``phi = 0``, radians.

    Returns
    -------
    LoopSystem
        Unknowns ``x_B, y_A`` (sliders), ``theta1`` (lever), ``w1``
        (a zero slack), ``p_x, p_y`` (the lever's point at distance ``l``),
        ``theta8`` (driven gear), ``w8`` (a zero slack).

    Notes
    -----
    Loop 1: the double slider of eq. 5-6 (see :func:`double_slider_system`).
    Loop 2: the sliders turn the lever, ``(rA + rB) theta1 = y_A - x_B + K``
    (eq. 8 integrated; ``K`` puts the lever at ``lever_angle0`` for
    ``phi = 0``), written as collinear vectors with a zero slack ``w1`` for
    the second component.  Loop 3: the lever's point
    ``l e^{i theta1} = p_x + i p_y``, whose second analogues are eq. 16.
    Loop 4: Willis, ``theta8 = (1 - i) theta1 + i phi`` with ``i = -ratio``
    (external) or ``+ratio`` (internal) (eqs. 3, 13).

    Examples
    --------
    >>> zrdpm_contour_system(10.0).unknowns
    ('x_B', 'y_A', 'theta1', 'w1', 'p_x', 'p_y', 'theta8', 'w8')
    """
    l = positive("l", l)
    r = finite("r", r)
    r_a = l / 2 if r_a is None else positive("r_a", r_a)
    r_b = l / 2 if r_b is None else positive("r_b", r_b)
    ratio = positive("ratio", ratio)
    i = signed_ratio(ratio, mesh)  # Willis' sign rule, gears/willis.py
    th0 = finite("lever_angle0", lever_angle0)
    K = (r_a + r_b) * th0 - r + l
    return LoopSystem(
        [
            [
                Vector("B", "x_B", 0.0),
                Vector("r", r, math.pi / 2),
                Vector("A", "y_A", math.pi / 2, -1),
                Vector("BA", l, Input(-1.0, 0.0), -1),
            ],
            [
                Vector("lever", Unknown("theta1", 0.0, r_a + r_b), 0.0),
                Vector("yA", "y_A", 0.0, -1),
                Vector("xB", "x_B", 0.0),
                Vector("K", K, 0.0, -1),
                Vector("w1", "w1", math.pi / 2),
            ],
            [Vector("L1", l, "theta1"), Vector("px", "p_x", 0.0, -1), Vector("py", "p_y", math.pi / 2, -1)],
            [
                Vector("gear8", "theta8", 0.0),
                Vector("carrier", Unknown("theta1", 0.0, 1.0 - i), 0.0, -1),
                Vector("lead", Input(i, 0.0), 0.0, -1),
                Vector("w8", "w8", math.pi / 2),
            ],
        ]
    )


def zrdpm_contour(
    l, phi, r=0.0, r_a=None, r_b=None, ratio=0.5, mesh="external", lever_angle0=-math.pi / 2, *, strict=False
) -> LoopSolution:
    """Solve :func:`zrdpm_contour_system` over ``phi`` with the batched Newton engine.

    Parameters are those of :func:`zrdpm_contour_system`; ``phi`` is the
    leading gear's angle (radians, any shape, in path order).  ``strict``
    raises :class:`~gearlever.errors.ClosureError` where the loops cannot
    close (never, for this contour) instead of returning NaN.

    The seed at ``phi[0]`` is the sliders' position of eq. 6 with the lever at
    ``lever_angle0``; everything else (the lever's analogues ``u_1, e_1``, the
    point accelerations of eq. 16, the gear's ``u_8, e_8``) comes from the
    engine.

    Returns
    -------
    LoopSolution
        ``sol.d1("theta1")`` is ``u_1``, ``sol.d2("theta1")`` is ``e_1``,
        ``sol.d2("p_x")``, ``sol.d2("p_y")`` are eq. 16's point accelerations
        (over ``omega9**2``), ``sol.d1("theta8")``, ``sol.d2("theta8")`` are
        ``u_8, e_8``.

    Notes
    -----
    Paper eqs. 5-9 (the double slider turning the lever), 3 and 11-14
    (Willis), 16 (the lever's point); :mod:`gearlever.zrdpm` gives the same
    numbers in closed form, which the tests check.

    Examples
    --------
    >>> s = zrdpm_contour(10.0, [0.0, 0.5])
    >>> np.allclose(s.d1("theta1"), np.sin([0.0, 0.5]) + np.cos([0.0, 0.5]))
    True
    """
    system = zrdpm_contour_system(l, r, r_a, r_b, ratio, mesh, lever_angle0)
    phi = finite_array("phi", phi)
    p0 = float(phi.reshape(-1)[0]) if phi.size else 0.0
    th = float(lever_angle0)
    guess = {
        "x_B": l * math.cos(p0),
        "y_A": l * math.sin(p0) + r,
        "theta1": th,
        "w1": 0.0,
        "p_x": l * math.cos(th),
        "p_y": l * math.sin(th),
        "theta8": th,
        "w8": 0.0,
    }
    return system.solve(phi, guess, strict=strict)


# --------------------------------------------------------------------------
# closed forms of the ZRDPM contour (paper eqs. 6-9, 16-17, 25-28, 35-36)


def double_slider_projections(l: float, r: float, phi) -> tuple[np.ndarray, ...]:
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
    >>> x, y, dx, dy, d2x, d2y = double_slider_projections(2.0, 1.0, [0.0])
    >>> float(x[0]), float(y[0]), float(dx[0]), float(dy[0])
    (2.0, 1.0, -0.0, 2.0)
    """
    l = positive("l", l)
    r = finite("r", r)
    phi = finite_array("phi", phi)
    c, s = np.cos(phi), np.sin(phi)
    return l * c, l * s + r, -l * s, l * c, -l * c, -l * s


def point_acceleration(l: float, theta, u, e) -> tuple[np.ndarray, np.ndarray]:
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


def recover_analogues(l: float, theta, a_x, a_y) -> tuple[np.ndarray, np.ndarray]:
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


def slider_lever(l: float, r_a: float, r_b: float, phi) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
