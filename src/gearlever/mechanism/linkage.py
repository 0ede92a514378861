"""The challenge's form of a planar revolute linkage, its ``.links.json`` file and its dyadic solve plan.

A model file format of its own: :meth:`gearlever.mechanism.Mechanism.load`
opens a ``.links.json`` through :func:`read_linkage_model`, which converts it
to the model dict :func:`linkage_model` (fixed joints ``O<i>``, moving joints
``J<i>``, traced joint ``P``, input the crank) and reads that with the one
loader :func:`gearlever.mechanism.model.model_from_dict`.  The topology
synthesis :mod:`gearlever.synthesis.curve` imports the linkage from here.

A linkage of ``N`` joints is ``x0`` (``N x 2`` sketch positions), ``edges``
(``E x 2`` joint indices, one binary link each), ``fixed_joints`` (the ground
pivots), ``motor`` (``[fixed pivot, crank tip]``, an edge) and
``target_joint`` (the traced joint; absent or ``null``: the last joint the
dyadic solve reaches, as in the challenge).  The linkage is *dyadic*: starting
from the fixed joints and the crank tip, every other joint is joined by
exactly two edges to joints already known when it is reached, so it is placed
by one circle-circle intersection (a dyad), on the side of the line through
its two parents where the sketch has it.

Notes
-----
Definitions of the MIT 2.156 linkage synthesis challenge (A. H. Nobari,
F. Ahmed et al., repository ``ahnobari/2155-Optimization-Challenge-Problem``,
``LINKS.Kinematics``: the dyadic path and the sorted solve order),
implemented from their description.

>>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
>>> lk.target_joint, solve_plan(lk).dyads.tolist()
(3, [[3, 1, 2, 0]])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gearlever._io import read_json_capped
from gearlever.errors import GearleverError
from gearlever.mechanism.modelfile import mechanism_table

__all__ = [
    "Linkage",
    "SolvePlan",
    "joint_names",
    "linkage_from_dict",
    "linkage_model",
    "linkage_to_dict",
    "read_linkage",
    "read_linkage_model",
    "solve_plan",
]

#: File name ending of a linkage in the MIT 2.156 challenge's form.
LINKS_SUFFIX = ".links.json"

#: Most joints a ``.links.json`` may hold (the challenge scores at most 20; more are refused as a size cap).
MAX_JOINTS = 200
#: Largest coordinate accepted.
MAX_COORDINATE = 1e9


@dataclass(frozen=True, eq=False)
class Linkage:
    """A planar revolute linkage in the challenge's form (see the module docstring).

    Attributes
    ----------
    x0 : ndarray, shape (N, 2)
    edges : ndarray of int, shape (E, 2)
    fixed_joints : ndarray of int
    motor : tuple of int
        (fixed pivot, crank tip).
    target_joint : int

    Examples
    --------
    >>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> lk.n_joints, lk.motor, lk.as_dict()["target_joint"]
    (4, (0, 1), 3)
    """

    x0: np.ndarray
    edges: np.ndarray
    fixed_joints: np.ndarray
    motor: tuple
    target_joint: int

    @property
    def n_joints(self) -> int:
        return int(self.x0.shape[0])

    def as_dict(self) -> dict:
        return linkage_to_dict(self)


@dataclass(frozen=True, eq=False)
class SolvePlan:
    """Order of the dyadic solve of one topology.

    Attributes
    ----------
    n : int
        Number of joints.
    pivot, tip : int
        Motor pivot and crank tip.
    fixed : ndarray of int
        Fixed joints.
    dyads : ndarray of int, shape (D, 4)
        One row per solved joint, in solve order: ``[k, i, j, e]``, joint ``k``
        placed from parents ``i < j`` (``e`` unused, kept 0 for padding).
    """

    n: int
    pivot: int
    tip: int
    fixed: np.ndarray
    dyads: np.ndarray

    @property
    def order(self) -> np.ndarray:
        """Joints in solve order: pivot, tip, other fixed joints, then the dyads."""
        rest = [int(f) for f in self.fixed if f != self.pivot]
        return np.array([self.pivot, self.tip, *rest, *self.dyads[:, 0].tolist()], dtype=int)


def _int(where: str, v) -> int:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or (isinstance(v, float) and not v.is_integer()):
        raise GearleverError(f"{where} must be an integer joint index, got {_short_repr(v)}")
    return int(v)


def _short_repr(v) -> str:
    """``repr(v)``, cut to 40 characters (a 5,000-digit integer is not echoed whole)."""
    text = repr(v)
    return text if len(text) <= 40 else text[:37] + "..."


def linkage_from_dict(d, n_max: int = MAX_JOINTS) -> Linkage:
    """Validate a dict in the challenge's form and return a :class:`Linkage`.

    Refused, naming the key: a missing key, ``x0`` not ``N x 2`` finite
    numbers, an edge out of range, a self-loop or a repeated edge, fixed joints
    out of range, a motor that is not ``[fixed joint, moving joint]`` joined
    by an edge, a moving joint with a single edge, a linkage that is not dyadic
    or is over-constrained, a fixed target joint.

    Examples
    --------
    >>> linkage_from_dict({"x0": [[0, 0], [1, 0]], "edges": [[0, 1]], "fixed_joints": [1], "motor": [0, 1]})
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: motor: the pivot 0 must be a fixed joint (fixed_joints [1])
    """
    if not isinstance(d, dict):
        raise GearleverError("the linkage must be a JSON object with keys x0, edges, fixed_joints, motor")
    for key in ("x0", "edges", "fixed_joints", "motor"):
        if key not in d:
            raise GearleverError(f"{key}: missing (keys x0, edges, fixed_joints, motor[, target_joint])")
    try:
        x0 = np.array(d["x0"], dtype=float)
    except (TypeError, ValueError):
        raise GearleverError("x0 must be a list of [x, y] pairs of numbers") from None
    except OverflowError:
        raise GearleverError(f"x0 must hold finite coordinates of size at most {MAX_COORDINATE:g}") from None
    if x0.ndim != 2 or x0.shape[1] != 2 or x0.shape[0] < 2:
        raise GearleverError(f"x0 must be a list of at least 2 [x, y] pairs, got shape {x0.shape}")
    n = x0.shape[0]
    if n > n_max:
        raise GearleverError(f"x0: {n} joints, more than the cap {n_max}")
    if not np.all(np.isfinite(x0)) or np.abs(x0).max() > MAX_COORDINATE:
        raise GearleverError(f"x0 must hold finite coordinates of size at most {MAX_COORDINATE:g}")
    raw_edges = d["edges"]
    if not isinstance(raw_edges, list) or not raw_edges:
        raise GearleverError("edges must be a non-empty list of [i, j] joint pairs")
    edges, seen = [], set()
    for e, pair in enumerate(raw_edges):
        if not isinstance(pair, list) or len(pair) != 2:
            raise GearleverError(f"edges[{e}] must be a pair [i, j], got {pair!r}")
        i, j = (_int(f"edges[{e}]", v) for v in pair)
        if not (0 <= i < n and 0 <= j < n):
            raise GearleverError(f"edges[{e}] = {[i, j]}: joint out of range 0..{n - 1}")
        if i == j:
            raise GearleverError(f"edges[{e}] = {[i, j]}: joins a joint to itself")
        key = (min(i, j), max(i, j))
        if key in seen:
            raise GearleverError(f"edges[{e}] = {[i, j]}: repeated edge")
        seen.add(key)
        edges.append([i, j])
    fx = d["fixed_joints"]
    if not isinstance(fx, list) or not fx:
        raise GearleverError("fixed_joints must be a non-empty list of joint indices")
    fixed = sorted({_int("fixed_joints", v) for v in fx})
    if fixed[0] < 0 or fixed[-1] >= n:
        raise GearleverError(f"fixed_joints: joint out of range 0..{n - 1}")
    mo = d["motor"]
    if not isinstance(mo, list) or len(mo) != 2:
        raise GearleverError(f"motor must be [fixed pivot, crank tip], got {mo!r}")
    pivot, tip = (_int("motor", v) for v in mo)
    if not (0 <= pivot < n and 0 <= tip < n):
        raise GearleverError(f"motor = {[pivot, tip]}: joint out of range 0..{n - 1}")
    if pivot not in fixed:
        raise GearleverError(f"motor: the pivot {pivot} must be a fixed joint (fixed_joints {fixed})")
    if tip in fixed:
        raise GearleverError(f"motor: the crank tip {tip} must not be a fixed joint")
    if (min(pivot, tip), max(pivot, tip)) not in seen:
        raise GearleverError(f"motor = {[pivot, tip]}: the crank must be one of the edges")
    degree = np.zeros(n, dtype=int)
    for i, j in edges:
        degree[i] += 1
        degree[j] += 1
    for k in range(n):
        if k not in fixed and k != tip and degree[k] < 2:
            raise GearleverError(f"edges: joint {k} has {degree[k]} edge(s); a moving joint needs two")
    if float(np.hypot(*(x0[tip] - x0[pivot]))) == 0.0:
        raise GearleverError("x0: the crank has zero length (motor pivot and tip coincide)")
    tgt = d.get("target_joint")
    plan = _plan(n, np.array(edges, dtype=int), np.array(fixed, dtype=int), pivot, tip)
    if tgt is None:
        tgt = int(plan.order[-1])
    else:
        tgt = _int("target_joint", tgt)
        if not 0 <= tgt < n:
            raise GearleverError(f"target_joint = {tgt}: joint out of range 0..{n - 1}")
        if tgt in fixed:
            raise GearleverError(f"target_joint = {tgt}: must be a moving joint (it is fixed)")
    return Linkage(x0 + 0.0, np.array(edges, dtype=int).reshape(-1, 2), np.array(fixed, dtype=int), (pivot, tip), tgt)


def linkage_to_dict(lk: Linkage) -> dict:
    """The challenge's form as plain lists (``json.dumps`` ready)."""
    return {
        "x0": [[float(x), float(y)] for x, y in lk.x0],
        "edges": [[int(i), int(j)] for i, j in lk.edges],
        "fixed_joints": [int(f) for f in lk.fixed_joints],
        "motor": [int(lk.motor[0]), int(lk.motor[1])],
        "target_joint": int(lk.target_joint),
    }


