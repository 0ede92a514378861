"""Plan figures: the same bytes when the loop numbers differ in the last bit (another CPU's arithmetic)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from gearlever.loops import acceleration_plan, fourbar, fourbar_system
from gearlever.plotting.plans import PLOT_BITS, _rounded


def _terms():
    th = np.array([math.radians(40.0)])
    r = fourbar(9.0, 5.0, 8.0, 8.0, th, strict=True)
    system = fourbar_system(9.0, 5.0, 8.0, 8.0)
    sol = system.solve(th, {"theta3": float(r.theta3[0]), "theta4": float(r.theta4[0])}, strict=True)
    return acceleration_plan(system, sol, 0, 1.0, 0.5)


def _nudged(terms):
    """Every value moved by one unit in the last place (what another libm or an FMA may give)."""
    up = [
        dataclasses.replace(t, value=complex(np.nextafter(t.value.real, np.inf), np.nextafter(t.value.imag, -np.inf)))
        for t in terms
    ]
    return up


def test_plotted_values_are_identical_when_the_numbers_differ_in_the_last_bit():
    """The values handed to matplotlib do not change when every input moves by one ulp."""
    terms = _terms()
    a, b = _rounded(terms), _rounded(_nudged(terms))
    assert [t.value for t in a] == [t.value for t in b]
    assert [t.value for t in terms] != [t.value for t in _nudged(terms)]


def test_rounding_moves_values_by_at_most_half_the_grid():
    terms = _terms()
    big = max(abs(t.value) for t in terms)
    grid = 2.0 ** (math.frexp(big)[1] - PLOT_BITS)
    for t, r in zip(terms, _rounded(terms)):
        assert abs(t.value.real - r.value.real) <= grid / 2 and abs(t.value.imag - r.value.imag) <= grid / 2
    assert grid < 1e-8 * big
