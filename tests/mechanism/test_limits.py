"""Input limits (dead points): against the law of cosines for four-bars whose input cannot turn, and the six-bars."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism, input_limits
from gearlever.mechanism.limits import LIMIT_TOL


def fourbar(a, b, c, d, theta):
    """Four-bar: ground O (0, 0) - Q (d, 0), input O-A of length a at ``theta``, coupler A-B = b, follower Q-B = c."""
    A = np.array([a * math.cos(theta), a * math.sin(theta)])
    Q = np.array([d, 0.0])
    r = float(np.linalg.norm(Q - A))
    x = (b * b - c * c + r * r) / (2 * r)
    e = (Q - A) / r
    B = A + x * e + math.sqrt(b * b - x * x) * np.array([-e[1], e[0]])
    return Mechanism.from_dict(
        {
            "points": {"O": [0, 0], "Q": [d, 0], "A": A.tolist(), "B": B.tolist()},
            "links": {"ground": ["O", "Q"], "rocker": ["O", "A"], "coupler": ["A", "B"], "follower": ["Q", "B"]},
            "inputs": [{"link": "rocker"}],
        }
    )


def dead_point(a, d, s):
    """Input angle at which |A Q| = s (coupler and follower collinear): the law of cosines."""
    return math.acos((a * a + d * d - s * s) / (2 * a * d))


def test_rocker_input_limits_where_coupler_and_follower_stretch_law_of_cosines():
    # a = 2, d = 4: |AQ| in [2, 6]; b + c = 5 binds, |b - c| = 1 does not: the input rocks symmetrically
    lim = input_limits(fourbar(2.0, 3.0, 2.0, 4.0, math.pi / 2))
    t = dead_point(2.0, 4.0, 5.0)
    assert lim.rocks and not lim.full_turn and not lim.locked
    assert abs(lim.upper - t) < 1e-9 and abs(lim.lower + t) < 1e-9
    assert lim.binding_upper == ("coupler", "follower") == lim.binding_lower


def test_double_rocker_limits_between_the_folded_and_the_stretched_dyad_law_of_cosines():
    # a = 2, d = 4, b = 3.5, c = 0.5: |AQ| between |b - c| = 3 (folded) and b + c = 4 (stretched)
    lim = input_limits(fourbar(2.0, 3.5, 0.5, 4.0, math.radians(60.0)))
    assert abs(lim.lower - dead_point(2.0, 4.0, 3.0)) < 1e-9  # 46.567 deg
    assert abs(lim.upper - dead_point(2.0, 4.0, 4.0)) < 1e-9  # 75.522 deg
    assert lim.tol == LIMIT_TOL


def test_a_crank_that_turns_fully_has_no_limit():
    lim = input_limits(Mechanism.load(example_path("fourbar.toml")))
    assert lim.full_turn and not lim.rocks and lim.lower == -math.inf and lim.upper == math.inf


def test_the_limit_is_reachable_and_a_hair_past_it_is_not():
    m = Mechanism.load(example_path("watt_i.toml"))
    lim = input_limits(m)
    assert f"{math.degrees(lim.lower):.3f} {math.degrees(lim.upper):.3f}" == "67.284 78.254"  # as the issue reads
    for edge, out in ((lim.lower, -1e-8), (lim.upper, 1e-8)):
        r = m.solve(np.array([lim.start, edge, edge + out]))
        assert r.closed.tolist() == [True, True, False]


@pytest.mark.parametrize("name", ["watt_i.toml", "stephenson_iii.toml"])
def test_solve_never_raises_and_closes_exactly_inside_the_limits(name):
    m = Mechanism.load(example_path(name))
    lim = input_limits(m)
    rng = np.random.default_rng(7)
    for q in rng.uniform(-4 * math.pi, 4 * math.pi, 40):
        r = m.solve(np.array([q]))  # one row, from the sketch: the continuation or the closed-form dyads
        inside = lim.lower + 1e-9 < q < lim.upper - 1e-9
        assert bool(r.closed[0]) == inside, (q, r.reason[0])
        if not inside:
            assert np.isnan(r.x).all() and r.reason[0]


def test_just_past_the_lower_limit_of_watt_i_is_not_closed_never_an_exception():
    # the closed-form dyads let a NaN through (the second dyad's margin was dropped by fmin): the case
    m = Mechanism.load(example_path("watt_i.toml"))
    r = m.solve(np.radians([67.2815]))
    assert not r.closed[0] and r.reason[0].startswith("dead point")


def test_bad_arguments_are_refused():
    m = Mechanism.load(example_path("watt_i.toml"))
    for kw, word in (({"index": 1}, "index"), ({"tol": 0.0}, "tol"), ({"start": [1.0, 2.0]}, "start")):
        with pytest.raises(GearleverError, match=word):
            input_limits(m, **kw)
    with pytest.raises(GearleverError, match="start: the mechanism does not assemble"):
        input_limits(m, start=[math.radians(60.0)])


def test_a_sketch_at_a_dead_point_names_the_binding_links():
    # b - c = a + d: the input assembles at 180 deg only (coupler and rocker folded onto each other)
    d = {
        "points": {"O2": [0, 0], "O4": [4, 0], "A": [-1, 0], "B": [5, 0]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }
    with pytest.raises(GearleverError, match="the sketch is a dead point of the links coupler, rocker"):
        Mechanism.from_dict(d).solve([math.pi])
