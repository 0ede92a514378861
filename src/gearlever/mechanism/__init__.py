"""Planar mechanisms: structure (mobility with redundant constraints).

- :mod:`~gearlever.mechanism.structure`: the mobility formula
  W = 3n - 2 P5 - P4 + q and its inverse for redundant constraints.

Numeric core: may import numpy, :mod:`gearlever.loops`, :mod:`gearlever.gears`,
:mod:`gearlever.errors`, :mod:`gearlever._validate`; never pandas or matplotlib.
"""

from gearlever.mechanism.structure import mobility, redundant_constraints

__all__ = ["mobility", "redundant_constraints"]
