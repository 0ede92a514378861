"""Choosing the tooth numbers of a train of wheels for a wanted velocity ratio.

Two ways are offered.

* :func:`design_train` follows the rules of the classic text (seed 004, page
  marked (41)): the number of pairs between |log B - log C| / log 6 and
  |log B - log C| / log 3; B and C resolved into that many factors, or
  multiples of them, between the least tooth number t and 6t; when B or C
  holds an awkward large prime, a neighbouring fraction found by continued
  fractions (convergents and semiconvergents) that does factor, with its
  error; each driver paired with a follower so that their greatest common
  divisor is 1 or as small as possible.
* :func:`search_best` finds, for K pairs with teeth in [t_min, t_max], every
  train (up to the order of drivers and of followers) whose ratio is closest
  to the target, and proves it: it runs over every distinct product of K
  teeth, so nothing is left out.

Ratios are exact :class:`fractions.Fraction` throughout; ``ratio`` may be
given as a number, a Fraction, or a string ``"B/C"`` whose parts may be
decimals (``"1/6.931"`` is exactly 1000/6931).  The velocity ratio is that of
the last axis to the first, prod(drivers) / prod(followers).
"""

from __future__ import annotations

import functools
import itertools
import math
import numbers
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from gearlever import _validate
from gearlever.errors import GearleverError

__all__ = [
    "TOOTH_FORMS",
    "Approximant",
    "DesignResult",
    "PREFERENCES",
    "PairCountBounds",
    "SearchResult",
    "TrainDesign",
    "TrainSolution",
    "approximants",
    "best_pairing",
    "continued_fraction",
    "convergents",
    "design_train",
    "exact_trains",
    "factorizations",
    "min_teeth_for_form",
    "neighbours",
    "pair_count_bounds",
    "parse_ratio",
    "rules",
    "search_best",
    "sandgren_published",
    "search_space_size",
]

#: Tooth forms known to :func:`min_teeth_for_form` (values in data/train_rules.csv).
TOOTH_FORMS = ("epicycloidal", "smooth", "involute")

#: Default limit of :func:`search_best`: tooth multisets per side.
DEFAULT_MAX_SPACE = 5_000_000


# --------------------------------------------------------------------------- data


@functools.cache
def rules() -> dict[str, float]:
    """The text's numeric rules, read from ``data/train_rules.csv``.

    Returns
    -------
    dict
        quantity -> value (least tooth numbers per tooth form, Young's 3.59,
        the practical per-pair limits 3 and 6, the factor 6 of 6t).

    Notes
    -----
    Source: seed 004, page marked (41) (see the data file's header).

    Examples
    --------
    >>> rules()["young_pair_ratio"]
    3.59
    """
    return {k: float(v) for k, v in _read_quantity_csv("train_rules.csv").items()}


def _read_quantity_csv(name: str) -> dict[str, str]:
    from gearlever.data import read_records

    return {row["quantity"]: row["value"] for row in read_records(name)}


def sandgren_published() -> dict:
    """Published optimum of Sandgren's gear-train problem, from ``data/sandgren_gear_train.csv``.

    Returns
    -------
    dict
        ``target`` (Fraction 1/6.931), ``min_teeth``, ``max_teeth``,
        ``best_squared_error`` (float, 7 significant digits as published) and
        ``teeth`` = (Td, Tb, Ta, Tf).

    Notes
    -----
    Problem: Sandgren (1990), ASME J. Mech. Des. 112: 223-229: minimise
    (1/6.931 - Td Tb / (Ta Tf))**2 over integer teeth in [12, 60].  The best
    value 2.700857e-12 at (16, 19, 43, 49) is the one quoted in the later
    literature (source details in the data file's header).

    Examples
    --------
    >>> sandgren_published()["teeth"]
    (16, 19, 43, 49)
    """
    q = _read_quantity_csv("sandgren_gear_train.csv")
    return {
        "target": 1 / Fraction(q["target_inverse_ratio"]),
        "min_teeth": int(q["min_teeth"]),
        "max_teeth": int(q["max_teeth"]),
        "best_squared_error": float(q["best_squared_error"]),
        "teeth": tuple(int(q[n]) for n in ("Td", "Tb", "Ta", "Tf")),
    }


