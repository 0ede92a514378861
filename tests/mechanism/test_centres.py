"""Instant centres: against the geometry of the four-bar, slider-crank and gear pair, finite
differences of positions (zero relative velocity at the centre) and Kennedy's theorem."""

from __future__ import annotations

import numpy as np
import pytest

from gearlever.mechanism import Mechanism
from gearlever.mechanism.centres import centre_columns, instant_centres, kennedy_defect

from ._models import example

ONE_DOF = ["fourbar", "slider_crank", "whitworth", "watt_sixbar", "geared_fivebar", "engine"]


def _turn(mech, n=73):
    return mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, n, endpoint=False)


def _intersect(p1, p2, p3, p4):
    """Intersection of line p1-p2 with line p3-p4, rows of (N, 2)."""
    d1, d2 = p2 - p1, p4 - p3
    den = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    t = ((p3 - p1)[:, 0] * d2[:, 1] - (p3 - p1)[:, 1] * d2[:, 0]) / den
    return p1 + t[:, None] * d1


def test_fourbar_coupler_ground_centre_is_the_intersection_of_crank_and_rocker_lines():
    mech = Mechanism.load(example("fourbar"))
    r = mech.solve(_turn(mech))
    ic = instant_centres(r)
    P = r.point
    want = _intersect(P["O2"], P["A"], P["O4"], P["B"])
    got = ic.centre("ground", "coupler")
    scale = np.maximum(np.hypot(*want.T), 1.0)[:, None]
    np.testing.assert_allclose(got / scale, want / scale, atol=1e-9)
    # the pins themselves: primary centres
    np.testing.assert_allclose(ic.centre("ground", "crank"), P["O2"], atol=1e-9)
    np.testing.assert_allclose(ic.centre("crank", "coupler"), P["A"], atol=1e-9)
    np.testing.assert_allclose(ic.centre("rocker", "ground"), P["O4"], atol=1e-9)
    # at the sketch O2, A and O4 are collinear: the coupler turns about O4 like the rocker, so
    # coupler and rocker have equal angular velocities and their centre is at infinity
    k = ic.pairs.index("coupler/rocker")
    assert ic.at_infinity[0, k] and np.isnan(ic.xy[0, k]).all()
    assert r.omega["coupler"][0] == pytest.approx(r.omega["rocker"][0], rel=1e-9)
    np.testing.assert_allclose(ic.centre("coupler", "rocker")[1:], P["B"][1:], atol=1e-9)
    assert ic.at_infinity.sum() == 1


def test_slider_crank_piston_ground_centre_is_at_infinity_normal_to_the_guide():
    mech = Mechanism.load(example("slider_crank"))
    r = mech.solve(_turn(mech))
    ic = instant_centres(r)
    k = ic.pairs.index("ground/piston")
    assert ic.at_infinity[:, k].all()
    assert np.isnan(ic.xy[:, k]).all()
    # guide along x: the centre is at infinity along +-y
    np.testing.assert_allclose(np.abs(ic.direction[:, k, 1]), 1.0, atol=1e-12)
    np.testing.assert_allclose(ic.direction[:, k, 0], 0.0, atol=1e-12)
    # the rod/piston centre is the wrist pin B; the rod/ground centre is where the crank line
    # meets the normal to the guide through B
    np.testing.assert_allclose(ic.centre("rod", "piston"), r.point["B"], atol=1e-9)
    want = _intersect(r.point["O2"], r.point["A"], r.point["B"], r.point["B"] + [0.0, 1.0])
    got = ic.centre("ground", "rod")
    fin = np.isfinite(got[:, 0])
    scale = np.maximum(np.hypot(*want.T), 1.0)[:, None]
    np.testing.assert_allclose((got / scale)[fin], (want / scale)[fin], atol=1e-9)
    assert fin.sum() >= len(fin) - 2  # only at the dead points can the crank be parallel to the normal


def test_gear_pair_centre_is_the_pitch_point():
    """External pair z = 20, 30, module 2 on ground pivots 50 apart: the pitch point is 20 from O1."""
    mech = Mechanism.load(example("geared_fivebar"))
    r = mech.solve(_turn(mech))
    ic = instant_centres(r)
    r1 = mech.model.pitch_radius("g1")
    assert r1 == pytest.approx(20.0)
    O1, O2 = np.array(mech.model.points["O1"]), np.array(mech.model.points["O2"])
    want = O1 + r1 * (O2 - O1) / np.linalg.norm(O2 - O1)
    np.testing.assert_allclose(ic.centre("left", "right"), np.broadcast_to(want, (73, 2)), atol=1e-9)


