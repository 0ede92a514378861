"""Benchmark: simulate 10**6 chariot path steps in one vectorised pass.

Prints steps per second beside numpy's own time for one ``np.cumsum`` over an
array of the same length (the floor: a simulation must at least accumulate
the headings), and the ratio floor_time / simulate_time (target >= 0.2).
Both are timed in this process, best of several repeats.
"""

from __future__ import annotations

import time

import numpy as np

from gearlever.gears.chariot import NuttallTeeth, design_nuttall, random_path, simulate

STEPS = 10**6
REPEATS = 15


def best(fn, repeats=REPEATS) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    design = design_nuttall(NuttallTeeth(30, 24, 18, 36, 20, 25, 40))
    ds_left, ds_right = random_path(STEPS / 1000, seed=1, steps_per_turn=1000, track=design.track)
    assert ds_left.size == STEPS
    run = simulate(design, ds_left, ds_right)
    # interleave the two timings so that both see the same machine load
    t_sim, t_floor = float("inf"), float("inf")
    for _ in range(REPEATS):
        t_sim = min(t_sim, best(lambda: simulate(design, ds_left, ds_right), 1))
        t_floor = min(t_floor, best(lambda: np.cumsum(ds_left), 1))
    ratio = t_floor / t_sim
    print(
        f"chariot simulate: {STEPS} steps in {t_sim * 1e3:.2f} ms = {STEPS / t_sim:.3e} steps/s "
        f"(chassis {run.turns:.0f} turns, max pointer drift {run.max_drift:.1e} rad)"
    )
    print(
        f"numpy floor: one np.cumsum over {STEPS} floats in {t_floor * 1e3:.2f} ms = {STEPS / t_floor:.3e} elements/s"
    )
    print(f"ratio floor/simulate = {ratio:.2f} (target >= 0.2): {'ok' if ratio >= 0.2 else 'BELOW TARGET'}")


if __name__ == "__main__":
    main()
