"""Batched population search in a box: differential evolution and a CMA-ES for comparison.

Both take an objective that evaluates a whole population at once, ``f(Z)``
with ``Z`` of shape ``(n, d)`` returning ``(n,)`` (``inf`` for a candidate
that must be rejected), and a :class:`numpy.random.Generator` so that a run
is fixed by its seed.  Neither loops over candidates in Python.

Pure numpy.
"""

from __future__ import annotations

import threading

import numpy as np

__all__ = ["differential_evolution", "cma_es", "feasible_population", "STOP"]

#: Set to stop every running search at its next generation (Ctrl-C in the caller's thread).
STOP = threading.Event()


def feasible_population(sample, f, n: int, rng, max_rounds: int = 50, budget: int | None = None):
    """``n`` candidates drawn by ``sample(rng, m)`` whose objective is finite, and their values.

    Infeasible draws (``f = inf``) are rejected and drawn again (at most
    ``max_rounds`` rounds, and at most ``budget`` evaluations in all: the
    population is then smaller); the evaluations spent are returned too.
    """
    keep_z, keep_f, evals = [], [], 0
    have = 0
    for _ in range(max_rounds):
        m = max(2 * (n - have), 8)
        if budget is not None:
            m = min(m, budget - evals)
            if m <= 0:
                break
        Z = sample(rng, m)
        F = f(Z)
        evals += m
        ok = np.isfinite(F)
        keep_z.append(Z[ok])
        keep_f.append(F[ok])
        have += int(ok.sum())
        if have >= n:
            break
    if not keep_z:
        return np.zeros((0, 0)), np.zeros(0), evals
    Z = np.concatenate(keep_z)[:n]
    F = np.concatenate(keep_f)[:n]
    return Z, F, evals


