"""``gearlever train ratio|design|search``: trains of wheels."""

from __future__ import annotations

from gearlever.cli._common import emit, positive_int, to_json

#: Solutions listed by ``train search`` without ``--all``.
DEFAULT_LISTED = 10


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
    d.add_argument("--ratio", required=True, help="wanted ratio: a number or B/C (decimals allowed, e.g. 1/6.931)")
    g = d.add_mutually_exclusive_group()
    g.add_argument(
        "--tooth-form",
        choices=("involute", "epicycloidal", "smooth"),
        default="involute",
        help="sets the least tooth number: 24, 12, 15 (default involute)",
    )
    g.add_argument("--min-teeth", type=positive_int, help="least tooth number t")
    d.add_argument("--max-teeth", type=positive_int, help="largest tooth number (default 6t)")
    d.add_argument("--pairs", type=positive_int, help="number of pairs (default: the text's bounds)")
    d.add_argument("--keep", type=positive_int, default=5, help="designs listed (default 5)")
    d.add_argument(
        "--prefer",
        choices=("teeth", "wear"),
        default="teeth",
        help="order designs by least total teeth (Young) or least gcd per pair (even wear)",
    )
    d.add_argument("--format", choices=("table", "json"), default="table")
    d.add_argument("--out", help="write to this file instead of stdout")
    d.set_defaults(func=_design)

    s = tsub.add_parser("search", help="every train closest to a ratio, proven by exhaustive search")
    s.add_argument("--ratio", required=True, help="target ratio: a number or B/C (decimals allowed)")
    s.add_argument("--pairs", type=positive_int, required=True, help="number of pairs K")
    s.add_argument("--min-teeth", type=positive_int, required=True)
    s.add_argument("--max-teeth", type=positive_int, required=True)
    s.add_argument("--metric", choices=("absolute", "relative"), default="absolute")
    s.add_argument("--all", action="store_true", help=f"list every optimal train (default: the first {DEFAULT_LISTED})")
    s.add_argument(
        "--max-space",
        type=positive_int,
        default=None,
        help="refuse searches with more tooth multisets per side than this",
    )
    s.add_argument("--format", choices=("table", "json"), default="table")
    s.add_argument("--out", help="write to this file instead of stdout")
    s.set_defaults(func=_search)


def _ratio(args) -> int:
    from gearlever.trains import train_ratio

    res = train_ratio(args.drivers, args.followers, internal=args.internal, idlers=args.idlers)
    rec = res.as_dict()
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
    from gearlever.trains.synthesis import design_train

    res = design_train(
        args.ratio,
        min_teeth=args.min_teeth,
        max_teeth=args.max_teeth,
        pairs=args.pairs,
        tooth_form=args.tooth_form,
        keep=args.keep,
        prefer=args.prefer,
    )
    if args.format == "json":
        emit(to_json(res.as_dict()), args.out)
        return 0
    b = res.bounds
    lines = [
        f"target           {res.target} = {float(res.target):.12g}",
        f"teeth            {res.min_teeth} .. {res.max_teeth}",
        f"pairs            between {b.lower:.3f} and {b.upper:.3f} (Young 3.59: {b.young:.3f})",
        f"method           {res.method}" + ("" if res.method == "exact" else f", using {res.approximation}"),
        "designs (" + ("least total teeth first" if args.prefer == "teeth" else "least gcd per pair first") + "):",
    ]
    lines += [_design_lines(d) for d in res.designs]
    emit("\n".join(lines), args.out)
    return 0


def _search(args) -> int:
    from gearlever.trains.synthesis import DEFAULT_MAX_SPACE, search_best

    res = search_best(
        args.ratio,
        args.pairs,
        args.min_teeth,
        args.max_teeth,
        metric=args.metric,
        max_space=args.max_space or DEFAULT_MAX_SPACE,
        limit=None if args.all else DEFAULT_LISTED,
    )
    if args.format == "json":
        emit(to_json(res.as_dict()), args.out)
        return 0
    lines = [
        f"target           {res.target} = {float(res.target):.12g}",
        f"pairs            {res.pairs}, teeth {res.min_teeth} .. {res.max_teeth}",
        f"best error       {float(res.best_error):.6e} ({res.metric})",
        f"best ratio       {', '.join(f'{r} = {float(r):.12g}' for r in res.best_ratios)}",
        f"optimal sets     {res.n_solutions} up to order ({res.n_ordered} ordered tuples)",
        f"searched         {res.n_products} distinct products per side",
    ]
    for s in res.solutions:
        pairing = ", ".join(f"{a}:{b}" for a, b in s.pairing)
        lines.append(f"  drivers {list(s.drivers)} followers {list(s.followers)}  pairs {pairing}")
    if len(res.solutions) < res.n_solutions:
        lines.append(f"  ... {res.n_solutions - len(res.solutions)} more (use --all)")
    emit("\n".join(lines), args.out)
    return 0
