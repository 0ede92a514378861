"""``gearlever synthesize law`` and ``gearlever mechanism law``: a mechanism for a law, and the law of a mechanism.

Registered on the ``synthesize`` sub-parsers by :func:`register_law`::

    gearlever synthesize law LAW.toml --type KIND|auto (the law kinds of gearlever.synthesis.kinds("law"))
        --out MODEL.toml [--report R.json] [--figure F.png] [--seed N] [--budget EVALS]
        [--workers N | --scheduler ADDRESS] [--min-transmission DEG] [--teeth ZMIN ZMAX]
        [--dwell-tolerance TOL]

and on the ``mechanism`` sub-parsers by :func:`register_mechanism_law`::

    gearlever mechanism law MODEL.toml --output LINK [--samples N] [--threshold F] [--format table|json]

The model is written sketched at law input 0, its crank turning
counter-clockwise as the law's input grows, its output link named
``output`` (:mod:`gearlever.synthesis.law`).  A law the kind cannot give (a
displacement law for a rocker, a net output rotation for a linkage that
returns every turn, a net rotation no whole teeth give) is refused with
exit 2 naming the LAW file; nothing is written then.  With ``--type
auto`` each kind that gave no design is listed with the reason.  A design
whose largest error exceeds 2 % of the law's range
(:data:`~gearlever.synthesis.law.measure.MISS_FRACTION`) is still written,
with a warning on stderr naming the error, the fraction and the time ratio
achieved against the one wanted.
"""

from __future__ import annotations

import math
import sys

from gearlever._format import rounded
from gearlever._progress import TerminalProgress
from gearlever.cli._common import (
    capped_int,
    check_output,
    emit,
    finite_float,
    flagged,
    nonnegative_int,
    to_json,
)
from gearlever.errors import GearleverError

#: Most dask threads.
MAX_WORKERS = 256
#: Largest tooth count accepted by --teeth.
MAX_TEETH = 1000


def register_law(ss) -> None:
    """Add the ``law`` sub-command to the ``synthesize`` sub-parsers ``ss``."""
    from gearlever.synthesis.law.driver import DEFAULT_BUDGET, MAX_BUDGET, MIN_TRANSMISSION_DEG
    from gearlever.synthesis.registry import names

    p = ss.add_parser(
        "law",
        help="a linkage or geared linkage whose output follows a motion law over the whole cycle",
        description="Law synthesis: a mechanism of the given type whose output link follows LAW.toml over a "
        "full turn of its crank (global search by differential evolution in seeded starts on dask, then a "
        "minimax polish; dwell samples weigh 4 times). The model is written sketched at law input 0.",
    )
    p.add_argument("law", metavar="LAW.toml", help="the motion law ([law] with [[law.segment]] or samples)")
    p.add_argument("--type", dest="kind", choices=(*names("law"), "auto"), required=True, help="mechanism type")
    p.add_argument("--out", required=True, help="model file to write (TOML, atomically)")
    p.add_argument("--report", default=None, metavar="R.json", help="write a JSON report")
    p.add_argument("--figure", default=None, metavar="F.png", help="write a figure (wanted and achieved law, error)")
    p.add_argument("--seed", type=nonnegative_int, default=0, help="fixes the result (default 0)")
    p.add_argument(
        "--budget",
        type=capped_int(MAX_BUDGET, low=100),
        default=DEFAULT_BUDGET,
        help=f"evaluations per type, searches and polishes together: a cap (default {DEFAULT_BUDGET}, "
        f"at most {MAX_BUDGET:.0e})",
    )
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=capped_int(MAX_WORKERS), default=None, help="local dask threads")
    g.add_argument("--scheduler", default=None, metavar="ADDRESS", help="address of a dask.distributed scheduler")
    p.add_argument(
        "--min-transmission",
        type=finite_float,
        default=MIN_TRANSMISSION_DEG,
        metavar="DEG",
        help=f"smallest transmission angle allowed over the turn, 0 <= DEG < 90 (default {MIN_TRANSMISSION_DEG:g})",
    )
    p.add_argument(
        "--teeth",
        nargs=2,
        type=capped_int(MAX_TEETH),
        default=(17, 120),
        metavar=("ZMIN", "ZMAX"),
        help="bounds of gear teeth (default 17 120)",
    )
    p.add_argument(
        "--dwell-tolerance",
        type=finite_float,
        default=None,
        metavar="TOL",
        help="largest excursion (peak to peak) of the output over each dwell, in the law's units (deg for an "
        "angle law): a constraint of the search",
    )
    p.set_defaults(func=_run)


