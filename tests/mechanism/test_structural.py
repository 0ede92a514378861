"""Rank-based structure: counts, dof and redundant constraints, against the ZRDPM paper's eq. 1 cases."""

from __future__ import annotations

import gearlever
from gearlever.mechanism.mobility import published_mobility_cases

from ._models import all_examples, example


def test_parallel_levers_give_the_papers_lever_part_numbers():
    s = gearlever.Mechanism.load(example("parallel_levers")).structure()
    lever = next(c for c in published_mobility_cases() if c["n"] == 5)
    assert (s.n, s.P5, s.P4) == (lever["n"], lever["p5"], lever["p4"])
    assert s.W_formula == -1
    assert (s.dof, s.redundant) == (lever["w"], lever["q"])
    assert len(s.redundant_rows) == 2


def test_zrdpm_gear_contour_has_two_degrees_of_freedom():
    s = gearlever.Mechanism.load(example("zrdpm_gear_contour")).structure()
    assert (s.n, s.P5, s.P4, s.dof, s.redundant) == (3, 3, 1, 2, 0)


def test_three_planets_make_two_redundant_meshes():
    s = gearlever.Mechanism.load(example("planetary")).structure()
    assert (s.W_formula, s.dof, s.redundant) == (-1, 1, 2)
    assert all(r.startswith("mesh") for r in s.redundant_rows)


def test_dof_equals_formula_plus_redundant_for_every_example():
    for p in all_examples():
        s = gearlever.Mechanism.load(p).structure()
        assert s.dof == s.W_formula + s.redundant == gearlever.mobility(s.n, s.P5, s.P4, s.redundant)
        assert s.dof == s.inputs
