"""``gearlever mechanism``: structure, kinematic sweep, drawing and animation of a model file (TOML).

Sub-commands::

    gearlever mechanism structure MODEL [--format table|json]
    gearlever mechanism analyze MODEL [--points N] [--input START STOP ...] [--format csv|json] [--out FILE]
    gearlever mechanism draw MODEL --out FILE.png [--points N] [--input START STOP ...]
    gearlever mechanism animate MODEL --out FILE.gif [--frames N] [--input START STOP ...]

Sweep: one rotary input turns a full turn from its sketch angle by default;
otherwise ``--input START STOP`` is given once per input, in the order of
``[[inputs]]`` (degrees for a link, length for a slider), and all inputs move
together, linearly, over the points.  Velocities and accelerations are then
derivatives with respect to the first input (rad or length): the other
inputs move at ``(stop_i - start_i) / (stop_1 - start_1)`` (with respect to
the sweep fraction 0..1 if the first input does not move).
Caps: ``--points`` at most :data:`MAX_POINTS`, ``--frames`` at most :data:`MAX_FRAMES`.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gearlever.cli._common import check_input_span, emit, finite_float, positive_int, table_text, to_json
from gearlever.errors import GearleverError

#: Largest ``--points`` accepted (rows of a sweep).
MAX_POINTS = 100_000
#: Largest ``--frames`` accepted (GIF frames).
MAX_FRAMES = 360
DRAW_POINTS = 361


def register(sub) -> None:
    p = sub.add_parser(
        "mechanism",
        help="any planar mechanism of links, pins, sliders and gears from a TOML model file",
        description="Structure, positions, velocities and accelerations of a mechanism model file (TOML).",
    )
    ms = p.add_subparsers(dest="mechanism_command", metavar="ACTION")
    ms.required = True

    s = ms.add_parser("structure", help="counts n, P5, P4, formula mobility, dof and redundant constraints")
    s.add_argument("model", help="model file (TOML)")
    s.add_argument("--format", choices=("table", "json"), default="table")
    s.set_defaults(func=_structure)

    a = ms.add_parser("analyze", help="positions, velocities and accelerations over a sweep of the inputs")
    a.add_argument("model", help="model file (TOML)")
    _sweep_args(a, points=True)
    a.add_argument("--format", choices=("csv", "json"), default="csv")
    a.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    a.set_defaults(func=_analyze)

    d = ms.add_parser("draw", help="PNG: the sketch, joints, gears as pitch circles and the point paths")
    d.add_argument("model", help="model file (TOML)")
    d.add_argument("--out", required=True, help="output image (.png, .svg or .pdf)")
    _sweep_args(d, points=True, default=DRAW_POINTS)
    d.set_defaults(func=_draw)

    g = ms.add_parser("animate", help="GIF of the mechanism over the sweep")
    g.add_argument("model", help="model file (TOML)")
    g.add_argument("--out", required=True, help="output GIF")
    g.add_argument("--frames", type=positive_int, default=36, help=f"frames (default 36, at most {MAX_FRAMES})")
    _sweep_args(g, points=False)
    g.set_defaults(func=_animate)

    from gearlever.cli._mechanism_dynamics import register_dynamics

    register_dynamics(ms)


def _sweep_args(p, points: bool, default: int = 360):
    if points:
        p.add_argument(
            "--points", type=positive_int, default=default, help=f"input rows (default {default}, at most {MAX_POINTS})"
        )
    p.add_argument(
        "--input",
        nargs=2,
        type=finite_float,
        action="append",
        metavar=("START", "STOP"),
        help="range of one input (deg, or length for a slider); once per input, in [[inputs]] order",
    )


def sweep(mech, points: int, ranges=None):
    """Input rows ``q`` (N, W), their rates ``qdot`` and the CLI's input column names."""
    if points > MAX_POINTS:
        raise GearleverError(f"--points must be at most {MAX_POINTS}, got {points}")
    m = mech.model
    W = len(m.inputs)
    conv = [1.0 if spec.kind == "slider" else math.pi / 180.0 for spec in m.inputs]
    if ranges is None:
        if W != 1 or m.inputs[0].kind == "slider":
            raise GearleverError(f"--input START STOP must be given once per input ({W} input(s), in [[inputs]] order)")
        q0 = mech.sketch_inputs[0]
        q = (q0 + np.linspace(0.0, 2 * np.pi, points, endpoint=False))[:, None]
        qdot = np.ones((points, 1))
    else:
        if len(ranges) != W:
            raise GearleverError(f"--input must be given once per input: {W} expected, got {len(ranges)}")
        check_input_span(m, ranges)
        start = np.array([r[0] * c for r, c in zip(ranges, conv)])
        stop = np.array([r[1] * c for r, c in zip(ranges, conv)])
        t = np.linspace(0.0, 1.0, points)
        q = start + t[:, None] * (stop - start)
        span = stop - start
        rates = span / span[0] if span[0] != 0 else span
        qdot = np.broadcast_to(rates, (points, W)).copy()
    return q, qdot


def _load(path):
    from gearlever.mechanism import Mechanism

    return Mechanism.load(path)


def _structure(args) -> int:
    mech = _load(args.model)
    s = mech.structure()
    if args.format == "json":
        d = dict(s.summary())
        d["redundant_constraints"] = list(s.redundant_rows)
        emit(to_json(d))
        return 0
    lines = [f"{k:10s} {v}" for k, v in s.summary().items()]
    lines.append("redundant constraints: " + (", ".join(s.redundant_rows) if s.redundant_rows else "none"))
    emit("\n".join(lines))
    return 0


def _fmt(v) -> str:
    return "nan" if not math.isfinite(v) else f"{v + 0.0:.12g}"  # + 0.0: no "-0"


def _analyze(args) -> int:
    mech = _load(args.model)
    q, qdot = sweep(mech, args.points, args.input)
    r = mech.solve(q, qdot)
    cols = dict(r.columns(degrees=True))
    cols["closed"] = r.closed.astype(bool)
    if args.format == "csv":
        cols["reason"] = [str(x).split(":")[0] for x in r.reason]
    else:
        cols["reason"] = [x or None for x in r.reason]
    text = table_text(cols, args.format, {"mechanism": mech.model.name})
    emit(text, args.out)
    return 0


def _check_suffix(out, allowed):
    suffix = Path(out).suffix.lower().lstrip(".")
    if suffix not in allowed:
        raise GearleverError(f"--out must end with {' or '.join('.' + a for a in allowed)}, got {out!r}")


def _draw(args) -> int:
    _check_suffix(args.out, ("png", "svg", "pdf"))
    mech = _load(args.model)
    r = None
    if args.input is not None or (len(mech.model.inputs) == 1 and mech.model.inputs[0].kind == "link"):
        q, qdot = sweep(mech, args.points, args.input)
        r = mech.solve(q, qdot)
    from gearlever.plotting._common import save
    from gearlever.plotting.mechanism import draw_mechanism

    ax = draw_mechanism(mech, r)
    save(ax.figure, args.out)
    return 0


def _animate(args) -> int:
    _check_suffix(args.out, ("gif",))
    if args.frames > MAX_FRAMES:
        raise GearleverError(f"--frames must be at most {MAX_FRAMES}, got {args.frames}")
    mech = _load(args.model)
    q, qdot = sweep(mech, args.frames, args.input)
    r = mech.solve(q, qdot)
    from gearlever.plotting.mechanism import animate_mechanism

    animate_mechanism(mech, r, args.out)
    return 0
