"""Exhaustive best search for the tooth numbers of a train, with exact counts.

:func:`search_best` finds, for K pairs with teeth in [t_min, t_max], the
least error ``|prod(drivers) / prod(followers) - r|`` over every train, proves it
(every distinct product of K teeth is examined, against the only followers'
products that can be best for it), counts every optimal tooth set exactly
without listing them (:func:`factorization_counts`: ordered tuples by
multiplicative convolution, multisets by Polya's cycle index), and lists the
first ``limit``.  This is the gear-train problem of Sandgren (1990), ASME J.
Mech. Des. 112: 223-229, for any ratio and any number of pairs.
"""

from __future__ import annotations

import functools
import itertools
import math
import operator
from collections.abc import Iterator
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from gearlever._progress import Progress
from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.trains._caps import (
    DEFAULT_LIMIT,
    DEFAULT_MAX_SPACE,
    MAX_LIMIT,
    MAX_PAIRS,
    MAX_SPACE_CAP,
    capped_int,
    teeth_range,
)
from gearlever.trains.continued import parse_ratio
from gearlever.trains.pairing import best_pairing

__all__ = [
    "DEFAULT_LIMIT",
    "DEFAULT_MAX_SPACE",
    "MAX_LIMIT",
    "MAX_PAIRS",
    "MAX_SPACE_CAP",
    "METRICS",
    "SearchResult",
    "TrainSolution",
    "factorization_counts",
    "search_best",
    "search_space_size",
]

#: Error measures of :func:`search_best`.
METRICS = ("absolute", "relative")

#: Up to this many distinct optimal products, their factorizations are counted
#: by memoized recursion; beyond it, from whole distributions (vectorized).
RECURSIVE_COUNT_MAX = 512

# Driver products handled at once by the neighbour search (4 follower candidates each).
_CHUNK = 1 << 18
# Offsets of the follower candidates around the insertion point of P / r.
_WINDOW = np.arange(-2, 2)


def search_space_size(pairs, min_teeth, max_teeth) -> int:
    """Number of tooth multisets of one side: C(n + K - 1, K), n = max - min + 1.

    Parameters
    ----------
    pairs : int
        K, at most :data:`MAX_PAIRS`.
    min_teeth, max_teeth : int
        Tooth range.

    Returns
    -------
    int

    Notes
    -----
    Multisets of K teeth out of n sizes (combinations with repetition); the
    size checked by :func:`search_best` before it starts.

    Examples
    --------
    >>> search_space_size(5, 12, 60)
    2869685
    """
    k = capped_int("pairs", pairs, MAX_PAIRS)
    lo, hi = teeth_range(min_teeth, max_teeth)
    return math.comb(hi - lo + 1 + k - 1, k)


def _check_space(k: int, lo: int, hi: int, max_space: int) -> int:
    size = math.comb(hi - lo + k, k)
    if size > max_space:
        raise GearleverError(
            f"max_space: search space too large: {size:,} tooth multisets per side for {k} pairs "
            f"of teeth in [{lo}, {hi}] (limit max_space={max_space:,}, at most {MAX_SPACE_CAP:,}); "
            "use fewer pairs, a narrower tooth range (min_teeth to max_teeth) or a larger max_space"
        )
    if hi**k >= 2**52:
        raise GearleverError(
            f"max_teeth: products up to {hi}**{k} are beyond 2**52, too large for an exact float search; "
            "use fewer pairs or smaller teeth"
        )
    return size


def _tick(progress: Progress | None, stage: str, done: int, total: int) -> None:
    if progress is not None:
        progress(stage, done, total)


