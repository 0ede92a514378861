"""``gearlever mechanism``: structure, kinematic sweep, drawing and animation of a model file (TOML).

Sub-commands::

    gearlever mechanism structure MODEL [--format table|json]
    gearlever mechanism analyze MODEL [--points N] [--input START STOP ...] [--rpm NAME=VALUE ...]
                                      [--format csv|json] [--out FILE] [--centres]
    gearlever mechanism draw MODEL --out FILE.png [--points N] [--input START STOP ...] [--size W H] [--dpi N]
    gearlever mechanism animate MODEL --out FILE.gif [--frames N] [--fps N] [--input START STOP ...]
                                [--size W H] [--dpi N]
    gearlever mechanism assemble MODEL [--out EXACT.toml] [--free-inputs]

The sweep rule (:mod:`gearlever.mechanism.sweep`, in the library; every
command that sweeps uses it, and so does the viewer):

- rows: ``--points`` (default :data:`DEFAULT_POINTS` = 360) for analyze and
  draw, ``--frames`` (default 36) for animate;
- no ``--input``: the *first* input of ``[[inputs]]`` turns one full turn
  from its sketch angle, the end excluded (it would repeat the first row),
  and any other input is held at its sketch value.  An input that cannot
  turn fully (it rocks between two dead points on the sketch's branch)
  sweeps one oscillation instead: sketch, upper limit, lower limit, back to
  the sketch, with a ``direction`` column (+1/-1) and rates signed by the
  motion; one line on stderr says so
  (``AB rocks between 67.284 and 78.254 deg: sweeping one oscillation``);
- ``--input START STOP`` given once per input, in ``[[inputs]]`` order
  (degrees for a link, length for a slider): all inputs move together,
  linearly, from START to STOP, the end included.  Giving it for some
  inputs only is refused, naming the inputs; a range of the one moving
  input past its limits is refused, naming them (exit 2).

Rates (analyze): without ``--rpm`` the columns are *analogues*, derivatives
with respect to the first input (``omega_coupler_per_crank``, rad per rad;
``v_P_x_mm_per_crank``, mm per rad; accelerations ``..._per_crank_sq``): the
first input moves at rate 1, the others at ``(stop_i - start_i) / (stop_1 -
start_1)`` (or 0 when held), and the names end in ``_per_<first input>``
(``_per_sweep``: per unit fraction of the sweep, when the first input does
not move).  With ``--rpm NAME=VALUE`` (once per rotary input; a bare value
for a model with one input) they are velocities and accelerations in time
at those constant input speeds, at every swept position
(``omega_coupler_rad_s``, ``v_P_x_mm_s``; an input not given turns at 0).
Angles are in degrees (``_deg``), angular rates in rad.
Caps: ``--points`` at most :data:`MAX_POINTS`, ``--frames`` at most
:data:`gearlever.cli.animate.MAX_FRAMES`.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from gearlever._io import table_text
from gearlever.cli._common import emit, finite_float, named_values, positive_int, to_json
from gearlever.cli._shared import add_branch_argument, say_branch_points
from gearlever.cli._shared import load_model as _load
from gearlever.errors import GearleverError
from gearlever.mechanism.sweep import (
    DEFAULT_POINTS,
    MAX_POINTS,
    input_labels,
    input_ranges,
    sweep,
)
from gearlever.mechanism.sweep import sweep_rows as _sweep_rows


def register(sub) -> None:
    p = sub.add_parser(
        "mechanism",
        help="any planar mechanism of links, pins, sliders and gears from a TOML model file",
        description="Structure, positions, velocities and accelerations of a mechanism model file (TOML, or a "
        "linkage in the MIT 2.156 challenge's form, .links.json).",
    )
    ms = p.add_subparsers(dest="mechanism_command", metavar="ACTION")
    ms.required = True

    s = ms.add_parser("structure", help="counts n, P5, P4, formula mobility, dof and redundant constraints")
    s.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    s.add_argument("--format", choices=("table", "json"), default="table")
    s.set_defaults(func=_structure)

    a = ms.add_parser("analyze", help="positions, velocities and accelerations over a sweep of the inputs")
    a.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    _sweep_args(a, points=True)
    a.add_argument(
        "--rpm",
        action="append",
        metavar="NAME=VALUE",
        help="speed of a rotary input (rev/min), once per input (a bare VALUE for one input): "
        "velocities in time instead of analogues per unit rate of the first input",
    )
    a.add_argument("--format", choices=("csv", "json"), default="csv")
    a.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    a.add_argument("--centres", action="store_true", help="add the instant centres of every pair of links")
    a.set_defaults(func=_analyze)

    from gearlever.cli.animate import add_animation_args, add_figure_args
    from gearlever.plotting._limits import DRAWING_SIZE

    d = ms.add_parser(
        "draw",
        help="PNG: names, joints, ground, sliders, gears, inputs, loads, point paths and a legend",
        description="Draw the model at its sketch over the paths of its points: link and point names, "
        "pin joints, hatched ground pivots and guides, sliders, gears as pitch circles with their tooth counts, "
        "each input as an arrow, the [[loads]] with their values, gravity, a legend.",
    )
    d.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    d.add_argument("--out", required=True, help="output image (.png, .svg or .pdf)")
    _sweep_args(d, points=True)
    add_figure_args(d, DRAWING_SIZE, 120)
    d.set_defaults(func=_draw)

    g = ms.add_parser(
        "animate",
        help="GIF of the mechanism over the sweep (the one animation of every model)",
        description="A GIF of the model over the sweep, one frame per input row, each frame drawn as "
        "`mechanism draw` draws (names, inputs, loads, legend), 800 x 600 pixels by default "
        "(--size 8 6 at --dpi 100). `gearlever animate --fourbar ...` is the four-bar shortcut.",
    )
    g.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    g.add_argument("--out", required=True, help="output GIF")
    add_animation_args(g)
    _sweep_args(g, points=False)
    g.set_defaults(func=_animate)

    x = ms.add_parser(
        "assemble",
        help="close a rough sketch to the exact lengths of its [lengths] table; write the exact model",
        description="Move the sketch points the least needed to make every [lengths] entry exact, on the "
        "sketch's assembly branch (ground points stay; link inputs keep their sketch angle when they can), "
        "and write the model with exact points as TOML.",
    )
    x.add_argument("model", help="model file (TOML) with a [lengths] table")
    x.add_argument(
        "--out", default=None, help="write the exact model (TOML) to this file (atomically) instead of stdout"
    )
    x.add_argument(
        "--free-inputs",
        action="store_true",
        help="let the inputs move too (default: keep their sketch angles, freed only when the lengths need it)",
    )
    x.set_defaults(func=_assemble)

    from gearlever.cli._mechanism_dynamics import register_dynamics

    register_dynamics(ms)
    from gearlever.cli._mechanism_view import register_view

    register_view(ms)
    from gearlever.cli._mechanism_check import register_check

    register_check(ms)
    from gearlever.cli._mechanism_export import register_export

    register_export(ms)
    from gearlever.cli.synthesize_law import register_mechanism_law

    register_mechanism_law(ms)


def _sweep_args(p, points: bool):
    if points:
        p.add_argument(
            "--points",
            type=positive_int,
            default=DEFAULT_POINTS,
            help=f"input rows (default {DEFAULT_POINTS}, at most {MAX_POINTS})",
        )
    p.add_argument(
        "--input",
        nargs=2,
        action=_InputRange,
        metavar=("[NAME=]START", "STOP"),
        help="range of one input (deg, or length for a slider), end included; once per input, named "
        "(--input crank=0 90) or in [[inputs]] order (default: the first input turns a full turn from the "
        "sketch, the others stay at the sketch)",
    )
    add_branch_argument(p)


class _InputRange(argparse.Action):
    """``--input [NAME=]START STOP`` (appended): one input's range, as ``(name or None, start, stop)``."""

    def __call__(self, parser, namespace, values, option_string=None):
        first, stop = values
        name, sep, start = str(first).rpartition("=") if "=" in str(first) else (None, "", first)
        nums = []
        for v in (start, stop):
            try:
                nums.append(finite_float(v))
            except argparse.ArgumentTypeError as exc:
                raise argparse.ArgumentError(self, str(exc)) from None
        if sep and not name.strip():
            raise argparse.ArgumentError(self, f"an input name must come before '=', got {first!r}")
        items = list(getattr(namespace, self.dest, None) or [])
        items.append((name.strip() if sep else None, nums[0], nums[1]))
        setattr(namespace, self.dest, items)


