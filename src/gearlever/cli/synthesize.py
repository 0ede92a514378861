"""``gearlever synthesize function|motion|path``: dimensional synthesis of linkages, written as model files.

``function``: a four-bar (crank angle -> rocker angle) or slider-crank (crank
angle -> slider travel) through target pairs from a CSV file, or through
precision points of a formula.  ``motion``: a four-bar whose coupler passes
through 3, 4 or 5 poses (x, y, angle).  ``--out`` is a model file that
``gearlever mechanism analyze`` opens directly, assembled at the first
target; ``--report`` strict JSON; ``--figure`` a PNG.  Caps: at most
:data:`~gearlever.synthesis.function.MAX_TARGETS` targets or points, 5 poses,
formulas of 500 characters.

``path``: a four-bar, geared five-bar or six-bar whose coupler point passes
through target points, with or without timing, searched on dask
(:mod:`gearlever.cli._synthesize_path`).
"""

from __future__ import annotations

import math
import sys
import time
import warnings

from gearlever._format import DIGITS_DESIGN, below, rounded
from gearlever.cli._common import (
    FIGURE_SUFFIXES,
    capped_float,
    capped_int,
    check_output,
    check_output_folder,
    commit_outputs,
    emit,
    finite_float,
    flagged,
    to_json,
)
from gearlever.errors import GearleverError, GearleverWarning

MAX_ROWS = 10_000

_FLAGS = {
    "x_range": "--x-range",
    "input_range": "--input-range",
    "output_range": "--output-range",
    "points": "--points",
    "spacing": "--spacing",
    "fixed_pivots": "--fixed-pivots",
    "moving_pivots": "--moving-pivots",
    "ground_pivot": "--fixed-pivots",
    "moving_pivot": "--moving-pivots",
    "ground": "--ground",
    "expression": "--expr",
}


def register(sub) -> None:
    p = sub.add_parser(
        "synthesize", help="dimensional synthesis: function, motion and path generation, written as models"
    )
    ss = p.add_subparsers(dest="synth_command", metavar="KIND")
    ss.required = True

    f = ss.add_parser("function", help="a four-bar or slider-crank whose output follows a function of its input")
    f.add_argument("pairs", nargs="?", help="CSV of targets: input_deg,output_deg (slider-crank: input_deg,output)")
    f.add_argument("--expr", help='formula y = f(x), e.g. "log10(x)" (numbers, x, + - * / **, sin cos exp log ...)')
    f.add_argument("--x-range", nargs=2, type=finite_float, metavar=("A", "B"), help="x from, to")
    f.add_argument(
        "--input-range", nargs=2, type=finite_float, metavar=("DEG", "DEG"), help="crank angle at x from, to"
    )
    f.add_argument(
        "--output-range",
        nargs=2,
        type=finite_float,
        metavar=("OUT", "OUT"),
        help="output at f(x from), f(x to): rocker angle (deg) or slider travel (length)",
    )
    f.add_argument("--points", type=capped_int(MAX_ROWS), default=3, help="precision points (default 3: exact)")
    f.add_argument("--spacing", choices=("chebyshev", "even"), default="chebyshev")
    from gearlever.synthesis.registry import names as kind_names  # --type: the registered function kinds

    f.add_argument("--type", choices=kind_names("function"), default="fourbar", dest="kind")
    f.add_argument(
        "--ground", type=capped_float(1e12), default=1.0, help="four-bar ground link length (scale; default 1)"
    )
    f.add_argument("--out", required=True, help="model file (TOML) to write")
    f.add_argument("--report", help="JSON report to write")
    f.add_argument("--figure", help="figure to write (.png, .svg or .pdf)")
    f.set_defaults(func=_function)

    m = ss.add_parser("motion", help="a four-bar whose coupler passes through 3, 4 or 5 poses")
    m.add_argument("poses", help="CSV of poses: x,y,angle_deg (coupler point and coupler angle)")
    g = m.add_mutually_exclusive_group()
    g.add_argument(
        "--fixed-pivots", nargs=4, type=finite_float, metavar=("X2", "Y2", "X4", "Y4"), help="3 poses: O2, O4"
    )
    g.add_argument(
        "--moving-pivots", nargs=4, type=finite_float, metavar=("XA", "YA", "XB", "YB"), help="3 poses: A, B"
    )
    m.add_argument("--out", required=True, help="model file (TOML) of the best four-bar")
    m.add_argument(
        "--all", metavar="DIR", help="write every ranked solution here (solution_01.toml, ...; created if missing)"
    )
    m.add_argument("--report", help="JSON report to write")
    m.add_argument("--figure", help="figure to write (.png, .svg or .pdf)")
    m.set_defaults(func=_motion)
    from gearlever.cli._synthesize_path import register_path

    register_path(ss)
    from gearlever.cli.synthesize_law import register_law

    register_law(ss)

    from gearlever.cli._synthesize_curve import register_curve

    register_curve(ss)


