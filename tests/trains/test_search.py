"""Tests of gearlever.trains.search: the exhaustive best search and its exact counts.

References: numpy brute force over every ordered tuple (small ranges), and
the published optimum of Sandgren's gear-train problem (Sandgren 1990, ASME
J. Mech. Des. 112: 223-229) read from its data file.
"""

import itertools
import math
from collections import Counter
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.trains import search as search_mod
from gearlever.trains.rules import sandgren_published
from gearlever.trains.search import (
    MAX_LIMIT,
    factorization_counts,
    search_best,
    search_space_size,
)

SANDGREN = Fraction(1000, 6931)  # 1/6.931


def _brute_force_k2(target: Fraction, lo: int, hi: int):
    """Every ordered (d1, d2, f1, f2) with the least |d1 d2 / (f1 f2) - target|, by numpy."""
    t = np.arange(lo, hi + 1, dtype=np.int64)
    p = np.multiply.outer(t, t)  # [d1, d2]
    err = np.abs(p[:, :, None, None] / p[None, None, :, :] - float(target))
    near = np.argwhere(err <= err.min() * (1 + 1e-9) + 1e-15)
    exact = [(abs(Fraction(int(p[a, b]), int(p[c, d])) - target), (a, b, c, d)) for a, b, c, d in near]
    best = min(e for e, _ in exact)
    tuples = {tuple(int(t[i]) for i in idx) for e, idx in exact if e == best}
    return best, tuples


def _brute_force_ordered(target: Fraction, k: int, lo: int, hi: int):
    """Least error and number of optimal ordered (d_1..d_k, f_1..f_k), over every tuple."""
    t = np.arange(lo, hi + 1, dtype=np.int64)
    p = t
    for _ in range(k - 1):
        p = np.multiply.outer(p, t)
    p = p.ravel()  # products of every ordered k-tuple
    err = np.abs(p[:, None] / p[None, :] - float(target))
    near = np.argwhere(err <= err.min() * (1 + 1e-9) + 1e-15)
    exact = [(abs(Fraction(int(p[i]), int(p[j])) - target), i, j) for i, j in near]
    best = min(e for e, _, _ in exact)
    return best, sum(1 for e, _, _ in exact if e == best)


def test_sandgren_search_agrees_with_brute_force_over_49_to_the_4():
    best, tuples = _brute_force_k2(SANDGREN, 12, 60)  # all 49**4 = 5,764,801 tuples
    res = search_best("1/6.931", 2, 12, 60)
    assert res.best_error == best
    assert tuples == {(16, 19, 43, 49), (19, 16, 43, 49), (16, 19, 49, 43), (19, 16, 49, 43)}
    assert res.n_ordered == len(tuples) == 4
    assert res.n_solutions == 1
    assert [(s.drivers, s.followers) for s in res.solutions] == [((16, 19), (43, 49))]


def test_sandgren_against_published_optimum():
    pub = sandgren_published()
    res = search_best(pub["target"], 2, pub["min_teeth"], pub["max_teeth"])
    # published to 7 significant digits: relative tolerance 1e-6
    assert float(res.best_error) ** 2 == pytest.approx(pub["best_squared_error"], rel=1e-6)
    td, tb, ta, tf = pub["teeth"]
    assert (tuple(sorted((td, tb))), tuple(sorted((ta, tf)))) == (
        res.solutions[0].drivers,
        res.solutions[0].followers,
    )


@settings(max_examples=15, deadline=None)
@given(st.integers(1, 500), st.integers(1, 500), st.integers(5, 20), st.integers(0, 14))
def test_search_k2_agrees_with_brute_force(p, q, lo, width):
    hi = lo + width
    target = Fraction(p, q)
    best, tuples = _brute_force_k2(target, lo, hi)
    res = search_best(target, 2, lo, hi, limit=None)  # None: list up to the cap (1000)
    assert res.best_error == best
    assert res.n_ordered == len(tuples)
    assert res.count == len({(tuple(sorted(t[:2])), tuple(sorted(t[2:]))) for t in tuples})
    listed = set()
    for s in res.solutions:
        assert abs(s.ratio - target) == best
        listed.add((s.drivers, s.followers))
    assert listed == {(tuple(sorted(t[:2])), tuple(sorted(t[2:]))) for t in tuples}


