"""Motion generation: poses from a known four-bar give back its dyads (3, 4, 5 poses); engine residuals; refusals."""

import numpy as np
import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.synthesis.model import fourbar_model
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


# ---------------------------------------------------------------------------
# completeness of the five-pose solution, against an independent formulation
# ---------------------------------------------------------------------------


def _design_matrix(pts, ang, G):
    """Rows ``[a_i, -a_i . P_1i]``, ``a_i = (G - P_1i)^T [A(phi_1i) - I]``, i = 2..5, for fixed pivots G (..., 2).

    The RR design equations of J. M. McCarthy and G. S. Soh, *Geometric Design of Linkages*, 2nd ed.,
    Springer, 2011, eq. 5.17 (P_1i the pole and phi_1i the rotation from pose 1 to pose i), written as
    linear equations in the moving pivot W_1 (their eq. 5.19): a fixed pivot reaches the five poses
    exactly when this 4 x 3 matrix has rank two.
    """
    z = pts[:, 0] + 1j * pts[:, 1]
    rows = []
    for i in range(1, 5):
        phi = ang[i] - ang[0]
        e = np.exp(1j * phi)
        pole = (z[i] - e * z[0]) / (1 - e)
        p = np.array([pole.real, pole.imag])
        rot = np.array([[np.cos(phi) - 1, -np.sin(phi)], [np.sin(phi), np.cos(phi) - 1]])
        a = (G - p) @ rot
        rows.append(np.concatenate([a, -(a @ p)[..., None]], axis=-1))
    return np.stack(rows, axis=-2)


def _brute_force_fixed_pivots(pts, ang, half, n=400):
    """Every fixed pivot in the square |x|, |y| < half where the design matrix loses rank: local minima of
    its smallest relative singular value on an n x n grid, each refined by least squares on the four 3 x 3
    minors (no use of gearlever's resultant)."""
    from itertools import combinations

    from scipy.optimize import least_squares

    xs = np.linspace(-half, half, n)
    G = np.stack(np.meshgrid(xs, xs, indexing="ij"), -1)
    s = np.linalg.svd(_design_matrix(pts, ang, G), compute_uv=False)
    q = s[..., 2] / s[..., 0]
    inner = q[1:-1, 1:-1]
    around = np.min([q[1 + di : n - 1 + di, 1 + dj : n - 1 + dj] for di in (-1, 0, 1) for dj in (-1, 0, 1)], axis=0)
    cand = np.argwhere((inner == around) & (inner < 0.05)) + 1

    def minors(g):
        M = _design_matrix(pts, ang, g)
        return np.array([np.linalg.det(M[list(k)]) for k in combinations(range(4), 3)]) / np.linalg.norm(M) ** 3

    found = []
    for i, j in cand:
        g = least_squares(minors, G[i, j], xtol=1e-15, ftol=1e-15, gtol=1e-15).x
        sv = np.linalg.svd(_design_matrix(pts, ang, g), compute_uv=False)
        if sv[2] / sv[0] < 1e-9 and not any(np.hypot(*(g - f)) < 1e-4 * half for f in found):
            found.append(g)
    return found


def _pose_sets():
    rng = np.random.default_rng(0)
    sets = [tuple(np.asarray(v) for v in _poses(5))]
    for _ in range(6):
        sets.append((rng.uniform(-2, 2, (5, 2)), np.sort(rng.uniform(0, 1.5, 5))))
    return sets


@pytest.mark.parametrize("k", range(7))
def test_five_poses_every_burmester_point_is_found_against_mccarthy_soh_design_equations(k):
    """Completeness: the fixed pivots that gearlever's resultant finds (roots of one polynomial) are exactly
    those that a brute-force search on McCarthy and Soh's bilinear design equations finds in a square of
    half-width 12 around the poses (the known four-bar's poses and six random pose sets; 2 or 4 each)."""
    pts, ang = _pose_sets()[k]
    half = 12.0
    ours = [np.array(d.ground_pivot) for d in burmester_points(pts, ang)]
    ours_in = [g for g in ours if np.all(np.abs(g) < half - 0.05)]
    brute = [g for g in _brute_force_fixed_pivots(pts, ang, half) if np.all(np.abs(g) < half - 0.05)]
    assert len(ours) in (2, 4) and len(ours_in) == len(brute), (ours, brute)
    # (the brute force stops at a relative singular value of 1e-9: where the rank drops slowly, as near
    # the known pivots of the first set, that leaves its points up to ~1e-6 from the exact ones)
    for g in brute:
        assert min(np.hypot(*(g - h)) for h in ours_in) < 1e-5 * half
    # and each of ours satisfies the design equations: the matrix has rank two
    for g in ours:
        sv = np.linalg.svd(_design_matrix(pts, ang, g), compute_uv=False)
        assert sv[2] < 1e-10 * sv[0]
