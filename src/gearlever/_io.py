"""Atomic file output: write to a temporary file beside the target, then rename.

No caller of gearlever is ever left with a half-written file: either the old
file (or none) is there, or the complete new one.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import tempfile
from fractions import Fraction
from pathlib import Path

import numpy as np


@contextlib.contextmanager
def atomic_path(target, suffix: str | None = None):
    """Yield a temporary path in ``target``'s folder; rename it onto ``target`` on success.

    The folder is created if missing.  If the body raises, the temporary file
    is removed and ``target`` is left as it was.

    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "x.txt") as tmp:
    ...     _ = tmp.write_text("hi")
    >>> (d / "x.txt").read_text()
    'hi'
    """
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp_name = tempfile.mkstemp(
        prefix=f".{target.name}.",
        suffix=suffix if suffix is not None else ".tmp" + target.suffix,
        dir=target.parent,
    )
    os.close(fd)
    tmp = Path(tmp_name)
    try:
        yield tmp
        # mkstemp makes the file 0600; give it the mode a plain open() would.
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text_atomic(target, text: str) -> Path:
    """Write ``text`` (UTF-8, ``\\n`` line ends) to ``target`` atomically and return the path."""
    target = Path(target)
    with atomic_path(target) as tmp:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
    return target


def _strict(obj):
    """``obj`` with NaN and infinities as None, numpy values as Python ones, Fractions as "p/q"."""
    if isinstance(obj, dict):
        return {str(k): _strict(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_strict(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _strict(obj.tolist())
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        value = float(obj)
        return value if math.isfinite(value) else None
    if isinstance(obj, Fraction):
        return str(obj)
    return obj


def to_json(obj, indent: int | None = 2) -> str:
    """Strict JSON text of ``obj``: the one JSON writer of gearlever.

    Keys keep the order of the dicts given (insertion order); NaN and
    infinities become ``null`` (bare ``NaN`` is not JSON); numpy scalars and
    arrays become numbers and lists; a :class:`~fractions.Fraction` becomes
    the string ``"p/q"``.

    >>> to_json({"b": float("nan"), "a": [1.5, float("inf")]}, indent=None)
    '{"b": null, "a": [1.5, null]}'
    """
    return json.dumps(_strict(obj), indent=indent, allow_nan=False)
