"""The one sweep rule of the ``mechanism`` commands (analyze, draw, animate, forces, view) and reproduce.

- rows: ``points`` (default :data:`DEFAULT_POINTS` = 360, at most
  :data:`MAX_POINTS`);
- no ranges: the *first* input of ``[[inputs]]`` turns one full turn from its
  sketch angle, the end excluded (it would repeat the first row), and any
  other input is held at its sketch value.  When the first input cannot turn
  fully (:func:`~gearlever.mechanism.limits.input_limits`: it rocks between
  two dead points on the sketch's branch) the rows are *one oscillation*
  instead: from the sketch up to the upper limit, back down to the lower
  limit, back up to the sketch (end excluded), evenly spaced along that
  path, with a :attr:`Sweep.direction` of +1 or -1 per row and rates with
  the sign of the motion.  A slider as the first input oscillates the same
  way between its dead points; one that no dead point stops is refused
  (give its range);
- ranges ``(start, stop)`` once per input, in ``[[inputs]]`` order or named
  (degrees for a link, length for a slider): all inputs move together,
  linearly, from start to stop, the end included.  A range of the one
  moving input that leaves its reachable range (the others held) is refused,
  naming the limits.

Numeric core: numpy only (no command-line parsing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = [
    "DEFAULT_POINTS",
    "MAX_POINTS",
    "Sweep",
    "input_labels",
    "input_ranges",
    "oscillation",
    "sweep",
    "sweep_rows",
]

#: Largest number of rows of a sweep.
MAX_POINTS = 100_000
#: Rows of a sweep when none is given (analyze, draw, the viewer).
DEFAULT_POINTS = 360
#: Largest sweep of one rotary input (turns): the continuation walks the range in steps of a few degrees.
MAX_INPUT_TURNS = 1000
#: Largest sweep of one slider input, in multiples of the model's size.
MAX_SLIDER_SPAN = 1000.0


@dataclass(frozen=True)
class Sweep(Result):
    """Input rows of a sweep.

    Attributes
    ----------
    q : ndarray
        ``(points, W)`` inputs for :meth:`~gearlever.mechanism.Mechanism.solve`
        (rad for a link, length for a slider).
    qdot : ndarray
        ``(points, W)`` rates per unit rate of the first input, with the sign
        of the motion (-1 on the rows where a rocking input moves back).
    direction : ndarray
        ``(points,)``: +1 where the first input moves up, -1 where it moves
        back (an oscillation), 0 where it does not move.
    limits : InputLimits or None
        The first input's limits when the rows are one oscillation, else None.

    Examples
    --------
    One oscillation of the Watt I six-bar's rocking input in 8 rows:

    >>> import numpy as np
    >>> from gearlever.data import example_path
    >>> from gearlever.mechanism import Mechanism
    >>> s = sweep_rows(Mechanism.load(example_path("watt_i.toml")), points=8)
    >>> np.round(np.degrees(s.q[:, 0]), 3).tolist(), s.direction.tolist()
    ([72.922, 75.664, 78.102, 75.359, 72.616, 69.874, 67.436, 70.179], [1, 1, -1, -1, -1, -1, 1, 1])
    """

    q: np.ndarray
    qdot: np.ndarray
    direction: np.ndarray
    limits: object = None

    @property
    def oscillates(self) -> bool:
        """True when the rows are one oscillation of a rocking first input."""
        return self.limits is not None

    def message(self) -> str | None:
        """The one line that says so (``"AB rocks between 67.284 and 78.254 deg: sweeping one oscillation"``)."""
        if self.limits is None:
            return None
        return f"{self.limits.input} rocks between {self.limits.text()}: sweeping one oscillation"


def input_labels(mech) -> list:
    """Names of the model's inputs, as in ``--rpm NAME=VALUE`` and the result columns."""
    from gearlever.mechanism.solve import input_name

    return [input_name(spec) for spec in mech.model.inputs]


def input_ranges(mech, given):
    """The ranges in ``[[inputs]]`` order: ``[(start, stop), ...]``, or None when none is given.

    ``given`` holds ``(name or None, start, stop)`` (or ``(start, stop)``): all named, each input once
    in any order, or all unnamed, in ``[[inputs]]`` order.

    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> input_ranges(m, [("crank", 0.0, 90.0)]), input_ranges(m, [(None, 10.0, 20.0)])
    ([(0.0, 90.0)], [(10.0, 20.0)])
    """
    if not given:
        return None
    items = [g if len(g) == 3 else (None, *g) for g in given]
    named = [g[0] is not None for g in items]
    if not any(named):
        return [(g[1], g[2]) for g in items]
    labels = input_labels(mech)
    if not all(named):
        raise GearleverError(
            "--input: name every input (--input NAME=START STOP) or none (in [[inputs]] order), not some"
        )
    out: dict = {}
    for name, a, b in items:
        if name not in labels:
            from gearlever.mechanism.solve import _unknown

            raise GearleverError(f"--input: {_unknown(name, 'input', labels)}")
        if name in out:
            raise GearleverError(f"--input: input {name!r} given twice")
        out[name] = (a, b)
    missing = [n for n in labels if n not in out]
    if missing:
        raise GearleverError(
            f"--input: model {mech.model.name!r} has inputs {', '.join(labels)}; give --input NAME=START STOP "
            f"once for each (missing: {', '.join(missing)}), or none to turn the first with the others held"
        )
    return [out[n] for n in labels]


