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
    """A sweep of every input from its sketch value: a full turn (or +-1.2 rad for the parallel levers).

    A one-input model whose input rocks (the Watt I six-bar) sweeps the middle fifth of its range instead, at rate 1
    (nearer its dead points its rates vary too fast for the tests' finite differences and the closed-form dyads).
    """
    from gearlever.mechanism.limits import input_limits

    q0 = mech.sketch_inputs
    W = q0.size
    if "parallel" in mech.name:
        t = np.linspace(-1.2, 1.2, points)
    elif W == 1 and (lim := input_limits(mech)).rocks:
        pad = 0.4 * (lim.upper - lim.lower)
        return np.linspace(lim.lower + pad, lim.upper - pad, points)[:, None], np.ones((points, 1))
    elif "square-rod" in mech.name:
        t = np.linspace(0.0, 2 * np.pi, points) + 0.05  # off its square pose (270 deg) and off the sketch
    else:
        t = np.linspace(0.0, 2 * np.pi, points)
    rates = np.array([1.0, 0.37, -0.21][:W])
    return q0 + t[:, None] * rates, np.broadcast_to(rates, (points, W)).copy()
