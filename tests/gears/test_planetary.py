"""Tests of gearlever.gears.planetary and gearlever.gears.epicyclic: Willis' equation, the tabular
method, the assembly conditions and the exhaustive tooth search (checked by brute force)."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.gears import willis
from gearlever.gears.epicyclic import tabular_method
from gearlever.gears.networks import FRAME, Gear, Mesh, Network, SameShaft, parse_network
from gearlever.gears.planetary import (
    MAX_TEETH,
    basic_ratio,
    design_planetary,
    planetary_network,
    speed_ratio,
)

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def example(name):
    return parse_network((EXAMPLES / f"{name}.csv").read_text())


def willis_driven(lead, carrier, z_lead, z_driven, mesh):
    """Willis' equation in floats, from the other helper's module (the one statement of its sign rule)."""
    return float(willis.driven_speed(lead, carrier, z_lead / z_driven, mesh))


# --- the example networks against their hand derivations --------------------------------------


def test_ferguson_paradox_minus_1_99_zero_plus_1_101_per_arm_turn():
    # hand derivation: 100 (0 - a) + 20 (p - a) = 0 -> 20 (p - a) = 100 a; z (w - a) = -100 a -> w = a (1 - 100/z)
    sol = example("ferguson_paradox").solve(["arm"])
    for z in (99, 100, 101):
        assert sol.coefficients[f"w{z}"] == (1 - Fraction(100, z),)
    assert [sol.coefficients[f"w{z}"][0] for z in (99, 100, 101)] == [Fraction(-1, 99), 0, Fraction(1, 101)]
    assert sol.coefficients["planet"] == (Fraction(6),)
    # Willis (floats): arm 1 turn, fixed wheel 0: planet relative turns, then each wheel
    planet = willis_driven(0.0, 1.0, 100, 20, "external")
    for z in (99, 101):
        assert willis_driven(planet, 1.0, 20, z, "external") == pytest.approx(float(sol.coefficients[f"w{z}"][0]))


def test_ferguson_tabular_method_rows_match_the_textbook_procedure():
    t = tabular_method(example("ferguson_paradox"), "arm", ["arm"])
    rows = {r.member: r for r in t.rows}
    assert t.turned == "fixed" and t.x == (-1,) and t.y == (1,)
    # arm fixed, the fixed wheel turned +1: planet -100/20, wheel z: +100/z
    assert rows["planet"].relative == Fraction(-5)
    assert rows["w99"].relative == Fraction(100, 99) and rows["w101"].relative == Fraction(100, 101)
    for r in t.rows:
        assert r.total == (t.y[0] + t.x[0] * r.relative,)


def test_simple_planetary_ratio_is_1_plus_zr_over_zs_and_planet_by_willis():
    sol = example("simple_planetary").solve(["sun"])
    assert sol.coefficients["carrier"] == (1 / (1 + Fraction(60, 24)),)
    c = float(sol.coefficients["carrier"][0])
    assert float(sol.coefficients["planet"][0]) == pytest.approx(willis_driven(1.0, c, 24, 18, "external"))
    assert willis_driven(float(sol.coefficients["planet"][0]), c, 18, 60, "internal") == pytest.approx(0, abs=1e-15)


def test_compound_planetary_ratio_is_1_plus_zp1_zr_over_zs_zp2():
    sol = example("compound_planetary").solve(["sun"])
    assert sol.coefficients["carrier"] == (1 / (1 + Fraction(40 * 80, 20 * 20)),)
    assert sol.coefficients["p1"] == sol.coefficients["p2"]


def test_car_differential_example_equals_car_network():
    from gearlever.gears.car import car_network

    a = example("car_differential").solve(["pinion", "left"])
    b = car_network(10, 40).solve(["pinion", "left"])
    assert a.coefficients == b.coefficients
    t = tabular_method(example("car_differential"), "carrier", ["pinion", "left"], turned="left")
    rows = {r.member: r for r in t.rows}
    assert rows["pinion"].relative is None and rows["right"].relative == -1


def test_reverted_train_is_product_of_drivers_over_followers():
    sol = example("reverted_train").solve(["A"])
    assert sol.coefficients["D"] == (Fraction(20 * 18, 40 * 42),)


# --- Willis: random planetary networks against the closed form ---------------------------------

roles = st.permutations(["sun", "ring", "carrier"])


@settings(max_examples=80, deadline=None)
@given(st.integers(8, 80), st.integers(8, 60), st.integers(8, 60), roles, st.booleans())
def test_random_planetary_network_equals_closed_form_willis_ratio(zs, p1, p2, order, compound):
    fixed, inp, out = order
    if compound:
        zr = zs + p1 + p2
        net = planetary_network(zs, zr, planet1=p1, planet2=p2, fixed=fixed)
        i0 = basic_ratio(zs, zr, p1, p2)
    else:
        zr = zs + 2 * p1
        net = planetary_network(zs, zr, planet=p1, fixed=fixed)
        i0 = basic_ratio(zs, zr)
    sol = net.solve([inp])
    assert 1 / sol.coefficients[out][0] == speed_ratio(i0, fixed, inp, out)
    # Willis with the carrier held, in floats: i0 = (w_s - w_c)/(w_r - w_c)
    free = Network(net.gears, [c for c in net.constraints if c.label != "fixed"]).solve(["ring", "carrier"])
    s = free.rotation("sun", {"ring": 1, "carrier": 0})
    assert s == i0
    planet = "planet" if not compound else "planet1"
    w_p = float(free.rotation(planet, {"ring": 1, "carrier": 0}))
    assert willis_driven(float(s), 0.0, zs, p1, "external") == pytest.approx(w_p)


@settings(max_examples=40, deadline=None)
@given(st.integers(8, 80), st.integers(8, 60), roles)
def test_tabular_totals_equal_the_network_solution(zs, zp, order):
    fixed, inp, _ = order
    net = planetary_network(zs, zs + 2 * zp, planet=zp, fixed=fixed)
    t = tabular_method(net, "carrier", [inp], turned="sun")
    sol = net.solve([inp])
    for r in t.rows:
        assert r.total == sol.coefficients[r.member]
        assert r.total[0] == t.y[0] + t.x[0] * r.relative


def test_tabular_method_errors():
    net = example("simple_planetary")
    with pytest.raises(ValueError, match="carrier 'arm' is not a member"):
        tabular_method(net, "arm", ["sun"])
    with pytest.raises(ValueError, match="other than the carrier"):
        tabular_method(net, "carrier", ["sun"], turned="carrier")
    with pytest.raises(ValueError, match="no gear meshes on it"):
        tabular_method(net, "sun", ["sun"])


# --- assembly conditions and the exhaustive search ---------------------------------------------


def brute_simple(target, n, lo, hi, fixed="ring", inp="sun", out="carrier"):
    sets = []
    for zs in range(lo, hi + 1):
        for zp in range(lo, hi + 1):
            zr = zs + 2 * zp
            if zr > hi:
                break
            if (zs + zr) % n or not (zp + 2 < (zs + zp) * math.sin(math.pi / n)):
                continue
            sets.append((zs, zp, zr, speed_ratio(Fraction(-zr, zs), fixed, inp, out)))
    best = min(abs(r - target) for *_, r in sets)
    return sorted(((zr, zs, zp) for zs, zp, zr, r in sets if abs(r - target) == best)), best


@pytest.mark.parametrize(
    "target, n, hi, roles",
    [
        (Fraction(9, 2), 3, 100, ("ring", "sun", "carrier")),
        (Fraction(437, 100), 4, 120, ("ring", "sun", "carrier")),
        (Fraction(-3, 1), 5, 120, ("carrier", "sun", "ring")),
        (Fraction(5, 4), 3, 90, ("sun", "carrier", "ring")),
    ],
)
def test_simple_search_equals_brute_force_enumeration(target, n, hi, roles):
    fixed, inp, out = roles
    d = design_planetary(target, n, fixed=fixed, input=inp, output=out, min_teeth=12, max_teeth=hi)
    want, best = brute_simple(target, n, 12, hi, fixed, inp, out)
    assert [(s.ring, s.sun, s.planet) for s in d.solutions] == want
    assert d.count == len(want) and all(s.error == best for s in d.solutions)
    # candidates: every coaxial set in the range
    assert d.candidates == sum(1 for zs in range(12, hi + 1) for zp in range(12, hi + 1) if zs + 2 * zp <= hi)


def test_compound_search_equals_brute_force_and_conditions_hold():
    n, lo, hi, target = 3, 12, 60, Fraction(31, 3)
    d = design_planetary(target, n, kind="compound", min_teeth=lo, max_teeth=hi)
    sets = []
    for zs in range(lo, hi + 1):
        for a in range(lo, hi + 1):
            for b in range(lo, hi + 1):
                zr = zs + a + b
                if zr > hi or (zs * b + zr * a) % (n * math.gcd(a, b)):
                    continue
                if not max(a, b) + 2 < (zs + a) * math.sin(math.pi / n):
                    continue
                sets.append((zr, zs, a, b, 1 + Fraction(a * zr, zs * b)))
    best = min(abs(r - target) for *_, r in sets)
    want = sorted(s[:4] for s in sets if abs(s[4] - target) == best)
    assert [(s.ring, s.sun, s.planet1, s.planet2) for s in d.solutions] == want
    assert d.feasible == len(sets)


@settings(max_examples=30, deadline=None)
@given(st.integers(12, 40), st.integers(12, 40), st.integers(12, 40), st.integers(2, 6))
def test_compound_equal_spacing_reduces_to_simple_when_planet_gears_are_equal(zs, zp, _, n):
    zr = zs + 2 * zp
    simple = (zs + zr) % n == 0
    compound = (zs * zp + zr * zp) % (n * math.gcd(zp, zp)) == 0
    assert simple == compound


def test_simple_design_solution_network_reaches_its_ratio():
    d = design_planetary("4.5", 3, max_teeth=100, limit=2)
    assert d.count > 2 and len(d.solutions) == 2
    for s in d.solutions:
        sol = planetary_network(s.sun, s.ring, planet=s.planet).solve(["sun"])
        assert 1 / sol.coefficients["carrier"][0] == s.ratio == Fraction(9, 2)


def test_unreachable_target_answers_nearest_sets_with_a_note():
    d = design_planetary(Fraction(3, 2), 3, max_teeth=100)
    assert d.note and "outside the ratios" in d.note
    assert d.solutions[0].ratio == d.ratio_range[0] > Fraction(2)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"planets": 1}, r"planets must be an integer in \[2, 64\]"),
        ({"min_teeth": 0}, r"min_teeth must be an integer >= 1"),
        ({"min_teeth": -5}, r"min_teeth must be an integer >= 1"),
        ({"min_teeth": 50, "max_teeth": 40}, "tooth range is empty"),
        ({"max_teeth": MAX_TEETH["simple"] + 1}, r"max_teeth must be at most 2000"),
        ({"kind": "compound", "max_teeth": 301}, r"max_teeth must be at most 300"),
        ({"fixed": "sun", "input": "sun"}, "different members"),
        ({"ratio": 0}, "ratio must be non-zero"),
        ({"ratio": "x"}, "ratio must be a number"),
        ({"planets": 12, "max_teeth": 30}, "no simple tooth set"),
    ],
)
def test_bad_design_input_names_the_parameter(kwargs, message):
    args = {"ratio": 4, "planets": 3, **kwargs}
    ratio, planets = args.pop("ratio"), args.pop("planets")
    with pytest.raises(ValueError, match=message):
        design_planetary(ratio, planets, **args)


def test_clearance_is_exact_at_the_rational_sines():
    # N = 6: sin(pi/6) = 1/2, equality z_p + 2 = (z_s + z_p)/2 must fail the strict test
    from gearlever.gears.planetary import _less_than_sin

    assert not _less_than_sin(20, 40, 6) and _less_than_sin(19, 40, 6)
    assert not _less_than_sin(5, 5, 2) and _less_than_sin(4, 5, 2)
    assert _less_than_sin(866, 1000, 3) and not _less_than_sin(867, 1000, 3)
    assert np.isclose(
        float(__import__("gearlever.gears.planetary", fromlist=["x"])._sin_pi_over(7)), math.sin(math.pi / 7)
    )


def test_fixed_sun_mesh_on_carrier_is_not_a_locked_train():
    net = Network(
        [Gear("sun", 30), Gear("planet", 15), Gear("arm")],
        [SameShaft("fix", "sun", FRAME), Mesh("m", "sun", "planet", carrier="arm")],
    )
    a = net.analyse()
    assert a.dof == 1 and a.locked == {"sun": "fix"}
