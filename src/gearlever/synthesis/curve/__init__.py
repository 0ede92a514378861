"""Topology synthesis of linkages for a traced curve, scored like the MIT 2.156 linkage challenge.

What lives here:

* (in :mod:`gearlever.mechanism.linkage`, a model file format): the
  challenge's form of a planar revolute linkage (``x0``, ``edges``,
  ``fixed_joints``, ``motor``, ``target_joint``), read and validated from
  ``.links.json``, and its dyadic solve plan; re-exported here as
  ``Linkage``, ``linkage_from_dict``, ``read_linkage``, ``solve_plan``.
* :mod:`~gearlever.synthesis.curve.simulate`: a batched simulator of many dyadic
  linkages over a crank turn in one array pass, with the analytic Jacobian of
  the joint paths with respect to the sketch positions.
* :mod:`~gearlever.synthesis.curve.score`: the challenge's curve distance, material,
  feasibility and the exact 2-D hypervolume.
* :mod:`~gearlever.synthesis.curve.search`: the synthesis (library of four-, six- and
  eight-bar topologies, retrieval over pre-simulated mechanisms, NSGA-II from
  pymoo, least-squares refinement) and the writer of gearlever models.
* :mod:`~gearlever.synthesis.curve.library`: the search's retrieval library stored
  in the user's cache folder (``gearlever curve library build``).

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import numpy, scipy, pymoo, dask and
gearlever's ``_format``, ``_io``, ``_progress``, ``_result``, ``_validate``,
``data``, ``errors``, ``gears``, ``loops``, ``mechanism``, ``synthesis`` (the ``.links.json`` form is
:mod:`gearlever.mechanism.linkage`, the model writer :mod:`gearlever.mechanism.modelfile`); never
matplotlib, pandas or the CLI.  Figures are in :mod:`gearlever.plotting.curves`.
"""

from gearlever.mechanism.linkage import Linkage, linkage_from_dict, read_linkage, solve_plan
from gearlever.synthesis.curve.score import distance, feasible, hypervolume, material
from gearlever.synthesis.curve.simulate import simulate, simulate_jacobian

__all__ = [
    "Linkage",
    "distance",
    "feasible",
    "hypervolume",
    "linkage_from_dict",
    "material",
    "read_linkage",
    "simulate",
    "simulate_jacobian",
    "solve_plan",
]
