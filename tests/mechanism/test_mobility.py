"""Mobility with redundant constraints (paper eq. 1) and the paper's three cases."""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.mechanism.mobility import mobility, published_mobility_cases, redundant_constraints

# The three published cases (n, P5, P4, q, W), from the data file, checked against the formula.
CASES = published_mobility_cases()


def test_data_file_holds_the_three_published_cases():
    assert [c["case"] for c in CASES] == ["lever part", "gear part", "whole gear-lever mechanism"]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c["case"])
def test_published_case_mobility(case):
    assert mobility(case["n"], case["p5"], case["p4"], case["q"]) == case["w"]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c["case"])
def test_published_case_redundant_constraints(case):
    assert redundant_constraints(case["n"], case["p5"], case["p4"], case["w"]) == case["q"]


def test_lever_part_values_as_in_the_paper_text():
    # paper: n = 5, P5 = 8, P4 = 0 with W = 1 gives q = 2
    assert redundant_constraints(5, 8, 0, 1) == 2


@settings(max_examples=60, deadline=None)
@given(n=st.integers(0, 30), p5=st.integers(0, 40), p4=st.integers(0, 10), q=st.integers(0, 10))
def test_round_trip_mobility_and_redundant_constraints(n, p5, p4, q):
    w = mobility(n, p5, p4, q)
    if w >= 0:
        assert redundant_constraints(n, p5, p4, w) == q


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: mobility(-1, 0, 0), "n"),
        (lambda: mobility(1, 1.5, 0), "p5"),
        (lambda: mobility(1, 0, "x"), "p4"),
        (lambda: mobility(1, 0, 0, q=-2), "q"),
        (lambda: redundant_constraints(9, 0, 0, 1), "w"),
        (lambda: redundant_constraints(1, 0, 0, -1), "w"),
    ],
)
def test_bad_input_raises_value_error_naming_the_parameter(call, name):
    with pytest.raises(ValueError, match=f"^{name} must"):
        call()
