"""Law synthesis: closed forms against the mechanism engine, derivatives against finite differences,
exact recovery of known designs, written models reproducing the achieved law, refusals, determinism."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.laws import law_from_segments
from gearlever.mechanism import Mechanism
from gearlever.synthesis.law import KINDS, LawProblem, law_target, synthesize_law
from gearlever.synthesis.law.driver import target_of_law
from gearlever.synthesis.law.geared_fourbar import teeth_for_ratio
from gearlever.synthesis.law.measure import fit_segments, law_report, mechanism_law

TH = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
ANGLE = law_target(TH, np.zeros(TH.size))
SLIDE = law_target(TH, np.zeros(TH.size), output="displacement", units="mm")
NET720 = law_target(TH, 2 * TH, net=4 * math.pi)

#: A design of each kind (variables in the order of the kind's ``names``) and its target.
DESIGNS = {
    "fourbar": (ANGLE, [2.0, 1.6, 0.4, 0.7, 1.0]),
    "slider-crank": (SLIDE, [0.5, 0.2, 0.6, 0.4, -1.0]),
    "geared-fourbar": (ANGLE, [1.5, 1.2, 0.5, 0.3, 30, 20, -1.0]),
    "geared-fourbar+crank": (NET720, [1.5, 1.2, 0.5, 0.3, 20, 20, 1.0]),
    "sixbar-dwell": (ANGLE, [0.4, 0.7, 0.5, -1.6, -1.3, 1.4, 3.7, 3.8, 2.3, 4.3, 1.0, -1.0]),
}
DWELL = [{"to": 120, "motion": "dwell"}, {"to": 240, "motion": "cycloidal", "rise": 45}, {"to": 360, "motion": "345"}]
DWELL[-1]["rise"] = -45


def _kind(name):
    return KINDS[name.split("+")[0]]


@pytest.mark.parametrize("name", list(DESIGNS))
def test_closed_form_matches_the_mechanism_engine_on_the_written_model(name):
    target, z = DESIGNS[name]
    z = np.array(z, dtype=float)
    kind = _kind(name)(target)
    G, ok = kind.generate(z[None, :], TH)
    assert ok[0]
    ml = mechanism_law(Mechanism.from_dict(kind.model(z, 0.0)), "output", TH.size)
    assert ml.closed.all()
    assert np.abs(ml.s - (G[0] - G[0, 0])).max() < 1e-9
    if name == "geared-fourbar+crank":  # the output gear turns on by 360 (1 + z3/z5) deg per cycle
        assert math.isclose(ml.net, 4 * math.pi, rel_tol=1e-12)
    else:
        assert ml.net == 0.0


@pytest.mark.parametrize("name", list(DESIGNS))
def test_complex_step_jacobian_matches_central_differences(name):
    target, z = DESIGNS[name]
    z = np.array(z, dtype=float)
    pb = LawProblem(name.split("+")[0], target)
    J = pb.jacobian(z)
    free = [i for i, n in enumerate(pb.kind.names) if n not in pb.kind.fixed]
    h = 1e-6
    for j in free:
        e = np.zeros(z.size)
        e[j] = h
        fd = (pb.kind.generate((z + e)[None], TH)[0][0] - pb.kind.generate((z - e)[None], TH)[0][0]) / (2 * h)
        assert np.abs(fd - J[:, j]).max() < 1e-6 * max(1.0, np.abs(J[:, j]).max()), pb.kind.names[j]


def _law_of(kind, z):
    G, _ = kind.generate(np.asarray(z, dtype=float)[None, :], TH)
    return G[0] - G[0, 0]


def test_search_recovers_a_fourbar_law_exactly():
    z0 = np.array([[2.0, 1.6, 0.4, 0.7, 1.0]])
    kind = KINDS["fourbar"](ANGLE)

    def exact(th):  # the known four-bar's output from its value at law input 0
        return kind.generate(z0, np.asarray(th))[0][0] - kind.generate(z0, np.zeros(1))[0][0, 0]

    res = synthesize_law(law_target(TH, exact(TH)), kind="fourbar", budget=8000, workers=1, law=exact)
    assert np.abs(res.error).max() < 1e-9
    assert res.details["lengths"]["coupler"] == pytest.approx(200.0, rel=1e-8)
    assert res.details["lengths"]["output"] == pytest.approx(160.0, rel=1e-8)


def test_polish_from_a_perturbed_geared_fourbar_recovers_it_to_1e_9():
    z0 = np.array([1.5, 1.2, 0.5, 0.3, 30, 20, -1.0])
    s = _law_of(KINDS["geared-fourbar"](ANGLE), z0)
    pb = LawProblem("geared-fourbar", law_target(TH, s), 0.0)
    z1 = z0 + np.array([0.01, -0.01, 0.01, 0.005, 0, 0, 0])
    z, k, f = pb.polish(z1)
    assert f < 1e-9
    assert np.abs(z[:4] - z0[:4]).max() < 1e-7


def test_written_model_reproduces_the_achieved_law_to_1e_9():
    law = law_from_segments("angle", "deg", DWELL)
    res = synthesize_law(law, kind="geared-fourbar", budget=3000, workers=1)
    ml = mechanism_law(Mechanism.from_dict(res.model()), "output", 720)
    want = res.achieved_at(ml.theta) - res.achieved_at(np.zeros(1))[0]
    assert ml.closed.all() and np.abs(ml.s - want).max() < 1e-9
    rep = law_report(res)
    assert rep["transmission_deg"][0] >= 20 - 1e-9
    assert [s["motion"] for s in rep["segments"]] == ["dwell", "cycloidal", "345"]
    assert rep["segments"][0]["dwell_excursion_deg"] <= 2 * rep["segments"][0]["error_max_deg"] + 1e-9
    assert set(rep["design"]["teeth"].values()) <= set(range(17, 121))


def test_slider_crank_meets_a_harmonic_stroke_exactly():
    # a centred slider-crank with an infinitely long rod is harmonic; a real one is near it: check it is found
    law = law_from_segments(
        "displacement",
        "mm",
        [{"to": 180, "motion": "harmonic", "rise": 40}, {"to": 360, "motion": "harmonic", "rise": -40}],
    )
    res = synthesize_law(law, kind="slider-crank", budget=3000, workers=1)
    assert res.feasible and np.abs(res.error).max() < 0.1 * 40
    ml = mechanism_law(Mechanism.from_dict(res.model()), "output", 360)
    assert np.abs(ml.s - (res.achieved_at(ml.theta) - res.achieved_at(np.zeros(1))[0])).max() < 1e-9


def test_same_result_for_one_or_two_workers():
    law = law_from_segments("angle", "deg", DWELL)
    a = synthesize_law(law, kind="fourbar", budget=2000, workers=1, seed=3)
    b = synthesize_law(law, kind="fourbar", budget=2000, workers=2, seed=3)
    assert np.array_equal(a.z, b.z) and a.offset == b.offset


def test_refusals_name_what_is_wrong():
    disp = law_from_segments(
        "displacement",
        "mm",
        [{"to": 180, "motion": "cycloidal", "rise": 1}, {"to": 360, "motion": "cycloidal", "rise": -1}],
    )
    with pytest.raises(GearleverError, match="output angle"):
        synthesize_law(disp, kind="fourbar", budget=200)
    net = law_target(TH, TH * 1.5, net=3 * math.pi)
    with pytest.raises(GearleverError, match="returns to its start"):
        synthesize_law(net, kind="fourbar", budget=200)
    odd = law_target(TH, TH * (1 + math.pi), net=2 * math.pi * (1 + math.pi))
    with pytest.raises(GearleverError, match="no such teeth"):
        synthesize_law(odd, kind="geared-fourbar", budget=200)
    with pytest.raises(GearleverError, match="kind must be one of"):
        synthesize_law(net, kind="cam", budget=200)


def test_teeth_for_ratio_is_exact_and_within_bounds():
    assert teeth_for_ratio(1.0, (17, 120)) == (17, 17)
    assert teeth_for_ratio(0.5, (17, 120)) == (17, 34)
    assert teeth_for_ratio(7.5, (17, 120)) is None  # 120/16: the pinion would have 16 < 17 teeth


def test_fit_segments_finds_the_dwell_rise_and_return_of_a_dwell_law():
    law = law_from_segments("angle", "deg", DWELL)
    t = target_of_law(law, 3600)
    segs = fit_segments(t.theta, t.s, t.v)
    assert [g["motion"] for g in segs] == ["dwell", "rise", "return"]
    # |v| below 1 % of its peak: the dwell reaches a few degrees into the motions around it
    assert segs[0]["from_deg"] == pytest.approx(356.9, abs=0.2) and segs[0]["to_deg"] == pytest.approx(123.9, abs=0.2)
    assert segs[1]["rise"] == pytest.approx(math.radians(45), abs=5e-4)
