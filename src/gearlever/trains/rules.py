"""The classical rules for choosing the tooth numbers of a train, and their data.

The numbers (least pinion teeth per tooth form, Young's 3.59 per pair, 3 to 6
per pair, factors between t and 6t) are read from ``data/train_rules.csv``;
the published optimum of Sandgren's gear-train problem from
``data/sandgren_gear_train.csv``.  Source of the rules: the classic text on
trains of wheelwork, page marked (41).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from fractions import Fraction

from gearlever.errors import GearleverError
from gearlever.trains.continued import parse_ratio

__all__ = [
    "TOOTH_FORMS",
    "PairCountBounds",
    "min_teeth_for_form",
    "pair_count_bounds",
    "rules",
    "sandgren_published",
]

#: Tooth forms known to :func:`min_teeth_for_form` (values in data/train_rules.csv).
TOOTH_FORMS = ("epicycloidal", "smooth", "involute")


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
    The classic text on trains of wheelwork, page marked (41): least pinion
    teeth 12 (epicycloidal), 15 (for smoothness), about 24 (involute);
    Young's 3.59 per pair for the least total number of teeth; 3 to 6 per
    pair in practice; factors between t and 6t.  Read from the data file,
    whose header names the page and units.

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
    The classic text on trains of wheelwork, page marked (41): 12 teeth for
    epicycloidal teeth, 15 for smoother running, about 24 for involute teeth.

    Examples
    --------
    >>> min_teeth_for_form("involute")
    24
    """
    if tooth_form not in TOOTH_FORMS:
        raise GearleverError(f"tooth_form must be one of {', '.join(TOOTH_FORMS)}, got {tooth_form!r}")
    return int(rules()[f"min_teeth_{tooth_form}"])


@dataclass(frozen=True)
class PairCountBounds:
    """Bounds on the number of pairs (elementary combinations) for a ratio.

    Attributes
    ----------
    lower, upper : float
        ``|log B - log C| / log 6`` and ``|log B - log C| / log 3``.
    young : float
        ``|log B - log C| / log 3.59`` (Young's least-teeth number of pairs).
    candidates : tuple of int
        The whole numbers of pairs to try, smallest first: those within
        [lower, upper]; when no whole number lies there, the next one above
        ``lower``; always at least 1.

    Examples
    --------
    >>> pair_count_bounds("1/6.931").candidates  # Sandgren's ratio: two pairs
    (2,)
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
    The classic text on trains of wheelwork, page marked (41): for B/C > 6
    the number of elementary combinations (pairs) is taken between
    ``|log B - log C| / log 6`` and ``|log B - log C| / log 3``, each pair giving a
    ratio of 3 to 6; Young's rule for the least total number of teeth is
    3.59 per pair.

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