def register_mechanism_law(ms) -> None:
    """Add the ``law`` sub-command to the ``mechanism`` sub-parsers ``ms``."""
    p = ms.add_parser(
        "law",
        help="the law an output link or slider follows over one input turn: dwells, rises, returns, peaks",
        description="Turn the model's input once counter-clockwise from its sketch and print the output's "
        "law: segments fitted (a dwell where the speed analogue is below --threshold of its peak), each with "
        "its rise, and the peak velocity and acceleration analogues.",
    )
    p.add_argument("model", help="model file (TOML) with one link input")
    p.add_argument("--output", required=True, metavar="LINK", help="the output link or slider")
    p.add_argument("--samples", type=capped_int(100_000, low=8), default=3600, help="input angles (default 3600)")
    p.add_argument(
        "--threshold",
        type=finite_float,
        default=None,
        metavar="F",
        help="dwell: |speed| below F times its peak (default 0.01)",
    )
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.set_defaults(func=_mechanism_law)


def _run(args) -> int:
    from gearlever.laws import load_law
    from gearlever.mechanism.modelfile import model_toml
    from gearlever.synthesis.law import synthesize_law
    from gearlever.synthesis.law.measure import cam_comparison, law_report

    check_output(args.out, "--out")
    for flag, path in (("--report", args.report), ("--figure", args.figure)):
        if path is not None:
            check_output(path, flag)
    if args.figure is not None and not args.figure.lower().endswith(".png"):
        raise GearleverError(f"--figure must end with .png, got {args.figure!r}")
    if not 0 <= args.min_transmission < 90:
        raise GearleverError(f"--min-transmission must be 0 <= DEG < 90, got {args.min_transmission:g}")
    if args.teeth[0] > args.teeth[1]:
        raise GearleverError(f"--teeth must be ZMIN <= ZMAX, got {args.teeth[0]} {args.teeth[1]}")
    if args.dwell_tolerance is not None and not args.dwell_tolerance > 0:
        raise GearleverError(f"--dwell-tolerance must be greater than 0, got {args.dwell_tolerance:g}")
    law = load_law(args.law)
    tol = args.dwell_tolerance
    if tol is not None and law.output == "angle":
        tol = math.radians(tol)
    flags = {
        "dwell_tolerance": "--dwell-tolerance",
        "scheduler": "--scheduler",
        "budget": "--budget",
        "kind": "--type",
        "min_transmission": "--min-transmission",
        "teeth": "--teeth",
    }
    bar = TerminalProgress("gearlever synthesize law")
    try:
        res = synthesize_law(
            law,
            kind=args.kind,
            seed=args.seed,
            budget=args.budget,
            workers=args.workers,
            scheduler=args.scheduler,
            min_transmission=math.radians(args.min_transmission),
            teeth=tuple(args.teeth),
            progress=bar,
            dwell_tolerance=tol,
        )
    except GearleverError as exc:
        text = str(exc)
        if text.startswith(("the law", "a ", "no kind", "dwell_tolerance bounds")):
            if text.startswith("dwell_tolerance"):
                text = "--dwell-tolerance" + text[len("dwell_tolerance") :]
            raise GearleverError(f"LAW {args.law!r}: {text}") from None
        raise flagged(exc, flags) from None
    finally:
        bar.close()
    rep = law_report(res)
    rep["law"] = args.law
    rep["time_s"] = round(float(res.seconds), 2)
    rep["cam"] = cam_comparison(law)
    rep = rounded(rep, 10)
    ang = law.output == "angle"
    unit = "_deg" if ang else ""
    comment = (
        f"Synthesized by gearlever synthesize law ({res.kind}, seed {args.seed}, budget {args.budget}) for "
        f"{args.law}; sketched at law input 0; max error {rep['error_max' + unit]:.6g}"
        + (" deg" if ang else f" {law.units}")
    )
    emit(model_toml(res.model(), comment), args.out)
    if args.report is not None:
        rep["model"] = args.out
        emit(to_json(rep), args.report, "--report")
    if args.figure is not None:
        from gearlever.plotting._common import save
        from gearlever.plotting.law_synthesis import law_synthesis_figure

        save(law_synthesis_figure(res), args.figure)
    u = " deg" if ang else f" {law.units}"
    tried = ", ".join(f"{k} {v:.4g}" for k, v in rep["types_tried"].items() if v is not None)
    lines = [
        f"type             {res.kind}" + (f" (tried, weighted max error: {tried})" if args.kind == "auto" else ""),
    ]
    if args.kind == "auto":
        lines += [f"not tried        {k}: {why}" for k, why in rep["types_not_tried"].items()]
        lines += [f"no design        {k}: {why}" for k, why in rep["types_without_design"].items()]
    lines.append(
        f"error            max {rep['error_max' + unit]:.4g}{u}, rms {rep['error_rms' + unit]:.4g}{u} "
        f"over {rep['samples']} input angles ({100 * rep['error_fraction_of_range']:.3g} % of the range "
        f"{rep['range' + unit]:.4g}{u})"
    )
    tr = rep["time_ratio"]
    if tr["wanted"] is not None:
        got = "none (the output does not both rise and return)" if tr["achieved"] is None else f"{tr['achieved']:.3g}"
        lines.append(
            f"time ratio       {got} (wanted {tr['wanted']:.3g}): rise over {tr['rise_deg']['achieved']:.4g} deg, "
            f"return over {tr['return_deg']['achieved']:.4g} deg of input"
        )
    if rep["dwell_excursion" + unit] is not None:
        bound = rep["dwell_tolerance" + unit]
        lines.append(
            f"dwell excursion  {rep['dwell_excursion' + unit]:.4g}{u} peak to peak"
            + ("" if bound is None else f" (at most {bound:.4g}{u})")
        )
    for s in rep["segments"]:
        extra = f", dwell excursion {s['dwell_excursion' + unit]:.4g}{u}" if "dwell_excursion" + unit in s else ""
        lines.append(
            f"segment {s['segment']:<8} {s['motion']} {s['from_deg']:.6g}..{s['to_deg']:.6g} deg: "
            f"error max {s['error_max' + unit]:.4g}{u}{extra}"
        )
    pv, pa = rep[f"peak_velocity{unit}_per_rad"], rep[f"peak_acceleration{unit}_per_rad2"]
    mu = rep["transmission_deg"]
    lines += [
        f"peak velocity    {pv['achieved']:.4g} (wanted {pv['wanted']:.4g}){u} per rad",
        f"peak accel.      {pa['achieved']:.4g} (wanted {pa['wanted']:.4g}){u} per rad^2",
        f"transmission     {mu[0]:.4g} .. {mu[1]:.4g} deg",
    ]
    cam = rep["cam"]
    if cam["available"]:
        pivot = f", pivot at {cam['pivot_distance']:.4g} (arm {cam['arm']:.4g})" if "pivot_distance" in cam else ""
        lines.append(
            f"cam ({cam['follower']}) base radius {cam['base_radius']:.4g}{pivot}, pressure angle max "
            f"{cam['pressure_angle_max_deg']:.4g} deg (transmission {cam['transmission_min_deg']:.4g} deg), exact"
        )
    teeth = res.details.get("teeth")
    if teeth:
        lines.append("teeth            " + ", ".join(f"{k} {v}" for k, v in teeth.items()))
    slide = rep["design"].get("slide_range")
    if slide:  # the gear-lever's adjusting slide: the law at other settings of the centre distance
        cells = [
            f"{r['centre_distance']:.4g}: " + (f"{r['error_max' + unit]:.3g}{u}" if r["feasible"] else "no assembly")
            for r in slide
        ]
        lines.append("slide (err max)  " + ", ".join(cells))
    lines += [
        f"evaluations      {rep['evaluations']} (budget {args.budget} per type; seed {args.seed}, "
        f"{rep['starts']} starts)",
        f"model            {args.out} (output link 'output')",
    ]
    emit("\n".join(lines))
    if rep["misses_law"]:
        tr = rep["time_ratio"]
        ratio = ""
        if tr["wanted"] is not None:
            got = "none" if tr["achieved"] is None else f"{tr['achieved']:.3g}"
            ratio = f"; time ratio {got} achieved, {tr['wanted']:.3g} wanted"
        print(
            f"gearlever synthesize law: warning: the best design ({res.kind}) misses the law by "
            f"{rep['error_max' + unit]:.4g}{u}, {100 * rep['error_fraction_of_range']:.3g} % of its range "
            f"{rep['range' + unit]:.4g}{u} (more than {100 * rep['miss_fraction_limit']:g} %){ratio}",
            file=sys.stderr,
        )
    return 0


