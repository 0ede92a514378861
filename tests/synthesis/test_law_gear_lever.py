"""The gear-lever (ZRDPM) kind of law synthesis: closed form against the mechanism engine (both variants and
other slide settings), complex-step derivatives against finite differences, whole teeth and the mesh's
assembly constraint, exact recovery of a known design by the polish, refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.synthesis.law import KINDS, LawProblem, law_target, synthesize_law
from gearlever.synthesis.law.fourbar import SIZE
from gearlever.synthesis.law.measure import law_report, mechanism_law

TH = np.linspace(0.0, 2 * math.pi, 360, endpoint=False)
HELD = law_target(TH, np.zeros(TH.size))
#: a law whose output turns -180 deg per cycle: gear 9 driven, z9 / z8 = 1/2
DRIVEN = law_target(TH, -0.5 * TH, net=-math.pi)
#: b, c, u2, alpha, c2, beta, b2, l, z9, z8, branch, branch2
Z0 = np.array([0.3627, 1.0966, 0.6747, 0.4434, 0.5598, 2.8402, 0.624, 1.5799, 31, 91, -1.0, -1.0])
GL = KINDS["gear-lever"]


def _z(target):
    z = Z0.copy()
    kind = GL(target)
    if kind.variant == "driven":
        z[8:10] = kind.lo[8:10]
    return kind, z


@pytest.mark.parametrize("target", [HELD, DRIVEN], ids=["held", "driven"])
def test_closed_form_matches_the_mechanism_engine_on_the_written_model(target):
    kind, z = _z(target)
    G, ok = kind.generate(z[None, :], TH)
    assert ok[0]
    mech = Mechanism.from_dict(kind.model(z, 0.0))  # checks |O1 E| = m (z9 + z8) / 2 (assembly)
    assert mech.model.module == pytest.approx(2 * SIZE * z[7] / (z[8] + z[9]), rel=1e-12)
    ml = mechanism_law(mech, "output", TH.size)
    assert ml.closed.all()
    assert np.abs(ml.s - (G[0] - G[0, 0])).max() < 1e-9
    z9, z8 = int(z[8]), int(z[9])
    # Willis (Alimukhamedov et al. 2020, eqs. 2-4): the driven gear turns -360 z9/z8 deg per turn of gear 9
    want_net = -2 * math.pi * z9 / z8 if kind.variant == "driven" else 0.0
    assert math.isclose(ml.net, want_net, rel_tol=1e-12, abs_tol=1e-12)


@pytest.mark.parametrize("slide", [0.95, 1.05])
def test_slide_sweep_matches_the_engine_with_the_slide_moved(slide):
    kind, z = _z(HELD)
    model = kind.model(z, 0.0)
    G, ok, _, _ = kind._outputs(z[None, :], TH, slide)
    assert ok[0]
    # the model at another slide setting: O3 moved along the guide, the rocker B, D re-assembled at input 0
    _, psi, Dx, Dy, _ = kind._rocker(z[None, :], np.zeros(1), slide)
    _, _, _, th1 = kind._outputs(z[None, :], np.zeros(1), slide)
    S, psi, th1 = SIZE, float(psi[0, 0]), float(th1[0, 0])
    pts = model["points"]
    pts["O3"] = [slide * S, 0.0]
    pts["B"] = [slide * S + S * z[1] * math.cos(psi), S * z[1] * math.sin(psi)]
    pts["D"] = [S * float(Dx[0, 0]), S * float(Dy[0, 0])]
    E = (S * z[7] * math.cos(th1), S * z[7] * math.sin(th1))
    r8 = S * z[7] * z[9] / (z[8] + z[9])
    th8 = float(G[0, 0])
    pts["E"], pts["P"] = list(E), [E[0] + r8 * math.cos(th8), E[1] + r8 * math.sin(th8)]
    ml = mechanism_law(Mechanism.from_dict(model), "output", TH.size)
    assert ml.closed.all() and np.abs(ml.s - (G[0] - G[0, 0])).max() < 1e-9
    rows = {round(r["slide"], 6): r for r in kind.slide_sweep(z, [slide, 1.0])}
    assert rows[slide]["output_swing_deg"] == pytest.approx(math.degrees(np.ptp(G[0])), rel=1e-12)


@pytest.mark.parametrize("target", [HELD, DRIVEN], ids=["held", "driven"])
def test_complex_step_jacobian_matches_central_differences(target):
    kind, z = _z(target)
    pb = LawProblem("gear-lever", target)
    J = pb.jacobian(z)
    h = 1e-6
    for j, n in enumerate(pb.kind.names):
        if n in pb.kind.fixed:
            continue
        e = np.zeros(z.size)
        e[j] = h
        fd = (kind.generate((z + e)[None], TH)[0][0] - kind.generate((z - e)[None], TH)[0][0]) / (2 * h)
        assert np.abs(fd - J[:, j]).max() < 1e-6 * max(1.0, np.abs(J[:, j]).max()), n


@pytest.mark.parametrize("target", [HELD, DRIVEN], ids=["held", "driven"])
def test_polish_from_a_perturbed_gear_lever_recovers_it_to_1e_9(target):
    kind, z0 = _z(target)
    G, _ = kind.generate(z0[None, :], TH)
    pb = LawProblem("gear-lever", law_target(TH, G[0] - G[0, 0], net=target.net), 0.0)
    assert pb.kind.variant == kind.variant
    z1 = z0 + np.array([0.002, -0.002, 0.002, 0.0015, 0.0015, -0.0015, 0.0015, -0.0015, 0, 0, 0, 0])
    # the six-bar's law is nearly blind to one combination of its lengths (the Jacobian's smallest singular
    # value is ~5e-6 of its largest), so the law is recovered to 1e-9 while the lengths are to ~1e-4
    z, k, f = pb.polish(z1, rounds=100)
    assert f < 1e-9
    assert np.abs(z[:8] - z0[:8]).max() < 1e-3
    G1, _ = kind.generate(z[None, :], TH)
    assert np.abs(G1[0] + k - (G[0] - G[0, 0])).max() < 1e-9
    assert np.array_equal(z[8:], z0[8:])  # teeth and branches held


def test_teeth_are_whole_within_bounds_and_the_mesh_assembles():
    law = law_target(TH, math.radians(20) * np.sin(TH) ** 2)
    res = synthesize_law(law, kind="gear-lever", budget=12_000, workers=1, teeth=(20, 40))
    rep = law_report(res)
    z9, z8 = rep["design"]["teeth"].values()
    assert isinstance(z9, int) and isinstance(z8, int) and 20 <= z9 <= 40 and 20 <= z8 <= 40
    model = res.model()
    assert model["gears"]["g9"]["teeth"] == z9 and model["gears"]["g8"]["teeth"] == z8
    # assembly: the gears' centre distance O1 E is m (z9 + z8) / 2
    E = np.array(model["points"]["E"], dtype=float)
    assert float(np.hypot(*E)) == pytest.approx(rep["design"]["module"] * (z9 + z8) / 2, rel=1e-12)
    assert rep["transmission_deg"][0] >= 20 - 1e-9
    rows = rep["design"]["slide_range"]
    assert len(rows) == 9 and any(r["slide"] == pytest.approx(1.0) for r in rows)
    one = next(r for r in rows if r["slide"] == pytest.approx(1.0))
    assert one["feasible"] and one["error_max_deg"] == pytest.approx(rep["error_max_deg"], rel=0.05, abs=1e-6)


def test_driven_variant_takes_the_teeth_the_net_rotation_asks_for_and_refuses_others():
    kind = GL(DRIVEN)
    assert kind.variant == "driven" and list(kind.lo[8:10]) == [17, 34] and list(kind.hi[8:10]) == [17, 34]
    with pytest.raises(GearleverError, match="-360 z9/z8"):
        GL(law_target(TH, TH, net=2 * math.pi)).check()
    with pytest.raises(GearleverError, match="output angle"):
        GL(law_target(TH, np.zeros(TH.size), output="displacement", units="mm")).check()


def test_the_registry_and_so_type_auto_include_the_gear_lever():
    from gearlever.synthesis.law import driver

    assert "gear-lever" in KINDS  # synthesize_law(kind="auto") loops over KINDS
    assert driver.KINDS is KINDS
