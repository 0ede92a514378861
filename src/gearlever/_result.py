"""The one result convention: frozen dataclasses with array fields.

Every result class of the package is a ``@dataclass(frozen=True)`` that
inherits :class:`Result` (exported as :class:`gearlever.Result`), which gives it

- :meth:`Result.as_dict`: its fields in declaration order, as they are;
- :meth:`Result.to_frame`: a pandas DataFrame, one row per input point,
  built by :func:`gearlever._frame.frame` (which imports pandas) only when
  called, so the numeric core never loads pandas;
- :meth:`Result.summary`: its JSON-ready summary (plain dicts, lists,
  numbers and strings, NaN as None), rounded by the digits rule of
  :mod:`gearlever._format`.  The default keeps the scalars and short arrays
  of :meth:`~Result.as_dict`; a result whose command-line report is more
  than that overrides it (the keys of a written report never change).

Names of the same quantity across results (a short glossary; every result
uses these, and a written report that spelled a quantity otherwise keeps its
key, mapped by its writer):

=======================  ====================================================
name                     quantity
=======================  ====================================================
``target``               what the design is asked for at the targets (a ratio,
                         the wanted outputs of a function generator, the
                         points of a path, a law over its samples);
                         ``target_at(x)`` gives it elsewhere and
                         ``dense_target`` over a dense sampling
``achieved``             what the design gives at the targets (the output of a
                         function generator, the traced points of a path
                         generator, the law a linkage produces);
                         ``achieved_at(x)`` and ``dense_achieved`` likewise
``error``                ``achieved - target`` at each target, or its size per
                         target (one array; a scalar error is ``max_error``
                         or ``rms_error``); in a search's front, each
                         design's error (a curve synthesis: the distance of
                         its traced curve to the target).  An error of one
                         kind of quantity is qualified: ``point_error``,
                         ``angle_error``, ``structural_error_max``
``objective``            the number a search minimizes (a weighted sum or
                         maximum of the errors)
``transmission_range``   ``(min, max)`` of the transmission angle over the
                         motion, rad
``model``                the model dict of a synthesized linkage (a method
                         ``model()`` where it is built on demand)
``designs``              the listed designs of a search, best first
=======================  ====================================================

The object a result was asked for, when it is kept, is named by its type
(``law_target``: a :class:`~gearlever.synthesis.law.LawTarget`), never
``target``, which is always the wanted values themselves.

Imports only the standard library, numpy and :mod:`gearlever._format`.
"""

from __future__ import annotations

from dataclasses import fields
from fractions import Fraction

import numpy as np

from gearlever._format import DIGITS_DESIGN, rounded

__all__ = ["Result", "SUMMARY_MAX_ITEMS"]

#: Most elements of an array (or list) the default :meth:`Result.summary` keeps; longer ones are left to
#: :meth:`Result.to_frame`.
SUMMARY_MAX_ITEMS = 16

_SKIP = object()


def _plain(v):
    """``v`` as plain JSON-ready Python (numbers, strings, lists, dicts), or ``_SKIP`` when it is not short data."""
    if v is None or isinstance(v, (bool, str)):
        return v
    if isinstance(v, np.bool_):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v)
    if isinstance(v, Fraction):
        return f"{v.numerator}/{v.denominator}"
    if isinstance(v, Result):
        return v.summary()
    if isinstance(v, np.ndarray):
        if v.size > SUMMARY_MAX_ITEMS or v.dtype.kind not in "biuf":
            return _SKIP
        return _plain(v.tolist())
    if isinstance(v, (list, tuple)):
        if len(v) > SUMMARY_MAX_ITEMS:
            return _SKIP
        out = [_plain(x) for x in v]
        return _SKIP if any(x is _SKIP for x in out) else out
    if isinstance(v, dict):
        if len(v) > SUMMARY_MAX_ITEMS or not all(isinstance(k, str) for k in v):
            return _SKIP
        out = {k: _plain(x) for k, x in v.items()}
        return _SKIP if any(x is _SKIP for x in out.values()) else out
    return _SKIP


class Result:
    """Base of the result dataclasses: :meth:`as_dict`, :meth:`to_frame` and :meth:`summary`.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class R(Result):
    ...     phi: np.ndarray
    ...     u: np.ndarray
    ...     peak: float
    >>> r = R(np.array([0.0, 1.0]), np.array([1.0, 2.0 / 3.0]), float("nan"))
    >>> r.to_frame().shape
    (2, 2)
    >>> r.summary()
    {'phi': [0.0, 1.0], 'u': [1.0, 0.6666666667], 'peak': None}
    """

    #: Significant digits of :meth:`summary` (:mod:`gearlever._format`: reports are written at 10).
    SUMMARY_DIGITS = DIGITS_DESIGN

    def as_dict(self) -> dict:
        """The fields in declaration order (arrays are not copied)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def summary(self) -> dict:
        """JSON-ready summary: the scalars and short arrays of :meth:`as_dict`, rounded by the digits rule.

        Numbers are rounded to :attr:`SUMMARY_DIGITS` significant digits
        (:func:`gearlever._format.rounded`); NaN and infinities are None
        (strict JSON); exact fractions are written ``"p/q"``; nested results
        give their own summary.  Arrays of more than
        :data:`SUMMARY_MAX_ITEMS` elements, and fields that are not data,
        are left out (they are in :meth:`to_frame` and :meth:`as_dict`).
        """
        out = {}
        for k, v in self.as_dict().items():
            p = _plain(v)
            if p is not _SKIP:
                out[k] = p
        return rounded(out, self.SUMMARY_DIGITS)

    def _frame_columns(self) -> dict:
        """Columns of :meth:`to_frame`: 1-D array fields of the leading length.

        A field of shape (N, 2) gives two columns, ``name_x`` and ``name_y``;
        (N, k) gives ``name_0`` ... ``name_{k-1}``.  Scalars and other shapes
        are left to :meth:`as_dict`.  Subclasses override this to name
        columns with their units.
        """
        arrays = {k: v for k, v in self.as_dict().items() if isinstance(v, np.ndarray) and v.ndim >= 1}
        if not arrays:
            return {}
        n = max(v.shape[0] for v in arrays.values())
        cols = {}
        for name, v in arrays.items():
            if v.shape[0] != n:
                continue
            if v.ndim == 1:
                cols[name] = v
            elif v.ndim == 2 and v.shape[1] == 2:
                cols[f"{name}_x"], cols[f"{name}_y"] = v[:, 0], v[:, 1]
            elif v.ndim == 2:
                for j in range(v.shape[1]):
                    cols[f"{name}_{j}"] = v[:, j]
        return cols

    def to_frame(self):
        """A :class:`pandas.DataFrame`, one row per input point (built by :func:`gearlever._frame.frame`)."""
        from gearlever._frame import frame

        return frame(self._frame_columns())
