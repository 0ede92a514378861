"""The four-bar model against the `mechanism` package (PyPI; scipy fsolve per position).

The package's own closure is only as good as fsolve's tolerance, so the bound
on positions is that of its solve; analogues are compared at 1e-7.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import gearlever

from ._models import example, wrap

mechanism = pytest.importorskip("mechanism")

OMEGA = 1.0
L_CRANK, L_COUPLER = 10.0, math.dist((10, 0), (45.1, 28.3))
L_GROUND, L_ROCKER = 40.0, math.dist((40, 0), (45.1, 28.3))


def run_package(theta2, guess3, guess4):
    O, A, B, C = mechanism.get_joints("O A B C")
    a = mechanism.Vector((O, A), r=L_CRANK)
    b = mechanism.Vector((A, B), r=L_COUPLER)
    c = mechanism.Vector((O, C), r=L_GROUND, theta=0, style="ground")
    d = mechanism.Vector((C, B), r=L_ROCKER)

    def loops(x, inp):
        return a(inp) + b(x[0]) - c() - d(x[1])

    n = theta2.size
    m = mechanism.Mechanism(
        vectors=(a, b, c, d),
        origin=O,
        loops=loops,
        pos=theta2,
        vel=np.full(n, OMEGA),
        acc=np.zeros(n),
        guess=(np.array([guess3, guess4]), np.array([1.0, 1.0]), np.array([1.0, 1.0])),
    )
    m.iterate()
    return b, d


@pytest.mark.filterwarnings("ignore:The iteration is not making good progress:RuntimeWarning")
def test_fourbar_model_agrees_with_mechanism_package():
    theta2 = np.linspace(0.0, 2 * np.pi, 120, endpoint=False)
    r = gearlever.Mechanism.load(example("fourbar")).solve(theta2)
    coupler, rocker = run_package(theta2, r.angle["coupler"][0], r.angle["rocker"][0])
    assert np.abs(wrap(coupler.pos.thetas - r.angle["coupler"])).max() < 1e-9
    assert np.abs(wrap(rocker.pos.thetas - r.angle["rocker"])).max() < 1e-9
    assert np.abs(coupler.vel.omegas - r.omega["coupler"]).max() < 1e-7
    assert np.abs(rocker.vel.omegas - r.omega["rocker"]).max() < 1e-7
    assert np.abs(coupler.acc.alphas - r.alpha["coupler"]).max() < 1e-7
    assert np.abs(rocker.acc.alphas - r.alpha["rocker"]).max() < 1e-7