def differential_evolution(f, lo, hi, rng, *, budget: int, pop: int, init=None, cr: float = 0.9):
    """Minimize ``f`` over the box ``[lo, hi]`` by DE/current-to-best/1/bin with dithered F.

    Parameters
    ----------
    f : callable
        Batched objective ``(n, d) -> (n,)``; ``inf`` rejects a candidate.
    lo, hi : ndarray (d,)
        Box bounds.
    rng : numpy.random.Generator
    budget : int
        Candidate evaluations at most, the initial population included (a
        cap: the search never evaluates more).
    pop : int
        Population size.
    init : callable, optional
        ``init(rng, m) -> (m, d)`` candidates for the initial population
        (default uniform in the box); infeasible ones are redrawn.
    cr : float
        Crossover probability.

    Returns
    -------
    (z_best, f_best, evaluations)

    Notes
    -----
    Storn and Price, "Differential evolution - a simple and efficient
    heuristic for global optimization over continuous spaces", J. Global
    Optimization 11 (1997) 341-359: the mutant of member ``i`` is
    ``x_i + F (x_best - x_i) + F (x_r1 - x_r2)``, binomial crossover with
    probability ``cr`` (one coordinate always from the mutant), greedy
    one-to-one selection.  ``F`` is drawn per generation in ``[0.5, 1]``
    (dither).  A mutant outside the box is reflected back inside; a trial
    whose objective is ``inf`` (an infeasible linkage) never replaces its
    parent, so the population stays feasible.
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    d = lo.size
    span = hi - lo

    def uniform(r, m):
        return lo + r.random((m, d)) * span

    X, F, evals = feasible_population(init or uniform, f, pop, rng, budget=budget)
    n = X.shape[0]
    if n < 4:
        i = int(np.argmin(F)) if n else 0
        return (X[i].copy(), float(F[i]), evals) if n else (None, np.inf, evals)
    idx = np.arange(n)
    while evals + n <= budget and not STOP.is_set():
        best = X[np.argmin(F)]
        r1 = rng.integers(0, n - 1, n)
        r1 += r1 >= idx
        r2 = rng.integers(0, n - 2, n)
        # r2 distinct from i and r1
        a, b = np.minimum(idx, r1), np.maximum(idx, r1)
        r2 += r2 >= a
        r2 += r2 >= b
        Fw = 0.5 + 0.5 * rng.random()
        V = X + Fw * (best - X) + Fw * (X[r1] - X[r2])
        # reflect into the box
        V = np.where(V < lo, 2 * lo - V, V)
        V = np.where(V > hi, 2 * hi - V, V)
        V = np.clip(V, lo, hi)
        cross = rng.random((n, d)) < cr
        cross[idx, rng.integers(0, d, n)] = True
        T = np.where(cross, V, X)
        FT = f(T)
        evals += n
        better = FT <= F
        X[better] = T[better]
        F[better] = FT[better]
    i = int(np.argmin(F))
    return X[i].copy(), float(F[i]), evals


def cma_es(f, lo, hi, rng, *, budget: int, pop: int, init=None):
    """Minimize ``f`` over the box ``[lo, hi]`` by a (mu/mu_w, lambda) CMA-ES (for comparison).

    The search runs in the unit cube (coordinates scaled by the box);
    candidates outside it are clipped, and ``inf`` values rank last.

    Notes
    -----
    N. Hansen, "The CMA evolution strategy: a tutorial", arXiv:1604.00772
    (2016), algorithm in its appendix A (default weights, cumulation and
    learning rates, no restarts).
    """
    lo = np.asarray(lo, dtype=float)
    hi = np.asarray(hi, dtype=float)
    d = lo.size
    span = hi - lo
    lam = pop
    mu = lam // 2
    w = np.log(mu + 0.5) - np.log(np.arange(1, mu + 1))
    w /= w.sum()
    mueff = 1.0 / np.sum(w**2)
    cc = (4 + mueff / d) / (d + 4 + 2 * mueff / d)
    cs = (mueff + 2) / (d + mueff + 5)
    c1 = 2 / ((d + 1.3) ** 2 + mueff)
    cmu = min(1 - c1, 2 * (mueff - 2 + 1 / mueff) / ((d + 2) ** 2 + mueff))
    damps = 1 + 2 * max(0.0, np.sqrt((mueff - 1) / (d + 1)) - 1) + cs
    chin = np.sqrt(d) * (1 - 1 / (4 * d) + 1 / (21 * d * d))

    def to_box(U):
        return lo + np.clip(U, 0.0, 1.0) * span

    if init is not None:
        X0, F0, evals = feasible_population(init, f, lam, rng, budget=budget)
        if X0.shape[0] == 0:
            return None, np.inf, evals
        m = (X0[np.argmin(F0)] - lo) / span
        best_z, best_f = X0[np.argmin(F0)].copy(), float(F0.min())
    else:
        m, evals, best_z, best_f = rng.random(d), 0, None, np.inf
    sigma = 0.3
    C = np.eye(d)
    pc = np.zeros(d)
    ps = np.zeros(d)
    B, D = np.eye(d), np.ones(d)
    gen = 0
    while evals + lam <= budget and not STOP.is_set():
        Y = rng.standard_normal((lam, d)) * D @ B.T
        U = m + sigma * Y
        Z = to_box(U)
        FZ = f(Z)
        evals += lam
        order = np.argsort(np.where(np.isfinite(FZ), FZ, np.inf), kind="stable")
        if FZ[order[0]] < best_f:
            best_f, best_z = float(FZ[order[0]]), Z[order[0]].copy()
        Ysel = Y[order[:mu]]
        yw = w @ Ysel
        m = m + sigma * yw
        invsqrtC = B @ np.diag(1 / D) @ B.T
        ps = (1 - cs) * ps + np.sqrt(cs * (2 - cs) * mueff) * invsqrtC @ yw
        gen += 1
        hsig = np.linalg.norm(ps) / np.sqrt(1 - (1 - cs) ** (2 * gen)) / chin < 1.4 + 2 / (d + 1)
        pc = (1 - cc) * pc + hsig * np.sqrt(cc * (2 - cc) * mueff) * yw
        C = (1 - c1 - cmu) * C + c1 * (np.outer(pc, pc) + (1 - hsig) * cc * (2 - cc) * C) + cmu * (Ysel.T * w) @ Ysel
        sigma *= np.exp((cs / damps) * (np.linalg.norm(ps) / chin - 1))
        sigma = min(sigma, 1.0)
        C = np.triu(C) + np.triu(C, 1).T
        ev, B = np.linalg.eigh(C)
        D = np.sqrt(np.maximum(ev, 1e-20))
    return best_z, best_f, evals
