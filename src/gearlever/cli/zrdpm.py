"""``gearlever zrdpm``: analogue table of one ZRDPM contour (self-consistent model)."""

from __future__ import annotations

import argparse
import math

from gearlever._io import table_text
from gearlever.cli._common import (
    emit,
    finite_float,
    positive_float,
    positive_int,
    progress,
    to_json,
)
from gearlever.errors import GearleverError

#: Keys of the JSON records and the CSV columns, followed by the two point
#: accelerations named as in the API (``a_B_cm, a_A_cm`` for contour 1,
#: ``a_D_cm, a_E_cm`` for contour 2; cm over the leading link's omega^2).
KEYS = ("phi_deg", "u_carrier", "u_gear", "e_carrier", "e_gear")

#: Most angles in a table or CSV: a row is ~70 bytes of text and the model
#: keeps six float64 arrays, so 10^6 angles take ~70 MB of text and ~50 MB of
#: arrays, and about two seconds.
MAX_ANGLES = 10**6
#: Most angles in JSON: a record is ~170 bytes of text and ~1 kB of Python
#: objects while the document is built, so 10^5 angles take ~120 MB.
MAX_JSON_ANGLES = 10**5
#: Largest gear ratio r_lead/r_driven accepted (and smallest, as 1/MAX_RATIO):
#: beyond it the radii overflow or underflow and no gear pair is meant.
MAX_RATIO = 1e12


def _ratio(text: str) -> float:
    """argparse type of ``--ratio``: a number in [1/MAX_RATIO, MAX_RATIO]."""
    value = positive_float(text)
    if not 1.0 / MAX_RATIO <= value <= MAX_RATIO:
        raise argparse.ArgumentTypeError(f"must be between 1e-12 and 1e12 (a gear ratio), got {text!r}")
    return value


def register(sub) -> None:
    p = sub.add_parser(
        "zrdpm",
        help="velocity and acceleration analogues of a ZRDPM contour",
        description="Analogues of the carrier (lever) and the driven gear of ZRDPM contour 1 "
        "(lever 1, gear 8, leading gear 9) or 2 (lever 2, gear 7, leading gear 6) over the "
        "leading gear's angle. Angles: --phi DEG ... or --start/--stop/--step "
        f"(default 0 to 360 by 30); at most {MAX_ANGLES:.0e} angles ({MAX_JSON_ANGLES:.0e} with "
        "--format json). Negative values: --start=-90.",
    )
    p.add_argument("--contour", type=int, choices=(1, 2), required=True, help="contour 1 or 2")
    p.add_argument("--phi", type=finite_float, nargs="+", metavar="DEG", help="angles, degrees")
    p.add_argument("--start", type=finite_float, help="first angle, degrees (default 0)")
    p.add_argument("--stop", type=finite_float, help="last angle, degrees, inclusive (default 360)")
    p.add_argument("--step", type=positive_float, help="angle step, degrees (default 30)")
    g = p.add_mutually_exclusive_group()
    g.add_argument(
        "--ratio",
        type=_ratio,
        default=None,
        help="gear ratio r9/r8 (contour 1) or r6/r7 (contour 2), 1e-12 to 1e12, default 0.5",
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
    """The angles in degrees, refused (naming the flags) when there would be more than the cap."""
    import numpy as np

    cap = MAX_JSON_ANGLES if args.format == "json" else MAX_ANGLES
    fmt = f" with --format {args.format}" if args.format == "json" else ""
    if args.phi is not None:
        if any(v is not None for v in (args.start, args.stop, args.step)):
            raise GearleverError("--phi must not be combined with --start/--stop/--step")
        if len(args.phi) > cap:
            raise GearleverError(f"--phi gives {len(args.phi)} angles, more than the cap {cap:,}{fmt}")
        return np.asarray(args.phi, dtype=float)
    start = 0.0 if args.start is None else args.start
    stop = 360.0 if args.stop is None else args.stop
    step = 30.0 if args.step is None else args.step
    if stop < start:
        raise GearleverError(f"--stop must be >= --start (the angle range is empty), got {start:g} to {stop:g}")
    span = stop - start
    if not math.isfinite(span):
        raise GearleverError(
            f"--start {start:g} and --stop {stop:g} must be less than 1.7e308 apart (the range overflows)"
        )
    count = span / step + 1.0  # may be huge: tested before any integer is made of it
    n = int(math.floor(span / step + 1e-9)) + 1 if count <= cap + 2 else count
    if n > cap:
        shown = f"{n:d}" if isinstance(n, int) else f"{n:.3g}"
        raise GearleverError(
            f"--start {start:g}, --stop {stop:g} and --step {step:g} give {shown} angles, "
            f"more than the cap {cap:,}{fmt}"
        )
    return start + step * np.arange(n)


def _format(phi_deg, kin, names, fmt) -> str:
    """``names``: the six paper names of the contour (``u_1, u_8, e_1, e_8, a_B, a_A``)."""
    keys = (*KEYS, *(f"{n}_cm" for n in names[4:6]))
    cols = (phi_deg, kin.u_carrier, kin.u_gear, kin.e_carrier, kin.e_gear, kin.a_x, kin.a_y)
    if fmt == "json":
        return to_json([dict(zip(keys, map(float, row))) for row in zip(*cols)])
    if fmt == "csv":
        return table_text(dict(zip(keys, cols)), "csv")
    header = ["phi_deg", *names[:4], *(f"{n}_cm" for n in names[4:6])]
    lines = ["".join(f"{h:>12}" for h in header)]
    lines += ["".join(f"{v:12.6f}" for v in row) for row in zip(*(c.tolist() for c in cols))]
    return "\n".join(lines)


def _run(args) -> int:
    import numpy as np

    from gearlever import zrdpm

    phi_deg = _angles(args)
    kwargs = {"l": args.l, "r_a": args.r_a, "r_b": args.r_b}
    if args.teeth is not None:
        params = zrdpm.ZrdpmContour.from_teeth(args.contour, args.teeth[0], args.teeth[1], mesh=args.mesh, **kwargs)
    else:
        ratio = 0.5 if args.ratio is None else args.ratio
        params = zrdpm.ZrdpmContour(contour=args.contour, mesh=args.mesh, **kwargs).with_ratio(ratio)
    with progress("computing the analogues"):
        kin = zrdpm.analogues(params, np.deg2rad(phi_deg))
        text = _format(phi_deg, kin, params.names, args.format)
    emit(text, args.out)
    return 0