def read_linkage(path, what: str = "DESIGN") -> Linkage:
    """Read and validate a ``.links.json`` file; refusals name the file and the key.

    Examples
    --------
    >>> import json, pathlib, tempfile
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "d.links.json"
    >>> _ = p.write_text(json.dumps({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]}))
    >>> read_linkage(p).target_joint
    3
    """
    d = read_json_capped(path, what)
    try:
        return linkage_from_dict(d)
    except GearleverError as exc:
        raise GearleverError(f"{what} {str(path)!r}: {exc}") from None


def _plan(n, edges, fixed, pivot, tip) -> SolvePlan:
    nbrs = [[] for _ in range(n)]
    for i, j in edges:
        nbrs[int(i)].append(int(j))
        nbrs[int(j)].append(int(i))
    known = np.zeros(n, dtype=bool)
    known[fixed] = True
    known[tip] = True
    unknown = [k for k in range(n) if not known[k]]
    dyads = []
    while unknown:
        for pos, k in enumerate(unknown):
            parents = [p for p in nbrs[k] if known[p]]
            if len(parents) > 2:
                raise GearleverError(
                    f"edges: joint {k} is joined to {len(parents)} known joints {sorted(parents)}: "
                    "over-constrained (a dyad takes two)"
                )
            if len(parents) == 2:
                i, j = sorted(parents)
                dyads.append([k, i, j, 0])
                known[k] = True
                del unknown[pos]
                break
        else:
            raise GearleverError(
                f"edges: joints {unknown} cannot be placed by dyads (the linkage is not dyadic or has more than one "
                "degree of freedom)"
            )
    # an edge between two joints that are both known before either is solved as a child over-constrains
    used = {(min(i, j), max(i, j)) for k, i, j, _ in dyads for i, j in ((k, i), (k, j))}
    used.add((min(pivot, tip), max(pivot, tip)))
    fset = set(int(f) for f in fixed)
    for i, j in edges:
        key = (min(int(i), int(j)), max(int(i), int(j)))
        if key not in used and not (key[0] in fset and key[1] in fset):
            raise GearleverError(f"edges: the edge {list(key)} over-constrains the linkage (it closes no dyad)")
    return SolvePlan(n, int(pivot), int(tip), np.asarray(fixed, dtype=int), np.array(dyads, dtype=int).reshape(-1, 4))


