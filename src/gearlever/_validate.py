"""Input checks shared by the numeric modules.

Every check raises :class:`gearlever.errors.GearleverError` (a
:class:`ValueError`) whose message starts with the name of the parameter and
says what it must be, e.g. ``"l1 must be a positive finite
number, got -2.0"``.  The CLI prints that message as its one line on stderr.
"""

from __future__ import annotations

import math
import numbers

import numpy as np

from gearlever.errors import GearleverError


def _is_real_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def finite(name: str, value) -> float:
    """Return ``value`` as a float, or raise if it is not a finite real number.

    >>> finite("x", 2)
    2.0
    """
    if not _is_real_number(value) or not math.isfinite(float(value)):
        raise GearleverError(f"{name} must be a finite number, got {value!r}")
    return float(value)


def positive(name: str, value) -> float:
    """Return ``value`` as a float, or raise if it is not finite and > 0.

    >>> positive("l1", 21.0)
    21.0
    """
    if not _is_real_number(value) or not math.isfinite(float(value)) or float(value) <= 0:
        raise GearleverError(f"{name} must be a positive finite number, got {value!r}")
    return float(value)


def nonnegative(name: str, value) -> float:
    """Return ``value`` as a float, or raise if it is not finite and >= 0."""
    if not _is_real_number(value) or not math.isfinite(float(value)) or float(value) < 0:
        raise GearleverError(f"{name} must be a non-negative finite number, got {value!r}")
    return float(value)


def positive_int(name: str, value) -> int:
    """Return ``value`` as an int, or raise if it is not an integer >= 1.

    >>> positive_int("n2", 30)
    30
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and float(value).is_integer() and not isinstance(value, bool):
            value = int(value)
        else:
            raise GearleverError(f"{name} must be a positive integer, got {value!r}")
    if value < 1:
        raise GearleverError(f"{name} must be a positive integer, got {value!r}")
    return int(value)


def nonnegative_int(name: str, value) -> int:
    """Return ``value`` as an int, or raise if it is not an integer >= 0."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and float(value).is_integer() and not isinstance(value, bool):
            value = int(value)
        else:
            raise GearleverError(f"{name} must be a non-negative integer, got {value!r}")
    if value < 0:
        raise GearleverError(f"{name} must be a non-negative integer, got {value!r}")
    return int(value)


def finite_array(name: str, values) -> np.ndarray:
    """Return ``values`` as a float ndarray (any shape), or raise if any is not finite.

    >>> finite_array("phi", [0.0, 1.0]).shape
    (2,)
    """
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be an array of finite numbers") from None
    if not np.all(np.isfinite(arr)):
        raise GearleverError(f"{name} must be an array of finite numbers (found NaN or inf)")
    return arr


def nonempty_array(name: str, values) -> np.ndarray:
    """Like :func:`finite_array`, and the array must hold at least one value."""
    arr = finite_array(name, values)
    if arr.size == 0:
        raise GearleverError(f"{name} must hold at least one value, got an empty array")
    return arr
