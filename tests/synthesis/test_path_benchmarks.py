"""Path-synthesis benchmark cases of the literature: default settings against the best published objective.

Cases, constraint sets and published values: ``gearlever/data/path_benchmarks.toml``
(sources there: Cabrera, Simon, Prado, Mech. Mach. Theory 37 (2002); Kunjur and
Krishnamurty (1997); Acharyya and Mandal, Mech. Mach. Theory 44 (2009); Lin,
Mech. Mach. Theory 45 (2010)).
"""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

from gearlever.data import read_text
from gearlever.synthesis.path import synthesize_path

CASES = tomllib.loads(read_text("path_benchmarks.toml"))["cases"]
SLOW = {"ellipse10"}


def run(case):
    T = np.column_stack([case["x"], case["y"]])
    ang = np.radians(case["input_deg"]) if "input_deg" in case else None
    return synthesize_path(
        T, ang, timing=case["timing"], length_range=case["length_range"], coord_range=case["coord_range"], seed=0
    )


@pytest.mark.parametrize(
    "name", [pytest.param(n, marks=pytest.mark.slow) if n in SLOW else n for n in CASES if "best_published" in CASES[n]]
)
def test_default_settings_reach_the_best_published_objective(name):
    case = CASES[name]
    r = run(case)
    assert r.feasible and r.grashof == "crank-rocker"
    assert r.objective <= case["best_published"] + case["tolerance"], (name, r.objective, case["best_published_source"])


def test_every_case_names_its_source_and_constraint_set():
    for name, case in CASES.items():
        assert case["source"] and case["timing"] in ("none", "relative", "absolute"), name
        assert len(case["x"]) == len(case["y"]) >= 2, name
        assert case["length_range"][0] < case["length_range"][1], name
        if "best_published" in case:
            assert case["best_published_source"] and case["tolerance"] >= 0, name
