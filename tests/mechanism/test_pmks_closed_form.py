"""gearlever against the closed-form cases of the PMKS+ application's verification suite.

Source: PMKS-Web, "PMKS+ (Planar Mechanism Kinematic Simulator)", the web application's verification tests
(https://github.com/PMKS-Web/Planar-Mechanism-Kinematic-Simulator, MIT licence): the gear pair
(gear-kinematics), the inverted slider-crank and its Whitworth proportions (inverted-slider-crank,
slot-kinematics), the Scotch yoke (scotch-yoke-kinematics), the driven elliptical trammel (slot-mobility), the
Peaucellier-Lipkin cell (peaucellier) and the five-cylinder radial engine (radial-engine).  The numbers PMKS+
states are in ``gearlever/data/pmks_closed_form.csv`` with that source in its header; where PMKS+ states only
the closed form, the reference is that closed form evaluated here, from the case's dimensions, independently
of gearlever's solver.  The models (test data beside this file) are PMKS+'s fixtures, one for one.

PMKS+ asserts its closed forms to 3 decimals (its positions are rounded to 4); gearlever is held to 1e-12
(positions, relative to the model's size), 1e-11 (velocities) and 1e-10 (accelerations), relative to the
largest value of the quantity.  Sign convention: the slot rates compared here are derivatives of the travel
(PMKS+ writes a grounded slider's velocity and acceleration in its prismatic tables as minus the derivative;
none of these cases uses them).  The rocking cases (trammel, Peaucellier cell) are swept as PMKS+ sweeps
them: from the sketch to one limit, back to the other, back (directions +1, -1, +1).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import brentq

from gearlever.data import read_records
from gearlever.mechanism import Mechanism, input_limits, sweep_rows

DATA = Path(__file__).parent / "data"
TOL = {"position": 1e-12, "velocity": 1e-11, "acceleration": 1e-10}
REF = {(r["case"], r["quantity"]): r for r in read_records("pmks_closed_form.csv")}


def load(case: str) -> Mechanism:
    return Mechanism.load(DATA / f"pmks_{case}.toml")


def published(case: str, quantity: str) -> tuple[float, float]:
    """The value PMKS+ states and its tolerance (absolute; ``1e-12`` is relative)."""
    r = REF[(case, quantity)]
    value, tol = float(r["value"]), float(r["tolerance"])
    return value, (tol * max(abs(value), 1.0) if tol <= 1e-12 else tol)


def close(name: str, got, ref, kind: str) -> float:
    got, ref = np.asarray(got, float), np.asarray(ref, float)
    scale = max(float(np.abs(ref).max()), 1.0)
    err = float(np.abs(got - ref).max())
    assert err <= TOL[kind] * scale, f"{name}: max difference {err:.3g} > {TOL[kind]:g} x {scale:.3g}"
    return err


def turn(deg_step: float = 1.0, start: float = 0.0) -> np.ndarray:
    """One turn of an input in ``deg_step`` steps from ``start`` (rad), end excluded."""
    return start + np.radians(np.arange(0.0, 360.0, deg_step))


def pmks_oscillation(start: float, lower: float, upper: float, step: float) -> tuple[np.ndarray, np.ndarray]:
    """PMKS+'s sweep of a rocking input: inputs and directions.

    From ``start`` by ``step`` while the next step stays before ``upper``, reverse (the last row again, direction
    -1), down while the next step stays above ``lower``, reverse, up to ``start``: directions +1, -1, +1.
    """
    up = start + step * np.arange(0, math.floor((upper - start) / step) + 1)
    down = up[-1] - step * np.arange(0, math.floor((up[-1] - lower) / step) + 1)
    back = down[-1] + step * np.arange(0, math.floor((start - down[-1]) / step + 1e-9) + 1)
    q = np.concatenate([up, down, back])
    d = np.concatenate([np.ones(up.size), -np.ones(down.size), np.ones(back.size)])
    return q, d


def test_every_published_value_has_its_source_and_every_case_its_model():
    cases = {c for c, _ in REF}
    assert cases == {
        "gear_pair",
        "inverted_slider_crank",
        "whitworth",
        "scotch_yoke",
        "elliptical_trammel",
        "peaucellier",
        "radial_engine",
    }
    for (case, _q), r in REF.items():
        assert (DATA / f"pmks_{case}.toml").is_file()
        assert r["pmks_test"] and r["closed_form"]
        assert r["value"] == "" or r["tolerance"] != ""


@pytest.mark.parametrize("direction", [1, -1])
def test_gear_pair_turns_the_big_gear_at_minus_half_the_speed_pmks_closed_form(direction):
    """D on gear 2 at theta = pi/3 - q/2; omega = -pi for 2 pi rad/s at gear 1; v_Dx = pi y_D, a_Dx = -pi^2 x_D."""
    m = load("gear_pair")
    ratio, rtol = published("gear_pair", "speed_ratio")
    turns, _ = published("gear_pair", "cycle_turns")
    w = direction * 2.0 * math.pi
    q = direction * np.radians(np.arange(0.0, 360.0 * turns + 1.0, 2.0))
    r = m.solve(q, np.full_like(q, w), np.zeros_like(q))
    assert r.closed.all()
    theta = math.pi / 3 + ratio * q
    D = np.stack([np.cos(theta), np.sin(theta)], axis=1)
    close("gear pair D", r.point["D"], D, "position")
    close("gear pair omega", r.omega["gear2"], ratio * w + 0 * q, "velocity")
    assert abs(r.omega["gear2"][0] - (-direction * math.pi)) <= rtol * math.pi
    close("gear pair alpha", r.alpha["gear2"], 0 * q, "acceleration")
    close("gear pair v_D", r.velocity["D"], np.stack([-ratio * w * D[:, 1], ratio * w * D[:, 0]], 1), "velocity")
    assert np.abs(r.velocity["D"][:, 0] - direction * math.pi * D[:, 1]).max() <= 1e-11 * math.pi
    close("gear pair a_D", r.acceleration["D"], -((ratio * w) ** 2) * D, "acceleration")
    assert np.abs(r.acceleration["D"][:, 0] + math.pi**2 * D[:, 0]).max() <= 1e-10 * math.pi**2
    # the cycle: after `turns` turns of gear 1 gear 2 is back at its sketch, after one it is half a turn on
    assert np.abs(r.point["D"][-1] - r.point["D"][0]).max() <= 1e-12
    half = np.flatnonzero(np.isclose(np.abs(q), 2 * math.pi))[0]
    assert np.abs(r.point["D"][half] + r.point["D"][0]).max() <= 1e-12


def _inverted(case, r_crank, d_offset, w):
    m = load(case)
    t = turn(1.0, math.pi / 2)
    res = m.solve(t, np.full_like(t, w), np.zeros_like(t))
    assert res.closed.all()
    s = np.sqrt(r_crank**2 + d_offset**2 - 2 * r_crank * d_offset * np.cos(t))
    return m, t, res, s


@pytest.mark.parametrize("w", [1.0, -1.0])
@pytest.mark.parametrize("case, r_crank, d_offset", [("inverted_slider_crank", 1.0, 3.0), ("whitworth", 3.0, 1.0)])
def test_inverted_slider_crank_slot_travel_and_lever_match_the_pmks_closed_forms(case, r_crank, d_offset, w):
    """Travel s from C to the block along the lever and the lever's angle, rate and acceleration (PMKS+'s formulas)."""
    m, t, res, s = _inverted(case, r_crank, d_offset, w)
    rd = r_crank * d_offset
    s0 = math.sqrt(r_crank**2 + d_offset**2)  # the sketch: t = 90 deg
    close(f"{case} travel", res.displacement["block"], s - s0, "position")
    close(f"{case} travel rate", res.slider_velocity["block"], w * rd * np.sin(t) / s, "velocity")
    sdd = w**2 * rd * (s**2 * np.cos(t) - rd * np.sin(t) ** 2) / s**3
    close(f"{case} travel acceleration", res.slider_acceleration["block"], sdd, "acceleration")
    phi = np.arctan2(r_crank * np.sin(t), r_crank * np.cos(t) - d_offset)
    dphi = np.angle(np.exp(1j * (res.angle["lever"] - phi)))  # angles compared on the circle
    close(f"{case} lever angle", dphi, 0 * t, "position")
    close(f"{case} lever omega", res.omega["lever"], w * r_crank * (r_crank - d_offset * np.cos(t)) / s**2, "velocity")
    a4 = w**2 * rd * np.sin(t) * (d_offset**2 - r_crank**2) / s**4
    close(f"{case} lever alpha", res.alpha["lever"], a4, "acceleration")


def test_the_rocking_lever_reverses_where_cos_t_is_r_over_d_and_gives_the_quick_return_ratio():
    """PMKS+: reversals at cos t = r/d (r = 1, d = 3); time ratio (pi - beta)/beta, beta = acos(r/d)."""
    m = load("inverted_slider_crank")
    cos_rev, tol = published("inverted_slider_crank", "reversal_cos")

    def lever_omega(t):
        return m.solve(np.array([t]), np.array([1.0]), np.array([0.0])).omega["lever"][0]

    found = [brentq(lever_omega, a, b, xtol=1e-14) for a, b in ((0.5, 1.5), (-1.5, -0.5))]
    assert all(abs(math.cos(t) - cos_rev) <= tol for t in found)
    beta = math.acos(1.0 / 3.0)
    slow, quick = 2 * math.pi - (found[0] - found[1]), found[0] - found[1]
    assert slow / quick == pytest.approx((math.pi - beta) / beta, rel=1e-12)
    assert quick == pytest.approx(2 * beta, rel=1e-12)


def test_the_whitworth_lever_turns_once_per_crank_turn_without_reversing():
    m, t, res, s = _inverted("whitworth", 3.0, 1.0, 1.0)
    turns, tol = published("whitworth", "lever_turns_per_crank_turn")
    assert np.all(res.omega["lever"] > 0)
    t2 = np.append(t, t[0] + 2 * math.pi)
    full = m.solve(t2, np.ones_like(t2), np.zeros_like(t2))
    swept = np.unwrap(full.angle["lever"])
    assert (swept[-1] - swept[0]) / (2 * math.pi) == pytest.approx(turns, abs=tol)


@pytest.mark.parametrize("w", [1.0, -1.0])
def test_scotch_yoke_translates_as_r_cos_t_and_never_turns_pmks_closed_form(w):
    m = load("scotch_yoke")
    t = turn(1.0)
    res = m.solve(t, np.full_like(t, w), np.zeros_like(t))
    assert res.closed.all()
    omega0, tol = published("scotch_yoke", "yoke_omega")
    close("yoke x", res.point["C"][:, 0], np.cos(t), "position")
    close("yoke y", res.point["C"][:, 1], 0 * t - 2.0, "position")
    close("yoke x'", res.velocity["C"][:, 0], -w * np.sin(t), "velocity")
    close("yoke x''", res.acceleration["C"][:, 0], -(w**2) * np.cos(t), "acceleration")
    for name in ("C", "D"):
        assert np.abs(res.velocity[name][:, 1]).max() <= 1e-12
    assert np.abs(res.omega["yoke"] - omega0).max() <= tol and np.abs(res.alpha["yoke"] - omega0).max() <= tol


def test_elliptical_trammel_swept_as_pmks_keeps_its_ends_on_a_circle_and_traces_the_ellipse():
    """A at (p, 0), B at (0, q): p^2 + q^2 = L^2; T = A + (B - A)/3 on x^2/(L - d)^2 + y^2/d^2 = 1, d = L/3."""
    m = load("elliptical_trammel")
    L2, tol = published("elliptical_trammel", "bar_ends")
    L = math.sqrt(L2)
    lim = input_limits(m)
    assert lim.rocks and lim.lower == pytest.approx(-1 - L, abs=1e-9) and lim.upper == pytest.approx(L - 1, abs=1e-9)
    s, d = pmks_oscillation(0.0, lim.lower, lim.upper, 0.01)
    assert s.max() <= lim.upper and s.min() >= lim.lower and np.count_nonzero(np.diff(d)) == 2
    pdot = 1.0 * d  # PMKS+ drives the slide at a constant speed signed by the direction
    res = m.solve(s, pdot, np.zeros_like(s))
    assert res.closed.all()
    p = 1.0 + s
    A, B, T = res.point["A"], res.point["B"], res.point["T"]
    assert np.abs(A[:, 0] ** 2 + B[:, 1] ** 2 - L2).max() <= tol
    q = np.sqrt(L2 - p**2)
    close("trammel A", A, np.stack([p, 0 * p], 1), "position")
    close("trammel B", B, np.stack([0 * p, q], 1), "position")
    d = L / 3
    x, y = T[:, 0], T[:, 1]
    assert np.abs(x**2 / (L - d) ** 2 + y**2 / d**2 - 1.0).max() <= 1e-12
    # rates, away from the limits (q -> 0 there): q' = -p p'/q, T' = (2 p'/3, q'/3)
    inner = np.abs(q) > 0.05
    qdot = -p * pdot / q
    close("trammel T'", res.velocity["T"][inner], np.stack([2 * pdot / 3, qdot / 3], 1)[inner], "velocity")
    qddot = -(pdot**2 + qdot**2) / q
    close("trammel B''", res.acceleration["B"][inner, 1], qddot[inner], "acceleration")


def test_peaucellier_cell_rules_the_line_x_4_6875_between_its_published_stops():
    """Swept as PMKS+ sweeps it; Q.x = (5^2 - 2.5^2)/(2 * 2) and |OP||OQ| = 18.75 at every row."""
    m = load("peaucellier")
    line_x, tol_x = published("peaucellier", "line_x")
    power, tol_p = published("peaucellier", "inversion_power")
    limit_deg, tol_deg = published("peaucellier", "crank_limit")
    length, tol_len = published("peaucellier", "line_length")
    lim = input_limits(m)
    # the stops: |OP| = 4 cos(t/2) = long - side, t from the far point of the crank circle (the +x axis)
    t_lim = 2 * math.acos((5.0 - 2.5) / 4.0)
    assert lim.rocks and lim.upper == pytest.approx(t_lim, abs=1e-9) and lim.lower == pytest.approx(-t_lim, abs=1e-9)
    assert math.degrees(lim.upper) == pytest.approx(limit_deg, abs=tol_deg)
    assert math.degrees(-lim.lower) == pytest.approx(limit_deg, abs=tol_deg)
    sw = sweep_rows(m, 200)
    assert sw.oscillates and sw.direction[0] == 1 and np.count_nonzero(np.diff(sw.direction)) == 2
    res = m.solve(sw.q, sw.qdot, np.zeros_like(sw.q))
    assert res.closed.all()
    Q, P = res.point["Q"], res.point["P"]
    assert np.abs(Q[:, 0] - line_x).max() <= tol_x * 10  # 1e-11: positions to 1e-12 of the size (5)
    assert np.abs(np.hypot(*P.T) * np.hypot(*Q.T) - power).max() <= tol_p * 100
    assert np.abs(res.velocity["Q"][:, 0]).max() <= 1e-10 and np.abs(res.acceleration["Q"][:, 0]).max() <= 1e-8
    # PMKS+'s own sweep (1-degree steps, reversing before each stop) stays on the line too
    t, d = pmks_oscillation(m.sketch_inputs[0], lim.lower, lim.upper, math.radians(1.0))
    own = m.solve(t, 10 * math.pi / 30 * d, np.zeros_like(t))  # PMKS+ turns it at 10 rpm
    assert own.closed.all() and np.abs(own.point["Q"][:, 0] - line_x).max() <= tol_x * 10
    # the pen's stroke between the stops: Q.y = x_Q tan(t/2), the published 11.7 units
    path = np.concatenate([np.linspace(m.sketch_inputs[0], lim.upper, 50), np.linspace(lim.upper, lim.lower, 100)])
    ends = m.solve(path * (1 - 1e-9), np.zeros_like(path), np.zeros_like(path))
    stroke = np.ptp(ends.point["Q"][[49, -1], 1])
    assert stroke == pytest.approx(2 * line_x * math.tan(t_lim / 2), rel=1e-6)
    assert stroke == pytest.approx(length, abs=tol_len)


@pytest.mark.parametrize("w", [1.0, -1.0])
def test_radial_engine_pistons_follow_the_slider_crank_closed_form_with_a_stroke_of_twice_the_throw(w):
    m = load("radial_engine")
    stroke, tol = published("radial_engine", "stroke")
    spacing, tol_s = published("radial_engine", "tdc_spacing")
    r_crank, rod = 1.0, 3.0
    t = turn(1.0)
    res = m.solve(t, np.full_like(t, w), np.zeros_like(t))
    assert res.closed.all()
    axes = [math.pi / 2 + k * 2 * math.pi / 5 for k in range(5)]
    for k, name in enumerate("BCDEF"):
        u = t - axes[k]
        root = np.sqrt(rod**2 - (r_crank * np.sin(u)) ** 2)
        s = r_crank * np.cos(u) + root
        s0 = r_crank * math.cos(-axes[k]) + math.sqrt(rod**2 - (r_crank * math.sin(-axes[k])) ** 2)
        ds = -r_crank * np.sin(u) * (1 + r_crank * np.cos(u) / root)
        dds = -r_crank * np.cos(u) - (
            r_crank**2 * np.cos(2 * u) / root + r_crank**4 * np.sin(u) ** 2 * np.cos(u) ** 2 / root**3
        )
        close(f"piston {name}", res.displacement[f"piston{name}"], s - s0, "position")
        close(f"piston {name} rate", res.slider_velocity[f"piston{name}"], w * ds, "velocity")
        close(f"piston {name} acceleration", res.slider_acceleration[f"piston{name}"], w**2 * dds, "acceleration")
        # top and bottom dead centres: the crank along the guide (t = a) and against it (t = a + pi)
        tb = np.array([axes[k], axes[k] + math.pi])
        ends = m.solve(tb, np.ones(2), np.zeros(2))
        travel = ends.displacement[f"piston{name}"]
        assert travel[0] - travel[1] == pytest.approx(stroke * r_crank, abs=tol)
        assert np.abs(ends.slider_velocity[f"piston{name}"]).max() <= 1e-12
        assert travel[0] >= res.displacement[f"piston{name}"].max() - 1e-12
        assert travel[1] <= res.displacement[f"piston{name}"].min() + 1e-12
    gaps = np.diff(np.array(axes)) / (2 * math.pi)
    assert np.abs(gaps - spacing).max() <= tol_s
