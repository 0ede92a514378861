"""``gearlever synthesize path``: a four-bar whose coupler point passes through target points.

Registered on the ``synthesize`` sub-parsers by :func:`register_path`::

    gearlever synthesize path POINTS.csv --out MODEL.toml [--timing none|relative|absolute]
        [--pivot X Y] [--ground-angle DEG] [--length-range LO HI] [--coord-range LO HI]
        [--min-transmission DEG] [--type fourbar|geared-fivebar|sixbar|auto] [--seed N] [--budget EVALS]
        [--workers N | --scheduler ADDRESS] [--report R.json] [--figure F.png]

POINTS.csv holds ``x,y`` or ``x,y,input_deg`` per row (a header row naming
the columns is optional; ``#`` lines are skipped).  Timing defaults to
``relative`` when the ``input_deg`` column is present, else ``none``.

Constraints are exact (see :mod:`gearlever.synthesis.path`): every
candidate is a buildable Grashof crank-rocker with the crank the shortest
link, inside the ranges, reaching the targets counter-clockwise in order on
one assembly branch; with ``--min-transmission DEG`` the angle between
coupler and rocker also stays within ``[DEG, 180 - DEG]`` over the whole
turn (four-bars only).  A constraint set that admits no such linkage (a pivot
outside the coordinate range, an empty range, timing that is not
counter-clockwise within one turn) is refused with exit 2 naming the flag or
file element; nothing is written then.  ``--type geared-fivebar`` synthesizes
the geared five-bar of :mod:`gearlever.synthesis.fivebar` (a model with
``[gears]`` and ``[[meshes]]``); ``auto`` tries the four-bar, then the geared
five-bar and then the Stephenson six-bar (:mod:`gearlever.synthesis.sixbar`)
while the targets are not reached, and the report says which type was best
(``type``, ``types_tried``).
"""

from __future__ import annotations

import math

from gearlever._format import below
from gearlever._progress import TerminalProgress
from gearlever.cli._common import (
    capped_int,
    check_output,
    emit,
    finite_float,
    nonnegative_int,
    to_json,
)
from gearlever.errors import GearleverError

#: Most target rows read from POINTS.
MAX_TARGETS = 1000
#: Most dask threads (each holds one chunk of starts; more than the starts is pointless).
MAX_WORKERS = 256


def register_path(ss) -> None:
    """Add the ``path`` sub-command to the ``synthesize`` sub-parsers ``ss``."""
    from gearlever.synthesis.path import DEFAULT_BUDGET, KINDS, MAX_BUDGET, min_budget

    p = ss.add_parser(
        "path",
        help="four-bar whose coupler point passes through target points (path generation)",
        description="Dimensional synthesis for path generation: a Grashof crank-rocker whose coupler point "
        "passes through the target points in order as the crank turns counter-clockwise; global search "
        "(differential evolution, seeded starts on dask) then a least-squares polish. The model is written "
        "assembled at the first target.",
    )
    p.add_argument("points", metavar="POINTS.csv", help="targets: x,y[,input_deg] per row")
    p.add_argument("--out", required=True, help="model file to write (TOML, atomically)")
    p.add_argument(
        "--timing",
        choices=("none", "relative", "absolute"),
        default=None,
        help="none; relative (input_deg increments, start free; default with input_deg); "
        "absolute (crank angles from the ground line)",
    )
    p.add_argument("--pivot", nargs=2, type=finite_float, metavar=("X", "Y"), help="fixed crank pivot O2")
    p.add_argument("--ground-angle", type=finite_float, metavar="DEG", help="fixed ground line angle O2->O4")
    p.add_argument(
        "--length-range",
        nargs=2,
        type=finite_float,
        metavar=("LO", "HI"),
        help="bounds of link lengths (LO 0: any positive length)",
    )
    p.add_argument(
        "--coord-range",
        nargs=2,
        type=finite_float,
        metavar=("LO", "HI"),
        help="bounds of pivot and coupler-point coordinates",
    )
    p.add_argument(
        "--min-transmission",
        type=finite_float,
        metavar="DEG",
        help="smallest transmission angle allowed over the turn, 0..90 (four-bar only; default: no bound)",
    )
    p.add_argument("--type", dest="kind", choices=KINDS, default="fourbar")  # the registered kinds and "auto"
    p.add_argument("--seed", type=nonnegative_int, default=0, help="fixes the result (default 0)")
    p.add_argument(
        "--budget",
        type=capped_int(MAX_BUDGET),
        default=DEFAULT_BUDGET,
        help=f"candidate evaluations of the search, a cap (default {DEFAULT_BUDGET}, at least "
        f"{min_budget(10)} for a four-bar, at most {MAX_BUDGET:.0e})",
    )
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=capped_int(MAX_WORKERS), default=None, help="local dask threads")
    g.add_argument("--scheduler", default=None, metavar="ADDRESS", help="address of a dask.distributed scheduler")
    p.add_argument("--report", default=None, metavar="R.json", help="write a JSON report")
    p.add_argument("--figure", default=None, metavar="F.png", help="write a figure (targets, curve, linkage)")
    p.set_defaults(func=_run)


