"""Benchmark: curve synthesis (hypervolume and time per target) and the batched dyadic simulator's speed.

Three parts, each printed as a table:

1. **Own suite** (free to ship: every curve is made here; scored as a user's
   curves are, in the relative scoring of :mod:`gearlever.synthesis.curve.score`): curves traced by
   known mechanisms of 7, 9 and 11 joints (random dyadic linkages of fixed
   seeds, feasible: material below 10; exact recovery means a best distance
   below 0.01) and closed shapes
   (egg, kidney, figure-eight, D, bean), all at the RMS radius of the
   challenge's targets (0.191).  Per curve: hypervolume against
   (0.75, 10), best distance, least material, designs, seconds.
2. **The MIT 2.156 challenge's six curves** (the challenge's scoring), only with ``--challenge DIR``
   (a clone of ``ahnobari/2155-Optimization-Challenge-Problem``: the
   repository has no licence, so its data is read from there and never
   copied): our hypervolume per curve beside the published NSGA-II starter
   baseline (mean 1.339) and the best student result (4.856), and the
   hypervolume of the front's ideal point (least distance with least
   material: what no front of those ends can exceed) and the headroom left
   to it; ``--time 300 --curves 1,5`` runs curves on the clock instead.
3. **Simulator speed**: mechanisms x steps per second of
   :func:`gearlever.synthesis.curve.simulate.simulate` on a batch of 12-joint
   linkages, against the challenge's JAX solver (``--challenge DIR`` and
   ``jax`` installed: the bench extra) jit-compiled on CPU on the same
   mechanisms, in the same process; ratio = JAX time / ours.

Usage::

    python benchmarks/bench_curves.py [--budget 20000] [--challenge DIR] [--quick] [--part challenge]
        [--time 300] [--curves 1,5] [--workers N]
"""

from __future__ import annotations

import argparse
import importlib.util
import time
from pathlib import Path

import numpy as np

from gearlever.synthesis.curve import search as S
from gearlever.synthesis.curve import topology as T
from gearlever.synthesis.curve.score import hypervolume
from gearlever.synthesis.curve.simulate import simulate
from gearlever.synthesis.curve.targets import SUITE_RMS, known_mechanism

PUBLISHED_BASELINE = [2.08, 1.63, 1.29, 1.39, 0.86, 0.79]  # mean 1.339 (challenge starter notebook, NSGA-II)
BEST_STUDENT = 4.856
#: The best public submission per curve (found in public forks of the challenge's repository; issue 33).
BEST_PUBLIC = [6.011, 4.018, 4.774, 5.358, 4.448, 4.534]


#: RMS radius of every suite curve: that of the challenge's six targets (material is absolute, so size matters).
RMS = SUITE_RMS


def _sized(curve):
    c = np.asarray(curve, dtype=float)
    c = c - c.mean(0)
    return c * (RMS / np.sqrt((c**2).sum(-1).mean()))