def min_teeth_for_form(tooth_form: str) -> int:
    """Least number of teeth of a pinion for a tooth form, after the text.

    Parameters
    ----------
    tooth_form : {"epicycloidal", "smooth", "involute"}

    Returns
    -------
    int
        12, 15 or 24.

    Notes
    -----
    Seed 004, page marked (41): twelve for epicycloidal teeth, better not
    below fifteen for smoothness, about twenty-four for involute teeth.

    Examples
    --------
    >>> min_teeth_for_form("involute")
    24
    """
    if tooth_form not in TOOTH_FORMS:
        raise GearleverError(f"tooth_form must be one of {', '.join(TOOTH_FORMS)}, got {tooth_form!r}")
    return int(rules()[f"min_teeth_{tooth_form}"])


# --------------------------------------------------------------------------- ratios


def parse_ratio(value, name: str = "ratio") -> Fraction:
    """Return a positive exact ratio from a number, a Fraction or a ``"B/C"`` string.

    A float is read as the decimal it prints as (``0.25`` -> 1/4); a string
    ``"B/C"`` may hold decimals in B and C.

    Parameters
    ----------
    value : int, float, Fraction or str
    name : str
        Parameter name used in the error message.

    Returns
    -------
    Fraction
        In lowest terms, > 0.

    Examples
    --------
    >>> parse_ratio("1/6.931")
    Fraction(1000, 6931)
    >>> parse_ratio(3.59)
    Fraction(359, 100)
    """
    bad = f"{name} must be a positive finite number or B/C, got {value!r}"
    try:
        if isinstance(value, Fraction):
            frac = value
        elif isinstance(value, bool):
            raise GearleverError(bad)
        elif isinstance(value, numbers.Integral):
            frac = Fraction(int(value))
        elif isinstance(value, numbers.Real):
            if not math.isfinite(float(value)):
                raise GearleverError(bad)
            frac = Fraction(repr(float(value)))
        elif isinstance(value, str):
            text = value.strip()
            if "/" in text:
                num, den = text.split("/", 1)
                num_f, den_f = Fraction(num.strip()), Fraction(den.strip())
                if den_f == 0:
                    raise GearleverError(bad)
                frac = num_f / den_f
            else:
                frac = Fraction(text)
        else:
            raise GearleverError(bad)
    except (ValueError, ZeroDivisionError, TypeError):
        raise GearleverError(bad) from None
    if frac <= 0:
        raise GearleverError(bad)
    try:
        as_float = float(frac)
    except OverflowError:
        as_float = math.inf
    if not 1e-300 < as_float < 1e300:
        raise GearleverError(f"{name} must be between 1e-300 and 1e300, got {value!r}")
    return frac


def _teeth_range(min_teeth, max_teeth) -> tuple[int, int]:
    lo = _validate.positive_int("min_teeth", min_teeth)
    hi = _validate.positive_int("max_teeth", max_teeth)
    if lo > hi:
        raise GearleverError(f"min_teeth must not exceed max_teeth, got min_teeth={lo} > max_teeth={hi}")
    return lo, hi


# --------------------------------------------------------------------------- number of pairs


@dataclass(frozen=True)
class PairCountBounds:
    """Bounds on the number of pairs (elementary combinations) for a ratio.

    Attributes
    ----------
    lower, upper : float
        |log B - log C| / log 6 and |log B - log C| / log 3.
    young : float
        |log B - log C| / log 3.59 (Young's least-teeth number of pairs).
    candidates : tuple of int
        The whole numbers of pairs to try, smallest first: those within
        [lower, upper]; when no whole number lies there, the next one above
        ``lower``; always at least 1.
    """

    lower: float
    upper: float
    young: float
    candidates: tuple[int, ...]


