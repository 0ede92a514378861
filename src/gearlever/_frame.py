"""The DataFrame of a result's columns: the one door from the numeric core to pandas.

:meth:`gearlever._result.Result.to_frame` (the base of every result) builds
its DataFrame here, and so does :mod:`gearlever.tables`.  This is a leaf: it
imports nothing of gearlever, and pandas only inside :func:`frame`, when a
frame is asked for, so ``import gearlever`` never loads pandas.  It sits
outside :mod:`gearlever.tables` because that package imports the numeric core
(its tables are computed there), and a base class importing it would put
every package of the core in one import circle.
"""

from __future__ import annotations

__all__ = ["frame"]


def frame(columns: dict):
    """A :class:`pandas.DataFrame` of ``columns`` (name -> 1-D array), in the order given.

    >>> frame({"x": [1.0, 2.0], "y": [3.0, 4.0]}).shape
    (2, 2)
    """
    import pandas as pd

    return pd.DataFrame(columns)
