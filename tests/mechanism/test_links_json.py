"""Mechanism.load opens a linkage in the challenge's form (.links.json): the curves simulator's curve, refusals."""

import json

import numpy as np
import pytest

from gearlever._io import to_json
from gearlever.errors import GearleverError
from gearlever.mechanism import Mechanism
from gearlever.mechanism.linkage import linkage_from_dict, solve_plan
from gearlever.synthesis.curve.simulate import crank_angles, simulate
from tests.synthesis.curve._designs import SIXBAR, turning


def _turning(n_dyads, seed):
    """A random dyadic linkage of the synthesis' library that turns fully (``n_dyads`` dyads, two ground pivots)."""
    topo, x0 = turning(n_dyads, seed)
    return topo.linkage(x0)


def _write(path, lk):
    """As ``gearlever synthesize curve`` writes NNNN.links.json."""
    path.write_text(to_json(lk.as_dict(), indent=None) + "\n")
    return path


@pytest.mark.parametrize("case", ["sixbar", "seven-joint", "ten-joint"])
def test_a_written_design_traces_the_curve_of_the_curves_simulator(tmp_path, case):
    lk = {
        "sixbar": lambda: linkage_from_dict(SIXBAR),
        "seven-joint": lambda: _turning(4, 5),
        "ten-joint": lambda: _turning(7, 11),
    }[case]()
    mech = Mechanism.load(_write(tmp_path / "0001.links.json", lk))
    assert mech.name == "0001" and mech.structure().dof == 1
    t = crank_angles()
    expect = simulate(lk.x0[None], solve_plan(lk), thetas=t)[0]
    assert np.isfinite(expect).all()
    r = mech.solve(t)
    assert r.closed.all()
    np.testing.assert_allclose(r.point["P"], expect[lk.target_joint], rtol=0, atol=1e-9)
    # every joint, under its model name
    fixed = set(lk.fixed_joints.tolist())
    for k in range(lk.n_joints):
        name = "P" if k == lk.target_joint else (f"O{k}" if k in fixed else f"J{k}")
        np.testing.assert_allclose(r.point[name], expect[k], rtol=0, atol=1e-9)


def test_a_plain_json_holding_a_linkage_opens_too_and_other_json_is_refused(tmp_path):
    p = tmp_path / "six.json"
    p.write_text(json.dumps(SIXBAR))
    assert Mechanism.load(p).name == "six"
    q = tmp_path / "other.json"
    q.write_text(json.dumps({"points": {}}))
    with pytest.raises(GearleverError, match=r"other\.json: a \.json model must be a linkage.*x0, edges"):
        Mechanism.load(q)


@pytest.mark.parametrize(
    "edit, needle",
    [
        ({"edges": [[0, 1], [1, 3], [2, 3], [3, 5], [4, 5], [1, 6], [2, 4]]}, "edges: joint 6 has 1 edge(s)"),
        ({"edges": [[0, 1], [1, 3], [2, 3], [3, 5], [4, 5], [5, 6], [3, 6], [2, 4], [1, 5]]}, "edges: "),
        ({"x0": [*SIXBAR["x0"], [4, 4]], "edges": [*SIXBAR["edges"], [6, 7], [5, 7], [3, 7]]}, "edges: joint 7"),
        ({"motor": [1, 3]}, "motor: the pivot 1 must be a fixed joint"),
        ({"edges": [[0, 1], [1, 9]]}, "edges[1] = [1, 9]: joint out of range"),
        ({"fixed_joints": [0]}, "not dyadic"),
        ({"x0": [[0, 0]]}, "x0"),
        ({"target_joint": 2}, "target_joint"),
    ],
)
def test_a_malformed_linkage_is_refused_naming_the_file_and_the_key(tmp_path, edit, needle):
    p = tmp_path / "bad.links.json"
    p.write_text(json.dumps({**SIXBAR, **edit}))
    with pytest.raises(GearleverError) as info:
        Mechanism.load(p)
    msg = str(info.value)
    assert msg.startswith(str(p) + ": ") and needle in msg and "\n" not in msg


@pytest.mark.parametrize("text, needle", [("{", "not JSON"), ("[1, 2]", "JSON object"), ("{}", "x0: missing")])
def test_a_file_that_is_no_linkage_object_is_refused(tmp_path, text, needle):
    p = tmp_path / "bad.links.json"
    p.write_text(text)
    with pytest.raises(GearleverError, match="bad.links.json") as info:
        Mechanism.load(p)
    assert needle in str(info.value)
