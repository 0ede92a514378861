"""Assembly from lengths: a rough sketch closed to exact lengths, on its branch; impossible lengths refused."""

from __future__ import annotations

import math
import sys
import tomllib

import numpy as np
import pytest

import gearlever
from gearlever.cli import main
from gearlever.errors import GearleverError
from gearlever.mechanism import assemble, load_model, model_from_dict
from gearlever.mechanism.model import parse_lengths

from ._models import all_examples, example

A_MOD = sys.modules["gearlever.mechanism.assemble"]


def _exact():
    return load_model(example("fourbar")).points


def _rough_fourbar(lengths=None, factor=1.1):
    """The shipped four-bar with its moving points pushed 10% out from the crank pivot, and its exact lengths."""
    P = _exact()
    pts = {k: list(v) for k, v in P.items()}
    for k in ("A", "B", "P"):
        pts[k] = [factor * P[k][0], factor * P[k][1]]
    if lengths is None:
        lengths = {
            "crank": math.dist(P["O2"], P["A"]),
            "coupler": math.dist(P["A"], P["B"]),
            "coupler.A-P": math.dist(P["A"], P["P"]),
            "coupler.B-P": math.dist(P["B"], P["P"]),
            "rocker": math.dist(P["O4"], P["B"]),
        }
    return {
        "mechanism": {"name": "rough four-bar", "units": "mm"},
        "points": pts,
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": ["A", "B", "P"], "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
        "lengths": lengths,
    }


def test_fourbar_sketched_10_percent_off_closes_to_the_shipped_exact_model():
    # the crank angle is held (A was pushed radially), B and P come back to the same branch:
    # the result is the shipped model itself
    rough = _rough_fourbar()
    assert max(math.dist(rough["points"][k], _exact()[k]) for k in "ABP") > 4.0
    exact = assemble(rough)["points"]
    for k, xy in _exact().items():
        assert math.dist(exact[k], xy) < 1e-12, k
    for key, (_, p, q, value) in parse_lengths(rough["lengths"], rough["links"]).items():
        assert abs(math.dist(exact[p], exact[q]) - value) < 1e-12, key


def test_lengths_only_of_the_links_keep_the_coupler_point_body_fixed_and_the_branch():
    rough = _rough_fourbar()
    for k in ("coupler.A-P", "coupler.B-P"):
        del rough["lengths"][k]
    m = model_from_dict(rough)
    out = assemble(rough)["points"]
    for key in ("crank", "coupler", "rocker"):
        (_, p, q, v) = parse_lengths(rough["lengths"], rough["links"])[key]
        assert abs(math.dist(out[p], out[q]) - v) < 1e-12
    # P keeps its sketch coordinates in the coupler frame (from A, along and across A-B)
    loc = m.links["coupler"].local["P"]
    u = np.subtract(out["B"], out["A"]) / math.dist(out["A"], out["B"])
    d = np.subtract(out["P"], out["A"])
    assert abs(u @ d - loc[0]) < 1e-12 and abs(u[0] * d[1] - u[1] * d[0] - loc[1]) < 1e-12

    # same assembly branch as the sketch: B on the same side of the line A-O4
    def side(pts):
        a, b, o = (np.array(pts[k]) for k in ("A", "B", "O4"))
        (ux, uy), (vx, vy) = o - a, b - a
        return np.sign(ux * vy - uy * vx)

    assert side(out) == side(rough["points"])
    # the crank keeps its sketch angle
    assert (
        abs(math.atan2(out["A"][1], out["A"][0]) - math.atan2(rough["points"]["A"][1], rough["points"]["A"][0])) < 1e-14
    )


def test_cli_writes_an_exact_model_that_solves(tmp_path, capsys):
    from gearlever.mechanism.modelfile import model_toml

    rough = _rough_fourbar()
    src = tmp_path / "rough.toml"
    lengths = rough.pop("lengths")
    src.write_text(
        model_toml(rough)
        + "\n[lengths]\n"
        + "\n".join(f'"{k}" = {v!r}' if "." in k else f"{k} = {v!r}" for k, v in lengths.items())
        + "\n"
    )
    out = tmp_path / "exact.toml"
    assert main(["mechanism", "assemble", str(src), "--out", str(out)]) == 0
    d = tomllib.loads(out.read_text())
    for key, (_, p, q, v) in parse_lengths(lengths, rough["links"]).items():
        assert abs(math.dist(d["points"][p], d["points"][q]) - v) < 1e-12, key
    m = gearlever.Mechanism.load(out)
    r = m.solve(m.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, 90, endpoint=False))
    assert r.closed.all()
    assert np.abs(np.hypot(*(r.point["B"] - r.point["A"]).T) - lengths["coupler"]).max() < 1e-9


