"""``gearlever mobility``: degree of mobility W, or redundant constraints q (paper eq. 1)."""

from __future__ import annotations

from gearlever.cli._common import emit, nonnegative_int


def register(sub) -> None:
    p = sub.add_parser(
        "mobility",
        help="mobility W = 3n - 2*P5 - P4 + q, or q for a known W",
        description="Planar mobility with redundant constraints (ZRDPM paper eq. 1). "
        "Give --q to get W, or --w to get q.",
    )
    p.add_argument("--n", type=nonnegative_int, required=True, help="moving links")
    p.add_argument("--p5", type=nonnegative_int, required=True, help="lower pairs (class 5)")
    p.add_argument("--p4", type=nonnegative_int, required=True, help="higher pairs (class 4, gear meshes)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--q", type=nonnegative_int, help="redundant constraints: print W")
    g.add_argument("--w", type=nonnegative_int, help="known mobility: print q")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from gearlever.mechanism.mobility import mobility, redundant_constraints

    if args.q is not None:
        emit(f"W = {mobility(args.n, args.p5, args.p4, args.q)}")
    else:
        emit(f"q = {redundant_constraints(args.n, args.p5, args.p4, args.w)}")
    return 0
