"""Network torques: virtual work, exact power conservation, textbook closed forms, carrier-frame losses."""

from __future__ import annotations

from fractions import Fraction

import pytest
from hypothesis import given, reject, settings
from hypothesis import strategies as st

from gearlever.data import read_text
from gearlever.errors import GearleverError
from gearlever.gears.car import car_differential, car_network
from gearlever.gears.networks import FRAME, Differential, Gear, Mesh, Network, SameShaft, parse_network
from gearlever.gears.torques import network_torques, torque_report

NUTTALL_TEETH = dict(n2=30, n5=24, n6=18, n7=36, n8=20, n9=25, n11=40)


def planetary(zs=20, zr=80):
    return Network(
        [Gear("sun", zs), Gear("ring", zr), Gear("carrier")],
        [Differential("planets", "sun", "ring", "carrier"), SameShaft("held", "ring", FRAME)],
    )


def _rank(rows):
    rows = [list(r) for r in rows if any(r)]
    rank, col, n = 0, 0, len(rows[0]) if rows else 0
    while rank < len(rows) and col < n:
        p = next((i for i in range(rank, len(rows)) if rows[i][col]), None)
        if p is None:
            col += 1
            continue
        rows[rank], rows[p] = rows[p], rows[rank]
        for i in range(len(rows)):
            if i != rank and rows[i][col]:
                f = rows[i][col] / rows[rank][col]
                rows[i] = [a - f * b for a, b in zip(rows[i], rows[rank])]
        rank += 1
        col += 1
    return rank


def check_virtual_work(net, res, loads):
    """T is a combination of the rows of C (same rank with T appended) and T . v = 0 for every motion."""
    T = [res.torques.get(n, Fraction(0)) for n in net.names]
    C = net.matrix()
    assert _rank(C + [T]) == _rank(C)
    sol = net.solve(list(loads))
    for k in range(len(loads)):
        assert sum(T[j] * sol.coefficients[n][k] for j, n in enumerate(net.names)) == 0


# ---------------------------------------------------------------- closed forms


@pytest.mark.parametrize("zs, zr", [(20, 80), (17, 61), (30, 72)])
def test_planetary_fixed_ring_carrier_torque_and_ring_reaction_textbook(zs, zr):
    """Sun in, ring held, carrier out: T_c = -(1 + z_r/z_s) T_s, ring reaction z_r/z_s T_s.

    Closed form from the Willis relation with torque balance about the axis
    (T_s + T_c + T_r = 0) and power balance (T_s w_s + T_c w_c = 0).
    """
    net = planetary(zs, zr)
    res = network_torques(net, {"sun": 7}, ["carrier"], speeds={"sun": 300})
    assert res.torques["carrier"] == -7 * (1 + Fraction(zr, zs))
    assert res.frame_reactions["held"] == 7 * Fraction(zr, zs)
    assert res.speeds["carrier"] == 300 * Fraction(zs, zs + zr)
    assert sum(res.power.values()) == 0
    assert sum(res.torques.values()) + sum(res.frame_reactions.values()) == 0
    check_virtual_work(net, res, ["carrier"])


@pytest.mark.parametrize("left", [0, 25, -10, Fraction(7, 3)])
def test_car_differential_side_gear_torques_equal_half_ring_torque(left):
    """Open differential: left and right wheel torques are equal, G4 = G5 = G2/2, whatever the wheel speeds
    (against gearlever.gears.car.car_differential, the source's closed form)."""
    net = car_network(10, 40)
    res = network_torques(net, {"pinion": 3}, ["left", "right"], speeds={"pinion": 100, "left": left})
    ref = car_differential(10, 40, 100.0, 3.0, left_speed=float(left))
    assert res.torques["left"] == res.torques["right"]
    assert -float(res.torques["left"]) == ref.left_torque == ref.right_torque
    assert sum(res.power.values()) == 0
    check_virtual_work(net, res, ["left", "right"])


