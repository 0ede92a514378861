"""Tests of gearlever.trains.design: tooth numbers by the rules of the classic text on trains of wheelwork."""

import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.trains.design import (
    MAX_DESIGN_STEPS,
    best_pairing,
    design_train,
    exact_trains,
    factorizations,
)
from gearlever.trains.search import search_best

SANDGREN = Fraction(1000, 6931)  # 1/6.931


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


def test_exact_trains_awkward_prime_gives_nothing():
    assert exact_trains(SANDGREN, 2, 12, 60) == []  # 239 | 6931 and 239 > 60
    assert exact_trains(Fraction(239, 2), 3, 12, 200) == []
    assert exact_trains(Fraction(239, 2), 2, 12, 240)[0].ratio == Fraction(239, 2)


def test_design_with_huge_partial_quotient():
    # 123456789/987654321 = [0; 8, 13717421]: the long run of semiconvergents is cut at 144**2
    res = design_train("123456789/987654321")
    assert res.method == "continued fraction" and res.approximation == Fraction(1, 8)
    assert res.designs[0].ratio == Fraction(1, 8)


def test_design_whole_number_with_awkward_prime_uses_neighbours():
    res = design_train(593, tooth_form="epicycloidal")  # 593 is prime, > 72
    assert res.method == "continued fraction" and res.tried[-1][0].kind == "neighbour"
    d = res.designs[0]
    assert d.ratio == res.approximation != 593 and all(12 <= x <= 72 for x in d.drivers + d.followers)
    assert abs(d.ratio - 593) < Fraction(1, 20)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(ratio=2, pairs=13), "^pairs must be at most 12"),
        (dict(ratio=2, min_teeth=12, max_teeth=10_001), "^max_teeth must be at most 10,000"),
        (dict(ratio=2, keep=1001), "^keep must be at most 1,000"),
        (dict(ratio="1e-20"), "^ratio .* needs at least 26 pairs"),
    ],
)
def test_design_caps_are_named(kwargs, message):
    with pytest.raises(ValueError, match=message):
        design_train(**kwargs)


def test_design_gives_up_within_its_work_cap():
    # twelve pairs of teeth up to 10,000 for a ratio of two large primes: far too many trials
    with pytest.raises(ValueError, match=f"^pairs: the design gave up after {MAX_DESIGN_STEPS:,} trial divisions"):
        design_train("999983/1000003", min_teeth=12, max_teeth=10_000, pairs=12)
    with pytest.raises(ValueError, match="^pairs: the design gave up after 10 trial divisions"):
        exact_trains(12, 2, 12, 72, max_steps=10)