def _weighted_products(exponents, base: np.ndarray, progress: Progress | None = None, stage: str = ""):
    """Sorted distinct values of prod(t_i ** e_i) over t_i in ``base``, with the number of tuples giving each."""
    vals = np.ones(1, dtype=np.int64)
    cnt = np.ones(1, dtype=np.int64)
    for step, e in enumerate(exponents, start=1):
        b = base**e
        allv = np.multiply.outer(vals, b).ravel()
        allc = np.repeat(cnt, b.size)
        order = np.argsort(allv)
        allv = allv[order]
        allc = allc[order]
        del order
        starts = np.flatnonzero(np.concatenate(([True], allv[1:] != allv[:-1])))
        vals = allv[starts]
        cnt = np.add.reduceat(allc, starts)
        _tick(progress, stage, step, len(exponents))
    return vals, cnt


def _distinct_products(k: int, base: np.ndarray, progress: Progress | None = None) -> np.ndarray:
    """Sorted distinct products of k values of ``base`` (sorting values only: faster than with counts)."""
    prods = base
    _tick(progress, "products", 1, k)
    for step in range(2, k + 1):
        allp = np.multiply.outer(prods, base).ravel()
        allp.sort()
        keep = np.empty(allp.size, dtype=bool)
        keep[0] = True
        np.not_equal(allp[1:], allp[:-1], out=keep[1:])
        prods = allp[keep]
        _tick(progress, "products", step, k)
    return prods


