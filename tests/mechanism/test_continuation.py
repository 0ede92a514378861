"""Continuation of mechanism models: coarse sweeps keep the branch, dead points are reported, degrees are flagged."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import gearlever
from gearlever.errors import GearleverWarning
from gearlever.loops import fourbar

from ._models import example, wrap


def _fourbar(O4, A, B):
    return gearlever.Mechanism.from_dict(
        {
            "points": {"O2": [0.0, 0.0], "O4": list(O4), "A": list(A), "B": list(B)},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )


def _triple_rocker(rocker: float):
    """Ground 10, crank 8 (sketch at 90 deg), coupler 5: a triple-rocker for coupler + rocker > 18 > rocker - 5."""
    A = np.array([0.0, 8.0])
    O4 = np.array([10.0, 0.0])
    d = float(np.linalg.norm(O4 - A))
    ex = (O4 - A) / d
    ey = np.array([-ex[1], ex[0]])
    x = (25.0 - rocker**2 + d * d) / (2 * d)
    B = A + x * ex + math.sqrt(25.0 - x * x) * ey
    return _fourbar(O4, A, B)


@pytest.mark.parametrize("n", [2, 3, 4, 8])
def test_coarse_fourbar_sweep_is_on_the_branch_of_a_fine_one(n):
    m = gearlever.Mechanism.load(example("fourbar"))
    q0 = m.sketch_inputs[0]
    fine = m.solve(q0 + np.linspace(0.0, 2 * np.pi, 3600, endpoint=False))
    coarse = m.solve(q0 + np.linspace(0.0, 2 * np.pi, n, endpoint=False))
    sub = slice(None, None, 3600 // n)
    assert coarse.closed.all() and coarse.dead_rows.size == 0
    for k in ("coupler", "rocker"):
        assert np.abs(coarse.angle[k] - fine.angle[k][sub][:n]).max() < 1e-9, k


def test_coarse_sweep_the_other_way_round_and_far_from_the_sketch_keeps_the_branch():
    # rows that start three turns away and go backwards in steps of 100 deg: the same
    # assembly (the open one of the sketch) as the closed form with the sketch's branch
    m = gearlever.Mechanism.load(example("fourbar"))
    q = m.sketch_inputs[0] + 6 * np.pi - np.radians(100.0) * np.arange(12)
    r = m.solve(q)
    f = fourbar(40.0, 10.0, math.dist((10, 0), (45.1, 28.3)), math.dist((40, 0), (45.1, 28.3)), q)
    assert r.closed.all()
    assert np.abs(wrap(r.angle["rocker"] - f.theta4)).max() < 1e-9


@pytest.mark.parametrize("n", [8, 13, 20, 26, 29, 37, 100, 721])
def test_a_narrow_dead_zone_is_never_stepped_over(n):
    # coupler + rocker = 17.99 < 18 = ground + crank: no assembly for the crank within
    # +-0.067 rad of 180 deg, a gap narrower than the coarse step and the row spacing
    m = _triple_rocker(12.99)
    q = np.pi / 2 + np.linspace(0.0, 2 * np.pi, n)
    r = m.solve(q)
    gap = math.acos((164.0 - 17.99**2) / 160.0)  # |A - O4| = coupler + rocker
    first = int(np.argmin(r.closed))
    assert 0 < first < n and not r.closed[first:].any()
    assert q[first - 1] <= gap and q[first] > gap
    assert r.dead_rows.tolist() == [first]
    assert r.reason[first].startswith(f"dead point between row {first - 1} and this row (at crank = ")


def test_triple_rocker_dead_point_is_reported_where_the_closed_form_puts_it():
    # ground 10, crank 8, coupler 5, rocker hypot(7, 12): the crank stops where
    # |A - O4| = rocker - coupler, cos(theta) = (164 - (rocker - 5)^2) / 160
    m = _triple_rocker(math.hypot(7.0, 12.0))
    limit = 2 * np.pi - math.acos((164.0 - (math.hypot(7.0, 12.0) - 5.0) ** 2) / 160.0)
    for n in (8, 36, 721):
        r = m.solve(np.pi / 2 + np.linspace(0.0, 2 * np.pi, n))
        (row,) = r.dead_rows
        assert r.closed[:row].all() and not r.closed[row:].any()
        at = float(r.reason[row].split("crank = ")[1].split(" rad")[0])
        assert at == pytest.approx(limit, abs=1e-5)
        assert all(s.startswith("not reached") for s in r.reason[row + 1 :])


def test_change_point_parallelogram_stops_at_the_change_point_and_says_so_with_branch_stop():
    # Grashof change point (s + l = p + q): crank 4, coupler 10, rocker 4, ground 10; at
    # crank 180 deg all links are collinear and the parallelogram could become an antiparallelogram
    m = _fourbar((10.0, 0.0), (0.0, 4.0), (10.0, 4.0))
    for n in (8, 360):
        q = np.pi / 2 + np.linspace(0.0, 2 * np.pi, n, endpoint=False)
        r = m.solve(q, branch="stop")
        ok = q < np.pi - 1e-12
        assert r.closed[ok].all()
        assert np.abs(r.angle["rocker"][ok] - q[ok]).max() < 1e-9  # parallelogram: rocker parallel to the crank
        assert r.dead_rows.size and not r.closed[r.dead_rows[-1] :].any()
        assert "dead point" in r.reason[r.dead_rows[0]]


def test_inputs_in_degrees_warn_once_and_radians_do_not():
    m = gearlever.Mechanism.load(example("fourbar"))
    with pytest.warns(GearleverWarning, match="looks like degrees") as rec:
        m.solve(np.arange(0.0, 361.0, 10.0))
    assert len([w for w in rec if issubclass(w.category, GearleverWarning)]) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error", GearleverWarning)
        m.solve(np.linspace(0.0, 4 * np.pi, 50))
        m.solve(np.array([0.0, 1.0, 2.0, 3.0]))


def test_first_row_beyond_a_dead_point_from_the_sketch_says_so():
    # the sketch is at 90 deg; 180 deg lies in the dead zone of the narrow triple-rocker
    m = _triple_rocker(12.99)
    r = m.solve(np.array([np.pi, np.pi / 2]))
    assert not r.closed[0] and r.dead_rows.tolist() == [0]
    assert r.reason[0].startswith("dead point between the sketch and this row (at crank = ")
    # row 1 is the sketch itself: reached again from the sketch, on the sketch's branch
    assert r.closed[1] and r.reason[1] == ""
    assert abs(r.angle["rocker"][1] - m.model.links["rocker"].angle0) < 1e-12
