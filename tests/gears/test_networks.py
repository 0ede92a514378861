"""Tests of gearlever.gears.networks: exact solving, redundancy, locked networks, the float path."""

import itertools
import re
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gearlever.gears.networks import (
    FRAME,
    Differential,
    Gear,
    Mesh,
    Network,
    SameShaft,
    format_linear,
    parse_network,
)

NUTTALL_ROWS = {
    "a": lambda: Differential("a", "2", "5", "4"),
    "b": lambda: Differential("b", "9", "11", "4"),
    "c": lambda: Differential("c", "6", "8", FRAME),
    "d": lambda: Mesh("d", "7", "8"),
    "e": lambda: Mesh("e", "7", "6", sign=-1),
    "f": lambda: SameShaft("f", "1", "2"),
    "g": lambda: SameShaft("g", "5", "6"),
    "h": lambda: SameShaft("h", "8", "9"),
    "i": lambda: SameShaft("i", "11", "12"),
}


def nuttall(order="abcdefghi", teeth=(30, 24, 18, 36, 20, 25, 40)):
    n2, n5, n6, n7, n8, n9, n11 = teeth
    gears = [
        Gear("1"),
        Gear("2", n2),
        Gear("4"),
        Gear("5", n5),
        Gear("6", n6),
        Gear("7", n7),
        Gear("8", n8),
        Gear("9", n9),
        Gear("11", n11),
        Gear("12"),
    ]
    return Network(gears, [NUTTALL_ROWS[k]() for k in order])


def test_two_gear_train_ratio_and_sense_exact():
    net = Network([Gear("p", 18), Gear("q", 45)], [Mesh("m", "p", "q")])
    sol = net.solve(["p"])
    assert sol.coefficients["q"] == (Fraction(-18, 45),)
    assert sol.rotation("q", {"p": 5}) == Fraction(-2)


def test_compound_train_is_product_of_drivers_over_followers_and_idler_keeps_sense():
    # a(12) -> b(36) on shaft with c(15) -> d(45); then d -> idler(20) -> e(30)
    gears = [Gear("a", 12), Gear("b", 36), Gear("c", 15), Gear("d", 45), Gear("i", 20), Gear("e", 30)]
    cons = [
        Mesh("ab", "a", "b"),
        SameShaft("bc", "b", "c"),
        Mesh("cd", "c", "d"),
        Mesh("di", "d", "i"),
        Mesh("ie", "i", "e"),
    ]
    sol = Network(gears, cons).solve(["a"])
    assert sol.coefficients["d"] == (Fraction(12 * 15, 36 * 45),)  # two external meshes: same sense
    assert sol.coefficients["e"] == (Fraction(12 * 15, 36 * 30),)  # idler 20 drops out, four meshes
    assert sol.coefficients["i"] == (-Fraction(12 * 15, 36 * 20),)  # three meshes: reversed


def test_nuttall_counts_and_redundant_constraint_e_equals_d_minus_c():
    net = nuttall()
    a = net.analyse()
    assert (a.unknowns, a.rank, a.dof, a.redundant) == (10, 8, 2, ("e",))
    assert a.dependencies["e"] == {"c": -1, "d": 1}
    rows = dict(zip("abcdefghi", net.matrix()))
    assert rows["e"] == [d - c for d, c in zip(rows["d"], rows["c"])]


@pytest.mark.parametrize("order", ["".join(p) + "abfghi" for p in itertools.permutations("cde")])
def test_redundancy_found_whichever_of_c_d_e_comes_last(order):
    order = order[3:5] + order[:3] + order[5:]  # put a, b first then the permutation of c, d, e
    a = nuttall(order).analyse()
    last = [k for k in order if k in "cde"][-1]
    assert a.redundant == (last,)
    assert a.rank == 8
    others = set("cde") - {last}
    assert set(a.dependencies[last]) == others


def test_differential_with_frame_as_carrier_reverses_equal_side_gears():
    net = Network([Gear("a", 16), Gear("b", 16)], [Differential("x", "a", "b", FRAME)])
    assert net.solve(["a"]).coefficients["b"] == (Fraction(-1),)


def test_willis_relation_of_a_differential_is_exact():
    net = Network([Gear("a", 30), Gear("b", 20), Gear("c")], [Differential("w", "a", "b", "c")])
    sol = net.solve(["a", "b"])
    assert sol.coefficients["c"] == (Fraction(30, 50), Fraction(20, 50))
    assert sol.relation("c") == "rot_c = 3/5*rot_a + 2/5*rot_b"