def shapes() -> dict:
    t = np.linspace(0, 2 * np.pi, 240, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    d = np.stack([np.where(c > 0.3, 0.3, c), s], -1)  # a D: a circle with a flat side
    curves = {
        "egg": np.stack([c * (1 + 0.25 * s), 0.8 * s], -1),
        "kidney": np.stack([c + 0.35 * np.cos(2 * t), s + 0.1 * np.sin(3 * t)], -1),
        "figure-eight": np.stack([s, s * c], -1),
        "D": d,
        "bean": np.stack([c * (1.2 + 0.3 * c), s * (0.8 - 0.35 * c * c)], -1),
    }
    return {k: _sized(v) for k, v in curves.items()}


def run(name, curve, budget, seed=0, workers=None):
    t0 = time.perf_counter()
    r = S.synthesize_curve(curve, budget=budget, seed=seed, workers=workers)
    dt = time.perf_counter() - t0
    best = float(r.error[0]) if len(r.designs) else float("nan")
    least = float(r.material.min()) if len(r.designs) else float("nan")
    print(f"| {name} | {r.hypervolume:.3f} | {best:.4f} | {least:.3f} | {len(r.designs)} | {dt:.0f} |", flush=True)
    return r.hypervolume, best, dt


def suite(budget, quick, workers=None):
    print("\n| curve | hypervolume | best distance | least material | designs | seconds |")
    print("|---|---|---|---|---|---|")
    for n_dyads, seed in ((4, 11), (6, 12), (8, 13)):
        topo, _, curve = known_mechanism(n_dyads, seed)
        _, best, _ = run(f"known {topo.n}-joint linkage", curve, budget, workers=workers)
        print(f"| (exact recovery, distance < 0.01: {'yes' if best < 0.01 else 'no'}) ||||||")
        if quick:
            break
    for name, curve in shapes().items():
        run(name, curve, budget, workers=workers)
        if quick:
            break


def ideal_point_hypervolume(result) -> float:
    """Hypervolume of the front's ideal point (its least distance and least material together): the most any
    front of those ends could reach; minus the front's own hypervolume, the headroom."""
    if not len(result.designs):
        return 0.0
    return float(hypervolume(np.array([[result.error.min(), result.material.min()]])))


def challenge(dirpath, budget, time_limit=None, curves=None, workers=None):
    targets = np.load(Path(dirpath) / "target_curves.npy")
    print(
        "\n| challenge curve | our hypervolume | best public | ideal point | headroom | published baseline"
        " | best published (mean) | seconds |"
    )
    print("|---|---|---|---|---|---|---|---|")
    hvs = []
    for i, t in enumerate(targets):
        if curves is not None and i + 1 not in curves:
            continue
        t0 = time.perf_counter()
        r = S.synthesize_curve(  # the challenge's own rules
            t,
            budget=None if time_limit else budget,
            time_limit=time_limit,
            seed=0,
            workers=workers,
            scoring="challenge",
        )
        dt = time.perf_counter() - t0
        hvs.append(r.hypervolume)
        ideal = ideal_point_hypervolume(r)
        print(
            f"| {i + 1} | {r.hypervolume:.3f} | {BEST_PUBLIC[i]:.3f} | {ideal:.3f} | {ideal - r.hypervolume:.3f}"
            f" | {PUBLISHED_BASELINE[i]:.2f}"
            f" | {BEST_STUDENT} | {dt:.0f} |",
            flush=True,
        )
    picked = [BEST_PUBLIC[i] for i in range(len(targets)) if curves is None or i + 1 in curves]
    print(f"| mean | {np.mean(hvs):.3f} | {np.mean(picked):.3f} | | | 1.339 | {BEST_STUDENT} | |")


def _jax_solver(dirpath):
    path = Path(dirpath) / "LINKS" / "Kinematics" / "_solvers" / "_JAX.py"
    spec = importlib.util.spec_from_file_location("links_jax_solver", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod.solve_rev_vectorized_batch


def speed(dirpath, batch=1000, repeats=5):
    rng = np.random.default_rng(7)
    topo = T.random_topology(rng, 9, 2)  # 12 joints: pivot, tip, one more pivot, nine dyads
    x0 = T.random_sketches(rng, topo, batch)
    steps = 200
    simulate(x0, topo.plan)
    t_ours = min(_timed(lambda: simulate(x0, topo.plan)) for _ in range(repeats))
    rate = batch * steps / t_ours
    print(
        f"\nsimulator: {batch} mechanisms of {topo.n} joints x {steps} steps: ours {t_ours * 1e3:.1f} ms "
        f"({rate:.3g} mechanism-steps/s)"
    )
    if dirpath is None:
        return
    try:
        import jax
        import jax.numpy as jnp
    except ImportError:
        print("jax not installed: no comparison (pip install jax)")
        return
    solve = jax.jit(_jax_solver(dirpath))
    order = topo.plan.order
    for size in (topo.n, 20):  # as sorted for the solver; 20 = the challenge's padded size
        xs = np.zeros((batch, size, 2))
        xs[:, : topo.n] = x0[:, order]
        A = np.zeros((batch, size, size))
        inv = np.argsort(order)
        for i, j in topo.edges:
            A[:, inv[i], inv[j]] = A[:, inv[j], inv[i]] = 1.0
        types = np.zeros((batch, size, 1))
        types[:, inv[topo.fixed], 0] = 1.0
        types[:, topo.n :, 0] = 1.0
        th = np.linspace(0, 2 * np.pi, steps)
        args = [jnp.asarray(a) for a in (A, xs, types, th)]
        out = solve(*args).block_until_ready()
        t_jax = min(_timed(lambda: solve(*args).block_until_ready()) for _ in range(repeats))  # noqa: B023
        ours = simulate(x0, topo.plan)[:, order]
        ok = np.isfinite(ours).all(axis=(1, 2, 3))
        err = float(np.nanmax(np.abs(np.asarray(out)[ok, : topo.n] - ours[ok])))
        print(
            f"  challenge JAX solver (jit, CPU, {out.dtype}, padded to {size} joints): {t_jax * 1e3:.1f} ms; "
            f"ratio JAX / ours = {t_jax / t_ours:.2f}; max position difference {err:.2g}"
        )


def _timed(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--budget", type=int, default=20_000)
    ap.add_argument("--challenge", default=None, help="clone of ahnobari/2155-Optimization-Challenge-Problem")
    ap.add_argument("--quick", action="store_true", help="one known mechanism and one shape")
    ap.add_argument("--part", choices=("all", "suite", "challenge", "speed"), default="all")
    ap.add_argument("--time", type=float, default=None, help="seconds a challenge curve (instead of --budget)")
    ap.add_argument("--curves", default=None, help="challenge curves to run, e.g. 1,5 (default: all six)")
    ap.add_argument("--workers", type=int, default=None, help="local processes (default: synthesize_curve's)")
    a = ap.parse_args()
    if a.part in ("all", "speed"):
        speed(a.challenge)
    if a.part in ("all", "suite"):
        suite(a.budget, a.quick, a.workers)
    if a.part in ("all", "challenge") and a.challenge is not None:
        curves = None if a.curves is None else {int(c) for c in a.curves.split(",")}
        challenge(a.challenge, a.budget, a.time, curves, a.workers)


if __name__ == "__main__":
    main()