def solve_plan(lk: Linkage) -> SolvePlan:
    """The dyadic solve plan of a linkage (joint order and each solved joint's two parents).

    Examples
    --------
    >>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2], [1, 3]],
    ...     "edges": [[0, 1], [1, 3], [2, 3], [1, 4], [3, 4]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> solve_plan(lk).order.tolist()
    [0, 1, 2, 3, 4]
    """
    return _plan(lk.n_joints, lk.edges, lk.fixed_joints, lk.motor[0], lk.motor[1])


def crank_length(x0, motor) -> float:
    """Length of the crank of a sketch."""
    return math.dist(x0[motor[0]], x0[motor[1]])


# --------------------------------------------------------------------------- as a model
def joint_names(lk: Linkage) -> list[str]:
    """Point name of each joint of ``lk``: ``P`` the traced joint, ``O<i>`` a fixed one, ``J<i>`` a moving one."""
    fixed = {int(f) for f in lk.fixed_joints}
    return ["P" if k == lk.target_joint else (f"O{k}" if k in fixed else f"J{k}") for k in range(lk.n_joints)]


def linkage_model(lk: Linkage, *, name: str = "synthesized linkage", units: str = "") -> dict:
    """Model dict (accepted by :func:`gearlever.mechanism.model_from_dict`) of a :class:`Linkage`.

    Names: the fixed joints ``O<i>``, the moving joints ``J<i>`` (``i`` the
    joint's index in ``x0``), the traced joint ``P``; links ``ground`` (the
    fixed joints), ``crank`` (the motor's edge) and ``L<e>`` for edge ``e``.
    An edge between two fixed joints is part of the ground.

    Examples
    --------
    >>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
    >>> sorted(linkage_model(lk)["links"])
    ['L1', 'L2', 'crank', 'ground']
    """
    names = joint_names(lk)
    fixed = {int(f) for f in lk.fixed_joints}
    points = {names[k]: [float(x) + 0.0, float(y) + 0.0] for k, (x, y) in enumerate(lk.x0)}
    links = {"ground": [names[k] for k in sorted(fixed)]}
    motor = {int(lk.motor[0]), int(lk.motor[1])}
    for e, (i, j) in enumerate(lk.edges):
        i, j = int(i), int(j)
        if i in fixed and j in fixed:
            continue
        key = "crank" if {i, j} == motor else f"L{e}"
        a, b = (i, j) if key != "crank" else (int(lk.motor[0]), int(lk.motor[1]))
        links[key] = [names[a], names[b]]
    links = {"ground": links.pop("ground"), "crank": links.pop("crank"), **links}
    return {"mechanism": mechanism_table(name, units), "points": points, "links": links, "inputs": [{"link": "crank"}]}


