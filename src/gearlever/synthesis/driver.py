"""The one multistart driver of every searched synthesis: seeded starts, a polish each, a named record per start.

A *problem* (:class:`Problem`) is what a search needs to know of a
synthesis: its box (:attr:`Problem.lo`, :attr:`Problem.hi`), a seeded
sampling of feasible-looking candidates (:meth:`Problem.sample`), a batched
objective (:meth:`Problem.objective`, ``inf`` for an infeasible candidate:
that is the feasibility rule), the candidate evaluations it has spent
(:attr:`Problem.evaluations`) and a local polish (:meth:`Problem.polish`,
one signature for every family).  :func:`multistart` runs ``starts`` starts
of it: start ``k`` draws from ``numpy.random.default_rng([seed, k])``, runs
a global search of ``budget // starts`` evaluations
(:func:`search_start`: differential evolution, or CMA-ES for comparison)
and polishes its best; the starts are reduced by (objective at
:data:`~gearlever.synthesis._dask.TIE_DIGITS` digits, start index), so the
answer does not depend on the workers: ``workers`` is an int (local dask
threads), a map-like (anything with ``.map``, e.g. a
:class:`concurrent.futures.Executor`) or the address of a running
``dask.distributed`` scheduler.

The path (:mod:`gearlever.synthesis.path`), law
(:mod:`gearlever.synthesis.law.driver`) and curve
(:mod:`gearlever.synthesis.curve.search`) syntheses are uses of :func:`multistart`;
each returns the records of :class:`Start`.  A family whose start is not a
box search (the curve's: refinement, topology moves, NSGA-II) passes its own
``start`` function.

The one budget rule is :func:`check_budget`: an integer (a float only when
it is a whole number) within the family's bounds, refused with one wording.
What ``evaluations`` counts: the global search's candidate evaluations
(at most the budget); the polish's are counted apart
(:attr:`Start.polish_evaluations`); each family's result states which it
reports.

Imports numpy, :mod:`gearlever.errors` and the leaf modules
:mod:`gearlever.synthesis._search` and :mod:`gearlever.synthesis._dask`.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

import numpy as np

from gearlever.errors import GearleverError
from gearlever.synthesis import _dask, _search

__all__ = ["Problem", "Start", "check_budget", "multistart", "population", "search_start"]


@runtime_checkable
class Problem(Protocol):
    """What :func:`multistart` needs of a synthesis problem (one fresh instance per start).

    Attributes
    ----------
    lo, hi : ndarray (d,)
        The search box.
    evaluations : int
        Candidate evaluations spent so far (the objective's and the polish's).

    Notes
    -----
    Feasibility is part of the objective: an infeasible candidate's value is
    ``inf`` (the search never keeps it), as in the penalty form of
    scipy.optimize's global solvers.
    """

    lo: np.ndarray
    hi: np.ndarray
    evaluations: int

    def sample(self, rng: np.random.Generator, m: int) -> np.ndarray:
        """``m`` candidates ``(m, d)`` drawn from ``rng`` (infeasible ones are drawn again)."""

    def objective(self, Z: np.ndarray) -> np.ndarray:
        """Objective of each candidate row of ``Z`` ``(n, d) -> (n,)``; ``inf`` rejects a candidate."""

    def polish(self, x: np.ndarray, rounds: int | None = None) -> tuple:
        """Local polish of the search's best ``x``: ``(x, objective, info)`` (``info`` a dict, e.g. a mode)."""


@dataclass(frozen=True)
class Start:
    """One start of :func:`multistart`: what it found and what it spent.

    Attributes
    ----------
    index : int
        Start index ``k`` (its random stream is ``default_rng([seed, k])``).
    x : ndarray or None
        The polished design vector; None when the search found no feasible candidate.
    objective : float
        Its objective (``inf`` when none was found).
    feasible : bool
        A feasible candidate was found (finite objective).
    evaluations : int
        Candidate evaluations of the global search (at most the start's budget).
    polish_evaluations : int
        Candidate evaluations of the polish (not part of the budget).
    info : dict
        What the family's polish reports beside ``x`` (the path's discrete
        mode, the law's output offset, the curve's designs).
    """

    index: int
    x: np.ndarray | None
    objective: float
    feasible: bool
    evaluations: int
    polish_evaluations: int = 0
    info: dict = field(default_factory=dict)


def check_budget(name: str, value, minimum: int, cap: int, why: str = "") -> int:
    """The budget ``value`` as an int, or the one refusal naming ``name`` and the bounds.

    A whole-number float (``1e5``) is that integer; any other float, a
    bool, text or a number outside ``minimum..cap`` is refused (never
    truncated).  ``why`` explains the minimum (e.g. the starts it must feed).

    Examples
    --------
    >>> check_budget("budget", 1e5, 100, 10**7)
    100000
    >>> try:
    ...     check_budget("budget", 4000.5, 100, 10**7)
    ... except GearleverError as exc:
    ...     print(exc)
    budget must be a whole number from 100 to 10000000, got 4000.5
    """
    ok = isinstance(value, numbers.Integral) and not isinstance(value, bool)
    if not ok and isinstance(value, numbers.Real) and not isinstance(value, bool):
        ok = math.isfinite(float(value)) and float(value) == int(value)
    if ok and minimum <= int(value) <= cap:
        return int(value)
    why = f" ({why})" if why else ""
    raise GearleverError(f"{name} must be a whole number from {minimum} to {cap}{why}, got {value!r}")


