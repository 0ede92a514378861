"""Shared helpers of the mechanism tests: the shipped example models and finite differences."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def example(name: str) -> Path:
    return EXAMPLES / f"{name}.toml"


def all_examples() -> list:
    """The example mechanism models (motion laws, also TOML, left out)."""
    return sorted(p for p in EXAMPLES.glob("*.toml") if "[law]" not in p.read_text(encoding="utf-8"))


#: A known defect (kept visible by a strict xfail, which fails once it is fixed): a sweep of the square-rod
#: slider-crank that does not start at its sketch pose can pass the square pose (a branch point) without
#: detecting it, so rows past it stay on the kept branch under ``branch="continue"`` (the fast dyad path and the
#: general Newton path alike); a row exactly on the pose has extrapolated accelerations off by up to 1e-3.
BRANCH_DEFECT = pytest.mark.xfail(
    strict=True, reason="branch point missed by a sweep not starting at the sketch (known defect, issue 34)"
)


def examples_with_known_defects_marked() -> list:
    """:func:`all_examples`, the square-rod slider-crank marked with :data:`BRANCH_DEFECT`."""
    return [
        pytest.param(p, marks=BRANCH_DEFECT, id=p.stem)
        if p.stem == "square_rod_slider_crank"
        else pytest.param(p, id=p.stem)
        for p in all_examples()
    ]


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
        t = (
            np.linspace(0.0, 2 * np.pi, points) + 0.05
        )  # off its square pose (270 deg) and off the sketch: see BRANCH_DEFECT
    else:
        t = np.linspace(0.0, 2 * np.pi, points)
    rates = np.array([1.0, 0.37, -0.21][:W])
    return q0 + t[:, None] * rates, np.broadcast_to(rates, (points, W)).copy()
