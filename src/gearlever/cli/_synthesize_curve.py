"""``gearlever synthesize curve``: any dyadic linkage (up to 20 joints) whose traced joint follows a closed curve.

Registered on the ``synthesize`` sub-parsers by :func:`register_curve`::

    gearlever synthesize curve TARGET.csv --out DIR [--scoring relative|challenge] [--max-joints 20]
        [--designs 1000] [--budget EVALS | --time SECONDS] [--seed N] [--workers N | --scheduler ADDRESS]
        [--library-size N] [--library-seed S] [--report R.json] [--figure F.png]

TARGET.csv holds ``x,y`` rows of a closed curve (header optional), in any
units.  ``--scoring relative`` (default) scores it in its own size (closed,
material measured at the size of the challenge's targets);
``--scoring challenge`` keeps the MIT 2.156 challenge's absolute rules, for
its own targets (:mod:`gearlever.synthesis.curve.score`).  Every design is written in
the target's frame: its traced point ``P`` runs on the curve where it was
drawn (the transform of each is in the report).  DIR (new, or an existing
empty folder) receives, per design on the distance-material front (at most
``--designs``):
``NNNN.toml`` (a gearlever model, traced point ``P``) and ``NNNN.links.json``
(the MIT 2.156 challenge's form), then ``pareto.csv`` (design, distance,
material, joints, links).  Scores and search: :mod:`gearlever.synthesis.curve`.
``--budget`` (default 20000 evaluations) gives the same designs on any
machine and any number of workers; ``--time`` searches while the clock
allows (passes at the default budget, merged) and is not reproducible.
The retrieval library (``--library-size`` mechanisms, seed
``--library-seed``) is loaded from the cache folder when ``gearlever curve
library build`` stored it there, else built in memory: the same designs
either way.  An empty front (no design within distance 0.75 and material 10)
is said on stderr and in the report (``"empty": true``); the exit status is
still 0 (the run itself succeeded).
"""

from __future__ import annotations

from gearlever._io import table_text
from gearlever._progress import TerminalProgress
from gearlever.cli._common import (
    capped_float,
    capped_int,
    check_output,
    check_output_folder,
    emit,
    to_json,
)
from gearlever.errors import GearleverError

#: Most local dask threads.
MAX_WORKERS = 256


def register_curve(ss) -> None:
    p = ss.add_parser(
        "curve",
        help="topology and dimensions of linkages (up to 20 joints) tracing a closed curve, scored like the MIT "
        "2.156 challenge",
    )
    p.add_argument("target", metavar="TARGET.csv", help="closed target curve: x,y rows")
    p.add_argument(
        "--out",
        required=True,
        metavar="DIR",
        help="folder for NNNN.toml, NNNN.links.json, pareto.csv: new, or an existing empty folder",
    )
    p.add_argument(
        "--scoring",
        choices=("relative", "challenge"),
        default="relative",
        help="relative (default): the closed target in its own size, material at the size of the challenge's "
        "targets; challenge: the MIT 2.156 challenge's absolute rules, for its own targets",
    )
    p.add_argument("--max-joints", type=capped_int(1000), default=20, help="most joints of a design (4 to 20)")
    p.add_argument("--designs", type=capped_int(1000), default=1000, help="most designs written (default 1000)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--budget", type=capped_int(10**7), default=None, help="evaluations (default 20000; reproducible)")
    g.add_argument(
        "--time",
        type=capped_float(86_400.0),
        default=None,
        metavar="SECONDS",
        help="search while the clock allows: passes at the default budget, merged (not reproducible)",
    )
    p.add_argument("--seed", type=capped_int(2**31 - 1, low=0), default=0)
    w = p.add_mutually_exclusive_group()
    w.add_argument(
        "--workers",
        type=capped_int(MAX_WORKERS),
        default=None,
        help="local processes (default: the cores, at most 2; the designs are the same for any number)",
    )
    w.add_argument("--scheduler", default=None, metavar="ADDRESS", help="address of a dask.distributed scheduler")
    from gearlever.synthesis.curve.library import LIBRARY_SKETCHES, LIBRARY_TOPOLOGIES, MAX_LIBRARY_SIZE

    p.add_argument(
        "--library-size",
        type=capped_int(MAX_LIBRARY_SIZE),
        default=None,
        metavar="N",
        help=f"mechanisms of the retrieval library (default {LIBRARY_TOPOLOGIES * LIBRARY_SKETCHES}; read from the "
        "cache folder when gearlever curve library build stored it)",
    )
    p.add_argument("--library-seed", type=capped_int(2**31 - 1, low=0), default=0, metavar="S")
    p.add_argument("--report", default=None, metavar="R.json", help="write a JSON report")
    p.add_argument("--figure", default=None, metavar="F.png", help="write a figure (front, curves, best linkage)")
    p.set_defaults(func=_run, out_is_folder=True)