def _read_csv(path: str, flag: str, columns: tuple) -> dict:
    """Numeric columns of a CSV file (header row), every error naming the file, row and column."""
    from gearlever._io import read_csv_table

    table = read_csv_table(path, flag, columns=columns, max_rows=MAX_ROWS)
    return table.columns(columns)


def _check_outputs(args) -> None:
    """Every output declared before any work: refused if unwritable, of the wrong suffix, or one file twice."""
    check_output(args.out, "--out")
    check_output(args.report, "--report")
    check_output(args.figure, "--figure", FIGURE_SUFFIXES)
    if getattr(args, "all", None):
        check_output_folder(args.all, "--all", create=True)


def _function(args) -> int:
    from gearlever.mechanism.modelfile import model_toml
    from gearlever.synthesis.report import angle_offsets, function_summary

    _check_outputs(args)
    t0 = time.perf_counter()
    slider = args.kind == "slider-crank"
    res, targets = _function_result(args, slider)
    offsets = angle_offsets(res)
    note = res.proportions()
    warn = f"{note}; {_scale_hint(res, args)}" if note else None
    rep = function_summary(
        res,
        expression=args.expr,
        x=None if targets is None else targets.x,
        warnings=[warn] if warn else [],
        time_s=time.perf_counter() - t0,
    )
    lines = _function_lines(args, res, rep, offsets, slider)
    figure = None
    if args.figure:
        from gearlever.plotting.synthesis import function_figure

        figure = function_figure(res)
    # every output is ready: only now is anything staged (written all or none by commit_outputs)
    emit(model_toml(res.model, _function_comment(args, res, offsets)), args.out)
    if args.report:
        emit(to_json(rep), args.report, "--report")
    if figure is not None:
        from gearlever.plotting._common import save

        save(figure, args.figure)
    commit_outputs()  # the summary names the files written: they are there first
    if warn:
        print(f"gearlever synthesize function: warning: {warn}", file=sys.stderr)
    print("\n".join(lines))
    return 0


def _function_targets(args, slider: bool) -> tuple:
    """``(input angles, outputs, target function or None, FunctionTargets or None)`` from PAIRS.csv or --expr."""
    import numpy as np

    from gearlever.synthesis.function import function_targets
    from gearlever.synthesis.report import check_pairs

    out_col = "output" if slider else "output_deg"
    formula = [args.expr, args.x_range, args.input_range, args.output_range]
    if args.pairs is not None:
        if any(v is not None for v in formula[1:]):
            raise GearleverError("--x-range/--input-range/--output-range go with --expr, not with PAIRS.csv")
        cols = _read_csv(args.pairs, "PAIRS", ("input_deg", out_col))
        check_pairs(cols["input_deg"], cols[out_col], slider=slider, where=f"PAIRS {args.pairs!r}")
        phi = np.radians(cols["input_deg"])
        out = np.asarray(cols[out_col]) if slider else np.radians(cols[out_col])
        return phi, out, None, None
    for flag, v in zip(("--x-range", "--input-range", "--output-range"), formula[1:]):
        if v is None:
            raise GearleverError(f"--expr needs {flag}")
    if args.points < 3:
        raise GearleverError(f"--points must be at least 3, got {args.points}")
    orange = args.output_range if slider else np.radians(args.output_range)
    targets = function_targets(args.expr, args.x_range, np.radians(args.input_range), orange, args.points, args.spacing)
    return targets.input_angle, targets.target, targets.target_at, targets


def _function_result(args, slider: bool) -> tuple:
    """``(FunctionSynthesis, FunctionTargets or None)`` of the command's targets; a defect is refused."""
    import numpy as np

    from gearlever.synthesis.function import synthesize_function

    if (args.pairs is None) == (args.expr is None):
        raise GearleverError("give either PAIRS.csv or --expr with --x-range, --input-range, --output-range")
    try:
        phi, out, target_at, targets = _function_targets(args, slider)
        with warnings.catch_warnings():
            # the library's warning is replaced by the line below, which names the flags
            warnings.filterwarnings("ignore", message="impractical proportions", category=GearleverWarning)
            res = synthesize_function(
                phi,
                out,
                kind=args.kind,
                ground=args.ground,
                target_at=target_at,
                input_range=None if targets is None else targets.input_range,
            )
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    if res.defect:
        raise GearleverError(f"synthesize function: refused, {res.defect}; change the ranges or the points")
    checked = np.concatenate([res.achieved, res.dense_achieved, [res.structural_error_max]])
    if not np.all(np.isfinite(checked)):  # the engine reached every row (no defect): a gap is a bug, never written
        raise GearleverError("synthesize function: refused, the engine left outputs undefined over the range")
    return res, targets


