"""Target curves: read a ``TARGET.csv`` of ``x,y`` rows and refuse what is not a usable closed curve.

>>> import numpy as np
>>> t = np.linspace(0, 2 * np.pi, 50)
>>> check_target(np.stack([np.cos(t), np.sin(t)], -1)).shape
(50, 2)
"""

from __future__ import annotations

import csv
import io

import numpy as np

from gearlever.errors import GearleverError

__all__ = ["MAX_TARGET_ROWS", "MIN_DISTINCT", "check_target", "read_target"]

#: Most rows of a target file.
MAX_TARGET_ROWS = 100_000
#: Fewest distinct points of a target.
MIN_DISTINCT = 10


def check_target(xy, what: str = "target") -> np.ndarray:
    """Refuse a target that is not a curve with length and area: NaN, fewer than 10 distinct points, a segment.

    Examples
    --------
    >>> check_target([[0, 0]] * 20)
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: target: 1 distinct point(s); a curve needs at least 10
    """
    a = np.asarray(xy, dtype=float)
    if a.ndim != 2 or a.shape[1] != 2:
        raise GearleverError(f"{what}: must be rows of x, y, got shape {a.shape}")
    if not np.isfinite(a).all():
        bad = int(np.flatnonzero(~np.isfinite(a).all(1))[0])
        raise GearleverError(f"{what}: row {bad + 1} is not finite (x, y must be numbers)")
    n = len(np.unique(a, axis=0))
    if n < MIN_DISTINCT:
        raise GearleverError(f"{what}: {n} distinct point(s); a curve needs at least {MIN_DISTINCT}")
    c = a - a.mean(0)
    sv = np.linalg.svd(c, compute_uv=False)
    if sv[-1] <= 1e-9 * sv[0]:
        raise GearleverError(f"{what}: the points lie on a line (zero area); a closed curve is needed")
    return a


def read_target(path, what: str = "TARGET") -> np.ndarray:
    """Rows ``x,y`` of a CSV file (optional header naming x and y; ``#`` lines skipped), checked."""
    from gearlever._io import read_text_capped

    text = read_text_capped(path, what)
    where = f"{what} {str(path)!r}"
    rows = [r for r in csv.reader(io.StringIO(text)) if any(c.strip() for c in r) and not r[0].lstrip().startswith("#")]
    if not rows:
        raise GearleverError(f"{where}: no x,y rows")
    cols, start = (0, 1), 1
    try:
        float(rows[0][0])
    except ValueError:
        header = [c.strip().lower() for c in rows[0]]
        if "x" not in header or "y" not in header:
            raise GearleverError(f"{where}: the header must name columns x and y, got {rows[0]}") from None
        cols, start, rows = (header.index("x"), header.index("y")), 2, rows[1:]
    if len(rows) > MAX_TARGET_ROWS:
        raise GearleverError(f"{where}: more than {MAX_TARGET_ROWS} rows (the cap)")
    xy = np.empty((len(rows), 2))
    for n, r in enumerate(rows):
        try:
            xy[n] = [float(r[cols[0]]), float(r[cols[1]])]
        except (ValueError, IndexError):
            raise GearleverError(f"{where}: line {n + start}: x and y must be numbers, got {r}") from None
    return check_target(xy, where)
