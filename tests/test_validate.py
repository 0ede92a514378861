"""Input checks: each raises GearleverError naming the parameter and what it must be."""

import math

import numpy as np
import pytest

from gearlever import _validate as v
from gearlever.errors import GearleverError

CHECKS = [
    (v.finite, "nan"),
    (v.positive, -1.0),
    (v.nonnegative, -1.0),
    (v.positive_int, 0),
    (v.nonnegative_int, -1),
    (v.finite_array, [np.inf]),
    (v.nonempty_array, []),
]


@pytest.mark.parametrize(("check", "bad"), CHECKS, ids=[c.__name__ for c, _ in CHECKS])
def test_every_check_raises_gearlevererror_naming_the_parameter_and_what_it_must_be(check, bad):
    with pytest.raises(GearleverError, match=r"^the_param must (be|hold) "):
        check("the_param", bad)


def test_no_assert_guards_input_in_the_package():
    import pathlib
    import re

    import gearlever

    src = pathlib.Path(gearlever.__file__).parent
    users = [str(p.relative_to(src)) for p in src.rglob("*.py") if re.search(r"^\s*assert\b", p.read_text(), re.M)]
    assert users == []


@pytest.mark.parametrize("bad", [0, -1.5, math.nan, math.inf, "3", None, True])
def test_positive_rejects_with_parameter_name(bad):
    with pytest.raises(ValueError, match=r"^l1 must be a positive finite number"):
        v.positive("l1", bad)


@pytest.mark.parametrize("bad", [0, -3, 2.5, "7", True])
def test_positive_int_rejects_with_parameter_name(bad):
    with pytest.raises(ValueError, match=r"^n2 must be a positive integer"):
        v.positive_int("n2", bad)


def test_positive_int_accepts_integral_float():
    assert v.positive_int("n2", 30.0) == 30


def test_nonnegative_accepts_zero_and_rejects_negative():
    assert v.nonnegative("q", 0) == 0.0
    with pytest.raises(ValueError, match="^q must be a non-negative"):
        v.nonnegative("q", -1e-9)
    assert v.nonnegative_int("q", 0) == 0
    with pytest.raises(ValueError, match="^q must be a non-negative integer"):
        v.nonnegative_int("q", -1)


def test_finite_array_keeps_shape_and_rejects_nan():
    assert v.finite_array("phi", np.zeros((2, 3))).shape == (2, 3)
    with pytest.raises(ValueError, match="^phi must be an array of finite numbers"):
        v.finite_array("phi", [0.0, np.nan])
    with pytest.raises(ValueError, match="^phi must be an array of finite numbers"):
        v.finite_array("phi", ["a"])


def test_nonempty_array_rejects_empty():
    with pytest.raises(ValueError, match="^phi must hold at least one value"):
        v.nonempty_array("phi", [])
