"""A safe expression of one variable ``x``: parsed by :mod:`ast`, evaluated over numpy arrays, never by ``eval``.

Accepted: numbers, the name ``x``, the constants ``pi`` and ``e``, the
operators ``+ - * / **``, unary minus and plus, parentheses, and calls of one
argument to the functions in :data:`FUNCTIONS`.  Anything else (attributes,
other names, subscripts, keyword arguments, comparisons, strings, lambdas...)
is refused with a :class:`~gearlever.errors.GearleverError` naming the
expression.  Pure numpy.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Callable

import numpy as np

from gearlever.errors import GearleverError

__all__ = ["FUNCTIONS", "MAX_EXPRESSION_CHARS", "parse_expression"]

#: The whitelist of functions an expression may call (one argument each).
FUNCTIONS: dict[str, Callable] = {
    "sin": np.sin,
    "cos": np.cos,
    "tan": np.tan,
    "arcsin": np.arcsin,
    "arccos": np.arccos,
    "arctan": np.arctan,
    "asin": np.arcsin,
    "acos": np.arccos,
    "atan": np.arctan,
    "sinh": np.sinh,
    "cosh": np.cosh,
    "tanh": np.tanh,
    "exp": np.exp,
    "log": np.log,
    "ln": np.log,
    "log10": np.log10,
    "log2": np.log2,
    "sqrt": np.sqrt,
    "cbrt": np.cbrt,
    "abs": np.abs,
}
_CONSTANTS = {"pi": math.pi, "e": math.e}
_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply, ast.Div: np.divide, ast.Pow: np.power}
_UNARY = {ast.USub: np.negative, ast.UAdd: np.positive}
#: Longest expression accepted (characters).
MAX_EXPRESSION_CHARS = 500
_MAX_DEPTH = 60
#: Characters of a refused expression shown in its message.
_SHOWN_CHARS = 60


def shown(text: str) -> str:
    """``text`` cut to :data:`_SHOWN_CHARS` characters for a message (with ``...`` when cut)."""
    return text if len(text) <= _SHOWN_CHARS else text[: _SHOWN_CHARS - 3] + "..."


def _refuse(text: str, why: str) -> GearleverError:
    return GearleverError(f"expression {shown(text)!r}: {why}")


def _compile(node, text: str, depth: int = 0) -> Callable:
    if depth > _MAX_DEPTH:
        raise _refuse(text, f"nested deeper than {_MAX_DEPTH} levels")
    if isinstance(node, ast.Constant):
        v = node.value
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            raise _refuse(text, f"only numbers are allowed as constants, not {v!r:.40}")
        try:
            value = float(v)
        except OverflowError:
            digits = len(str(v))
            raise _refuse(
                text, f"a number of {digits} digits is too large (numbers must be finite floats, below 1.8e308)"
            ) from None
        if not math.isfinite(value):
            raise _refuse(text, "a number is beyond 1.8e308, infinite as a float (numbers must be finite)")
        return lambda x: value
    if isinstance(node, ast.Name):
        if node.id == "x":
            return lambda x: x
        if node.id in _CONSTANTS:
            value = _CONSTANTS[node.id]
            return lambda x: value
        raise _refuse(text, f"unknown name {node.id!r} (the variable is x; constants pi and e)")
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        op = _BINARY[type(node.op)]
        left, right = _compile(node.left, text, depth + 1), _compile(node.right, text, depth + 1)
        return lambda x: op(left(x), right(x))
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        op = _UNARY[type(node.op)]
        arg = _compile(node.operand, text, depth + 1)
        return lambda x: op(arg(x))
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            name = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
            raise _refuse(text, f"function {name!r} is not allowed (allowed: {', '.join(sorted(FUNCTIONS))})")
        if node.keywords or len(node.args) != 1:
            raise _refuse(text, f"{node.func.id}() takes exactly one argument and no keywords")
        fn = FUNCTIONS[node.func.id]
        arg = _compile(node.args[0], text, depth + 1)
        return lambda x: fn(arg(x))
    raise _refuse(text, f"{type(node).__name__} is not allowed ({ast.unparse(node)!r})")


def parse_expression(text: str) -> Callable[[np.ndarray], np.ndarray]:
    """Compile a formula in ``x`` to a function of a numpy array, refusing anything unsafe.

    Parameters
    ----------
    text : str
        The formula, e.g. ``"log10(x)"`` or ``"x**2 - 3*sin(pi*x)"``.

    Returns
    -------
    callable
        ``f(x)`` for an array ``x`` (float64); values where the formula is
        undefined are NaN or inf (numpy's rules), to be checked by the caller.

    Notes
    -----
    The text is parsed by Python's own grammar (:func:`ast.parse`, mode
    ``"eval"``) and the tree is walked node by node into numpy calls; only
    the node types named in the module docstring are accepted, so no Python
    code can run.  ``^`` is not a power (it is refused, as in Python it is a
    bitwise xor): write ``**``.

    Examples
    --------
    >>> f = parse_expression("log10(x)")
    >>> [round(float(v), 6) for v in f(np.array([1.0, 10.0, 2.0]))]
    [0.0, 1.0, 0.30103]
    >>> parse_expression("__import__('os')")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: expression "__import__('os')": function '__import__' is not allowed (allowed: ...
    """
    if not isinstance(text, str):
        raise GearleverError(f"expression must be text, got {type(text).__name__}")
    if not text.strip():
        raise GearleverError("expression must not be empty")
    if len(text) > MAX_EXPRESSION_CHARS:
        raise _refuse(text, f"longer than {MAX_EXPRESSION_CHARS} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise _refuse(text, f"not a formula ({exc.msg})") from None
    fn = _compile(tree.body, text)

    def f(x):
        x = np.asarray(x, dtype=float)
        with np.errstate(all="ignore"):
            return np.broadcast_to(np.asarray(fn(x), dtype=float), x.shape).copy()

    return f
