"""Gear networks as data, solved exactly with rational arithmetic.

A network is a set of members (gears, shafts, carriers, road wheels), some of
them with tooth numbers, tied together by linear constraints on their
rotations.  Three kinds of constraint cover the south-pointing chariots and
the car differential:

``Mesh(label, p, q, sign=1)``
    two gears on fixed axes in mesh: ``n_p*rot_p + sign*n_q*rot_q = 0``.
    ``sign=1`` is the external mesh; ``sign=-1`` is used when the two
    rotations are counted from opposite points of view (a bevel pair such as
    Nuttall (e), "POV to the far right") or for an internal (ring) gear.
``Differential(label, a, b, carrier)``
    side gears ``a`` and ``b`` in mesh through planets held by ``carrier``:
    ``n_a*rot_a + n_b*rot_b - (n_a + n_b)*rot_carrier = 0``; the carrier may
    be the fixed frame.
``SameShaft(label, p, q)``
    ``rot_p = rot_q`` (a rigid coupling).

The fixed frame is the member named :data:`FRAME` (``"frame"``): its rotation
is 0 and it is not an unknown.

:meth:`Network.analyse` returns the number of unknown rotations, the rank of
the constraint matrix, the degrees of freedom and the redundant constraints
(each with the exact combination of earlier constraints it follows from).
:meth:`Network.solve` expresses every member's rotation as an exact linear
function (:class:`fractions.Fraction` coefficients) of chosen input members;
:meth:`Network.solve_float` does the same with numpy in floating point, for
large networks, and is checked against the exact path in the tests.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from gearlever.errors import GearleverError

#: Name of the fixed frame (rotation 0, never an unknown).
FRAME = "frame"


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
    """Two fixed-axis gears in mesh: ``n_p*rot_p + sign*n_q*rot_q = 0``.

    Examples
    --------
    >>> Mesh("d", "7", "8").terms({"7": 10, "8": 20})
    {'7': Fraction(10, 1), '8': Fraction(20, 1)}
    """

    label: str
    p: str
    q: str
    sign: int = 1

    def __post_init__(self):
        _check_name("constraint label", self.label)
        if self.sign not in (1, -1) or isinstance(self.sign, bool):
            raise GearleverError(f"constraint ({self.label}): sign must be 1 or -1, got {self.sign!r}")

    def members(self) -> tuple[str, ...]:
        return (self.p, self.q)

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        """Coefficients of the constraint row (the frame's term dropped)."""
        n_p = _teeth_of(self, teeth, self.p)
        n_q = _teeth_of(self, teeth, self.q)
        return _collect([(self.p, Fraction(n_p)), (self.q, Fraction(self.sign * n_q))])


@dataclass(frozen=True)
class Differential:
    """Side gears ``a``, ``b`` through planets on ``carrier``: ``n_a*rot_a + n_b*rot_b - (n_a+n_b)*rot_c = 0``.

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

    def members(self) -> tuple[str, ...]:
        return (self.a, self.b, self.carrier)

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        n_a = _teeth_of(self, teeth, self.a)
        n_b = _teeth_of(self, teeth, self.b)
        return _collect([(self.a, Fraction(n_a)), (self.b, Fraction(n_b)), (self.carrier, Fraction(-(n_a + n_b)))])


@dataclass(frozen=True)
class SameShaft:
    """Two members rigidly coupled: ``rot_p - rot_q = 0``.

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
        return (self.p, self.q)

    def terms(self, teeth: Mapping[str, int | None]) -> dict[str, Fraction]:
        for name in (self.p, self.q):
            _known(self, teeth, name)
        return _collect([(self.p, Fraction(1)), (self.q, Fraction(-1))])


Constraint = Mesh | Differential | SameShaft


def _known(constraint, teeth, name):
    if name != FRAME and name not in teeth:
        raise GearleverError(f"constraint ({constraint.label}): unknown gear {name!r}")


def _teeth_of(constraint, teeth, name) -> int:
    _known(constraint, teeth, name)
    if name == FRAME:
        return 0  # its rotation is 0: the term drops out whatever its size
    n = teeth[name]
    if n is None:
        raise GearleverError(f"constraint ({constraint.label}): gear {name!r} has no tooth number")
    return n


def _collect(pairs) -> dict[str, Fraction]:
    out: dict[str, Fraction] = {}
    for name, coef in pairs:
        if name == FRAME:
            continue
        out[name] = out.get(name, Fraction(0)) + coef
    return {k: v for k, v in out.items() if v != 0}


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
class NetworkAnalysis:
    """Counts and redundancies of a network's constraint system (exact).

    Attributes
    ----------
    unknowns : number of unknown rotations (members other than the frame).
    rank : rank of the constraint matrix.
    dof : degrees of freedom, ``unknowns - rank``.
    redundant : labels of the constraints that follow from earlier ones (in order).
    dependencies : for each redundant label, ``{earlier label: factor}`` with
        row(redundant) = sum(factor * row(earlier)).
    locked : members the constraints force to stand still (e.g. a carrier
        between equal side gears turning opposite ways), ``{name: label of the
        constraint at which that happens}``.
    """

    unknowns: int
    rank: int
    dof: int
    redundant: tuple[str, ...]
    dependencies: Mapping[str, Mapping[str, Fraction]]
    locked: Mapping[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class NetworkSolution:
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

    Three gears in a ring lock each other, and the error names the constraint:

    >>> ring = Network([Gear("a", 10), Gear("b", 10), Gear("c", 10)],
    ...                [Mesh("ab", "a", "b"), Mesh("bc", "b", "c"), Mesh("ca", "c", "a")])
    >>> ring.analyse()  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: network is inconsistent: constraint (ca) locks gears 'a', 'b', 'c' ...

    Notes
    -----
    Rows: mesh ``n_p rot_p + n_q rot_q = 0``, differential
    ``n_a rot_a + n_b rot_b - (n_a+n_b) rot_c = 0``, same shaft ``rot_p = rot_q``
    (reference README, "The generic differential"; Nuttall (a)-(i)).
    """

    gears: tuple[Gear, ...]
    constraints: tuple[Constraint, ...]
    _teeth: Mapping[str, int | None] = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        gears = tuple(self.gears)
        constraints = tuple(self.constraints)
        for g in gears:
            if not isinstance(g, Gear):
                raise GearleverError(f"gears must be Gear objects, got {g!r}")
        for c in constraints:
            if not isinstance(c, (Mesh, Differential, SameShaft)):
                raise GearleverError(f"constraints must be Mesh, Differential or SameShaft, got {c!r}")
        names = [g.name for g in gears]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise GearleverError(f"gear {dup[0]!r} is defined more than once")
        labels = [c.label for c in constraints]
        dupl = sorted({x for x in labels if labels.count(x) > 1})
        if dupl:
            raise GearleverError(f"constraint label {dupl[0]!r} is used more than once")
        teeth = {g.name: g.teeth for g in gears}
        for c in constraints:
            ms = c.members()
            if len(set(ms)) != len(ms):
                raise GearleverError(f"constraint ({c.label}): a member appears twice in {ms}")
            c.terms(teeth)  # unknown gear / missing teeth -> ValueError naming the constraint
        object.__setattr__(self, "gears", gears)
        object.__setattr__(self, "constraints", constraints)
        object.__setattr__(self, "_teeth", teeth)

    @property
    def names(self) -> tuple[str, ...]:
        """Names of the unknown rotations, in the order given."""
        return tuple(g.name for g in self.gears)

    def matrix(self) -> list[list[Fraction]]:
        """Exact constraint matrix: one row per constraint, one column per member."""
        col = {n: j for j, n in enumerate(self.names)}
        rows = []
        for c in self.constraints:
            row = [Fraction(0)] * len(col)
            for name, coef in c.terms(self._teeth).items():
                row[col[name]] += coef
            rows.append(row)
        return rows

    def matrix_float(self) -> np.ndarray:
        """The constraint matrix in float64 (for the numpy path)."""
        m = self.matrix()
        return np.array([[float(x) for x in r] for r in m], dtype=float).reshape(len(m), len(self.names))

    def analyse(self) -> NetworkAnalysis:
        """Unknowns, rank, dof and redundant constraints; raise if the network is locked.

        Constraints are taken in order; one whose row is a combination of the
        rows before it is redundant.  The network is inconsistent (a locked
        train) when the constraints force every member to stand still, or
        force still a gear that meshes with another moving member: the
        ValueError names the constraint at which that happens.  Other members
        forced still are listed in ``locked``.

        Examples
        --------
        >>> net = Network([Gear("a", 30), Gear("b", 20), Gear("c")],
        ...               [Differential("w", "a", "b", "c"), Differential("w2", "a", "b", "c")])
        >>> a = net.analyse()
        >>> a.unknowns, a.rank, a.dof, a.redundant, a.dependencies["w2"]
        (3, 1, 2, ('w2',), {'w': Fraction(1, 1)})

        Notes
        -----
        Incremental Gauss-Jordan elimination over the rationals; each basis row
        carries the combination of constraints it came from, so a row that
        reduces to zero gives its dependency exactly.  Nuttall: (e) = (d) - (c).
        """
        names = self.names
        n = len(names)
        basis: list[tuple[int, list[Fraction], dict[str, Fraction]]] = []
        redundant: list[str] = []
        deps: dict[str, dict[str, Fraction]] = {}
        locked: dict[int, str] = {}
        # gears meshing with another moving member: if one of them is forced still the train is jammed
        meshing = {m for c in self.constraints if isinstance(c, Mesh) and FRAME not in (c.p, c.q) for m in (c.p, c.q)}
        for c, row0 in zip(self.constraints, self.matrix()):
            row = list(row0)
            combo = {c.label: Fraction(1)}
            for piv, brow, bcombo in basis:
                f = row[piv]
                if f:
                    row = [x - f * y for x, y in zip(row, brow)]
                    for k, v in bcombo.items():
                        combo[k] = combo.get(k, Fraction(0)) - f * v
            nz = [j for j, x in enumerate(row) if x]
            if not nz:
                redundant.append(c.label)
                deps[c.label] = {k: -v for k, v in combo.items() if k != c.label and v}
                continue
            piv = nz[0]
            f = row[piv]
            row = [x / f for x in row]
            combo = {k: v / f for k, v in combo.items()}
            new_basis = []
            for bp, brow, bcombo in basis:
                g = brow[piv]
                if g:
                    brow = [x - g * y for x, y in zip(brow, row)]
                    bcombo = dict(bcombo)
                    for k, v in combo.items():
                        bcombo[k] = bcombo.get(k, Fraction(0)) - g * v
                new_basis.append((bp, brow, bcombo))
            basis = new_basis + [(piv, row, combo)]
            now_locked = {bp for bp, brow, _ in basis if sum(1 for x in brow if x) == 1}
            fresh = now_locked - set(locked)
            jammed = sorted(j for j in fresh if names[j] in meshing)
            if jammed or (n and len(now_locked) == n):
                who = sorted(fresh)
                what = (
                    f"gears {', '.join(repr(names[j]) for j in who)} (forces them to stand still)"
                    if len(who) > 1
                    else f"gear {names[who[0]]!r} (forces it to stand still)"
                )
                raise GearleverError(f"network is inconsistent: constraint ({c.label}) locks {what}")
            locked.update({j: c.label for j in fresh})
        rank = len(basis)
        return NetworkAnalysis(
            unknowns=n,
            rank=rank,
            dof=n - rank,
            redundant=tuple(redundant),
            dependencies={k: dict(v) for k, v in deps.items()},
            locked={names[j]: label for j, label in sorted(locked.items())},
        )

    def _check_inputs(self, inputs, dof) -> tuple[str, ...]:
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
        if len(inputs) != dof:
            raise GearleverError(
                f"inputs: the network has {dof} degree(s) of freedom, "
                f"so it needs {dof} input(s), got {len(inputs)} {list(inputs)}"
            )
        return inputs

    def solve(self, inputs: Sequence[str]) -> NetworkSolution:
        """Every member's rotation as an exact linear function of ``inputs``.

        Raises ValueError if the inputs are not independent (a constraint ties
        them together), naming the constraints involved.

        Examples
        --------
        Willis for a differential (30 and 20 teeth) with the carrier held:

        >>> net = Network([Gear("a", 30), Gear("b", 20), Gear("c")], [Differential("w", "a", "b", "c")])
        >>> net.solve(["a", "c"]).relation("b")
        'rot_b = -3/2*rot_a + 5/2*rot_c'

        Notes
        -----
        Reduced row echelon form of the constraint matrix (exact), pivots taken
        first among the non-input members: each of them is then
        ``rot = -sum(R[row, input] * rot_input)``.  A pivot on an input column
        is a relation among the inputs, reported with its constraints.
        """
        analysis = self.analyse()
        inputs = self._check_inputs(inputs, analysis.dof)
        names = self.names
        others = [j for j, nm in enumerate(names) if nm not in inputs]
        in_cols = [names.index(nm) for nm in inputs]
        rows = self.matrix()
        labels = [c.label for c in self.constraints]
        m = len(rows)
        aug = [list(r) + [Fraction(int(i == k)) for k in range(m)] for i, r in enumerate(rows)]
        order = others + in_cols
        pivots: list[int] = []
        r = 0
        for col in order:
            p = next((i for i in range(r, m) if aug[i][col]), None)
            if p is None:
                continue
            aug[r], aug[p] = aug[p], aug[r]
            f = aug[r][col]
            aug[r] = [x / f for x in aug[r]]
            for i in range(m):
                if i != r and aug[i][col]:
                    g = aug[i][col]
                    aug[i] = [x - g * y for x, y in zip(aug[i], aug[r])]
            pivots.append(col)
            r += 1
        n = len(names)
        for i, col in enumerate(pivots):
            if col in in_cols:
                rel = {names[j]: aug[i][j] for j in in_cols if aug[i][j]}
                used = [labels[k] for k in range(m) if aug[i][n + k]]
                raise GearleverError(
                    f"inputs {list(inputs)} are not independent: constraints "
                    f"({'), ('.join(used)}) force {format_linear(rel)} = 0"
                )
        coefs: dict[str, tuple[Fraction, ...]] = {}
        row_of = {col: i for i, col in enumerate(pivots)}
        for j, nm in enumerate(names):
            if nm in inputs:
                coefs[nm] = tuple(Fraction(int(nm == k)) for k in inputs)
            else:
                i = row_of[j]  # every other member is a pivot: rank == len(others) here
                coefs[nm] = tuple(-aug[i][c] for c in in_cols)
        return NetworkSolution(inputs=inputs, coefficients=coefs, analysis=analysis)

    def solve_float(self, inputs: Sequence[str], rtol: float = 1e-10) -> np.ndarray:
        """Float path: matrix (members x inputs) of d rot_member / d rot_input by numpy.

        Rows follow :attr:`names`.  The rank is taken from the singular values
        with tolerance ``rtol`` (relative to the largest); dependent inputs or
        an undetermined member raise ValueError.

        Examples
        --------
        >>> net = Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")])
        >>> net.solve_float(["p"]).ravel().tolist()
        [1.0, -0.5]

        Notes
        -----
        Least squares ``A_o X = -A_i`` (numpy ``lstsq``) on the float constraint
        matrix split into non-input and input columns; exact when ``A_o`` has
        full column rank, which is checked first.
        """
        A = self.matrix_float()
        n = len(self.names)
        if A.shape[0]:
            s = np.linalg.svd(A, compute_uv=False)
            rank = int(np.sum(s > rtol * s[0])) if s.size and s[0] > 0 else 0
        else:
            rank = 0
        inputs = self._check_inputs(inputs, n - rank)
        in_cols = [self.names.index(nm) for nm in inputs]
        others = [j for j in range(n) if j not in in_cols]
        A_o, A_i = A[:, others], A[:, in_cols]
        if others:
            s_o = np.linalg.svd(A_o, compute_uv=False) if A_o.size else np.zeros(0)
            r_o = int(np.sum(s_o > rtol * s_o[0])) if s_o.size and s_o[0] > 0 else 0
            if r_o < len(others):
                raise GearleverError(f"inputs {list(inputs)} are not independent (float rank test)")
            X, *_ = np.linalg.lstsq(A_o, -A_i, rcond=None)
        out = np.zeros((n, len(inputs)))
        out[in_cols, range(len(inputs))] = 1.0
        if others:
            out[others, :] = X
        return out


def parse_network(text: str, teeth: Mapping[str, int] | None = None) -> Network:
    """Read a network from CSV records (the format of ``gearlever/data/nuttall_network.csv``).

    One record per line, ``#`` lines are comments::

        member,NAME,KIND,TEETH,,,,DESCRIPTION
        constraint,LABEL,differential|mesh|shaft,FIRST,SECOND,CARRIER,SIGN,DESCRIPTION

    ``TEETH`` is a positive integer, empty (no teeth), or a symbol looked up in
    ``teeth`` (e.g. ``n2``).  A differential's carrier may be ``frame``; a
    mesh's ``SIGN`` is 1 (default) or -1.  Errors name the line.

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
                    rows.append(Mesh(rec[1], rec[3], rec[4], int(sign)))
                elif kind == "shaft":
                    rows.append(SameShaft(rec[1], rec[3], rec[4]))
                else:
                    raise GearleverError(
                        f"constraint ({rec[1]}): kind must be differential, mesh or shaft, got {rec[2]!r}"
                    )
            else:
                raise GearleverError(f"record must start with 'member' or 'constraint', got {rec[0]!r}")
        except ValueError as exc:
            raise GearleverError(f"network line {k}: {exc}") from None
    return Network(gears, rows)
