"""Stephenson six-bar path synthesis: analytic Jacobian, exact recovery, dyad closure, model file."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from gearlever.mechanism.modelfile import model_toml
from gearlever.synthesis.path import synthesize_path
from gearlever.synthesis.path_fourbar import _coupler
from gearlever.synthesis.sixbar import StephensonSixBarPathProblem

from ._jacobian import check_problem_jacobian

RANGES = dict(length_range=(0.5, 6.0), coord_range=(-5.0, 5.0))


@pytest.mark.parametrize("timing", ["none", "relative", "absolute"])
def test_jacobian_matches_central_finite_differences(timing):
    check_problem_jacobian(StephensonSixBarPathProblem, 4, 800, timing, RANGES)


def known_sixbar():
    """A Stephenson six-bar (crank-rocker 4/1/3.5/3 and a dyad that closes all around) and points of its path."""
    pb = StephensonSixBarPathProblem([[0, 0], [1, 1]], "absolute", [0.0, 1.0], **RANGES)
    # x0, y0, theta0, r1, r3, r4, u2, cx, cy, x6, y6, l5, l6, px, py, branch
    z = np.array([0.3, -0.2, 0.4, 4.0, 3.5, 3.0, 0.3, 1.2, 0.8, 3.5, 3.5, 3.0, 2.9, 1.0, 0.5, 0.5])
    assert pb.feasible(z[None, :])[0]
    phi = 0.3 + np.array([0.0, 0.5, 1.1, 1.8, 2.6, 3.3, 4.1])
    P = pb._pts(z[None, :], phi[None, :], pb.mode_of(z[None, :]))[0]
    return P, phi


def test_targets_of_a_known_sixbar_are_met_exactly():
    T, phi = known_sixbar()
    r = synthesize_path(T, phi, timing="absolute", kind="sixbar", **RANGES, seed=0, budget=200_000, workers=2)
    assert r.feasible and r.kind == "sixbar" and r.grashof == "crank-rocker"
    ext = np.ptp(T, axis=0)
    assert r.objective < 1e-12 * float(ext @ ext)


def test_dyad_closes_all_around_on_a_fine_grid_and_the_model_reproduces_the_errors():
    from gearlever.mechanism import Mechanism

    T = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 1.0], [2.5, 2.0], [1.0, 2.5], [0.2, 1.2]])
    r = synthesize_path(T, kind="sixbar", seed=2, budget=20_000, workers=1)
    assert r.feasible
    p = r.params
    grid = np.linspace(0.0, 2 * math.pi, 36_001)
    C = _coupler(*(p[k] for k in ("x0", "y0", "th0", "r1", "r2", "r3", "r4", "cx", "cy")), grid, p["sigma"])
    f = np.hypot(p["x6"] - C[:, 0], p["y6"] - C[:, 1])
    assert f.min() > abs(p["l5"] - p["l6"]) and f.max() < p["l5"] + p["l6"]
    model = tomllib.loads(model_toml(r.model()))
    assert model["links"]["ground"] == ["O2", "O4", "O6"]
    m = Mechanism.from_dict(model)
    assert m.structure().dof == 1
    sol = m.solve(r.input_angles)
    assert sol.closed.all()
    err = np.hypot(*(sol.point["P"] - T).T)
    # the written model: coordinates at 10 digits of its size (gearlever._format)
    assert np.allclose(err, r.error, rtol=1e-6, atol=1e-8 * float(np.ptp(T)))


@pytest.mark.slow
def test_auto_moves_past_the_fourbar_when_it_cannot_reach_the_targets_of_a_sixbar():
    T, phi = known_sixbar()
    r = synthesize_path(T, phi, timing="absolute", kind="auto", **RANGES, seed=0, budget=200_000, workers=2)
    ext = np.ptp(T, axis=0)
    S2 = float(ext @ ext)
    assert r.tried["fourbar"] > 1e-6 * S2  # seven timed points: 14 equations, 9 four-bar unknowns
    assert r.kind != "fourbar" and r.objective < 1e-12 * S2
    assert r.objective == min(v for v in r.tried.values() if v is not None)
