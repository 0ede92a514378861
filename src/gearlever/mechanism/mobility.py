"""Structural analysis: mobility of a planar mechanism with redundant constraints.

Pure integer arithmetic; no numpy needed.
"""

from __future__ import annotations

from gearlever._validate import nonnegative_int
from gearlever.errors import GearleverError


def mobility(n, p5, p4, q=0):
    """Degree of mobility ``W`` of a planar mechanism.

    Parameters
    ----------
    n : int
        Number of moving links (>= 0).
    p5 : int
        Lower pairs, class 5 (revolute, prismatic) (>= 0).
    p4 : int
        Higher pairs, class 4 (gear meshes, cams) (>= 0).
    q : int, optional
        Redundant (excess) constraints (>= 0).

    Returns
    -------
    int
        ``W = 3 n - 2 p5 - p4 + q``.

    Notes
    -----
    Paper eq. 1 (the planar Chebyshev-Grubler formula with excess
    constraints).

    Examples
    --------
    >>> mobility(9, 12, 3, q=2)
    2
    """
    n = nonnegative_int("n", n)
    p5 = nonnegative_int("p5", p5)
    p4 = nonnegative_int("p4", p4)
    q = nonnegative_int("q", q)
    return 3 * n - 2 * p5 - p4 + q


def redundant_constraints(n, p5, p4, w):
    """Number of redundant constraints ``q`` for a known mobility ``W``.

    Parameters
    ----------
    n, p5, p4 : int
        As in :func:`mobility`.
    w : int
        The mechanism's actual degree of mobility (>= 0).

    Returns
    -------
    int
        ``q = W - 3 n + 2 p5 + p4`` (never negative).

    Notes
    -----
    Paper eq. 1 solved for ``q``; the paper does this for the linkage part
    (``n = 5, P5 = 8, P4 = 0, W = 1`` gives ``q = 2``).

    Examples
    --------
    >>> redundant_constraints(5, 8, 0, w=1)
    2
    """
    n = nonnegative_int("n", n)
    p5 = nonnegative_int("p5", p5)
    p4 = nonnegative_int("p4", p4)
    w = nonnegative_int("w", w)
    q = w - 3 * n + 2 * p5 + p4
    if q < 0:
        raise GearleverError(
            f"w must be at least 3n - 2p5 - p4 = {3 * n - 2 * p5 - p4} for these counts (q would be {q}), got {w}"
        )
    return q


def published_mobility_cases():
    """The paper's three mobility cases, read from the package data file.

    Returns
    -------
    list of dict
        Keys ``case`` (str), ``n``, ``p5``, ``p4``, ``q``, ``w`` (int), as
        published.

    Notes
    -----
    Data file ``zrdpm_mobility.csv`` (source and page in its header).

    Examples
    --------
    >>> [c["w"] for c in published_mobility_cases()]
    [1, 2, 2]
    """
    from gearlever.data import read_records

    rows = []
    for rec in read_records("zrdpm_mobility.csv"):
        rows.append({"case": rec["case"], **{k: int(rec[k]) for k in ("n", "p5", "p4", "q", "w")}})
    return rows