def _check_span(model, ranges, flag: str = "--input") -> None:
    """Refuse a range (degrees, or length for a slider) that spans more than the cap."""
    for spec, pair in zip(model.inputs, ranges):
        start, stop = (float(v) for v in pair)
        span = abs(stop - start)
        if spec.kind == "slider":
            cap = MAX_SLIDER_SPAN * model.length_scale
            if not span <= cap:
                raise GearleverError(
                    f"{flag} {start:g} {stop:g} ({spec.label}) spans {span:.3g}, more than the cap of "
                    f"{MAX_SLIDER_SPAN:g} times the model's size ({cap:.3g})"
                )
        elif not span / 360.0 <= MAX_INPUT_TURNS:
            raise GearleverError(
                f"{flag} {start:g} {stop:g} ({spec.label}) spans {span / 360.0:.3g} turns, "
                f"more than the cap of {MAX_INPUT_TURNS} turns"
            )


def oscillation(start: float, lower: float, upper: float, points: int, first: int = 1):
    """One oscillation between two limits from ``start``: values and directions, ``points`` rows, end excluded.

    From ``start`` to the limit in the ``first`` direction (+1: ``upper``),
    back to the other limit, back to ``start``; the rows are evenly spaced
    along that path (length ``2 (upper - lower)``); a row exactly at a limit
    starts the leg that leaves it.

    >>> v, d = oscillation(0.0, -1.0, 2.0, 6)
    >>> v.tolist(), d.tolist()
    ([0.0, 1.0, 2.0, 1.0, 0.0, -1.0], [1, 1, -1, -1, -1, 1])
    """
    span = upper - lower
    u = 2.0 * span * np.arange(points) / points
    if first < 0:  # mirror: the same path in -q
        v, d = oscillation(-start, -upper, -lower, points, 1)
        return -v + 0.0, -d
    a = upper - start  # first leg
    b = a + span  # end of the second leg
    v = np.where(u <= a, start + u, np.where(u <= b, upper - (u - a), lower + (u - b)))
    d = np.where(u < a, 1, np.where(u < b, -1, 1)).astype(int)
    return v, d


