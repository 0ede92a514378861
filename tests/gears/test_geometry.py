"""Tests of gearlever.gears.geometry: tooth outline, mesh geometry and published worked examples."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.gears import geometry as g

CASES = [
    (3.0, 12, 0.6, {}),
    (2.0, 20, 0.0, {}),
    (1.0, 8, 0.0, {}),  # undercut
    (1.0, 10, 0.2, {}),  # undercut
    (1.0, 40, -0.3, {}),
    (2.0, 30, 0.1, {"helix": math.radians(20)}),
    (2.0, 60, 0.0, {"internal": True}),
    (2.0, 24, 0.3, {"internal": True}),
    (1.5, 45, -0.2, {"internal": True, "helix": math.radians(15)}),
]


def _crossings(xy, radius):
    r = np.hypot(xy[:, 0], xy[:, 1])
    above = r > radius
    return int(np.count_nonzero(above & ~np.roll(above, 1)))


@pytest.mark.parametrize(("m", "z", "x", "kw"), CASES)
def test_flank_on_analytic_involute_to_1e9_module(m, z, x, kw):
    """Every flank point lies on the involute theta = s/(2r) + inv alpha_t - inv alpha_R (ISO 21771, eq. 54)."""
    p = g.tooth_profile(m, z, x, **kw)
    beta = kw.get("helix", 0.0)
    mt = m / math.cos(beta)
    at = math.atan(math.tan(math.radians(20)) / math.cos(beta))
    r = mt * z / 2
    rb = r * math.cos(at)
    s_half = (math.pi * mt / 4 + x * m * math.tan(at)) / r
    i0, i1 = p.flank
    assert i1 - i0 >= 20
    for sign in (1.0, -1.0):
        f = p.points[i0:i1] * np.array([1.0, sign])
        R = np.hypot(f[:, 0], f[:, 1])
        th = np.abs(np.arctan2(f[:, 1], f[:, 0]))
        aR = np.arccos(np.clip(rb / R, -1, 1))
        expected = s_half + g.involute(at) - (np.tan(aR) - aR)
        assert np.max(np.abs(R * (th - expected))) < 1e-9 * m


@pytest.mark.parametrize(("m", "z", "x", "kw"), CASES)
def test_outline_teeth_tip_and_root_circles(m, z, x, kw):
    """The outline has `teeth` teeth; its extreme radii are the tip and root radii (ISO 21771 eq. 20-23)."""
    xy = g.tooth_outline(m, z, x, **kw)
    p = g.tooth_profile(m, z, x, **kw)
    r = np.hypot(xy[:, 0], xy[:, 1])
    beta = kw.get("helix", 0.0)
    d = m * z / math.cos(beta)
    if kw.get("internal"):
        assert r.min() == pytest.approx(max((d - 2 * (1 - x) * m) / 2, p.base_radius), abs=1e-9 * m)
        assert r.max() == pytest.approx(d / 2 + (1.25 + x) * m, abs=1e-9 * m)
    else:
        assert r.max() == pytest.approx(d / 2 + (1 + x) * m, abs=1e-9 * m)
        assert r.min() == pytest.approx(d / 2 - (1.25 - x) * m, abs=1e-9 * m)
    assert _crossings(xy, p.reference_radius) == z
    # counter-clockwise (positive shoelace area)
    area = 0.5 * np.sum(xy[:, 0] * np.roll(xy[:, 1], -1) - np.roll(xy[:, 0], -1) * xy[:, 1])
    assert area > 0
    assert xy.shape == (z * (len(p.points) - 1), 2)


def test_outline_rejects_bad_input():
    with pytest.raises(GearleverError, match="teeth"):
        g.tooth_outline(1.0, 0)
    with pytest.raises(GearleverError, match="teeth"):
        g.tooth_outline(1.0, 12.5)
    with pytest.raises(GearleverError, match="module"):
        g.tooth_outline(-1.0, 12)
    with pytest.raises(GearleverError, match="helix"):
        g.tooth_outline(1.0, 12, helix=math.radians(45))
    with pytest.raises(GearleverError, match="points the tooth.*largest shift"):
        g.tooth_outline(1.0, 12, 1.0)
