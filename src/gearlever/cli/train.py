"""``gearlever train ratio|design|search``: trains of wheels.

Every size flag has a cap (refused above it, with the cap named): ``--pairs``
at most 12, ``--min-teeth``/``--max-teeth`` at most 10,000, ``--limit`` at
most 1,000 (``--all`` lists up to that cap), ``--keep`` at most 1,000,
``--max-space`` at most 20,000,000 tooth multisets per side.  Errors from
the library are reported with the user's flag names.
"""

from __future__ import annotations

from gearlever import trains  # the package face (its caps here; its functions are imported where called)
from gearlever._progress import TerminalProgress
from gearlever.cli._common import capped_int, emit, flagged, to_json
from gearlever.errors import GearleverError

#: Solutions listed by ``train search`` without ``--limit`` or ``--all``.
DEFAULT_LISTED = trains.DEFAULT_LIMIT
#: Tooth range of ``train search`` when not given: the text's least pinion for
#: epicycloidal teeth (12) to 60, the range of Sandgren's gear-train problem.
SEARCH_MIN_TEETH, SEARCH_MAX_TEETH = 12, 60

# Library parameter names -> the flags that set them.
_FLAGS = {
    "ratio": "--ratio",
    "pairs": "--pairs",
    "min_teeth": "--min-teeth",
    "max_teeth": "--max-teeth",
    "max_space": "--max-space",
    "limit": "--limit",
    "keep": "--keep",
    "prefer": "--prefer",
    "tooth_form": "--tooth-form",
    "metric": "--metric",
    "drivers": "--drivers",
    "followers": "--followers",
    "internal": "--internal",
    "idlers": "--idlers",
}


def register(sub) -> None:
    p = sub.add_parser("train", help="velocity ratio, rule-based design and exact best search of trains of wheels")
    tsub = p.add_subparsers(dest="train_command", metavar="ACTION")
    tsub.required = True

    r = tsub.add_parser("ratio", help="exact velocity ratio and sense of rotation of a train")
    r.add_argument("--drivers", type=int, nargs="+", required=True, help="teeth of the drivers, mesh by mesh")
    r.add_argument("--followers", type=int, nargs="+", required=True, help="teeth of the followers, mesh by mesh")
    r.add_argument("--internal", type=int, nargs="*", default=[], help="numbers (from 1) of internal meshes")
    r.add_argument("--idlers", type=int, nargs="*", default=[], help="teeth of idlers in external meshes")
    r.add_argument("--format", choices=("table", "json"), default="table")
    r.add_argument("--out", help="write to this file instead of stdout")
    r.set_defaults(func=_ratio)

    d = tsub.add_parser("design", help="tooth numbers for a wanted ratio by the classic rules")
    d.add_argument(
        "--ratio",
        required=True,
        help="wanted ratio: a positive number or B/C, B and C positive integers or decimals (e.g. 1/6.931)",
    )
    g = d.add_mutually_exclusive_group()
    g.add_argument(
        "--tooth-form",
        choices=("involute", "epicycloidal", "smooth"),
        default="involute",
        help="sets the least tooth number: 24, 12, 15 (default involute)",
    )
    g.add_argument(
        "--min-teeth", type=capped_int(trains.MAX_TEETH), help=f"least tooth number t (at most {trains.MAX_TEETH:,})"
    )
    d.add_argument(
        "--max-teeth",
        type=capped_int(trains.MAX_TEETH),
        help=f"largest tooth number (default 6t, at most {trains.MAX_TEETH:,})",
    )
    d.add_argument(
        "--pairs",
        type=capped_int(trains.MAX_PAIRS),
        help=f"number of pairs (default: the text's bounds; at most {trains.MAX_PAIRS})",
    )
    d.add_argument(
        "--keep",
        type=capped_int(trains.MAX_KEEP),
        default=5,
        help=f"designs listed (default 5, at most {trains.MAX_KEEP:,})",
    )
    d.add_argument(
        "--prefer",
        choices=("teeth", "wear"),
        default="teeth",
        help="order designs by least total teeth (Young) or least gcd per pair (even wear)",
    )
    d.add_argument("--format", choices=("table", "json"), default="table")
    d.add_argument("--out", help="write to this file instead of stdout")
    d.set_defaults(func=_design)

    s = tsub.add_parser("search", help="the trains closest to a ratio, proven by exhaustive search, with exact counts")
    s.add_argument(
        "--ratio",
        required=True,
        help="target ratio: a positive number or B/C, B and C positive integers or decimals",
    )
    s.add_argument(
        "--pairs",
        type=capped_int(trains.MAX_PAIRS),
        required=True,
        help=f"number of pairs K (at most {trains.MAX_PAIRS})",
    )
    s.add_argument(
        "--min-teeth",
        type=capped_int(trains.MAX_TEETH),
        default=SEARCH_MIN_TEETH,
        help=f"least tooth number (default {SEARCH_MIN_TEETH})",
    )
    s.add_argument(
        "--max-teeth",
        type=capped_int(trains.MAX_TEETH),
        default=SEARCH_MAX_TEETH,
        help=f"largest tooth number (default {SEARCH_MAX_TEETH}, at most {trains.MAX_TEETH:,})",
    )
    s.add_argument("--metric", choices=("absolute", "relative"), default="absolute")
    s.add_argument(
        "--limit",
        type=capped_int(trains.MAX_LIMIT),
        default=None,
        help=(
            f"optimal sets listed (default {DEFAULT_LISTED}, at most {trains.MAX_LIMIT:,}); "
            "the count is always complete"
        ),
    )
    s.add_argument("--all", action="store_true", help=f"list optimal sets up to the cap of {trains.MAX_LIMIT:,}")
    s.add_argument(
        "--max-space",
        type=capped_int(trains.MAX_SPACE_CAP),
        default=None,
        help=f"refuse searches with more tooth multisets per side than this "
        f"(default {trains.DEFAULT_MAX_SPACE:,}, at most {trains.MAX_SPACE_CAP:,})",
    )
    s.add_argument("--format", choices=("table", "json"), default="table")
    s.add_argument("--out", help="write to this file instead of stdout")
    s.set_defaults(func=_search)