def test_ring_of_three_meshes_is_locked_and_error_names_the_closing_constraint():
    net = Network(
        [Gear("a", 10), Gear("b", 20), Gear("c", 30)],
        [Mesh("ab", "a", "b"), Mesh("bc", "b", "c"), Mesh("ca", "c", "a")],
    )
    with pytest.raises(ValueError, match=r"constraint \(ca\) locks gears 'a', 'b', 'c'"):
        net.analyse()
    with pytest.raises(ValueError, match=r"\(ca\)"):
        net.solve(["a"])


def test_mesh_with_the_frame_locks_the_gear():
    net = Network([Gear("a", 10), Gear("b", 12)], [Mesh("ab", "a", "b"), Mesh("af", "a", FRAME)])
    with pytest.raises(ValueError, match=r"constraint \(af\) locks gears 'a', 'b'"):
        net.analyse()


def test_even_ring_of_equal_gears_is_consistent_with_one_redundant_mesh():
    # four equal gears in a ring: the fourth mesh follows from the other three
    g = [Gear(x, 20) for x in "abcd"]
    net = Network(g, [Mesh("ab", "a", "b"), Mesh("bc", "b", "c"), Mesh("cd", "c", "d"), Mesh("da", "d", "a")])
    a = net.analyse()
    assert (a.dof, a.redundant) == (1, ("da",))


@pytest.mark.parametrize("teeth", [0, -3, 2.5, True, "20"])
def test_bad_tooth_number_names_the_gear(teeth):
    with pytest.raises(ValueError, match=r"gear 'g7': teeth must be a positive integer"):
        Gear("g7", teeth)


def test_unknown_gear_names_constraint_and_gear():
    with pytest.raises(ValueError, match=r"constraint \(k\): unknown gear 'zz'"):
        Network([Gear("a", 10)], [Mesh("k", "a", "zz")])


def test_mesh_with_a_toothless_member_names_it():
    with pytest.raises(ValueError, match=r"constraint \(m\): gear 's' has no tooth number"):
        Network([Gear("a", 10), Gear("s")], [Mesh("m", "a", "s")])


def test_structural_errors():
    with pytest.raises(ValueError, match="defined more than once"):
        Network([Gear("a", 1), Gear("a", 2)], [])
    with pytest.raises(ValueError, match="used more than once"):
        Network([Gear("a", 1), Gear("b", 2)], [Mesh("m", "a", "b"), SameShaft("m", "a", "b")])
    with pytest.raises(ValueError, match="appears twice"):
        Network([Gear("a", 1)], [SameShaft("s", "a", "a")])
    with pytest.raises(ValueError, match="sign must be 1 or -1"):
        Mesh("m", "a", "b", sign=2)
    with pytest.raises(ValueError, match="reserved"):
        Gear(FRAME, 3)


def test_input_errors_name_the_problem():
    net = nuttall()
    with pytest.raises(ValueError, match="needs 2 input"):
        net.solve(["1"])
    with pytest.raises(ValueError, match="unknown gear 'x'"):
        net.solve(["1", "x"])
    with pytest.raises(ValueError, match=r"not independent: constraints \(f\)"):
        net.solve(["1", "2"])
    with pytest.raises(ValueError, match="not independent"):
        net.solve_float(["1", "2"])
    with pytest.raises(ValueError, match="fixed frame"):
        net.solve([FRAME, "1"])


def test_nuttall_float_path_matches_exact():
    net = nuttall()
    exact = net.solve(["1", "12"]).matrix(net.names)
    assert np.allclose(net.solve_float(["1", "12"]), exact, rtol=0, atol=1e-12)


def test_rotation_is_exact_for_fractions_and_broadcasts_arrays():
    sol = nuttall().solve(["1", "12"])
    c1, c12 = sol.coefficients["7"]
    assert sol.rotation("7", {"1": Fraction(3), "12": 2}) == 3 * c1 + 2 * c12
    v = sol.rotation("7", {"1": np.array([1.0, 2.0]), "12": np.array([0.0, 1.0])})
    assert np.allclose(v, [float(c1), 2 * float(c1) + float(c12)], rtol=1e-15)
    with pytest.raises(ValueError, match="inputs must be exactly"):
        sol.rotation("7", {"1": 1})


def test_format_linear():
    assert format_linear({"a": Fraction(1), "b": Fraction(-3, 2)}) == "rot_a - 3/2*rot_b"
    assert format_linear({}) == "0"