def test_nuttall_torques_by_virtual_work_and_indeterminate_reaction():
    """Nuttall chariot, pointer torque 1: wheel torques are minus the pointer's relation (l) coefficients;
    (e) = (d) - (c) is redundant, so the share of torque through (c), (d), (e) and the frame's reaction
    through (c) are statically indeterminate and reported as None."""
    net = parse_network(read_text("nuttall_network.csv"), teeth=NUTTALL_TEETH)
    res = network_torques(net, {"7": 1}, ["1", "12"], speeds={"1": 3, "12": -2})
    sol = net.solve(["1", "12"])
    assert res.torques["1"] == -sol.coefficients["7"][0] == Fraction(13, 37)
    assert res.torques["12"] == -sol.coefficients["7"][1] == Fraction(-72, 185)
    assert res.frame_reactions == {"c": None}
    assert {k for k, v in res.multipliers.items() if v is None} == {"c", "d", "e"}
    assert sum(res.power.values()) == 0
    check_virtual_work(net, res, ["1", "12"])
    rep = torque_report(net, {"7": 1}, ["1", "12"])
    assert rep["frame_reactions"] == {"c": None} and rep["indeterminate"] == ["c", "d", "e"]
    with pytest.raises(GearleverError, match="redundant"):
        network_torques(net, {"7": 1}, ["1", "12"], speeds={"1": 3, "12": -2}, efficiency=0.99)


def test_power_circulates_in_a_planetary_with_a_feedback_loop():
    """Sun 20 in, carrier out, ring 80 driven forward from the carrier by a pair 30:40 (w_r = 3/4 w_c).

    Willis: 20 w_s + 80 w_r = 100 w_c gives w_s = 2 w_c.  The planets give the
    carrier 100 lambda w_c = 5/2 P (P the input power) and the pair carries
    3/2 P back to the ring: power circulates, 5/(5 - 4k) P with k = 3/4.
    """
    net = Network(
        [Gear("sun", 20), Gear("ring", 80), Gear("carrier"), Gear("cg", 30), Gear("rg", 40)],
        [
            Differential("planets", "sun", "ring", "carrier"),
            SameShaft("c_shaft", "carrier", "cg"),
            SameShaft("r_shaft", "ring", "rg"),
            Mesh("loop", "cg", "rg", sign=-1),
        ],
    )
    res = network_torques(net, {"sun": 5}, ["carrier"], speeds={"sun": 40})
    P = res.input_power
    assert P == 200 and res.speeds["carrier"] == 20 and res.speeds["ring"] == 15
    assert res.throughput["planets"] == Fraction(5, 2) * P
    assert res.throughput["loop"] == Fraction(3, 2) * P
    assert set(res.circulating) >= {"planets", "loop"}
    assert sum(res.power.values()) == 0
    check_virtual_work(net, res, ["carrier"])


# ---------------------------------------------------------------- losses


@pytest.mark.parametrize("eta", [Fraction(98, 100), Fraction(9, 10), 0.95])
def test_planetary_efficiency_sun_in_matches_carrier_frame_formula(eta):
    """Ring held, sun in, carrier out: eta = (1 + eta0 R)/(1 + R), R = z_r/z_s, eta0 = eta^2 (two meshes);
    Pennestri & Freudenstein (ASME J. Mech. Des. 1993) / Macmillan (1961), carrier-frame power method."""
    net = planetary(20, 80)
    res = network_torques(net, {"sun": 10}, ["carrier"], speeds={"sun": 100}, efficiency=eta)
    e0 = Fraction(repr(eta)) ** 2 if isinstance(eta, float) else eta**2
    R = Fraction(80, 20)
    assert -res.power["carrier"] / res.power["sun"] == (1 + e0 * R) / (1 + R)
    assert sum(res.power.values()) == res.total_loss == res.losses["planets"] > 0
    assert res.losses["planets"] == (1 - e0) * res.rolling_power["planets"]


