"""Exact ratios and their continued fractions.

:func:`parse_ratio` reads a wanted velocity ratio exactly (a number, a
:class:`fractions.Fraction` or a ``"B/C"`` string); :func:`continued_fraction`,
:func:`convergents`, :func:`approximants` and :func:`neighbours` give the
nearby fractions the classic text on trains of wheelwork (page marked (41))
turns to when a ratio holds a prime too large for a wheel.
"""

from __future__ import annotations

import math
import numbers
import re
from dataclasses import dataclass
from fractions import Fraction

from gearlever import _validate
from gearlever.errors import GearleverError

__all__ = [
    "MAX_RATIO_CHARS",
    "Approximant",
    "approximants",
    "continued_fraction",
    "convergents",
    "neighbours",
    "parse_ratio",
]

#: Longest ratio string accepted by :func:`parse_ratio` (decimal digits cost
#: nothing to read, but a ratio of 100-digit terms is no wheel train).
MAX_RATIO_CHARS = 64

# One positive decimal: digits with an optional point, an optional exponent of
# at most three digits (so "1e999999999" cannot make a billion-digit integer).
_NUMBER = r"(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d{1,3})?"
_RATIO_RE = re.compile(rf"\s*({_NUMBER})\s*(?:/\s*({_NUMBER})\s*)?")


def parse_ratio(value, name: str = "ratio") -> Fraction:
    """Return a positive exact ratio from a number, a Fraction or a ``"B/C"`` string.

    A float is read as the decimal it prints as (``0.25`` -> 1/4).  A string
    is either one positive number or ``B/C`` with B and C positive integers
    or decimals (an exponent such as ``1e3`` is allowed); anything else, such
    as ``"1/3/4"``, a sign, ``"nan"`` or ``"inf"``, is refused.

    Parameters
    ----------
    value : int, float, Fraction or str
    name : str
        Parameter name used in the error message.

    Returns
    -------
    Fraction
        In lowest terms, between 1e-300 and 1e300.

    Raises
    ------
    GearleverError
        Naming ``name`` and the accepted forms.

    Notes
    -----
    The velocity ratio of a train is a ratio of whole numbers of teeth,
    prod(drivers) / prod(followers) (the classic text on trains of wheelwork,
    page marked (41)), so it is kept exact: ``"1/6.931"`` is 1000/6931.

    Examples
    --------
    >>> parse_ratio("1/6.931")
    Fraction(1000, 6931)
    >>> parse_ratio(3.59)
    Fraction(359, 100)
    """
    bad = (
        f"{name} must be a positive number or B/C with B and C positive integers or decimals "
        f"(e.g. 3.59 or 1/6.931), got {value!r}"
    )
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
        if len(value) > MAX_RATIO_CHARS:
            raise GearleverError(f"{name} must be at most {MAX_RATIO_CHARS} characters long, got {len(value)}")
        match = _RATIO_RE.fullmatch(value)
        if match is None:
            raise GearleverError(bad)
        num = Fraction(match.group(1))
        den = Fraction(match.group(2)) if match.group(2) is not None else Fraction(1)
        if num == 0 or den == 0:
            raise GearleverError(bad)
        frac = num / den
    else:
        raise GearleverError(bad)
    if frac <= 0:
        raise GearleverError(bad)
    try:
        as_float = float(frac)
    except OverflowError:
        as_float = math.inf
    if not 1e-300 < as_float < 1e300:
        raise GearleverError(f"{name} must be between 1e-300 and 1e300, got {value!r}")
    return frac


def continued_fraction(ratio) -> list[int]:
    """Partial quotients [a0; a1, a2, ...] of a positive rational.

    Notes
    -----
    Euclid's algorithm: a_k = floor(x_k), x_(k+1) = 1 / (x_k - a_k), until
    the remainder is 0: the method of continued fractions the classic text on
    trains of wheelwork prescribes for awkward ratios (page marked (41)).

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

    Examples
    --------
    >>> a = approximants("355/113")[0]
    >>> a.fraction, a.kind, a.error
    (Fraction(3, 1), 'convergent', Fraction(-16, 113))
    """

    fraction: Fraction
    kind: str
    index: int
    multiple: int
    error: Fraction


def approximants(ratio, max_term: int | None = None, max_per_term: int | None = None) -> list[Approximant]:
    """Every convergent and semiconvergent of ``ratio``, in order of growing terms.

    Parameters
    ----------
    ratio : number, Fraction or "B/C"
    max_term : int, optional
        Stop at the first approximant whose numerator or denominator exceeds
        this (numerators and denominators never decrease along the list).
    max_per_term : int, optional
        Keep at most this many of the run belonging to one partial quotient:
        the last ones (largest j), which are the most accurate.  Without it
        a partial quotient of 10**9 would list 10**9 fractions.

    Returns
    -------
    list of Approximant
        For each partial quotient a_k (k >= 1), the semiconvergents
        (p_(k-2) + j p_(k-1)) / (q_(k-2) + j q_(k-1)) for j = 1 .. a_k - 1,
        then the convergent (j = a_k).  The last entry is ``ratio`` itself.

    Notes
    -----
    The classic text on trains of wheelwork (page marked (41)) replaces a
    ratio whose terms hold large primes by a nearby ratio that factors,
    found by continued fractions.  Convergents and semiconvergents include every best rational
    approximation of the ratio.

    Examples
    --------
    >>> [str(a.fraction) for a in approximants("355/113")][:4]
    ['3', '4', '7/2', '10/3']
    """
    x = parse_ratio(ratio)
    if max_term is not None:
        max_term = _validate.positive_int("max_term", max_term)
    if max_per_term is not None:
        max_per_term = _validate.positive_int("max_per_term", max_per_term)
    terms = continued_fraction(x)
    p_prev2, q_prev2 = 0, 1
    p_prev, q_prev = 1, 0
    out = []
    for k, a in enumerate(terms):
        start, end = (1 if k > 0 else a), a
        if max_term is not None:  # largest j whose terms stay within max_term
            for base, step in ((p_prev2, p_prev), (q_prev2, q_prev)):
                if step > 0:
                    end = min(end, (max_term - base) // step)
        if max_per_term is not None:
            start = max(start, end - max_per_term + 1)
        for j in range(start, end + 1):
            p, q = p_prev2 + j * p_prev, q_prev2 + j * q_prev
            if p == 0:
                continue
            frac = Fraction(p, q)
            kind = "convergent" if j == a else "semiconvergent"
            out.append(Approximant(frac, kind, k, j, frac - x))
        if end < a:
            return out
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
    with M large; ``|x - neighbour|`` = 1 / (q_n (q_(n-1) + j q_n)) on the first
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
