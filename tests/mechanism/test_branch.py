"""Through branch points (``branch="continue" | "keep" | "stop"``): the square-rod slider-crank and a parallelogram.

The square-rod slider-crank (crank r = 10, rod l = 30, guide e = 20 above the crank pivot, the rod as long as
the offset plus the crank, as PMKS+ moves it: PMKS-Web/PMKSWeb pull request 231) has its rod square to the guide
where the crank tip is farthest from the guide, h = e - r sin(theta) = l: theta* = 270 deg.  Closed form there
(law of the slider-crank, x_B = x_A + sigma sqrt(l^2 - h^2)): l^2 - h^2 = 300 delta^2 + O(delta^3) about theta*,
so the smooth branch has x_B' = x_A' - sqrt(300) = 10 - 10 sqrt(3) at theta*, and the kept branch (sigma fixed)
turns back with x_B' = 10 + 10 sqrt(3).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import gearlever
from gearlever.data import example_path
from gearlever.errors import GearleverError
from gearlever.mechanism import input_limits, sweep_rows

R, L, E = 10.0, 30.0, 20.0
B0 = 32.360679774997898  # sketch x of B: 10 + sqrt(30^2 - 20^2)


def _square_rod():
    return gearlever.Mechanism.load(example_path("square_rod_slider_crank.toml"))


def _closed_form(theta, sigma):
    """x of the slider pin B for the crank angle theta on the branch sigma (+1: B ahead of the foot of A)."""
    xa = R * np.cos(theta)
    h = E - R * np.sin(theta)
    return xa + sigma * np.sqrt(np.maximum(L * L - h * h, 0.0))


def _parallelogram():
    return gearlever.Mechanism.from_dict(
        {
            "points": {"O": [0.0, 0.0], "Q": [10.0, 0.0], "A": [0.0, 4.0], "B": [10.0, 4.0]},
            "links": {"ground": ["O", "Q"], "crank": ["O", "A"], "coupler": ["A", "B"], "rocker": ["Q", "B"]},
            "inputs": [{"link": "crank"}],
        }
    )


@pytest.mark.parametrize("n", [720, 360, 1000, 7, 721])
def test_square_rod_slider_crank_full_turn_closes_every_row_on_the_closed_form(n):
    # 720, 360 and 1000 rows put a row exactly on the square pose (270 deg); 7 and 721 do not
    m = _square_rod()
    q = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = m.solve(q)
    assert r.closed.all() and np.isfinite(r.xdot).all() and np.isfinite(r.xddot).all()
    assert set(r.reason) == {""}
    x = r.point["B"][:, 0]
    sigma = np.where(q < 1.5 * np.pi, 1.0, -1.0)
    assert np.abs(x - _closed_form(q, sigma)).max() < 1e-9
    assert np.abs(r.point["B"][:, 1] - E).max() < 1e-12


def test_square_rod_branch_change_is_reported_at_the_square_pose():
    m = _square_rod()
    for n in (720, 7, 721):
        q = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
        r = m.solve(q)
        (p,) = r.branch_points
        assert p.q[0] == pytest.approx(1.5 * np.pi, abs=1e-9)  # h = e - r sin(theta) = l
        assert p.policy == "continue" and (p.sign_before, p.sign_after) == (1, -1)
        assert p.row == int(np.searchsorted(q, 1.5 * np.pi - 1e-9))
        assert (r.side[: p.row] == 1).all() and (r.side[p.row + 1 :] == -1).all()
    # two turns: back onto the sketch's branch at 630 deg
    q = np.linspace(0.0, 4 * np.pi, 1441)[:-1] + 0.001
    r = m.solve(q)
    assert r.closed.all()
    assert [round(math.degrees(p.q[0]), 9) for p in r.branch_points] == [270.0, 630.0]
    assert [p.sign_after for p in r.branch_points] == [-1, 1]


def test_square_rod_velocity_is_continuous_across_the_square_pose():
    # finite differences of the solved positions on each side of the pose agree with each other, with the
    # solved velocities and with the closed form 10 - 10 sqrt(3) at the pose
    m = _square_rod()
    h = 1e-4
    for delta in (0.0, 3e-5):  # a row exactly at the pose, and rows straddling it
        q = 1.5 * np.pi + delta + h * np.arange(-3, 4)
        r = m.solve(q)
        x = r.point["B"][:, 0]
        v = r.velocity["B"][:, 0]
        left = (x[3] - x[1]) / (2 * h) if delta else (x[2] - x[0]) / (2 * h)
        right = (x[5] - x[3]) / (2 * h) if delta else (x[6] - x[4]) / (2 * h)
        assert left == pytest.approx(right, abs=1e-6)
        assert np.abs(v - (x[4] - x[2]) / (2 * h)).max() < 1e-5
        assert np.isfinite(v).all()
    r = m.solve(np.array([0.0, 1.5 * np.pi]))
    assert r.velocity["B"][1, 0] == pytest.approx(10.0 - 10.0 * math.sqrt(3.0), abs=1e-8)
    assert r.omega["rod"][1] == pytest.approx(math.sqrt(R / L), abs=1e-8)  # d(rod angle) / d theta at the pose


def test_square_rod_branch_stop_is_the_old_behaviour():
    m = _square_rod()
    q = np.linspace(0.0, 2 * np.pi, 720, endpoint=False)
    r = m.solve(q, branch="stop")
    # row 540 lies exactly on the square pose: reached, and the last row closed (as a row exactly at a dead point)
    assert int(r.closed.sum()) == 541 and not r.closed[541:].any() and r.branch_points == ()
    assert r.dead_rows.tolist() == [540, 541] and r.reason[541].startswith("dead point between row 540")
    assert r.reason[540].startswith("dead point: the constraint Jacobian is singular") and np.isnan(r.xdot[540]).all()
    assert np.abs(r.point["B"][540] - [0.0, E]).max() < 1e-9  # on the pose: x_B = x_A = 0
    r = m.solve(q + 0.001, branch="stop")  # no row on the pose: the rows stop before it
    assert int(r.closed.sum()) == 540 and not r.closed[540:].any() and r.branch_points == ()
    assert r.dead_rows.tolist() == [540] and r.reason[540].startswith("dead point between row 539")
    lim = input_limits(m, branch="stop")
    assert lim.rocks and math.degrees(lim.upper) == pytest.approx(270.0, abs=1e-6)
    assert input_limits(m).full_turn and not sweep_rows(m, 8).oscillates


def test_square_rod_branch_stop_never_passes_a_row_closed_at_the_square_pose():
    # 1000 rows put row 750 exactly on the pose: it closes there, and the rows past it are not reached (before
    # the branch policy the continuation went on from it onto the kept branch for five rows, then stopped)
    m = _square_rod()
    r = m.solve(np.linspace(0.0, 2 * np.pi, 1000, endpoint=False), branch="stop")
    assert r.closed[:751].all() and not r.closed[751:].any() and r.dead_rows.tolist() == [750, 751]
    assert "(at crank = 4.71239 rad)" in r.reason[751]


def test_square_rod_branch_keep_holds_the_sketch_branch_and_the_velocity_jumps():
    m = _square_rod()
    q = np.linspace(0.0, 2 * np.pi, 721)[:-1] + 0.001
    r = m.solve(q, branch="keep")
    assert r.closed.all() and (r.side == 1).all()
    assert np.abs(r.point["B"][:, 0] - _closed_form(q, 1.0)).max() < 1e-9
    (p,) = r.branch_points
    assert p.policy == "keep" and p.q[0] == pytest.approx(1.5 * np.pi, abs=1e-9)
    v = r.velocity["B"][:, 0]
    assert v[p.row - 1] == pytest.approx(10 - 10 * math.sqrt(3), abs=0.01)
    assert v[p.row] == pytest.approx(10 + 10 * math.sqrt(3), abs=0.01)
    # a row exactly at the pose: closed, its velocity undefined there
    rk = m.solve(np.linspace(0.0, 2 * np.pi, 720, endpoint=False), branch="keep")
    assert rk.closed.all() and np.isnan(rk.xdot[540]).all() and rk.reason[540].startswith("dead point")


@pytest.mark.parametrize("n", [360, 8, 97])
def test_parallelogram_continue_stays_a_parallelogram_through_its_folding_poses(n):
    # all links on one line at crank 180 and 360 deg; the smooth branch is the parallelogram: rocker parallel
    # to the crank (omega 1), coupler translating (omega 0); the anti-parallelogram's rocker rate jumps there
    m = _parallelogram()
    q = np.pi / 2 + np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = m.solve(q)
    assert r.closed.all() and np.isfinite(r.xdot).all()
    assert np.abs(r.angle["rocker"] - q).max() < 1e-9 and np.abs(r.angle["coupler"]).max() < 1e-9
    assert np.abs(r.omega["rocker"] - 1).max() < 1e-8 and np.abs(r.omega["coupler"]).max() < 1e-8
    assert [round(math.degrees(p.q[0]), 9) for p in r.branch_points] == [180.0, 360.0]


def test_parallelogram_keep_becomes_the_anti_parallelogram():
    m = _parallelogram()
    q = np.radians(np.arange(90.0, 450.0, 7.0))
    r = m.solve(q, branch="keep")
    assert r.closed.all() and (r.side == 1).all()
    A, B = r.point["A"], r.point["B"]
    assert np.abs(np.hypot(*(B - A).T) - 10.0).max() < 1e-9 and np.abs(np.hypot(B[:, 0] - 10, B[:, 1]) - 4).max() < 1e-9
    past = (q > np.pi) & (q < 2 * np.pi)
    # anti-parallelogram between the folding poses: the rocker no longer parallel to the crank; past the
    # second (360 deg) the kept sign of det J is the parallelogram's again
    assert np.abs(np.sin(r.angle["rocker"][past] - q[past])).min() > 1e-3
    after = q > 2 * np.pi
    assert np.abs(np.sin(r.angle["rocker"][after] - q[after])).max() < 1e-9
    assert [round(math.degrees(p.q[0]), 9) for p in r.branch_points] == [180.0, 360.0]


def test_branch_policy_is_checked():
    m = _square_rod()
    with pytest.raises(GearleverError, match="branch must be one of 'continue', 'keep', 'stop', got 'smooth'"):
        m.solve([0.0, 1.0], branch="smooth")
    with pytest.raises(GearleverError, match="branch must be one of"):
        sweep_rows(m, 8, branch=None)


def test_a_true_dead_point_stays_a_limit_under_every_policy():
    # the Watt I six-bar rocks: its limits are dead points of the input, past which nothing assembles
    w = gearlever.Mechanism.load(example_path("watt_i.toml"))
    for policy in ("continue", "keep", "stop"):
        lim = input_limits(w, branch=policy)
        assert lim.rocks and round(math.degrees(lim.lower), 3) == 67.284 and round(math.degrees(lim.upper), 3) == 78.254
        r = w.solve(np.radians([72.0, 80.0]), branch=policy)
        assert r.closed.tolist() == [True, False] and r.branch_points == ()


# --- any rows: offsets x spacings x directions against the closed form of the continued branch -----------------
#
# With delta = theta - 3 pi / 2: h = e - r sin(theta) = 20 + 10 cos(delta) and l^2 - h^2 = 200 sin^2(delta / 2)
# (5 + cos(delta)), so the branch that passes the square pose smoothly is the analytic
#     x_B(delta) = 10 sin(delta) - 10 sqrt(2) sin(delta / 2) sqrt(5 + cos(delta))
# (period 4 pi in theta: one turn on each assembly branch).  Its derivatives below are taken by hand (product and
# chain rules); at the pose x_B' = 10 - 10 sqrt(3) and x_B'' = 0.


def _xb_terms(theta):
    d = np.asarray(theta, dtype=float) - 1.5 * np.pi
    p = np.sqrt(5.0 + np.cos(d))
    p1 = -np.sin(d) / (2.0 * p)
    p2 = -np.cos(d) / (2.0 * p) - np.sin(d) ** 2 / (4.0 * p**3)
    s, c = np.sin(d / 2.0), np.cos(d / 2.0)
    g = s * p
    g1 = 0.5 * c * p + s * p1
    g2 = -0.25 * s * p + c * p1 + s * p2
    r2 = 10.0 * math.sqrt(2.0)
    return (10.0 * np.sin(d) - r2 * g, 10.0 * np.cos(d) - r2 * g1, -10.0 * np.sin(d) - r2 * g2), s


def _crossings(path, at=1.5 * math.pi, period=2 * math.pi):
    """The inputs ``at + k period`` that the piecewise-linear path of inputs passes, in order."""
    out = []
    for a, b in zip(path[:-1], path[1:]):
        lo, hi = min(a, b), max(a, b)
        k0 = math.ceil((lo - at) / period - 1e-12)
        k1 = math.floor((hi - at) / period + 1e-12)
        hits = [t for t in (at + period * k for k in range(k0, k1 + 1)) if lo < t < hi or t == b]
        out += sorted(hits, reverse=bool(b < a))
    return out


def _check_square_rod_rows(m, q, qd=1.3, qdd=0.4):
    """Every row on the continued branch: positions, rates, sides and branch points as the closed form says."""
    r = m.solve(q, np.full(q.size, qd), np.full(q.size, qdd))
    assert r.closed.all() and set(r.reason) == {""}
    (x, v, a), s = _xb_terms(q)
    # positions to the solver's tolerance; rates to 1e-9 of their scale over the turn (x_B' up to 27.4 per rad,
    # x_B'' up to 18.1 per rad^2), rows at the square pose and beside it included where the rows pass it; a row
    # within 2e-2 rad of a pose the rows do not pass keeps the rates of the linear solves, which lose digits to the
    # nearly singular J_z there (the known limit: about 1e-5 of the acceleration's scale at 1e-3 rad)
    vs, as_ = 27.4 * abs(qd), 18.1 * qd * qd + 27.4 * abs(qdd)
    assert np.abs(r.point["B"][:, 0] - x).max() < 1e-9
    assert np.abs(r.point["B"][:, 1] - E).max() < 1e-9
    passed = np.array([p.q[0] for p in r.branch_points])
    pose = 1.5 * np.pi + 2 * np.pi * np.round((q - 1.5 * np.pi) / (2 * np.pi))
    fine = (np.abs(q - pose) > 2e-2) | np.any(np.abs(pose[:, None] - passed[None, :]) < 1e-6, axis=1)
    assert np.abs(r.velocity["B"][fine, 0] - v[fine] * qd).max(initial=0.0) < 1e-9 * vs
    assert np.abs(r.acceleration["B"][fine, 0] - (a * qd * qd + v * qdd)[fine]).max(initial=0.0) < 1e-9 * as_
    # the branch (the sign of det J_z): the sketch's while B is ahead of the foot of the rod (sin(delta / 2) < 0)
    off_pose = np.abs(s) > 1e-9
    assert (r.side[off_pose] == np.where(s[off_pose] < 0, 1, -1)).all()
    # one branch point a crossing, from the sketch through every row, each at 270 deg (mod 360)
    expect = _crossings(np.concatenate([[0.0], q]))
    got = [p.q[0] for p in r.branch_points]
    assert len(got) == len(expect) and np.allclose(got, expect, rtol=0, atol=1e-9), (got, expect)
    assert all(p.sign_after == -p.sign_before and p.policy == "continue" for p in r.branch_points)
    return r


OFFSETS = (0.0, 1e-3, -1e-3, 0.05, -0.05, 0.137, -0.29, 0.5, -0.5, 1.3, 2.2, -2.9)


@pytest.mark.parametrize("direction", [1, -1])
@pytest.mark.parametrize("n", [7, 13, 37, 100, 361, 2001])
def test_square_rod_any_rows_move_as_the_dense_sweep_through_the_square_pose(n, direction):
    # 12 offsets x 6 spacings x 2 directions: rows that do not start at the sketch, large steps (7 rows a turn:
    # 60 deg), rows on the pose (offset 0 puts one there for n = 13, 37, 361), backward sweeps (each crosses the
    # pose in its lead-in from the sketch and again on the way back); the continued branch at every row
    m = _square_rod()
    for off in OFFSETS:
        q = np.linspace(0.0, 2 * np.pi, n) + off
        r = _check_square_rod_rows(m, q[::direction], qd=1.3 * direction)
        if n >= 361:  # velocity continuous: central differences of the positions agree with the velocities
            x, qq = r.point["B"][:, 0], r.q[:, 0]
            fd = (x[2:] - x[:-2]) / (qq[2:] - qq[:-2])
            assert np.abs(fd - r.velocity["B"][1:-1, 0] / r.qdot[1:-1, 0]).max() < 1e-3


@settings(max_examples=25, deadline=None)
@given(
    start=st.floats(-7.0, 7.0),
    steps=st.lists(st.floats(-1.2, 1.2).filter(lambda v: abs(v) > 1e-4), min_size=1, max_size=40),
)
def test_square_rod_rows_in_any_order_follow_the_continued_branch(start, steps):
    # any row order: a random walk of the crank (steps up to 69 deg either way), crossing the pose as it comes
    _check_square_rod_rows(_square_rod(), start + np.concatenate([[0.0], np.cumsum(steps)]))


def test_square_rod_rates_at_the_square_pose_are_the_limit_of_the_continued_branch():
    # a row exactly on the pose (and rows 1e-12 .. 3e-2 rad from it): J_z is singular there, the rates are the
    # limit of the branch either side: v_B = (10 - 10 sqrt(3)) qd, a_B = (10 - 10 sqrt(3)) qdd + 0 qd^2, and the rod
    # turns at sqrt(r / l) qd = qd / sqrt(3) with angular acceleration qdd / sqrt(3) (its second derivative in
    # theta is 0 there: rod angle = atan2(h, x_B - x_A) with |AB| = 30 and (x_B - x_A)'' = h'' ... = 0 at the pose)
    m = _square_rod()
    qd, qdd = 2.0, 0.7
    for d in (0.0, 1e-12, -1e-10, 1e-8, 1e-6, -1e-5, 1e-4, -1e-3, 5e-3, -1.2e-2, 3e-2):
        q = np.array([0.0, 1.5 * np.pi + d, 1.5 * np.pi + 0.1])
        r = m.solve(q, np.full(3, qd), np.full(3, qdd))
        assert r.closed.all() and r.reason[1] == ""
        (x, v, a), _ = _xb_terms(q[1])
        assert abs(r.velocity["B"][1, 0] - v * qd) < 1e-11 * 27.4 * qd
        assert abs(r.acceleration["B"][1, 0] - (a * qd * qd + v * qdd)) < 1e-9 * (18.1 * qd * qd + 27.4 * qdd)
        if d == 0.0:
            assert v == pytest.approx(10.0 - 10.0 * math.sqrt(3.0), rel=1e-15) and abs(a) < 1e-14
            assert abs(r.velocity["B"][1, 0] - (10.0 - 10.0 * math.sqrt(3.0)) * qd) < 1e-10
            assert abs(r.acceleration["B"][1, 0] - (10.0 - 10.0 * math.sqrt(3.0)) * qdd) < 1e-8
            assert abs(r.omega["rod"][1] - qd / math.sqrt(3.0)) < 1e-11
            assert abs(r.alpha["rod"][1] - qdd / math.sqrt(3.0)) < 1e-9


@pytest.mark.parametrize("direction", [1, -1])
@pytest.mark.parametrize("n", [7, 37, 361, 2001])
def test_parallelogram_any_rows_stay_a_parallelogram(n, direction):
    # the parallelogram four-bar 4 / 10 / 4 / 10 from any start and either way: the rocker parallel to the crank
    # (its angle the crank's, rate qd, acceleration qdd), the coupler translating (angle, rate, acceleration 0)
    m = _parallelogram()
    for off in OFFSETS:
        q = (np.pi / 2 + off + np.linspace(0.0, 2 * np.pi, n))[::direction]
        qd = 1.3 * direction
        r = m.solve(q, np.full(n, qd), np.full(n, 0.4))
        assert r.closed.all() and set(r.reason) == {""}
        assert np.abs(np.sin(r.angle["rocker"] - q)).max() < 1e-9 and np.abs(np.sin(r.angle["coupler"])).max() < 1e-9
        assert np.abs(r.omega["rocker"] - qd).max() < 1e-8 and np.abs(r.omega["coupler"]).max() < 1e-8
        assert np.abs(r.alpha["rocker"] - 0.4).max() < 1e-6 and np.abs(r.alpha["coupler"]).max() < 1e-6
        # a branch point at each folding pose passed (crank at 180 and 360 deg), from the sketch through every row
        expect = _crossings(np.concatenate([[np.pi / 2], q]), at=math.pi, period=math.pi)
        got = [p.q[0] for p in r.branch_points]
        assert len(got) == len(expect) and np.allclose(got, expect, rtol=0, atol=1e-9), (got, expect)
