"""The compiled sine and cosine (gearlever.loops.compiled) against numpy's np.sin and np.cos, on any CPU."""

from __future__ import annotations

import os
import platform
import subprocess
import sys

import numba
import numpy as np
import pytest

from gearlever.loops import compiled
from gearlever.loops.compiled import SINCOS_LIMIT, sincos_into

#: Measured 2.3e-16 at most; a wrong quadrant or sign is off by O(1), a lost term of the reduction by ~1e-11.
TOL = 4e-16


def _sincos(phi, block=32768):
    s, c = np.empty_like(phi), np.empty_like(phi)
    sincos_into(phi, s, c, block)
    return s, c


@pytest.mark.parametrize(
    "lo, hi",
    [(-7.0, 7.0), (-1e3, 1e3), (1e5, SINCOS_LIMIT), (SINCOS_LIMIT, 1e6), (1e6, 1e12), (-1e300, 1e300)],
)
def test_compiled_sin_and_cos_equal_numpys_to_rounding_over_every_range(lo, hi):
    phi = np.random.default_rng(11).uniform(lo, hi, 100_000)
    s, c = _sincos(phi)
    assert np.abs(s - np.sin(phi)).max() <= TOL
    assert np.abs(c - np.cos(phi)).max() <= TOL


def test_compiled_sin_and_cos_at_the_quadrant_points_and_the_limit():
    k = np.arange(-9, 10)
    phi = np.concatenate(
        [k * np.pi / 2, k * np.pi / 4, [5e-324, -0.0, np.nextafter(np.pi, 4.0), SINCOS_LIMIT, -SINCOS_LIMIT]]
    )
    s, c = _sincos(phi)
    np.testing.assert_allclose(s, np.sin(phi), rtol=0, atol=TOL)
    np.testing.assert_allclose(c, np.cos(phi), rtol=0, atol=TOL)


def test_a_far_angle_sends_its_block_and_only_its_block_through_the_c_library():
    # one angle beyond the limit among ordinary ones: its block is redone exactly, the others keep the polynomial
    phi = np.random.default_rng(5).uniform(-7.0, 7.0, 1000)
    phi[500] = 3.0e15
    s, c = _sincos(phi, block=100)
    assert np.abs(s - np.sin(phi)).max() <= TOL and np.abs(c - np.cos(phi)).max() <= TOL
    near, _ = _sincos(np.delete(phi, 500), block=100)
    np.testing.assert_array_equal(np.delete(s, 500)[:500], near[:500])  # blocks before it: the same bits


_BITS_SCRIPT = """
import sys, numpy as np
from gearlever.loops.compiled import sincos_into
phi = np.random.default_rng(2).uniform(-40.0, 40.0, 50_000)
s, c = np.empty_like(phi), np.empty_like(phi)
sincos_into(phi, s, c)
np.save(sys.argv[1], np.stack([s, c]))
"""


def _has_avx2() -> bool:
    from numpy._core._multiarray_umath import __cpu_features__

    return bool(__cpu_features__.get("AVX2")) and bool(__cpu_features__.get("FMA3"))


@pytest.mark.skipif(platform.machine() not in ("x86_64", "AMD64"), reason="numba's x86 target CPUs")
@pytest.mark.parametrize("cpu", ["generic", "haswell"])
def test_compiled_sin_and_cos_give_the_same_bits_for_every_target_cpu(cpu, tmp_path):
    # compiled for plain x86-64 (SSE2), for AVX2 (haswell) and here for this machine's own CPU: same bits,
    # since no multiply-add is fused and the vector width does not change an element's arithmetic
    if cpu == "haswell" and not _has_avx2():
        pytest.skip("this CPU has no AVX2")
    env = {**os.environ, "NUMBA_CPU_NAME": cpu, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    out = tmp_path / "bits.npy"
    subprocess.run([sys.executable, "-c", _BITS_SCRIPT, str(out)], env=env, check=True, timeout=300)
    phi = np.random.default_rng(2).uniform(-40.0, 40.0, 50_000)
    here = np.stack(_sincos(phi))
    assert np.array_equal(np.load(out).view(np.int64), here.view(np.int64))


def test_jit_compiles_without_the_cache_where_none_can_be_written(monkeypatch):
    real = numba.njit

    def no_locator(*args, **kwargs):
        if kwargs.get("cache"):
            raise RuntimeError("cannot cache function 'f': no locator available for file '<string>'")
        return real(*args, **kwargs)

    monkeypatch.setattr(numba, "njit", no_locator)

    def f(x):
        return 2.0 * x + 1.0

    assert compiled.jit(f)(3.0) == 7.0
