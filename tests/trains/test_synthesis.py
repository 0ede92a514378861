"""Tests of gearlever.trains.synthesis: the text's rules, continued fractions and the exact search."""

import math
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.trains.synthesis import (
    approximants,
    best_pairing,
    continued_fraction,
    convergents,
    design_train,
    exact_trains,
    factorizations,
    min_teeth_for_form,
    neighbours,
    pair_count_bounds,
    parse_ratio,
    rules,
    sandgren_published,
    search_best,
    search_space_size,
)

SANDGREN = Fraction(1000, 6931)  # 1/6.931


# ----------------------------------------------------------------- brute force references


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


# ----------------------------------------------------------------- ratios and rules


@pytest.mark.parametrize(
    "value, expected",
    [
        ("1/6.931", Fraction(1000, 6931)),
        ("355/113", Fraction(355, 113)),
        (3.59, Fraction(359, 100)),
        (12, Fraction(12)),
        (Fraction(3, 4), Fraction(3, 4)),
        ("0.25", Fraction(1, 4)),
    ],
)
def test_parse_ratio(value, expected):
    assert parse_ratio(value) == expected


@pytest.mark.parametrize(
    "value",
    [0, -1, "-2/3", "nan", float("nan"), float("inf"), "1/0", "abc", True, None, "0/5", "1e400", "1/1e400"],
)
def test_parse_ratio_rejects(value):
    with pytest.raises(ValueError, match="^ratio must be"):
        parse_ratio(value)


def test_rules_from_data_file():
    r = rules()
    assert r["young_pair_ratio"] == 3.59
    assert (r["practical_pair_ratio_min"], r["practical_pair_ratio_max"]) == (3, 6)
    assert [min_teeth_for_form(f) for f in ("epicycloidal", "smooth", "involute")] == [12, 15, 24]
    with pytest.raises(ValueError, match="^tooth_form"):
        min_teeth_for_form("cycloid")


def test_pair_count_bounds_by_hand():
    b = pair_count_bounds(100)  # log 100 / log 6 = 2.570, log 100 / log 3 = 4.192
    assert b.lower == pytest.approx(2.5701, abs=1e-4)
    assert b.upper == pytest.approx(4.1918, abs=1e-4)
    assert b.young == pytest.approx(math.log(100) / math.log(3.59))
    assert b.candidates == (3, 4)
    assert pair_count_bounds(7).candidates == (2,)  # 1.086 .. 1.771: no whole number, next above
    assert pair_count_bounds(Fraction(1, 2)).candidates == (1,)
    assert pair_count_bounds("1/100").candidates == (3, 4)  # symmetric in B and C


# ----------------------------------------------------------------- factors


def test_factorizations_by_hand():
    assert factorizations(2107, 2, 12, 60) == [(43, 49)]  # 2107 = 7^2 * 43
    assert factorizations(304, 2, 12, 60) == [(16, 19)]  # 304 = 2^4 * 19
    assert factorizations(6931, 2, 12, 60) == []  # 6931 = 29 * 239, 239 prime
    assert factorizations(1728, 2, 12, 72) == [(24, 72), (27, 64), (32, 54), (36, 48)]
    assert factorizations(60, 3, 3, 5) == [(3, 4, 5)]


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 5000), st.integers(1, 3), st.integers(2, 20), st.integers(0, 40))
def test_factorizations_are_complete_and_correct(n, k, lo, width):
    hi = lo + width
    got = factorizations(n, k, lo, hi)
    assert all(math.prod(f) == n and all(lo <= x <= hi for x in f) and list(f) == sorted(f) for f in got)
    assert len(set(got)) == len(got)
    # independent count by brute force over non-decreasing tuples
    import itertools

    ref = [c for c in itertools.combinations_with_replacement(range(lo, hi + 1), k) if math.prod(c) == n]
    assert sorted(got) == sorted(ref)


def test_best_pairing_least_gcd():
    assert best_pairing([30, 28], [15, 14]) == ((30, 14), (28, 15))
    with pytest.raises(ValueError, match="^followers"):
        best_pairing([1, 2], [3])


# ----------------------------------------------------------------- continued fractions


def test_continued_fraction_of_pi_approximation():
    assert continued_fraction("355/113") == [3, 7, 16]
    assert convergents("355/113") == [Fraction(3), Fraction(22, 7), Fraction(355, 113)]
    fr = [a.fraction for a in approximants("355/113")]
    # a1 = 7: (1 + 3j)/j for j = 1..6 then 22/7; a2 = 16: (3 + 22j)/(1 + 7j), j = 1..15, then 355/113
    assert fr[:7] == [
        Fraction(3),
        Fraction(4),
        Fraction(7, 2),
        Fraction(10, 3),
        Fraction(13, 4),
        Fraction(16, 5),
        Fraction(19, 6),
    ]
    assert fr[8] == Fraction(25, 8) and fr[-2] == Fraction(333, 106) and fr[-1] == Fraction(355, 113)


def test_sandgren_target_continued_fraction():
    # 1000/6931 = [0; 6, 1, 13, 2, 34]; convergents 1/6, 1/7, 14/97, 29/201, 1000/6931
    assert continued_fraction(SANDGREN) == [0, 6, 1, 13, 2, 34]
    assert convergents(SANDGREN) == [  # 0/1 (a0 = 0) is left out
        Fraction(1, 6),
        Fraction(1, 7),
        Fraction(14, 97),
        Fraction(29, 201),
        SANDGREN,
    ]
    semi = [a for a in approximants(SANDGREN) if a.fraction == Fraction(304, 2107)]
    # 304 = 14 + 10*29, 2107 = 97 + 10*201: the 10th semiconvergent before the last convergent
    assert len(semi) == 1 and semi[0].kind == "semiconvergent" and semi[0].multiple == 10
    assert semi[0].error == Fraction(304, 2107) - SANDGREN


