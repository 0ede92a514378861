"""Batched dyadic simulation: link lengths kept over the turn, locking, Jacobian against finite differences."""

import numpy as np
import pytest

from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve.simulate import crank_angles, simulate, simulate_jacobian

SIXBAR = {
    "x0": [[0, 0], [0.3, 0.2], [2, 0], [1.5, 1.5], [3, 1], [2.5, 2.5], [1.0, 2.2]],
    "edges": [[0, 1], [1, 3], [2, 3], [3, 5], [4, 5], [1, 6], [3, 6]],
    "fixed_joints": [0, 2, 4],
    "motor": [0, 1],
}


def _lengths(x, edges):
    e = np.asarray(edges)
    return np.hypot(*(x[..., e[:, 0], :, :] - x[..., e[:, 1], :, :]).transpose(3, 0, 1, 2))


def test_every_link_keeps_its_sketch_length_at_every_step_for_a_batch():
    lk = linkage_from_dict(SIXBAR)
    rng = np.random.default_rng(1)
    x0s = lk.x0[None] + 0.02 * rng.standard_normal((5, 7, 2))
    x = simulate(x0s, solve_plan(lk))
    assert x.shape == (5, 7, 200, 2) and np.isfinite(x).all()
    L = _lengths(x, lk.edges)  # (B, E, T)
    L0 = np.hypot(*(x0s[:, lk.edges[:, 0]] - x0s[:, lk.edges[:, 1]]).transpose(2, 0, 1))
    np.testing.assert_allclose(L, L0[..., None].repeat(200, -1), rtol=1e-12, atol=1e-12)
    # crank tip on its circle at the absolute crank angle
    th = crank_angles()
    r = np.hypot(*(x0s[:, 1] - x0s[:, 0]).T)
    np.testing.assert_allclose(x[:, 1, :, 0], x0s[:, 0, None, 0] + r[:, None] * np.cos(th), atol=1e-14)


def test_dyad_stays_on_the_sketch_side_of_its_parents():
    lk = linkage_from_dict(SIXBAR)
    x = simulate(lk.x0[None], solve_plan(lk))[0]
    for k, i, j in ((3, 1, 2), (5, 3, 4)):
        u, v = x[j] - x[i], x[k] - x[i]
        side = np.sign(u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])
        u0, v0 = lk.x0[j] - lk.x0[i], lk.x0[k] - lk.x0[i]
        assert (side == np.sign(u0[0] * v0[1] - u0[1] * v0[0])).all()


def test_a_crank_too_long_to_turn_locks_with_nan():
    d = {
        "x0": [[0, 0], [2.5, 0], [3, 0], [3, 1]],
        "edges": [[0, 1], [1, 3], [2, 3]],
        "fixed_joints": [0, 2],
        "motor": [0, 1],
    }
    lk = linkage_from_dict(d)
    x = simulate(lk.x0[None], solve_plan(lk))
    assert np.isnan(x[0, 3]).any() and np.isfinite(x[0, 3, 0]).all()


def test_analytic_jacobian_matches_central_finite_differences():
    lk = linkage_from_dict(SIXBAR)
    plan = solve_plan(lk)
    rng = np.random.default_rng(2)
    x0s = lk.x0[None] + 0.02 * rng.standard_normal((2, 7, 2))
    x, J = simulate_jacobian(x0s, plan, steps=40)
    h = 1e-6
    fd = np.empty_like(J)
    for q in range(7):
        for e in range(2):
            xp, xm = x0s.copy(), x0s.copy()
            xp[:, q, e] += h
            xm[:, q, e] -= h
            fd[..., 2 * q + e] = (simulate(xp, plan, steps=40) - simulate(xm, plan, steps=40)) / (2 * h)
    assert np.isfinite(J).all()
    np.testing.assert_allclose(J, fd, atol=2e-6 * max(1.0, np.abs(fd).max()))
    _, Jt = simulate_jacobian(x0s, plan, steps=40, joints=[6])
    np.testing.assert_array_equal(Jt[:, 0], J[:, 6])


@pytest.mark.parametrize("steps", [3, 200])
def test_steps_sets_the_number_of_crank_positions(steps):
    lk = linkage_from_dict(SIXBAR)
    assert simulate(lk.x0[None], solve_plan(lk), steps=steps).shape[2] == steps
