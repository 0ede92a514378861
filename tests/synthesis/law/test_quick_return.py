"""The quick-return law kinds (slotted lever, six-bar with a slider): closed forms against the mechanism engine,
the slotted lever's time ratio against its textbook formula, derivatives against finite differences, and the
quick-return law (a linear stroke over 240 deg, a cycloidal return over 120 deg) met by ``auto`` with a time
ratio near 2, the written model turned by the engine reproducing the reported motion."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.laws import law_from_segments
from gearlever.mechanism import Mechanism
from gearlever.synthesis import kinds
from gearlever.synthesis.law import LawProblem, kind_class, law_target, synthesize_law
from gearlever.synthesis.law.measure import MISS_FRACTION, law_report, mechanism_law, time_ratio
from gearlever.synthesis.law.slotted_lever import time_ratio as lever_time_ratio

TH = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
#: Targets whose range (100 mm, 1 rad) sets the kinds' unit: the designs below are in it.
SLIDE = law_target(TH, 50.0 * np.sin(TH), output="displacement", units="mm")
SWING = law_target(TH, 0.5 * np.sin(TH))
#: The quick-return law: the ram at constant speed over 240 deg, back by a cycloidal return over 120 deg.
QUICK_RETURN = [{"to": 240, "motion": "linear", "rise": 100}, {"to": 360, "motion": "cycloidal", "rise": -100}]

#: A design of each quick-return kind (variables in the order of the kind's ``names``) on its target.
DESIGNS = {
    "slotted-lever+ram": (SLIDE, [2.0, 150.0, 0.3, 0.4]),
    "slotted-lever+lever": (SWING, [2.5, -0.7]),
    "sixbar-slider+whitworth": (SLIDE, [0.5, -1.4, 180.0, 0.2, 60.0, 30.0, 0.5, 1.0]),
    "sixbar-slider+shaper": (SLIDE, [1.8, -1.6, 250.0, 0.0, 50.0, 260.0, 1.2, -1.0]),
}


def _kind(name, target):
    return kind_class(name.split("+")[0])(target)


def test_the_quick_return_kinds_are_in_the_one_registry_with_family_law():
    listed = {k.name: k for k in kinds("law")}
    for name in ("slotted-lever", "sixbar-slider"):
        assert listed[name].family == "law" and listed[name].spec is kind_class(name)
    assert list(listed)[-2:] == ["slotted-lever", "sixbar-slider"]


@pytest.mark.parametrize("name", list(DESIGNS))
def test_closed_form_matches_the_mechanism_engine_on_the_written_model(name):
    target, z = DESIGNS[name]
    z = np.array(z, dtype=float)
    kind = _kind(name, target)
    G, ok = kind.generate(z[None, :], TH)
    assert ok[0]
    ml = mechanism_law(Mechanism.from_dict(kind.model(z, 0.0)), "output", TH.size)
    assert ml.closed.all() and ml.net == 0.0
    assert np.abs(ml.s - (G[0] - G[0, 0])).max() < 1e-9 * max(1.0, np.ptp(G[0]))


@pytest.mark.parametrize("name", list(DESIGNS))
def test_complex_step_jacobian_matches_central_differences(name):
    target, z = DESIGNS[name]
    z = np.array(z, dtype=float)
    pb = LawProblem(name.split("+")[0], target)
    J = pb.jacobian(z)
    h = 1e-6
    for j, var in enumerate(pb.kind.names):
        if var in pb.kind.fixed:
            continue
        e = np.zeros(z.size)
        e[j] = h
        fd = (pb.kind.generate((z + e)[None], TH)[0][0] - pb.kind.generate((z - e)[None], TH)[0][0]) / (2 * h)
        assert np.abs(fd - J[:, j]).max() < 1e-6 * max(1.0, np.abs(J[:, j]).max()), var


@pytest.mark.parametrize("d", [1.2, 2.0, 3.5])
def test_the_slotted_levers_swing_takes_the_crank_arc_of_the_textbook_time_ratio(d):
    # Shigley and Uicker, Theory of Machines and Mechanisms, quick-return mechanisms: the lever's stroke one
    # way spans pi + 2 asin(a/d) of crank, the other pi - 2 asin(a/d)
    th = np.linspace(0.0, 2 * math.pi, 36_000, endpoint=False)
    kind = kind_class("slotted-lever")(law_target(th, np.zeros(th.size)))
    G, _ = kind.generate(np.array([[d, 0.3]]), th)
    r = time_ratio(th, G[0])
    want = float(lever_time_ratio(d))
    ratio = max(r["ratio"], 1 / r["ratio"])
    assert ratio == pytest.approx(want, rel=2e-3)
    assert lever_time_ratio(2.0) == pytest.approx(2.0, rel=1e-15)


def test_the_lever_is_driven_square_to_its_slot_and_the_ram_kinds_bound_their_transmission():
    mn, mx = kind_class("slotted-lever")(SWING).transmission(np.array([[2.0, 0.1]]))
    assert mn[0] == mx[0] == pytest.approx(math.pi / 2)
    _, z = DESIGNS["sixbar-slider+whitworth"]
    kind = kind_class("sixbar-slider")(SLIDE)
    mn, mx = kind.transmission(np.array([z]))
    _, (_, By), r, e = kind._points(np.array([z]), TH)
    assert mn[0] == pytest.approx(np.arccos(np.abs(e - By) / r).min())


@pytest.fixture(scope="module")
def quick_return():
    law = law_from_segments("displacement", "mm", [dict(g) for g in QUICK_RETURN])
    return law, synthesize_law(law, kind="auto", budget=20_000, workers=1)


def test_auto_meets_the_quick_return_law_with_a_time_ratio_near_two(quick_return):
    law, res = quick_return
    rep = law_report(res)
    assert res.kind in ("slotted-lever", "sixbar-slider")
    # the slider-crank misses by far more (its return takes far longer than 120 deg)
    assert res.tried["slider-crank"] > 2 * res.objective
    assert rep["time_ratio"]["wanted"] == pytest.approx(2.0, rel=1e-12)
    assert 1.6 < rep["time_ratio"]["achieved"] < 2.6
    # measured at this budget: 3.07 mm on a 100 mm stroke (a linkage cannot turn the corner of the
    # linear stroke's constant speed exactly); the report says whether it misses by more than 2 %
    assert rep["error_max"] < 4.0
    assert rep["misses_law"] == (rep["error_max"] > MISS_FRACTION * 100.0)
    for k in ("fourbar", "geared-fourbar", "gear-lever", "sixbar-dwell"):
        assert "gives an output angle, the law is displacement" in res.not_tried[k]


def test_the_written_quick_return_model_turned_by_the_engine_follows_the_reported_motion(quick_return):
    _, res = quick_return
    ml = mechanism_law(Mechanism.from_dict(res.model()), "output", res.theta.size)
    assert ml.closed.all()
    assert np.abs(ml.s - (res.achieved - res.achieved[0])).max() < 1e-8
    assert np.abs(ml.s + res.achieved[0] - res.target).max() == pytest.approx(np.abs(res.error).max(), rel=1e-6)


def test_the_lever_follows_an_angle_law_it_generates_to_rounding():
    kind = kind_class("slotted-lever")(SWING)
    G, _ = kind.generate(np.array([[2.2, 0.9]]), TH)
    assert kind.names == ("d", "alpha")  # the angle variant's two variables
    pb = LawProblem("slotted-lever", law_target(TH, G[0] - G[0, 0]))
    z, k, f = pb.polish(np.array([2.0, 0.7]), rounds=10)
    assert f < 1e-9 and z == pytest.approx([2.2, 0.9], abs=1e-6)