def _recursive_counts(values, k: int, lo: int, hi: int) -> tuple[list[int], list[int]]:
    """Ordered and multiset factorization counts of a few values, by memoized recursion on the factors.

    g(n, k) = sum over t | n of g(n / t, k - 1); f(n, k, m) = sum over d >= m, d | n,
    d**k <= n of f(n / d, k - 1, d).  Nothing is listed.
    """

    @functools.cache
    def g(n: int, j: int) -> int:
        if j == 1:
            return int(lo <= n <= hi)
        if n < lo**j or n > hi**j:
            return 0
        return sum(g(n // t, j - 1) for t in range(lo, min(hi, n // lo ** (j - 1)) + 1) if n % t == 0)

    @functools.cache
    def f(n: int, j: int, m: int) -> int:
        if j == 1:
            return int(m <= n <= hi)
        if n < m**j or n > hi**j:
            return 0
        total, d = 0, m
        while d <= hi and d**j <= n:
            if n % d == 0:
                total += f(n // d, j - 1, d)
            d += 1
        return total

    vals = [int(v) for v in values]
    return [g(v, k) for v in vals], [f(v, k, lo) for v in vals]


def _partitions(k: int, largest: int | None = None) -> Iterator[tuple[int, ...]]:
    """Partitions of k into non-increasing parts."""
    largest = k if largest is None else largest
    if k == 0:
        yield ()
        return
    for first in range(min(k, largest), 0, -1):
        for rest in _partitions(k - first, first):
            yield (first,) + rest


def _class_size(lam: tuple[int, ...]) -> int:
    """Number of permutations of K = sum(lam) places with cycle type ``lam``: K! / z_lam."""
    k = sum(lam)
    z = 1
    for part, mult in ((p, lam.count(p)) for p in set(lam)):
        z *= part**mult * math.factorial(mult)
    return math.factorial(k) // z


def _lookup(vals: np.ndarray, cnt: np.ndarray, queries: np.ndarray) -> np.ndarray:
    pos = np.searchsorted(vals, queries)
    pos_c = np.minimum(pos, vals.size - 1)
    hit = (pos < vals.size) & (vals[pos_c] == queries)
    return np.where(hit, cnt[pos_c], 0)


def _multiset_counts(queries: np.ndarray, k: int, base: np.ndarray, ordered, progress=None) -> np.ndarray:
    """Number of K-multisets of ``base`` with product q, for each q in ``queries`` (Polya)."""
    total = np.zeros(queries.size, dtype=np.int64)
    lams = list(_partitions(k))
    for i, lam in enumerate(lams, start=1):
        if lam == (1,) * k and ordered is not None:
            counts = _lookup(ordered[0], ordered[1], queries)
        else:
            vals, cnt = _weighted_products(lam, base)
            counts = _lookup(vals, cnt, queries)
        total += _class_size(lam) * counts
        _tick(progress, "counting sets", i, len(lams))
    return total // math.factorial(k)


def factorization_counts(values, pairs, min_teeth, max_teeth, ordered: bool = False) -> np.ndarray:
    """How many ways each value is a product of K teeth in [min_teeth, max_teeth].

    Parameters
    ----------
    values : array_like of int
        Products to count.
    pairs : int
        K, the number of factors (at most :data:`MAX_PAIRS`).
    min_teeth, max_teeth : int
        Range of each factor.
    ordered : bool
        False: multisets (factors in any order counted once), as
        :func:`~gearlever.trains.design.factorizations` lists them;
        True: ordered K-tuples.

    Returns
    -------
    ndarray of int64
        Same shape as ``values``.

    Notes
    -----
    Ordered tuples: the distribution of t_1 ... t_K is built as a
    multiplicative convolution (sorted distinct products, with the number of
    tuples giving each).  Multisets: by Polya's enumeration (Burnside's
    lemma over the symmetric group S_K acting on the K places),
    f(n) = (1/K!) sum over cycle types lam of (K!/z_lam) c_lam(n), where
    c_lam(n) counts the tuples (t_1 .. t_l) with prod t_i ** lam_i = n and
    z_lam = prod_i i**m_i m_i! (G. Polya, Acta Math. 68 (1937) 145-254).  No
    factorization is listed.  The space of multisets must not exceed
    :data:`MAX_SPACE_CAP`.

    Examples
    --------
    >>> factorization_counts([144, 2107], 2, 2, 20).tolist()
    [3, 0]
    >>> factorization_counts([144], 2, 2, 20, ordered=True).tolist()
    [5]
    """
    k = capped_int("pairs", pairs, MAX_PAIRS)
    lo, hi = teeth_range(min_teeth, max_teeth)
    _check_space(k, lo, hi, MAX_SPACE_CAP)
    try:
        q = np.asarray(values, dtype=np.int64)
    except (TypeError, ValueError, OverflowError):
        raise GearleverError("values must be an array of integers below 2**63") from None
    base = np.arange(lo, hi + 1, dtype=np.int64)
    flat = q.ravel()
    if ordered:
        vals, cnt = _weighted_products((1,) * k, base)
        return _lookup(vals, cnt, flat).reshape(q.shape)
    return _multiset_counts(flat, k, base, None).reshape(q.shape)


def _iter_factorizations(n: int, k: int, lo: int, hi: int) -> Iterator[tuple[int, ...]]:
    """Non-decreasing k-tuples in [lo, hi] with product n, in lexicographic order (lazily)."""
    if k == 1:
        if lo <= n <= hi:
            yield (n,)
        return
    if n < lo**k or n > hi**k:
        return
    d = lo
    while d <= hi and d**k <= n:
        if n % d == 0:
            for rest in _iter_factorizations(n // d, k - 1, d, hi):
                yield (d,) + rest
        d += 1


@dataclass(frozen=True)
class TrainSolution(Result):
    """One optimal tooth set (drivers and followers each as a sorted multiset).

    Attributes
    ----------
    drivers, followers : tuple of int
        Non-decreasing.
    ratio : Fraction

    Examples
    --------
    >>> s = search_best("1/6.931", 2, 12, 60).solutions[0]  # Sandgren's gear-train problem
    >>> s.drivers, s.followers, s.pairing
    ((16, 19), (43, 49), ((16, 43), (19, 49)))
    """

    drivers: tuple[int, ...]
    followers: tuple[int, ...]
    ratio: Fraction

    @property
    def pairing(self) -> tuple[tuple[int, int], ...]:
        """Driver-follower pairs arranged for the least gcd (:func:`~gearlever.trains.pairing.best_pairing`)."""
        return best_pairing(self.drivers, self.followers)

    def summary(self) -> dict:
        """JSON-ready record (the command line's json): teeth, exact ratio ``"p/q"``, pairing and gcds."""
        pairing = self.pairing
        return {
            "drivers": list(self.drivers),
            "followers": list(self.followers),
            "ratio": f"{self.ratio.numerator}/{self.ratio.denominator}",
            "pairs": [list(p) for p in pairing],
            "gcd": [math.gcd(d, f) for d, f in pairing],
        }


@dataclass(frozen=True)
class SearchResult(Result):
    """Result of :func:`search_best`.

    :meth:`summary` gives JSON-ready values; :meth:`to_frame` one row per
    listed solution.

    Attributes
    ----------
    target : Fraction
    pairs, min_teeth, max_teeth : int
    metric : {"absolute", "relative"}
    best_error : Fraction
        Least error, exact (absolute ``|ratio - target|`` or relative
        ``|ratio - target| / target``).
    best_ratios : tuple of Fraction
        The optimal ratio(s) in lowest terms (two only if they lie at equal
        distance on both sides of the target).
    solutions : tuple of TrainSolution
        The first ``limit`` optimal tooth sets, smallest products first.
    n_solutions : int
        Number of optimal tooth sets up to order (all of them, counted, not
        listed); also :attr:`count`.
    n_ordered : int
        Number of optimal ordered tooth tuples (d_1..d_K, f_1..f_K), as a
        brute force over every tuple would count them.
    n_products : int
        Number of distinct products of K teeth per side, each examined as a
        driver product.
    space_size : int
        Tooth multisets per side (:func:`search_space_size`).
    n_candidates : int
        (driver product, follower product) pairs whose error was evaluated:
        4 per driver product (the proof's bound, see :func:`search_best`).
    n_product_pairs : int
        Optimal (driver product, follower product) pairs.
    limit : int
        Most solutions listed.

    Examples
    --------
    >>> best = search_best("1000/6931", pairs=2, min_teeth=12, max_teeth=60)
    >>> best.count, best.solutions[0].drivers, best.solutions[0].followers
    (1, (16, 19), (43, 49))
    """

    target: Fraction
    pairs: int
    min_teeth: int
    max_teeth: int
    metric: str
    best_error: Fraction
    best_ratios: tuple[Fraction, ...]
    solutions: tuple[TrainSolution, ...]
    n_solutions: int
    n_ordered: int
    n_products: int
    space_size: int
    n_candidates: int = 0
    n_product_pairs: int = 0
    limit: int = DEFAULT_LIMIT

    @property
    def count(self) -> int:
        """Number of optimal tooth sets up to order (= :attr:`n_solutions`)."""
        return self.n_solutions

    @property
    def complete(self) -> bool:
        """True if every optimal tooth set is listed."""
        return len(self.solutions) == self.n_solutions

    def summary(self) -> dict:
        """JSON-ready record of the search (the command line's json), every listed solution included."""
        return {
            "target": f"{self.target.numerator}/{self.target.denominator}",
            "target_float": float(self.target),
            "pairs": self.pairs,
            "min_teeth": self.min_teeth,
            "max_teeth": self.max_teeth,
            "metric": self.metric,
            "best_error": float(self.best_error),
            "best_ratio": float(self.best_ratios[0]),
            "best_ratio_exact": [f"{r.numerator}/{r.denominator}" for r in self.best_ratios],
            "count": self.n_solutions,
            "n_solutions": self.n_solutions,
            "n_ordered": self.n_ordered,
            "n_products": self.n_products,
            "n_candidates": self.n_candidates,
            "n_product_pairs": self.n_product_pairs,
            "space_size": self.space_size,
            "limit": self.limit,
            "listed": len(self.solutions),
            "solutions": [s.summary() for s in self.solutions],
        }

    def _frame_columns(self) -> dict:
        sols = self.solutions
        return {
            "drivers": np.array([" ".join(map(str, s.drivers)) for s in sols], dtype=object),
            "followers": np.array([" ".join(map(str, s.followers)) for s in sols], dtype=object),
            "ratio": np.array([str(s.ratio) for s in sols], dtype=object),
            "ratio_float": np.array([float(s.ratio) for s in sols]),
        }


def _near_best(prods: np.ndarray, r: float, progress: Progress | None):
    """Every (P, Q) whose float error is within rounding of the least one; pairs evaluated."""
    n = prods.size
    pf = prods.astype(float)
    chunks = range(0, n, _CHUNK)

    def errors(start):
        p = pf[start : start + _CHUNK]
        cand = np.clip(np.searchsorted(pf, p / r)[:, None] + _WINDOW, 0, n - 1)
        return cand, np.abs(p[:, None] / pf[cand] - r)

    best = math.inf
    for i, start in enumerate(chunks, start=1):
        best = min(best, float(errors(start)[1].min()))
        _tick(progress, "searching", i, 2 * len(chunks))
    tol = 16 * np.finfo(float).eps * (r + best)
    ps, qs = [], []
    for i, start in enumerate(chunks, start=len(chunks) + 1):
        cand, err = errors(start)
        rows, cols = np.nonzero(err <= best + tol)
        ps.append(prods[start + rows])
        qs.append(prods[cand[rows, cols]])
        _tick(progress, "searching", i, 2 * len(chunks))
    return np.concatenate(ps), np.concatenate(qs), n * _WINDOW.size


def _optimal_pairs(prods: np.ndarray, best: list[tuple[int, int]]):
    """Every (P, Q) = (p m, q m) with both in ``prods``, for each best p/q; sorted by (P, Q)."""
    ps, qs = [], []
    top = int(prods[-1])
    for p, q in best:
        m = prods[prods % q == 0] // q
        m = m[m <= top // p]
        pm = p * m
        ok = _lookup(prods, np.ones(prods.size, dtype=np.int64), pm) == 1
        ps.append(pm[ok])
        qs.append(q * m[ok])
    ps, qs = np.concatenate(ps), np.concatenate(qs)
    order = np.lexsort((qs, ps))
    return ps[order], qs[order]


def search_best(
    ratio,
    pairs,
    min_teeth,
    max_teeth,
    metric: str = "absolute",
    max_space: int = DEFAULT_MAX_SPACE,
    limit: int | None = DEFAULT_LIMIT,
    progress: Progress | None = None,
) -> SearchResult:
    """The trains of K pairs, teeth in [min_teeth, max_teeth], closest to ``ratio``.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
        Target prod(drivers) / prod(followers).
    pairs : int
        K, the number of drivers (= number of followers), at most
        :data:`MAX_PAIRS` (12).
    min_teeth, max_teeth : int
        Tooth range, the same for every wheel (at most 10,000).
    metric : {"absolute", "relative"}
        ``|R - r|`` or ``|R - r| / r``.  (Since r is fixed both have the same optima;
        only the reported error differs.)
    max_space : int
        Refuse (before any work) when the number of tooth multisets per side
        exceeds this; default 5,000,000, at most :data:`MAX_SPACE_CAP`
        (20,000,000).
    limit : int or None
        List at most this many optimal sets (default 20, at most
        :data:`MAX_LIMIT` = 1000; None means the cap).  The counts are
        always complete.
    progress : callable, optional
        ``progress(stage, done, total)``, called between steps of the work.

    Returns
    -------
    SearchResult

    Notes
    -----
    Exhaustive over distinct products, so the optimum is proven.  Let S be
    the sorted distinct products of K teeth (repeated outer products with
    de-duplication).  For a driver product P the error ``|P/Q - r|`` falls as Q
    rises to P/r and then grows, so the best follower product for P is one
    of the two neighbours of P/r in S, found by bisection; four neighbours
    are checked, against rounding ( ``n_candidates = 4 |S|`` pairs).  The
    pairs within a few ulps of the least float error are reduced to lowest
    terms p/q and compared in exact rational arithmetic.  Every optimal pair
    of products is then (p m, q m) for a whole m, found by one pass over S.
    The optimal tooth sets are counted, not listed: the number of multisets
    (or of ordered tuples) of K teeth with product P is
    :func:`factorization_counts`, and the count is
    sum over optimal (P, Q) of f(P) f(Q).  Only the first ``limit`` sets are
    factored back into teeth.  The problem with r = 1/6.931, K = 2, teeth
    12-60 is Sandgren's gear-train problem (E. Sandgren, "Nonlinear integer
    and discrete programming in mechanical design optimization", ASME J.
    Mech. Des. 112 (1990) 223-229).

    Examples
    --------
    >>> res = search_best("1/6.931", 2, 12, 60)
    >>> [(s.drivers, s.followers) for s in res.solutions], res.count, res.n_ordered
    ([((16, 19), (43, 49))], 1, 4)
    >>> f"{float(res.best_error)**2:.6e}"
    '2.700857e-12'
    """
    target = parse_ratio(ratio)
    k = capped_int("pairs", pairs, MAX_PAIRS)
    lo, hi = teeth_range(min_teeth, max_teeth)
    if metric not in METRICS:
        raise GearleverError(f"metric must be 'absolute' or 'relative', got {metric!r}")
    max_space = capped_int("max_space", max_space, MAX_SPACE_CAP)
    limit = MAX_LIMIT if limit is None else capped_int("limit", limit, MAX_LIMIT)
    size = _check_space(k, lo, hi, max_space)
    base = np.arange(lo, hi + 1, dtype=np.int64)
    prods = _distinct_products(k, base, progress)
    near_p, near_q, n_candidates = _near_best(prods, float(target), progress)

    g = np.gcd(near_p, near_q)
    reduced = np.unique(np.stack([near_p // g, near_q // g], axis=1), axis=0)
    exact = [(abs(Fraction(int(p), int(q)) - target), int(p), int(q)) for p, q in reduced]
    best_exact = min(e for e, _, _ in exact)
    best = [(p, q) for e, p, q in exact if e == best_exact]
    opt_p, opt_q = _optimal_pairs(prods, best)

    values = np.unique(np.concatenate([opt_p, opt_q]))
    if values.size <= RECURSIVE_COUNT_MAX:
        ordered, sets = (np.array(c, dtype=np.int64) for c in _recursive_counts(values, k, lo, hi))
    else:  # many optimal products: whole distributions, vectorized
        dist = _weighted_products((1,) * k, base, progress, "counting tuples")
        ordered = _lookup(*dist, values)
        sets = _multiset_counts(values, k, base, dist, progress)
    n_ordered = sum(
        map(operator.mul, _lookup(values, ordered, opt_p).tolist(), _lookup(values, ordered, opt_q).tolist())
    )
    n_sets = sum(map(operator.mul, _lookup(values, sets, opt_p).tolist(), _lookup(values, sets, opt_q).tolist()))

    solutions: list[TrainSolution] = []
    for p, q in zip(opt_p.tolist(), opt_q.tolist()):
        if len(solutions) >= limit:
            break
        room = limit - len(solutions)
        fd = list(itertools.islice(_iter_factorizations(p, k, lo, hi), room))
        fq = list(itertools.islice(_iter_factorizations(q, k, lo, hi), room))
        frac = Fraction(p, q)
        solutions.extend(TrainSolution(d, fo, frac) for d, fo in itertools.islice(itertools.product(fd, fq), room))

    best_err = best_exact if metric == "absolute" else best_exact / target
    ratios = tuple(sorted(Fraction(p, q) for p, q in best))
    return SearchResult(
        target,
        k,
        lo,
        hi,
        metric,
        best_err,
        ratios,
        tuple(solutions),
        n_sets,
        n_ordered,
        int(prods.size),
        size,
        n_candidates,
        int(opt_p.size),
        limit,
    )
