"""Published textbook problems: epicyclic holding torques, engine crank effort and flywheel sizing.

Source of every problem and answer: R. S. Khurmi and J. K. Gupta, *Theory of Machines*,
14th ed., Eurasia Publishing House, New Delhi, 2009 (example and page named in each test),
answers as reproduced in the FOSSEE Python Textbook Companion to that edition.  The data and
the published answers live in the package data files; each tolerance and its reason is there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from gearlever.data import read_records
from gearlever.errors import GearleverError
from gearlever.flywheels import published as P
from gearlever.flywheels.flywheel import flywheel


@pytest.fixture(scope="module")
def checks():
    return P.textbook_checks()


def _assert_rows(checks, example):
    rows = checks.example == example
    assert rows.sum() >= 1
    for q, pub, comp, tol in zip(
        checks.quantity[rows], checks.published[rows], checks.computed[rows], checks.tolerance[rows], strict=True
    ):
        assert abs(comp - pub) <= tol, f"example {example} {q}: computed {comp}, published {pub} +- {tol}"


def _book_method_forces(example):
    """The book's own arithmetic run through the model: a massless piston loaded by the gas force less
    the reciprocating mass times the two-term series acceleration w^2 r (cos t + cos 2t / n)."""
    spec = dict(P.problems()["engine"][example])
    mass = spec["reciprocating_mass"]
    spec["reciprocating_mass"] = 0.0
    th = math.radians(spec["crank_angle_deg"])
    w = P._omega(spec)
    n = spec["rod"] / spec["crank"]
    a_series = w**2 * spec["crank"] * (math.cos(th) + math.cos(2 * th) / n)
    return P.engine_forces(spec, P._gas_force(spec) - mass * a_series)


# --------------------------------------------------------------------------- epicyclic torques


def test_khurmi_gupta_example_13_20_page_465_holding_torque_of_the_internal_gear(checks):
    """Sun 16, planets 24, internal gear 64 held, 100 N m on the sun (speed ratio 5): the internal gear
    must be held with 400 N m; the arm gives 500 N m, and the external torques sum to zero."""
    _assert_rows(checks, "13.20")
    r = P.epicyclic_problem("13.20")
    assert r["output_speed"] == pytest.approx(1.0 / 5.0, rel=1e-15)
    assert r["output_torque"] == pytest.approx(100.0 + r["holding_torque"], rel=1e-15)


def test_khurmi_gupta_example_13_22_page_468_compound_epicyclic_holding_torque(checks):
    """Internal gear A 60 on the input shaft at 740 rad/s with 130 kW, compound planet B 15 / C 20,
    sun D 25 held: arm X at 563.8 rad/s, holding torque on D 54.9 N m; power in equals power out."""
    _assert_rows(checks, "13.22")
    r = P.epicyclic_problem("13.22")
    assert r["output_torque"] * r["output_speed"] == pytest.approx(130e3, rel=1e-12)


# --------------------------------------------------------------------------- engine crank effort


def test_khurmi_gupta_example_15_7_page_533_horizontal_engine_crank_effort(checks):
    """Horizontal engine, crank 300 mm, rod 1.2 m, bore 0.5 m, 0.35 N/mm^2 net, 250 kg at 250 rpm, 60 deg
    from i.d.c.: slide-bar force 10.97 kN, rod thrust 50.65 kN, crank-pin effort 48.30 kN, 14.491 kN m."""
    _assert_rows(checks, "15.7")
    assert checks.value("15.7", "crank_torque")[1] == pytest.approx(14.4895, abs=1e-4)


def test_khurmi_gupta_example_15_7_page_533_book_series_acceleration_gives_the_printed_digits(checks):
    """With the book's series piston acceleration put in, the model's force analysis gives every printed
    answer to its last digit: the remaining deviation of the exact model is the series, nothing else."""
    book = _book_method_forces("15.7")
    for q in ("slide_bar_force", "rod_thrust", "crank_pin_tangential_force"):
        pub = checks.value("15.7", q)[0]
        assert book[q] / 1e3 == pytest.approx(pub, abs=0.005), q
    assert book["crank_torque"] / 1e3 == pytest.approx(checks.value("15.7", "crank_torque")[0], abs=0.0005)


def test_khurmi_gupta_example_15_12_page_538_double_acting_steam_engine_bearing_thrust_and_flywheel(checks):
    """Double-acting steam engine, piston rod 50 mm, 550 and 70 kN/m^2, 60 kg at 120 rpm, 45 deg:
    thrust on the bearings 11.98 kN; with 20 kW taken off and a 60 kg flywheel of k = 0.6 m its
    acceleration is 108.2 rad/s^2."""
    _assert_rows(checks, "15.12")
    book = _book_method_forces("15.12")
    assert book["bearing_thrust"] / 1e3 == pytest.approx(checks.value("15.12", "bearing_thrust")[0], abs=0.005)


def test_khurmi_gupta_example_15_20_page_555_connecting_rod_inertia_torque(checks):
    """Horizontal engine with a heavy rod (250 kg, G 500 mm from the crank pin, k = 650 mm), 300 kg
    reciprocating, 125 rpm, 30 deg from i.d.c.: inertia and rod-weight torque on the shaft 3840 N m."""
    _assert_rows(checks, "15.20")
    # the rod's weight is part of it: without gravity the torque is some 425 N m smaller
    spec = dict(P.problems()["engine"]["15.20"], gravity=0.0)
    mech, th = P.engine_mechanism(spec)
    w = P._omega(spec)
    no_weight = abs(float(mech.inverse_dynamics([th], [w], [0.0]).input_force[0, 0]))
    weight_torque = 250.0 * 9.81 * (1.0 / 1.5) * 0.3 * math.cos(th)  # rod mass at the crank pin, m2 g r cos t
    assert checks.value("15.20", "inertia_torque")[1] - no_weight == pytest.approx(weight_torque, rel=1e-12)


# --------------------------------------------------------------------------- flywheel sizing


def test_khurmi_gupta_example_16_11_page_585_multicylinder_engine_flywheel(checks):
    """T = 20000 + 9500 sin 2t - 5700 cos 2t N m at 180 rpm, speed within +-0.5 %: 377 kW,
    dE = 11078 N m, I = 3121 kg m^2, acceleration 3.044 rad/s^2 at 45 deg."""
    _assert_rows(checks, "16.11")
    assert checks.value("16.11", "energy_fluctuation")[1] == pytest.approx(math.hypot(9500, 5700), rel=1e-7)


def test_khurmi_gupta_example_16_12_page_587_flywheel_with_varying_resisting_torque(checks):
    """Driving 5000 + 600 sin 2t, resisting 5000 + 500 sin t N m, 500 kg flywheel of k = 0.4 m at
    150 rpm: dE = 1204 N m, fluctuation 6.1 %, acceleration extremes 3.46 (35 deg) and -12.2 rad/s^2
    (127.6 deg)."""
    _assert_rows(checks, "16.12")


def test_khurmi_gupta_example_16_13_page_589_three_crank_engine_flywheel(checks):
    """T = 5000 + 1500 sin 3t N m, I = 1000 kg m^2 at 300 rpm, constant load: 157.1 kW, fluctuation 0.1 %."""
    _assert_rows(checks, "16.13")
    # one loop of 1500 sin 3t over 60 deg: dE = 1000 N m exactly
    assert P.flywheel_problem("16.13")["energy_fluctuation"] == pytest.approx(1000.0, rel=1e-7)


def test_every_published_answer_is_checked_and_has_a_source_page():
    rows = read_records(P.ANSWERS)
    pages = {"13.20": "465", "13.22": "468", "15.7": "533", "15.12": "538", "15.20": "555"}
    pages |= {"16.11": "585", "16.12": "587", "16.13": "589"}
    assert {r["example"] for r in rows} == set(pages)  # each has its named test above
    kinds = {"13": "epicyclic", "15": "engine", "16": "flywheel"}
    problems = P.problems()
    for r in rows:
        assert r["page"] == pages[r["example"]]
        assert problems[kinds[r["example"][:2]]][r["example"]]["page"] == int(r["page"])
        assert r["basis"], f"{r['example']} {r['quantity']}: the tolerance has no stated reason"


def test_a_tolerance_above_half_a_percent_is_only_the_printed_precision(checks):
    """6.1 %, 35 deg and 0.1 % are printed with one or two digits: half their last digit is the bound."""
    wide = checks.tolerance > 0.005 * np.abs(checks.published)
    for pub, tol, basis in zip(checks.published[wide], checks.tolerance[wide], checks.basis[wide], strict=True):
        assert basis.startswith("printed to"), basis
        last_digit = 10.0 ** math.floor(math.log10(2 * tol) + 1e-9)  # 0.05 -> 0.1, 0.5 -> 1
        assert tol == pytest.approx(last_digit / 2) and pub == pytest.approx(round(pub / last_digit) * last_digit)


def test_the_table_of_checks_has_units_and_no_failing_row(checks):
    df = checks.to_frame()
    assert {"example", "published", "computed", "tolerance"} <= set(df.columns)
    assert bool(checks.within.all())


def test_unknown_example_is_refused_by_name():
    with pytest.raises(GearleverError, match="example must be one of"):
        P.crank_effort("99.9")
    with pytest.raises(GearleverError, match="example must be one of"):
        P.flywheel_problem("15.7")


# --------------------------------------------------------------------------- the acceleration it uses


def test_flywheel_acceleration_is_the_time_derivative_of_the_speed_finite_differences():
    """omega(theta) = sqrt(w0^2 + 2 E / I) and alpha = d omega/dt = omega d omega/d theta = (T - L) / I."""
    th = np.linspace(0.0, 2 * np.pi, 20001)
    T = 1000.0 + 300.0 * np.sin(2 * th) - 120.0 * np.cos(3 * th)
    f = flywheel(th, T, 200.0, inertia=5.0)
    w0 = f.mean_speed
    omega = np.sqrt(w0**2 + 2.0 * f.energy / f.inertia)
    fd = omega * np.gradient(omega, th)
    inner = slice(5, -5)
    assert np.max(np.abs(fd[inner] - f.angular_acceleration[inner])) <= 1e-5 * np.max(np.abs(f.angular_acceleration))


def test_flywheel_acceleration_needs_an_inertia():
    th = np.linspace(0.0, 2 * np.pi, 101)
    assert flywheel(th, 10.0 + np.sin(th), 100.0).angular_acceleration is None
