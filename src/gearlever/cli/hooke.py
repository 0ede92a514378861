"""``gearlever hooke``: velocity ratio of a single or double Hooke's coupling.

Angles are in degrees here (the library works in radians).  ``--input-angle``
takes at most 10,000 angles; the default is 0, 15, ..., 360.  Errors name the
flags; JSON output is strict (no NaN).
"""

from __future__ import annotations

import argparse

import numpy as np

from gearlever.cli._common import emit, finite_float, flagged, to_json
from gearlever.errors import GearleverError

#: Most input angles accepted by ``--input-angle``.
MAX_INPUT_ANGLES = 10_000

# Library parameter names (radians or degrees) -> the flags that set them.
_FLAGS = {
    "shaft_angle": "--shaft-angle",
    "shaft_angle_deg": "--shaft-angle",
    "second_angle": "--second-angle",
    "second_angle_deg": "--second-angle",
    "phase": "--phase",
    "phase_deg": "--phase",
    "phi": "--input-angle",
    "input_deg": "--input-angle",
}


def _shaft_deg(text: str) -> float:
    """argparse type: a shaft angle in degrees, 0 <= angle < 90."""
    value = finite_float(text)
    if not 0.0 <= value < 90.0:
        raise argparse.ArgumentTypeError(f"must be at least 0 and below 90 degrees, got {text!r}")
    return value


def register(sub) -> None:
    p = sub.add_parser("hooke", help="output angle and velocity ratio of a Hooke's coupling (angles in degrees)")
    p.add_argument(
        "--shaft-angle",
        type=_shaft_deg,
        required=True,
        help="angle between the shafts (of the first joint), degrees, 0 <= angle < 90",
    )
    p.add_argument(
        "--input-angle",
        type=finite_float,
        nargs="+",
        default=None,
        help="input angles, degrees (default 0, 15, ..., 360; at most 10,000 angles); "
        "0 = input fork in the plane of the shafts",
    )
    p.add_argument(
        "--second-angle",
        type=_shaft_deg,
        default=None,
        help="double coupling: angle between intermediate and last shafts, degrees",
    )
    p.add_argument(
        "--phase",
        type=finite_float,
        default=0.0,
        help="double coupling: turn of the intermediate shaft's second fork, degrees (default 0)",
    )
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--out", help="write to this file instead of stdout")
    p.set_defaults(func=_run)


def _run(args) -> int:
    from gearlever.trains.hooke import HookeJoint

    if args.phase != 0.0 and args.second_angle is None:
        raise GearleverError("--phase needs --second-angle (a double coupling)")
    if args.input_angle is not None and len(args.input_angle) > MAX_INPUT_ANGLES:
        raise GearleverError(f"--input-angle takes at most {MAX_INPUT_ANGLES:,} angles, got {len(args.input_angle):,}")
    phi_deg = np.arange(0.0, 360.0 + 1e-9, 15.0) if args.input_angle is None else np.asarray(args.input_angle)
    try:
        joint = HookeJoint.from_degrees(args.shaft_angle, args.second_angle, args.phase)
        records = joint.turn(np.radians(phi_deg)).as_records_deg()
    except GearleverError as exc:
        raise flagged(exc, _FLAGS) from None
    for rec, a in zip(records, phi_deg):
        rec["input_deg"] = float(a) + 0.0  # the angle as given, not a round trip through radians
    if args.format == "json":
        emit(to_json(records), args.out)
        return 0
    kind = (
        f"double coupling, {args.shaft_angle:g} and {args.second_angle:g} deg, phase {args.phase:g} deg"
        if joint.double
        else f"single joint, shaft angle {args.shaft_angle:g} deg"
    )
    lines = [kind, f"{'input_deg':>10} {'output_deg':>12} {'ratio':>12} {'accel_ratio':>12}"]
    lines += [
        f"{r['input_deg']:10.3f} {r['output_deg']:12.6f} {r['ratio']:12.9f} {r['acceleration_ratio']:12.9f}"
        for r in records
    ]
    emit("\n".join(lines), args.out)
    return 0