@st.composite
def random_networks(draw):
    """A random tree-like network: each new member joined to earlier ones by a random kind."""
    size = draw(st.integers(2, 9))
    teeth = st.integers(6, 90)
    gears = [Gear("g0", draw(teeth))]
    cons = []
    for k in range(1, size):
        gears.append(Gear(f"g{k}", draw(teeth)))
        kind = draw(st.sampled_from(["mesh", "shaft", "diff"]))
        j = draw(st.integers(0, k - 1))
        if kind == "mesh":
            cons.append(Mesh(f"c{k}", f"g{j}", f"g{k}", sign=draw(st.sampled_from([1, -1]))))
        elif kind == "shaft":
            cons.append(SameShaft(f"c{k}", f"g{j}", f"g{k}"))
        elif k >= 2:
            i = draw(st.integers(0, k - 1).filter(lambda x, j=j: x != j))
            carrier = draw(st.sampled_from([f"g{k}", FRAME]))
            if carrier == FRAME:
                cons.append(Differential(f"c{k}", f"g{j}", f"g{k}", FRAME))
            else:
                cons.append(Differential(f"c{k}", f"g{i}", f"g{j}", carrier))
        else:
            cons.append(Mesh(f"c{k}", f"g{j}", f"g{k}"))
    return Network(gears, cons)


@settings(max_examples=60, deadline=None)
@given(random_networks())
def test_exact_solution_satisfies_every_constraint_and_float_path_agrees(net):
    try:
        a = net.analyse()
    except ValueError as exc:
        # a locked network: every gear the error names must really be forced still
        names = re.findall(r"'(g\d+)'", str(exc))
        assert "locks" in str(exc) and names
        A = net.matrix_float()
        _, s, vt = np.linalg.svd(A)
        null = vt[int(np.sum(s > 1e-10 * s[0])) :]
        for name in names:
            assert np.all(np.abs(null[:, net.names.index(name)]) < 1e-9)
        return
    for name in a.locked:
        A = net.matrix_float()
        _, s, vt = np.linalg.svd(A)
        null = vt[int(np.sum(s > 1e-10 * s[0])) :]
        assert np.all(np.abs(null[:, net.names.index(name)]) < 1e-9)
    assert a.dof == a.unknowns - a.rank
    # free members: pick inputs greedily that keep the system solvable
    inputs = []
    for name in net.names:
        if len(inputs) == a.dof:
            break
        try:
            net.solve(inputs + [name] + [n for n in net.names if n not in inputs + [name]][: a.dof - len(inputs) - 1])
        except ValueError:
            continue
        inputs.append(name)
    inputs = inputs + [n for n in net.names if n not in inputs][: a.dof - len(inputs)]
    sol = net.solve(inputs)
    A = net.matrix()
    for k in range(len(inputs)):
        col = [sol.coefficients[n][k] for n in net.names]
        assert all(sum(r * c for r, c in zip(row, col)) == 0 for row in A)
    assert np.allclose(net.solve_float(inputs), sol.matrix(net.names), rtol=1e-9, atol=1e-9)


def test_carrier_between_opposed_equal_side_gears_is_reported_locked_not_an_error():
    net = Network([Gear("a", 24), Gear("b", 24), Gear("c")], [Mesh("ab", "a", "b"), Differential("w", "a", "b", "c")])
    a = net.analyse()
    assert a.locked == {"c": "w"} and a.dof == 1
    assert net.solve(["a"]).coefficients["c"] == (Fraction(0),)
    with pytest.raises(ValueError, match=r"constraints \(ab\), \(w\) force"):
        net.solve(["c"])


def test_long_train_float_path_agrees_with_exact():
    """31 members: alternating meshes, shafts and differentials on a common carrier k."""
    rng = np.random.default_rng(0)
    gears = [Gear("g0", 20), Gear("k", 30)]
    cons = []
    for k in range(1, 30):
        gears.append(Gear(f"g{k}", int(rng.integers(8, 90))))
        if k % 3 == 0:
            cons.append(Differential(f"c{k}", f"g{k - 1}", f"g{k}", "k"))
        elif k % 3 == 1:
            cons.append(Mesh(f"c{k}", f"g{k - 1}", f"g{k}"))
        else:
            cons.append(SameShaft(f"c{k}", f"g{k - 1}", f"g{k}"))
    net = Network(gears, cons)
    a = net.analyse()
    assert a.unknowns == 31 and a.dof == 2
    exact = net.solve(["g0", "k"]).matrix(net.names)
    scale = np.abs(exact).max()
    assert np.allclose(net.solve_float(["g0", "k"]), exact, rtol=1e-9, atol=1e-10 * scale)


