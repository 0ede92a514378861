"""A challenge-form linkage as a gearlever model (points, binary links, the crank as input).

Names: the fixed joints ``O<i>``, the moving joints ``J<i>`` (``i`` the
joint's index in ``x0``), the traced joint ``P``; links ``ground`` (the fixed
joints), ``crank`` (the motor's edge) and ``L<e>`` for edge ``e``.  An edge
between two fixed joints is part of the ground.

>>> from gearlever.curves.links import linkage_from_dict
>>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
>>> sorted(linkage_model(lk)["links"])
['L1', 'L2', 'crank', 'ground']
"""

from __future__ import annotations

from gearlever.synthesis.model import mechanism_table, model_toml

__all__ = ["joint_names", "linkage_model", "linkage_toml"]


def joint_names(lk) -> list[str]:
    """Point name of each joint of ``lk``."""
    fixed = {int(f) for f in lk.fixed_joints}
    return ["P" if k == lk.target_joint else (f"O{k}" if k in fixed else f"J{k}") for k in range(lk.n_joints)]


def linkage_model(lk, *, name: str = "synthesized linkage", units: str = "") -> dict:
    """Model dict (accepted by :func:`gearlever.mechanism.model_from_dict`) of a :class:`~gearlever.curves.Linkage`."""
    names = joint_names(lk)
    fixed = {int(f) for f in lk.fixed_joints}
    points = {names[k]: [float(x) + 0.0, float(y) + 0.0] for k, (x, y) in enumerate(lk.x0)}
    links = {"ground": [names[k] for k in sorted(fixed)]}
    motor = {int(lk.motor[0]), int(lk.motor[1])}
    for e, (i, j) in enumerate(lk.edges):
        i, j = int(i), int(j)
        if i in fixed and j in fixed:
            continue
        key = "crank" if {i, j} == motor else f"L{e}"
        a, b = (i, j) if key != "crank" else (int(lk.motor[0]), int(lk.motor[1]))
        links[key] = [names[a], names[b]]
    links = {"ground": links.pop("ground"), "crank": links.pop("crank"), **links}
    return {"mechanism": mechanism_table(name, units), "points": points, "links": links, "inputs": [{"link": "crank"}]}


def linkage_toml(lk, comment: str = "", **kw) -> str:
    """TOML text of :func:`linkage_model`."""
    return model_toml(linkage_model(lk, **kw), comment)