def population(d: int) -> int:
    """Population of one start's search over ``d`` variables: ``max(24, 6 d)``.

    >>> population(4), population(10)
    (24, 60)
    """
    return max(24, 6 * int(d))


def search_start(make: Callable[[], Problem], seed: int, k: int, evals: int, method: str = "de") -> Start:
    """One start: a global search of ``evals`` evaluations from ``default_rng([seed, k])``, then the polish.

    The same for the same arguments on any machine, thread or process.
    ``make`` builds the start's own :class:`Problem` (its counters are its
    own).

    Examples
    --------
    >>> from gearlever.synthesis.path import search_problem
    >>> s = search_start(search_problem({"targets": [[0, 0], [1, 0], [1, 1], [0, 1]]}), 0, 3, 2000)
    >>> s.index, s.feasible, s.evaluations <= 2000
    (3, True, True)
    """
    pb = make()
    rng = np.random.default_rng([seed, k])
    if method == "de":
        run = _search.differential_evolution
    elif method == "cma":
        run = _search.cma_es
    else:
        raise GearleverError(f"method must be 'de' or 'cma', got {method!r}")
    z, _, _ = run(pb.objective, pb.lo, pb.hi, rng, budget=evals, pop=population(pb.lo.size), init=pb.sample)
    searched = pb.evaluations  # the global search's (at most ``evals``); the polish is counted apart
    if z is None:
        return Start(k, None, math.inf, False, searched)
    x, f, info = pb.polish(z)
    return Start(k, x, float(f), bool(math.isfinite(f)), searched, pb.evaluations - searched, dict(info))


def _chunk(start, make, seed, ks, evals, method) -> list:
    """``start(make, seed, k, evals, method)`` for each start in ``ks`` (one task)."""
    return [start(make, seed, k, evals, method) for k in ks]


def multistart(
    problem: Callable[[], Problem],
    starts: int,
    seed: int,
    *,
    budget: int,
    workers: Any = None,
    progress: Callable | None = None,
    method: str = "de",
    start: Callable = search_start,
    tie: float | None = None,
) -> list[Start]:
    """Run ``starts`` seeded starts of ``problem``; their :class:`Start` records, best first.

    Parameters
    ----------
    problem : callable
        ``problem()`` returns a fresh :class:`Problem` (one per start).  It
        must pickle for a ``dask.distributed`` scheduler: a module-level
        function over plain data (e.g. :func:`functools.partial`).
    starts : int
        Independent starts, set by the problem and the budget, never by the workers.
    seed : int
        Start ``k`` draws from ``default_rng([seed, k])``.
    budget : int
        Candidate evaluations of the global searches, all starts together:
        each start gets ``budget // starts`` (at least 1).
    workers : int, map-like or str, optional
        Local dask threads (an int; default dask's default), anything with
        a ``.map`` (run in its order), or the address of a running
        ``dask.distributed`` scheduler.
    progress : callable, optional
        ``progress("starts", done, total)`` after each finished chunk of starts.
    method : {"de", "cma"}
    start : callable, optional
        ``start(problem, seed, k, evals, method) -> Start`` (default
        :func:`search_start`); module-level, for the scheduler.
    tie : float, optional
        Objective at or below which a start is exact (exact starts are taken in start order).

    Returns
    -------
    list of Start
        Sorted by (objective at :data:`~gearlever.synthesis._dask.TIE_DIGITS`
        digits, index): the same list for any ``workers``.

    Examples
    --------
    >>> from gearlever.synthesis.path import search_problem
    >>> make = search_problem({"targets": [[0, 0], [1, 0], [1, 1], [0, 1]]})
    >>> a = multistart(make, 4, 0, budget=4000, workers=1)
    >>> b = multistart(make, 4, 0, budget=4000, workers=2)
    >>> [s.index for s in a] == [s.index for s in b], a[0].objective == b[0].objective
    (True, True)
    """
    per = max(int(budget) // int(starts), 1)
    out = _dask.run_tasks(_chunk, (start, problem, seed), int(starts), per, method, workers=workers, progress=progress)
    return order(out, lambda s: s.objective, lambda s: s.index, tie)


def order(items, objective: Callable, index: Callable, tie: float | None = None) -> list:
    """``items`` sorted by (``objective`` at :data:`~gearlever.synthesis._dask.TIE_DIGITS` digits, ``index``).

    The last digits of an objective differ between machines (OpenBLAS picks
    its kernels by CPU): compared at that many digits, and with objectives
    at or below ``tie`` (default :data:`~gearlever.synthesis._dask.TIE_FLOOR`
    of the largest finite one) all equal, the order is the same on every
    machine.

    >>> order([(2.0, 1), (1.0000001, 0), (1.0, 2)], lambda r: r[0], lambda r: r[1])
    [(1.0000001, 0), (1.0, 2), (2.0, 1)]
    """
    from gearlever._format import quantize

    fin = [abs(objective(r)) for r in items if math.isfinite(objective(r))]
    floor = float(tie) if tie is not None else (_dask.TIE_FLOOR * max(fin) if fin else 0.0)

    def key(r):
        f = objective(r)
        if not math.isfinite(f):
            return (math.inf, index(r))
        return (0.0 if abs(f) <= floor else quantize(f, 0.0, _dask.TIE_DIGITS), index(r))

    return sorted(items, key=key)
