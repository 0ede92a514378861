"""A user's own curve (issue 33, section 1): closed targets, size-free scoring, designs written in the target's frame.

The challenge's definitions (A. H. Nobari, F. Ahmed et al., MIT 2.156 linkage synthesis challenge, ``LINKS``)
score the target as the open polyline of its points with absolute material; the relative scoring closes the
target and measures material at the size of the challenge's targets (:mod:`gearlever.synthesis.curve.score`).
"""

import json

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve import library as L
from gearlever.synthesis.curve import search as S
from gearlever.synthesis.curve.score import (
    REFERENCE_RMS,
    closed,
    distance,
    material,
    material_scale,
    resample,
    rms_radius,
    score_distance,
    scoring_target,
)
from gearlever.synthesis.curve.simulate import crank_angles, simulate
from tests.synthesis.curve._designs import SIXBAR


def _d_mm(n=60):
    """A 50 mm D drawn in millimetres: a circle of radius 25 with a flat side, centred near (706, 400)."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    return np.stack([np.where(c > 0.3, 0.3, c), s], -1) * 25.0 + [706.0, 400.0]


def _crank(r, centre=(0.0, 0.0)):
    t = crank_angles()
    return (r * np.stack([np.cos(t), np.sin(t)], -1) + centre)[None]


def _polygon(n, r=25.0, sub=1):
    """A regular ``n``-gon of circumradius ``r``, each side divided into ``sub`` pieces (same polyline)."""
    a = np.linspace(0, 2 * np.pi, n, endpoint=False)
    v = r * np.stack([np.cos(a), np.sin(a)], -1) + [700.0, 400.0]
    w = np.linspace(0, 1, sub, endpoint=False)[:, None]
    return np.concatenate([v[i] + w * (v[(i + 1) % n] - v[i]) for i in range(n)])


def test_a_repeated_first_point_changes_nothing_in_the_relative_scoring_and_everything_in_the_challenges():
    c60 = _polygon(60)
    rep = np.concatenate([c60, c60[:1]])
    crank = _crank(25.0)
    rel = [float(distance(crank, scoring_target(t))[0]) for t in (c60, rep)]
    assert rel[0] == rel[1] == pytest.approx(0.0057, abs=2e-4)
    # the challenge's open polyline misses the closing segment unless the first point is repeated (issue 33)
    assert float(distance(crank, scoring_target(c60, "challenge"))[0]) == pytest.approx(0.091, abs=2e-3)
    assert closed(rep).shape == rep.shape and closed(c60).shape == rep.shape


def test_a_sparse_target_is_scored_by_its_polyline_not_by_its_sampling():
    crank = _crank(25.0)
    sparse, dense = _polygon(12), _polygon(12, sub=10)  # the same 12-gon: 12 vertices, or 120 points on its sides
    d12, d120 = (float(distance(crank, scoring_target(t))[0]) for t in (sparse, dense))
    assert d12 == pytest.approx(d120, abs=2e-3)
    # a circle against the inscribed 12-gon: 0.145 (the chords' sag), against 0.66 for the open polyline
    assert d12 < 0.15 and float(distance(crank, scoring_target(sparse, "challenge"))[0]) > 0.6


def test_relative_material_is_the_same_at_any_size_and_the_challenges_is_absolute():
    lk = linkage_from_dict(SIXBAR)
    target = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint]
    m = float(material(lk.x0[None], lk.edges)[0])
    for size in (1e-2, 1.0, 250.0):
        t = target * size + 3.0
        assert material_scale(t) * m * size == pytest.approx(m * REFERENCE_RMS / rms_radius(target), rel=1e-9)
        assert material_scale(t, "challenge") == 1.0
    with pytest.raises(GearleverError, match="^scoring"):
        material_scale(target, "absolute")


@pytest.fixture(scope="module")
def d_mm():
    """The synthesis of the D in millimetres with the small library and search of tests/synthesis/curve/_designs.py."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(L, "LIBRARY_TOPOLOGIES", 8)
        mp.setattr(L, "LIBRARY_SKETCHES", 60)
        mp.setattr(S, "STARTS", 2)
        mp.setattr(S, "PRESELECT", 4)
        mp.setattr(S, "LAMBDAS", np.geomspace(1e-3, 0.3, 3))
        mp.setattr(S, "LAMBDAS_SQUARED", np.geomspace(1e-3, 0.3, 3))
        target = _d_mm()
        return target, S.synthesize_curve(target, budget=1000, seed=0, workers=1, use_cache=False)


