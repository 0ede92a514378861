"""``gearlever chariot``: size the Nuttall south-pointing chariot and drive it.

``gearlever chariot nuttall --n2 .. --n11 .. [--track T] [--format table|json]``
``gearlever chariot simulate --design nuttall --n2 .. --n11 .. [--track T] [--d1 X] [--d12 Y]
[--path random --turns N --seed S | --waypoints FILE] [--format table|json]``
"""

from __future__ import annotations

import math
from pathlib import Path

from gearlever.cli._common import emit, finite_float, nonnegative_int, positive_float, positive_int, to_json
from gearlever.errors import GearleverError

_TEETH = ("n2", "n5", "n6", "n7", "n8", "n9", "n11")


def _add_teeth(p) -> None:
    for name in _TEETH:
        p.add_argument(
            f"--{name}",
            type=positive_int,
            required=True,
            metavar="TEETH",
            help=f"tooth number {name} (see the Nuttall parts list)",
        )
    p.add_argument(
        "--track",
        type=positive_float,
        default=1.0,
        metavar="T",
        help="track width t; diameters come out in its units (default 1)",
    )
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")


def register(sub) -> None:
    p = sub.add_parser("chariot", help="Nuttall south-pointing chariot: wheel sizes and a simulated drive")
    cmds = p.add_subparsers(dest="chariot_command", metavar="{nuttall,simulate}")
    cmds.required = True

    n = cmds.add_parser("nuttall", help="solve the gear network and size the road wheels d1, d12")
    _add_teeth(n)
    n.set_defaults(func=_nuttall)

    s = cmds.add_parser("simulate", help="drive the chariot and report the pointer's drift")
    s.add_argument("--design", choices=("nuttall",), default="nuttall")
    _add_teeth(s)
    s.add_argument(
        "--d1",
        type=positive_float,
        default=None,
        metavar="X",
        help="actual diameter of wheel 1 (right), units of T (default: the computed one)",
    )
    s.add_argument(
        "--d12",
        type=positive_float,
        default=None,
        metavar="Y",
        help="actual diameter of wheel 12 (left), units of T (default: the computed one)",
    )
    s.add_argument("--path", choices=("random",), default="random", help="random drive (default)")
    s.add_argument(
        "--turns",
        type=positive_float,
        default=10.0,
        metavar="N",
        help="random path: total chassis turning in full turns (default 10)",
    )
    s.add_argument("--seed", type=nonnegative_int, default=0, metavar="S", help="random path seed (default 0)")
    s.add_argument(
        "--steps-per-turn",
        type=positive_int,
        default=1000,
        metavar="K",
        help="random path: steps per full turn (default 1000)",
    )
    s.add_argument(
        "--waypoints",
        default=None,
        metavar="FILE",
        help="drive through the x y pairs in FILE (CSV or whitespace) instead of a random path",
    )
    s.add_argument(
        "--step",
        type=positive_float,
        default=0.01,
        metavar="L",
        help="way-point path: longest step of a contact point, units of T (default 0.01)",
    )
    s.add_argument(
        "--heading",
        type=finite_float,
        default=0.0,
        metavar="RAD",
        help="random path: starting chassis heading in rad (default 0)",
    )
    s.set_defaults(func=_simulate)


def _design(args):
    from gearlever.gears.chariot import NuttallTeeth, design_nuttall

    teeth = NuttallTeeth(*(getattr(args, k) for k in _TEETH))
    return design_nuttall(teeth, track=args.track)


