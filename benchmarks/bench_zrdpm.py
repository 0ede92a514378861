"""Benchmark: ZRDPM contour-1 outputs for 10^6 angles against numpy's sin + cos alone.

In one process and one run, times
  (a) all six contour-1 outputs u_1, u_8, e_1, e_8, a_B, a_A for 10^6 angles, and
  (b) numpy computing only sin and cos of the same array (the floor for any
      implementation that calls numpy's sin and cos; the fast path is a compiled kernel
      with a vectorized sin and cos of its own, gearlever.loops.compiled, so it runs above
      this floor on any x86 CPU),
and prints both rates and the ratio rate(a)/rate(b) (1.0 would be "as fast as the floor").

(a) is timed for the tables model (the one that regenerates Tables I and II: eq. 16 with
constant analogues; one sin and one cos per angle) on the fast path, once allocating its
(6, N) result and once writing into a given one (out=); the floor likewise once allocating
and once writing into given arrays.  For comparison: the plain numpy path, and the
self-consistent model, whose lever angle needs a second sin/cos pair per angle.  Each
timing is the best of interleaved repeats.

Run: .venv/bin/python benchmarks/bench_zrdpm.py   (or: make bench)
"""

from __future__ import annotations

import time

import numpy as np
from _machine import machine_line

from gearlever import zrdpm
from gearlever.loops.compiled import sincos_into
from gearlever.loops.trig import sincos_half_angle

N = 1_000_000
REPEATS = 21
BLOCK = 32768  # angles per call of the compiled loop


def main() -> None:
    print(machine_line())
    phi = np.linspace(0.0, 2.0 * np.pi, N)
    params = zrdpm.ZrdpmContour(contour=1, l=10.0, r_a=5.0, r_b=5.0).with_ratio(0.5)
    consts = zrdpm.TablesConstants(contour=1, l_u2=21.0, l_e=-2.24)

    out = np.empty((6, N))
    sin_out, cos_out = np.empty(N), np.empty(N)
    cases = {
        "floor: np.sin + np.cos": lambda: (np.sin(phi), np.cos(phi)),
        "floor, into given arrays": lambda: (np.sin(phi, out=sin_out), np.cos(phi, out=cos_out)),
        "half-angle sin + cos, given": lambda: sincos_half_angle(phi, sin_out, cos_out),
        "compiled sin + cos, given": lambda: sincos_into(phi, sin_out, cos_out),
        "tables model, fast": lambda: zrdpm.tables_outputs(params, consts, phi, block=BLOCK),
        "tables model, fast, out=": lambda: zrdpm.tables_outputs(params, consts, phi, block=BLOCK, out=out),
        "tables model, plain numpy": lambda: zrdpm.tables_outputs(params, consts, phi),
        "self-consistent, fast": lambda: zrdpm.analogues(params, phi, block=BLOCK),
        "self-consistent, plain numpy": lambda: zrdpm.analogues(params, phi),
    }
    # the fast path must give the plain results (its first call also compiles or loads the kernels)
    for fast, plain in (
        (zrdpm.tables_outputs(params, consts, phi, block=BLOCK), zrdpm.tables_outputs(params, consts, phi)),
        (zrdpm.analogues(params, phi, block=BLOCK), zrdpm.analogues(params, phi)),
    ):
        for a, b in zip(fast, plain):
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=1e-12)

    best = {name: float("inf") for name in cases}
    for _ in range(REPEATS):
        for name, fn in cases.items():  # interleaved, so load changes hit every case alike
            t0 = time.perf_counter()
            fn()
            best[name] = min(best[name], time.perf_counter() - t0)

    floor = best["floor: np.sin + np.cos"]
    floor_out = best["floor, into given arrays"]
    print(
        f"ZRDPM contour 1 (u_1, u_8, e_1, e_8, a_B, a_A), {N:.0e} angles, "
        f"best of {REPEATS} interleaved runs, block {BLOCK}"
    )
    for name, t in best.items():
        print(f"  {name:30s} {t * 1e3:8.2f} ms  {N / t / 1e6:7.2f} M angles/s  ratio to floor {floor / t:5.2f}")
    fresh = floor / best["tables model, fast"]
    reuse = floor_out / best["tables model, fast, out="]
    print(f"ratio, tables model fast path vs floor, both allocating their outputs: {fresh:.2f}")
    print(f"ratio, tables model fast path vs floor, both writing into given arrays: {reuse:.2f}  (target >= 0.8)")


if __name__ == "__main__":
    main()
