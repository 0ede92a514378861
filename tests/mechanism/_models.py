"""Shared helpers of the mechanism tests: the shipped example models and finite differences."""

from __future__ import annotations

from pathlib import Path

import numpy as np

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def example(name: str) -> Path:
    return EXAMPLES / f"{name}.toml"


def all_examples() -> list:
    """The example mechanism models (motion laws, also TOML, left out)."""
    return sorted(p for p in EXAMPLES.glob("*.toml") if "[law]" not in p.read_text(encoding="utf-8"))


def wrap(x):
    return np.arctan2(np.sin(x), np.cos(x))


def sweep(mech, points: int = 721):
    """A sweep of every input from its sketch value: a full turn (or +-1.2 rad for the parallel levers)."""
    q0 = mech.sketch_inputs
    W = q0.size
    if "parallel" in mech.name:
        t = np.linspace(-1.2, 1.2, points)
    else:
        t = np.linspace(0.0, 2 * np.pi, points)
    rates = np.array([1.0, 0.37, -0.21][:W])
    return q0 + t[:, None] * rates, np.broadcast_to(rates, (points, W)).copy()
