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

    Bools and strings are refused (``True`` is not the number 1 here, ``"1"``
    is text), as are ragged nestings.

    >>> finite_array("phi", [0.0, 1.0]).shape
    (2,)
    >>> finite_array("q", [True, False])
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: q must be an array of finite numbers, got bools
    """
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError):
        raise GearleverError(f"{name} must be an array of finite numbers (a ragged nesting is not)") from None
    kind = raw.dtype.kind
    if kind == "b":
        raise GearleverError(f"{name} must be an array of finite numbers, got bools")
    if kind in "USVMm":
        raise GearleverError(
            f"{name} must be an array of finite numbers, got {'text' if kind in 'US' else raw.dtype.name}"
        )
    if kind == "O" and not all(_is_real_number(v) for v in raw.flat):
        bad = next(v for v in raw.flat if not _is_real_number(v))
        shown = repr(bad) if len(repr(bad)) <= 40 else repr(bad)[:37] + "..."
        raise GearleverError(f"{name} must be an array of finite numbers, got {shown}")
    try:
        arr = np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError):
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


#: Largest speed (rad/s, or length/s) accepted where its square enters forces:
#: ``1e100**2`` times masses and lengths of ordinary size stays far from overflow.
MAX_SPEED = 1e100


def speed(name: str, value) -> np.ndarray:
    """Return ``value`` (a speed, scalar or array) as floats, refusing NaN, inf and sizes above :data:`MAX_SPEED`.

    Inertia forces grow with the square of the speed; a speed beyond the cap
    would give infinite forces (NaN after cancellation), passed off as a result.

    >>> float(speed("qdot", 10.0))
    10.0
    >>> speed("qdot", 1e200)
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: qdot must be at most 1e+100 in size (its square enters the forces), got 1e+200
    """
    arr = finite_array(name, value)
    if arr.size and float(np.max(np.abs(arr))) > MAX_SPEED:
        worst = float(arr.flat[int(np.argmax(np.abs(arr)))])
        raise GearleverError(
            f"{name} must be at most {MAX_SPEED:g} in size (its square enters the forces), got {worst:g}"
        )
    return arr
