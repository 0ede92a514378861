"""Shared check of the path problems' analytic Jacobians against central finite differences."""

from __future__ import annotations

import numpy as np


def central_differences(residual, w, mode):
    """Central finite differences of ``residual(w, mode)`` (step 1e-6 relative, at least 1e-6)."""
    cols = []
    for j in range(w.size):
        h = 1e-6 * max(1.0, abs(w[j]))
        e = np.zeros_like(w)
        e[j] = h
        cols.append((residual(w + e, mode) - residual(w - e, mode)) / (2 * h))
    return np.column_stack(cols)


def check_problem_jacobian(problem, seed: int, samples: int, timing: str, ranges: dict) -> None:
    """Three feasible random designs of ``problem`` (a geared five-bar or six-bar path problem): the
    analytic Jacobian equals central differences of the residual to 1e-6 of its largest entry."""
    rng = np.random.default_rng(seed)
    T = rng.random((5, 2)) * 3
    ang = None if timing == "none" else np.radians([10, 30, 60, 100, 150])
    pb = problem(T, timing, ang, **ranges)
    Z = pb.sample(rng, samples)
    Z = Z[np.isfinite(pb.objective(Z))][:3]
    assert len(Z) == 3
    for z in Z:
        mode = float(pb.mode_of(z[None, :])[0])
        w = pb.to_w(z)
        J = pb.jacobian(w, mode)
        Jn = central_differences(pb.residual, w, mode)
        assert np.abs(J - Jn).max() <= 1e-6 * np.abs(J).max()
