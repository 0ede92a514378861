"""``gearlever zrdpm``: analogue table of one ZRDPM contour (self-consistent model)."""

from __future__ import annotations

from gearlever.cli._common import emit, finite_float, positive_float, positive_int, to_json
from gearlever.errors import GearleverError

#: Keys of the JSON records and the CSV columns.
KEYS = ("phi_deg", "u_carrier", "u_gear", "e_carrier", "e_gear")


def register(sub) -> None:
    p = sub.add_parser(
        "zrdpm",
        help="velocity and acceleration analogues of a ZRDPM contour",
        description="Analogues of the carrier (lever) and the driven gear of ZRDPM contour 1 "
        "(lever 1, gear 8, leading gear 9) or 2 (lever 2, gear 7, leading gear 6) over the "
        "leading gear's angle. Angles: --phi DEG ... or --start/--stop/--step "
        "(default 0 to 360 by 30).",
    )
    p.add_argument("--contour", type=int, choices=(1, 2), required=True, help="contour 1 or 2")
    p.add_argument("--phi", type=finite_float, nargs="+", metavar="DEG", help="angles, degrees")
    p.add_argument("--start", type=finite_float, help="first angle, degrees (default 0)")
    p.add_argument("--stop", type=finite_float, help="last angle, degrees, inclusive (default 360)")
    p.add_argument("--step", type=positive_float, help="angle step, degrees (default 30)")
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--ratio",
        type=positive_float,
        default=None,
        help="gear ratio r9/r8 (contour 1) or r6/r7 (contour 2), default 0.5",
    )
    g.add_argument(
        "--teeth",
        type=positive_int,
        nargs=2,
        metavar=("Z_LEAD", "Z_DRIVEN"),
        help="tooth numbers of the leading and the driven gear (ratio Z_LEAD/Z_DRIVEN)",
    )
    p.add_argument("--l", type=positive_float, default=10.0, help="contour link length, cm (default 10)")
    p.add_argument("--r-a", type=positive_float, default=None, help="slider radius rA, cm (default l/2)")
    p.add_argument("--r-b", type=positive_float, default=None, help="slider radius rB, cm (default l/2)")
    p.add_argument("--mesh", choices=("external", "internal"), default="external", help="gear mesh")
    p.add_argument("--format", choices=("table", "csv", "json"), default="table", help="output format")
    p.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    p.set_defaults(func=_run)


def _angles(args):
    import numpy as np

    if args.phi is not None:
        if any(v is not None for v in (args.start, args.stop, args.step)):
            raise GearleverError("--phi must not be combined with --start/--stop/--step")
        return np.asarray(args.phi, dtype=float)
    start = 0.0 if args.start is None else args.start
    stop = 360.0 if args.stop is None else args.stop
    step = 30.0 if args.step is None else args.step
    if stop < start:
        raise GearleverError(f"--stop must be >= --start (the angle range is empty), got {start} to {stop}")
    n = int(np.floor((stop - start) / step + 1e-9)) + 1
    if n > 10_000_000:
        raise GearleverError(f"--step must give at most 10^7 angles, got {n}")
    return start + step * np.arange(n)


def _format(records, names, fmt) -> str:
    if fmt == "json":
        return to_json(records)
    if fmt == "csv":
        lines = [",".join(KEYS)]
        lines += [",".join(f"{rec[k]:.12g}" for k in KEYS) for rec in records]
        return "\n".join(lines)
    header = ["phi_deg", *names]
    lines = ["".join(f"{h:>12}" for h in header)]
    lines += ["".join(f"{rec[k]:12.6f}" for k in KEYS) for rec in records]
    return "\n".join(lines)


def _run(args) -> int:
    import numpy as np

    from gearlever.zrdpm import model as zrdpm

    phi_deg = _angles(args)
    kwargs = {
        "l": args.l,
        "r_a": args.r_a if args.r_a else args.l / 2,
        "r_b": args.r_b if args.r_b else args.l / 2,
    }
    if args.teeth is not None:
        params = zrdpm.ZrdpmContour.from_teeth(args.contour, args.teeth[0], args.teeth[1], mesh=args.mesh, **kwargs)
    else:
        ratio = 0.5 if args.ratio is None else args.ratio
        params = zrdpm.ZrdpmContour(contour=args.contour, mesh=args.mesh, **kwargs).with_ratio(ratio)
    kin = zrdpm.analogues(params, np.deg2rad(phi_deg))
    records = [
        dict(zip(KEYS, map(float, row))) for row in zip(phi_deg, kin.u_carrier, kin.u_gear, kin.e_carrier, kin.e_gear)
    ]
    emit(_format(records, params.names[:4], args.format), args.out)
    return 0