def _mechanism_law(args) -> int:
    import numpy as np

    from gearlever.mechanism import Mechanism
    from gearlever.synthesis.law.measure import DWELL_THRESHOLD, fit_segments, mechanism_law

    thr = DWELL_THRESHOLD if args.threshold is None else args.threshold
    if not 0 < thr < 1:
        raise GearleverError(f"--threshold must be greater than 0 and less than 1, got {thr:g}")
    mech = Mechanism.load(args.model)
    try:
        ml = mechanism_law(mech, args.output, args.samples)
    except GearleverError as exc:
        raise flagged(exc, {"output": "--output", "samples": "--samples"}) from None
    if not ml.closed.all():
        bad = float(np.degrees(ml.theta[int(np.flatnonzero(~ml.closed)[0])]))
        raise GearleverError(
            f"{args.model}: the mechanism does not turn its input through a full turn from the sketch "
            f"(it stops at {bad:.6g} deg): no law over a cycle"
        )
    ang = ml.kind == "angle"
    conv = np.degrees if ang else (lambda x: x)
    u = " deg" if ang else ""
    segs = fit_segments(ml.theta, ml.s, ml.v, thr, net=ml.net)
    for g in segs:
        for key in ("rise", "excursion"):
            g[key] = float(conv(g[key]))
    rep = rounded(
        {
            "output": ml.output,
            "kind": ml.kind,
            "net_change" + ("_deg" if ang else ""): float(conv(ml.net)),
            "range" + ("_deg" if ang else ""): float(conv(np.ptp(ml.s))),
            "peak_velocity_per_rad" + ("_deg" if ang else ""): float(conv(np.max(np.abs(ml.v)))),
            "peak_acceleration_per_rad2" + ("_deg" if ang else ""): float(conv(np.max(np.abs(ml.a)))),
            "dwell_threshold": thr,
            "segments": segs,
            "samples": int(ml.theta.size),
        },
        8,
    )
    if args.format == "json":
        emit(to_json(rep))
        return 0
    k = "_deg" if ang else ""
    lines = [
        f"output           {ml.output} ({'rotation' if ang else 'travel'} over one ccw input turn from the sketch)",
        f"range            {rep['range' + k]:.6g}{u}; net change {rep['net_change' + k]:.6g}{u}",
        f"peak velocity    {rep['peak_velocity_per_rad' + k]:.6g}{u} per rad of input",
        f"peak accel.      {rep['peak_acceleration_per_rad2' + k]:.6g}{u} per rad^2",
        f"segments         {len(segs)} (dwell: |v| < {thr:g} of its peak)",
    ]
    for g in segs:
        lines.append(
            f"  {g['motion']:<7} {g['from_deg']:8.3f} .. {g['to_deg']:8.3f} deg  rise {g['rise']:+.6g}{u}"
            + (f"  excursion {g['excursion']:.3g}{u}" if g["motion"] == "dwell" else "")
        )
    emit("\n".join(lines))
    return 0
