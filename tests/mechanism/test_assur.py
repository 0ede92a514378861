"""The closed-form dyad path (gearlever.mechanism.assur) against the general Newton path and finite differences."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import gearlever
from gearlever.mechanism.assur import plan_dyads

from ._models import all_examples, sweep

TOL = 1e-12
#: Tolerance by derivative order: positions agree to the Newton stopping rule
#: (1e-14 L); each derivative is one more linear solve with the same Jacobian,
#: whose condition number (1/sin of the transmission angle) multiplies the
#: round-off, so velocities and accelerations get one and two decades more.
TOL_BY_ORDER = {0: 1e-12, 1: 1e-11, 2: 1e-10}


def newton_and_fast(m, q, qd=None, qdd=None):
    """Results of the fast path and of the general path (dyad plan switched off) on the same rows."""
    fast = m.solve(q, qd, qdd)
    ks = m.system
    plan = ks.dyad_plan
    ks._dyad_plan = None
    try:
        slow = m.solve(q, qd, qdd)
    finally:
        ks._dyad_plan = plan
    return fast, slow


def used_fast(r) -> bool:
    return "_fast_points" in r.__dict__


def close(a, b, what, order=0):
    a, b = np.asarray(a), np.asarray(b)
    tol = TOL_BY_ORDER[order]
    scale = max(1.0, float(np.nanmax(np.abs(b))))
    np.testing.assert_array_equal(np.isnan(a), np.isnan(b), err_msg=what)
    err = float(np.nanmax(np.abs(a - b))) if a.size else 0.0
    assert err <= tol * scale, f"{what}: {err:.3e} > {tol} * {scale:.3g}"


def assert_same(fast, slow, model):
    np.testing.assert_array_equal(fast.closed, slow.closed)
    np.testing.assert_array_equal(fast.reason, slow.reason)
    for order, a in enumerate(("x", "xdot", "xddot")):
        close(getattr(fast, a), getattr(slow, a), a, order)
    for order, a in enumerate(("pose", "pose_velocity", "pose_acceleration")):
        close(getattr(fast, a), getattr(slow, a), a, order)
    for order, d in enumerate(("point", "velocity", "acceleration")):
        for p in model.points:
            close(getattr(fast, d)[p], getattr(slow, d)[p], f"{d}[{p}]", order)
    for order, d in enumerate(("angle", "omega", "alpha")):
        for k in model.links:
            close(getattr(fast, d)[k], getattr(slow, d)[k], f"{d}[{k}]", order)


PLANNED = {
    "engine",
    "fivebar_two_inputs",
    "fourbar",
    "slider_crank",
    "square_rod_slider_crank",
    "stephenson_iii",
    "watt_i",
    "watt_sixbar",
}


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_fast_path_equals_newton_on_every_example_model(path):
    m = gearlever.Mechanism.load(path)
    plan = m.system.dyad_plan
    assert (plan is not None) == (path.stem in PLANNED)
    if plan is None:
        return  # declined, as it must be: the general Newton path answers (tested elsewhere)
    q, qd = sweep(m, 2001)
    qdd = 0.3 * qd - 0.1
    fast, slow = newton_and_fast(m, q, qd, qdd)
    # the fast path answers away from dead and branch points: a sweep through a branch point (the square-rod
    # slider-crank's square pose) is answered by the continuation, through the pose on the smooth branch
    assert used_fast(fast) == (not slow.branch_points) and not used_fast(slow)
    assert fast.closed.all()
    assert_same(fast, slow, m.model)
    if slow.branch_points:  # the rows before the pose, well away from it: the fast path answers them
        keep = np.abs(q[:, 0] - slow.branch_points[0].q[0]) > 0.5
        keep[slow.branch_points[0].row :] = False
        fast, slow = newton_and_fast(m, q[keep], qd[keep], qdd[keep])
        assert used_fast(fast) and not slow.branch_points
        assert_same(fast, slow, m.model)


def fourbar_model(ground, crank, coupler, rocker, start, up):
    """A four-bar dict with the crank at ``start`` and the assembly branch ``up``."""
    ax, ay = crank * math.cos(start), crank * math.sin(start)
    dx, dy = ground - ax, -ay
    d = math.hypot(dx, dy)
    a = (coupler**2 - rocker**2 + d * d) / (2 * d)
    h = math.sqrt(coupler**2 - a * a) * (1 if up else -1)
    bx, by = ax + (a * dx - h * dy) / d, ay + (a * dy + h * dx) / d
    return {
        "points": {"O2": [0, 0], "O4": [ground, 0], "A": [ax, ay], "B": [bx, by], "P": [ax + 3.0, ay + 7.0]},
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B", "P"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }


def slider_crank_model(crank, rod, offset, start, right, angle):
    ax, ay = crank * math.cos(start), crank * math.sin(start)
    c, s = math.cos(angle), math.sin(angle)
    # guide through (0, offset) turned by angle: points (t c - offset s, t s + offset c)
    px, py = -offset * s, offset * c
    wx, wy = px - ax, py - ay
    uw = c * wx + s * wy
    t = -uw + (1 if right else -1) * math.sqrt(uw * uw - (wx * wx + wy * wy - rod * rod))
    bx, by = px + t * c, py + t * s
    return {
        "points": {"O2": [0, 0], "A": [ax, ay], "B": [bx, by]},
        "links": {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "piston": ["B"]},
        "sliders": [{"link": "piston", "on": "ground", "point": "B", "direction": [c, s]}],
        "inputs": [{"link": "crank"}],
    }


@settings(max_examples=40, deadline=None)
@given(
    ground=st.floats(20.0, 60.0),
    crank=st.floats(3.0, 15.0),
    coupler=st.floats(15.0, 70.0),
    rocker=st.floats(10.0, 60.0),
    start=st.floats(-math.pi, math.pi),
    up=st.booleans(),
    turns=st.floats(-2.5, 2.5),
)
def test_random_fourbars_fast_path_equals_newton(ground, crank, coupler, rocker, start, up, turns):
    ax, ay = crank * math.cos(start), crank * math.sin(start)
    d = math.hypot(ground - ax, ay)
    assume(abs(coupler - rocker) + 0.5 < d < coupler + rocker - 0.5)
    m = gearlever.Mechanism.from_dict(fourbar_model(ground, crank, coupler, rocker, start, up))
    assert m.system.dyad_plan is not None
    q = start + np.linspace(0.0, 2 * np.pi * turns, 3001)
    qd = 1.0 + 0.2 * np.sin(q)
    qdd = 0.2 * np.cos(q)
    fast, slow = newton_and_fast(m, q, qd, qdd)
    if used_fast(fast):
        assert fast.closed.all()
    assert_same(fast, slow, m.model)


@settings(max_examples=40, deadline=None)
@given(
    crank=st.floats(3.0, 15.0),
    rod=st.floats(20.0, 60.0),
    offset=st.floats(-8.0, 8.0),
    start=st.floats(-math.pi, math.pi),
    right=st.booleans(),
    angle=st.floats(-math.pi, math.pi),
    turns=st.floats(-2.5, 2.5),
)
def test_random_slider_cranks_fast_path_equals_newton(crank, rod, offset, start, right, angle, turns):
    assume(rod > crank + abs(offset) + 1.0)
    m = gearlever.Mechanism.from_dict(slider_crank_model(crank, rod, offset, start, right, angle))
    assert m.system.dyad_plan is not None
    q = start + np.linspace(0.0, 2 * np.pi * turns, 3001)
    fast, slow = newton_and_fast(m, q, 1.5, -0.4)
    assert used_fast(fast) and fast.closed.all()
    assert_same(fast, slow, m.model)


def two_input_guide_model():
    """Two driven links; a rod pinned to the first ends in a block sliding along the second (RRP, moving guide)."""
    return {
        "points": {"O2": [0, 0], "O4": [30, 0], "A": [8, 0], "B": [30, 40], "G": [30, 60]},
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "lever": ["O4", "G"],
            "rod": ["A", "B"],
            "block": ["B"],
        },
        "sliders": [{"link": "block", "on": "lever", "point": "B", "direction": [0.0, 1.0]}],
        "inputs": [{"link": "crank"}, {"link": "lever"}],
    }


def test_moving_guide_and_two_inputs_fast_path_equals_newton():
    m = gearlever.Mechanism.from_dict(two_input_guide_model())
    assert m.system.dyad_plan is not None
    t = np.linspace(0.0, 2 * np.pi, 4001)
    q = m.sketch_inputs + np.stack([t, 0.3 * np.sin(t)], axis=1)
    qd = np.stack([np.ones_like(t), 0.3 * np.cos(t)], axis=1)
    qdd = np.stack([np.zeros_like(t), -0.3 * np.sin(t)], axis=1)
    fast, slow = newton_and_fast(m, q, qd, qdd)
    assert used_fast(fast)
    assert_same(fast, slow, m.model)


def test_drag_link_rotations_are_unwrapped_like_the_continuation():
    # double crank (shortest link is the ground): every link turns fully; start three turns away from the sketch
    m = gearlever.Mechanism.from_dict(fourbar_model(10.0, 25.0, 30.0, 30.0, 0.7, True))
    q = 0.7 + 6 * np.pi + np.linspace(0.0, -10 * np.pi, 6001)
    fast, slow = newton_and_fast(m, q)
    assert used_fast(fast)
    assert_same(fast, slow, m.model)
    assert np.ptp(fast.x[:, 2]) > 4 * np.pi  # the rocker (a crank here) turned several times


def test_rows_far_apart_or_past_a_dead_point_go_the_general_way():
    m = gearlever.Mechanism.load(all_examples()[0].parent / "fourbar.toml")
    fast, slow = newton_and_fast(m, np.linspace(0.0, 2 * np.pi, 12))  # steps above COARSE_STEP
    assert not used_fast(fast)
    assert_same(fast, slow, m.model)
    # a triple rocker: the crank cannot turn fully, rows past the limit are NaN with a reason
    tr = gearlever.Mechanism.from_dict(fourbar_model(30.0, 20.0, 25.0, 20.0, 0.5, True))
    q = np.linspace(0.5, 0.5 + 2 * np.pi, 3001)
    fast, slow = newton_and_fast(tr, q)
    assert not used_fast(fast) and not fast.closed.all()
    assert_same(fast, slow, tr.model)


def test_fast_path_rates_match_finite_differences():
    for model in (
        fourbar_model(40.0, 10.0, 36.0, 30.0, 0.3, True),
        slider_crank_model(10.0, 35.0, 5.0, 0.3, True, 0.4),
        two_input_guide_model(),
    ):
        m = gearlever.Mechanism.from_dict(model)
        W = m.sketch_inputs.size
        t = np.linspace(0.0, 2 * np.pi, 20001)
        rates = np.array([1.0, 0.2][:W])
        q = m.sketch_inputs + t[:, None] * rates
        r = m.solve(q, np.broadcast_to(rates, q.shape), np.zeros_like(q))
        assert used_fast(r)
        h = t[1] - t[0]
        for p in m.model.points:
            P, V, A = r.point[p], r.velocity[p], r.acceleration[p]
            scale = 1.0 + np.abs(V).max()
            assert np.abs((P[2:] - P[:-2]) / (2 * h) - V[1:-1]).max() < 1e-6 * scale
            assert np.abs((V[2:] - V[:-2]) / (2 * h) - A[1:-1]).max() < 1e-6 * (1.0 + np.abs(A).max())
            assert np.abs((P[2:] - 2 * P[1:-1] + P[:-2]) / h**2 - A[1:-1]).max() < 1e-4 * (1.0 + np.abs(A).max())


def test_plan_declines_what_is_not_a_chain_of_dyads():
    for name in ("whitworth", "geared_fivebar", "parallel_levers", "planetary"):
        m = gearlever.Mechanism.load(all_examples()[0].parent / f"{name}.toml")
        assert plan_dyads(m.system) is None


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_blocked_in_place_evaluation_gives_the_bits_of_one_pass_over_all_rows(path):
    # DyadPlan.solve evaluates BLOCK rows at a time into scratch rows and its result arrays; DyadPlan.run
    # without a destination evaluates the same formulas as plain expressions over all rows at once
    from gearlever.mechanism.assur import BLOCK

    m = gearlever.Mechanism.load(path)
    plan = m.system.dyad_plan
    if plan is None:
        pytest.skip("not a chain of dyads")
    q, qd = sweep(m, points=2 * BLOCK + 37)  # two whole blocks and a ragged one
    q = q[: 2 * BLOCK + 37]
    qdd = np.sin(np.arange(q.size)).reshape(q.shape)
    got = plan.solve(q.T, qd.T, qdd.T)
    if got is None:
        pytest.skip("a row near a dead point: the general path answers")
    x, xd, xdd, (C, S), points = got
    phi, st, _, pts, _ = plan.run(q.T - m.system.q0[:, None], qd.T, qdd.T)
    for k in m.model.moving:
        i = m.system.idx[k]
        for got_row, want in zip((C[i], S[i], xd[i], xdd[i]), st[k][:4]):
            np.testing.assert_array_equal(got_row, np.broadcast_to(want, got_row.shape), err_msg=k)
        # x: the wrapped rotation made continuous (whole turns added)
        np.testing.assert_allclose(np.mod(x[i] - phi[k] + np.pi, 2 * np.pi) - np.pi, 0.0, atol=1e-12, err_msg=k)
    assert points, "the dyads' points are kept"
    for p, (P, V, A) in points.items():
        X, Y, VX, VY, AX, AY = pts[p]
        for arr, (a, b) in ((P, (X, Y)), (V, (VX, VY)), (A, (AX, AY))):
            np.testing.assert_array_equal(arr, np.stack([a, b], axis=1), err_msg=p)
