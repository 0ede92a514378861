"""Motion generation: poses from a known four-bar give back its dyads (3, 4, 5 poses); engine residuals; refusals."""

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.synthesis._model import fourbar_model
from gearlever.synthesis.motion import burmester_curves, burmester_points, synthesize_motion

O2, O4, A, B, P = (0.0, 0.0), (4.0, 0.0), (1.0, 0.3), (4.5, 2.8), (2.0, 3.0)
SIZE = 4.5


def _poses(n, span=1.6):
    m = Mechanism.from_dict(fourbar_model(O2, O4, A, B, P))
    q = m.sketch_inputs[0] + np.linspace(0.0, span, n)
    r = m.solve(q[:, None])
    return r.point["P"], r.angle["coupler"]


def test_three_poses_given_fixed_pivots_recover_the_moving_pivots():
    pts, ang = _poses(3)
    s = synthesize_motion(pts, ang, fixed_pivots=[O2, O4]).best
    np.testing.assert_allclose([s.crank.moving_pivot, s.rocker.moving_pivot], [A, B], atol=1e-9 * SIZE)
    assert s.residual < 1e-9 and s.defect == ""


def test_three_poses_given_moving_pivots_recover_the_fixed_pivots():
    pts, ang = _poses(3)
    s = synthesize_motion(pts, ang + 0.7, moving_pivots=[A, B]).best  # only angle differences matter
    np.testing.assert_allclose([s.crank.ground_pivot, s.rocker.ground_pivot], [O2, O4], atol=1e-9 * SIZE)
    assert s.residual < 1e-9


def test_four_poses_centre_point_curve_passes_through_the_known_pivots():
    pts, ang = _poses(4)
    c = burmester_curves(pts, ang, samples=20000)
    C = c.center.reshape(-1, 2)
    for G in (O2, O4):
        assert np.nanmin(np.hypot(C[:, 0] - G[0], C[:, 1] - G[1])) < 2e-3 * SIZE
    s = synthesize_motion(pts, ang)
    assert s.best.residual < 1e-9 and s.best.defect == ""
    assert all(x.residual < 1e-9 for x in s.solutions if not x.defect)


def test_five_poses_burmester_points_include_the_known_dyads_to_1e9():
    pts, ang = _poses(5)
    dyads = burmester_points(pts, ang)
    assert 2 <= len(dyads) <= 4
    for G, M in ((O2, A), (O4, B)):
        err = min(np.hypot(*np.subtract(d.ground_pivot, G)) + np.hypot(*np.subtract(d.moving_pivot, M)) for d in dyads)
        assert err < 1e-9 * SIZE
    s = synthesize_motion(pts, ang)
    pairs = {(s_.crank.ground_pivot, s_.rocker.ground_pivot) for s_ in s.solutions}
    assert len(pairs) == len(s.solutions)
    good = [x for x in s.solutions if not x.defect]
    assert good and all(x.residual < 1e-9 for x in good)
    # every Burmester dyad is a circle point: its moving pivot stays on a circle about its ground pivot
    for d in dyads:
        z = pts[:, 0] + 1j * pts[:, 1]
        Mj = z + np.exp(1j * (ang - ang[0])) * (complex(*d.moving_pivot) - z[0])
        r = np.abs(Mj - complex(*d.ground_pivot))
        assert np.ptp(r) < 1e-9 * max(r.max(), SIZE)


def test_defects_are_ranked_after_defect_free_solutions():
    pts, ang = _poses(5)
    sols = synthesize_motion(pts, ang).solutions
    flags = [bool(s.defect) for s in sols]
    assert flags == sorted(flags)


@pytest.mark.parametrize(
    ("n", "kw", "match"),
    [
        (2, {}, "at least 3"),
        (6, {}, "at most 5"),
        (3, {}, "exactly one of"),
        (4, {"fixed_pivots": [O2, O4]}, "three poses"),
    ],
)
def test_bad_pose_sets_refused(n, kw, match):
    pts, ang = _poses(max(n, 3))
    if n == 2:
        pts, ang = pts[:2], ang[:2]
    if n == 6:
        pts, ang = _poses(6)
    with pytest.raises(GearleverError, match=match):
        synthesize_motion(pts, ang, **kw)


def test_repeated_pose_refused():
    pts, ang = _poses(3)
    pts[2], ang[2] = pts[0], ang[0]
    with pytest.raises(GearleverError, match="same pose"):
        synthesize_motion(pts, ang, fixed_pivots=[O2, O4])


def test_order_defect_when_a_rocking_crank_meets_the_poses_out_of_order():
    m = Mechanism.from_dict(fourbar_model(O2, O4, (2.0, 1.0), B, P))  # triple-rocker: the crank rocks
    q = m.sketch_inputs[0] + np.linspace(0.0, 0.5, 3)
    r = m.solve(q[:, None])
    pts, ang = r.point["P"], r.angle["coupler"]
    ok = synthesize_motion(pts, ang, fixed_pivots=[O2, O4]).best
    assert ok.defect == "" and not ok.crank_turns
    swapped = synthesize_motion(pts[[0, 2, 1]], ang[[0, 2, 1]], fixed_pivots=[O2, O4]).best
    assert swapped.defect.startswith("order defect")
    assert swapped.residual < 1e-9  # the poses are still met, but not in order


def test_three_poses_moving_pivot_on_a_line_refused():
    # a pure translation along x: a moving pivot's three positions are collinear
    with pytest.raises(GearleverError, match="on a line"):
        synthesize_motion([(0, 0), (1, 0), (2, 0)], [0.0, 0.0, 0.0], moving_pivots=[(0, 1), (1, 1)])
