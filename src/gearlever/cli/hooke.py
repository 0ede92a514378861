"""``gearlever hooke``: velocity ratio of a single or double Hooke's coupling."""

from __future__ import annotations

import numpy as np

from gearlever.cli._common import emit, finite_float, to_json
from gearlever.errors import GearleverError


def register(sub) -> None:
    p = sub.add_parser("hooke", help="output angle and velocity ratio of a Hooke's coupling (angles in degrees)")
    p.add_argument(
        "--shaft-angle",
        type=finite_float,
        required=True,
        help="angle between the shafts (of the first joint), degrees, 0 <= angle < 90",
    )
    p.add_argument(
        "--input-angle",
        type=finite_float,
        nargs="+",
        default=None,
        help="input angles, degrees (default 0, 15, ..., 360); 0 = input fork in the plane of the shafts",
    )
    p.add_argument(
        "--second-angle",
        type=finite_float,
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
        raise GearleverError("phase needs --second-angle (a double coupling)")
    joint = HookeJoint(args.shaft_angle, args.second_angle, args.phase)
    phi = np.arange(0.0, 360.0 + 1e-9, 15.0) if args.input_angle is None else np.asarray(args.input_angle)
    out = joint.output_angle_deg(phi)
    ratio = joint.velocity_ratio(phi)
    acc = joint.acceleration_ratio(phi)
    records = [
        # "+ 0.0" turns a negative zero into 0.0 so that no "-0.000" is printed
        {
            "input_deg": float(a) + 0.0,
            "output_deg": float(b) + 0.0,
            "ratio": float(c) + 0.0,
            "acceleration_ratio": float(d) + 0.0,
        }
        for a, b, c, d in zip(phi, out, ratio, acc)
    ]
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
