"""Velocity and acceleration plans (vector polygons) computed from a loop's analogues.

The graphical method writes each loop as "sum of the + vectors = sum of the -
vectors" and draws both sides from one pole.  Here every vector's velocity or
acceleration is split into its textbook components and returned as complex
numbers (x + i y), in the order of the loop, so that a drawing only has to add
them head to tail.  Pure numpy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gearlever._validate import finite
from gearlever.errors import GearleverError
from gearlever.loops.engine import LoopSystem

__all__ = ["PlanTerm", "velocity_plan", "acceleration_plan"]

#: component kinds: rotation (velocity), sliding, normal, tangential, Coriolis
KINDS = ("r", "s", "n", "t", "c")


@dataclass(frozen=True)
class PlanTerm:
    """One arrow of a plan.

    Attributes
    ----------
    vector : str
        Name of the loop vector (e.g. ``"BA"``).
    kind : str
        ``"r"`` rotational velocity ``i L A' e^{iA}``, ``"s"`` sliding
        (``L' e^{iA}`` or ``L'' e^{iA}``), ``"n"`` normal ``-L A'^2 e^{iA}``,
        ``"t"`` tangential ``i L A'' e^{iA}``, ``"c"`` Coriolis
        ``2 i L' A' e^{iA}``.
    value : complex
        The arrow, ``x + i y`` (velocity or acceleration units).
    side : int
        +1 or -1: the side of the loop equation (the vector's sign).

    Examples
    --------
    >>> from gearlever.loops.fourbar import fourbar_system
    >>> s = fourbar_system(9, 5, 8, 8)
    >>> term = velocity_plan(s, s.solve([1.0], {"theta3": 0.4, "theta4": 1.6}))[0]
    >>> term.kind, term.side, type(term.value).__name__
    ('r', 1, 'complex')
    """

    vector: str
    kind: str
    value: complex
    side: int


def _one(system, sol, index):
    if not isinstance(system, LoopSystem):
        raise GearleverError("system must be a LoopSystem")
    i = int(index)
    if not (-sol.phi.size <= i < sol.phi.size):
        raise GearleverError(f"index must be within the solution's {sol.phi.size} points, got {index!r}")
    phi = sol.phi.reshape(-1)[i]
    n = len(system.unknowns)
    x = sol.x.reshape(-1, n)[i]
    dx = sol.dx_dphi.reshape(-1, n)[i]
    d2x = sol.d2x_dphi2.reshape(-1, n)[i]
    if not sol.valid.reshape(-1)[i]:
        raise GearleverError(f"index must point at a valid (closed, non-dead) position, got {index!r}")
    return system.vector_analogues(np.array(phi), x, dx, d2x)


def _kinds(system):
    out = []
    for _, _, ls, as_ in system._specs:
        out.append((ls[0] != "fixed", as_[0] != "fixed"))
    return out


def velocity_plan(system, sol, index=0, omega=1.0) -> list[PlanTerm]:
    """Velocity-plan arrows of every moving vector at one input value.

    Parameters
    ----------
    system : LoopSystem
    sol : LoopSolution
        A solution of ``system`` (from a closed form or :meth:`LoopSystem.solve`).
    index : int
        Which point of ``sol`` (flat index).
    omega : float
        Input speed (rad/s, or length/s for a sliding input).

    Returns
    -------
    list of PlanTerm
        Kinds ``"s"`` and ``"r"``; each side sums to the same vector.

    Notes
    -----
    ``d/dt (L e^{iA}) = (L' + i L A') omega e^{iA}`` (Norton, eq. 6.7).

    Examples
    --------
    >>> from gearlever.loops.fourbar import fourbar_system
    >>> s = fourbar_system(9, 5, 8, 8)
    >>> sol = s.solve([1.0], {"theta3": 0.4, "theta4": 1.6})
    >>> terms = velocity_plan(s, sol)
    >>> [t.vector + t.kind for t in terms]
    ['Ar', 'BAr', 'Br']
    >>> lhs = sum(t.value for t in terms if t.side > 0); rhs = sum(t.value for t in terms if t.side < 0)
    >>> abs(lhs - rhs) < 1e-12
    True
    """
    omega = finite("omega", omega)
    out = []
    for v, (L, A, Lp, Ap, _, _), (lv, av) in zip(system.vectors, _one(system, sol, index), _kinds(system)):
        e = complex(np.cos(A), np.sin(A))
        if lv:
            out.append(PlanTerm(v.name, "s", complex(Lp * omega) * e, v.sign))
        if av:
            out.append(PlanTerm(v.name, "r", 1j * float(L) * float(Ap) * omega * e, v.sign))
    return out


def acceleration_plan(system, sol, index=0, omega=1.0, alpha=0.0) -> list[PlanTerm]:
    """Acceleration-plan arrows of every moving vector at one input value.

    Parameters
    ----------
    system, sol, index : see :func:`velocity_plan`
    omega, alpha : float
        Input speed and input acceleration.

    Returns
    -------
    list of PlanTerm
        Kinds ``"s"``, ``"c"``, ``"n"``, ``"t"`` as they apply; each side sums
        to the same vector.

    Notes
    -----
    With time derivatives ``dL = L' omega``, ``ddL = L'' omega^2 + L' alpha``
    (and the same for ``A``)::

        d2/dt2 (L e^{iA}) = (ddL + 2 i dL dA - L dA^2 + i L ddA) e^{iA}

    sliding + Coriolis + normal + tangential (Norton, eq. 7.4).  For the
    ZRDPM double slider this is paper eqs. 19-20:
    ``a_B = a_A + a_BA^n + a_BA^t``.

    Examples
    --------
    >>> from gearlever.loops.closed import double_slider, double_slider_system
    >>> terms = acceleration_plan(double_slider_system(2.0, 0.0), double_slider(2.0, 0.0, [0.3]))
    >>> [(t.vector + t.kind, t.side) for t in terms]
    [('Bs', 1), ('As', -1), ('BAn', -1), ('BAt', -1)]
    """
    omega = finite("omega", omega)
    alpha = finite("alpha", alpha)
    out = []
    for v, (L, A, Lp, Ap, Lpp, App), (lv, av) in zip(system.vectors, _one(system, sol, index), _kinds(system)):
        e = complex(np.cos(A), np.sin(A))
        L = float(L)
        dL, dA = float(Lp) * omega, float(Ap) * omega
        ddL = float(Lpp) * omega**2 + float(Lp) * alpha
        ddA = float(App) * omega**2 + float(Ap) * alpha
        if lv:
            out.append(PlanTerm(v.name, "s", ddL * e, v.sign))
        if lv and av:
            out.append(PlanTerm(v.name, "c", 2j * dL * dA * e, v.sign))
        if av:
            out.append(PlanTerm(v.name, "n", -L * dA * dA * e, v.sign))
            out.append(PlanTerm(v.name, "t", 1j * L * ddA * e, v.sign))
    return out
