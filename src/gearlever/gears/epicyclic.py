"""The tabular method of epicyclic trains, done exactly on any gear network.

The textbook procedure (first hold the arm and turn one member +1, then turn
the whole train with the arm) is Willis' principle of superposition: every
constraint of an epicyclic train is unchanged when the same rotation is added
to every member, so the motion is ``rot_m = y + x * r_m`` where ``r_m`` is the
member's turns with the arm fixed and the chosen member turned once, ``x`` the
chosen member's turns relative to the arm and ``y`` the arm's turns.  The
conditions of the problem (a member tied to the frame, fixed-axis gearing
outside the epicyclic, the inputs) fix ``x`` and ``y``.

:func:`tabular_method` builds that table from a :class:`~gearlever.gears.networks.Network`
with exact fractions, and checks every total against the network's own solution.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.networks import FRAME, Mesh, Network, _Elimination, format_linear

__all__ = ["TabularRow", "TabularMethod", "tabular_method"]


def _frac(f: Fraction) -> str:
    return str(f.numerator) if f.denominator == 1 else f"{f.numerator}/{f.denominator}"


@dataclass(frozen=True)
class TabularRow(Result):
    """One member's line of the table.

    Attributes
    ----------
    member, teeth : the member and its tooth number (None for shafts and arms).
    relative : turns with the arm fixed and the chosen member turned +1
        (None when the epicyclic train does not determine it: a member joined
        to the train only by fixed-axis gearing).
    total : its rotation, one exact factor per input.
    """

    member: str
    teeth: int | None
    relative: Fraction | None
    total: tuple[Fraction, ...]


@dataclass(frozen=True)
class TabularMethod(Result):
    """The table of the tabular method (see :func:`tabular_method`).

    ``x`` and ``y`` are exact linear functions of the inputs (one factor per
    input): ``x = rot_turned - rot_carrier``, ``y = rot_carrier``; every row's
    total is ``y + x * relative``.

    Examples
    --------
    >>> from gearlever.data import example_path
    >>> from gearlever.gears.networks import parse_network
    >>> net = parse_network(example_path("ferguson_paradox.csv").read_text())
    >>> t = tabular_method(net, "arm", ["arm"])
    >>> t.carrier, len(t.rows)
    ('arm', 6)
    """

    carrier: str
    turned: str
    inputs: tuple[str, ...]
    x: tuple[Fraction, ...]
    y: tuple[Fraction, ...]
    rows: tuple[TabularRow, ...]

    def _lin(self, coefs) -> str:
        return format_linear(dict(zip(self.inputs, coefs)))

    def lines(self) -> list[str]:
        """The table as text, one line per member, exact fractions."""
        c, t = self.carrier, self.turned
        head = [
            f"tabular method: carrier {c}, {t} turned +1 with the {c} fixed, then the whole train turned with the {c}",
            f"x = rot_{t} - rot_{c} = {self._lin(self.x)}",
            f"y = rot_{c} = {self._lin(self.y)}",
        ]
        table = [("member", "teeth", f"{c} fixed, {t} +1", f"{c} fixed, {t} +x", f"train with {c} +y", "total")]
        for r in self.rows:
            rel = "-" if r.relative is None else _frac(r.relative)
            times = "-" if r.relative is None else self._lin([r.relative * v for v in self.x])
            table.append(
                (
                    r.member,
                    "" if r.teeth is None else str(r.teeth),
                    rel,
                    times,
                    "-" if r.relative is None else self._lin(self.y),
                    self._lin(r.total),
                )
            )
        widths = [max(len(row[k]) for row in table) for k in range(len(table[0]))]
        return head + [" | ".join(v.ljust(w) for v, w in zip(row, widths)).rstrip() for row in table]


def _is_train_row(row) -> bool:
    return sum(v for _, v in row) == 0


def tabular_method(network: Network, carrier: str, inputs, turned: str | None = None) -> TabularMethod:
    """The textbook table of an epicyclic train: arm fixed and one member turned +1, then all turned with the arm.

    Parameters
    ----------
    network : the train, with its conditions (members tied to the frame).
    carrier : the arm (a member of the network).
    inputs : input members, as many as the network's degrees of freedom.
    turned : the member turned +1 with the arm fixed (default: the first gear
        meshing on ``carrier``).

    Returns
    -------
    TabularMethod
        One row per member; each total equals the network's solution.

    Examples
    --------
    Ferguson's paradox (fixed 100 teeth, planet 20 on the arm, coaxial 99):

    >>> from gearlever.gears.networks import Gear, SameShaft
    >>> net = Network([Gear("arm"), Gear("s100", 100), Gear("planet", 20), Gear("w99", 99)],
    ...               [SameShaft("fix", "s100", "frame"), Mesh("a", "s100", "planet", carrier="arm"),
    ...                Mesh("b", "w99", "planet", carrier="arm")])
    >>> t = tabular_method(net, "arm", ["arm"])
    >>> [(r.member, str(r.relative), r.total) for r in t.rows][3]
    ('w99', '100/99', (Fraction(-1, 99),))

    Notes
    -----
    Willis' principle: the absolute turns of the wheels of an epicyclic train
    are the sum of their turns relative to the arm and the arm's own turns
    (R. Willis, *Principles of Mechanism*, 2nd ed., 1870, the section on
    epicyclic trains; the "tabular method" of J. E. Shigley and J. J. Uicker,
    *Theory of Machines and Mechanisms*, and of R. L. Norton, *Design of
    Machinery*, chapter "Gear trains").  The train's constraints are the rows
    whose coefficients sum to zero (meshes on a carrier, differentials,
    shafts): exactly those unchanged when the whole train turns.
    """
    names = network.names
    if carrier == FRAME or carrier not in names:
        raise GearleverError(f"carrier {carrier!r} is not a member of the network (members: {', '.join(names)})")
    if turned is None:
        turned = next(
            (c.p for c in network.constraints if isinstance(c, Mesh) and c.carrier == carrier),
            None,
        )
        if turned is None:
            raise GearleverError(f"carrier {carrier!r}: no gear meshes on it, so the tabular method does not apply")
    if turned == carrier or turned not in names:
        raise GearleverError(f"turned member {turned!r} must be a member of the network other than the carrier")
    sol = network.solve(inputs)
    index = network._index
    rows = [r for r in network._int_rows if _is_train_row(r)] + [((index[carrier], 1),)]
    expr = _Elimination(rows, len(names), frozenset([index[turned]])).expressions()
    t = index[turned]
    if not expr[t]:
        raise GearleverError(
            f"with the carrier {carrier!r} fixed, {turned!r} cannot turn (the train holds it): choose another member"
        )
    x = tuple(a - b for a, b in zip(sol.coefficients[turned], sol.coefficients[carrier]))
    y = tuple(sol.coefficients[carrier])
    out = []
    for j, name in enumerate(names):
        e = expr[j]
        rel = e.get(t, Fraction(0)) if set(e) <= {t} else None
        total = tuple(sol.coefficients[name])
        if rel is not None and tuple(b + rel * a for a, b in zip(x, y)) != total:
            raise GearleverError(f"member {name!r}: the tabular total disagrees with the network solution")
        out.append(TabularRow(member=name, teeth=network._teeth[name], relative=rel, total=total))
    return TabularMethod(carrier=carrier, turned=turned, inputs=sol.inputs, x=x, y=y, rows=tuple(out))