def _run(args) -> int:
    from pathlib import Path

    from gearlever._io import to_json as strict_json
    from gearlever._io import write_text_atomic
    from gearlever.synthesis.curve.model import linkage_toml
    from gearlever.synthesis.curve.search import synthesize_curve
    from gearlever.synthesis.curve.targets import read_target

    check_output_folder(args.out, "--out")
    _check_empty_folder(args.out)
    for flag, path in (("--report", args.report), ("--figure", args.figure)):
        if path is not None:
            check_output(path, flag)
    if args.figure is not None and not args.figure.lower().endswith(".png"):
        raise GearleverError(f"--figure must end with .png, got {args.figure!r}")
    if not 4 <= args.max_joints <= 20:
        raise GearleverError(f"--max-joints must be 4 to 20, got {args.max_joints}")
    if args.budget is not None and args.budget < 1000:
        raise GearleverError(f"--budget must be at least 1000 evaluations, got {args.budget}")
    if args.time is not None and args.time < 1.0:
        raise GearleverError(f"--time must be at least 1 second, got {args.time:g}")
    target = read_target(args.target, "TARGET")
    budget = None if args.time is not None else (args.budget or 20_000)
    bar = TerminalProgress("gearlever synthesize curve")
    try:
        res = synthesize_curve(
            target,
            max_joints=args.max_joints,
            designs=args.designs,
            budget=budget,
            time_limit=args.time,
            seed=args.seed,
            workers=args.workers,
            scheduler=args.scheduler,
            progress=bar,
            library_size=args.library_size,
            library_seed=args.library_seed,
            scoring=args.scoring,
        )
    except GearleverError as exc:
        from gearlever.cli._common import flagged

        raise flagged(
            exc,
            {
                "scheduler": "--scheduler",
                "budget": "--budget",
                "time_limit": "--time",
                "library_size": "--library-size",
                "library_seed": "--library-seed",
            },
        ) from None
    finally:
        bar.close()
    out = Path(args.out)
    names = []
    spent = f"budget {budget}" if budget is not None else f"time limit {args.time:g} s"
    for n, (lk, d, m) in enumerate(zip(res.designs, res.error, res.material), 1):
        name = f"{n:04d}"
        comment = (
            f"Synthesized by gearlever synthesize curve (seed {args.seed}, {spent}, {args.scoring} scoring); "
            f"distance {d:.6g}, material {m:.6g} (MIT 2.156 challenge definitions"
            + (
                f", material x {res.material_scale:.6g}: at the size of the challenge's targets)"
                if args.scoring == "relative"
                else ")"
            )
        )
        write_text_atomic(out / f"{name}.toml", linkage_toml(lk, comment), mkdir=True)
        write_text_atomic(out / f"{name}.links.json", strict_json(lk.as_dict(), indent=None) + "\n", mkdir=True)
        names.append(name)
    cols = {
        "design": names,
        "distance": res.error,
        "material": res.material,
        "joints": [lk.n_joints for lk in res.designs],
        "links": [len(lk.edges) for lk in res.designs],
    }
    write_text_atomic(out / "pareto.csv", table_text(cols) + "\n", mkdir=True)
    rep = res.summary()
    rep["seconds"] = round(float(res.seconds), 2)
    rep["budget"] = budget
    rep["time_limit"] = args.time
    rep["out"] = str(out)
    if args.report is not None:
        emit(to_json(rep), args.report, "--report")
    if args.figure is not None:
        from gearlever.plotting._common import save
        from gearlever.plotting.curves import curve_synthesis_plot

        fig = curve_synthesis_plot(res, target)
        save(fig, args.figure)
    best = f"best distance {res.error[0]:.4g}, least material {res.material.min():.4g}" if names else "none"
    emit(f"{len(names)} designs on the front (hypervolume {res.hypervolume:.4f}; {best}) in {out}")
    if not names:
        import sys

        hint = ", or --scoring relative for a curve not at the challenge's size"
        print(
            "gearlever synthesize curve: warning: no design on the front: none is within distance 0.75 and "
            f"material 10 ({args.scoring} scoring); try a larger --budget or --time"
            + (hint if args.scoring == "challenge" else ""),
            file=sys.stderr,
        )
    return 0


def _check_empty_folder(folder) -> None:
    """Refuse an existing ``--out`` folder that holds anything (the designs would mix with its files)."""
    import os

    if os.path.isdir(folder):
        with os.scandir(folder) as it:
            first = next(it, None)
        if first is not None:
            raise GearleverError(
                f"--out {str(folder)!r}: the folder is not empty (holds {first.name!r}); give a new or an empty folder"
            )