def sweep_rows(mech, points: int = DEFAULT_POINTS, ranges=None, first: int = 1, branch: str = "continue") -> Sweep:
    """Input rows of a sweep, their rates and directions: the one sweep rule (module docstring).

    Parameters
    ----------
    mech : gearlever.Mechanism
    points : int
        Rows, at most :data:`MAX_POINTS`.
    ranges : sequence of (start, stop) or (name, start, stop), optional
        One per input, degrees for a link and length for a slider (the
        ``--input`` values): in ``[[inputs]]`` order, or named
        (:func:`input_ranges`).
    first : {1, -1}
        Direction of the first leg of an oscillation (the sign of the speed).
    branch : {"continue", "keep", "stop"}
        The policy at branch points (:func:`~gearlever.mechanism.solve.solve`),
        which decides the limits: with ``"stop"`` a branch point is one; solve
        the rows with the same policy.

    Returns
    -------
    Sweep

    Raises
    ------
    GearleverError
        Too many points; ranges given for some inputs only; no ranges and the
        first input is a slider that no dead point stops (a slider between dead
        points oscillates between them, as a rocking link); a range of the
        one moving input past its limits (the message names them); a first
        input that cannot move from the sketch (locked, naming the links).

    Notes
    -----
    Limits by :func:`~gearlever.mechanism.limits.input_limits` (coarse scan,
    then bisection to 1e-10 rad).  A range is refused when it leaves the
    limits by more than 1e-9 rad (or 1e-9 model sizes).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> s = sweep_rows(m, 4)
    >>> np.degrees(s.q[:, 0]).round(9).tolist(), s.direction.tolist(), s.oscillates
    ([0.0, 90.0, 180.0, 270.0], [1, 1, 1, 1], False)
    """
    from gearlever.mechanism.branch import check_branch
    from gearlever.mechanism.limits import input_limits

    check_branch(branch)
    if points > MAX_POINTS:
        raise GearleverError(f"--points must be at most {MAX_POINTS}, got {points}")
    m = mech.model
    W = len(m.inputs)
    labels = ", ".join(input_labels(mech))
    if ranges and any(len(r) == 3 for r in ranges):
        ranges = input_ranges(mech, ranges)
    if not ranges:
        lim = input_limits(mech, 0, branch=branch)
        if m.inputs[0].kind == "slider" and not (math.isfinite(lim.lower) and math.isfinite(lim.upper)):
            raise GearleverError(
                f"--input: the first input of model {m.name!r} ({labels}) is a slider that no dead point "
                "stops, so it has no one cycle; give --input START STOP once per input"
            )
        q = np.broadcast_to(mech.sketch_inputs, (points, W)).copy()
        qdot = np.zeros((points, W))
        if lim.full_turn:
            q[:, 0] += np.linspace(0.0, 2 * np.pi, points, endpoint=False)
            qdot[:, 0] = 1.0
            return Sweep(q, qdot, np.ones(points, dtype=int))
        _check_moves(lim)
        v, d = oscillation(lim.start, lim.lower, lim.upper, points, 1 if first >= 0 else -1)
        q[:, 0] = v
        qdot[:, 0] = d
        return Sweep(q, qdot, d, lim)
    if len(ranges) != W:
        raise GearleverError(
            f"--input: model {m.name!r} has {W} input{'s' if W != 1 else ''} ({labels}); "
            f"give --input [NAME=]START STOP once per input (got {len(ranges)}), "
            "or none to turn the first a full turn with the others held"
        )
    _check_span(m, ranges)
    conv = [1.0 if spec.kind == "slider" else math.pi / 180.0 for spec in m.inputs]
    start = np.array([r[0] * c for r, c in zip(ranges, conv)])
    stop = np.array([r[1] * c for r, c in zip(ranges, conv)])
    _check_reach(mech, ranges, start, stop, branch)
    t = np.linspace(0.0, 1.0, points)
    q = start + t[:, None] * (stop - start)
    span = stop - start
    rates = span / span[0] if span[0] != 0 else span
    moving = np.flatnonzero(span)
    d = np.full(points, int(np.sign(span[moving[0]])) if moving.size else 0)
    return Sweep(q, np.broadcast_to(rates, (points, W)).copy(), d)


def _check_moves(lim) -> None:
    if lim.locked:
        links = ", ".join(dict.fromkeys(lim.binding_lower + lim.binding_upper)) or "its links"
        raise GearleverError(
            f"{lim.input} cannot move from the sketch: it is locked by the links {links} (a dead point either way)"
        )


def _check_reach(mech, ranges, start, stop, branch: str = "continue") -> None:
    """Refuse the range of the one moving input when it leaves that input's limits (the others held)."""
    from gearlever.mechanism.limits import input_limits

    span = stop - start
    moving = np.flatnonzero(span != 0)
    if moving.size > 1:
        return
    i = int(moving[0]) if moving.size else 0
    held = mech.sketch_inputs.astype(float)
    others = np.arange(held.size) != i
    held[others] = start[others]
    try:
        lim = input_limits(mech, i, start=held, branch=branch)
    except GearleverError:
        return  # the held values do not assemble: the rows say so (not closed)
    if lim.full_turn:
        return
    _check_moves(lim)
    slack = 1e-9 * (mech.model.length_scale if lim.kind == "slider" else 1.0)
    lo, hi = min(start[i], stop[i]), max(start[i], stop[i])
    if lo < lim.lower - slack or hi > lim.upper + slack:
        spec = mech.model.inputs[i]
        a, b = ranges[i]
        unit = " deg" if spec.kind == "link" else ""
        raise GearleverError(
            f"--input {a:g} {b:g}{unit} ({spec.label}): from the sketch, on its assembly branch, {spec.label} "
            f"moves only between {lim.text()} (dead points, the other inputs held); give a range within them"
        )


def sweep(mech, points: int = DEFAULT_POINTS, ranges=None):
    """Input rows of a sweep and their rates: ``(q, qdot)`` of :func:`sweep_rows`.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> q, qdot = sweep(m, 4)
    >>> np.degrees(q[:, 0]).round(9).tolist(), qdot[:, 0].tolist()
    ([0.0, 90.0, 180.0, 270.0], [1.0, 1.0, 1.0, 1.0])
    >>> np.degrees(sweep(m, 3, [(0.0, 90.0)])[0][:, 0]).round(9).tolist()
    [0.0, 45.0, 90.0]
    """
    s = sweep_rows(mech, points, ranges)
    return s.q, s.qdot
