"""Limits of an input: the dead points that bound its motion on the sketch's assembly branch.

An input that cannot turn fully from the sketch (the other inputs held) rocks
between two *dead points* of the input, where the constraint Jacobian of the
driven links becomes singular (a dyad stretched or folded: the coupler and
follower of a four-bar collinear).  :func:`input_limits` finds them:

1. a coarse batched scan of :meth:`~gearlever.mechanism.Mechanism.solve`
   from the sketch, one degree apart over a turn each way (a slider input:
   :data:`SLIDER_SCAN` model sizes each way, in 1/200 of the size), brackets
   each limit between the last row that closes and the first that does not
   (the continuation never changes branch: a row past a dead point is not
   closed);
2. bisection of that bracket to :data:`LIMIT_TOL` (rad, or times the model
   size for a slider): a trial input is *reachable* when Newton's method,
   started at the last reachable pose, closes the loops to 1e-12 of the
   model size with the Jacobian's determinant of the sketch's sign.  The
   limit returned is the reachable end of the final bracket (inside the
   range, at most :data:`LIMIT_TOL` from the dead point).

Numeric core: numpy only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = ["LIMIT_TOL", "InputLimits", "input_limits"]

#: Width of the final bisection bracket of a limit (rad; times the model size for a slider input).
LIMIT_TOL = 1e-10
#: Rows of the coarse scan per turn (one degree apart).
SCAN_ROWS = 360
#: Model sizes scanned each way for a slider input.
SLIDER_SCAN = 4.0
#: Residual (times the model size) below which a trial pose of the bisection counts as closed.
CLOSE_TOL = 1e-12


@dataclass(frozen=True)
class InputLimits(Result):
    """Reachable range of one input from the sketch, the other inputs held.

    Attributes
    ----------
    input : str
        The input's name (its label in ``[[inputs]]``).
    kind : str
        ``"link"`` (values in rad) or ``"slider"`` (length).
    start : float
        The value the motion starts from (the sketch's, unless given).
    lower, upper : float
        The limits (dead points) below and above ``start``; ``-inf``/``inf``
        where there is none (a link input that turns fully, or a slider input
        with no limit within the scan).
    full_turn : bool
        The input turns a full turn (a link input with no limit).
    binding_lower, binding_upper : tuple of str
        The links that move in the singular direction at each limit (the
        stretched or folded dyad), empty where there is no limit.
    tol : float
        Width of the final bisection bracket (:data:`LIMIT_TOL`).

    Examples
    --------
    A rocker-input four-bar (ground 4, input 2, coupler 3, follower 2): it rocks
    where coupler and follower stretch, ``cos theta = (2^2 + 4^2 - 5^2) / (2 2 4)``:

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [0, 2], "B": [2.987339717240448, 1.7246794344808962],
    ...     "Q": [4, 0]}, "links": {"ground": ["O", "Q"], "rocker": ["O", "A"], "coupler": ["A", "B"],
    ...     "follower": ["Q", "B"]}, "inputs": [{"link": "rocker"}]})
    >>> lim = input_limits(m)
    >>> lim.rocks, round(math.degrees(lim.lower), 6), round(math.degrees(lim.upper), 6), lim.binding_upper
    (True, -108.209957, 108.209957, ('coupler', 'follower'))
    >>> round(math.degrees(math.acos(-5 / 16)), 6)
    108.209957
    """

    input: str
    kind: str
    start: float
    lower: float
    upper: float
    full_turn: bool
    binding_lower: tuple
    binding_upper: tuple
    tol: float

    @property
    def rocks(self) -> bool:
        """True when the input is bounded on both sides (it oscillates between two dead points)."""
        return math.isfinite(self.lower) and math.isfinite(self.upper)

    @property
    def locked(self) -> bool:
        """True when the input cannot move from ``start`` (both limits within :attr:`tol` of it)."""
        return self.upper - self.lower <= 4 * self.tol * (1.0 if self.kind == "link" else 1.0)

    def contains(self, value: float, slack: float = 0.0) -> bool:
        """True when ``value`` lies within the limits (widened by ``slack``)."""
        return self.lower - slack <= value <= self.upper + slack

    def text(self, unit_scale: float = 1.0) -> str:
        """``"67.284 and 78.254 deg"`` (a link input) or ``"-1.5 and 2.25"`` (a slider input)."""
        if self.kind == "link":
            return f"{math.degrees(self.lower):.3f} and {math.degrees(self.upper):.3f} deg"
        return f"{self.lower:.6g} and {self.upper:.6g}"


def _binding(ks, x) -> tuple:
    """Links that move in the singular direction of the closure Jacobian at the reduced coordinates ``x``."""
    if ks.dz == 0 or not np.all(np.isfinite(x)):
        return ()
    xx = x[:, None]
    C, S = ks.trig(xx)
    J = ks.jz(xx, C, S)[ks.sel][:, :, 0]
    v = np.linalg.svd(J)[2][-1]
    move = ks.N @ v  # (nx,)
    rot = np.abs(move[: ks.n])
    big = rot.max() if rot.size else 0.0
    names = [k for k in ks.model.moving if big > 0 and rot[ks.idx[k]] > 0.05 * big]
    names += [s.name for j, s in enumerate(ks.model.sliders) if abs(move[ks.n + j]) > 0.05 * max(big, 1e-300) * ks.L]
    return tuple(names)


def _reachable(ks, dq, z, sgn0):
    """Newton from ``z`` at the input offsets ``dq`` (W,): ``(z, x)`` if it closes on the sketch's branch, else None."""
    z1, x, C, S, _ = ks.newton(dq[:, None], z[:, None], max_iter=25)
    if not np.all(np.isfinite(x)):
        return None
    G = ks.residual(x, C, S)
    if not np.all(np.abs(G) <= CLOSE_TOL * ks.L):
        return None
    ratio, sgn = ks._hadamard(ks.jz(x, C, S)[ks.sel])
    if not (ratio[0] > 0.0 and sgn[0] == sgn0):
        return None
    return z1[:, 0], x[:, 0]