def test_planetary_efficiency_carrier_in_reverse_flow():
    """Ring held, carrier in, sun out: in the carrier's frame the ring drives the sun, so
    eta = eta0 (1 + R)/(eta0 + R) (the other branch of the same carrier-frame method)."""
    net = planetary(20, 80)
    e = Fraction(9, 10)
    res = network_torques(net, {"carrier": 50}, ["sun"], speeds={"sun": 100}, efficiency=e)
    e0, R = e**2, Fraction(4)
    assert res.power["carrier"] > 0
    assert -res.power["sun"] / res.power["carrier"] == e0 * (1 + R) / (e0 + R)


@pytest.mark.parametrize("driver", ["a", "c"])
def test_fixed_axis_train_efficiency_is_eta_per_mesh_either_way(driver):
    """Three gears in a row: two meshes, overall efficiency eta^2 whichever end drives."""
    net = Network([Gear("a", 12), Gear("b", 30), Gear("c", 18)], [Mesh("ab", "a", "b"), Mesh("bc", "b", "c")])
    other = "c" if driver == "a" else "a"
    e = Fraction(97, 100)
    res = network_torques(net, {driver: 4}, [other], speeds={"a": 60}, efficiency=e)
    assert -res.power[other] / res.power[driver] == e**2
    assert res.total_loss == sum(res.power.values())


@pytest.mark.parametrize("eta", [1, Fraction(95, 100)])
def test_meshes_on_a_carrier_equal_the_differential_model(eta):
    """Sun-planet and planet-ring meshes on the carrier give the same torques and losses as the one-row
    Differential model, ideal and lossy.  The ring is a load at speed 0; its torque equals the held
    ring's frame reaction."""
    two = Network(
        [Gear("sun", 20), Gear("planet", 30), Gear("ring", 80), Gear("carrier")],
        [Mesh("sp", "sun", "planet", 1, "carrier"), Mesh("pr", "planet", "ring", -1, "carrier")],
    )
    one = Network(
        [Gear("sun", 20), Gear("ring", 80), Gear("carrier")], [Differential("planets", "sun", "ring", "carrier")]
    )
    kw = dict(speeds={"sun": 100, "ring": 0}, efficiency=eta)
    a = network_torques(two, {"sun": 10}, ["carrier", "ring"], **kw)
    b = network_torques(one, {"sun": 10}, ["carrier", "ring"], **kw)
    held = network_torques(planetary(), {"sun": 10}, ["carrier"], speeds={"sun": 100}, efficiency=eta)
    assert a.torques == b.torques
    assert a.torques["carrier"] == held.torques["carrier"]
    assert a.torques["ring"] == held.frame_reactions["held"]
    assert a.total_loss == b.total_loss == held.total_loss


# ---------------------------------------------------------------- properties


@st.composite
def random_networks(draw, coaxial=False):
    """Networks built member by member, each constraint adding one new member: no lock, full row rank."""
    n_free = draw(st.integers(1, 3))
    gears = [Gear(f"g{i}", draw(st.integers(8, 60))) for i in range(n_free)]
    rows = []
    for k in range(draw(st.integers(1, 6))):
        new = f"g{len(gears)}"
        gears.append(Gear(new, draw(st.integers(8, 60))))
        old = [g.name for g in gears[:-1]] + [FRAME]
        kind = draw(st.sampled_from(["diff", "shaft"] if coaxial else ["mesh", "diff", "shaft"]))
        if kind == "mesh":
            rows.append(Mesh(f"c{k}", new, draw(st.sampled_from(old[:-1])), draw(st.sampled_from([1, -1]))))
        elif kind == "shaft":
            rows.append(SameShaft(f"c{k}", new, draw(st.sampled_from(old))))
        else:
            a = draw(st.sampled_from(old[:-1]))
            c = draw(st.sampled_from([x for x in old if x != a]))
            rows.append(Differential(f"c{k}", a, new, c))
    net = Network(gears, rows)
    try:
        net.analyse()
    except GearleverError:  # a gear in mesh forced still: a jammed train, not a network to load
        reject()
    return net, [g.name for g in gears[:n_free]]