def _frac(f) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def _nuttall(args) -> int:
    from gearlever.gears.networks import format_linear

    d = _design(args)
    a = d.solution.analysis
    result = {
        "d1": d.d1,
        "d12": d.d12,
        "d1_fraction": _frac(d.d1_over_t),
        "d12_fraction": _frac(d.d12_over_t),
        "dof": a.dof,
        "redundant": list(a.redundant),
        "unknowns": a.unknowns,
        "rank": a.rank,
        "track": d.track,
        "relation_l": d.solution.relation("7"),
        "rot1_per_pointer_turn": _frac(d.rot1_per_pointer_turn),
        "rot12_per_pointer_turn": _frac(d.rot12_per_pointer_turn),
    }
    if args.format == "json":
        emit(to_json(result), args.out)
        return 0
    deps = "; ".join(
        f"({k}) = {format_linear({f'({j})': v for j, v in dep.items()}).replace('rot_', '')}"
        for k, dep in a.dependencies.items()
    )
    lines = [
        f"Nuttall chariot, track t = {d.track:g}",
        f"unknown rotations {a.unknowns}, rank {a.rank}, degrees of freedom {a.dof}",
        f"redundant constraints: {', '.join(a.redundant) or 'none'}" + (f"  [{deps}]" if deps else ""),
        f"relation (l): {result['relation_l']}",
        f"wheel 1 (right): {result['rot1_per_pointer_turn']} turns per pointer turn, "
        f"d1  = {d.d1:.12g}  ({result['d1_fraction']} t)",
        f"wheel 12 (left): {result['rot12_per_pointer_turn']} turns per pointer turn, "
        f"d12 = {d.d12:.12g}  ({result['d12_fraction']} t)",
    ]
    emit("\n".join(lines), args.out)
    return 0


def _simulate(args) -> int:
    from gearlever.gears.chariot import parse_waypoints, random_path, simulate, waypoint_path

    d = _design(args)
    if args.waypoints is not None:
        try:
            text = Path(args.waypoints).read_text(encoding="utf-8")
        except (OSError, UnicodeDecodeError) as exc:
            reason = getattr(exc, "strerror", None) or type(exc).__name__
            raise GearleverError(f"waypoints file {args.waypoints!r} cannot be read: {reason}") from None
        pts = parse_waypoints(text)
        dl, dr, h0 = waypoint_path(pts, track=d.track, step=args.step * d.track)
        run = simulate(
            d,
            dl,
            dr,
            d1=args.d1 and args.d1 * d.track,
            d12=args.d12 and args.d12 * d.track,
            heading0=h0,
            start=pts[0],
        )
        path = f"path through the {len(pts)} way-points of {args.waypoints}"
    else:
        dl, dr = random_path(args.turns, seed=args.seed, steps_per_turn=args.steps_per_turn, track=d.track)
        run = simulate(
            d,
            dl,
            dr,
            d1=args.d1 and args.d1 * d.track,
            d12=args.d12 and args.d12 * d.track,
            heading0=args.heading,
        )
        path = f"random path, seed {args.seed}"
    turns = run.turns
    result = {
        "max_drift_rad": run.max_drift,
        "final_drift_rad": run.final_drift,
        "distance": run.distance,
        "turns": turns,
        "drift_per_turn_rad": run.max_drift / turns if turns > 0 else 0.0,
        "steps": int(dl.size),
        "d1": d.d1 if args.d1 is None else args.d1 * d.track,
        "d12": d.d12 if args.d12 is None else args.d12 * d.track,
        "d1_design": d.d1,
        "d12_design": d.d12,
        "track": d.track,
    }
    if args.format == "json":
        emit(to_json(result), args.out)
        return 0
    lines = [
        f"Nuttall chariot, {path}: {result['steps']} steps, distance {run.distance:.6g}, "
        f"chassis turning {turns:.6g} turns",
        f"wheels: d1 = {result['d1']:.12g} (design {d.d1:.12g}), d12 = {result['d12']:.12g} (design {d.d12:.12g})",
        f"pointer drift: max {run.max_drift:.3e} rad ({math.degrees(run.max_drift):.3e} deg), "
        f"final {run.final_drift:.3e} rad, {result['drift_per_turn_rad']:.3e} rad per turn",
    ]
    emit("\n".join(lines), args.out)
    return 0