def read_targets(path: str):
    """Targets (N, 2) and input angles in degrees (N,) or None from a CSV file (the CLI's reader).

    Every refusal names the file and its line: a value that is not a finite
    number or is beyond :data:`gearlever.synthesis.path_fourbar.MAX_TARGET_COORDINATE`,
    a row with more values than the columns (a header of ``x,y`` and a row
    ``0,0,7`` would silently lose the 7), input angles that do not increase,
    and, without input angles, a target equal to the one before it (the
    closing repeat of the first target as the last is the closed-path form).
    """
    import numpy as np

    from gearlever._io import read_csv_table
    from gearlever.synthesis.path_fourbar import MAX_TARGET_COORDINATE

    table = read_csv_table(path, "POINTS", header=None, comments=True)
    where = table.where
    if not table.rows and not table.header:
        raise GearleverError(f"{where}: no target rows")
    names = ["x", "y", "input_deg"]
    table = table.only(names, 2)  # the package's one rule for a user's CSV
    header, rows, lines = table.header, table.rows, table.lines
    cols = [header.index(n) if n in header else None for n in names]
    if len(rows) > MAX_TARGETS:
        raise GearleverError(f"{where}: at most {MAX_TARGETS} target rows, got {len(rows)}")
    xy, ang = [], []
    for r, line in zip(rows, lines):
        at = f"{where} line {line}"
        vals = []
        for name, c in zip(names, cols):
            if c is None:
                vals.append(None)
                continue
            if c >= len(r) or not r[c].strip():
                raise GearleverError(f"{at}: column {name} is missing")
            try:
                v = float(r[c])
            except ValueError:
                raise GearleverError(f"{at}: {name} must be a number, got {r[c]!r}") from None
            if not math.isfinite(v):
                raise GearleverError(f"{at}: {name} must be finite, got {r[c]!r}")
            if name != "input_deg" and abs(v) > MAX_TARGET_COORDINATE:
                raise GearleverError(
                    f"{at}: {name} must be at most {MAX_TARGET_COORDINATE:g} in size (the model's coordinates "
                    f"stay within 1e+12), got {r[c]!r}"
                )
            vals.append(v)
        if ang and vals[2] is not None and not vals[2] > ang[-1]:
            raise GearleverError(
                f"{at}: input_deg {vals[2]:g} must be greater than {ang[-1]:g} on the line before "
                "(the crank turns counter-clockwise through the targets in order)"
            )
        if xy and vals[2] is None and vals[:2] == xy[-1]:
            raise GearleverError(
                f"{at}: the target ({vals[0]:g}, {vals[1]:g}) repeats the one before it; without input_deg "
                "two targets in a row at one place are one target (give input_deg to pass a point twice)"
            )
        xy.append(vals[:2])
        ang.append(vals[2])
    if len(xy) < 2:
        raise GearleverError(f"{where}: at least 2 target rows are needed, got {len(xy)}")
    angles = None if cols[2] is None else np.array(ang, dtype=float)
    return np.array(xy, dtype=float), angles


