"""Tooth numbers for a wanted ratio by the rules of the classic text on trains of wheelwork.

:func:`design_train` follows the text (page marked (41)): the number of pairs
between ``|log B - log C| / log 6`` and ``|log B - log C| / log 3``; B and C resolved
into that many factors, or multiples of them, between the least tooth number
t and 6t (:func:`exact_trains`, :func:`factorizations`); when B or C holds a
prime too large for a wheel, a neighbouring fraction from the continued
fraction that does factor, with its error; each driver paired with a follower
so that their greatest common divisor is 1 or as small as possible
(:func:`best_pairing`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.trains._caps import MAX_KEEP, MAX_PAIRS, MAX_TEETH, capped_int, teeth_range
from gearlever.trains.continued import approximants, neighbours, parse_ratio
from gearlever.trains.pairing import best_pairing
from gearlever.trains.rules import PairCountBounds, min_teeth_for_form, pair_count_bounds, rules

__all__ = [
    "PREFERENCES",
    "DesignResult",
    "TrainDesign",
    "best_pairing",
    "design_train",
    "exact_trains",
    "factorizations",
]

#: Trial divisions a design may spend in all its factorizations (about 2 s);
#: beyond them :func:`design_train` refuses, naming ``pairs``.
MAX_DESIGN_STEPS = 5_000_000
#: Most semiconvergents tried per partial quotient by :func:`design_train`
#: (the most accurate of each run; a quotient of 10**9 would otherwise give 10**9).
MAX_RUN = 10_000


def factorizations(n: int, k: int, lo: int, hi: int) -> list[tuple[int, ...]]:
    """Every way of writing ``n`` as a product of ``k`` whole numbers in [lo, hi].

    Factors are returned in non-decreasing order, so each multiset once.

    Parameters
    ----------
    n, k, lo, hi : int
        Product, number of factors (>= 1), least and largest factor.

    Returns
    -------
    list of tuple of int

    Notes
    -----
    Depth-first over the smallest factor d, lo <= d <= n**(1/k), d | n.
    The classic text on trains of wheelwork (page marked (41)) resolves B
    and C into as many factors as there are pairs, each between t and 6t.

    Examples
    --------
    >>> factorizations(2107, 2, 12, 60)
    [(43, 49)]
    >>> factorizations(144, 2, 2, 20)
    [(8, 18), (9, 16), (12, 12)]
    """
    return _factorizations(int(n), int(k), int(lo), int(hi), None)


def _factorizations(n, k, lo, hi, budget) -> list[tuple[int, ...]]:
    out: list[tuple[int, ...]] = []
    _factor_rec(n, k, lo, hi, (), out, budget)
    return out


class _Budget:
    """Trial divisions left to a design (shared by every factorization it tries)."""

    def __init__(self, steps: int):
        self.cap = steps
        self.left = steps

    def spend(self, steps: int) -> None:
        self.left -= steps
        if self.left < 0:
            raise GearleverError(
                f"pairs: the design gave up after {self.cap:,} trial divisions (its work cap); "
                "use fewer pairs, a narrower tooth range (min_teeth to max_teeth), "
                "or the exhaustive search (search_best, gearlever train search)"
            )


def _factor_rec(n, k, lo, hi, prefix, out, budget) -> None:
    if k == 1:
        if lo <= n <= hi:
            out.append(prefix + (n,))
        return
    if n < lo**k or n > hi**k:
        return
    top = min(hi, math.isqrt(n) if k == 2 else int(round(n ** (1.0 / k))) + 1)
    if budget is not None:
        budget.spend(top - lo + 1)
    for d in range(lo, top + 1):
        if n % d == 0 and d**k <= n:
            _factor_rec(n // d, k - 1, d, hi, prefix + (d,), out, budget)


@dataclass(frozen=True)
class TrainDesign(Result):
    """One train: drivers and followers paired for even wear.

    Attributes
    ----------
    drivers, followers : tuple of int
        Paired: driver i meshes with follower i.
    ratio : Fraction
        prod(drivers) / prod(followers), exact.
    target : Fraction
    multiplier : int
        lambda with prod(drivers) = lambda * B', prod(followers) = lambda * C',
        B'/C' the (possibly approximated) ratio in lowest terms.

    Examples
    --------
    >>> d = exact_trains(12, 2, 12, 72)[0]
    >>> d.drivers, d.followers, d.ratio, d.gcds
    ((36, 48), (12, 12), Fraction(12, 1), (12, 12))
    """

    drivers: tuple[int, ...]
    followers: tuple[int, ...]
    ratio: Fraction
    target: Fraction
    multiplier: int

    @property
    def error(self) -> float:
        """Absolute error ratio - target (signed float)."""
        return float(self.ratio - self.target)

    @property
    def gcds(self) -> tuple[int, ...]:
        """Greatest common divisor of each pair's teeth."""
        return tuple(math.gcd(d, f) for d, f in zip(self.drivers, self.followers))

    @property
    def shared_divisor_pairs(self) -> tuple[int, ...]:
        """Numbers (from 1) of the pairs whose teeth share a divisor > 1."""
        return tuple(i + 1 for i, g in enumerate(self.gcds) if g > 1)

    @property
    def total_teeth(self) -> int:
        return sum(self.drivers) + sum(self.followers)

    def _frame_columns(self) -> dict:
        """One row: teeth as space-separated text, exact and float ratio (as :class:`DesignResult`'s rows)."""
        return _design_columns((self,))

    def summary(self) -> dict:
        """JSON-ready record of the design (the command line's json): exact ratio as ``"p/q"``, its error, gcds."""
        return {
            "drivers": list(self.drivers),
            "followers": list(self.followers),
            "ratio": f"{self.ratio.numerator}/{self.ratio.denominator}",
            "ratio_float": float(self.ratio),
            "error": self.error,
            "relative_error": float((self.ratio - self.target) / self.target),
            "gcd": list(self.gcds),
            "pairs_sharing_divisor": list(self.shared_divisor_pairs),
            "total_teeth": self.total_teeth,
        }


