"""Tooth geometry of a model's meshes (gearlever.mechanism.mesh_check) against the handbooks' worked values."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.mesh_check import check_mechanism, involute, mesh_geometry

GEARED = ["geared_fivebar", "planetary", "compound_planetary", "ferguson", "zrdpm_gear_contour"]


def test_shifted_spur_pair_matches_khk_worked_example():
    # KHK, Gear Technical Reference, "Calculation of profile shifted spur gears": m 3, alpha 20 deg,
    # z 12 and 24, x 0.6 and 0.36: inv alpha_w 0.034316, alpha_w 26.0886 deg, a 56.4999 mm
    g = mesh_geometry(3.0, (12, 24), shift=(0.6, 0.36))
    assert g.tight_center_distance == pytest.approx(56.4999, abs=1e-4)
    assert math.degrees(g.working_pressure_angle[0]) == pytest.approx(26.0886, abs=1e-4)
    assert float(involute(g.working_pressure_angle[0])) == pytest.approx(0.034316, abs=1e-6)
    assert g.backlash[0] == pytest.approx(0.0, abs=1e-12)


def test_undercut_limit_is_17_teeth_at_20_degrees():
    # Shigley's Mechanical Engineering Design (10th ed.), eq. 13-11: N_P = 2 k / sin^2 phi = 17.1 for a rack,
    # so 17 teeth undercut and 18 do not; a shift x = 1 - 17 sin^2(20 deg) / 2 = 0.0056 cures 17
    assert mesh_geometry(1.0, (17, 60)).undercut.tolist() == [True, False]
    assert mesh_geometry(1.0, (18, 60)).undercut.tolist() == [False, False]
    assert mesh_geometry(1.0, (17, 60), shift=(0.006, 0.0)).undercut.tolist() == [False, False]


def test_backlash_grows_as_2_tan_alpha_w_per_unit_centre_distance():
    # KHK, "Backlash": j_t = 2 tan(alpha_w) delta_a for a small centre-distance change (finite difference)
    g0 = mesh_geometry(2.0, (20, 30), shift=(0.3, -0.1))
    a0, h = g0.tight_center_distance, 1e-6
    g = mesh_geometry(2.0, (20, 30), shift=(0.3, -0.1), center_distance=[a0 - h, a0 + h])
    slope = (g.backlash[1] - g.backlash[0]) / (2 * h)
    assert slope == pytest.approx(2 * math.tan(g0.working_pressure_angle[0]), rel=1e-6)
    # an internal pair jams the other way: a larger centre distance takes backlash away
    gi = mesh_geometry(2.0, (20, 60), internal=(False, True), center_distance=[39.9, 40.1])
    assert gi.backlash[0] > 0 > gi.backlash[1]


def test_contact_ratio_of_a_standard_pair_against_the_line_of_action():
    # eps = (length of the path of contact) / base pitch, the path found by intersecting the tip circles
    # with the line of action numerically (not the closed form)
    m, z1, z2, a = 2.0, 20, 30, 50.0
    alpha = math.radians(20)
    rb1, rb2 = m * z1 / 2 * math.cos(alpha), m * z2 / 2 * math.cos(alpha)
    ra1, ra2 = m * z1 / 2 + m, m * z2 / 2 + m
    # line of action through the pitch point P = (r1, 0), direction (sin alpha, cos alpha) from pinion centre O1
    p = np.array([m * z1 / 2, 0.0])
    u = np.array([math.sin(alpha), math.cos(alpha)])
    t = np.linspace(-20, 20, 400001)
    pts = p + t[:, None] * u
    inside1 = np.hypot(*pts.T) <= ra1
    inside2 = np.hypot(pts[:, 0] - a, pts[:, 1]) <= ra2
    both = t[inside1 & inside2]
    eps = (both.max() - both.min()) / (math.pi * m * math.cos(alpha))
    g = mesh_geometry(m, (z1, z2))
    assert g.contact_ratio_transverse[0] == pytest.approx(eps, abs=1e-3)
    assert rb1 < ra1 and rb2 < ra2


def test_internal_involute_interference_follows_the_khk_criterion():
    # KHK, "Internal gears": no involute interference when z1/z2 >= 1 - tan(alpha_a2) / tan(alpha_w)
    for z1 in range(12, 40):
        g = mesh_geometry(2.0, (z1, 60), internal=(False, True))
        ra2, rb2 = g.tip_diameter[1] / 2, g.base_diameter[1] / 2
        limit = 1 - math.sqrt(ra2**2 - rb2**2) / rb2 / math.tan(g.working_pressure_angle[0])
        assert bool(g.interference[0]) == (z1 / 60 < limit)


def test_helical_overlap_ratio():
    # eps_beta = b sin(beta) / (pi m_n)
    g = mesh_geometry(2.0, (20, 40), helix=math.radians(15), face_width=20.0)
    assert g.contact_ratio_overlap[0] == pytest.approx(20 * math.sin(math.radians(15)) / (2 * math.pi), rel=1e-12)
    assert g.tight_center_distance == pytest.approx(2 * 60 / (2 * math.cos(math.radians(15))), rel=1e-12)


@pytest.mark.parametrize("name", GEARED)
def test_every_shipped_example_with_gears_is_checked(name):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    checks = check_mechanism(mech, points=24)
    assert [c.mesh for c in checks] == [m.name for m in mech.model.meshes]
    for c in checks:
        assert c.over == "constant"  # every shipped mesh has a carrier holding its centre distance
        assert np.isfinite(c.sketch.contact_ratio_total).all()


def test_shipped_examples_flags():
    flags = {c.mesh: c.flags for c in check_mechanism(Mechanism.load(example_path("planetary.toml")))}
    # 18 teeth in a 60-tooth ring: 18/60 < 1 - tan(alpha_a2)/tan(alpha_w) = 0.337 (KHK criterion)
    assert all("interferes" in f[0] for k, f in flags.items() if k.endswith("ring"))
    assert all(not f for k, f in flags.items() if k.startswith("sun"))
    fer = {c.mesh: c for c in check_mechanism(Mechanism.load(example_path("ferguson.toml")))}
    # 20 + 101 teeth at module 1 on a 60 centre distance (reference 60.5): needs a negative shift sum
    assert fer["planet-z101"].shift_sum < 0 and any("jams" in f for f in fer["planet-z101"].flags)
    assert fer["planet-z99"].shift_sum > 0 and fer["planet-z100"].shift_sum == pytest.approx(0, abs=1e-12)


def test_zrdpm_adjusting_slide_range():
    mech = Mechanism.load(example_path("zrdpm_gear_contour.toml"))
    (c,) = check_mechanism(mech, points=501, adjust={"z9-z8": (44.0, 49.0)})
    g = c.sweep
    assert c.over == "adjustment" and g.tight_center_distance == pytest.approx(45.0)
    assert (g.jammed == (g.center_distance < 45.0 - 1e-9)).all()
    # contact is lost where the path of contact falls below one base pitch
    last = g.center_distance[g.contact_ratio_total >= 1].max()
    assert 46.2 < last < 46.4
    assert any(f.startswith("jams") for f in c.flags) and any(f.startswith("loses contact") for f in c.flags)


def test_cycle_path_reports_the_worst_angle():
    # a mesh whose centre distance changes as the mechanism moves (a model with no common carrier):
    # a stand-in for the solved result with the gear centres moving apart over the turn
    mech = Mechanism.load(example_path("geared_fivebar.toml"))
    n = 36
    q = np.linspace(0, 2 * np.pi, n, endpoint=False)[:, None]
    a = 50 + 0.8 * np.sin(q[:, 0])
    fake = SimpleNamespace(
        model=mech.model,
        sketch_inputs=mech.sketch_inputs,
        solve=lambda qq: SimpleNamespace(
            q=q,
            closed=np.ones(n, bool),
            point={"O1": np.zeros((n, 2)), "O2": np.stack([a, 0 * a], axis=1)},
        ),
    )
    (c,) = check_mechanism(fake, points=n)
    assert c.over == "cycle"
    i = int(np.argmin(c.sweep.contact_ratio_total))
    assert math.degrees(c.angle[i]) == pytest.approx(90.0)
    assert any(f.startswith("jams") and "= 190 deg" in f for f in c.flags)


def test_bad_input_is_refused_naming_it():
    with pytest.raises(GearleverError, match="module"):
        mesh_geometry(0.0, (20, 30))
    with pytest.raises(GearleverError, match="helix"):
        mesh_geometry(1.0, (20, 30), helix=math.radians(45))
    mech = Mechanism.load(example_path("zrdpm_gear_contour.toml"))
    with pytest.raises(GearleverError, match="unknown mesh 'z8-z9'"):
        check_mechanism(mech, adjust={"z8-z9": (44.0, 46.0)})


@pytest.mark.parametrize(
    "teeth, shift, internal, helix",
    [
        ((20, 30), (0.3, -0.1), (False, False), 0.0),
        ((17, 45), (0.2, 0.4), (False, False), 0.3),
        ((16, 24), (0.0, 0.5), (False, True), 0.0),
        ((60, 18), (0.2, 0.1), (True, False), 0.2),
    ],
)
def test_centre_distance_sweep_agrees_with_gears_geometry(teeth, shift, internal, helix):
    # the vectorised sweep against gears.geometry's scalar mesh and backlash (its own derivation of j_bt)
    from gearlever.gears.geometry import backlash, mesh

    ring = internal[0]
    order = (1, 0) if ring else (0, 1)
    kind = "internal" if any(internal) else "external"
    ref = mesh(
        2.0, teeth[order[0]], teeth[order[1]], shift[order[0]], shift[order[1]], kind=kind, helix=helix, check=False
    )
    deltas = np.array([0.0, 0.05, -0.05, 0.2])
    g = mesh_geometry(2.0, teeth, shift, internal, helix=helix, center_distance=ref.center_distance + deltas)
    assert g.tight_center_distance == pytest.approx(ref.center_distance, rel=1e-12)
    assert g.working_pressure_angle[0] == pytest.approx(ref.working_pressure_angle, rel=1e-12)
    assert g.contact_ratio_transverse[0] == pytest.approx(ref.contact_ratio_transverse, rel=1e-12)
    assert g.backlash[0] == pytest.approx(0.0, abs=1e-12)  # the tight mesh has none, by definition
    for dlt, j, aw in zip(deltas, g.backlash, g.working_pressure_angle):
        b = backlash(ref, center_distance_change=float(dlt))
        assert aw == pytest.approx(b["working_pressure_angle"], rel=1e-12)
        assert j == pytest.approx(b["circumferential"], abs=1e-12)
