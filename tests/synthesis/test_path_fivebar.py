"""Geared five-bar path synthesis: analytic Jacobian, exact recovery, closure over the period, model file."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from gearlever.mechanism.modelfile import model_toml
from gearlever.synthesis.fivebar import RATIOS, TURNS, GearedFiveBarPathProblem
from gearlever.synthesis.path import synthesize_path

from ._jacobian import check_problem_jacobian

RANGES = dict(length_range=(0.5, 6.0), coord_range=(-5.0, 5.0))


@pytest.mark.parametrize("timing", ["none", "relative", "absolute"])
def test_jacobian_matches_central_finite_differences(timing):
    check_problem_jacobian(GearedFiveBarPathProblem, 3, 600, timing, RANGES)


def known_fivebar():
    """A geared five-bar (gears 40:20) that closes over its whole period, and points of its path."""
    pb = GearedFiveBarPathProblem([[0, 0], [1, 1]], "absolute", [0.0, 1.0], **RANGES)
    z = np.array([0.2, -0.1, 0.3, 2.5, 1.0, 1.2, 3.2, 3.0, 1.1, 0.6, 0.7, 1.0, 2.2])  # gears (40, 20), open
    assert pb.names[-1] == "branch" and RATIOS[int(z[-1]) // 2] == (40, 20)
    assert pb.feasible(z[None, :])[0]
    phi = 0.4 + np.array([0.0, 0.6, 1.3, 2.1, 2.9, 3.6])
    P = pb._pts(z[None, :], phi[None, :], pb.mode_of(z[None, :]))[0]
    return P, phi


def test_targets_of_a_known_geared_fivebar_are_met_exactly():
    T, phi = known_fivebar()
    r = synthesize_path(T, phi, timing="relative", kind="geared-fivebar", **RANGES, seed=0, budget=200_000, workers=2)
    assert r.feasible and r.kind == "geared-fivebar"
    ext = np.ptp(T, axis=0)
    assert r.objective < 1e-12 * float(ext @ ext)


def test_closure_holds_over_the_whole_period_on_a_fine_grid_and_the_model_reproduces_the_errors():
    from gearlever.mechanism import Mechanism

    T = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 1.0], [2.5, 2.0], [1.0, 2.5], [0.2, 1.2]])
    r = synthesize_path(T, kind="geared-fivebar", seed=2, budget=20_000, workers=1)
    assert r.feasible
    p = r.params
    pb = GearedFiveBarPathProblem(T, "none", **dict(zip(("length_range", "coord_range"), _ranges(T))))
    grid = np.linspace(0.0, 2 * math.pi * TURNS, 72_001)[None, :]
    _, _, Dx, Dy, _ = pb._AD({k: np.array([v]) for k, v in p.items()}, grid, np.array([p["rho"]]))
    f = np.hypot(Dx, Dy)
    assert f.min() > abs(p["c"] - p["d"]) and f.max() < p["c"] + p["d"]
    model = tomllib.loads(model_toml(r.model()))
    assert (model["gears"]["g1"]["teeth"], model["gears"]["g2"]["teeth"]) == r.teeth
    assert model["meshes"] == [{"gears": ["g1", "g2"]}]
    m = Mechanism.from_dict(model)
    assert m.structure().dof == 1
    sol = m.solve(r.input_angles)
    assert sol.closed.all()
    err = np.hypot(*(sol.point["P"] - T).T)
    assert np.allclose(err, r.error, rtol=1e-6, atol=1e-9 * float(np.ptp(T)))


def _ranges(T):
    from gearlever.synthesis.path import default_ranges

    return default_ranges(T)


def test_auto_reports_every_type_tried_and_keeps_the_best():
    T = np.array([[0.0, 0.0], [1.0, 0.2], [2.0, 1.0], [2.5, 2.0], [1.0, 2.5], [0.2, 1.2], [-0.5, 1.0]])
    ang = np.radians([0, 40, 80, 130, 190, 250, 300])
    r = synthesize_path(T, ang, kind="auto", seed=1, budget=8_000, workers=1)
    assert set(r.tried) <= {"fourbar", "geared-fivebar", "sixbar"} and "fourbar" in r.tried
    done = {k: v for k, v in r.tried.items() if v is not None}
    assert r.objective == min(done.values())
    assert r.tried[r.kind] == r.objective
