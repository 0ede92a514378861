"""``gearlever differential car``: speeds, torques and power of a car differential.

``gearlever differential car --pinion-teeth Z1 --ring-teeth Z2 --pinion-speed W --pinion-torque G
[--turn-radius R --track T | --left-speed W4] [--format table|json]``
(neither a turn nor a left speed: a straight run).

Caps: tooth numbers at most :data:`MAX_TEETH`.  Speeds and torques are any
finite numbers; a result too large for a float is printed as ``inf`` (table)
or ``null`` (json).
"""

from __future__ import annotations

from gearlever.cli._common import capped_int, emit, finite_float, positive_float, to_json
from gearlever.errors import GearleverError

#: Largest tooth number accepted: far above any built ring or pinion; it keeps
#: ``Z1/Z2`` and ``Z2/Z1`` ordinary floats (a huge integer ratio overflows).
MAX_TEETH = 10**6


def register(sub) -> None:
    p = sub.add_parser("differential", help="differentials: the car (bevel) differential")
    cmds = p.add_subparsers(dest="differential_command", metavar="{car}")
    cmds.required = True
    c = cmds.add_parser("car", help="ring and pinion, carrier, wheel speeds, torques and power")
    c.add_argument("--pinion-teeth", type=capped_int(MAX_TEETH), required=True, metavar="Z1")
    c.add_argument("--ring-teeth", type=capped_int(MAX_TEETH), required=True, metavar="Z2")
    c.add_argument(
        "--pinion-speed",
        type=finite_float,
        required=True,
        metavar="W",
        help="pinion speed w1 (any unit; the outputs use it)",
    )
    c.add_argument(
        "--pinion-torque",
        type=finite_float,
        required=True,
        metavar="G",
        help="pinion torque G1 (any unit; the outputs use it)",
    )
    c.add_argument(
        "--turn-radius",
        type=finite_float,
        default=None,
        metavar="R",
        help="radius of the axle mid-point's turn, > 0 turning left, < 0 right (needs --track)",
    )
    c.add_argument("--track", type=positive_float, default=None, metavar="T", help="track width, units of R")
    c.add_argument(
        "--left-speed",
        type=finite_float,
        default=None,
        metavar="W4",
        help="left wheel speed (0: left wheel held)",
    )
    c.add_argument("--format", choices=("table", "json"), default="table")
    c.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")
    c.set_defaults(func=_car)


def _car(args) -> int:
    from gearlever.gears.car import car_differential

    if (args.turn_radius is None) != (args.track is None):
        raise GearleverError("--turn-radius and --track must be given together")
    state = car_differential(
        args.pinion_teeth,
        args.ring_teeth,
        args.pinion_speed,
        args.pinion_torque,
        left_speed=args.left_speed,
        turn_radius=args.turn_radius,
        track=args.track,
    )
    result = state.summary()
    if args.format == "json":
        emit(to_json(result), args.out)
        return 0
    width = max(len(k) for k in result)
    emit("\n".join(f"{k:<{width}}  {v:.12g}" for k, v in result.items()), args.out)
    return 0
