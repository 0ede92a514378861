"""Target curves: read a ``TARGET.csv`` of ``x,y`` rows and refuse what is not a usable closed curve.

>>> import numpy as np
>>> t = np.linspace(0, 2 * np.pi, 50)
>>> check_target(np.stack([np.cos(t), np.sin(t)], -1)).shape
(50, 2)
"""

from __future__ import annotations

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism.linkage import MAX_COORDINATE

__all__ = ["MAX_TARGET_ROWS", "MIN_DISTINCT", "SUITE_RMS", "check_target", "known_mechanism", "read_target"]

#: Most rows of a target file.
MAX_TARGET_ROWS = 100_000
#: Fewest distinct points of a target.
MIN_DISTINCT = 10
#: RMS radius of the suite's curves: that of the MIT 2.156 challenge's six targets (material is absolute).
SUITE_RMS = 0.191


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
    if np.abs(a).max() > MAX_COORDINATE:
        bad = int(np.flatnonzero(np.abs(a).max(1) > MAX_COORDINATE)[0])
        raise GearleverError(
            f"{what}: row {bad + 1} has a coordinate larger than {MAX_COORDINATE:g} in size "
            "(the distances of the score would overflow or lose every digit): scale the curve down"
        )
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
    from gearlever._io import read_csv_table

    table = read_csv_table(path, what, header=None, comments=True)
    where = table.where
    if not table.rows:
        raise GearleverError(f"{where}: no x,y rows")
    if len(table.rows) > MAX_TARGET_ROWS:
        raise GearleverError(f"{where}: more than {MAX_TARGET_ROWS} rows (the cap)")
    table = table.only(("x", "y"), 2)  # the package's one rule for a user's CSV: no column dropped silently
    cols = (table.header.index("x"), table.header.index("y"))
    xy = np.array([[table.number(k, cols[0], "x"), table.number(k, cols[1], "y")] for k in range(len(table))])
    return check_target(xy, where)


def known_mechanism(n_dyads: int, seed: int, rms: float = SUITE_RMS):
    """A random dyadic linkage that turns fully and is feasible, and the curve its traced joint draws.

    The suite's exact-recovery targets: the first of the random sketches of
    the first random topology (``n_dyads`` dyads on a crank, two ground
    pivots) that turns over a whole crank turn and whose material, once the
    linkage is scaled so that its curve has RMS radius ``rms``, is below the
    challenge's 10 (a design of more material is off the front, so it could
    not be recovered there).

    Parameters
    ----------
    n_dyads : int
        Dyads beyond the crank (the linkage has ``n_dyads + 3`` joints).
    seed : int
        Seed of the draws.
    rms : float
        RMS radius of the curve.

    Returns
    -------
    topology : gearlever.synthesis.curve.topology.Topology
    x0 : ndarray, shape (N, 2)
        The sketch.
    curve : ndarray, shape (200, 2)
        The traced joint's positions over a crank turn.

    Notes
    -----
    Draws of :func:`gearlever.synthesis.curve.topology.random_topology` and
    :func:`~gearlever.synthesis.curve.topology.random_sketches` from
    ``numpy.random.default_rng(seed)``; the challenge's material and bound
    as :mod:`gearlever.synthesis.curve.score`.

    Examples
    --------
    >>> topo, x0, curve = known_mechanism(6, 12)
    >>> topo.n, curve.shape
    (9, (200, 2))
    """
    from gearlever.synthesis.curve.score import MAX_MATERIAL, material
    from gearlever.synthesis.curve.simulate import simulate
    from gearlever.synthesis.curve.topology import random_sketches, random_topology

    rng = np.random.default_rng(seed)
    while True:
        topo = random_topology(rng, int(n_dyads), 2)
        x0 = random_sketches(rng, topo, 400)
        x = simulate(x0, topo.plan)
        ok = np.isfinite(x).all(axis=(1, 2, 3))
        c = x[:, topo.target]
        size = np.sqrt(((c - c.mean(1, keepdims=True)) ** 2).sum(-1).mean(1))
        with np.errstate(invalid="ignore", divide="ignore"):
            ok &= material(x0, topo.edges) * (rms / size) < MAX_MATERIAL
        if ok.any():
            i = int(np.flatnonzero(ok)[0])
            x = x0[i] * (rms / size[i])
            return topo, x, simulate(x[None], topo.plan)[0, topo.target]
