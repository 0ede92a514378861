"""The one result convention: frozen dataclasses with array fields.

Every result class of the numeric core is a ``@dataclass(frozen=True)`` that
inherits :class:`Result`, which gives it

- :meth:`Result.as_dict`: its fields in declaration order, as they are;
- :meth:`Result.to_frame`: a pandas DataFrame, one row per input point,
  built by :func:`gearlever._frame.frame` (which imports pandas) only when
  called, so the numeric core never loads pandas.

Imports only the standard library and numpy.
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

__all__ = ["Result"]


class Result:
    """Mixin of the result dataclasses: :meth:`as_dict` and :meth:`to_frame`.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class R(Result):
    ...     phi: np.ndarray
    ...     u: np.ndarray
    >>> R(np.array([0.0, 1.0]), np.array([1.0, 2.0])).to_frame().shape
    (2, 2)
    """

    def as_dict(self) -> dict:
        """The fields in declaration order (arrays are not copied)."""
        return {f.name: getattr(self, f.name) for f in fields(self)}

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