def test_impossible_lengths_are_refused_naming_the_loop_and_links(tmp_path, capsys):
    rough = _rough_fourbar({"crank": 10.0, "coupler": 5.0, "rocker": 5.0})
    with pytest.raises(GearleverError) as exc:
        assemble(rough)
    msg = str(exc.value)
    for words in ("ground O2-O4 = 40", "crank = 10", "coupler = 5", "rocker = 5", "polygon inequality"):
        assert words in msg
    # a triangle of a ternary link
    with pytest.raises(GearleverError, match=r'"coupler.A-P" = 100 is longer than the others together'):
        assemble(_rough_fourbar({"coupler": 45.0, "coupler.A-P": 100.0, "coupler.B-P": 10.0}))
    # command line: exit 2, one line, no file
    from gearlever.mechanism.modelfile import model_toml

    lengths = rough.pop("lengths")
    src = tmp_path / "bad.toml"
    src.write_text(model_toml(rough) + "\n[lengths]\n" + "\n".join(f"{k} = {v}" for k, v in lengths.items()) + "\n")
    out = tmp_path / "x.toml"
    assert main(["mechanism", "assemble", str(src), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "polygon inequality" in err and not out.exists()


def test_input_freed_when_the_sketch_angle_cannot_close():
    # crank 30: at the sketch angle A is 10.5 from O4, too close for coupler 45 and rocker 30 (45 > 10.5 + 30);
    # the crank is freed and the lengths close at another angle
    rough = _rough_fourbar({"crank": 30.0, "coupler": 45.0, "rocker": 30.0})
    out = assemble(rough)["points"]
    assert abs(math.dist(out["O2"], out["A"]) - 30.0) < 1e-12
    assert abs(math.dist(out["A"], out["B"]) - 45.0) < 1e-12
    assert abs(math.dist(out["O4"], out["B"]) - 30.0) < 1e-12
    assert math.dist(out["A"], out["O4"]) >= 15.0 - 1e-9  # |coupler - rocker| <= |A - O4|


def test_slider_crank_rod_length_keeps_the_slider_on_its_guide():
    m = load_model(example("slider_crank"))
    d = A_MOD.model_dict(m)
    d["points"]["B"] = [40.0, 5.0]  # rough: rod 30.0 instead of 35
    d["lengths"] = {"rod": 35.0}
    out = assemble(d)["points"]
    assert abs(math.dist(out["A"], out["B"]) - 35.0) < 1e-12
    assert out["B"][1] == pytest.approx(5.0, abs=1e-13)
    assert out["B"][0] == pytest.approx(m.points["B"][0], abs=1e-11)  # the shipped (exact) sketch


@pytest.mark.parametrize(
    "lengths, words",
    [
        ({"cranc": 1.0}, "lengths.cranc: unknown link 'cranc'"),
        ({"coupler.A-Q": 1.0}, "must name two points of link 'coupler' as \"coupler.P-Q\""),
        ({"crank": -1.0}, "lengths.crank must be a positive length"),
        ({"crank": 10.0, "crank.O2-A": 10.0}, "already given as 'crank'"),
        ({"crank": "ten"}, "lengths.crank must be a number"),
    ],
)
def test_bad_lengths_tables_are_refused_by_the_loader(lengths, words):
    with pytest.raises(GearleverError, match=None) as exc:
        model_from_dict(_rough_fourbar(lengths))
    assert words in str(exc.value)


def test_over_determined_link_is_refused():
    d = _rough_fourbar({"coupler": 45.0})
    d["points"]["Q"] = [20.0, 30.0]
    d["links"]["coupler"] = ["A", "B", "P", "Q"]
    # a rigid link of 4 points takes 5 lengths: 6 over-determine it
    pairs = ["A-B", "A-P", "A-Q", "B-P", "B-Q", "P-Q"]
    d["lengths"] = {f"coupler.{pq}": math.dist(d["points"][pq[0]], d["points"][pq[2]]) for pq in pairs}
    with pytest.raises(GearleverError, match="link 'coupler' is over-determined by .* takes 5 independent lengths"):
        assemble(d)


def test_complex_step_jacobian_matches_central_differences():
    for d in (_rough_fourbar(), {**A_MOD.model_dict(load_model(example("whitworth"))), "lengths": {"rod": 100.0}}):
        m = model_from_dict(d)
        eq = A_MOD._Equations(m, A_MOD._rows(m, parse_lengths(d["lengths"], m.links), True))
        x = eq.x0 + 0.3
        J = eq.jacobian(x)
        h = 1e-6
        for j in range(x.size):
            e = np.zeros(x.size)
            e[j] = h
            fd = (eq.residual((x + e)[:, None])[:, 0] - eq.residual((x - e)[:, None])[:, 0]) / (2 * h)
            assert np.abs(fd - J[:, j]).max() < 1e-6, (m.name, j)


@pytest.mark.parametrize("path", all_examples(), ids=lambda p: p.stem)
def test_model_dict_round_trips_every_example(path):
    m = load_model(path)
    assert model_from_dict(A_MOD.model_dict(m)) == m
