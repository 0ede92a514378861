"""Tests of gearlever.trains.rules: the classical rules read from their data files."""

import math
from fractions import Fraction

import pytest

from gearlever.trains.rules import min_teeth_for_form, pair_count_bounds, rules, sandgren_published


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


def test_sandgren_published_reads_its_data_file():
    pub = sandgren_published()  # Sandgren (1990), ASME J. Mech. Des. 112: 223-229
    assert pub["target"] == Fraction(1000, 6931)
    assert (pub["min_teeth"], pub["max_teeth"]) == (12, 60)
    assert pub["teeth"] == (16, 19, 43, 49)
    # the published squared error is that of the published teeth, to its 7 digits
    td, tb, ta, tf = pub["teeth"]
    assert float((Fraction(td * tb, ta * tf) - pub["target"]) ** 2) == pytest.approx(
        pub["best_squared_error"], rel=1e-6
    )


def test_pair_count_bounds_follow_log_ratios_for_any_ratio():
    for r in (7, 100, Fraction(1000, 6931), 3600):
        b = pair_count_bounds(r)
        span = abs(math.log(Fraction(r)))
        assert b.lower == pytest.approx(span / math.log(6)) and b.upper == pytest.approx(span / math.log(3))
        assert b.candidates[0] >= 1 and all(isinstance(k, int) for k in b.candidates)