def _function_comment(args, res, offsets: dict) -> str:
    """The model file's header comment: the command, the targets' source and the crank angle of target 1."""
    phi0 = math.degrees(res.input_angle[0])
    return (
        f"gearlever synthesize function ({args.kind}): "
        + (f"y = {args.expr}" if args.expr else f"pairs from {args.pairs}")
        + f"; the crank angle of target 1 is {phi0:.10g} deg"
        + (f"; the model's crank angle is the input angle {offsets['crank']:+d} deg" if offsets["crank"] else "")
    )


def _function_lines(args, res, rep: dict, offsets: dict, slider: bool) -> list:
    """The summary printed on stdout, from the report ``rep`` (its rounded numbers)."""
    import numpy as np

    unit = "" if slider else "_deg"
    phi0 = math.degrees(res.input_angle[0])
    out_scale = float(np.ptp([float(v) if slider else math.degrees(v) for v in res.target])) or 1.0
    model_at = f"crank angle at target 1: {phi0:.10g} deg"
    if offsets["crank"]:
        model_at += f"; the model's crank angle there: {phi0 + offsets['crank']:.10g} deg"
    return [
        f"type             {args.kind} ({rep['objective']})",
        "lengths          " + ", ".join(f"{k} {rep['lengths'][k]:.10g}" for k in res.lengths),
        f"grashof          {res.grashof}; branch {res.branch}",
        f"target error     max {below(rep[f'max_target_error{unit}'], out_scale, fmt='.3g')}"
        + ("" if slider else " deg"),
        f"structural error max {rep[f'structural_error_max{unit}']:.6g}, rms {rep[f'structural_error_rms{unit}']:.6g}"
        f"{' deg' if not slider else ''} over {res.dense_input.size} crank angles (engine)",
        f"transmission     {rep['transmission_angle_deg'][0]:.4g} .. {rep['transmission_angle_deg'][1]:.4g} deg",
        f"model            {args.out} ({model_at})",
    ]


def _scale_hint(res, args) -> str:
    """What a designer can do about impractical proportions: other ranges, and the scale that sizes the linkage."""
    named = {k: abs(v) for k, v in res.lengths.items()}
    longest = max(named, key=named.get)
    if res.kind == "fourbar":
        size = f"--ground {args.ground / named[longest]:.4g} makes the {longest} 1 long"
    else:
        what = "--output-range" if args.expr else "the PAIRS outputs"
        size = f"{what} times {1 / named[longest]:.4g} makes the {longest} 1 long"
    return (
        "the ratios follow from the ranges, not from the scale: other --input-range/--output-range "
        f"(start angles and spans) give other proportions; to size this linkage, {size}"
    )