def _run(args) -> int:
    import numpy as np

    from gearlever.mechanism.modelfile import model_toml
    from gearlever.synthesis.path import synthesize_path

    check_output(args.report, "--report")
    check_output(args.figure, "--figure", ("png",))
    targets, angles = read_targets(args.points)
    timing = args.timing or ("relative" if angles is not None else "none")
    if timing != "none" and angles is None:
        raise GearleverError(f"--timing {timing}: POINTS {args.points!r} has no input_deg column")
    if args.length_range is not None and not 0 <= args.length_range[0] < args.length_range[1]:
        lo, hi = args.length_range
        raise GearleverError(f"--length-range must be 0 <= LO < HI (LO 0: any positive length), got {lo:g} {hi:g}")
    if args.coord_range is not None and not args.coord_range[0] < args.coord_range[1]:
        raise GearleverError(f"--coord-range must be LO < HI, got {args.coord_range[0]:g} {args.coord_range[1]:g}")
    if args.min_transmission is not None and not 0 <= args.min_transmission < 90:
        raise GearleverError(f"--min-transmission must be 0 <= DEG < 90, got {args.min_transmission:g}")
    if args.min_transmission is not None and args.kind != "fourbar":
        raise GearleverError(f"--min-transmission bounds a four-bar's transmission angle: not with --type {args.kind}")
    flags = {
        "pivot": "--pivot",
        "ground_angle": "--ground-angle",
        "length_range": "--length-range",
        "coord_range": "--coord-range",
        "angles": "POINTS input_deg",
        "targets": "POINTS",
        "scheduler": "--scheduler",
        "budget": "--budget",
        "kind": "--type",
        "min_transmission": "--min-transmission",
    }
    bar = TerminalProgress("gearlever synthesize path")
    try:
        res = synthesize_path(
            targets,
            None if angles is None or timing == "none" else np.radians(angles),
            timing=timing,
            pivot=args.pivot,
            ground_angle=None if args.ground_angle is None else math.radians(args.ground_angle),
            length_range=args.length_range,
            coord_range=args.coord_range,
            kind=args.kind,
            seed=args.seed,
            budget=args.budget,
            workers=args.workers,
            scheduler=args.scheduler,
            progress=bar,
            min_transmission=None if args.min_transmission is None else math.radians(args.min_transmission),
        )
    except GearleverError as exc:
        from gearlever.cli._common import flagged

        raise flagged(exc, flags) from None
    finally:
        bar.close()
    rep = res.summary()  # rounded by the digits rule
    S = float(np.hypot(*np.ptp(res.target, axis=0))) or 1.0
    rep["time_s"] = round(float(res.seconds), 2)
    if not res.feasible:  # a command writes all its files or none
        raise GearleverError("no buildable linkage meets the constraints: nothing was written")
    comment = (
        f"Synthesized by gearlever synthesize path ({res.kind}, seed {args.seed}, budget {args.budget}); "
        f"objective {below(rep['objective'], S * S)}; input at the first target {rep['input_deg'][0]:.10g} deg"
    )
    emit(model_toml(res.model(), comment), args.out)
    if args.report is not None:
        rep["model"] = args.out
        emit(to_json(rep), args.report, "--report")
    if args.figure is not None:
        from gearlever.plotting._common import save
        from gearlever.plotting.synthesis_path import path_synthesis_plot

        ax = path_synthesis_plot(res)
        save(ax.figure, args.figure)
    err = max(rep["per_target_error"]) if rep["per_target_error"] else math.nan
    tried = (
        ", ".join(f"{k} {below(v, S * S)}" for k, v in rep["types_tried"].items()) if rep["types_tried"] else res.kind
    )
    mu = rep["transmission_deg"]
    emit(
        "\n".join(
            [
                f"type             {res.kind} (tried: {tried})",
                f"objective        {below(rep['objective'], S * S)} (sum of squared distances to the targets)",
                f"target error     max {below(err, S)}",
                f"grashof          {rep['grashof']}; branch {rep['branch']}",
                f"transmission     {mu[0]:.4g} .. {mu[1]:.4g} deg",
                f"evaluations      {rep['evaluations']} (seed {rep['seed']})",
                f"model            {args.out} (input at target 1: {rep['input_deg'][0]:.10g} deg)",
            ]
        )
    )
    return 0
