"""The challenge's distance, material and hypervolume on hand-checkable cases (Nobari, Ahmed et al., LINKS)."""

import numpy as np
import pytest

from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve.score import distance, feasible, hypervolume, material, resample
from gearlever.synthesis.curve.simulate import simulate

T = np.linspace(0, 2 * np.pi, 200)
CIRCLE = np.stack([np.cos(T), np.sin(T)], -1)


def _ellipse(a=2.0, b=1.0, start=0.0, n=200, sense=1):
    t = start + sense * np.linspace(0, 2 * np.pi, n)
    return np.stack([a * np.cos(t), b * np.sin(t)], -1)


def test_crank_tip_traces_the_target_circle_with_zero_distance():
    # a four-bar whose crank tip (radius 0.5) is traced, target a circle of radius 0.5 elsewhere
    d = {
        "x0": [[0, 0], [0.5, 0], [3, 0], [2, 2]],
        "edges": [[0, 1], [1, 3], [2, 3]],
        "fixed_joints": [0, 2],
        "motor": [0, 1],
        "target_joint": 1,
    }
    lk = linkage_from_dict(d)
    x = simulate(lk.x0[None], solve_plan(lk))
    target = 0.5 * CIRCLE[::-1] + [7.0, -3.0]  # other sense, other centre
    assert distance(x[:, 1], target)[0] == pytest.approx(0.0, abs=1e-9)


def test_rotated_shifted_reversed_copies_are_at_zero_distance():
    target = _ellipse()
    rot = np.array([[np.cos(0.7), -np.sin(0.7)], [np.sin(0.7), np.cos(0.7)]])
    curves = [_ellipse(start=1.3) @ rot.T + 5.0, _ellipse(sense=-1) + [1, 2], _ellipse(start=-0.4, n=733) @ rot.T]
    d = [float(distance(c[None], target)[0]) for c in curves]
    # an arbitrary start resamples at points up to half a spacing apart: 2 pi x (half of ~0.031)
    assert d == pytest.approx([0, 0, 0], abs=0.1)
    assert d[1] == pytest.approx(0.0, abs=1e-9)  # same start, other sense
    # a circle started a whole number of spacings later, rotated and reversed: exactly the target
    shifted = np.roll(CIRCLE[:-1], 37, axis=0)[::-1]
    closed = np.concatenate([shifted, shifted[:1]]) @ rot.T
    assert distance(closed[None], CIRCLE)[0] == pytest.approx(0.0, abs=1e-9)


def test_scale_counts_twice_as_large_is_two_pi_away():
    # target's RMS radius is 1: a concentric circle twice as large has gap 1 at every point
    # (the closed curve repeats its first point, which shifts the mean by ~1e-5)
    assert distance(2 * CIRCLE[None], CIRCLE)[0] == pytest.approx(2 * np.pi, rel=1e-4)
    assert distance(np.full((1, 200, 2), 3.0), CIRCLE)[0] == np.inf  # a point has no length
    assert distance(np.where(np.arange(200)[:, None] > 50, np.nan, CIRCLE)[None], CIRCLE)[0] == np.inf


def test_fast_mode_equals_exact_with_all_alignments_and_bounds_it_above():
    rng = np.random.default_rng(3)
    curves = np.cumsum(rng.standard_normal((6, 200, 2)), 1)
    target = _ellipse(3, 1)
    exact = distance(curves, target)
    assert distance(curves, target, keep=400) == pytest.approx(exact, rel=1e-12)
    assert (distance(curves, target, keep=4) >= exact - 1e-12).all()


def test_resample_is_even_in_arc_length():
    line = np.array([[[0, 0], [0.1, 0], [0.15, 0], [2.0, 0], [3.0, 0]]])
    np.testing.assert_allclose(resample(line, 7)[0, :, 0], np.linspace(0, 3, 7), atol=1e-15)
    assert np.isnan(resample(np.zeros((1, 5, 2)), 7)).all()


def test_material_is_twice_the_link_lengths():
    assert material([[[0, 0], [3, 0], [3, 4]]], [[0, 1], [1, 2], [0, 2]])[0] == pytest.approx(24.0)
    assert feasible([0.7, 0.8, 0.1], [9.9, 1, 10.0], [20, 4, 4]).tolist() == [True, False, False]
    assert not feasible(0.1, 1.0, 21)


def test_hypervolume_of_known_fronts():
    assert hypervolume([]) == 0.0
    assert hypervolume([[0.0, 0.0]]) == pytest.approx(7.5)
    assert hypervolume([[0.5, 5.0], [0.25, 8.0]], reference=(1, 10)) == pytest.approx(0.75 * 2 + 0.5 * 3)
    # dominated points, duplicates and points beyond the reference add nothing
    base = [[0.1, 9.0], [0.5, 2.0]]
    extra = base + [[0.6, 9.5], [0.5, 2.0], [0.8, 1.0], [0.2, 11.0], [np.inf, 0.0]]
    assert hypervolume(extra) == pytest.approx(hypervolume(base)) == pytest.approx(0.65 * 1 + 0.25 * 7)


def test_hypervolume_matches_pymoo_on_random_sets():
    from pymoo.indicators.hv import HV

    rng = np.random.default_rng(4)
    for _ in range(5):
        F = rng.uniform([0, 0], [0.75, 10], (40, 2))
        assert hypervolume(F) == pytest.approx(HV(ref_point=np.array([0.75, 10.0]))(F), rel=1e-12)
