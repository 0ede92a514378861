"""Trains of wheels: ratio and sense, tooth-number design, exact search, Hooke's coupling.

- :mod:`~gearlever.trains.ratio`: velocity ratio and sense of a simple or
  compound train.
- :mod:`~gearlever.trains.rules`: the classical rules and their data.
- :mod:`~gearlever.trains.continued`: exact ratios and continued fractions.
- :mod:`~gearlever.trains.design`: tooth numbers by the classical rules.
- :mod:`~gearlever.trains.search`: the exhaustive best search, with exact counts.
- :mod:`~gearlever.trains.hooke`: Hooke's (cardan) coupling, single and double
  (radians; ``HookeJoint.from_degrees`` for degrees).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy, :mod:`fractions` and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``data``, ``errors``; never pandas or matplotlib.

This package is the one public face of the tooth-number design: every public
name of ``rules``, ``continued``, ``design`` and ``search`` is importable from
``gearlever.trains``, except the function ``rules.rules``, whose name is its
module's.  Ratios are exact :class:`fractions.Fraction`
throughout; the velocity ratio is that of the last axis to the first,
prod(drivers) / prod(followers).
"""

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
from gearlever.trains.hooke import HookeJoint, HookeTurn
from gearlever.trains.ratio import TrainRatio, train_ratio
from gearlever.trains.rules import (
    TOOTH_FORMS,
    PairCountBounds,
    min_teeth_for_form,
    pair_count_bounds,
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
    "HookeJoint",
    "HookeTurn",
    "PairCountBounds",
    "SearchResult",
    "TrainDesign",
    "TrainRatio",
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
    "sandgren_published",
    "search_best",
    "search_space_size",
    "train_ratio",
]