torque_values = st.fractions(min_value=-100, max_value=100, max_denominator=50)


@settings(max_examples=60, deadline=None)
@given(random_networks(), st.data())
def test_random_networks_virtual_work_and_exact_power_conservation(netfree, data):
    net, free = netfree
    others = [n for n in net.names if n not in free]
    applied = {n: data.draw(torque_values) for n in others}
    speeds = {n: data.draw(torque_values) for n in free}
    res = network_torques(net, applied, free, speeds=speeds)
    check_virtual_work(net, res, free)
    assert sum(res.power.values()) == 0


@settings(max_examples=60, deadline=None)
@given(random_networks(coaxial=True), st.data())
def test_coaxial_networks_torques_and_frame_reactions_balance(netfree, data):
    """Differentials and couplings share one axis: external torques plus frame reactions sum to zero."""
    net, free = netfree
    applied = {n: data.draw(torque_values) for n in net.names if n not in free}
    res = network_torques(net, applied, free)
    assert None not in res.frame_reactions.values()
    assert sum(res.torques.values()) + sum(res.frame_reactions.values()) == 0


@settings(max_examples=60, deadline=None)
@given(random_networks(), st.data(), st.fractions(min_value=Fraction(1, 2), max_value=1, max_denominator=100))
def test_random_lossy_networks_power_balance_equals_losses(netfree, data, eta):
    """With losses: the external powers sum to the losses, each (1 - eta_k) x its carrier-frame power, >= 0."""
    net, free = netfree
    applied = {n: data.draw(torque_values) for n in net.names if n not in free}
    speeds = {n: data.draw(torque_values) for n in free}
    try:
        res = network_torques(net, applied, free, speeds=speeds, efficiency=eta)
    except GearleverError as exc:  # a self-locking configuration is refused, never answered wrongly
        assert "self-lock" in str(exc)
        return
    assert sum(res.power.values()) == res.total_loss >= 0
    for c in net.constraints:
        k = 2 if isinstance(c, Differential) else 1
        if isinstance(c, SameShaft):
            assert res.losses[c.label] == 0
        else:
            assert res.losses[c.label] == (1 - eta**k) * res.rolling_power[c.label]


# ---------------------------------------------------------------- refusals


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(applied={"nope": 1}, loads=["carrier"]), "unknown member 'nope'"),
        (dict(applied={"frame": 1}, loads=["carrier"]), "reaction"),
        (dict(applied={"sun": 1}, loads=["sun"]), "applied torque"),
        (dict(applied={"sun": 1}, loads=["carrier", "ring"]), "input"),
        (dict(applied={"sun": 1}, loads=["carrier"], efficiency=0), "efficiency must be in"),
        (dict(applied={"sun": 1}, loads=["carrier"], efficiency=1.5), "efficiency must be in"),
        (dict(applied={"sun": 1}, loads=["carrier"], efficiency=0.9), "speeds must be given"),
        (dict(applied={"sun": float("nan")}, loads=["carrier"]), "finite number"),
    ],
)
def test_bad_input_is_refused_naming_it(kwargs, needle):
    with pytest.raises(GearleverError, match=needle):
        network_torques(planetary(), **kwargs)


def test_cli_parsers_read_exact_values_and_name_the_flag():
    from gearlever.gears.torques import parse_assignments, parse_number

    assert parse_assignments("sun=100, ring=-2.5,c=3/4", "--torque") == {
        "sun": 100,
        "ring": Fraction(-5, 2),
        "c": Fraction(3, 4),
    }
    assert parse_number("0.98", "--efficiency") == Fraction(49, 50)
    for text, needle in [("sun", "MEMBER=VALUE"), ("sun=1,sun=2", "twice"), ("sun=abc", "--torque sun")]:
        with pytest.raises(GearleverError, match=needle):
            parse_assignments(text, "--torque")