def pair_count_bounds(ratio) -> PairCountBounds:
    """Number of pairs a train should have, after the text's rule.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"

    Returns
    -------
    PairCountBounds

    Notes
    -----
    Seed 004, page marked (41): for B/C > 6 the best number of elementary
    combinations lies between |log B - log C| / log 6 and
    |log B - log C| / log 3 (each pair turning 3 to 6 times faster); Young's
    least total number of teeth asks 3.59 per pair.

    Examples
    --------
    >>> b = pair_count_bounds(100)
    >>> round(b.lower, 3), round(b.upper, 3), b.candidates
    (2.57, 4.192, (3, 4))
    """
    frac = parse_ratio(ratio)
    span = abs(math.log(frac.numerator) - math.log(frac.denominator))
    r = rules()
    lower = span / math.log(r["practical_pair_ratio_max"])
    upper = span / math.log(r["practical_pair_ratio_min"])
    young = span / math.log(r["young_pair_ratio"])
    first = max(1, math.ceil(lower - 1e-12))
    last = max(first, math.floor(upper + 1e-12))
    return PairCountBounds(lower, upper, young, tuple(range(first, last + 1)))


# --------------------------------------------------------------------------- factors


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
    Depth-first over the smallest factor d, lo <= d <= n**(1/k), d | n
    (seed 004: B and C "resolved into factors ... not less than t nor
    greater than 6t").

    Examples
    --------
    >>> factorizations(2107, 2, 12, 60)
    [(43, 49)]
    >>> factorizations(144, 2, 2, 20)
    [(8, 18), (9, 16), (12, 12)]
    """
    out: list[tuple[int, ...]] = []
    _factor_rec(int(n), int(k), int(lo), int(hi), (), out)
    return out


def _factor_rec(n, k, lo, hi, prefix, out) -> None:
    if k == 1:
        if lo <= n <= hi:
            out.append(prefix + (n,))
        return
    if n < lo**k or n > hi**k:
        return
    d = lo
    while d <= hi and d**k <= n:
        if n % d == 0:
            _factor_rec(n // d, k - 1, d, hi, prefix + (d,), out)
        d += 1


def _multiset_permutations(t: tuple[int, ...]) -> int:
    counts = {}
    for v in t:
        counts[v] = counts.get(v, 0) + 1
    res = math.factorial(len(t))
    for c in counts.values():
        res //= math.factorial(c)
    return res


def best_pairing(drivers, followers) -> tuple[tuple[int, int], ...]:
    """Pair each driver with a follower so that the teeth wear evenly.

    Parameters
    ----------
    drivers, followers : sequence of int
        Same length K.

    Returns
    -------
    tuple of (driver, follower)
        For K <= 6, the pairing with the least largest gcd, then the least
        sum of gcds, then the per-pair ratios closest to one another (all K!
        pairings tried).  For K > 6, an optimal assignment (scipy) for the
        cost sum(gcd**3), which puts the largest gcd first.

    Notes
    -----
    Seed 004, page marked (41): for equable wear the greatest common divisor
    of the teeth N and n of each pair should be 1 or as small as possible.

    Examples
    --------
    >>> best_pairing([30, 28], [15, 14])
    ((30, 14), (28, 15))
    """
    drivers = tuple(int(d) for d in drivers)
    followers = tuple(int(f) for f in followers)
    if len(drivers) != len(followers):
        raise GearleverError(f"followers must have as many entries as drivers ({len(drivers)}), got {len(followers)}")
    k = len(drivers)
    g = [[math.gcd(d, f) for f in followers] for d in drivers]
    if k > 6:
        from scipy.optimize import linear_sum_assignment

        rows, cols = linear_sum_assignment(np.array(g, dtype=float) ** 3)
        return tuple((drivers[r], followers[c]) for r, c in zip(rows, cols))
    lg = [[math.log(d / f) for f in followers] for d in drivers]
    best_key, best = None, None
    for perm in itertools.permutations(range(k)):
        gcds = [g[i][j] for i, j in enumerate(perm)]
        logs = [lg[i][j] for i, j in enumerate(perm)]
        key = (max(gcds), sum(gcds), max(logs) - min(logs), tuple(followers[j] for j in perm))
        if best_key is None or key < best_key:
            best_key, best = key, key[3]
    return tuple(zip(drivers, best))


# --------------------------------------------------------------------------- continued fractions


def continued_fraction(ratio) -> list[int]:
    """Partial quotients [a0; a1, a2, ...] of a positive rational.

    Notes
    -----
    Euclid's algorithm: a_k = floor(x_k), x_(k+1) = 1 / (x_k - a_k), until
    the remainder is 0 (seed 004: "the method of continued fractions").

    Examples
    --------
    >>> continued_fraction("355/113")
    [3, 7, 16]
    """
    x = parse_ratio(ratio)
    terms = []
    while True:
        a, rem = divmod(x.numerator, x.denominator)
        terms.append(a)
        if rem == 0:
            return terms
        x = Fraction(x.denominator, rem)


def convergents(ratio) -> list[Fraction]:
    """Convergents p_k/q_k of the continued fraction of ``ratio``.

    Notes
    -----
    p_k = a_k p_(k-1) + p_(k-2), q_k = a_k q_(k-1) + q_(k-2), with
    p_(-1)/q_(-1) = 1/0 and p_(-2)/q_(-2) = 0/1.  A zero convergent (when
    ratio < 1, a0 = 0) is left out: no train has ratio 0.

    Examples
    --------
    >>> convergents("355/113")
    [Fraction(3, 1), Fraction(22, 7), Fraction(355, 113)]
    """
    return [a.fraction for a in approximants(ratio) if a.kind == "convergent"]


@dataclass(frozen=True)
class Approximant:
    """A convergent or semiconvergent of a continued fraction.

    Attributes
    ----------
    fraction : Fraction
    kind : {"convergent", "semiconvergent", "neighbour"}
    index : int
        k of the partial quotient a_k it belongs to (for a neighbour, the
        side +1 or -1, see :func:`neighbours`).
    multiple : int
        j in (p_(k-2) + j p_(k-1)) / (q_(k-2) + j q_(k-1)); a_k for a convergent.
    error : Fraction
        fraction - target (signed, exact).
    """

    fraction: Fraction
    kind: str
    index: int
    multiple: int
    error: Fraction


def approximants(ratio, max_term: int | None = None) -> list[Approximant]:
    """Every convergent and semiconvergent of ``ratio``, in order of growing terms.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
    max_term : int, optional
        Stop at the first approximant whose numerator or denominator exceeds
        this (numerators and denominators never decrease along the list).

    Returns
    -------
    list of Approximant
        For each partial quotient a_k (k >= 1), the semiconvergents
        (p_(k-2) + j p_(k-1)) / (q_(k-2) + j q_(k-1)) for j = 1 .. a_k - 1,
        then the convergent (j = a_k).  The last entry is ``ratio`` itself.

    Notes
    -----
    Seed 004, page marked (41): an awkward ratio is replaced by "some ratio
    approximating to that ratio ... found by the method of continued
    fractions".  Convergents and semiconvergents include every best rational
    approximation of the ratio.

    Examples
    --------
    >>> [str(a.fraction) for a in approximants("355/113")][:4]
    ['3', '4', '7/2', '10/3']
    """
    x = parse_ratio(ratio)
    if max_term is not None:
        max_term = _validate.positive_int("max_term", max_term)
    terms = continued_fraction(x)
    p_prev2, q_prev2 = 0, 1
    p_prev, q_prev = 1, 0
    out = []
    for k, a in enumerate(terms):
        start = 1 if k > 0 else a
        for j in range(start, a + 1):
            p, q = p_prev2 + j * p_prev, q_prev2 + j * q_prev
            if max_term is not None and max(p, q) > max_term:
                return out
            if p == 0:
                continue
            frac = Fraction(p, q)
            kind = "convergent" if j == a else "semiconvergent"
            out.append(Approximant(frac, kind, k, j, frac - x))
        p_prev2, q_prev2, p_prev, q_prev = p_prev, q_prev, p_prev2 + a * p_prev, q_prev2 + a * q_prev
    return out


def neighbours(ratio, count: int = 64, max_term: int | None = None) -> list[Approximant]:
    """Fractions next to ``ratio`` on both sides, continuing its continued fraction.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
        x = p_n / q_n, with previous convergent p_(n-1) / q_(n-1) (1/0 when x
        is a whole number).
    count : int
        At most this many on each side.
    max_term : int, optional
        Leave out fractions whose numerator or denominator exceeds this.

    Returns
    -------
    list of Approximant
        kind "neighbour": (p_(n-1) + j p_n) / (q_(n-1) + j q_n) and
        (j p_n - p_(n-1)) / (j q_n - q_(n-1)) for j = 1, 2, ...; ``index`` is
        +1 or -1 for the side (above or below x in the order of the
        expansion), ``multiple`` is j.

    Notes
    -----
    These are the semiconvergents of the numbers just beside x, whose
    expansions continue [a0; ..., a_n, M, ...] or [a0; ..., a_n - 1, 1, M, ...]
    with M large; |x - neighbour| = 1 / (q_n (q_(n-1) + j q_n)) on the first
    side.  They serve when x itself, or every approximant before it, holds a
    prime too large for a wheel: e.g. a whole-number ratio N, whose only
    convergent is N itself, gets (jN + 1)/j and (jN - 1)/j.

    Examples
    --------
    >>> [str(a.fraction) for a in neighbours(9488, count=2)]
    ['9489', '18977/2', '9487', '18975/2']
    """
    x = parse_ratio(ratio)
    count = _validate.positive_int("count", count)
    terms = continued_fraction(x)
    p2, q2, p1, q1 = 0, 1, 1, 0
    for a in terms:
        p2, q2, p1, q1 = p1, q1, a * p1 + p2, a * q1 + q2
    pn, qn, pm, qm = p1, q1, p2, q2  # x = pn/qn, previous convergent pm/qm
    out = []
    for side, make in ((1, lambda j: (pm + j * pn, qm + j * qn)), (-1, lambda j: (j * pn - pm, j * qn - qm))):
        for j in range(1, count + 1):
            p, q = make(j)
            if p <= 0 or q <= 0:
                continue
            if max_term is not None and max(p, q) > max_term:
                break
            frac = Fraction(p, q)
            out.append(Approximant(frac, "neighbour", side, j, frac - x))
    return out


# --------------------------------------------------------------------------- designs by the rules


@dataclass(frozen=True)
class TrainDesign:
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

    def as_dict(self) -> dict:
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
    lambda: this is the text's "factors, or multiples of them" (seed 004,
    page marked (41)).  lambda runs from ceil(t**K / min(B, C)) up.  If B or
    C has a prime factor above max_teeth, no lambda helps (the "awkward large
    prime" of the text) and the list is empty at once.

    Examples
    --------
    >>> d = exact_trains(12, 2, 12, 72)[0]
    >>> d.drivers, d.followers, d.ratio
    ((36, 48), (12, 12), Fraction(12, 1))
    """
    frac = parse_ratio(ratio)
    k = _validate.positive_int("pairs", pairs)
    lo, hi = _teeth_range(min_teeth, max_teeth)
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
        f_small = factorizations(lam * small, k, lo, hi)
        if f_small:
            f_large = factorizations(lam * large, k, lo, hi)
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
class DesignResult:
    """Result of :func:`design_train`.

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
    """

    target: Fraction
    min_teeth: int
    max_teeth: int
    bounds: PairCountBounds
    method: str
    approximation: Fraction
    designs: tuple[TrainDesign, ...]
    tried: tuple

    def as_dict(self) -> dict:
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
            "designs": [d.as_dict() for d in self.designs],
        }


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
    Seed 004, page marked (41).  With B/C in lowest terms: try to resolve B
    and C into K factors (or multiples) within [t, T] for K between
    |log B - log C|/log 6 and |log B - log C|/log 3 (:func:`exact_trains`);
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
    keep = _validate.positive_int("keep", keep)
    if min_teeth is None:
        t = min_teeth_for_form(tooth_form)
    else:
        t = _validate.positive_int("min_teeth", min_teeth)
    big = int(rules()["max_teeth_factor"]) * t if max_teeth is None else _validate.positive_int("max_teeth", max_teeth)
    lo, hi = _teeth_range(t, big)
    bounds = pair_count_bounds(frac)
    ks = (_validate.positive_int("pairs", pairs),) if pairs is not None else bounds.candidates
    for k in ks:
        designs = exact_trains(frac, k, lo, hi, keep=keep, prefer=prefer)
        if designs:
            return DesignResult(frac, lo, hi, bounds, "exact", frac, tuple(designs), ())
    candidates = [a for a in approximants(frac, max_term=hi ** max(ks)) if a.fraction != frac]
    candidates += neighbours(frac, max_term=hi ** max(ks))
    candidates.sort(key=lambda a: abs(a.error))  # most accurate first; stable for ties
    tried = []
    for approx in candidates:
        p, q = approx.fraction.numerator, approx.fraction.denominator
        for k in ks:
            if max(p, q) > hi**k:
                tried.append((approx, k, False))
                continue
            designs = exact_trains(approx.fraction, k, lo, hi, keep=keep, prefer=prefer)
            tried.append((approx, k, bool(designs)))
            if designs:
                designs = tuple(TrainDesign(d.drivers, d.followers, d.ratio, frac, d.multiplier) for d in designs)
                return DesignResult(frac, lo, hi, bounds, "continued fraction", approx.fraction, designs, tuple(tried))
    raise GearleverError(
        f"ratio {frac} cannot be built with {', '.join(map(str, ks))} pair(s) of teeth in [{lo}, {hi}]; "
        "by factors or continued fractions; use search_best (gearlever train search) or a wider tooth range"
    )


