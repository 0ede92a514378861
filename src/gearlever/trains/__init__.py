"""Trains of wheels: ratio and sense, tooth-number design, exact search, Hooke's coupling.

- :mod:`~gearlever.trains.ratio`: velocity ratio and sense of a simple or
  compound train.
- :mod:`~gearlever.trains.rules`: the classical rules and their data.
- :mod:`~gearlever.trains.continued`: exact ratios and continued fractions.
- :mod:`~gearlever.trains.design`: tooth numbers by the classical rules.
- :mod:`~gearlever.trains.search`: the exhaustive best search, with exact counts.
- :mod:`~gearlever.trains.teeth`: the four above under one name.
- :mod:`~gearlever.trains.hooke`: Hooke's (cardan) coupling, single and double
  (radians; ``HookeJoint.from_degrees`` for degrees).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy, :mod:`fractions` and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``data``, ``errors``; never pandas or matplotlib.
"""

from gearlever.trains.continued import parse_ratio
from gearlever.trains.design import DesignResult, design_train
from gearlever.trains.hooke import HookeJoint, HookeTurn
from gearlever.trains.ratio import TrainRatio, train_ratio
from gearlever.trains.search import SearchResult, factorization_counts, search_best

__all__ = [
    "DesignResult",
    "HookeJoint",
    "HookeTurn",
    "SearchResult",
    "TrainRatio",
    "design_train",
    "factorization_counts",
    "parse_ratio",
    "search_best",
    "train_ratio",
]
