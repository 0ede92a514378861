"""Gear networks as data, solved exactly with rational arithmetic.

A network is a set of members (gears, shafts, carriers, road wheels), some of
them with tooth numbers, tied together by linear constraints on their
rotations.  Three kinds of constraint cover fixed-axis trains, epicyclic
(planetary) trains, the south-pointing chariots and the car differential:

``Mesh(label, p, q, sign=1, carrier=None)``
    two gears in mesh whose axes are held by ``carrier`` (the Willis relation
    seen from the carrier): ``z_p*(rot_p - rot_c) + sign*z_q*(rot_q - rot_c) = 0``
    with ``rot_c = 0`` when there is no carrier (fixed axes).  ``sign=1`` is
    the external mesh; ``sign=-1`` an internal (ring) gear, or two rotations
    counted from opposite points of view (a bevel pair such as Nuttall (e),
    "POV to the far right").  A planet meshing a sun or a ring on an arm is
    ``Mesh("m", "sun", "planet", carrier="arm")``.
``Differential(label, a, b, carrier)``
    side gears ``a`` and ``b`` in mesh through planets held by ``carrier``:
    ``n_a*rot_a + n_b*rot_b - (n_a + n_b)*rot_carrier = 0``; the carrier may
    be the fixed frame, a side gear may not (its tooth number is needed).
``SameShaft(label, p, q)``
    ``rot_p = rot_q`` (a rigid coupling; ``SameShaft(label, p, FRAME)`` holds
    ``p`` still: that is how a fixed sun or ring is written).

The fixed frame is the member named :data:`FRAME` (``"frame"``): its rotation
is 0 and it is not an unknown.  A gear held still is a member with teeth tied
to the frame by a shaft; a constraint that would need the frame's own tooth
number is refused with an error that says how to write it, never answered by
dropping a term.

Exact rows: :meth:`Constraint.terms(teeth) <Mesh.terms>` gives one
constraint's row ``{member: Fraction}`` and :meth:`Network.rows` all of them
(sparse), :meth:`Network.matrix` the dense matrix; these are the stable public
way to read the constraint system (e.g. for a static force analysis, whose
equilibrium equations are the transpose of these rows).

:meth:`Network.analyse` returns the number of unknown rotations, the rank of
the constraint matrix, the degrees of freedom, the redundant constraints (each
with the exact combination of earlier constraints it follows from) and the
members forced to stand still.  :meth:`Network.solve` expresses every member's
rotation as an exact linear function (:class:`fractions.Fraction`
coefficients) of chosen input members; both use sparse elimination, linear in
the size of networks without fill-in (trains, branches, epicyclics).
:meth:`Network.solve_float` does the same in floating point with a sparse LU
factorisation (scipy, imported only when called), for large networks, and is
checked against the exact path in the tests.
"""

from __future__ import annotations

import heapq
import math
import numbers
from collections import Counter
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.willis import willis_row

#: Name of the fixed frame (rotation 0, never an unknown).
FRAME = "frame"

#: How to write a gear held still (quoted by the errors that refuse the frame as a toothed member).
_HOW_TO_FIX = (
    "declare the fixed gear as a member with teeth tied to the frame "
    "(Gear('G', N) and SameShaft('fix', 'G', 'frame'); CSV: member,G,gear,N and constraint,fix,shaft,G,frame)"
)


def _check_name(what: str, name) -> str:
    if not isinstance(name, str) or not name.strip():
        raise GearleverError(f"{what} must be a non-empty string, got {name!r}")
    return name


@dataclass(frozen=True)
class Gear:
    """A member of a network: a gear (with ``teeth``) or a shaft, wheel or carrier (``teeth=None``).

    Examples
    --------
    >>> Gear("2", 30)
    Gear(name='2', teeth=30)
    >>> Gear("x", 0)
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: gear 'x': teeth must be a positive integer, got 0
    """

    name: str
    teeth: int | None = None

    def __post_init__(self):
        _check_name("gear name", self.name)
        if self.name == FRAME:
            raise GearleverError(f"gear name {FRAME!r} is reserved for the fixed frame")
        t = self.teeth
        if t is None:
            return
        ok = isinstance(t, numbers.Integral) and not isinstance(t, bool)
        if not ok and isinstance(t, numbers.Real) and not isinstance(t, bool):
            ok = float(t).is_integer()
            if ok:
                object.__setattr__(self, "teeth", int(t))
        if not ok or self.teeth < 1:
            raise GearleverError(f"gear {self.name!r}: teeth must be a positive integer, got {t!r}")
        object.__setattr__(self, "teeth", int(self.teeth))