def sweep_rows(mech, points: int = DEFAULT_POINTS, ranges=None, first: int = 1, branch: str = "continue"):
    """:func:`gearlever.mechanism.sweep.sweep_rows`, saying on stderr when the rows are one oscillation.

    ``AB rocks between 67.284 and 78.254 deg: sweeping one oscillation``: one
    line, when the first input cannot turn fully and no ``--input`` is given.
    """
    s = _sweep_rows(mech, points, ranges, first, branch=branch)
    if s.oscillates:
        print(s.message(), file=sys.stderr)
    return s


def solve_rows(mech, q, qdot, branch: str = "continue"):
    """``mech.solve(q, qdot, branch=branch)``, saying on stderr in one line where the rows passed branch points."""
    r = mech.solve(q, qdot, branch=branch)
    say_branch_points(mech, r)
    return r


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


def _rates(mech, args, q, qdot, direction=None):
    """Rates of analyze: ``(qdot, per)``, analogues per the first input, or velocities from ``--rpm``.

    ``direction`` (an oscillation's +1/-1 per row): the ``--rpm`` are speeds, signed by the motion.
    """
    names = input_labels(mech)
    if not args.rpm:
        ranges = input_ranges(mech, args.input)
        moving_first = ranges is None or ranges[0][0] != ranges[0][1]
        return qdot, (names[0] if moving_first else "sweep")
    rotary = [n for n, spec in zip(names, mech.model.inputs) if spec.kind == "link"]
    if not rotary:
        raise GearleverError(f"--rpm: model {mech.model.name!r} has no rotary input ({', '.join(names)} are sliders)")
    rpm = named_values(args.rpm, "--rpm", rotary)
    rates = np.array([rpm.get(n, 0.0) * math.pi / 30.0 for n in names])
    out = np.broadcast_to(rates, q.shape).copy()
    if direction is not None:
        out[:, 0] = abs(rates[0]) * direction
    return out, None


