"""Challenge-form linkages: validation naming the key, and the dyadic solve plan (Nobari, Ahmed et al., LINKS)."""

import json
import re

import pytest

from gearlever.errors import GearleverError
from gearlever.mechanism.linkage import linkage_from_dict, read_linkage, solve_plan

FOURBAR = {
    "x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
    "edges": [[0, 1], [1, 3], [2, 3]],
    "fixed_joints": [0, 2],
    "motor": [0, 1],
}


def _with(**kw):
    d = json.loads(json.dumps(FOURBAR))
    d.update(kw)
    return d


def test_fourbar_plan_places_the_coupler_joint_from_crank_tip_and_rocker_pivot():
    lk = linkage_from_dict(FOURBAR)
    plan = solve_plan(lk)
    assert plan.dyads.tolist() == [[3, 1, 2, 0]]
    assert plan.order.tolist() == [0, 1, 2, 3]
    assert lk.target_joint == 3  # the last joint solved, as in the challenge


def test_sixbar_plan_orders_joints_by_known_parents():
    d = {
        "x0": [[0, 0], [0.3, 0.2], [2, 0], [1.5, 1.5], [3, 1], [2.5, 2.5]],
        "edges": [[0, 1], [1, 3], [2, 3], [3, 5], [4, 5]],
        "fixed_joints": [0, 2, 4],
        "motor": [0, 1],
        "target_joint": 3,
    }
    lk = linkage_from_dict(d)
    assert solve_plan(lk).dyads[:, :3].tolist() == [[3, 1, 2], [5, 3, 4]]
    assert lk.target_joint == 3


@pytest.mark.parametrize(
    "change, key",
    [
        ({"edges": [[0, 1], [1, 3], [2, 7]]}, "edges[2]"),
        ({"motor": [1, 0]}, "motor"),
        ({"motor": [0, 3]}, "motor"),
        ({"edges": [[0, 1], [1, 3], [2, 3], [3, 3]]}, "edges[3]"),
        ({"x0": [[0, 0], [0, 1], [3, 0]]}, "edges[1]"),
        ({"fixed_joints": [0]}, "edges"),  # joint 2 and 3 then form a two-degree-of-freedom chain
        ({"target_joint": 2}, "target_joint"),
        ({"x0": [[0, 0], [0, 1], [3, 0], [2, float("nan")]]}, "x0"),
    ],
)
def test_malformed_linkage_is_refused_naming_the_key(change, key):
    with pytest.raises(GearleverError, match="^" + re.escape(key)):
        linkage_from_dict(_with(**change))
    for k in FOURBAR:
        bad = dict(FOURBAR)
        del bad[k]
        with pytest.raises(GearleverError, match=rf"^{k}: missing"):
            linkage_from_dict(bad)


def test_joint_with_one_edge_is_refused():
    d = _with(x0=[[0, 0], [0, 1], [3, 0], [2, 2], [5, 5]], edges=[[0, 1], [1, 3], [2, 3], [3, 4]])
    with pytest.raises(GearleverError, match=r"^edges: joint 4 has 1 edge"):
        linkage_from_dict(d)


def test_overconstrained_joint_is_refused():
    # joint 3 joined to the tip and two fixed pivots: three known parents
    d = _with(
        x0=[[0, 0], [0, 1], [3, 0], [2, 2], [4, 4]], edges=[[0, 1], [1, 3], [2, 3], [4, 3]], fixed_joints=[0, 2, 4]
    )
    with pytest.raises(GearleverError, match="over-constrained"):
        linkage_from_dict(d)


def test_read_linkage_names_the_file(tmp_path):
    p = tmp_path / "d.links.json"
    p.write_text(json.dumps(_with(motor=[1, 0])))
    with pytest.raises(GearleverError, match=r"^DESIGN '.*d\.links\.json': motor"):
        read_linkage(p)
    p.write_text("{")
    with pytest.raises(GearleverError, match="not JSON"):
        read_linkage(p)