@dataclass(frozen=True)
class Mesh:
    """Two gears in mesh, on fixed axes or on a carrier: ``z_p (rot_p - rot_c) + sign z_q (rot_q - rot_c) = 0``.

    ``rot_c = 0`` when ``carrier`` is None (or the frame).  On fixed axes a
    mesh with the frame holds the other gear still (the frame's term is zero
    whatever its size); on a carrier the frame's tooth number would be needed,
    so that is refused: tie a toothed member to the frame instead.

    Examples
    --------
    >>> Mesh("d", "7", "8").terms({"7": 10, "8": 20})
    {'7': Fraction(10, 1), '8': Fraction(20, 1)}
    >>> Mesh("r", "planet", "ring", sign=-1, carrier="arm").terms({"planet": 18, "ring": 60, "arm": None})
    {'planet': Fraction(18, 1), 'ring': Fraction(-60, 1), 'arm': Fraction(42, 1)}

    Notes
    -----
    Willis' equation: seen from the carrier the pair is a fixed-axis mesh,
    ``(rot_q - rot_c)/(rot_p - rot_c) = -sign z_p/z_q`` (R. Willis,
    *Principles of Mechanism*, 2nd ed., 1870, chapter on epicyclic trains;
    J. E. Shigley and J. J. Uicker, *Theory of Machines and Mechanisms*,
    "planetary gear trains", the formula method).  The same statement in
    floats is :func:`gearlever.gears.willis.driven_speed`.
    """

    label: str
    p: str
    q: str
    sign: int = 1
    carrier: str | None = None

    def __post_init__(self):
        _check_name("constraint label", self.label)
        if self.sign not in (1, -1) or isinstance(self.sign, bool):
            raise GearleverError(f"constraint ({self.label}): sign must be 1 or -1, got {self.sign!r}")
        c = self.carrier
        if c is None:
            return
        _check_name(f"constraint ({self.label}): carrier", c)
        if c in (self.p, self.q):
            raise GearleverError(
                f"constraint ({self.label}): the carrier {c!r} must differ from "
                f"the meshing gears {self.p!r}, {self.q!r}"
            )
        if c != FRAME and FRAME in (self.p, self.q):
            raise GearleverError(
                f"constraint ({self.label}): the frame cannot mesh on carrier {c!r} (its tooth number is needed); "
                + _HOW_TO_FIX
            )

    def members(self) -> tuple[str, ...]:
        """Names the constraint ties together (the carrier last, when there is one)."""
        return (self.p, self.q) if self.carrier is None else (self.p, self.q, self.carrier)

    def _int_terms(self, teeth) -> list[tuple[str, int]]:
        on_carrier = self.carrier is not None and self.carrier != FRAME
        if on_carrier:
            _known(self, teeth, self.carrier)
        n_p = _teeth_of(self, teeth, self.p)
        n_q = _teeth_of(self, teeth, self.q)
        c_p, c_q, c_c = willis_row(n_p, n_q, self.sign)
        pairs = [(self.p, c_p), (self.q, c_q)]
        if on_carrier:
            pairs.append((self.carrier, c_c))
        return pairs

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        """Exact coefficients of the constraint row, ``{member: Fraction}`` (the frame, rotation 0, has none)."""
        return _collect(self._int_terms(teeth))


@dataclass(frozen=True)
class Differential:
    """Side gears ``a``, ``b`` through planets on ``carrier``: ``n_a*rot_a + n_b*rot_b - (n_a+n_b)*rot_c = 0``.

    The carrier may be the frame; a side gear may not (write it as a toothed
    member tied to the frame).

    Examples
    --------
    >>> Differential("c", "6", "8", FRAME).terms({"6": 12, "8": 12})
    {'6': Fraction(12, 1), '8': Fraction(12, 1)}
    """

    label: str
    a: str
    b: str
    carrier: str

    def __post_init__(self):
        _check_name("constraint label", self.label)
        if FRAME in (self.a, self.b):
            raise GearleverError(
                f"constraint ({self.label}): the frame cannot be a side gear of a differential "
                "(its tooth number is needed); " + _HOW_TO_FIX
            )

    def members(self) -> tuple[str, ...]:
        """Names the constraint ties together (side gears, then the carrier)."""
        return (self.a, self.b, self.carrier)

    def _int_terms(self, teeth) -> list[tuple[str, int]]:
        _known(self, teeth, self.carrier)
        c_a, c_b, c_c = willis_row(_teeth_of(self, teeth, self.a), _teeth_of(self, teeth, self.b))
        return [(self.a, c_a), (self.b, c_b), (self.carrier, c_c)]

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        """Exact coefficients of the constraint row, ``{member: Fraction}`` (the frame has none)."""
        return _collect(self._int_terms(teeth))


@dataclass(frozen=True)
class SameShaft:
    """Two members rigidly coupled: ``rot_p - rot_q = 0`` (``q`` may be the frame: ``p`` held still).

    Examples
    --------
    >>> SameShaft("f", "1", "2").terms({"1": None, "2": 30})
    {'1': Fraction(1, 1), '2': Fraction(-1, 1)}
    """

    label: str
    p: str
    q: str

    def __post_init__(self):
        _check_name("constraint label", self.label)

    def members(self) -> tuple[str, ...]:
        """Names the constraint ties together."""
        return (self.p, self.q)

    def _int_terms(self, teeth) -> list[tuple[str, int]]:
        for name in (self.p, self.q):
            _known(self, teeth, name)
        return [(self.p, 1), (self.q, -1)]

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        """Exact coefficients of the constraint row, ``{member: Fraction}`` (the frame has none)."""
        return _collect(self._int_terms(teeth))


