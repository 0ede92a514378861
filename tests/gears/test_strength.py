"""Tests of gearlever.gears.strength: Lewis, Hertz and AGMA stresses, Shigley's worked example, mechanism cycles."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from gearlever.data import example_path, read_text
from gearlever.errors import GearleverError
from gearlever.gears import strength as s


def _entry(section, name):
    return next(e for e in tomllib.loads(read_text("gear_published.toml"))[section] if e["name"] == name)


def test_shigley_example_14_1_lewis_rating_unverified():
    """UNVERIFIED. Shigley 9th ed., Example 14-1 (P 8, F 1.5 in, 16 teeth, 1200 rev/min, S_y 30 kpsi, n_d 3):
    V 628.3 ft/min (0.05), K_v 1.52 (0.005), Y 0.296 (table), W_t 364 lbf (0.5), H 6.93 hp (0.005, from the
    printed W_t as the book does). Entered from the book, not read in a retrieved copy (verified = false)."""
    e = _entry("lewis", "shigley-example-14-1")
    assert not e["verified"]
    d = e["teeth"] / e["diametral_pitch"]
    v = math.pi * d * e["speed_rpm"] / 12
    assert v == pytest.approx(e["pitch_line_velocity"], abs=0.05)
    kv = float(s.barth_velocity_factor(v, "cut"))
    assert kv == pytest.approx(e["velocity_factor"], abs=0.005)
    y = s.lewis_form_factor(e["teeth"])
    assert y == e["form_factor"]
    allowable = e["yield_strength"] / e["design_factor"]
    assert allowable == e["allowable_stress"]
    # the tangential force whose Lewis stress is the allowable
    wt = allowable / float(s.lewis_bending_stress(1.0, e["face_width"], 1 / e["diametral_pitch"], y, kv))
    assert wt == pytest.approx(e["tangential_force"], abs=0.5)
    assert e["tangential_force"] * v / 33000 == pytest.approx(e["horsepower"], abs=0.005)
    # and back: the stress of that force is the allowable
    assert float(s.lewis_bending_stress(wt, e["face_width"], 1 / 8, y, kv)) == pytest.approx(allowable, rel=1e-12)


def test_shigley_example_14_4_agma_unverified():
    """UNVERIFIED (entered from Shigley 9th ed. without a readable copy). Example 14-4, AGMA 2001-D04 as in
    Shigley ch. 14 (17/52 teeth, P 10, F 1.5 in, 1800 rev/min, 4 hp, Q_v 6, steel on steel).

    Taken from the example (inputs, not computed): J_P 0.30, J_G 0.40 (Fig. 14-6), K_o 1, K_B 1, C_f 1.
    Computed by gearlever: V 801.1 ft/min and W_t 164.8 lbf (to the printed digit), K_v 1.377 (eq. 14-27,
    5e-4), Y from Table 14-2, K_s 1.043/1.052 (sec. 14-10 (a), 5e-4), K_m 1.22 (eq. 14-30, commercial
    enclosed), C_p 2291 (eq. 14-13; the book's Table 14-8 rounds it to 2300, which the stresses below use as
    it does), I 0.121 (eq. 14-23, 5e-4), the pinion's bending stress 6417 psi (eq. 14-15) and contact stress
    70 360 psi (eq. 14-16).  The book rounds each factor before multiplying: gearlever's unrounded chain gives
    6416.9 and 70 331 psi; with the printed factors it gives 6417 and 70 362 (half a unit; 0.05 % for the
    contact stress's 4 printed digits)."""
    e = _entry("agma", "shigley-example-14-4")
    assert not e["verified"]
    zp, zg = e["teeth"]
    p, f = e["diametral_pitch"], e["face_width"]
    dp = zp / p
    v = math.pi * dp * e["speed_rpm"] / 12
    wt = 33000 * e["horsepower"] / v
    assert v == pytest.approx(e["pitch_line_velocity"], abs=0.05)
    assert wt == pytest.approx(e["tangential_force"], abs=0.05)
    kv = float(s.agma_velocity_factor(v, e["quality"]))
    assert kv == pytest.approx(e["dynamic_factor"], abs=0.5e-3)
    ks = [s.agma_size_factor(f, s.lewis_form_factor(z), p) for z in (zp, zg)]
    np.testing.assert_allclose(ks, e["size_factor"], atol=0.5e-3)
    km = s.agma_load_distribution_factor(f, dp, condition="commercial")  # uncrowned, straddle-mounted
    assert km == pytest.approx(e["load_distribution"], abs=0.5e-2)
    cp = s.elastic_coefficient(e["young_modulus"], e["poisson"])
    assert cp == pytest.approx(e["elastic_coefficient"], rel=0.005)  # Table 14-8 rounds 2291 to 2300
    i = s.agma_pitting_geometry_factor(math.radians(e["pressure_angle_deg"]), zg / zp)
    assert i == pytest.approx(e["pitting_geometry_factor"], abs=0.5e-3)
    common = {"overload": e["overload"], "size": e["size_factor"][0], "load_distribution": e["load_distribution"]}
    jp = e["geometry_factor_bending"][0]
    sigma = float(
        s.agma_bending_stress(
            e["tangential_force"], f, 1 / p, jp, dynamic=e["dynamic_factor"], rim_thickness=e["rim_thickness"], **common
        )
    )
    assert sigma == pytest.approx(e["bending_stress_pinion"], abs=0.5)
    sigma_c = float(
        s.agma_contact_stress(
            e["tangential_force"],
            f,
            dp,
            e["pitting_geometry_factor"],
            e["elastic_coefficient"],
            dynamic=e["dynamic_factor"],
            surface_condition=e["surface_condition"],
            **common,
        )
    )
    assert sigma_c == pytest.approx(e["contact_stress_pinion"], rel=0.5e-3)
    # gearlever's own chain, unrounded, within the book's rounding of its factors
    own = float(s.agma_bending_stress(wt, f, 1 / p, jp, dynamic=kv, size=ks[0], load_distribution=km))
    assert own == pytest.approx(e["bending_stress_pinion"], rel=2e-3)
    own_c = float(
        s.agma_contact_stress(wt, f, dp, i, e["elastic_coefficient"], dynamic=kv, size=ks[0], load_distribution=km)
    )
    assert own_c == pytest.approx(e["contact_stress_pinion"], rel=2e-3)


def test_lewis_form_factor_from_the_generated_tooth_near_shigleys_table():
    """Lewis's parabola on the rack-generated tooth (fillet 0.300 as the table's) lies 0 to 9 % below Table 14-2:
    a consistency check of the construction, not a printed-digit check (the table's teeth were not cut by this rack)."""
    tab = tomllib.loads(read_text("gear_published.toml"))["lewis_form_factor"]
    for z, y in zip(tab["teeth"], tab["Y"]):
        yg = s.lewis_form_factor_geometry(z, root_radius=0.3)
        assert 0.91 * y < yg <= 1.0 * y, z
    # monotone in the teeth and raised by a positive shift
    assert s.lewis_form_factor_geometry(14, 0.4) > s.lewis_form_factor_geometry(14)


def test_hertz_equals_johnsons_line_contact():
    """sigma_C = C_p sqrt(K_v W_t / (F cos phi) (1/r1 + 1/r2)) equals Hertz's p0 = sqrt(P' E* / (pi R)) with the
    flanks' radii at the pitch point (K. L. Johnson, Contact Mechanics, 1985, eq. 4.45)."""
    e1, n1, e2, n2 = 210e3, 0.3, 110e3, 0.28  # MPa
    cp = s.elastic_coefficient(e1, n1, e2, n2)
    wt, b, d1, d2, phi = 2500.0, 20.0, 40.0, 120.0, math.radians(20)
    r1, r2 = d1 * math.sin(phi) / 2, d2 * math.sin(phi) / 2
    estar = 1 / ((1 - n1**2) / e1 + (1 - n2**2) / e2)
    p_line = wt / math.cos(phi) / b
    p0 = math.sqrt(p_line * estar * (1 / r1 + 1 / r2) / math.pi)
    assert float(s.hertz_contact_stress(wt, b, d1, d2, cp, phi)) == pytest.approx(p0, rel=1e-12)
    # internal: the ring's curvature is subtracted
    p0i = math.sqrt(p_line * estar * (1 / r1 - 1 / r2) / math.pi)
    assert float(s.hertz_contact_stress(wt, b, d1, d2, cp, phi, internal=True)) == pytest.approx(p0i, rel=1e-12)


def test_agma_factors_and_stresses():
    """AGMA (Shigley 9th ed. eq. 14-15, 14-16, 14-23, 14-27): stress proportional to each factor; I for 20 deg,
    17/52 teeth = cos sin / 2 * 52/69; K_v at Q_v 6, 1000 ft/min by eq. 14-27."""
    i = s.agma_pitting_geometry_factor(math.radians(20), 52 / 17)
    assert i == pytest.approx(math.cos(math.radians(20)) * math.sin(math.radians(20)) / 2 * 52 / 69, rel=1e-14)
    b = 0.25 * 6 ** (2 / 3)
    a = 50 + 56 * (1 - b)
    assert float(s.agma_velocity_factor(1000.0, 6)) == pytest.approx(((a + math.sqrt(1000)) / a) ** b, rel=1e-14)
    assert float(s.agma_velocity_factor(1000.0 * 0.00508, 6, units="m/s")) == pytest.approx(
        float(s.agma_velocity_factor(1000.0, 6)), rel=5e-3
    )  # the SI form's sqrt(200 V) rounds 196.85 ft/min per m/s to 200
    base = float(s.agma_bending_stress(100.0, 1.0, 0.1, 0.3))
    assert base == pytest.approx(100 / (1 * 0.1 * 0.3))
    k = dict(overload=1.25, dynamic=1.4, size=1.05, load_distribution=1.2, rim_thickness=1.1)
    assert float(s.agma_bending_stress(100.0, 1.0, 0.1, 0.3, **k)) == pytest.approx(
        base * 1.25 * 1.4 * 1.05 * 1.2 * 1.1
    )
    c0 = float(s.agma_contact_stress(100.0, 1.0, 2.0, i, 2300.0))
    assert c0 == pytest.approx(2300 * math.sqrt(100 / (2.0 * 1.0 * i)))
    arr = s.agma_contact_stress(np.array([100.0, 400.0]), 1.0, 2.0, i, 2300.0)
    assert arr[1] == pytest.approx(2 * arr[0])


def test_stress_arrays_and_safety_factors():
    w = np.linspace(-50, 150, 9)
    sig = s.lewis_bending_stress(w, 10.0, 2.0, 0.3)
    assert sig.shape == (9,) and np.all(sig >= 0)
    np.testing.assert_allclose(sig, np.abs(w) / (10 * 2 * 0.3))
    sf = s.safety_factor(100.0, sig)
    assert np.isinf(sf[2]) and sf[-1] == pytest.approx(100 / sig[-1])
    with pytest.raises(GearleverError, match="face_width"):
        s.lewis_bending_stress(w, 0.0, 2.0, 0.3)
    with pytest.raises(GearleverError, match="teeth"):
        s.lewis_form_factor(5)


def test_mesh_stresses_over_the_geared_fivebar_cycle():
    """mesh_stresses turns the inverse dynamics' tangential tooth force into Lewis and Hertz stresses row by row;
    the worst row is the largest |W_t|; safety factors are allowable / stress."""
    import gearlever

    mech = gearlever.Mechanism.load(example_path("geared_fivebar.toml"))
    q = np.linspace(0, 2 * np.pi, 25)
    res = mech.inverse_dynamics(q, 1.0, 0.0, loads=[{"link": "link4", "point": "C", "force": [0, -100.0]}])
    out = s.mesh_stresses(mech, res, face_width=8.0, allowables={"bending": 200.0, "contact": 900.0})
    (ms,) = out.values()
    w = res.mesh_tangential["g1-g2"]
    m = mech.model.module
    for k, gear in enumerate(("g1", "g2")):
        y = s.lewis_form_factor_geometry(mech.model.gears[gear].teeth)
        np.testing.assert_allclose(ms.bending_stress[:, k], np.abs(w) / (8.0 * m * y), rtol=1e-12)
        np.testing.assert_allclose(ms.bending_safety[:, k], 200.0 / ms.bending_stress[:, k], rtol=1e-12)
    cp = 189.8
    d1, d2 = m * 20, m * 30
    phi = res.pressure_angle
    ref = cp * np.sqrt(np.abs(w) / (8.0 * math.cos(phi)) * (2 / (d1 * math.sin(phi)) + 2 / (d2 * math.sin(phi))))
    np.testing.assert_allclose(ms.contact_stress, ref, rtol=1e-12)
    assert ms.worst_row == int(np.argmax(np.abs(w)))
    assert ms.angle[ms.worst_row] == q[ms.worst_row]
    # the tooth forces are the inverse dynamics' (checked by equilibrium in tests/mechanism); along the line of
    # action the force is |W_t| / cos(phi)
    np.testing.assert_allclose(res.mesh_force["g1-g2"], np.abs(w) / math.cos(phi), rtol=1e-12)


def test_mesh_stresses_refusals():
    import gearlever

    mech = gearlever.Mechanism.load(example_path("geared_fivebar.toml"))
    res = mech.inverse_dynamics(np.linspace(0, 1, 3), 1.0, 0.0)
    with pytest.raises(GearleverError, match="face_width"):
        s.mesh_stresses(mech, res)
    with pytest.raises(GearleverError, match="result must be an InverseDynamics"):
        s.mesh_stresses(mech, object(), face_width=5.0)


def test_agma_load_distribution_factor_pieces():
    """K_m = 1 + C_mc (C_pf C_pm + C_ma C_e) (Shigley 9th ed. eq. 14-30 to 14-35): C_pf's three pieces meet at
    F = 1 and 17 in (to 2e-4, the book's rounding), the F/(10 d) floor of 0.05, each modifier's factor, and the
    refusals naming the parameter."""
    km = s.agma_load_distribution_factor
    for edge in (1.0, 17.0):
        assert km(edge - 1e-9, 20.0) == pytest.approx(km(edge + 1e-9, 20.0), abs=2e-4)
    base = km(2.0, 4.0, condition="precision")
    cpf = max(2.0 / 40.0, 0.05) - 0.0375 + 0.0125 * 2.0
    cma = 0.0675 + 0.0128 * 2.0 - 0.926e-4 * 4.0
    assert base == pytest.approx(1 + cpf + cma, rel=1e-14)
    assert km(2.0, 4.0, condition="precision", crowned=True) - 1 == pytest.approx(0.8 * (base - 1), rel=1e-14)
    assert km(2.0, 4.0, condition="precision", straddle_offset=0.2) == pytest.approx(base + 0.1 * cpf, rel=1e-14)
    assert km(2.0, 4.0, condition="precision", adjusted=True) == pytest.approx(base - 0.2 * cma, rel=1e-14)
    assert km(0.5, 100.0) == pytest.approx(1 + 0.05 - 0.025 + 0.127 + 0.0158 * 0.5 - 0.930e-4 * 0.25, rel=1e-14)
    with pytest.raises(GearleverError, match="condition"):
        km(1.0, 2.0, condition="sloppy")
    with pytest.raises(GearleverError, match="face_width"):
        km(41.0, 30.0)
    with pytest.raises(GearleverError, match="straddle_offset"):
        km(1.0, 2.0, straddle_offset=0.6)
    assert s.agma_size_factor(1.5, 0.303, 10.0) == pytest.approx(1.192 * (1.5 * 0.303**0.5 / 10) ** 0.0535)
    with pytest.raises(GearleverError, match="diametral_pitch"):
        s.agma_size_factor(1.5, 0.303, 0.0)