def is_linkage_file(path) -> bool:
    """Whether ``path`` names a ``.json`` file (a linkage in the challenge's form), not a TOML model."""
    return str(path).lower().endswith(".json")


def read_linkage_model(path) -> dict:
    """The model dict of a ``.links.json`` file (or a ``.json`` holding ``x0`` and ``edges``); errors name the file.

    The model is named after the file (``d.links.json``: ``d``).

    Examples
    --------
    >>> import json, pathlib, tempfile
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "d.links.json"
    >>> _ = p.write_text(json.dumps({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
    ...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]}))
    >>> read_linkage_model(p)["mechanism"], list(read_linkage_model(p)["points"])
    ({'name': 'd'}, ['O0', 'J1', 'O2', 'P'])
    """
    from pathlib import Path

    p = Path(path)
    data = read_json_capped(p, "model file", where=str(p))
    linkage = str(p).lower().endswith(LINKS_SUFFIX)
    if not linkage and not (isinstance(data, dict) and "x0" in data and "edges" in data):
        raise GearleverError(
            f"{p}: a .json model must be a linkage in the challenge's form (keys x0, edges, fixed_joints, motor); "
            "other models are TOML files"
        )
    name = p.name[: -len(LINKS_SUFFIX)] if linkage else p.stem
    if not (name and len(name) <= 200 and name.isprintable()):
        name = "linkage"
    try:
        return linkage_model(linkage_from_dict(data), name=name)
    except GearleverError as exc:
        raise GearleverError(f"{p}: {exc}") from None
