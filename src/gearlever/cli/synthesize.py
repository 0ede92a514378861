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

import csv
import io
import math
import sys
import time
import warnings

from gearlever._format import DIGITS_DESIGN, decade_unit, quantize
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
    from gearlever._io import read_text_capped

    text = read_text_capped(path, flag)
    reader = csv.DictReader(io.StringIO(text))
    header = [h.strip() for h in (reader.fieldnames or [])]
    missing = [c for c in columns if c not in header]
    if missing:
        raise GearleverError(f"{flag} {path!r}: missing column(s) {', '.join(missing)} (header: {','.join(header)})")
    reader.fieldnames = header
    out = {c: [] for c in columns}
    for i, row in enumerate(reader, start=2):
        if i - 1 > MAX_ROWS:
            raise GearleverError(f"{flag} {path!r}: more than {MAX_ROWS} rows")
        for c in columns:
            cell = (row.get(c) or "").strip()
            try:
                v = float(cell)
            except ValueError:
                raise GearleverError(f"{flag} {path!r} row {i} column {c}: not a number ({cell!r})") from None
            if not math.isfinite(v):
                raise GearleverError(f"{flag} {path!r} row {i} column {c}: must be finite, got {cell!r}")
            out[c].append(v)
    return out


def _check_outputs(args) -> None:
    """Every output declared before any work: refused if unwritable, of the wrong suffix, or one file twice."""
    check_output(args.out, "--out")
    check_output(args.report, "--report")
    check_output(args.figure, "--figure", FIGURE_SUFFIXES)
    if getattr(args, "all", None):
        check_output_folder(args.all, "--all", create=True)


def _r(v, digits=DIGITS_DESIGN, scale=0.0):
    """``v`` at ``digits`` of ``scale`` (of itself when 0): :func:`gearlever._format.quantize`, None for NaN."""
    if v is None or not math.isfinite(float(v)):
        return None
    return quantize(float(v), scale, digits)


def _bound(v: float, scale: float) -> str:
    """A quantized error as printed: ``below 1e-10`` of ``scale`` when it is zero at :data:`DIGITS_DESIGN`."""
    if v == 0:
        return f"below {decade_unit(scale, DIGITS_DESIGN):g}"
    return f"{v:.3g}"