def _fd_relative_velocity(mech, q, P, li, lj, h=1e-6):
    """Velocity of the point at P fixed on link li minus that on link lj, by central differences."""
    m = mech.model

    def carried(link, r0, r1):
        if link == "ground":
            return P.copy()
        i = m.moving.index(link)
        o0, t0 = r0.pose[:, i, :2], r0.pose[:, i, 2]
        o1, t1 = r1.pose[:, i, :2], r1.pose[:, i, 2]
        d = P - o0
        c, s = np.cos(t1 - t0), np.sin(t1 - t0)
        return o1 + np.stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]], axis=1)

    r0 = mech.solve(q)
    rp, rm = mech.solve(q + h), mech.solve(q - h)
    vi = (carried(li, r0, rp) - carried(li, r0, rm)) / (2 * h)
    vj = (carried(lj, r0, rp) - carried(lj, r0, rm)) / (2 * h)
    return vi - vj


@pytest.mark.parametrize("name", ONE_DOF)
def test_centre_has_zero_relative_velocity_by_finite_differences_of_positions(name):
    mech = Mechanism.load(example(name))
    q = _turn(mech, 37) + 0.013
    r = mech.solve(q)
    ic = instant_centres(r)
    L = mech.model.length_scale
    checked = 0
    for p, key in enumerate(ic.pairs):
        a, b = key.split("/")
        P = ic.xy[:, p]
        fin = np.all(np.isfinite(P), axis=1) & (np.hypot(*P.T) < 100 * L)
        if not fin.any():
            continue
        dv = _fd_relative_velocity(mech, q[fin], P[fin], a, b)
        # relative velocity of two generic points of the pair at distance L: |w_a - w_b| L
        wa = r.omega[a][fin]
        wb = r.omega[b][fin]
        ref = np.maximum(np.abs(wa - wb) * L, 1e-3 * L)
        assert np.max(np.hypot(*dv.T) / ref) < 1e-5, key
        checked += 1
    assert checked >= len(ic.pairs) // 2


@pytest.mark.parametrize("name", ONE_DOF)
def test_kennedy_three_centres_are_collinear(name):
    mech = Mechanism.load(example(name))
    r = mech.solve(_turn(mech, 41) + 0.021)
    triples, dev = kennedy_defect(instant_centres(r))
    n = len(mech.model.moving) + 1
    assert len(triples) == n * (n - 1) * (n - 2) // 6
    assert np.isfinite(dev).sum() > 0.5 * dev.size
    assert np.nanmax(dev) < 1e-7


def test_kennedy_defect_detects_a_moved_centre():
    mech = Mechanism.load(example("fourbar"))
    ic = instant_centres(mech.solve(_turn(mech, 5)))
    xy = ic.xy.copy()
    xy[:, ic.pairs.index("ground/coupler")] += [3.0, -2.0]
    bad = type(ic)(ic.links, ic.pairs, xy, ic.at_infinity, ic.direction, ic.closed)
    _, dev = kennedy_defect(bad)
    assert np.nanmax(dev) > 1e-3


def test_pairs_ground_first_then_links_in_model_order():
    mech = Mechanism.load(example("watt_sixbar"))
    ic = mech.instant_centres(_turn(mech, 3))
    assert ic.links == ("ground", "crank", "coupler", "rocker", "link5", "output")
    assert ic.pairs[:3] == ("ground/crank", "ground/coupler", "ground/rocker")
    assert len(ic.pairs) == 15
    assert ic.xy.shape == (3, 15, 2)


def test_parallel_links_give_centre_at_infinity():
    """A parallelogram: the coupler translates, so its centre with ground is at infinity."""
    mech = Mechanism.from_dict(
        {
            "points": {"O2": [0, 0], "O4": [4, 0], "A": [0, 1], "B": [4, 1]},
            "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B"], "rocker": ["O4", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )
    ic = instant_centres(mech.solve(mech.sketch_inputs[0] + np.array([0.0, 0.4, 0.8])))
    k = ic.pairs.index("ground/coupler")
    assert ic.at_infinity[:, k].all()
    # crank and rocker turn together: their centre is at infinity too
    assert ic.at_infinity[:, ic.pairs.index("crank/rocker")].all()
    assert not ic.at_infinity[:, ic.pairs.index("ground/crank")].any()


def test_centre_columns_carry_units_and_match_the_centres():
    mech = Mechanism.load(example("slider_crank"))
    r = mech.solve(_turn(mech, 4))
    cols = centre_columns(r)
    assert "ic_ground/crank_x_mm" in cols and "ic_rod/piston_y_mm" in cols
    np.testing.assert_allclose(cols["ic_ground/crank_x_mm"], 0.0, atol=1e-12)
    assert np.isnan(cols["ic_ground/piston_x_mm"]).all()
    assert len(cols) == 2 * 6