def with_direction(cols: dict, s, width: int) -> dict:
    """``cols`` with the sweep's ``direction`` column after the first ``width`` (input) columns, when it oscillates."""
    if not s.oscillates:
        return cols
    items = list(cols.items())
    return dict(items[:width] + [("direction", s.direction)] + items[width:])


def _analyze(args) -> int:
    mech = _load(args.model)
    s = sweep_rows(mech, args.points, args.input, branch=args.branch)
    q, qdot = s.q, s.qdot
    qdot, per = _rates(mech, args, q, qdot, s.direction if s.oscillates else None)
    r = solve_rows(mech, q, qdot, args.branch)
    cols = with_direction(r.columns(degrees=True, per=per), s, 3 * len(mech.model.inputs))
    if r.branch_points:  # the assembly branch of each row: +1 the sketch's, -1 the other (0: not closed)
        width = 3 * len(mech.model.inputs) + (1 if s.oscillates else 0)
        items = list(cols.items())
        cols = dict(items[:width] + [("branch", r.side)] + items[width:])
    if args.centres:
        from gearlever.mechanism.centres import centre_columns

        # a centre at infinity (or of a pose that does not close) is empty in CSV, null in JSON
        cols.update({k: [None if math.isnan(x) else x for x in v.tolist()] for k, v in centre_columns(r).items()})
    if args.format == "csv":
        cols["closed"] = r.closed
        cols["reason"] = [s.split(":")[0] for s in r.reason]
        text = table_text(cols, "csv")
    else:
        cols["closed"] = r.closed.tolist()
        cols["reason"] = [s or None for s in r.reason]
        rates = f"analogues per unit rate of {per}" if per else "velocities (rad/s, length/s) at the --rpm speeds"
        text = table_text(cols, "json", {"mechanism": mech.model.name, "rates": rates})
    emit(text, args.out)
    return 0