def _function(args) -> int:
    import numpy as np

    from gearlever.synthesis.function import MAX_ANGLE, MAX_LENGTH, function_targets, synthesize_function
    from gearlever.synthesis.model import model_toml

    _MAX_PAIR_DEG = round(math.degrees(MAX_ANGLE), -3)  # 57000 deg, within the library's cap

    _check_outputs(args)
    t0 = time.perf_counter()
    slider = args.kind == "slider-crank"
    out_col = "output" if slider else "output_deg"
    formula = [args.expr, args.x_range, args.input_range, args.output_range]
    if (args.pairs is None) == (args.expr is None):
        raise GearleverError("give either PAIRS.csv or --expr with --x-range, --input-range, --output-range")
    try:
        if args.pairs is not None:
            if any(v is not None for v in formula[1:]):
                raise GearleverError("--x-range/--input-range/--output-range go with --expr, not with PAIRS.csv")
            cols = _read_csv(args.pairs, "PAIRS", ("input_deg", out_col))
            phi = np.radians(cols["input_deg"])
            out = np.asarray(cols[out_col]) if slider else np.radians(cols[out_col])
            if phi.size < 3:
                raise GearleverError(
                    f"PAIRS {args.pairs!r}: function generation needs at least 3 targets, got {phi.size}"
                )
            caps = (("input_deg", _MAX_PAIR_DEG), (out_col, MAX_LENGTH if slider else _MAX_PAIR_DEG))
            for col, cap in caps:
                big = [(i, v) for i, v in enumerate(cols[col]) if abs(v) > cap]
                if big:
                    i, v = big[0]
                    raise GearleverError(
                        f"PAIRS {args.pairs!r} row {i + 2} column {col}: must be at most {cap:g} in size, got {v:g}"
                    )
            if max(cols["input_deg"]) - min(cols["input_deg"]) >= 360:
                raise GearleverError(
                    f"PAIRS {args.pairs!r} column input_deg: the targets span "
                    f"{max(cols['input_deg']) - min(cols['input_deg']):g} deg; a crank is back in the same pose "
                    "after a full turn, so they must span less than 360 deg"
                )
            seen = {}
            for i, v in enumerate(cols["input_deg"]):
                if v in seen:
                    raise GearleverError(
                        f"PAIRS {args.pairs!r} row {i + 2} column input_deg: repeats row {seen[v] + 2} ({v!r})"
                    )
                seen[v] = i
            desired, targets = None, None
        else:
            for flag, v in zip(("--x-range", "--input-range", "--output-range"), formula[1:]):
                if v is None:
                    raise GearleverError(f"--expr needs {flag}")
            if args.points < 3:
                raise GearleverError(f"--points must be at least 3, got {args.points}")
            orange = args.output_range if slider else np.radians(args.output_range)
            targets = function_targets(
                args.expr, args.x_range, np.radians(args.input_range), orange, args.points, args.spacing
            )
            phi, out, desired = targets.input_angle, targets.output, targets.desired
        with warnings.catch_warnings():
            # the library's warning is replaced by the line below, which names the flags
            warnings.filterwarnings("ignore", message="impractical proportions", category=GearleverWarning)
            res = synthesize_function(
                phi,
                out,
                kind=args.kind,
                ground=args.ground,
                desired=desired,
                input_range=None if targets is None else targets.input_range,
            )
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    if res.defect:
        raise GearleverError(f"synthesize function: refused, {res.defect}; change the ranges or the points")
    checked = np.concatenate([res.generated, res.dense_generated, [res.structural_error_max]])
    if not np.all(np.isfinite(checked)):  # the engine reached every row (no defect): a gap is a bug, never written
        raise GearleverError("synthesize function: refused, the engine left outputs undefined over the range")
    conv = (lambda v: v) if slider else math.degrees
    unit = "" if slider else "_deg"
    offsets = _offsets(res)
    phi0 = math.degrees(res.input_angle[0])
    comment = (
        f"gearlever synthesize function ({args.kind}): "
        + (f"y = {args.expr}" if args.expr else f"pairs from {args.pairs}")
        + f"; the crank angle of target 1 is {phi0:.10g} deg"
        + (f"; the model's crank angle is the input angle {offsets['crank']:+d} deg" if offsets["crank"] else "")
    )
    note = res.proportions()
    warn = f"{note}; {_scale_hint(res, args)}" if note else None
    out_scale = float(np.ptp([conv(float(v)) for v in res.output])) or 1.0  # errors: at digits of the output range
    size = max(abs(v) for v in res.lengths.values())  # lengths: at digits of the largest
    rep = {
        "kind": args.kind,
        "objective": (
            "exact through 3 precision points"
            if res.exact
            else f"least squares of the design equation through {res.input_angle.size} targets"
        )
        + (" (Freudenstein's equation)" if not slider else " (slider-crank loop equation)"),
        "expression": args.expr,
        "lengths": {k: _r(v, scale=size) for k, v in res.lengths.items()},
        "link_ratio": _r(res.link_ratio, 6),
        "coefficients": [_r(k) for k in res.coefficients],
        "branch": res.branch,
        "grashof": res.grashof,
        "targets": [
            {
                "x": _r(targets.x[j]) if targets is not None else None,
                "input_deg": _r(math.degrees(res.input_angle[j])),
                "model_input_deg": _r(math.degrees(res.input_angle[j]) + offsets["crank"]),
                f"output{unit}": _r(conv(res.output[j])),
                f"generated{unit}": _r(conv(res.generated[j])),
                f"error{unit}": _r(conv(res.error[j]), scale=out_scale),
            }
            for j in range(res.input_angle.size)
        ],
        f"max_target_error{unit}": _r(conv(float(np.max(np.abs(res.error)))), scale=out_scale),
        f"structural_error_max{unit}": _r(conv(res.structural_error_max), 6),
        f"structural_error_rms{unit}": _r(conv(res.structural_error_rms), 6),
        "structural_error_samples": int(res.dense_input.size),
        "transmission_angle_deg": [
            _r(math.degrees(res.transmission_angle_min), 6),
            _r(math.degrees(res.transmission_angle_max), 6),
        ],
        "defect": res.defect or None,
        "model_angle_offsets_deg": offsets,
        "warnings": [warn] if warn else [],
        "evaluations": res.evaluations,
        "time_s": round(time.perf_counter() - t0, 2),
    }
    L = res.lengths
    model_at = f"crank angle at target 1: {phi0:.10g} deg"
    if offsets["crank"]:
        model_at += f"; the model's crank angle there: {phi0 + offsets['crank']:.10g} deg"
    lines = [
        f"type             {args.kind} ({rep['objective']})",
        "lengths          " + ", ".join(f"{k} {_r(v, scale=size):.10g}" for k, v in L.items()),
        f"grashof          {res.grashof}; branch {res.branch}",
        f"target error     max {_bound(rep[f'max_target_error{unit}'], out_scale)}{' deg' if not slider else ''}",
        f"structural error max {rep[f'structural_error_max{unit}']:.6g}, rms {rep[f'structural_error_rms{unit}']:.6g}"
        f"{' deg' if not slider else ''} over {res.dense_input.size} crank angles (engine)",
        f"transmission     {rep['transmission_angle_deg'][0]:.4g} .. {rep['transmission_angle_deg'][1]:.4g} deg",
        f"model            {args.out} ({model_at})",
    ]
    figure = None
    if args.figure:
        from gearlever.plotting.synthesis import function_figure

        figure = function_figure(res)
    # every output is ready: only now is anything staged (written all or none by commit_outputs)
    emit(model_toml(res.model, comment), args.out)
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