@pytest.mark.parametrize(
    "target, k, lo, hi",
    [
        (Fraction(1000, 6931), 3, 12, 24),  # 13**6 = 4.8 million ordered tuples
        (Fraction(355, 113), 3, 12, 24),
        (Fraction(1000, 6931), 4, 12, 18),  # 7**8 = 5.8 million
        (Fraction(7, 1), 4, 12, 18),
    ],
)
def test_search_k3_k4_agree_with_brute_force(target, k, lo, hi):
    best, count = _brute_force_ordered(target, k, lo, hi)
    res = search_best(target, k, lo, hi)
    assert res.best_error == best
    assert res.n_ordered == count


def test_search_lists_every_tie_on_both_sides():
    # teeth 12..13, one pair: ratios 12/13, 1, 13/12; 25/24 lies halfway between 1 and 13/12
    res = search_best("25/24", 1, 12, 13)
    assert res.best_ratios == (Fraction(1), Fraction(13, 12))
    assert res.best_error == Fraction(1, 24)
    assert {(s.drivers, s.followers) for s in res.solutions} == {
        ((12,), (12,)),
        ((13,), (13,)),
        ((13,), (12,)),
    }


def test_search_exact_hit_counts_every_set():
    res = search_best(2, 1, 12, 30)
    assert res.best_error == 0 and res.n_solutions == 4  # 24/12, 26/13, 28/14, 30/15
    limited = search_best(2, 1, 12, 30, limit=2)
    assert len(limited.solutions) == 2 and limited.n_solutions == 4


def test_relative_metric_same_optima_scaled_error():
    a = search_best("1/6.931", 3, 12, 60)
    r = search_best("1/6.931", 3, 12, 60, metric="relative")
    assert [(s.drivers, s.followers) for s in a.solutions] == [(s.drivers, s.followers) for s in r.solutions]
    assert r.best_error == a.best_error / SANDGREN


def test_search_space_pre_check():
    assert search_space_size(5, 12, 60) == math.comb(53, 5) == 2869685
    with pytest.raises(ValueError, match=r"^max_space: search space too large: 25,827,165"):
        search_best(2, 6, 12, 60)


@pytest.mark.parametrize(
    "args, kwargs, name",
    [
        (("nan", 2, 12, 60), {}, "ratio"),
        ((-1, 2, 12, 60), {}, "ratio"),
        ((0, 2, 12, 60), {}, "ratio"),
        ((2, 0, 12, 60), {}, "pairs"),
        ((2, 2, 61, 60), {}, "min_teeth"),
        ((2, 2, 12, 60), {"metric": "log"}, "metric"),
        ((2, 2, 0, 60), {}, "min_teeth"),
    ],
)
def test_search_bad_input(args, kwargs, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        search_best(*args, **kwargs)


# ----------------------------------------------------------------- exact counts


def _brute_counts(k, lo, hi):
    """Ordered and multiset counts of every product of k teeth in [lo, hi], by enumeration."""
    ordered = Counter(math.prod(t) for t in itertools.product(range(lo, hi + 1), repeat=k))
    sets = Counter(math.prod(t) for t in itertools.combinations_with_replacement(range(lo, hi + 1), k))
    return ordered, sets


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 5), st.integers(1, 30), st.integers(0, 9))
def test_factorization_counts_match_enumeration(k, lo, width):
    hi = lo + width
    ordered, sets = _brute_counts(k, lo, hi)
    values = sorted(set(ordered) | {lo**k - 1, hi**k + 1, 7919 * lo})  # some with no factorization
    assert factorization_counts(values, k, lo, hi).tolist() == [sets.get(v, 0) for v in values]
    assert factorization_counts(values, k, lo, hi, ordered=True).tolist() == [ordered.get(v, 0) for v in values]


def _brute_search_counts(target, k, lo, hi):
    """Least error and number of optimal (multiset, multiset) and ordered pairs, by enumeration."""
    ordered, sets = _brute_counts(k, lo, hi)
    err = {(p, q): abs(Fraction(p, q) - target) for p in ordered for q in ordered}
    best = min(err.values())
    opt = [pq for pq, e in err.items() if e == best]
    return best, sum(sets[p] * sets[q] for p, q in opt), sum(ordered[p] * ordered[q] for p, q in opt)