@settings(max_examples=50, deadline=None)
@given(st.integers(1, 10**6), st.integers(1, 10**6))
def test_convergents_bound(p, q):
    x = Fraction(p, q)
    conv = convergents(x)
    assert conv[-1] == x
    for c in conv[:-1]:
        assert abs(x - c) < Fraction(1, c.denominator**2)


# ----------------------------------------------------------------- the text's design rules


def test_exact_trains_hand_case():
    designs = exact_trains(12, 2, 12, 72)
    # lambda = 144: 12*144 = 1728 = 36*48 (least teeth), 144 = 12*12
    assert (designs[0].drivers, designs[0].followers, designs[0].multiplier) == ((36, 48), (12, 12), 144)
    assert designs[0].total_teeth == 108
    assert all(d.ratio == 12 and d.error == 0.0 for d in designs)
    assert all(12 <= x <= 72 for d in designs for x in d.drivers + d.followers)


def test_design_exact_ratio_within_pair_bounds():
    res = design_train(100)  # involute: t = 24, T = 144
    assert (res.method, res.min_teeth, res.max_teeth) == ("exact", 24, 144)
    d = res.designs[0]
    assert len(d.drivers) == 3 and d.ratio == 100
    wear = design_train(100, prefer="wear")
    assert all(g == 1 for g in wear.designs[0].gcds) and wear.designs[0].shared_divisor_pairs == ()
    assert d.shared_divisor_pairs == tuple(i + 1 for i, g in enumerate(d.gcds) if g > 1)


def test_design_pi_by_continued_fraction():
    res = design_train("355/113", tooth_form="epicycloidal")  # 113 prime > 72: awkward
    assert res.method == "continued fraction" and res.approximation == Fraction(22, 7)
    d = res.designs[0]
    assert (d.drivers, d.followers) == ((44,), (14,))
    assert d.ratio - res.target == Fraction(1, 791)  # 22/7 - 355/113 = (2486 - 2485) / 791
    # the exact search over one pair in [12, 72] agrees
    best = search_best("355/113", 1, 12, 72)
    assert best.best_ratios == (Fraction(22, 7),)


def test_design_sandgren_rules_reach_the_proven_optimum():
    res = design_train("1/6.931", min_teeth=12, max_teeth=60)
    assert res.method == "continued fraction" and res.approximation == Fraction(304, 2107)
    d = res.designs[0]
    assert (d.drivers, d.followers, d.gcds) == ((16, 19), (43, 49), (1, 1))
    best = search_best("1/6.931", 2, 12, 60)
    assert best.best_ratios == (d.ratio,)


def test_design_impossible_raises():
    with pytest.raises(ValueError, match="^ratio .* use search_best"):
        design_train(1000, min_teeth=12, max_teeth=13, pairs=1)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(ratio=0), "ratio"),
        (dict(ratio=2, min_teeth=30, max_teeth=20), "min_teeth"),
        (dict(ratio=2, pairs=0), "pairs"),
        (dict(ratio=2, tooth_form="x"), "tooth_form"),
        (dict(ratio=2, prefer="cost"), "prefer"),
    ],
)
def test_design_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=f"^{name}"):
        design_train(**kwargs)


# ----------------------------------------------------------------- exact best search


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
    res = search_best(target, 2, lo, hi)
    assert res.best_error == best
    assert res.n_ordered == len(tuples)
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
    with pytest.raises(ValueError, match=r"^pairs: search space too large: 25,827,165"):
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


def test_approximants_stop_at_max_term():
    fr = [a.fraction for a in approximants(SANDGREN, max_term=300)]
    assert fr[-2:] == [Fraction(29, 201), Fraction(43, 298)]  # next, 72/499, exceeds 300
    assert all(max(f.numerator, f.denominator) <= 300 for f in fr)


def test_exact_trains_awkward_prime_gives_nothing():
    assert exact_trains(SANDGREN, 2, 12, 60) == []  # 239 | 6931 and 239 > 60
    assert exact_trains(Fraction(239, 2), 3, 12, 200) == []
    assert exact_trains(Fraction(239, 2), 2, 12, 240)[0].ratio == Fraction(239, 2)


def test_design_with_huge_partial_quotient():
    # 123456789/987654321 = [0; 8, 13717421]: the long run of semiconvergents is cut at 144**2
    res = design_train("123456789/987654321")
    assert res.method == "continued fraction" and res.approximation == Fraction(1, 8)
    assert res.designs[0].ratio == Fraction(1, 8)


def test_neighbours_of_whole_number_and_fraction():
    assert [a.fraction for a in neighbours(9488, count=2)] == [
        Fraction(9489),
        Fraction(18977, 2),
        Fraction(9487),
        Fraction(18975, 2),
    ]
    # 355/113 = [3; 7, 16], previous convergent 22/7: (22 + 355j)/(7 + 113j) and (355j - 22)/(113j - 7)
    nb = neighbours("355/113", count=1)
    assert [a.fraction for a in nb] == [Fraction(377, 120), Fraction(333, 106)]
    assert all(abs(a.error) == Fraction(1, 113 * (7 + 113)) or abs(a.error) == Fraction(1, 113 * 106) for a in nb)


def test_design_whole_number_with_awkward_prime_uses_neighbours():
    res = design_train(593, tooth_form="epicycloidal")  # 593 is prime, > 72
    assert res.method == "continued fraction" and res.tried[-1][0].kind == "neighbour"
    d = res.designs[0]
    assert d.ratio == res.approximation != 593 and all(12 <= x <= 72 for x in d.drivers + d.followers)
    assert abs(d.ratio - 593) < Fraction(1, 20)
