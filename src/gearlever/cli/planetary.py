"""``gearlever planetary design --ratio R --planets N [--kind simple|compound] ...``.

Exhaustive search of planetary tooth sets (see
:func:`gearlever.gears.planetary.design_planetary`): every set with the least
ratio error, the assembly conditions each meets, and the number of candidate
sets examined.  Bad input (an empty tooth range, N < 2, a range above the cap,
equal roles): exit 2, one line.
"""

from __future__ import annotations

from gearlever.cli._common import emit, flagged, positive_int, to_json

#: Most solutions --limit may ask for.
MAX_LIMIT = 100_000


def _limit(text: str) -> int:
    import argparse

    value = positive_int(text)
    if value > MAX_LIMIT:
        raise argparse.ArgumentTypeError(f"must be at most {MAX_LIMIT}, got {text!r}")
    return value


def register(sub) -> None:
    from gearlever.cli import OneLineParser

    p = sub.add_parser("planetary", help="planetary gear sets: exact ratios and an exhaustive tooth search")
    inner = p.add_subparsers(dest="planetary_command", metavar="ACTION", parser_class=OneLineParser)
    inner.required = True
    d = inner.add_parser("design", help="every tooth set with the least ratio error (exact)")
    d.add_argument("--ratio", required=True, metavar="R", help="target input/output speed ratio, e.g. 4.5 or 9/2")
    d.add_argument("--planets", required=True, type=int, metavar="N", help="number of equally spaced planets (>= 2)")
    d.add_argument("--kind", choices=("simple", "compound"), default="simple")
    d.add_argument("--fixed", choices=("ring", "sun", "carrier"), default="ring")
    d.add_argument("--input", choices=("sun", "ring", "carrier"), default="sun")
    d.add_argument("--output", choices=("sun", "ring", "carrier"), default=None, help="default: the third member")
    d.add_argument("--min-teeth", type=int, default=12, metavar="A", help="least tooth number of every gear")
    d.add_argument(
        "--max-teeth",
        type=int,
        default=150,
        metavar="B",
        help="greatest tooth number of every gear, the ring included (cap: 2000 simple, 300 compound)",
    )
    d.add_argument("--limit", type=_limit, default=20, metavar="K", help="print at most K solutions (default 20)")
    d.add_argument("--format", choices=("table", "json"), default="table")
    d.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")
    d.set_defaults(func=_run)


_FLAGS = {"max_teeth": "--max-teeth", "min_teeth": "--min-teeth", "planets": "--planets", "ratio": "--ratio"}


def _run(args) -> int:
    from gearlever.errors import GearleverError
    from gearlever.gears.planetary import design_planetary

    try:
        res = design_planetary(
            args.ratio,
            args.planets,
            kind=args.kind,
            fixed=args.fixed,
            input=args.input,
            output=args.output,
            min_teeth=args.min_teeth,
            max_teeth=args.max_teeth,
            limit=args.limit,
        )
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    if args.format == "json":
        out = {
            "solutions": [s.record() for s in res.solutions],
            "candidates": res.candidates,
            "feasible": res.feasible,
            "count": res.count,
            "target": f"{res.target.numerator}/{res.target.denominator}",
            "kind": res.kind,
            "planets": res.planets,
            "fixed": res.fixed,
            "input": res.input,
            "output": res.output,
            "ratio_range": [f"{r.numerator}/{r.denominator}" for r in res.ratio_range],
            "note": res.note,
        }
        emit(to_json(out), args.out)
        return 0
    lines = [
        f"{res.kind} planetary, {res.planets} planets, {res.fixed} fixed, {res.input} in, {res.output} out, "
        f"target ratio {res.target}, every gear {res.min_teeth}..{res.max_teeth} teeth",
        f"candidates {res.candidates} (coaxial sets), feasible {res.feasible} (equal spacing and clearance), "
        f"least error {float(res.solutions[0].error):.6g}: {res.count} set(s)"
        + (f", first {len(res.solutions)} shown" if len(res.solutions) < res.count else ""),
    ]
    if res.note:
        lines.append("note: " + res.note)
    for s in res.solutions:
        teeth = (
            f"sun {s.sun}, planet {s.planet}"
            if s.planet is not None
            else f"sun {s.sun}, planets {s.planet1}/{s.planet2}"
        )
        lines.append(
            f"{teeth}, ring {s.ring}: ratio {s.ratio} (error {float(s.error):.6g}); " + "; ".join(s.conditions)
        )
    emit("\n".join(lines), args.out)
    return 0
