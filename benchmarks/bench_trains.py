"""Benchmark of the exact best-train search (teeth 12-60, target 1/6.931, every optimum listed).

Prints, for K = 2..5 pairs, the best of a few runs of ``search_best`` (one process), the
optimum and every optimal tooth set; for K = 2 also the time of a vectorized numpy brute
force over all 49**4 ordered tuples, and the ratio of the two.

    .venv/bin/python benchmarks/bench_trains.py
"""

from __future__ import annotations

import time
from fractions import Fraction

import numpy as np

from gearlever.trains.synthesis import search_best

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


if __name__ == "__main__":
    main()
