"""Planar mechanisms: structure (mobility with redundant constraints) and models as data.

- :mod:`~gearlever.mechanism.mobility`: the mobility formula
  W = 3n - 2 P5 - P4 + q and its inverse for redundant constraints.
- :mod:`~gearlever.mechanism.schema`: the model file's tables, keys, types,
  units and caps, declared once; :mod:`~gearlever.mechanism.model`: model
  files (TOML) of links, pins, sliders, gears and meshes, validated into a
  :class:`MechanismModel`; :mod:`~gearlever.mechanism.modelfile`: the one
  writer of model files; :mod:`~gearlever.mechanism.linkage`: the
  ``.links.json`` form of a linkage, read as a model.
- :mod:`~gearlever.mechanism.constraints`: constraint rows and their
  analytic Jacobian in absolute coordinates.
- :mod:`~gearlever.mechanism.structural`: counts, mobility and redundant
  constraints from the Jacobian's rank.
- :mod:`~gearlever.mechanism.solve`: positions, velocities, accelerations,
  batched over the inputs; :mod:`~gearlever.mechanism.core`: :class:`Mechanism`.
- :func:`sweep` / :func:`sweep_rows`: the one sweep rule of the commands
  (:mod:`gearlever.mechanism.sweep`); :func:`input_limits`: the dead points
  of an input that cannot turn fully (:mod:`gearlever.mechanism.limits`).
- :func:`assemble`: a rough sketch closed to the exact lengths of its
  ``[lengths]`` table (:mod:`gearlever.mechanism.assemble`).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy and gearlever's
``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``, ``data``,
``errors``, ``gears``, ``loops``; never pandas or matplotlib.
Nothing of :mod:`gearlever.synthesis.curve` or :mod:`gearlever.synthesis` (they import it): the
``.links.json`` form (:mod:`gearlever.mechanism.linkage`) and the model writer
(:mod:`gearlever.mechanism.modelfile`) live here.
"""

from gearlever.mechanism.assemble import assemble
from gearlever.mechanism.core import Mechanism
from gearlever.mechanism.limits import InputLimits, input_limits
from gearlever.mechanism.mobility import mobility, redundant_constraints
from gearlever.mechanism.model import MechanismModel, load_model, model_from_dict
from gearlever.mechanism.solve import MechanismResult
from gearlever.mechanism.structural import MechanismStructure
from gearlever.mechanism.sweep import Sweep, sweep, sweep_rows

__all__ = [
    "assemble",
    "input_limits",
    "InputLimits",
    "sweep",
    "sweep_rows",
    "Sweep",
    "mobility",
    "redundant_constraints",
    "Mechanism",
    "MechanismModel",
    "MechanismResult",
    "MechanismStructure",
    "load_model",
    "model_from_dict",
]
