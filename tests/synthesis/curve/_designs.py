"""Set-up shared by the curve-synthesis tests (tests/synthesis/curve, tests/cli, tests/mechanism).

``SIXBAR``: a six-bar in the challenge's form (.links.json) whose traced joint
6 turns fully; ``turning``: a random dyadic linkage of the synthesis' library
that turns fully; fixtures ``cache`` (an empty cache folder of the test's own)
and ``small`` (a small synthesis library and search, so that a synthesis runs
in a second or two).  A test module takes a fixture with ``cache = _designs.cache``.
"""

import numpy as np
import pytest

from gearlever.synthesis.curve import library as L
from gearlever.synthesis.curve import search as S
from gearlever.synthesis.curve import topology as T
from gearlever.synthesis.curve.simulate import simulate

SIXBAR = {
    "x0": [[0, 0], [0.3, 0.2], [2, 0], [1.5, 1.5], [3, 1], [2.5, 2.5], [1.0, 2.2]],
    "edges": [[0, 1], [1, 3], [2, 3], [3, 5], [4, 5], [1, 6], [3, 6], [2, 4]],
    "fixed_joints": [0, 2, 4],
    "motor": [0, 1],
    "target_joint": 6,
}


def turning(n_dyads, seed, **simulate_kw):
    """``(topology, sketch)``: the first of 200 random sketches of a random topology that turns fully.

    ``n_dyads`` dyads, two ground pivots; ``simulate_kw`` (``steps``) goes to the check of the turn.
    """
    rng = np.random.default_rng(seed)
    while True:
        topo = T.random_topology(rng, n_dyads, 2)
        x0 = T.random_sketches(rng, topo, 200)
        ok = np.isfinite(simulate(x0, topo.plan, **simulate_kw)).all(axis=(1, 2, 3))
        if ok.any():
            return topo, x0[np.flatnonzero(ok)[0]]


@pytest.fixture
def cache(tmp_path, monkeypatch):
    """The cache folder (``$GEARLEVER_CACHE``) of this test, not made yet."""
    folder = tmp_path / "cache"
    monkeypatch.setenv("GEARLEVER_CACHE", str(folder))
    return folder


@pytest.fixture
def small(monkeypatch):
    """A small library (8 topologies x 60 sketches) and search (2 starts, 4 preselected, 3 lambdas)."""
    monkeypatch.setattr(L, "LIBRARY_TOPOLOGIES", 8)
    monkeypatch.setattr(L, "LIBRARY_SKETCHES", 60)
    monkeypatch.setattr(S, "STARTS", 2)
    monkeypatch.setattr(S, "PRESELECT", 4)
    monkeypatch.setattr(S, "LAMBDAS", np.geomspace(1e-3, 0.3, 3))
    monkeypatch.setattr(S, "LAMBDAS_SQUARED", np.geomspace(1e-3, 0.3, 3))
