"""Parts of a mechanism for CAD (gearlever.export.outline): outlines around the pins, holes at the joints, gears."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.export.outline import _hull, mechanism_drawing, rounded_hull, slot
from gearlever.mechanism import Mechanism

GEARED = ["geared_fivebar", "planetary", "compound_planetary", "ferguson", "zrdpm_gear_contour"]


def _distance_to_polygon(pts, poly):
    """Least distance from each point to the closed polygon's edges."""
    a, b = poly, np.roll(poly, -1, axis=0)
    ab = b - a
    t = np.clip(np.einsum("pij,ij->pi", pts[:, None, :] - a, ab) / np.einsum("ij,ij->i", ab, ab), 0, 1)
    near = a + t[..., None] * ab
    return np.linalg.norm(pts[:, None, :] - near, axis=2).min(axis=1)


def test_slot_and_hull_keep_the_half_width_from_every_pin():
    for pts in ([(0, 0), (10, 3)], [(0, 0), (10, 0), (5, 8)], [(0, 0), (4, 0), (4, 4), (0, 4), (2, 1)]):
        outline = rounded_hull(pts, 1.5)
        sag = 1.5 * (1 - math.cos(math.pi / 2 / 24))  # chords of the arcs (25 points a half turn)
        d = _distance_to_polygon(np.array(pts, dtype=float), outline)
        assert (d >= 1.5 - sag - 1e-12).all()
        # and the outline hugs the hull: every outline point is 1.5 from the hull of the pins
        hull = _hull(np.array(pts, dtype=float))
        dist = _distance_to_polygon(outline, hull)
        assert dist.max() == pytest.approx(1.5, abs=1e-9) and dist.min() >= 1.5 - sag - 1e-12
    s = slot((0, 0), (10, 0), 2.0)
    assert s[:, 0].min() == pytest.approx(-2.0) and s[:, 0].max() == pytest.approx(12.0)


def test_holes_are_where_the_model_puts_the_joints():
    mech = Mechanism.load(example_path("fourbar.toml"))
    d = mechanism_drawing(mech, pin_diameter=2.0)
    m = mech.model
    for part in d.parts:
        centres = {tuple(np.round(c, 9)) for c, r in part.holes}
        assert centres == {tuple(np.round(m.points[p], 9)) for p in m.links[part.name].points}
        assert all(r == 1.0 for _, r in part.holes)


def test_pose_at_inputs_matches_the_solved_mechanism():
    mech = Mechanism.load(example_path("fourbar.toml"))
    q = math.radians(30.0)
    d = mechanism_drawing(mech, {"crank": q})
    r = mech.solve(np.array([[q]]))
    coupler = next(p for p in d.parts if p.name == "coupler")
    got = sorted(tuple(np.round(c, 9)) for c, _ in coupler.holes)
    want = sorted(tuple(np.round(r.point[p][0], 9)) for p in ("A", "B", "P"))
    assert got == want
    # the body frame puts the first point at the origin, the second on +x
    local = coupler.local()
    a, b = (np.array(local.holes[i][0]) for i in range(2))
    assert np.allclose(a, 0, atol=1e-9) and abs(b[1]) < 1e-9 and b[0] > 0


@pytest.mark.parametrize("name", GEARED)
def test_gears_are_whole_tooth_outlines_with_a_bore(name):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    d = mechanism_drawing(mech)
    m = mech.model
    for gname, g in m.gears.items():
        part = next(p for p in d.parts if p.name == g.link)
        c = np.array(m.points[g.centre])
        outline = max(part.outlines, key=lambda o: -abs(np.hypot(*(o - c).T).mean() - m.pitch_radius(gname)))
        rad = np.hypot(*(outline - c).T)
        # the teeth straddle the pitch circle, and as many tips as teeth (local maxima of the radius)
        rp = m.pitch_radius(gname)
        assert rad.min() < rp < rad.max()
        tips = np.flatnonzero(rad > rad.max() - 1e-9 * rp)
        runs = 1 + np.count_nonzero(np.diff(tips) > 1) - (tips[0] == 0 and tips[-1] == len(rad) - 1)
        assert runs == g.teeth
        assert any(np.allclose(h[0], c) for h in part.holes) or g.internal


def test_meshing_teeth_interleave_without_overlap():
    # tight mesh: the tooth outlines touch but do not cross; the drawn teeth sit in the mate's spaces
    from matplotlib.path import Path

    mech = Mechanism.load(example_path("geared_fivebar.toml"))
    d = mechanism_drawing(mech)
    g1 = next(p for p in d.parts if p.name == "left").outlines[0]
    g2 = next(p for p in d.parts if p.name == "right").outlines[0]
    inside = Path(g2).contains_points(g1, radius=-1e-3 * 2)  # shrunk by 0.002 mm: touching is allowed
    assert not inside.any()
    # the control: g1 turned by half a pitch (pi / 20) about its centre O1 = (0, 0) puts its teeth into g2's
    t = math.pi / 20
    turned = g1 @ np.array([[math.cos(t), math.sin(t)], [-math.sin(t), math.cos(t)]])
    assert Path(g2).contains_points(turned, radius=-1e-3 * 2).sum() > 10


@pytest.mark.parametrize("deg", [30.0, 77.0, 200.0])
def test_gears_still_mesh_at_a_pose(deg):
    # the gears turn with their links (20 : 30 teeth), so the teeth stay interleaved at any crank angle
    from matplotlib.path import Path

    mech = Mechanism.load(example_path("geared_fivebar.toml"))
    d = mechanism_drawing(mech, {"left": math.radians(deg)})
    g1 = next(p for p in d.parts if p.name == "left").outlines[0]
    g2 = next(p for p in d.parts if p.name == "right").outlines[0]
    assert not Path(g2).contains_points(g1, radius=-1e-3 * 2).any()


def test_bad_input_is_named():
    mech = Mechanism.load(example_path("fourbar.toml"))
    with pytest.raises(GearleverError, match="inputs: unknown input 'crnak'"):
        mechanism_drawing(mech, {"crnak": 0.3})
    with pytest.raises(GearleverError, match="pin_diameter must be a positive number"):
        mechanism_drawing(mech, pin_diameter=-1.0)