def _ratio(args) -> int:
    from gearlever.trains import train_ratio

    try:
        res = train_ratio(args.drivers, args.followers, internal=args.internal, idlers=args.idlers)
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    rec = res.summary()
    if args.format == "json":
        emit(to_json(rec), args.out)
    else:
        lines = [
            f"drivers          {' '.join(map(str, res.drivers))}",
            f"followers        {' '.join(map(str, res.followers))}",
        ]
        if res.idlers:
            lines.append(f"idlers           {' '.join(map(str, res.idlers))}")
        lines += [
            f"ratio            {rec['ratio']} = {rec['ratio_float']:.12g}",
            f"external meshes  {res.external_meshes}",
            f"sense            {rec['sense']}",
        ]
        emit("\n".join(lines), args.out)
    return 0


def _design_lines(d) -> str:
    pairs = ", ".join(f"{a}:{b} (gcd {g})" for a, b, g in zip(d.drivers, d.followers, d.gcds))
    shared = ", ".join(map(str, d.shared_divisor_pairs)) or "none"
    return (
        f"  drivers {list(d.drivers)} followers {list(d.followers)}  ratio {d.ratio} = {float(d.ratio):.12g}"
        f"  error {d.error:+.3e}  total teeth {d.total_teeth}\n    pairs {pairs}; sharing a divisor: {shared}"
    )


