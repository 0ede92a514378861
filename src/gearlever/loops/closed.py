"""Closed-form loops: slider-crank, inverted slider-crank, double slider.

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
from gearlever.loops.engine import INPUT, Input, LoopSolution, LoopSystem, Unknown, Vector
from gearlever import vector_loop

__all__ = [
    "slider_crank_system", "slider_crank",
    "inverted_slider_crank_system", "inverted_slider_crank",
    "double_slider_system", "double_slider",
]

_SIGN = {"open": 1.0, "crossed": -1.0}


def _sigma(branch):
    try:
        return _SIGN[branch]
    except (KeyError, TypeError):
        raise ValueError(f"branch must be 'open' or 'crossed', got {branch!r}") from None


def _finish(system, phi, x, closed, strict, singular_tol, what):
    x = np.where(closed[..., None], x, np.nan)
    dx, d2x, bad = system.analogues(phi, x, singular_tol)
    valid = closed & ~bad
    if strict and not valid.all():
        first = phi.reshape(-1)[int(np.flatnonzero(~valid.reshape(-1))[0])]
        raise ValueError(
            f"theta2: the {what} cannot close or is at a dead point at {first!r} "
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
    return LoopSystem([[Vector("A", a, INPUT), Vector("BA", b, "theta3"),
                        Vector("e", e, math.pi / 2, -1), Vector("B", "x_B", 0.0, -1)]])


def slider_crank(crank, rod, theta2, offset=0.0, branch="open", *, strict=False,
                 singular_tol=1e-7) -> LoopSolution:
    """Slider-crank positions (closed form) and analogues (linear solves).

    Parameters
    ----------
    crank, rod : float
        Crank and connecting-rod lengths (> 0).
    theta2 : array_like
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
    ``a sin(theta2) + b sin(theta3) = offset`` gives ``theta3``, and
    ``x_B = a cos(theta2) + b cos(theta3)`` (Norton, eq. 4.16).  Dead points
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
    th2 = finite_array("theta2", theta2)
    s3 = (e - a * np.sin(th2)) / b
    closed = np.abs(s3) <= 1.0
    s3c = np.clip(s3, -1.0, 1.0)
    c3 = sigma * np.sqrt(1.0 - s3c * s3c)
    theta3 = np.arctan2(s3c, c3)
    xb = a * np.cos(th2) + b * c3
    return _finish(system, th2, np.stack([theta3, xb], axis=-1), closed, strict, singular_tol,
                   "slider-crank")


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
    return LoopSystem([[Vector("A", a, INPUT), Vector("O4", d, 0.0, -1),
                        Vector("AO4", "b", "theta4", -1),
                        Vector("e", e, Unknown("theta4", math.pi / 2), -1)]])


def inverted_slider_crank(ground, crank, theta2, offset=0.0, branch="open", *, strict=False,
                          singular_tol=1e-7) -> LoopSolution:
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
    th2 = finite_array("theta2", theta2)
    px, py = a * np.cos(th2) - d, a * np.sin(th2)
    q = px * px + py * py - e * e
    closed = q >= 0
    b = sigma * np.sqrt(np.where(closed, q, 0.0))
    theta4 = np.arctan2(py, px) - np.arctan2(e, b)
    theta4 = np.arctan2(np.sin(theta4), np.cos(theta4))
    return _finish(system, th2, np.stack([b, theta4], axis=-1), closed, strict, singular_tol,
                   "inverted slider-crank")


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
    return LoopSystem([[Vector("B", "x_B", 0.0), Vector("r", r, math.pi / 2),
                        Vector("A", "y_A", math.pi / 2, -1), Vector("BA", l, Input(-1.0, 0.0), -1)]])


def double_slider(l, r, phi) -> LoopSolution:
    """Double-slider contour in closed form (:func:`gearlever.vector_loop.double_slider`).

    Returns
    -------
    LoopSolution
        Unknowns ``x_B`` and ``y_A`` with their analogues; always valid.

    Notes
    -----
    Paper eqs. 6-7 (contour 1) and 25-26 (contour 2), via
    :func:`gearlever.vector_loop.double_slider`.

    Examples
    --------
    >>> s = double_slider(2.0, 1.0, [0.0])
    >>> s["x_B"].tolist(), s["y_A"].tolist(), s.d1("y_A").tolist()
    ([2.0], [1.0], [2.0])
    """
    system = double_slider_system(l, r)
    phi = finite_array("phi", phi)
    xb, ya, dxb, dya, d2xb, d2ya = vector_loop.double_slider(l, r, phi)
    x = np.stack([xb, ya], axis=-1)
    dx = np.stack([dxb, dya], axis=-1)
    d2x = np.stack([d2xb, d2ya], axis=-1)
    ok = np.ones(phi.shape, dtype=bool)
    return LoopSolution(system.unknowns, phi, x, dx, d2x, ok, ok.copy())