#: Orders of preference of :func:`design_train`.
PREFERENCES = ("teeth", "wear")


def _design_key(d: TrainDesign, prefer: str = "teeth"):
    if prefer == "wear":
        return (max(d.gcds), sum(d.gcds), d.total_teeth, d.drivers, d.followers)
    return (d.total_teeth, max(d.gcds), sum(d.gcds), d.drivers, d.followers)


def _check_prefer(prefer: str) -> str:
    if prefer not in PREFERENCES:
        raise GearleverError(f"prefer must be one of {', '.join(PREFERENCES)}, got {prefer!r}")
    return prefer


def exact_trains(
    ratio,
    pairs,
    min_teeth,
    max_teeth,
    max_multipliers: int = 20000,
    keep: int = 10,
    prefer: str = "teeth",
    max_hits: int = 20,
    per_side: int = 12,
    max_steps: int = MAX_DESIGN_STEPS,
    _budget: _Budget | None = None,
) -> list[TrainDesign]:
    """Trains of exactly ``ratio`` with ``pairs`` pairs, teeth in [min_teeth, max_teeth].

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
    pairs : int
        Number of pairs K (>= 1).
    min_teeth, max_teeth : int
    max_multipliers : int
        How many multipliers lambda are tried at most (from the least).
    max_hits : int
        Stop after this many multipliers that give trains (larger lambda
        means larger wheels).
    per_side : int
        For each such multiplier, the drivers' and the followers' tooth sets
        with the fewest teeth that are combined (at most this many each).
    keep : int
        How many designs are returned.
    max_steps : int
        Trial divisions allowed (default and cap :data:`MAX_DESIGN_STEPS`,
        a few seconds); beyond them the design is refused, naming ``pairs``.
    prefer : {"teeth", "wear"}
        "teeth": least total number of teeth first (Young's criterion), then
        least gcd; "wear": least largest gcd of a pair first (the text's even
        wear), then least total teeth.

    Returns
    -------
    list of TrainDesign
        Best first; empty if none was found.

    Notes
    -----
    prod(drivers)/prod(followers) = B/C exactly if and only if
    prod(drivers) = lambda B and prod(followers) = lambda C for a whole
    lambda: these are the factors of B and C "or multiples of them" of the
    classic text on trains of wheelwork (page marked (41)).  lambda runs from ceil(t**K / min(B, C)) up.  If B or
    C has a prime factor above max_teeth, no lambda helps (the "awkward large
    prime" of the text) and the list is empty at once.

    Examples
    --------
    >>> d = exact_trains(12, 2, 12, 72)[0]
    >>> d.drivers, d.followers, d.ratio
    ((36, 48), (12, 12), Fraction(12, 1))
    """
    frac = parse_ratio(ratio)
    budget = _budget if _budget is not None else _Budget(capped_int("max_steps", max_steps, MAX_DESIGN_STEPS))
    k = capped_int("pairs", pairs, MAX_PAIRS)
    lo, hi = teeth_range(min_teeth, max_teeth)
    keep = capped_int("keep", keep, MAX_KEEP)
    prefer = _check_prefer(prefer)
    b, c = frac.numerator, frac.denominator
    if _has_prime_factor_above(b, hi) or _has_prime_factor_above(c, hi):
        return []  # no multiple of B or C splits into teeth <= max_teeth
    lam_min = max(1, -(-(lo**k) // min(b, c)))
    lam_max = hi**k // max(b, c)
    raw: list[tuple[int, tuple[int, ...], tuple[int, ...], int]] = []
    tried = hits = 0
    lam = lam_min
    small, large = (c, b) if c <= b else (b, c)
    while lam <= lam_max and tried < max_multipliers and hits < max_hits:
        tried += 1
        budget.spend(1)
        f_small = _factorizations(lam * small, k, lo, hi, budget)
        if f_small:
            f_large = _factorizations(lam * large, k, lo, hi, budget)
            if f_large:
                hits += 1
                f_b, f_c = (f_large, f_small) if c <= b else (f_small, f_large)
                # the fewest teeth come from the most even factors: keep the best few per side
                f_b = sorted(f_b, key=lambda t: (sum(t), t))[:per_side]
                f_c = sorted(f_c, key=lambda t: (sum(t), t))[:per_side]
                raw.extend((sum(dr) + sum(fo), dr, fo, lam) for dr in f_b for fo in f_c)
        lam += 1
    if prefer == "teeth":  # pair only the leading candidates
        raw.sort(key=lambda r: (r[0], r[1], r[2]))
        raw = raw[: max(4 * keep, 50)]
    found = []
    for _, dr, fo, lam in raw:
        paired = best_pairing(dr, fo)
        found.append(
            TrainDesign(
                tuple(p[0] for p in paired),
                tuple(p[1] for p in paired),
                Fraction(math.prod(dr), math.prod(fo)),
                frac,
                lam,
            )
        )
    found.sort(key=lambda d: _design_key(d, prefer))
    return found[:keep]


def _has_prime_factor_above(n: int, bound: int) -> bool:
    """True if ``n`` has a prime factor greater than ``bound`` (trial division by 2..bound)."""
    d = 2
    while d <= bound and d * d <= n:
        while n % d == 0:
            n //= d
        d += 1
    return n > bound


@dataclass(frozen=True)
class DesignResult(Result):
    """Result of :func:`design_train`.

    :meth:`summary` gives JSON-ready values (ratios as ``"B/C"`` text);
    :meth:`to_frame` one row per design.

    Attributes
    ----------
    target : Fraction
    min_teeth, max_teeth : int
    bounds : PairCountBounds
    method : {"exact", "continued fraction"}
    approximation : Fraction
        The ratio actually built (the target itself when exact).
    designs : tuple of TrainDesign
        Best first.
    tried : tuple of (Approximant, pairs, factors) triples
        Continued-fraction approximants tested, most accurate first, up to
        the one used (empty when exact).

    Examples
    --------
    >>> d = design_train("1/6.931", min_teeth=12, max_teeth=60)
    >>> d.approximation, d.designs[0].drivers, d.designs[0].followers
    (Fraction(304, 2107), (16, 19), (43, 49))
    """

    target: Fraction
    min_teeth: int
    max_teeth: int
    bounds: PairCountBounds
    method: str
    approximation: Fraction
    designs: tuple[TrainDesign, ...]
    tried: tuple

    def summary(self) -> dict:
        """JSON-ready record of the result (the command line's json): bounds, method and every design."""
        return {
            "target": f"{self.target.numerator}/{self.target.denominator}",
            "target_float": float(self.target),
            "min_teeth": self.min_teeth,
            "max_teeth": self.max_teeth,
            "pairs_lower_bound": self.bounds.lower,
            "pairs_upper_bound": self.bounds.upper,
            "pairs_young": self.bounds.young,
            "method": self.method,
            "approximation": f"{self.approximation.numerator}/{self.approximation.denominator}",
            "designs": [d.summary() for d in self.designs],
        }

    def _frame_columns(self) -> dict:
        """One row per design (best first): teeth as space-separated text, exact and float ratio."""
        return _design_columns(self.designs)


def design_train(
    ratio,
    min_teeth=None,
    max_teeth=None,
    pairs=None,
    tooth_form: str = "involute",
    keep: int = 5,
    prefer: str = "teeth",
) -> DesignResult:
    """Choose tooth numbers for a wanted ratio by the rules of the text.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
        Wanted velocity ratio of the last axis to the first.
    min_teeth : int, optional
        Least tooth number t; by default that of ``tooth_form``.
    max_teeth : int, optional
        Largest tooth number; default 6t.
    pairs : int, optional
        Number of pairs; by default each of :func:`pair_count_bounds`'s
        candidates is tried, fewest first.
    tooth_form : {"epicycloidal", "smooth", "involute"}
        Used only when ``min_teeth`` is None (12, 15, 24 teeth).
    keep : int
        Number of designs returned.
    prefer : {"teeth", "wear"}
        Order of the designs (:func:`exact_trains`).

    Returns
    -------
    DesignResult

    Notes
    -----
    The classic text on trains of wheelwork, page marked (41).  With B/C in lowest terms: try to resolve B
    and C into K factors (or multiples) within [t, T] for K between
    ``|log B - log C|/log 6`` and ``|log B - log C|/log 3`` (:func:`exact_trains`);
    if no K gives an exact train, take the convergents and semiconvergents
    of B/C (:func:`approximants`), and the fractions just beside B/C that
    continue its expansion (:func:`neighbours`), small enough to be built;
    most accurate first, build the first one that factors (fewest pairs
    first).  Drivers and followers are paired for the least
    gcd (:func:`best_pairing`).

    Examples
    --------
    >>> r = design_train("1/6.931", min_teeth=12, max_teeth=60)
    >>> r.method, r.approximation, r.designs[0].drivers, r.designs[0].followers
    ('continued fraction', Fraction(304, 2107), (16, 19), (43, 49))
    """
    frac = parse_ratio(ratio)
    prefer = _check_prefer(prefer)
    keep = capped_int("keep", keep, MAX_KEEP)
    budget = _Budget(MAX_DESIGN_STEPS)
    if min_teeth is None:
        t = min_teeth_for_form(tooth_form)
    else:
        t = capped_int("min_teeth", min_teeth, MAX_TEETH)
    big = int(rules()["max_teeth_factor"]) * t if max_teeth is None else capped_int("max_teeth", max_teeth, MAX_TEETH)
    lo, hi = teeth_range(t, min(big, MAX_TEETH) if max_teeth is None else big)
    bounds = pair_count_bounds(frac)
    if pairs is not None:
        ks = (capped_int("pairs", pairs, MAX_PAIRS),)
    else:
        ks = tuple(k for k in bounds.candidates if k <= MAX_PAIRS)
        if not ks:
            raise GearleverError(
                f"ratio {frac} needs at least {bounds.candidates[0]} pairs by the rule of 3 to 6 per pair; "
                f"at most {MAX_PAIRS} pairs are designed"
            )
    for k in ks:
        designs = exact_trains(frac, k, lo, hi, keep=keep, prefer=prefer, _budget=budget)
        if designs:
            return DesignResult(frac, lo, hi, bounds, "exact", frac, tuple(designs), ())
    candidates = [a for a in approximants(frac, max_term=hi ** max(ks), max_per_term=MAX_RUN) if a.fraction != frac]
    candidates += neighbours(frac, max_term=hi ** max(ks))
    candidates.sort(key=lambda a: abs(a.error))  # most accurate first; stable for ties
    tried = []
    for approx in candidates:
        p, q = approx.fraction.numerator, approx.fraction.denominator
        for k in ks:
            if max(p, q) > hi**k:
                tried.append((approx, k, False))
                continue
            designs = exact_trains(approx.fraction, k, lo, hi, keep=keep, prefer=prefer, _budget=budget)
            tried.append((approx, k, bool(designs)))
            if designs:
                designs = tuple(TrainDesign(d.drivers, d.followers, d.ratio, frac, d.multiplier) for d in designs)
                return DesignResult(frac, lo, hi, bounds, "continued fraction", approx.fraction, designs, tuple(tried))
    raise GearleverError(
        f"ratio {frac} cannot be built with {', '.join(map(str, ks))} pair(s) of teeth in [{lo}, {hi}]; "
        "by factors or continued fractions; use search_best (gearlever train search) or a wider tooth range"
    )


def exact_optimum(res: DesignResult, limit: int = 5, max_space: int | None = None):
    """The proven best train beside a classical design: the same pairs and tooth range, by exhaustive search.

    The rules of :func:`design_train` build the first continued-fraction
    approximant that factors into teeth in range; that need not be the
    closest ratio that any train of as many pairs can give.  This runs
    :func:`~gearlever.trains.search.search_best` on the same target, number of
    pairs and tooth range, so the classical design can be shown with the
    exact optimum beside it.

    Parameters
    ----------
    res : DesignResult
        A result of :func:`design_train`.
    limit : int
        Optimal sets listed (the count is always complete).
    max_space : int, optional
        Refuse searches with more tooth multisets per side than this (default
        that of :func:`~gearlever.trains.search.search_best`).

    Returns
    -------
    SearchResult
        With ``best_error`` 0 when the classical design is exact.

    Notes
    -----
    Exhaustive search over tooth multisets (:func:`~gearlever.trains.search.search_best`);
    the classical rules are those of :func:`design_train`.

    Examples
    --------
    >>> r = design_train("191/23", min_teeth=24, max_teeth=144)
    >>> r.approximation, r.designs[0].error < 4.25e-5
    (Fraction(8512, 1025), True)
    >>> best = exact_optimum(r)
    >>> best.best_ratios, float(best.best_error) < 2.72e-5
    ((Fraction(13287, 1600),), True)
    """
    from gearlever.trains.search import DEFAULT_MAX_SPACE, search_best

    pairs = len(res.designs[0].drivers)
    return search_best(
        res.target,
        pairs,
        res.min_teeth,
        res.max_teeth,
        max_space=DEFAULT_MAX_SPACE if max_space is None else max_space,
        limit=limit,
    )


def _design_columns(designs) -> dict:
    return {
        "drivers": np.array([" ".join(map(str, d.drivers)) for d in designs], dtype=object),
        "followers": np.array([" ".join(map(str, d.followers)) for d in designs], dtype=object),
        "ratio": np.array([str(d.ratio) for d in designs], dtype=object),
        "ratio_float": np.array([float(d.ratio) for d in designs]),
        "error": np.array([d.error for d in designs]),
        "gcd": np.array([" ".join(map(str, d.gcds)) for d in designs], dtype=object),
        "total_teeth": np.array([d.total_teeth for d in designs], dtype=np.int64),
    }