def _motion(args) -> int:
    import numpy as np

    from gearlever.mechanism.modelfile import model_toml
    from gearlever.synthesis.motion import MAX_POSES, burmester_curves, synthesize_motion

    _check_outputs(args)
    t0 = time.perf_counter()
    cols = _read_csv(args.poses, "POSES", ("x", "y", "angle_deg"))
    n = len(cols["x"])
    if n < 3:
        raise GearleverError(f"POSES {args.poses!r}: motion generation needs at least 3 poses, got {n}")
    if n > MAX_POSES:
        raise GearleverError(f"POSES {args.poses!r}: a four-bar is guided through at most {MAX_POSES} poses, got {n}")
    seen = {}
    for i, key in enumerate(zip(cols["x"], cols["y"], cols["angle_deg"])):
        if key in seen:
            raise GearleverError(f"POSES {args.poses!r} row {i + 2}: repeats row {seen[key] + 2}")
        seen[key] = i
    pts = np.column_stack([cols["x"], cols["y"]])
    ang = np.radians(cols["angle_deg"])
    if n == 3 and args.fixed_pivots is None and args.moving_pivots is None:
        raise GearleverError("POSES has 3 poses: give --fixed-pivots X2 Y2 X4 Y4 or --moving-pivots XA YA XB YB")
    if n > 3 and (args.fixed_pivots is not None or args.moving_pivots is not None):
        raise GearleverError(f"--fixed-pivots/--moving-pivots are for 3 poses; POSES has {n}")

    def two(v):
        return None if v is None else [(v[0], v[1]), (v[2], v[3])]

    try:
        res = synthesize_motion(pts, ang, fixed_pivots=two(args.fixed_pivots), moving_pivots=two(args.moving_pivots))
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    best = res.best
    if best.defect:
        raise GearleverError(f"synthesize motion: refused, every four-bar found has a defect (best: {best.defect})")
    elapsed = time.perf_counter() - t0
    emit(
        model_toml(best.model, f"gearlever synthesize motion ({res.method}) through the poses of {args.poses}"),
        args.out,
    )
    if args.all:
        from pathlib import Path

        for k, s in enumerate(res.solutions, start=1):
            emit(
                model_toml(s.model, f"rank {k}: {s.defect or 'no defect'}"),
                Path(args.all) / f"solution_{k:02d}.toml",
                "--all",
            )

    def sol_rec(k, s):
        return {
            "rank": k,
            "ground_pivots": [
                [rounded(float(v), DIGITS_DESIGN, s.size) for v in p]
                for p in (s.crank.ground_pivot, s.rocker.ground_pivot)
            ],
            "moving_pivots": [
                [rounded(float(v), DIGITS_DESIGN, s.size) for v in p]
                for p in (s.crank.moving_pivot, s.rocker.moving_pivot)
            ],
            "lengths": {k2: rounded(float(v), DIGITS_DESIGN, s.size) for k2, v in s.lengths.items()},
            "grashof": s.grashof,
            "crank_turns": s.crank_turns,
            "input_deg": [rounded(float(math.degrees(q)), DIGITS_DESIGN) for q in s.input_angle],
            "point_error": [rounded(float(e), DIGITS_DESIGN, s.size) for e in s.point_error],
            "angle_error_deg": [rounded(float(math.degrees(e)), DIGITS_DESIGN, 360.0) for e in s.angle_error],
            "residual_relative": rounded(float(s.residual), DIGITS_DESIGN, 1.0),
            "transmission_angle_deg": [
                rounded(float(math.degrees(s.transmission_range[0])), 6),
                rounded(float(math.degrees(s.transmission_range[1])), 6),
            ],
            "defect": s.defect or None,
        }

    rep = {
        "objective": f"exact rigid-body guidance through {n} poses ({res.method})",
        "poses": n,
        "dyads_found": len(res.dyads),
        "solutions": [sol_rec(k, s) for k, s in enumerate(res.solutions, start=1)],
        "evaluations": res.evaluations,
        "time_s": round(elapsed, 2),
    }
    if args.report:
        emit(to_json(rep), args.report, "--report")
    if args.figure:
        from gearlever.mechanism import Mechanism
        from gearlever.plotting._common import save
        from gearlever.plotting.synthesis import motion_figure

        q0 = best.input_angle[0]
        span = best.input_angle[-1] - q0
        sweep = q0 + np.linspace(0.0, 2 * np.pi if best.crank_turns else span, 361)
        path = Mechanism.from_dict(best.model).solve(sweep[:, None]).point["P"]
        curves = burmester_curves(pts, ang) if n == 4 else None
        save(motion_figure(res, curves, path), args.figure)
    b = rep["solutions"][0]
    lines = [
        f"method           {res.method}: {len(res.dyads)} dyad(s), {len(res.solutions)} four-bar(s) ranked",
        f"ground pivots    O2 ({b['ground_pivots'][0][0]:.10g}, {b['ground_pivots'][0][1]:.10g}), "
        f"O4 ({b['ground_pivots'][1][0]:.10g}, {b['ground_pivots'][1][1]:.10g})",
        f"moving pivots    A ({b['moving_pivots'][0][0]:.10g}, {b['moving_pivots'][0][1]:.10g}), "
        f"B ({b['moving_pivots'][1][0]:.10g}, {b['moving_pivots'][1][1]:.10g})",
        "lengths          " + ", ".join(f"{k} {v:.10g}" for k, v in b["lengths"].items()),
        f"grashof          {best.grashof}; crank turns fully: {'yes' if best.crank_turns else 'no'}",
        f"residual         {below(b['residual_relative'], 1.0, fmt='.3g')} of the size (engine, at every pose)",
        f"transmission     {b['transmission_angle_deg'][0]:.4g} .. {b['transmission_angle_deg'][1]:.4g} deg",
        "input at poses   " + ", ".join(f"{v:.8g}" for v in b["input_deg"]) + " deg",
        f"model            {args.out}",
    ]
    commit_outputs()  # the summary names the files written: they are there first
    print("\n".join(lines))
    return 0
