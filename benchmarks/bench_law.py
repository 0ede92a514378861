"""Law synthesis: the dwell benchmark of issue 26 section 4, and the batched law evaluation against the engine.

1. The dwell law (a 120 deg dwell of a rocker, a 45 deg cycloidal rise, a
   3-4-5 return: :data:`DWELL`) with the default settings
   (default budget, default transmission bound, 2 local dask threads), for
   each angle kind and ``auto``, seeds given on the command line (default 0):
   error over the cycle, error and excursion over the dwell, peak
   acceleration analogue against the law's, wall time.  The goal: within
   1 deg over the cycle and 0.25 deg over the dwell, under 2 minutes.
2. Law evaluations per second: the kind's closed form for a population of
   candidates at 360 inputs at once, against the mechanism engine solving
   the written model of one candidate at the same inputs (the same output,
   checked), one process; prints the ratio.

3. ``--examples DIR``: the guide's worked example per kind (a figure each and
   a table against the cam, :mod:`gearlever.reproduce._law_synthesis`).

Run: PYTHONPATH=src .venv/bin/python benchmarks/bench_law.py [SEED ...] [--quick] [--examples DIR]
"""

from __future__ import annotations

import sys
import time

import numpy as np

#: The dwell law of issue 26 section 4, as the segments of a LAW.toml.
DWELL = [
    {"to": 120, "motion": "dwell"},
    {"to": 240, "motion": "cycloidal", "rise": 45},
    {"to": 360, "motion": "345", "rise": -45},
]


def load_law(_=None):
    from gearlever.laws import law_from_segments

    return law_from_segments("angle", "deg", DWELL)


def dwell_benchmark(seeds, kinds) -> None:
    from gearlever.synthesis.law import synthesize_law
    from gearlever.synthesis.law.measure import law_report

    law = load_law()
    print("== 1. dwell law (120 deg dwell, 45 deg cycloidal rise, 3-4-5 return), default settings, 2 threads")
    print(f"{'kind':<15} {'seed':>4} {'err max':>8} {'dwell err':>9} {'dwell exc':>9} {'acc peak':>9} {'time s':>7}")
    for kind in kinds:
        for seed in seeds:
            t0 = time.perf_counter()
            res = synthesize_law(law, kind=kind, seed=seed, workers=2)
            dt = time.perf_counter() - t0
            rep = law_report(res)
            dw = next(s for s in rep["segments"] if s["motion"] == "dwell")
            pa = rep["peak_acceleration_deg_per_rad2"]
            name = kind if kind != "auto" else f"auto:{res.kind}"
            print(
                f"{name:<15} {seed:>4} {rep['error_max_deg']:8.3f} {dw['error_max_deg']:9.3f} "
                f"{dw['dwell_excursion_deg']:9.3f} {pa['achieved']:9.1f} {dt:7.1f}",
                flush=True,
            )
    print(f"(law's peak acceleration analogue {pa['wanted']:.1f} deg/rad^2; goal: err max <= 1, dwell err <= 0.25)")


def evaluation_ratio() -> None:
    from gearlever.mechanism import Mechanism
    from gearlever.synthesis.law import LawProblem
    from gearlever.synthesis.law.driver import target_of_law
    from gearlever.synthesis.law.measure import mechanism_law

    target = target_of_law(load_law())
    print("== 2. law evaluations per second (360 inputs each): closed form batched vs the engine per model")
    for kind in ("fourbar", "geared-fourbar", "sixbar-dwell", "gear-lever"):
        pb = LawProblem(kind, target, 0.0)
        rng = np.random.default_rng(0)
        Z = pb.sample(rng, 4096)
        ok = np.isfinite(pb.objective(Z))
        Z = Z[ok][:1024]
        t0 = time.perf_counter()
        reps = 5
        for _ in range(reps):
            G, _ = pb.kind.generate(Z, target.theta)
        batched = reps * Z.shape[0] / (time.perf_counter() - t0)
        m = 5
        t0 = time.perf_counter()
        worst = 0.0
        for z in Z[:m]:
            ml = mechanism_law(Mechanism.from_dict(pb.kind.model(z, 0.0)), "output", target.theta.size)
            g = pb.kind.generate(z[None, :], target.theta)[0][0]
            worst = max(worst, float(np.abs(ml.s - (g - g[0])).max()))
        engine = m / (time.perf_counter() - t0)
        print(
            f"{kind:<15} closed form {batched:10.0f}/s   engine {engine:6.1f}/s   ratio {batched / engine:8.0f}"
            f"   (same output to {worst:.1e} rad)"
        )


def main(argv) -> None:
    if "--examples" in argv:  # the guide's worked example per kind (docs/_static/law_synthesis)
        from pathlib import Path

        from gearlever.reproduce._law_synthesis import run

        folder = Path(argv[argv.index("--examples") + 1])
        folder.mkdir(parents=True, exist_ok=True)
        print("\n".join(run(folder, folder)))
        return
    quick = "--quick" in argv
    seeds = [int(a) for a in argv if a.isdigit()] or [0]
    kinds = ["sixbar-dwell"] if quick else ["fourbar", "geared-fourbar", "sixbar-dwell", "gear-lever", "auto"]
    dwell_benchmark(seeds, kinds)
    evaluation_ratio()


if __name__ == "__main__":
    main(sys.argv[1:])