# --------------------------------------------------------------------------- exact best search


def search_space_size(pairs, min_teeth, max_teeth) -> int:
    """Number of tooth multisets of one side: C(n + K - 1, K), n = max - min + 1.

    Notes
    -----
    Multisets of K teeth out of n sizes (combinations with repetition); the
    size checked by :func:`search_best` before it starts.

    Examples
    --------
    >>> search_space_size(5, 12, 60)
    2869685
    """
    k = _validate.positive_int("pairs", pairs)
    lo, hi = _teeth_range(min_teeth, max_teeth)
    return math.comb(hi - lo + 1 + k - 1, k)


def _distinct_products(k: int, lo: int, hi: int) -> np.ndarray:
    base = np.arange(lo, hi + 1, dtype=np.int64)
    prods = base
    for _ in range(k - 1):
        allp = np.multiply.outer(prods, base).ravel()
        allp.sort()
        keep = np.empty(allp.size, dtype=bool)
        keep[0] = True
        np.not_equal(allp[1:], allp[:-1], out=keep[1:])
        prods = allp[keep]
    return prods


@dataclass(frozen=True)
class TrainSolution:
    """One optimal tooth set (drivers and followers each as a sorted multiset).

    Attributes
    ----------
    drivers, followers : tuple of int
        Non-decreasing.
    ratio : Fraction
    """

    drivers: tuple[int, ...]
    followers: tuple[int, ...]
    ratio: Fraction

    @property
    def pairing(self) -> tuple[tuple[int, int], ...]:
        """Driver-follower pairs arranged for the least gcd (:func:`best_pairing`)."""
        return best_pairing(self.drivers, self.followers)

    def as_dict(self) -> dict:
        pairing = self.pairing
        return {
            "drivers": list(self.drivers),
            "followers": list(self.followers),
            "ratio": f"{self.ratio.numerator}/{self.ratio.denominator}",
            "pairs": [list(p) for p in pairing],
            "gcd": [math.gcd(d, f) for d, f in pairing],
        }


