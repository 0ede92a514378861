"""The four-bar through the `mechanism` package (fsolve at every step), for the agreement tests."""

from __future__ import annotations

import numpy as np


def run_fourbar(ground, crank, coupler, rocker, theta2, omega, guess3, guess4):
    """Coupler and rocker vectors of the package's solution over crank angles ``theta2`` at speed ``omega``."""
    import mechanism

    O, A, B, C = mechanism.get_joints("O A B C")
    a = mechanism.Vector((O, A), r=crank)
    b = mechanism.Vector((A, B), r=coupler)
    c = mechanism.Vector((O, C), r=ground, theta=0, style="ground")
    d = mechanism.Vector((C, B), r=rocker)

    def loops(x, inp):
        return a(inp) + b(x[0]) - c() - d(x[1])

    n = theta2.size
    m = mechanism.Mechanism(
        vectors=(a, b, c, d),
        origin=O,
        loops=loops,
        pos=theta2,
        vel=np.full(n, omega),
        acc=np.zeros(n),
        guess=(np.array([guess3, guess4]), np.array([1.0, 1.0]), np.array([1.0, 1.0])),
    )
    m.iterate()
    return b, d
