"""The challenge's form of a planar revolute linkage (``.links.json``) and its dyadic solve plan.

The form is a model file format and lives in :mod:`gearlever.mechanism.linkage`
(the mechanism package reads it without importing the synthesis); the topology
synthesis takes it from there.  See that module for the definitions and the
source (the MIT 2.156 linkage synthesis challenge).

>>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
>>> lk.target_joint, solve_plan(lk).dyads.tolist()
(3, [[3, 1, 2, 0]])
"""

from __future__ import annotations

from gearlever.mechanism.linkage import (
    MAX_COORDINATE,
    MAX_JOINTS,
    Linkage,
    SolvePlan,
    crank_length,
    linkage_from_dict,
    linkage_to_dict,
    read_linkage,
    solve_plan,
)
from gearlever.mechanism.linkage import _plan as _plan

__all__ = [
    "MAX_COORDINATE",
    "MAX_JOINTS",
    "Linkage",
    "SolvePlan",
    "crank_length",
    "linkage_from_dict",
    "linkage_to_dict",
    "read_linkage",
    "solve_plan",
]
