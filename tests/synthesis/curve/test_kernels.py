"""Compiled residuals of the curve refinement: equal to the numpy simulator and resampling, same bits on any CPU."""

import os
import platform
import subprocess
import sys

import numpy as np
import pytest

from gearlever.synthesis.curve import _kernels as K
from gearlever.synthesis.curve import search as S
from gearlever.synthesis.curve.score import _alignment_indices, resample
from gearlever.synthesis.curve.simulate import simulate
from gearlever.synthesis.curve.targets import known_mechanism


def _case(n_dyads, seed=12, n=200):
    topo, x, curve = known_mechanism(n_dyads, seed)
    x = x * 1.02 + 0.01  # off the target: gaps of every size
    tc = S._target(np.roll(curve, 17, 0))
    perm = np.ascontiguousarray(_alignment_indices(n)[23], dtype=np.int64)
    norm = np.random.default_rng(seed).uniform(0.5, 1.5, n)
    args = (np.ascontiguousarray(topo.plan.dyads, dtype=np.int64), topo.plan.pivot, topo.plan.tip, topo.target)
    return topo, x, tc, perm, norm, args


@pytest.mark.parametrize("n_dyads", [2, 4, 6])
def test_compiled_gaps_equal_the_numpy_simulator_resampled_by_arc_length(n_dyads):
    topo, x, tc, perm, norm, args = _case(n_dyads)
    s = np.linspace(0.0, 1.0, 200)
    g = K.gaps(x, *args, S._crank_cs(), s, perm, np.column_stack([tc.z.real, tc.z.imag]), tc.scale, 0.3, norm)
    c = resample(simulate(x[None], topo.plan)[:, topo.target], 200)[0]
    z = (c[:, 0] + 1j * c[:, 1] - (c[:, 0] + 1j * c[:, 1]).mean()) / tc.scale
    ref = norm * (np.exp(0.3j) * z[perm] - tc.z)
    np.testing.assert_allclose(g, np.concatenate([ref.real, ref.imag]), rtol=0, atol=1e-13)


@pytest.mark.parametrize("n_dyads, seed", [(2, 12), (4, 12), (6, 3), (8, 7)])
def test_compiled_jacobian_matches_central_differences_and_the_angles_column_is_exact(n_dyads, seed):
    """Five to eleven joints (sketches where no resampled point crosses a corner within the step)."""
    topo, x, tc, perm, norm, args = _case(n_dyads, seed)
    n = 200
    s = np.linspace(0.0, 1.0, n)
    J = K.gaps_jacobian(x, *args, S._crank_cs(), s, perm, tc.scale, 0.3, norm)
    assert J.shape == (2 * n, 2 * topo.n + 1)
    # the angle's column: d/d angle of e^(i angle) z = i e^(i angle) z
    g = K.gaps(x, *args, S._crank_cs(), s, perm, np.zeros((n, 2)), tc.scale, 0.3, norm)
    np.testing.assert_allclose(J[:n, -1], -g[n:], atol=1e-13)
    np.testing.assert_allclose(J[n:, -1], g[:n], atol=1e-13)
    # the sketch's columns against central differences of the compiled gaps (the residual test of test_search
    # checks the same through the refinement's residuals)
    h = 1e-6
    tz = np.column_stack([tc.z.real, tc.z.imag])
    fd = np.empty((2 * n, 2 * topo.n))
    for p in range(2 * topo.n):
        e = np.zeros(2 * topo.n)
        e[p] = h
        up = K.gaps(x + e.reshape(-1, 2), *args, S._crank_cs(), s, perm, tz, tc.scale, 0.3, norm)
        dn = K.gaps(x - e.reshape(-1, 2), *args, S._crank_cs(), s, perm, tz, tc.scale, 0.3, norm)
        fd[:, p] = (up - dn) / (2 * h)
    assert np.abs(J[:, :-1] - fd).max() <= 1e-6 * np.abs(fd).max()


def test_a_linkage_that_locks_gives_none_and_the_refinement_a_flat_penalty():
    topo, x, tc, perm, norm, args = _case(2)
    x = x.copy()
    k, i = (int(v) for v in topo.plan.dyads[0, :2])
    x[k] = x[i] + [1e-3, 0.0]  # a dyad link of 0.001: it cannot close once the crank turns
    assert not np.isfinite(simulate(x[None], topo.plan)).all()
    s = np.linspace(0.0, 1.0, 200)
    assert K.gaps(x, *args, S._crank_cs(), s, perm, np.zeros((200, 2)), tc.scale, 0.0, norm) is None
    assert K.gaps_jacobian(x, *args, S._crank_cs(), s, perm, tc.scale, 0.0, norm) is None
    fun, jac = S._residuals(topo, tc, 23, 0.0)
    q = np.append(x.ravel(), 0.0)
    assert np.all(fun(q) == 10.0) and not np.any(jac(q))


_BITS_SCRIPT = """
import sys
import numpy as np
from tests.synthesis.curve.test_kernels import _case
from gearlever.synthesis.curve import _kernels as K
from gearlever.synthesis.curve import search as S
topo, x, tc, perm, norm, args = _case(4)
J = K.gaps_jacobian(x, *args, S._crank_cs(), np.linspace(0.0, 1.0, 200), perm, tc.scale, 0.3, norm)
np.save(sys.argv[1], J)
"""


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"), reason="numba's x86 target CPUs")
def test_compiled_jacobian_gives_the_same_bits_compiled_for_plain_x86_64(tmp_path):
    env = {**os.environ, "NUMBA_CPU_NAME": "generic", "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    out = tmp_path / "bits.npy"
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
    subprocess.run([sys.executable, "-c", _BITS_SCRIPT, str(out)], env=env, check=True, timeout=300, cwd=root)
    topo, x, tc, perm, norm, args = _case(4)
    here = K.gaps_jacobian(x, *args, S._crank_cs(), np.linspace(0.0, 1.0, 200), perm, tc.scale, 0.3, norm)
    assert np.array_equal(np.load(out).view(np.int64), here.view(np.int64))
