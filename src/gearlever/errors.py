"""The one error family of gearlever.

Every refusal of bad input raises :class:`GearleverError`, a :class:`ValueError`
whose message names the parameter (or file element) and what it must be.  A
loop that cannot close at a requested input raises :class:`ClosureError`.
Input that is accepted but probably not what was meant (degrees where
radians are expected) gives a :class:`GearleverWarning`.
The command line turns both, and any :class:`OSError`, into exit status 2 and
one line on stderr.

Imports nothing from the rest of the package.

>>> from gearlever.errors import GearleverError
>>> issubclass(GearleverError, ValueError)
True
"""

from __future__ import annotations

__all__ = ["ClosureError", "GearleverError", "GearleverWarning"]


class GearleverError(ValueError):
    """Bad input: a value, file or element gearlever cannot model.

    The message names the parameter and what it must be, e.g.
    ``"teeth must be a positive integer, got -3"``.

    Examples
    --------
    >>> import gearlever
    >>> try:
    ...     gearlever.mobility(-1, 0, 0)
    ... except gearlever.GearleverError as exc:
    ...     print(exc)
    n must be a non-negative integer, got -1
    >>> issubclass(gearlever.GearleverError, ValueError)
    True
    """


class ClosureError(GearleverError):
    """A vector loop or mechanism cannot be closed at the requested input.

    Examples
    --------
    A four-bar (ground 9, crank 5, coupler 3, rocker 3) that assembles at a
    crank angle of 0 but not at 3 rad, solved strictly:

    >>> import gearlever
    >>> try:
    ...     gearlever.fourbar(9, 5, 3, 3, [0.0, 3.0], strict=True)
    ... except gearlever.ClosureError as exc:
    ...     print(type(exc).__name__, isinstance(exc, gearlever.GearleverError))
    ClosureError True
    """


def a(word: str) -> str:
    """``word`` with its indefinite article, for messages: ``an oscillating-roller``, ``a translating-flat``.

    >>> a("oscillating-roller"), a("displacement"), a("angle")
    ('an oscillating-roller', 'a displacement', 'an angle')
    """
    word = str(word)
    return f"{'an' if word[:1].lower() in 'aeio' else 'a'} {word}"


class GearleverWarning(UserWarning):
    """Input accepted but probably not meant, e.g. angles that look like degrees where radians are expected.

    Examples
    --------
    >>> import warnings
    >>> issubclass(GearleverWarning, UserWarning)
    True
    """