def _design(args) -> int:
    from gearlever.trains import design_train, parse_ratio

    try:
        res = design_train(
            parse_ratio(args.ratio),
            min_teeth=args.min_teeth,
            max_teeth=args.max_teeth,
            pairs=args.pairs,
            tooth_form=args.tooth_form,
            keep=args.keep,
            prefer=args.prefer,
        )
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    best, note = _exact_beside(res)
    if args.format == "json":
        rec = res.summary()
        rec["exact_optimum"] = None if best is None else _exact_record(best)
        rec["exact_optimum_note"] = note
        emit(to_json(rec), args.out)
        return 0
    b = res.bounds
    lines = [
        f"target           {res.target} = {float(res.target):.12g}",
        f"teeth            {res.min_teeth} .. {res.max_teeth}",
        f"pairs            between {b.lower:.3f} and {b.upper:.3f} (Young 3.59: {b.young:.3f})",
        f"method           {res.method} (classical rules)"
        + ("" if res.method == "exact" else f", using {res.approximation}"),
        "designs (" + ("least total teeth first" if args.prefer == "teeth" else "least gcd per pair first") + "):",
    ]
    lines += [_design_lines(d) for d in res.designs]
    if best is None:
        lines.append(f"exact optimum    {note}")
    else:
        lines.append(
            f"exact optimum    {best.best_ratios[0]} = {float(best.best_ratios[0]):.12g}  error "
            f"{float(best.best_ratios[0] - res.target):+.3e}  ({note})"
        )
        for s in best.solutions:
            lines.append(f"  drivers {list(s.drivers)} followers {list(s.followers)}")
    emit("\n".join(lines), args.out)
    return 0


def _exact_beside(res):
    """The exhaustive-search optimum for the design's pairs and tooth range, and a note saying what it is."""
    from gearlever.trains.design import exact_optimum

    pairs = len(res.designs[0].drivers)
    if res.method == "exact":
        return None, f"the classical design is exact (error 0): nothing closer with {pairs} pair(s)"
    try:
        best = exact_optimum(res, limit=3)
    except GearleverError as exc:
        return None, f"not searched: {exc}"
    verdict = (
        "the classical design is optimal"
        if abs(best.best_ratios[0] - res.target) >= abs(res.approximation - res.target)
        else "closer than the classical design"
    )
    return best, f"exhaustive search, {pairs} pair(s), teeth {res.min_teeth} .. {res.max_teeth}: {verdict}"


def _exact_record(best) -> dict:
    r = best.best_ratios[0]
    return {
        "ratio": f"{r.numerator}/{r.denominator}",
        "ratio_float": float(r),
        "error": float(r - best.target),
        "pairs": best.pairs,
        "optimal_sets": best.n_solutions,
        "solutions": [{"drivers": list(s.drivers), "followers": list(s.followers)} for s in best.solutions],
    }


def _search(args) -> int:
    from gearlever.trains import parse_ratio, search_best

    limit = trains.MAX_LIMIT if args.all else (args.limit or DEFAULT_LISTED)
    progress = TerminalProgress("train search")
    try:
        res = search_best(
            parse_ratio(args.ratio),
            args.pairs,
            args.min_teeth,
            args.max_teeth,
            metric=args.metric,
            max_space=args.max_space or trains.DEFAULT_MAX_SPACE,
            limit=limit,
            progress=progress,
        )
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    finally:
        progress.close()
    if args.format == "json":
        emit(to_json(res.summary()), args.out)
        return 0
    lines = [
        f"target           {res.target} = {float(res.target):.12g}",
        f"pairs            {res.pairs}, teeth {res.min_teeth} .. {res.max_teeth}",
        f"best error       {float(res.best_error):.6e} ({res.metric})",
        f"best ratio       {', '.join(f'{r} = {float(r):.12g}' for r in res.best_ratios)}",
        f"optimal sets     {res.n_solutions:,} up to order ({res.n_ordered:,} ordered tuples), "
        f"from {res.n_product_pairs:,} pair(s) of products",
        f"searched         {res.n_products:,} distinct products per side, {res.n_candidates:,} candidate pairs "
        "(every product against the 4 around its best partner: proven optimal)",
    ]
    for s in res.solutions:
        pairing = ", ".join(f"{a}:{b}" for a, b in s.pairing)
        lines.append(f"  drivers {list(s.drivers)} followers {list(s.followers)}  pairs {pairing}")
    if len(res.solutions) < res.n_solutions:
        more = res.n_solutions - len(res.solutions)
        hint = (
            f"--limit up to {trains.MAX_LIMIT:,}"
            if len(res.solutions) < trains.MAX_LIMIT
            else f"listing is capped at {trains.MAX_LIMIT:,}"
        )
        lines.append(f"  ... {more:,} more, counted but not listed ({hint}; use --all for the cap)")
    emit("\n".join(lines), args.out)
    return 0