def input_limits(mech, index: int = 0, start=None, tol: float = LIMIT_TOL, branch: str = "continue") -> InputLimits:
    """The limits (dead points) of one input on the sketch's assembly branch, the other inputs held.

    Parameters
    ----------
    mech : gearlever.Mechanism
    index : int
        Which input (``[[inputs]]`` order).
    start : sequence of float, optional
        Values of every input (rad, or length) the motion starts from and
        the others are held at; default the sketch's.
    tol : float
        Width of the final bisection bracket (rad; times the model size for
        a slider input), at least 1e-13.
    branch : {"continue", "keep", "stop"}
        The policy at branch points (:func:`~gearlever.mechanism.solve.solve`):
        with ``"continue"`` (the default) and ``"keep"`` the motion goes on
        through them and only a dead point of the input is a limit; with
        ``"stop"`` a branch point is a limit too (a parallelogram four-bar
        then rocks between its folding poses).

    Returns
    -------
    InputLimits

    Raises
    ------
    GearleverError
        A bad ``index``, ``tol`` or ``start``, or ``start`` not reached from
        the sketch.

    Notes
    -----
    Bracketing by a batched coarse scan of the continuation
    (:meth:`~gearlever.mechanism.Mechanism.solve`, one degree apart), then
    bisection to ``tol``: see the module docstring.  At a limit the closure
    Jacobian ``J_z`` (with the inputs fixed) is singular: the condition
    ``det J_z = 0`` of a dead point (the position problem's Jacobian singular:
    P. E. Nikravesh, *Computer-Aided Analysis of Mechanical Systems*, 1988);
    the links
    named as binding are those that move along its null vector.  For a
    four-bar whose input cannot turn the limits are where coupler and
    follower are collinear: ``cos theta = (a^2 + d^2 - (b +- c)^2) / (2 a d)``
    (law of cosines), which the tests check to 1e-9 rad.

    Examples
    --------
    The Watt I six-bar of PMKS+'s verification cases rocks its input AB:

    >>> import numpy as np
    >>> from gearlever.data import example_path
    >>> from gearlever.mechanism import Mechanism
    >>> lim = input_limits(Mechanism.load(example_path("watt_i.toml")))
    >>> lim.full_turn, np.round(np.degrees([lim.lower, lim.upper]), 3).tolist(), lim.binding_lower
    (False, [67.284, 78.254], ('DE', 'EF'))
    """
    ks = mech.system
    W = ks.W
    if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < W:
        raise GearleverError(f"index must be an input index from 0 to {W - 1}, got {index!r}")
    if not (isinstance(tol, (int, float)) and math.isfinite(tol) and tol >= 1e-13):
        raise GearleverError(f"tol must be a finite number of at least 1e-13, got {tol!r}")
    spec = mech.model.inputs[index]
    q0 = mech.sketch_inputs.astype(float) if start is None else np.asarray(start, dtype=float).reshape(-1).copy()
    if q0.shape != (W,) or not np.all(np.isfinite(q0)):
        raise GearleverError(f"start must hold {W} finite input values, got {start!r}")
    slider = spec.kind == "slider"
    scale = ks.L if slider else 1.0
    if slider:
        steps = SLIDER_SCAN * ks.L * np.arange(0, 801) / 800.0
    else:
        steps = 2 * np.pi * np.arange(0, SCAN_ROWS + 1) / SCAN_ROWS
    ends, binding = [], []
    full = True
    for sign in (1.0, -1.0):
        q = np.tile(q0, (steps.size, 1))
        q[:, index] += sign * steps
        r = mech.solve(q, np.zeros_like(q), branch=branch)
        if not r.closed[0]:
            raise GearleverError(
                f"start: the mechanism does not assemble at {spec.label} = {q0[index]:.6g} on the sketch's branch"
            )
        if r.closed.all():
            if not slider and sign > 0:  # a full turn on the sketch's branch: no limit either way
                ends += [math.inf, -math.inf]
                binding += [(), ()]
                break
            ends.append(sign * math.inf)
            binding.append(())
            continue
        full = False
        k = int(np.argmin(r.closed))
        if k >= 2 and ks.dz and ks._near_pose(q[k - 1] - ks.q0, ks.N.T @ r.x[k - 1]):
            k -= 1  # the last row reached lies at the singular pose itself: bisect up to it from the row before
        a, b = q[k - 1].copy(), q[k].copy()
        za = ks.N.T @ r.x[k - 1] if ks.dz else np.zeros(0)
        xa = r.x[k - 1].copy()
        sgn = ks.sgn0 * (r.side[k - 1] if r.side is not None and r.side[k - 1] else 1)  # the branch there
        dq0 = ks.q0
        while abs(b[index] - a[index]) > tol * scale:
            mid = a.copy()
            mid[index] = 0.5 * (a[index] + b[index])
            got = _reachable(ks, mid - dq0, za, sgn) if ks.dz else (np.zeros(0), None)
            if got is None:  # from the tangent's prediction (the other branch crosses nearby)
                st = ks._state(a - dq0, za)
                if st is not None:
                    got = _reachable(ks, mid - dq0, za + st[0] @ (mid - a), sgn)
            if got is None:
                b = mid
            else:
                a = mid
                za, xa = got[0], (got[1] if got[1] is not None else xa)
        ends.append(float(a[index]))
        binding.append(_binding(ks, xa))
    upper, lower = ends
    if full and not slider:
        binding = [(), ()]
    return InputLimits(
        input=spec.label,
        kind=spec.kind,
        start=float(q0[index]),
        lower=lower,
        upper=upper,
        full_turn=bool(full and not slider),
        binding_lower=binding[1],
        binding_upper=binding[0],
        tol=float(tol),
    )