def _to_polyline(points, poly):
    """Distance of each point to the closed polyline ``poly``."""
    a, b = poly, np.roll(poly, -1, axis=0)
    ab = b - a
    w = np.clip(((points[:, None] - a) * ab).sum(-1) / (ab**2).sum(-1), 0, 1)
    return np.hypot(*(points[:, None] - a - w[..., None] * ab).transpose(2, 0, 1)).min(1)


def test_a_curve_in_millimetres_gets_a_front_scored_in_its_own_size(d_mm):
    target, r = d_mm
    assert r.scoring == "relative" and len(r.designs) >= 3 and r.hypervolume > 2
    assert r.material_scale == pytest.approx(REFERENCE_RMS / rms_radius(closed(target)))
    s = r.summary()
    assert not s["empty"] and "0.191" in s["scoring_rule"]
    for lk, d, m, f in zip(r.designs, r.error, r.material, s["front"]):
        assert d < 0.75 and m < 10
        assert material(lk.x0[None], lk.edges)[0] == pytest.approx(m / r.material_scale, rel=1e-9)
        assert f["material_in_target_units"] == pytest.approx(m / r.material_scale, rel=1e-9)
    json.dumps(s, allow_nan=False)


def test_every_design_traces_the_target_where_it_was_drawn_within_its_score(d_mm):
    target, r = d_mm
    rms = rms_radius(closed(target))
    for lk, d, tf in zip(r.designs, r.error, r.transforms):
        x = simulate(lk.x0[None], solve_plan(lk))[0, lk.target_joint]
        gap = _to_polyline(resample(x[None])[0], target)  # along the path by arc length, as the score samples it
        # the score's mean gap in the target's units is d rms / (2 pi): the drawn path is no farther
        assert gap.mean() <= d * rms / (2 * np.pi) * 1.02
        # centred on the target: the means of both curves resampled by arc length (the score's centres)
        centre = [resample(c[None])[0].mean(0) for c in (x, closed(target))]
        assert np.hypot(*(centre[0] - centre[1])) < 2e-3 * rms  # the crank turns from an absolute 0: sampled anew
        assert tf[1] == pytest.approx(1 / r.material_scale)  # the scale back to millimetres


def test_the_same_curve_in_millimetres_under_the_challenges_rules_has_an_empty_front_and_says_so():
    target = _d_mm()
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(L, "LIBRARY_TOPOLOGIES", 8)
        mp.setattr(L, "LIBRARY_SKETCHES", 60)
        mp.setattr(S, "STARTS", 2)
        mp.setattr(S, "PRESELECT", 4)
        mp.setattr(S, "LAMBDAS", np.geomspace(1e-3, 0.3, 3))
        mp.setattr(S, "LAMBDAS_SQUARED", np.geomspace(1e-3, 0.3, 3))
        r = S.synthesize_curve(target, budget=1000, seed=0, workers=1, use_cache=False, scoring="challenge")
    s = r.summary()
    assert len(r.designs) == 0 and s["empty"] and s["best_distance"] is None and r.hypervolume == 0.0


def test_cranks_whose_tip_is_traced_are_offered_with_their_circle_scored():
    t = np.linspace(0, 2 * np.pi, 100, endpoint=False)
    egg = np.stack([0.3 * np.cos(t) * (1 + 0.2 * np.sin(t)), 0.24 * np.sin(t)], -1)
    tips = S._crank_tips(egg)
    assert len(tips) == len(S.CRANK_TIP_RADII)
    for tip in tips:
        lk = linkage_from_dict({"x0": tip.x0, "edges": [[0, 1]], "fixed_joints": [0], "motor": [0, 1]})
        x = simulate(lk.x0[None], solve_plan(lk))[:, 1]
        assert tip.distance == pytest.approx(float(distance(x, egg)[0]), rel=1e-12)
        assert tip.material == pytest.approx(2 * np.hypot(*lk.x0[1]), rel=1e-12)
    # a circle is within the challenge's distance of the egg: the front's low-material end is never empty
    assert min(tip.distance for tip in tips) < 0.75


def test_a_closed_target_has_no_first_point_in_the_relative_scoring():
    crank = _crank(25.0, (1.0, 2.0))
    c60 = _polygon(60)
    d = [float(score_distance(crank, np.roll(c60, k, axis=0))[0]) for k in (0, 7, 31)]
    assert max(d) - min(d) < 1e-3  # any start of the same closed polyline
    assert score_distance(crank, c60)[0] <= distance(crank, closed(c60))[0]
    assert score_distance(crank, c60, "challenge")[0] == distance(crank, c60)[0]