def test_parse_network_round_trip_of_nuttall_records():
    text = "\n".join(
        [
            "# comment",
            "member,1,wheel",
            "member,2,gear,n2",
            "member,4,carrier",
            "member,5,gear,24",
            "member,6,gear,18",
            "member,7,gear,36",
            "member,8,gear,20",
            "member,9,gear,25",
            "member,11,gear,40",
            "member,12,wheel",
            "constraint,a,differential,2,5,4",
            "constraint,b,differential,9,11,4",
            "constraint,c,differential,6,8,frame",
            "constraint,d,mesh,7,8,,1",
            "constraint,e,mesh,7,6,,-1",
            "constraint,f,shaft,1,2",
            "constraint,g,shaft,5,6",
            "constraint,h,shaft,8,9",
            "constraint,i,shaft,11,12",
        ]
    )
    net = parse_network(text, teeth={"n2": 30})
    assert net.matrix() == nuttall().matrix()


@pytest.mark.parametrize(
    "text, message",
    [
        ("member,a,gear,0", r"network line 1: gear 'a': teeth must be a positive integer"),
        ("member,a,gear,2.5", r"network line 1: gear 'a': tooth number '2.5'"),
        ("member,a,gear,nx", r"gear 'a': tooth number 'nx' is neither"),
        ("member,a,gear,10\nconstraint,k,belt,a,b", r"network line 2: constraint \(k\): kind must be"),
        ("member,a,gear,10\nconstraint,k,mesh,a,b", r"constraint \(k\): unknown gear 'b'"),
        ("member,a,gear,10\nmember,b,gear,10\nconstraint,k,mesh,a,b,,2", r"sign must be 1 or -1"),
        ("gear,a,10", r"network line 1: record must start with 'member' or 'constraint'"),
    ],
)
def test_parse_network_errors_name_line_gear_or_constraint(text, message):
    with pytest.raises(ValueError, match=message):
        parse_network(text)


# --- meshes on a carrier, the frame, empty networks, sparse paths ------------------------------


def test_mesh_on_carrier_row_is_willis_relative_to_the_carrier():
    m = Mesh("m", "s", "p", sign=1, carrier="c")
    assert m.terms({"s": 30, "p": 20, "c": None}) == {"s": 30, "p": 20, "c": -50}
    ring = Mesh("r", "p", "R", sign=-1, carrier="c")
    assert ring.terms({"p": 20, "R": 70, "c": None}) == {"p": 20, "R": -70, "c": 50}