@dataclass(frozen=True)
class SearchResult:
    """Result of :func:`search_best`.

    Attributes
    ----------
    target : Fraction
    pairs, min_teeth, max_teeth : int
    metric : {"absolute", "relative"}
    best_error : Fraction
        Least error, exact (absolute |ratio - target| or relative
        |ratio - target| / target).
    best_ratios : tuple of Fraction
        The optimal ratio(s) (two only if they lie at equal distance on both
        sides of the target).
    solutions : tuple of TrainSolution
        Every optimal tooth set up to order (or the first ``limit``).
    n_solutions : int
        Number of optimal tooth sets up to order (all of them, even if
        ``limit`` cut the list).
    n_ordered : int
        Number of optimal ordered tooth tuples (d_1..d_K, f_1..f_K), as a
        brute force over every tuple would count them.
    n_products : int
        Number of distinct products of K teeth searched per side.
    space_size : int
        Tooth multisets per side (:func:`search_space_size`).
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

    def as_dict(self) -> dict:
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
            "n_solutions": self.n_solutions,
            "n_ordered": self.n_ordered,
            "n_products": self.n_products,
            "solutions": [s.as_dict() for s in self.solutions],
        }


def search_best(
    ratio,
    pairs,
    min_teeth,
    max_teeth,
    metric: str = "absolute",
    max_space: int = DEFAULT_MAX_SPACE,
    limit: int | None = None,
) -> SearchResult:
    """Every train of K pairs, teeth in [min_teeth, max_teeth], closest to ``ratio``.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
        Target prod(drivers) / prod(followers).
    pairs : int
        K, the number of drivers (= number of followers).
    min_teeth, max_teeth : int
        Tooth range, the same for every wheel.
    metric : {"absolute", "relative"}
        |R - r| or |R - r| / r.  (Since r is fixed both have the same optima;
        only the reported error differs.)
    max_space : int
        Refuse (ValueError, before any work) when the number of tooth
        multisets per side exceeds this.
    limit : int, optional
        List at most this many solutions (the counts stay complete).

    Returns
    -------
    SearchResult

    Notes
    -----
    Exhaustive over distinct products.  Let S be the sorted distinct products
    of K teeth in range (built by repeated outer products and de-duplication).
    For a driver product P the error |P/Q - r| falls as Q rises to P/r and
    then grows, so the best follower product for P is one of the neighbours
    of P/r in S, found by bisection (``np.searchsorted``); four neighbours
    are checked for safety against rounding.  Candidates within a few ulps
    of the float minimum are then compared in exact rational arithmetic, and
    each optimal product pair is factored back into every tooth multiset
    (:func:`factorizations`).  No heuristic is involved, so the result is
    the proven optimum.

    Examples
    --------
    >>> res = search_best("1/6.931", 2, 12, 60)
    >>> [(s.drivers, s.followers) for s in res.solutions], res.n_ordered
    ([((16, 19), (43, 49))], 4)
    >>> f"{float(res.best_error)**2:.6e}"
    '2.700857e-12'
    """
    target = parse_ratio(ratio)
    k = _validate.positive_int("pairs", pairs)
    lo, hi = _teeth_range(min_teeth, max_teeth)
    if metric not in ("absolute", "relative"):
        raise GearleverError(f"metric must be 'absolute' or 'relative', got {metric!r}")
    max_space = _validate.positive_int("max_space", max_space)
    if limit is not None:
        limit = _validate.positive_int("limit", limit)
    size = search_space_size(k, lo, hi)
    if size > max_space:
        raise GearleverError(
            f"pairs: search space too large: {size:,} tooth multisets per side for {k} pairs "
            f"of teeth in [{lo}, {hi}] (limit {max_space:,}); use fewer pairs or a narrower range"
        )
    if hi**k >= 2**52:
        raise GearleverError(f"max_teeth: products up to {hi}**{k} are too large for an exact float search")
    prods = _distinct_products(k, lo, hi)
    r = float(target)
    pf = prods.astype(float)
    idx = np.searchsorted(prods, pf / r)
    cand = np.clip(idx[:, None] + np.arange(-2, 2), 0, prods.size - 1)
    qf = pf[cand]
    err = np.abs(pf[:, None] / qf - r)
    best_f = float(err.min())
    tol = 16 * np.finfo(float).eps * (r + best_f)
    rows, cols = np.nonzero(err <= best_f + tol)
    pairs_pq = sorted({(int(prods[i]), int(prods[cand[i, j]])) for i, j in zip(rows, cols)})
    exact = [(abs(Fraction(p, q) - target), p, q) for p, q in pairs_pq]
    best_exact = min(e for e, _, _ in exact)
    optimal = [(p, q) for e, p, q in exact if e == best_exact]
    solutions = []
    n_sets = n_ordered = 0
    for p, q in optimal:
        fd = factorizations(p, k, lo, hi)
        fq = factorizations(q, k, lo, hi)
        n_sets += len(fd) * len(fq)
        n_ordered += sum(map(_multiset_permutations, fd)) * sum(map(_multiset_permutations, fq))
        for d in fd:
            for f in fq:
                if limit is None or len(solutions) < limit:
                    solutions.append(TrainSolution(d, f, Fraction(p, q)))
    best_err = best_exact if metric == "absolute" else best_exact / target
    ratios = tuple(sorted({Fraction(p, q) for p, q in optimal}))
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
    )
