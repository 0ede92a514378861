"""Trains of wheels: ratio and sense, tooth-number synthesis, exact search, Hooke's coupling.

- :mod:`~gearlever.trains.ratio`: velocity ratio and sense of a simple or
  compound train.
- :mod:`~gearlever.trains.synthesis`: tooth numbers for a wanted ratio by the
  classical rules, continued fractions, and an exhaustive best search.
- :mod:`~gearlever.trains.hooke`: Hooke's (cardan) coupling, single and double.

Numeric core: may import numpy, scipy, :mod:`fractions`, :mod:`gearlever.errors`,
:mod:`gearlever._validate`, :mod:`gearlever.data`; never pandas or matplotlib.
"""

from gearlever.trains.hooke import HookeJoint
from gearlever.trains.ratio import TrainRatio, train_ratio
from gearlever.trains.synthesis import design_train, search_best

__all__ = ["HookeJoint", "TrainRatio", "design_train", "search_best", "train_ratio"]
