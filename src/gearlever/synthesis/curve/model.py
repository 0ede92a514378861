"""A challenge-form linkage as a gearlever model (points, binary links, the crank as input).

The conversion is part of the model file formats
(:func:`gearlever.mechanism.linkage.linkage_model`); :func:`linkage_toml`
writes it with the one model writer.

>>> from gearlever.mechanism.linkage import linkage_from_dict
>>> lk = linkage_from_dict({"x0": [[0, 0], [0, 1], [3, 0], [2, 2]],
...     "edges": [[0, 1], [1, 3], [2, 3]], "fixed_joints": [0, 2], "motor": [0, 1]})
>>> sorted(linkage_model(lk)["links"])
['L1', 'L2', 'crank', 'ground']
"""

from __future__ import annotations

from gearlever.mechanism.linkage import joint_names, linkage_model
from gearlever.mechanism.modelfile import model_toml

__all__ = ["joint_names", "linkage_model", "linkage_toml"]


def linkage_toml(lk, comment: str = "", **kw) -> str:
    """TOML text of :func:`linkage_model`."""
    return model_toml(linkage_model(lk, **kw), comment)