Constraint = Mesh | Differential | SameShaft


def _known(constraint, teeth, name):
    if name != FRAME and name not in teeth:
        raise GearleverError(f"constraint ({constraint.label}): unknown gear {name!r}")


def _teeth_of(constraint, teeth, name) -> int:
    _known(constraint, teeth, name)
    if name == FRAME:
        return 0  # only reached on fixed axes, where the frame's term is 0 * rot_frame = 0 whatever its size
    n = teeth[name]
    if n is None:
        raise GearleverError(f"constraint ({constraint.label}): gear {name!r} has no tooth number")
    return n


def _merge(pairs) -> dict[str, int]:
    out: dict[str, int] = {}
    for name, coef in pairs:
        if name == FRAME:
            continue  # rot_frame = 0: its term is zero
        out[name] = out.get(name, 0) + coef
    return {k: v for k, v in out.items() if v != 0}


def _collect(pairs) -> dict[str, Fraction]:
    return {k: Fraction(v) for k, v in _merge(pairs).items()}


def _fmt(coef: Fraction) -> str:
    return str(coef.numerator) if coef.denominator == 1 else f"{coef.numerator}/{coef.denominator}"


def format_linear(terms: Mapping[str, Fraction]) -> str:
    """Write ``{name: coef}`` as ``"c1*rot_a + c2*rot_b"`` (``"0"`` when empty).

    >>> from fractions import Fraction
    >>> format_linear({"1": Fraction(-1, 2), "12": Fraction(1, 2)})
    '-1/2*rot_1 + 1/2*rot_12'
    """
    parts = []
    for name, c in terms.items():
        if c == 0:
            continue
        mag = abs(c)
        body = f"rot_{name}" if mag == 1 else f"{_fmt(mag)}*rot_{name}"
        if not parts:
            parts.append(body if c > 0 else f"-{body}")
        else:
            parts.append(("+ " if c > 0 else "- ") + body)
    return " ".join(parts) if parts else "0"


@dataclass(frozen=True)
class NetworkAnalysis(Result):
    """Counts and redundancies of a network's constraint system (exact).

    Attributes
    ----------
    unknowns : number of unknown rotations (members other than the frame).
    rank : rank of the constraint matrix.
    dof : degrees of freedom, ``unknowns - rank``.
    redundant : labels of the constraints that follow from earlier ones (in order).
    dependencies : for each redundant label, ``{earlier label: factor}`` with
        row(redundant) = sum(factor * row(earlier)), in constraint order.
    locked : members the constraints force to stand still (e.g. a carrier
        between equal side gears turning opposite ways, a ring tied to the
        frame), ``{name: label of the first constraint with which that happens}``.
    """

    unknowns: int
    rank: int
    dof: int
    redundant: tuple[str, ...]
    dependencies: Mapping[str, Mapping[str, Fraction]]
    locked: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class NetworkSolution(Result):
    """Every member's rotation as an exact linear function of the input members.

    ``coefficients[name][k]`` is the factor of ``rot_inputs[k]`` in ``rot_name``.
    """

    inputs: tuple[str, ...]
    coefficients: Mapping[str, tuple[Fraction, ...]]
    analysis: NetworkAnalysis

    @property
    def dof(self) -> int:
        return self.analysis.dof

    @property
    def redundant(self) -> tuple[str, ...]:
        return self.analysis.redundant

    def relation(self, name: str) -> str:
        """``"rot_name = ..."`` in terms of the inputs, with exact fractions."""
        coefs = self._row(name)
        return f"rot_{name} = " + format_linear(dict(zip(self.inputs, coefs)))

    def _row(self, name: str) -> tuple[Fraction, ...]:
        if name == FRAME:
            return tuple(Fraction(0) for _ in self.inputs)
        try:
            return self.coefficients[name]
        except KeyError:
            raise GearleverError(f"unknown gear {name!r}") from None

    def rotation(self, name: str, inputs: Mapping[str, object]):
        """Rotation of ``name`` for input rotations ``{input name: value}``.

        Exact if the values are ints or Fractions; numpy arrays broadcast.

        >>> net = Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")])
        >>> net.solve(["p"]).rotation("q", {"p": 3})
        Fraction(-3, 2)
        """
        missing = [k for k in self.inputs if k not in inputs]
        extra = [k for k in inputs if k not in self.inputs]
        if missing or extra:
            raise GearleverError(f"inputs must be exactly {list(self.inputs)}, got {list(inputs)}")
        total = 0
        for c, k in zip(self._row(name), self.inputs):
            v = inputs[k]
            total = total + (c * v if isinstance(v, (int, Fraction)) else float(c) * np.asarray(v, float))
        return total

    def matrix(self, names: Sequence[str] | None = None) -> np.ndarray:
        """Float matrix (len(names) x len(inputs)) of the coefficients."""
        names = list(self.coefficients) if names is None else list(names)
        return np.array([[float(c) for c in self._row(n)] for n in names], dtype=float).reshape(
            len(names), len(self.inputs)
        )