def test_planet_meshing_fixed_axis_written_the_obvious_way_now_errors_or_is_right():
    # the planet written on the carrier gives Willis; the carrier can never silently drop out
    net = Network(
        [Gear("sun", 30), Gear("planet", 20), Gear("arm")],
        [SameShaft("fix", "sun", FRAME), Mesh("m", "sun", "planet", carrier="arm")],
    )
    assert net.solve(["arm"]).coefficients["planet"] == (1 + Fraction(30, 20),)


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: Differential("x", "S", FRAME, "C"), r"frame cannot be a side gear.*shaft"),
        (lambda: Differential("x", FRAME, "S", "C"), r"frame cannot be a side gear"),
        (lambda: Mesh("m", FRAME, "p", carrier="arm"), r"frame cannot mesh on carrier 'arm'.*shaft"),
        (lambda: Mesh("m", "p", "q", carrier="p"), r"carrier 'p' must differ"),
        (lambda: Mesh("m", "p", "q", carrier=""), r"carrier must be a non-empty string"),
    ],
)
def test_constraints_needing_the_frames_teeth_are_refused_with_how_to_write_them(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_unknown_carrier_and_toothless_planet_are_named():
    with pytest.raises(ValueError, match=r"constraint \(m\): unknown gear 'arm'"):
        Network([Gear("s", 20), Gear("p", 10)], [Mesh("m", "s", "p", carrier="arm")])
    with pytest.raises(ValueError, match="at least one member"):
        Network([], [])


def test_parse_network_reads_the_carrier_column_and_refuses_an_empty_file():
    net = parse_network("member,s,gear,30\nmember,p,gear,20\nmember,a,carrier\nconstraint,m1,mesh,s,p,a,1,\n")
    assert net.constraints[0] == Mesh("m1", "s", "p", 1, carrier="a")
    for text in ("", "# only a comment\n", "constraint,k,shaft,a,b\n"):
        with pytest.raises(ValueError, match="no member"):
            parse_network(text)
    with pytest.raises(ValueError, match=r"network line 3: .*third column must be empty"):
        parse_network("member,a,gear,1\nmember,b,gear,2\nconstraint,k,shaft,a,b,c\n")


def test_rows_are_the_terms_of_each_constraint_and_match_the_dense_matrix():
    net = nuttall()
    rows = net.rows()
    assert rows == [c.terms(net.teeth) for c in net.constraints]
    dense = net.matrix()
    for r, d in zip(rows, dense):
        assert {n: v for n, v in zip(net.names, d) if v} == r
    assert np.array_equal(net.matrix_sparse().toarray(), net.matrix_float())


@st.composite
def random_carrier_networks(draw):
    """Random networks mixing fixed-axis and carrier meshes, shafts, ties to the frame, differentials."""
    size = draw(st.integers(3, 12))
    gears = [Gear(f"g{k}", draw(st.integers(6, 90))) for k in range(size)]
    cons = []
    for k in range(1, size):
        j = draw(st.integers(0, k - 1))
        kind = draw(st.sampled_from(["mesh", "carrier", "shaft", "diff", "fix"]))
        others = [i for i in range(size) if i not in (j, k)]
        if kind == "mesh":
            cons.append(Mesh(f"c{k}", f"g{j}", f"g{k}", sign=draw(st.sampled_from([1, -1]))))
        elif kind == "carrier":
            c = draw(st.sampled_from(others))
            cons.append(Mesh(f"c{k}", f"g{j}", f"g{k}", sign=draw(st.sampled_from([1, -1])), carrier=f"g{c}"))
        elif kind == "shaft":
            cons.append(SameShaft(f"c{k}", f"g{j}", f"g{k}"))
        elif kind == "fix":
            cons.append(SameShaft(f"c{k}", f"g{k}", FRAME))
        else:
            c = draw(st.sampled_from(others + [None]))
            cons.append(Differential(f"c{k}", f"g{j}", f"g{k}", FRAME if c is None else f"g{c}"))
    return Network(gears, cons)


@settings(max_examples=80, deadline=None)
@given(random_carrier_networks())
def test_random_carrier_networks_exact_rank_matches_svd_and_float_path_agrees(net):
    A = net.matrix_float()
    s = np.linalg.svd(A, compute_uv=False)
    rank = int(np.sum(s > 1e-10 * s[0])) if s.size and s[0] > 0 else 0
    try:
        a = net.analyse()
    except ValueError as exc:
        assert "locks" in str(exc)
        return
    assert a.rank == rank
    # redundant rows: each equals the stated combination of earlier rows, exactly
    rows = dict(zip([c.label for c in net.constraints], net.rows()))
    for lab, dep in a.dependencies.items():
        combo = {}
        for k, f in dep.items():
            for n, v in rows[k].items():
                combo[n] = combo.get(n, 0) + f * v
        assert {n: v for n, v in combo.items() if v} == rows[lab]
    # inputs: the free columns of an exact elimination
    el = net._elimination()
    inputs = [net.names[j] for j in range(len(net.names)) if j not in el.pivot_of]
    sol = net.solve(inputs)
    for row in net.rows():
        for k in range(len(inputs)):
            assert sum(v * sol.coefficients[n][k] for n, v in row.items()) == 0
    for name in a.locked:
        assert all(c == 0 for c in sol.coefficients[name])
    if inputs:
        exact = sol.matrix(net.names)
        scale = max(1.0, np.abs(exact).max())
        assert np.allclose(net.solve_float(inputs), exact, rtol=1e-8, atol=1e-8 * scale)


def test_large_branch_network_exact_and_float_paths_agree():
    """A spine of equal gears with branches of meshes joined by differentials (the benchmark's shape)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location(
        "bench_networks", Path(__file__).resolve().parents[2] / "benchmarks" / "bench_networks.py"
    )
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    net = bench.branch_network(600)
    a = net.analyse()
    assert a.dof == 1 and not a.redundant and not a.locked
    exact = net.solve(["s0"]).matrix(net.names)
    assert np.allclose(net.solve_float(["s0"]), exact, rtol=1e-9, atol=1e-12)
