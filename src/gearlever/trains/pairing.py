"""Pairing of drivers with followers for even wear, shared by the design and the exact search.

:func:`best_pairing` is the rule of the classic text on trains of wheelwork
(the greatest common divisor of each pair 1, or as small as it can be).  Both
:mod:`~gearlever.trains.design` and :mod:`~gearlever.trains.search` pair their
trains with it, so it lives below both.  Imports numpy, scipy (lazily) and
:mod:`gearlever.errors`.
"""

from __future__ import annotations

import itertools
import math

import numpy as np

from gearlever.errors import GearleverError

__all__ = ["best_pairing"]


def best_pairing(drivers, followers) -> tuple[tuple[int, int], ...]:
    """Pair each driver with a follower so that the teeth wear evenly.

    Parameters
    ----------
    drivers, followers : sequence of int
        Same length K.

    Returns
    -------
    tuple of (driver, follower)
        For K <= 6, the pairing with the least largest gcd, then the least
        sum of gcds, then the per-pair ratios closest to one another (all K!
        pairings tried).  For K > 6, an optimal assignment (scipy) for the
        cost sum(gcd**3), which puts the largest gcd first.

    Notes
    -----
    The classic text on trains of wheelwork, page marked (41) (referring to
    its section 44): the teeth wear evenly when the greatest common divisor of
    the two tooth numbers of each pair is 1, or else as small as it can be.

    Examples
    --------
    >>> best_pairing([30, 28], [15, 14])
    ((30, 14), (28, 15))
    """
    drivers = tuple(int(d) for d in drivers)
    followers = tuple(int(f) for f in followers)
    if len(drivers) != len(followers):
        raise GearleverError(f"followers must have as many entries as drivers ({len(drivers)}), got {len(followers)}")
    k = len(drivers)
    g = [[math.gcd(d, f) for f in followers] for d in drivers]
    if k > 6:
        from scipy.optimize import linear_sum_assignment

        rows, cols = linear_sum_assignment(np.array(g, dtype=float) ** 3)
        return tuple((drivers[r], followers[c]) for r, c in zip(rows, cols))
    lg = [[math.log(d / f) for f in followers] for d in drivers]
    best_key, best = None, None
    for perm in itertools.permutations(range(k)):
        gcds = [g[i][j] for i, j in enumerate(perm)]
        logs = [lg[i][j] for i, j in enumerate(perm)]
        key = (max(gcds), sum(gcds), max(logs) - min(logs), tuple(followers[j] for j in perm))
        if best_key is None or key < best_key:
            best_key, best = key, key[3]
    return tuple(zip(drivers, best))