class _Elimination:
    """Sparse fraction-free elimination of integer rows, taken in the order given.

    Each new row is reduced by the basis rows whose pivot columns it contains,
    in the order the basis rows were made (a heap of their indices): a basis
    row contains no pivot of an earlier one, so the reduction ends.  The pivot
    of a reduced row is the column with the fewest occurrences in the rows
    still to come (a Markowitz-like choice that keeps chains and branches free
    of fill-in), never a column of ``keep_free`` unless nothing else is left.
    ``history`` records, for every basis row ``B_k``, ``B_k = s_k (A_i -
    sum_j h_kj B_j)`` so that a row which reduces to zero (redundant) gives its
    combination of earlier constraints exactly.
    """

    def __init__(self, rows: Sequence[Sequence[tuple[int, int]]], n: int, keep_free=frozenset(), stop_on_free=False):
        self.n = n
        remaining = [0] * n
        for r in rows:
            for c, _ in r:
                remaining[c] += 1
        self.pivot_of: dict[int, int] = {}  # column -> basis index
        self.basis: list[tuple[int, dict[int, int]]] = []  # (pivot column, int row)
        self.origin: list[int] = []  # constraint index of each basis row
        self.scale: list[Fraction] = []
        self.history: list[dict[int, Fraction]] = []
        self.redundant: list[tuple[int, dict[int, Fraction]]] = []  # (constraint index, h)
        self.free_relation: tuple[int, dict[int, int], dict[int, Fraction], Fraction] | None = None
        for i, r in enumerate(rows):
            row: dict[int, int] = {}
            for c, v in r:
                remaining[c] -= 1
                row[c] = row.get(c, 0) + v
            row = {c: v for c, v in row.items() if v}
            row, hist, scale = self.reduce(row)
            if not row:
                self.redundant.append((i, hist))
                continue
            cand = [c for c in row if c not in keep_free]
            if not cand:
                if stop_on_free:
                    self.free_relation = (i, row, hist, scale)
                    return
                cand = list(row)
            pc = min(cand, key=lambda c: (remaining[c], c))
            k = len(self.basis)
            self.pivot_of[pc] = k
            self.basis.append((pc, row))
            self.origin.append(i)
            self.scale.append(scale)
            self.history.append(hist)

    def reduce(self, row: dict[int, int]) -> tuple[dict[int, int], dict[int, Fraction], Fraction]:
        """Reduce an integer row by the basis: ``(rest, h, s)`` with ``rest = s (row - sum_k h[k] B_k)``.

        ``rest`` has no pivot column of the basis; it is empty when ``row`` is
        in the span of the basis rows, and then ``h`` are its coordinates.
        """
        scale = Fraction(1)
        hist: dict[int, Fraction] = {}
        heap = [self.pivot_of[c] for c in row if c in self.pivot_of]
        heapq.heapify(heap)
        seen = set(heap)
        while heap:
            k = heapq.heappop(heap)
            pc, brow = self.basis[k]
            rp = row.get(pc)
            if not rp:
                continue
            bp = brow[pc]
            # row' = bp*row - rp*B_k = (bp*scale) * (A_i - sum h B - rp/(bp*scale) B_k)
            hist[k] = hist.get(k, Fraction(0)) + Fraction(rp) / (bp * scale)
            new = {c: bp * v for c, v in row.items()}
            for c, v in brow.items():
                w = new.get(c, 0) - rp * v
                if w:
                    new[c] = w
                else:
                    new.pop(c, None)
                    continue
                j = self.pivot_of.get(c)
                if j is not None and j not in seen:
                    seen.add(j)
                    heapq.heappush(heap, j)
            scale *= bp
            g = math.gcd(*new.values()) if new else 1
            if g > 1:
                new = {c: v // g for c, v in new.items()}
                scale /= g
            row = new
        return row, hist, scale

    @property
    def rank(self) -> int:
        return len(self.basis)

    def combination(self, i: int, hist: Mapping[int, Fraction], scale: Fraction = Fraction(1)) -> dict[int, Fraction]:
        """``{constraint index: factor}`` of the row ``scale (A_i - sum_k hist[k] B_k)`` in terms of constraint rows."""
        out: dict[int, Fraction] = {i: Fraction(scale)}
        coef: dict[int, Fraction] = {k: -scale * h for k, h in hist.items() if h}
        heap = [-k for k in coef]
        heapq.heapify(heap)
        while heap:
            k = -heapq.heappop(heap)
            c = coef.pop(k, 0)
            if not c:
                continue
            s = self.scale[k]
            o = self.origin[k]
            out[o] = out.get(o, Fraction(0)) + c * s
            for j, h in self.history[k].items():
                if j not in coef:
                    heapq.heappush(heap, -j)
                coef[j] = coef.get(j, Fraction(0)) - c * s * h
        return {k: v for k, v in sorted(out.items()) if v}

    def expressions(self) -> dict[int, dict[int, Fraction]]:
        """Every column as an exact combination ``{free column: factor}`` of the non-pivot (free) columns."""
        expr: dict[int, dict[int, Fraction]] = {}
        for c in range(self.n):
            if c not in self.pivot_of:
                expr[c] = {c: Fraction(1)}
        for pc, brow in reversed(self.basis):
            bp = brow[pc]
            acc: dict[int, Fraction] = {}
            for c, v in brow.items():
                if c == pc:
                    continue
                f = Fraction(-v, bp)
                for fc, fv in expr[c].items():
                    acc[fc] = acc.get(fc, 0) + f * fv
            expr[pc] = {c: v for c, v in acc.items() if v}
        return expr


@dataclass(frozen=True)
class Network:
    """Gears and constraints; see the module docstring for the three constraint kinds.

    Examples
    --------
    A two-gear train (20 and 40 teeth) has one degree of freedom:

    >>> net = Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")])
    >>> net.analyse().dof
    1
    >>> net.solve(["p"]).relation("q")
    'rot_q = -1/2*rot_p'

    A planet on an arm rolling round a fixed 100-tooth sun (Ferguson's paradox):

    >>> ferguson = Network(
    ...     [Gear("arm"), Gear("sun", 100), Gear("planet", 20), Gear("w99", 99), Gear("w101", 101)],
    ...     [SameShaft("fix", "sun", FRAME), Mesh("m", "sun", "planet", carrier="arm"),
    ...      Mesh("a", "w99", "planet", carrier="arm"), Mesh("b", "w101", "planet", carrier="arm")])
    >>> sol = ferguson.solve(["arm"])
    >>> sol.relation("w99"), sol.relation("w101")
    ('rot_w99 = -1/99*rot_arm', 'rot_w101 = 1/101*rot_arm')

    Three gears in a ring lock each other, and the error names the constraint:

    >>> ring = Network([Gear("a", 10), Gear("b", 10), Gear("c", 10)],
    ...                [Mesh("ab", "a", "b"), Mesh("bc", "b", "c"), Mesh("ca", "c", "a")])
    >>> ring.analyse()  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: network is inconsistent: constraint (ca) locks gears 'a', 'b', 'c' ...

    Notes
    -----
    Rows: mesh ``z_p (rot_p - rot_c) + sign z_q (rot_q - rot_c) = 0`` (Willis'
    equation; ``rot_c = 0`` on fixed axes), differential
    ``n_a rot_a + n_b rot_b - (n_a+n_b) rot_c = 0``, same shaft ``rot_p = rot_q``
    (the generic differential of the Nuttall chariot page, constraints (a)-(i)).
    """

    gears: tuple[Gear, ...]
    constraints: tuple[Constraint, ...]
    _teeth: Mapping[str, int | None] = field(init=False, repr=False, compare=False)
    _index: Mapping[str, int] = field(init=False, repr=False, compare=False)
    _int_rows: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        gears = tuple(self.gears)
        constraints = tuple(self.constraints)
        if not gears:
            raise GearleverError("a network needs at least one member, got none")
        for g in gears:
            if not isinstance(g, Gear):
                raise GearleverError(f"gears must be Gear objects, got {g!r}")
        for c in constraints:
            if not isinstance(c, (Mesh, Differential, SameShaft)):
                raise GearleverError(f"constraints must be Mesh, Differential or SameShaft, got {c!r}")
        names = Counter(g.name for g in gears)
        dup = sorted(n for n, k in names.items() if k > 1)
        if dup:
            raise GearleverError(f"gear {dup[0]!r} is defined more than once")
        labels = Counter(c.label for c in constraints)
        dupl = sorted(x for x, k in labels.items() if k > 1)
        if dupl:
            raise GearleverError(f"constraint label {dupl[0]!r} is used more than once")
        teeth = {g.name: g.teeth for g in gears}
        index = {g.name: j for j, g in enumerate(gears)}
        rows = []
        for c in constraints:
            ms = c.members()
            if len(set(ms)) != len(ms):
                raise GearleverError(f"constraint ({c.label}): a member appears twice in {ms}")
            terms = _merge(c._int_terms(teeth))  # unknown gear / missing teeth -> error naming the constraint
            rows.append(tuple((index[k], v) for k, v in terms.items()))
        object.__setattr__(self, "gears", gears)
        object.__setattr__(self, "constraints", constraints)
        object.__setattr__(self, "_teeth", teeth)
        object.__setattr__(self, "_index", index)
        object.__setattr__(self, "_int_rows", tuple(rows))

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the unknown rotations, in the order given."""
        return tuple(g.name for g in self.gears)

    @property
    def teeth(self) -> Mapping[str, int | None]:
        """``{member: tooth number or None}`` (the argument of :meth:`Mesh.terms` and its siblings)."""
        return dict(self._teeth)

    def rows(self) -> list[dict[str, Fraction]]:
        """Exact constraint rows, one ``{member: Fraction}`` per constraint, in order (sparse; stable API).

        ``rows()[k]`` equals ``constraints[k].terms(teeth)``: the row of the
        constraint ``sum(coef * rot_member) = 0``.

        >>> Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")]).rows()
        [{'p': Fraction(20, 1), 'q': Fraction(40, 1)}]
        """
        names = self.names
        return [{names[j]: Fraction(v) for j, v in r} for r in self._int_rows]

    def matrix(self) -> list[list[Fraction]]:
        """Exact dense constraint matrix: one row per constraint, one column per member (:attr:`names`)."""
        n = len(self.gears)
        out = []
        for r in self._int_rows:
            row = [Fraction(0)] * n
            for j, v in r:
                row[j] = Fraction(v)
            out.append(row)
        return out

    def matrix_float(self) -> np.ndarray:
        """The dense constraint matrix in float64."""
        A = np.zeros((len(self._int_rows), len(self.gears)))
        for i, r in enumerate(self._int_rows):
            for j, v in r:
                A[i, j] = v
        return A

    def _coo(self):
        rows, cols, vals = [], [], []
        for i, r in enumerate(self._int_rows):
            for j, v in r:
                rows.append(i)
                cols.append(j)
                vals.append(v)
        return np.array(rows, dtype=np.int64), np.array(cols, dtype=np.int64), np.array(vals, dtype=float)

    def matrix_sparse(self):
        """The constraint matrix as a ``scipy.sparse.csr_array`` of float64 (scipy imported here)."""
        import scipy.sparse as sp

        r, c, v = self._coo()
        return sp.csr_array((v, (r, c)), shape=(len(self._int_rows), len(self.gears)))

    def _elimination(self, keep_free=frozenset(), stop_on_free=False) -> _Elimination:
        return _Elimination(self._int_rows, len(self.gears), keep_free, stop_on_free)

    def analyse(self) -> NetworkAnalysis:
        """Unknowns, rank, dof and redundant constraints; raise if the network is locked.

        Constraints are taken in order; one whose row is a combination of the
        rows before it is redundant.  The network is inconsistent (a locked
        train) when the constraints force every member to stand still, or
        force still a gear meshing on fixed axes with another moving member:
        the error names the constraint at which that happens.  Other members
        forced still (a fixed sun or ring, a gear the train holds still) are
        listed in ``locked``.

        Examples
        --------
        >>> net = Network([Gear("a", 30), Gear("b", 20), Gear("c")],
        ...               [Differential("w", "a", "b", "c"), Differential("w2", "a", "b", "c")])
        >>> a = net.analyse()
        >>> a.unknowns, a.rank, a.dof, a.redundant, a.dependencies["w2"]
        (3, 1, 2, ('w2',), {'w': Fraction(1, 1)})

        Notes
        -----
        Sparse fraction-free Gaussian elimination over the integers, rows in
        the order given, pivots chosen to avoid fill-in; each basis row keeps
        the multipliers it was reduced with, so a row that reduces to zero
        gives its dependency exactly (Nuttall: (e) = (d) - (c)).  Members
        forced still are the columns that back-substitution expresses as 0;
        the constraint that forces each is the latest one its unit row needs
        from the basis.
        """
        names = self.names
        n = len(names)
        el = self._elimination()
        labels = [c.label for c in self.constraints]
        deps = {}
        for i, hist in el.redundant:
            combo = el.combination(i, hist)
            deps[labels[i]] = {labels[k]: -v for k, v in combo.items() if k != i}
        still = {j for j, e in el.expressions().items() if not e}
        when = self._lock_points(el, still)
        meshing = {
            self._index[m]
            for c in self.constraints
            if isinstance(c, Mesh) and c.carrier in (None, FRAME) and FRAME not in (c.p, c.q)
            for m in (c.p, c.q)
        }
        triggers = [when[j] for j in still & meshing]
        if n and len(still) == n:
            triggers.append(max(when.values()))
        if triggers:
            at = min(triggers)
            who = sorted(j for j, k in when.items() if k == at)
            what = (
                f"gears {', '.join(repr(names[j]) for j in who)} (forces them to stand still)"
                if len(who) > 1
                else f"gear {names[who[0]]!r} (forces it to stand still)"
            )
            raise GearleverError(f"network is inconsistent: constraint ({labels[at]}) locks {what}")
        return NetworkAnalysis(
            unknowns=n,
            rank=el.rank,
            dof=n - el.rank,
            redundant=tuple(labels[i] for i, _ in el.redundant),
            dependencies=deps,
            locked={names[j]: labels[k] for j, k in sorted(when.items())},
        )

    @staticmethod
    def _lock_points(el: _Elimination, still: set[int]) -> dict[int, int]:
        """For each member forced still, the index of the first constraint after which it is.

        ``e_j`` lies in the span of the basis rows; its coordinates are unique,
        and the basis rows made from the first ``p`` constraints span exactly
        the rows of those constraints, so the answer is the latest origin among
        the basis rows ``e_j`` needs.
        """
        out: dict[int, int] = {}
        for j in sorted(still):
            rest, hist, _ = el.reduce({j: 1})
            if rest:  # j was found forced still, so e_j must lie in the row space
                raise RuntimeError(f"internal error: member {j} is forced still but not in the row space")
            out[j] = max(el.origin[k] for k, h in hist.items() if h)
        return out

    def _check_inputs(self, inputs, dof=None) -> tuple[str, ...]:
        if isinstance(inputs, str):
            inputs = [inputs]
        inputs = tuple(inputs)
        for name in inputs:
            if name == FRAME:
                raise GearleverError(f"input {FRAME!r} cannot be driven: it is the fixed frame")
            if name not in self._teeth:
                raise GearleverError(f"unknown gear {name!r} in inputs")
        if len(set(inputs)) != len(inputs):
            raise GearleverError(f"inputs must be distinct, got {list(inputs)}")
        if dof is not None and len(inputs) != dof:
            raise GearleverError(
                f"inputs: the network has {dof} degree(s) of freedom, "
                f"so it needs {dof} input(s), got {len(inputs)} {list(inputs)}"
            )
        return inputs

    def solve(self, inputs: Sequence[str]) -> NetworkSolution:
        """Every member's rotation as an exact linear function of ``inputs``.

        Raises an error if the inputs are not independent (a constraint ties
        them together), naming the constraints involved.

        Examples
        --------
        Willis for a differential (30 and 20 teeth) with the carrier held:

        >>> net = Network([Gear("a", 30), Gear("b", 20), Gear("c")], [Differential("w", "a", "b", "c")])
        >>> net.solve(["a", "c"]).relation("b")
        'rot_b = -3/2*rot_a + 5/2*rot_c'

        Notes
        -----
        Sparse elimination (as in :meth:`analyse`) that never pivots on an
        input column, then back-substitution: each other member is an exact
        combination of the free columns, which are then exactly the inputs.
        A row that reduces to input columns only is a relation among the
        inputs, reported with the constraints it combines.
        """
        analysis = self.analyse()
        inputs = self._check_inputs(inputs, analysis.dof)
        names = self.names
        in_cols = [self._index[nm] for nm in inputs]
        el = self._elimination(keep_free=frozenset(in_cols), stop_on_free=True)
        if el.free_relation is not None:
            i, row, hist, scale = el.free_relation
            lead = row[min(row)]
            rel = {names[j]: Fraction(v, lead) for j, v in sorted(row.items())}
            labels = [c.label for c in self.constraints]
            used = [labels[k] for k in el.combination(i, hist, scale)]
            raise GearleverError(
                f"inputs {list(inputs)} are not independent: constraints ({'), ('.join(used)}) force "
                f"{format_linear(rel)} = 0"
            )
        expr = el.expressions()
        coefs = {nm: tuple(expr[j].get(c, Fraction(0)) for c in in_cols) for j, nm in enumerate(names)}
        return NetworkSolution(inputs=inputs, coefficients=coefs, analysis=analysis)

    def _free_expressions(self, extra_rows=(), keep_free=()) -> dict[str, dict[str, Fraction]]:
        """Every member as ``{free member: factor}`` for the constraints plus ``extra_rows`` (``{name: int}``)."""
        rows = list(self._int_rows) + [tuple((self._index[k], v) for k, v in r.items()) for r in extra_rows]
        keep = frozenset(self._index[k] for k in keep_free)
        expr = _Elimination(rows, len(self.gears), keep).expressions()
        names = self.names
        return {names[j]: {names[c]: v for c, v in e.items()} for j, e in expr.items()}

    def solve_float(self, inputs: Sequence[str], rtol: float = 1e-10) -> np.ndarray:
        """Float path: matrix (members x inputs) of d rot_member / d rot_input by a sparse LU.

        Rows follow :attr:`names`.  Inputs that are dependent, too few or too
        many are refused (a pivot of the factorisation below ``rtol`` times the
        largest, or a residual above ``1e-8``).

        Examples
        --------
        >>> net = Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")])
        >>> net.solve_float(["p"]).ravel().tolist()
        [1.0, -0.5]

        Notes
        -----
        ``A_o X = -A_i`` with ``A`` the float constraint matrix split into
        non-input and input columns: a sparse LU (SuperLU through
        ``scipy.sparse.linalg.splu``) of ``A_o`` when it is square, of the
        normal equations ``A_o^T A_o`` when the network has redundant rows.
        """
        import scipy.sparse as sp
        import scipy.sparse.linalg as spla

        inputs = self._check_inputs(inputs)
        n = len(self.gears)
        m = len(self._int_rows)
        in_cols = [self._index[nm] for nm in inputs]
        newcol = np.full(n, -1, dtype=np.int64)
        is_in = np.zeros(n, bool)
        is_in[in_cols] = True
        others = np.flatnonzero(~is_in)
        newcol[others] = np.arange(others.size)
        r, c, v = self._coo()
        sel = ~is_in[c]
        A_o = sp.csc_array((v[sel], (r[sel], newcol[c[sel]])), shape=(m, others.size))
        B = np.zeros((m, len(inputs)))
        pos = {col: k for k, col in enumerate(in_cols)}
        for ri, ci, vi in zip(r[~sel], c[~sel], v[~sel]):
            B[ri, pos[int(ci)]] -= vi
        out = np.zeros((n, len(inputs)))
        out[in_cols, range(len(inputs))] = 1.0
        if others.size == 0:
            if np.abs(B).max(initial=0) > 0:
                raise GearleverError(f"inputs {list(inputs)} are not independent (float rank test)")
            return out
        why = f"inputs {list(inputs)} are not independent, or not as many as the degrees of freedom (float rank test)"
        if m < others.size:
            raise GearleverError(why)
        square = m == others.size
        M = A_o if square else (A_o.T @ A_o).tocsc()
        rhs = B if square else A_o.T @ B
        try:
            lu = spla.splu(M)
        except RuntimeError:
            raise GearleverError(why) from None
        d = np.abs(lu.U.diagonal())
        if d.size and d.min() <= rtol * d.max():
            raise GearleverError(why)
        X = lu.solve(rhs)
        scale = max(1.0, np.abs(X).max(initial=0))
        if np.abs(A_o @ X - B).max(initial=0) > 1e-8 * scale * max(1.0, np.abs(v).max(initial=0)):
            raise GearleverError(why)
        out[others, :] = X
        return out


def parse_network(text: str, teeth: Mapping[str, int] | None = None) -> Network:
    """Read a network from CSV records (the format of ``gearlever/data/nuttall_network.csv``).

    One record per line, ``#`` lines are comments::

        member,NAME,KIND,TEETH,,,,DESCRIPTION
        constraint,LABEL,mesh,GEAR,GEAR,CARRIER,SIGN,DESCRIPTION
        constraint,LABEL,differential,SIDE,SIDE,CARRIER,,DESCRIPTION
        constraint,LABEL,shaft,MEMBER,MEMBER,,,DESCRIPTION

    ``TEETH`` is a positive integer, empty (no teeth), or a symbol looked up in
    ``teeth`` (e.g. ``n2``).  A mesh's ``CARRIER`` (third column) is empty for
    fixed axes or names the arm that holds both axes; its ``SIGN`` is 1
    (default, external) or -1 (internal, or opposite points of view).  A
    differential's carrier may be ``frame``; a fixed gear is a toothed member
    tied to the frame: ``constraint,fix,shaft,RING,frame``.  A text with no
    member is refused.  Errors name the line.  Time and memory are linear in
    the text.

    Examples
    --------
    >>> net = parse_network('''member,p,gear,20
    ... member,q,gear,n
    ... constraint,pq,mesh,p,q''', teeth={"n": 40})
    >>> net.solve(["p"]).relation("q")
    'rot_q = -1/2*rot_p'
    """
    teeth = dict(teeth or {})
    gears, rows = [], []
    for k, raw in enumerate(text.splitlines(), start=1):
        if not raw.strip() or raw.lstrip().startswith("#"):
            continue
        rec = [x.strip() for x in raw.split(",", 7)]
        rec += [""] * (8 - len(rec))
        kind = rec[2].lower()
        try:
            if rec[0] == "member":
                size = rec[3]
                if not size:
                    n = None
                elif size.lstrip("+-").isdigit():
                    n = int(size)
                elif size in teeth:
                    n = teeth[size]
                else:
                    raise GearleverError(
                        f"gear {rec[1]!r}: tooth number {size!r} is neither an integer nor a given symbol"
                    )
                gears.append(Gear(rec[1], n))
            elif rec[0] == "constraint":
                if kind == "differential":
                    rows.append(Differential(rec[1], rec[3], rec[4], rec[5]))
                elif kind == "mesh":
                    sign = rec[6] or "1"
                    if sign not in ("1", "-1", "+1"):
                        raise GearleverError(f"constraint ({rec[1]}): sign must be 1 or -1, got {sign!r}")
                    rows.append(Mesh(rec[1], rec[3], rec[4], int(sign), carrier=rec[5] or None))
                elif kind == "shaft":
                    if rec[5]:
                        raise GearleverError(
                            f"constraint ({rec[1]}): a shaft joins two members, the third column must be empty, "
                            f"got {rec[5]!r}"
                        )
                    rows.append(SameShaft(rec[1], rec[3], rec[4]))
                else:
                    raise GearleverError(
                        f"constraint ({rec[1]}): kind must be differential, mesh or shaft, got {rec[2]!r}"
                    )
            else:
                raise GearleverError(f"record must start with 'member' or 'constraint', got {rec[0]!r}")
        except ValueError as exc:
            raise GearleverError(f"network line {k}: {exc}") from None
    if not gears:
        raise GearleverError("network has no member records (a network needs at least one 'member' line)")
    return Network(gears, rows)
