"""The sweep rule (gearlever.mechanism.sweep): a full turn, one oscillation of a rocking input, ranges and limits."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism, input_limits, sweep, sweep_rows
from gearlever.mechanism.sweep import oscillation


def test_a_crank_that_turns_fully_sweeps_one_turn_as_before():
    m = Mechanism.load(example_path("fourbar.toml"))
    s = sweep_rows(m, 360)
    q0 = m.sketch_inputs[0]
    assert np.array_equal(s.q[:, 0], q0 + np.linspace(0.0, 2 * np.pi, 360, endpoint=False))
    assert np.array_equal(s.qdot[:, 0], np.ones(360)) and not s.oscillates and s.message() is None
    q, qdot = sweep(m, 360)
    assert np.array_equal(q, s.q) and np.array_equal(qdot, s.qdot)


def test_a_rocking_input_sweeps_one_oscillation_sketch_upper_lower_sketch():
    m = Mechanism.load(example_path("watt_i.toml"))
    lim = input_limits(m)
    s = sweep_rows(m, 360)
    q, d = s.q[:, 0], s.direction
    assert s.oscillates and s.message() == "AB rocks between 67.284 and 78.254 deg: sweeping one oscillation"
    assert q[0] == lim.start and np.all((q >= lim.lower) & (q <= lim.upper))
    assert np.array_equal(s.qdot[:, 0], d.astype(float))
    flips = np.flatnonzero(np.diff(d))
    assert d[0] == 1 and d[-1] == 1 and flips.size == 2 and d[flips[0] + 1] == -1
    step = 2 * (lim.upper - lim.lower) / 360
    assert abs(np.abs(np.diff(q[: flips[0]])).max() - step) < 1e-12  # evenly spaced along the path
    assert abs((q[-1] + step) - lim.start) < 1e-12  # the end (the sketch again) excluded
    r = m.solve(s.q, s.qdot)
    assert r.closed.all()
    # rates with the sign of the motion: on the way back every link turns back (the same pose, rates negated)
    up = m.solve(s.q, np.ones_like(s.qdot))
    for k in ("BCD", "DE", "EF", "CFG"):
        assert np.allclose(r.omega[k], d * up.omega[k], rtol=0, atol=1e-9 * np.abs(up.omega[k]).max())
        assert np.allclose(r.alpha[k], up.alpha[k], rtol=0, atol=1e-9 * np.abs(up.alpha[k]).max())


def test_oscillation_first_down_mirrors_first_up():
    v, d = oscillation(0.0, -1.0, 2.0, 6, first=-1)
    assert v.tolist() == [0.0, -1.0, 0.0, 1.0, 2.0, 1.0] and d.tolist() == [-1, 1, 1, 1, -1, -1]


@pytest.mark.parametrize("rng", [(60.0, 70.0), (70.0, 80.0), (67.2815, 67.2815)])
def test_a_range_past_the_limits_is_refused_naming_them(rng):
    m = Mechanism.load(example_path("watt_i.toml"))
    with pytest.raises(GearleverError, match=r"AB moves only between 67\.284 and 78\.254 deg"):
        sweep_rows(m, 5, [rng])


def test_a_range_within_the_limits_is_swept_linearly():
    m = Mechanism.load(example_path("watt_i.toml"))
    s = sweep_rows(m, 3, [("AB", 70.0, 75.0)])
    assert np.allclose(np.degrees(s.q[:, 0]), [70.0, 72.5, 75.0]) and not s.oscillates
    assert m.solve(s.q, s.qdot).closed.all()


def test_too_many_points_and_a_slider_first_input_are_refused():
    m = Mechanism.load(example_path("watt_i.toml"))
    with pytest.raises(GearleverError, match="--points"):
        sweep_rows(m, 10**6)
    assert math.isfinite(input_limits(m).upper)


def test_a_slider_first_input_oscillates_between_dead_points_or_is_refused_without_them():
    """PMKS+ sweeps a slider input between its limits; a slider nothing stops has no one cycle (refused)."""
    free = Mechanism.from_dict(
        {
            "points": {"O2": [0.0, 0.0], "B": [1.0, 0.0]},
            "links": {"ground": ["O2"], "block": ["B"]},
            "sliders": [{"link": "block", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
            "inputs": [{"slider": "block"}],
        }
    )
    with pytest.raises(GearleverError, match="no dead point stops"):
        sweep_rows(free, 8)
    text = (
        example_path("slider_crank.toml")
        .read_text()
        .replace('[[inputs]]\nlink = "crank"', '[[inputs]]\nslider = "piston"')
    )
    m = Mechanism.loads(text)
    s = sweep_rows(m, 60)
    lim = input_limits(m)
    assert s.oscillates and set(s.direction.tolist()) == {1, -1}
    assert s.q[:, 0].min() >= lim.lower - 1e-12 and s.q[:, 0].max() <= lim.upper + 1e-12
    assert m.solve(s.q, s.qdot).closed.all()
