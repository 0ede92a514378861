"""``gearlever chariot``: size the Nuttall south-pointing chariot and drive it.

``gearlever chariot nuttall --n2 .. --n11 .. [--track T] [--format table|json]``
``gearlever chariot simulate --design nuttall --n2 .. --n11 .. [--track T] [--d1 X] [--d12 Y]
[--path random --turns N --seed S --steps-per-turn K --heading RAD | --waypoints FILE --step L]
[--format table|json]``

Caps (refused above, naming the cap): tooth numbers at most :data:`MAX_TEETH`;
a path of at most :data:`gearlever.gears.chariot.MAX_STEPS` steps (``--turns``
times ``--steps-per-turn``, or the way-points' length over ``--step``); a
way-point file of at most :data:`MAX_WAYPOINT_BYTES` bytes.  Options of the
random path and of the way-point path do not mix.
"""

from __future__ import annotations

import math

from gearlever._io import read_text_capped
from gearlever.cli._common import (
    capped_float,
    capped_int,
    check_cap,
    emit,
    finite_float,
    nonnegative_int,
    positive_float,
    progress,
    to_json,
)
from gearlever.errors import GearleverError
from gearlever.gears.chariot import MAX_STEPS

_TEETH = ("n2", "n5", "n6", "n7", "n8", "n9", "n11")

#: Largest tooth number accepted: no built gear comes near it, and it keeps the
#: exact fractions of the solver small (a few digits) and every diameter a
#: float well inside range (bigger numbers cost no memory but overflow floats).
MAX_TEETH = 10**6
#: Largest way-point file read (bytes): ~10^6 lines of x y pairs, parsed in a
#: few seconds and a few hundred MB at most; the file is read at most this far.
MAX_WAYPOINT_BYTES = 64 * 2**20
#: Defaults of the random path (its options are None when not given, so that
#: mixing them with --waypoints is refused rather than silently ignored).
RANDOM_DEFAULTS = {"turns": 10.0, "seed": 0, "steps_per_turn": 1000, "heading": 0.0}
#: Default longest step of the way-point path, units of the track.
DEFAULT_STEP = 0.01


def _add_teeth(p) -> None:
    for name in _TEETH:
        p.add_argument(
            f"--{name}",
            type=capped_int(MAX_TEETH),
            required=True,
            metavar="TEETH",
            help=f"tooth number {name} (see the Nuttall parts list), at most {MAX_TEETH:,}",
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
        type=capped_float(MAX_STEPS),
        default=None,
        metavar="N",
        help=f"random path: total chassis turning in full turns (default 10; N*K at most {MAX_STEPS:,} steps)",
    )
    s.add_argument("--seed", type=nonnegative_int, default=None, metavar="S", help="random path seed (default 0)")
    s.add_argument(
        "--steps-per-turn",
        type=capped_int(MAX_STEPS),
        default=None,
        metavar="K",
        help=f"random path: steps per full turn (default 1000; N*K at most {MAX_STEPS:,} steps)",
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
        default=None,
        metavar="L",
        help=f"way-point path: longest step of a contact point, units of T (default {DEFAULT_STEP}; "
        f"at most {MAX_STEPS:,} steps in all)",
    )
    s.add_argument(
        "--heading",
        type=finite_float,
        default=None,
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


def _read_waypoints(name: str) -> str:
    """The text of the way-point file ``name`` (a regular file, at most :data:`MAX_WAYPOINT_BYTES`)."""
    return read_text_capped(name, "--waypoints", MAX_WAYPOINT_BYTES)


def _path_options(args):
    """Refuse options of one kind of path given with the other; fill in the defaults."""
    random_given = [k for k in RANDOM_DEFAULTS if getattr(args, k) is not None]
    if args.waypoints is not None:
        if random_given:
            flags = ", ".join("--" + k.replace("_", "-") for k in random_given)
            verb = "belongs" if len(random_given) == 1 else "belong"
            raise GearleverError(f"{flags} {verb} to the random path and cannot be used with --waypoints")
        args.step = DEFAULT_STEP if args.step is None else args.step
    else:
        if args.step is not None:
            raise GearleverError("--step belongs to the way-point path: give it with --waypoints")
        for k, v in RANDOM_DEFAULTS.items():
            if getattr(args, k) is None:
                setattr(args, k, v)
        check_cap(
            f"--turns {args.turns:g} with --steps-per-turn {args.steps_per_turn}",
            args.turns * args.steps_per_turn,
            MAX_STEPS,
        )


def _simulate(args) -> int:
    from gearlever.gears.chariot import parse_waypoints, random_path, simulate, waypoint_path

    _path_options(args)
    d = _design(args)
    if args.waypoints is not None:
        pts = parse_waypoints(_read_waypoints(args.waypoints))
        with progress("chariot simulate: way-point path"):
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
        steps = max(1, round(args.turns * args.steps_per_turn))
        with progress(f"chariot simulate: random path of {steps:,} steps"):
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