def _assemble(args) -> int:
    from gearlever.mechanism import assemble
    from gearlever.mechanism.modelfile import model_toml

    mech = _load(args.model)
    exact = assemble(mech.model, hold_inputs=not args.free_inputs)
    lengths = exact.pop("lengths", {})
    moved = max(math.dist(mech.model.points[p], xy) for p, xy in exact["points"].items())
    given = ", ".join(f"{k} = {v}" for k, v in lengths.items())
    comment = (
        f"{mech.model.name}: the sketch of {Path(args.model).name} closed to the lengths {given}\n"
        f"by gearlever mechanism assemble (largest point move {moved:.6g} {mech.model.units or ''})".rstrip()
    )
    emit(model_toml(exact, comment), args.out)
    return 0


def _check_suffix(out, allowed):
    suffix = Path(out).suffix.lower().lstrip(".")
    if suffix not in allowed:
        raise GearleverError(f"--out must end with {' or '.join('.' + a for a in allowed)}, got {out!r}")


def _draw(args) -> int:
    _check_suffix(args.out, ("png", "svg", "pdf"))
    from gearlever.cli.animate import figure_args

    size, dpi = figure_args(args)
    mech = _load(args.model)
    s = sweep_rows(mech, args.points, args.input, branch=args.branch)
    r = solve_rows(mech, s.q, s.qdot, args.branch)
    from gearlever.plotting._common import save
    from gearlever.plotting.mechanism import draw_mechanism

    ax = draw_mechanism(mech, r, figsize=size, note=None if args.input else held_note(mech, s))
    save(ax.figure, args.out, dpi=dpi)
    return 0


def held_note(mech, s=None) -> str | None:
    """What the default sweep of a model with several inputs does, for the drawing: ``None`` with one input.

    With ``s`` (the :class:`~gearlever.mechanism.sweep.Sweep`) one oscillation
    of a rocking first input is named (``paths: AB rocks between ...``).

    The first input turns a full turn and the others stay at their sketch
    values (:func:`sweep`); a drawing says so, since the paths then show the
    motion of the first input alone.

    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> held_note(Mechanism.load(example_path("fivebar_two_inputs.toml")))
    'paths: left turns, right held at 90 deg (sketch)'
    """
    m = mech.model
    rocks = s is not None and s.oscillates
    if len(m.inputs) < 2:
        return f"paths: {s.message().split(':')[0]}, one oscillation" if rocks else None
    names = input_labels(mech)
    held = []
    for name, spec, v in zip(names[1:], m.inputs[1:], mech.sketch_inputs[1:]):
        if spec.kind == "slider":
            value = f"{float(v):.6g}" + (f" {m.units}" if m.units else "")
        else:
            value = f"{math.degrees(float(v)):.6g} deg"
        held.append(f"{name} held at {value}")
    moves = s.message().split(":")[0] if rocks else f"{names[0]} turns"
    return f"paths: {moves}, {', '.join(held)} (sketch)"


def _animate(args) -> int:
    _check_suffix(args.out, ("gif",))
    from gearlever.cli.animate import figure_args

    size, dpi = figure_args(args, args.frames)
    mech = _load(args.model)
    s = sweep_rows(mech, args.frames, args.input, branch=args.branch)
    r = solve_rows(mech, s.q, s.qdot, args.branch)
    paths = mech.solve(*sweep(mech, DEFAULT_POINTS, args.input), branch=args.branch)
    from gearlever.cli._common import progress
    from gearlever.plotting.mechanism import animate_mechanism

    with progress("drawing the frames"):
        animate_mechanism(mech, r, args.out, fps=args.fps, dpi=dpi, figsize=size, paths=paths)
    return 0
