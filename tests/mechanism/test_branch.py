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
    assert r.dead_rows.tolist() == [541] and r.reason[541].startswith("dead point between row 540")
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
    assert r.closed[:751].all() and not r.closed[751:].any() and r.dead_rows.tolist() == [751]
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
