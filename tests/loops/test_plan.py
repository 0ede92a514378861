"""Velocity and acceleration plans: numbers (gearlever.loops.plan) and drawings (plotting.plans)."""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from PIL import Image

from gearlever.loops import (
    acceleration_plan,
    closed,
    double_slider,
    double_slider_system,
    fourbar,
    fourbar_system,
    inverted_slider_crank,
    inverted_slider_crank_system,
    slider_crank,
    slider_crank_system,
    velocity_plan,
)


def sides(terms):
    return (sum((t.value for t in terms if t.side > 0), 0j), sum((t.value for t in terms if t.side < 0), 0j))


CASES = [
    (
        fourbar_system(9, 5, 8, 8),
        lambda th: fourbar_system(9, 5, 8, 8).solve(
            th,
            {
                "theta3": float(fourbar(9, 5, 8, 8, th[:1]).theta3[0]),
                "theta4": float(fourbar(9, 5, 8, 8, th[:1]).theta4[0]),
            },
        ),
    ),
    (slider_crank_system(1.0, 3.0, 0.4), lambda th: slider_crank(1.0, 3.0, th, 0.4)),
    (inverted_slider_crank_system(4.0, 1.5, 0.5), lambda th: inverted_slider_crank(4.0, 1.5, th, 0.5)),
    (double_slider_system(21.0, 1.0), lambda th: double_slider(21.0, 1.0, th)),
]


@pytest.mark.parametrize("case", range(len(CASES)))
@pytest.mark.parametrize("theta", [0.3, 2.0, 4.4])
def test_both_sides_of_every_plan_meet(case, theta):
    system, solve = CASES[case]
    sol = solve(np.array([theta]))
    for terms in (
        velocity_plan(system, sol, 0, omega=1.3),
        acceleration_plan(system, sol, 0, omega=1.3, alpha=-0.7),
    ):
        lhs, rhs = sides(terms)
        assert abs(lhs - rhs) <= 1e-12 * max(1.0, max(abs(t.value) for t in terms))


def test_inverted_slider_crank_plan_has_a_coriolis_term():
    sol = inverted_slider_crank(4.0, 1.5, np.array([1.0]), 0.5)
    kinds = {(t.vector, t.kind) for t in acceleration_plan(inverted_slider_crank_system(4.0, 1.5, 0.5), sol)}
    assert ("AO4", "c") in kinds and ("AO4", "s") in kinds


def test_fourbar_plan_terms_equal_the_rocker_acceleration():
    th, w, al = 1.1, 2.0, 0.5
    r = fourbar(9, 5, 8, 8, [th])
    system = fourbar_system(9, 5, 8, 8)
    sol = system.solve([th], {"theta3": float(r.theta3[0]), "theta4": float(r.theta4[0])})
    terms = {(t.vector, t.kind): t.value for t in acceleration_plan(system, sol, 0, w, al)}
    w4 = r.dtheta4_dphi[0] * w
    a4 = r.d2theta4_dphi2[0] * w**2 + r.dtheta4_dphi[0] * al
    e4 = np.exp(1j * r.theta4[0])
    assert abs(terms[("B", "n")] - (-8 * w4**2 * e4)) < 1e-12
    assert abs(terms[("B", "t")] - (8j * a4 * e4)) < 1e-12
    assert abs(terms[("A", "t")] - 5j * al * np.exp(1j * th)) < 1e-12


@pytest.mark.parametrize("phi_deg", [0.0, 30.0, 90.0, 200.0])
def test_zrdpm_plan_is_paper_eq_19_20_with_eq_16(phi_deg):
    l, w, al = 21.0, 1.5, 0.4
    phi = math.radians(phi_deg)
    terms = {
        (t.vector, t.kind): t.value
        for t in acceleration_plan(double_slider_system(l, 0.0), double_slider(l, 0.0, [phi]), 0, w, al)
    }
    # a_B along x and a_A along y (their guides)
    assert abs(terms[("B", "s")].imag) < 1e-12 and abs(terms[("A", "s")].real) < 1e-12
    xb, ya, dxb, dya, d2xb, d2ya = closed.double_slider_projections(l, 0.0, phi)
    assert abs(terms[("B", "s")].real - (d2xb * w**2 + dxb * al)) < 1e-12
    assert abs(terms[("A", "s")].imag - (d2ya * w**2 + dya * al)) < 1e-12
    # relative acceleration of B about A (link BA at -phi, u = -1, e = -alpha/omega^2): eq. 16
    ax, ay = closed.point_acceleration(l, -phi, -1.0, -al / w**2)
    rel = terms[("BA", "n")] + terms[("BA", "t")]
    assert abs(rel - complex(ax, ay) * w**2) < 1e-11
    # eq. 19: a_B = a_A + a_BA^n + a_BA^t
    assert abs(terms[("B", "s")] - (terms[("A", "s")] + rel)) < 1e-11


def test_plan_of_an_invalid_point_raises():
    sol = fourbar_system(9, 7, 8, 7).solve(np.array([0.0, 3.0]), {"theta3": 0.9, "theta4": 1.2})
    assert not sol.valid[1]
    with pytest.raises(ValueError, match="index"):
        velocity_plan(fourbar_system(9, 7, 8, 7), sol, 1)
    with pytest.raises(ValueError, match="index"):
        velocity_plan(fourbar_system(9, 7, 8, 7), sol, 5)


def test_plan_figures_are_written(tmp_path):
    from gearlever.plotting._common import save
    from gearlever.plotting.fourbar import fourbar_curves
    from gearlever.plotting.plans import fourbar_plans, zrdpm_acceleration_plan

    ax = zrdpm_acceleration_plan(21.0, 0.0, 30.0, alpha=0.5)
    assert ax.get_title() and ax.get_xlabel().endswith("(cm/s²)") and ax.get_legend() is not None
    texts = {t.get_text() for t in ax.texts}
    assert {"$a_B$", "$a_A$", "$a_{BA}^n$", "$a_{BA}^t$"} <= texts
    files = [
        save(ax.figure, tmp_path / "z.png"),
        save(fourbar_plans(9, 5, 8, 8, 60.0), tmp_path / "p.png"),
        save(fourbar_curves(9, 7, 8, 7, points=181), tmp_path / "c.png"),
    ]
    for f in files:
        with Image.open(f) as im:
            assert im.format == "PNG" and im.size[0] > 300 and im.size[1] > 300
