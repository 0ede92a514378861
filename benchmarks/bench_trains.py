"""Benchmark of the exact best-train search.

Prints, in one process:

1. for K = 2..5 pairs, teeth 12-60, target 1/6.931, the best of a few runs of
   ``search_best``, the optimum and every optimal tooth set; for K = 2 also a vectorized
   numpy brute force over all 49**4 ordered tuples, and the ratio of the two times;
2. the two cases that used to take 37 s and minutes (target 3, K = 5, teeth 12-60; target
   3, K = 2, teeth 12-3000), counted exactly without listing; and, for target 3 with K = 3,
   teeth 12-60, the count against listing every optimal set by enumeration, with the ratio.

    .venv/bin/python benchmarks/bench_trains.py
"""

from __future__ import annotations

import time
from fractions import Fraction

import numpy as np

from gearlever.trains.design import factorizations
from gearlever.trains.search import search_best

TARGET = Fraction(1000, 6931)
LO, HI = 12, 60
TARGETS_S = {2: 0.05, 3: 0.05, 4: 0.5, 5: 10.0}


def best_time(fn, repeats):
    times, result = [], None
    for _ in range(repeats):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), times[0], result


def brute_force_k2():
    t = np.arange(LO, HI + 1, dtype=np.int64)
    p = np.multiply.outer(t, t)
    err = np.abs(p[:, :, None, None] / p[None, None, :, :] - float(TARGET))
    near = np.argwhere(err <= err.min() * (1 + 1e-9))
    exact = [(abs(Fraction(int(p[a, b]), int(p[c, d])) - TARGET), (a, b, c, d)) for a, b, c, d in near]
    best = min(e for e, _ in exact)
    return best, sorted(tuple(int(t[i]) for i in idx) for e, idx in exact if e == best)


def main() -> None:
    print(f"exact search, teeth {LO}-{HI}, target 1/6.931 = {float(TARGET):.12f}, every optimum listed")
    print(
        f"{'K':>2} {'best (s)':>9} {'first (s)':>9} {'target (s)':>10} {'products':>9} "
        f"{'abs error':>12} {'sets':>5} {'ordered':>8}"
    )
    k2_time = None
    for k in (2, 3, 4, 5):
        repeats = 5 if k < 5 else 3
        t_best, t_first, res = best_time(lambda k=k: search_best(TARGET, k, LO, HI), repeats)
        if k == 2:
            k2_time = t_best
        ok = "ok" if t_best < TARGETS_S[k] else "SLOW"
        print(
            f"{k:>2} {t_best:9.4f} {t_first:9.4f} {TARGETS_S[k]:>8.2f} {ok:>2} {res.n_products:>7} "
            f"{float(res.best_error):12.4e} {res.n_solutions:>5} {res.n_ordered:>8}"
        )
        for s in res.solutions:
            print(f"      drivers {s.drivers}  followers {s.followers}  ratio {s.ratio}")
    t_bf, _, (bf_best, bf_tuples) = best_time(brute_force_k2, 3)
    print(
        f"K=2 brute force over {(HI - LO + 1) ** 4:,} ordered tuples: {t_bf:.4f} s, "
        f"{len(bf_tuples)} optimal tuples, error {float(bf_best):.4e}"
    )
    print(f"K=2 brute force / exact search time ratio: {t_bf / k2_time:.0f}")

    print("target 3: optimal sets counted exactly, 20 listed")
    for k, lo, hi in ((5, 12, 60), (2, 12, 3000)):
        t, _, res = best_time(lambda k=k, lo=lo, hi=hi: search_best(3, k, lo, hi), 1)
        print(
            f"  K={k} teeth {lo}-{hi}: {t:.2f} s, {res.count:,} sets, {res.n_ordered:,} ordered tuples, "
            f"{res.n_products:,} products, {res.n_candidates:,} candidates"
        )
    t_count, _, res = best_time(lambda: search_best(3, 3, LO, HI), 3)
    t_enum, _, n_enum = best_time(lambda: enumerate_sets(3, LO, HI, res), 1)
    print(
        f"  K=3 teeth {LO}-{HI}: count {res.count:,} in {t_count:.3f} s; listing every set by "
        f"enumeration {n_enum:,} in {t_enum:.3f} s; ratio {t_enum / t_count:.0f}"
    )


def enumerate_sets(k, lo, hi, res):
    """Every optimal set of ``res`` listed by factorizing each optimal product pair (the old way)."""
    n = 0
    for r in res.best_ratios:
        p, q = r.numerator, r.denominator
        m = 1
        while q * m <= hi**k and p * m <= hi**k:
            fd = factorizations(p * m, k, lo, hi)
            if fd:
                fq = factorizations(q * m, k, lo, hi)
                n += sum(1 for _ in fd for _ in fq)
            m += 1
    return n


if __name__ == "__main__":
    main()