@pytest.mark.parametrize("recursive_max", [0, 10**9])  # 0: whole distributions (Polya); else recursion
@pytest.mark.parametrize(
    "target, k, lo, hi",
    [(Fraction(3), 3, 12, 20), (Fraction(1000, 6931), 3, 12, 19), (Fraction(1), 2, 5, 15), (Fraction(7, 2), 4, 6, 10)],
)
def test_search_counts_match_enumeration_by_both_methods(monkeypatch, recursive_max, target, k, lo, hi):
    monkeypatch.setattr(search_mod, "RECURSIVE_COUNT_MAX", recursive_max)
    best, n_sets, n_ordered = _brute_search_counts(target, k, lo, hi)
    res = search_best(target, k, lo, hi, limit=7)
    assert (res.best_error, res.count, res.n_ordered) == (best, n_sets, n_ordered)
    assert len(res.solutions) == min(7, n_sets)


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 60), st.integers(1, 60), st.integers(1, 3), st.integers(2, 12), st.integers(0, 6))
def test_search_matches_brute_force_on_small_ranges(p, q, k, lo, width):
    hi = lo + width
    target = Fraction(p, q)
    best, n_sets, n_ordered = _brute_search_counts(target, k, lo, hi)
    res = search_best(target, k, lo, hi, limit=None)
    assert (res.best_error, res.count, res.n_ordered) == (best, n_sets, n_ordered)
    listed = [(s.drivers, s.followers) for s in res.solutions]
    assert len(set(listed)) == len(listed) == min(n_sets, MAX_LIMIT)
    for s in res.solutions:
        assert abs(Fraction(math.prod(s.drivers), math.prod(s.followers)) - target) == best
        assert all(lo <= t <= hi for t in s.drivers + s.followers)


def test_search_limit_lists_the_first_sets_and_counts_all():
    full = search_best(3, 3, 12, 24, limit=None)
    first = search_best(3, 3, 12, 24, limit=5)
    assert first.count == full.count > 5 and first.n_ordered == full.n_ordered
    assert first.solutions == full.solutions[:5]
    assert not first.complete and full.complete == (full.count <= MAX_LIMIT)
    # smallest driver products first
    prods = [math.prod(s.drivers) for s in full.solutions]
    assert prods == sorted(prods)


def test_search_large_exact_case_counts_without_listing():
    # 3 with five pairs of 12..60 teeth: 78 million optimal sets, counted, 20 listed
    res = search_best(3, 5, 12, 60)
    assert len(res.solutions) == 20 and res.best_error == 0
    assert res.n_products == 427080 and res.n_candidates == 4 * res.n_products
    # the count is the sum over optimal product pairs (3m, m) of f(3m) f(m), f counted independently
    m = np.array([math.prod(s.followers) for s in res.solutions[:1]])
    assert factorization_counts(m, 5, 12, 60)[0] >= 1
    assert res.count == 78477517 and res.n_ordered == 845740940215


def test_search_as_dict_and_frame():
    res = search_best("1/6.931", 2, 12, 60)
    d = res.summary()
    assert d["count"] == d["n_solutions"] == 1 and d["listed"] == 1 and d["limit"] == 20
    frame = res.to_frame()
    assert list(frame["drivers"]) == ["16 19"] and list(frame["followers"]) == ["43 49"]


def test_search_reports_progress():
    calls = []
    search_best("1/6.931", 3, 12, 40, progress=lambda stage, done, total: calls.append((stage, done, total)))
    stages = [c[0] for c in calls]
    assert "products" in stages and "searching" in stages
    assert all(1 <= done <= total for _, done, total in calls)


@pytest.mark.parametrize(
    "args, kwargs, message",
    [
        ((2, 13, 12, 12), {}, "^pairs must be at most 12"),
        ((2, 1, 12, 10_001), {}, "^max_teeth must be at most 10,000"),
        ((2, 2, 12, 60), {"limit": MAX_LIMIT + 1}, "^limit must be at most 1,000"),
        ((2, 2, 12, 60), {"max_space": 20_000_001}, "^max_space must be at most 20,000,000"),
        ((2, 12, 30, 30), {}, "^max_teeth: products up to 30\\*\\*12"),
    ],
)
def test_search_caps_are_named(args, kwargs, message):
    with pytest.raises(ValueError, match=message):
        search_best(*args, **kwargs)
