"""Tests of gearlever.trains.continued: exact ratios and continued fractions."""

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.errors import GearleverError
from gearlever.trains.continued import (
    MAX_RATIO_CHARS,
    approximants,
    continued_fraction,
    convergents,
    neighbours,
    parse_ratio,
)

SANDGREN = Fraction(1000, 6931)  # 1/6.931


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


def test_approximants_stop_at_max_term():
    fr = [a.fraction for a in approximants(SANDGREN, max_term=300)]
    assert fr[-2:] == [Fraction(29, 201), Fraction(43, 298)]  # next, 72/499, exceeds 300
    assert all(max(f.numerator, f.denominator) <= 300 for f in fr)


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


@pytest.mark.parametrize(
    "text",
    ["1/3/4", "1//3", "/3", "3/", "+3", "1/-3", "3 4", "1_000", "0x10", "inf", "1/inf", "", " ", "1e1000", "3/0.0"],
)
def test_parse_ratio_refuses_anything_but_a_number_or_b_over_c(text):
    with pytest.raises(ValueError, match="^ratio must be"):
        parse_ratio(text)


def test_parse_ratio_refuses_overlong_text_naming_the_cap():
    with pytest.raises(ValueError, match=f"^ratio must be at most {MAX_RATIO_CHARS} characters"):
        parse_ratio("1" * (MAX_RATIO_CHARS + 1))


positive = st.integers(1, 10**12)


@settings(max_examples=200, deadline=None)
@given(positive, positive)
def test_parse_ratio_of_integers_is_their_exact_quotient(b, c):
    assert parse_ratio(f"{b}/{c}") == Fraction(b, c)
    assert parse_ratio(f" {b} / {c} ") == Fraction(b, c)


@settings(max_examples=200, deadline=None)
@given(positive, st.integers(0, 6), positive, st.integers(0, 6))
def test_parse_ratio_of_decimals_is_exact(b, db, c, dc):
    # B = b / 10**db and C = c / 10**dc written as decimals
    def dec(n, d):
        s = str(n).rjust(d + 1, "0")
        return s[: len(s) - d] + ("." + s[len(s) - d :] if d else "")

    assert parse_ratio(f"{dec(b, db)}/{dec(c, dc)}") == Fraction(b, 10**db) / Fraction(c, 10**dc)


@settings(max_examples=200, deadline=None)
@given(st.fractions(min_value=Fraction(1, 10**9), max_value=10**9))
def test_parse_ratio_round_trips_its_own_text(x):
    """Any positive fraction whose text is within the 64-character cap parses back to itself;
    a longer text is refused naming the cap (never misread)."""
    if x > 0 and len(str(x)) <= 64:
        assert parse_ratio(str(x)) == x == parse_ratio(x)
    elif x > 0:
        with pytest.raises(GearleverError, match="at most 64 characters"):
            parse_ratio(str(x))


@settings(max_examples=100, deadline=None)
@given(positive, positive, positive)
def test_parse_ratio_refuses_three_terms(a, b, c):
    with pytest.raises(ValueError, match="^ratio"):
        parse_ratio(f"{a}/{b}/{c}")


def test_approximants_keep_the_most_accurate_of_a_long_run():
    # 1/1000001 = [0; 1000001]: its run is 1/j, j = 1 .. 1000001; only the last (most accurate) 5 are kept
    x = Fraction(1, 1000001)
    got = approximants(x, max_per_term=5)
    assert [a.fraction for a in got] == [Fraction(1, j) for j in range(999997, 1000002)]
    x = Fraction(1000, 6931)  # [0; 6, 1, 13, 2, 34]
    full = approximants(x)
    short = approximants(x, max_per_term=3)
    assert all(a in full for a in short)
    assert [a.multiple for a in short if a.index == 5] == [32, 33, 34]
