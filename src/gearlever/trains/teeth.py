"""Choosing the tooth numbers of a train of wheels for a wanted velocity ratio.

This module gathers, under one name, the four modules that do the work:

- :mod:`~gearlever.trains.rules`: the classical rules and their data
  (:func:`rules`, :func:`min_teeth_for_form`, :func:`pair_count_bounds`,
  :func:`sandgren_published`);
- :mod:`~gearlever.trains.continued`: exact ratios and continued fractions
  (:func:`parse_ratio`, :func:`continued_fraction`, :func:`convergents`,
  :func:`approximants`, :func:`neighbours`);
- :mod:`~gearlever.trains.design`: design by the rules
  (:func:`factorizations`, :func:`best_pairing`, :func:`exact_trains`,
  :func:`design_train`);
- :mod:`~gearlever.trains.search`: the exhaustive best search with exact
  counts (:func:`search_space_size`, :func:`factorization_counts`,
  :func:`search_best`).

Ratios are exact :class:`fractions.Fraction` throughout.  The velocity ratio
is that of the last axis to the first, prod(drivers) / prod(followers).
"""

from __future__ import annotations

from gearlever.trains._caps import (
    DEFAULT_LIMIT,
    DEFAULT_MAX_SPACE,
    MAX_KEEP,
    MAX_LIMIT,
    MAX_PAIRS,
    MAX_SPACE_CAP,
    MAX_TEETH,
)
from gearlever.trains.continued import (
    MAX_RATIO_CHARS,
    Approximant,
    approximants,
    continued_fraction,
    convergents,
    neighbours,
    parse_ratio,
)
from gearlever.trains.design import (
    PREFERENCES,
    DesignResult,
    TrainDesign,
    best_pairing,
    design_train,
    exact_trains,
    factorizations,
)
from gearlever.trains.rules import (
    TOOTH_FORMS,
    PairCountBounds,
    min_teeth_for_form,
    pair_count_bounds,
    rules,
    sandgren_published,
)
from gearlever.trains.search import (
    METRICS,
    SearchResult,
    TrainSolution,
    factorization_counts,
    search_best,
    search_space_size,
)

__all__ = [
    "DEFAULT_LIMIT",
    "DEFAULT_MAX_SPACE",
    "MAX_KEEP",
    "MAX_LIMIT",
    "MAX_PAIRS",
    "MAX_RATIO_CHARS",
    "MAX_SPACE_CAP",
    "MAX_TEETH",
    "METRICS",
    "PREFERENCES",
    "TOOTH_FORMS",
    "Approximant",
    "DesignResult",
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
    "factorization_counts",
    "factorizations",
    "min_teeth_for_form",
    "neighbours",
    "pair_count_bounds",
    "parse_ratio",
    "rules",
    "sandgren_published",
    "search_best",
    "search_space_size",
]