def _offsets(res) -> dict:
    """The model's crank input minus the design's input angle (a multiple of 180 deg: reversed, whole turns);
    the model's rocker angle minus the output angle (0 or 180 deg)."""
    out = {"crank": round(math.degrees(res.input_offset))}
    if res.kind == "fourbar":
        out["rocker"] = round(math.degrees(res.output_offset)) % 360
    return out


def _motion(args) -> int:
    import numpy as np

    from gearlever.synthesis.model import model_toml
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
            "ground_pivots": [[_r(v, scale=s.size) for v in p] for p in (s.crank.ground_pivot, s.rocker.ground_pivot)],
            "moving_pivots": [[_r(v, scale=s.size) for v in p] for p in (s.crank.moving_pivot, s.rocker.moving_pivot)],
            "lengths": {k2: _r(v, scale=s.size) for k2, v in s.lengths.items()},
            "grashof": s.grashof,
            "crank_turns": s.crank_turns,
            "input_deg": [_r(math.degrees(q)) for q in s.input_angle],
            "point_error": [_r(e, scale=s.size) for e in s.point_error],
            "angle_error_deg": [_r(math.degrees(e), scale=360.0) for e in s.angle_error],
            "residual_relative": _r(s.residual, scale=1.0),
            "transmission_angle_deg": [
                _r(math.degrees(s.transmission_angle_min), 6),
                _r(math.degrees(s.transmission_angle_max), 6),
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
        f"residual         {_bound(b['residual_relative'], 1.0)} of the size (engine, at every pose)",
        f"transmission     {b['transmission_angle_deg'][0]:.4g} .. {b['transmission_angle_deg'][1]:.4g} deg",
        "input at poses   " + ", ".join(f"{v:.8g}" for v in b["input_deg"]) + " deg",
        f"model            {args.out}",
    ]
    commit_outputs()  # the summary names the files written: they are there first
    print("\n".join(lines))
    return 0
