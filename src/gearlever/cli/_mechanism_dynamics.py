"""``gearlever mechanism forces|simulate``: input torque, pair forces and motion of a model file.

Sub-commands (added to ``gearlever mechanism`` by :func:`register_dynamics`)::

    gearlever mechanism forces MODEL --rpm N [--points K] [--format csv|json] [--out FILE]
    gearlever mechanism simulate MODEL --rpm N --time T [--torque X] [--points K] [--format csv|json] [--out FILE]

``forces``: the single rotary input turns once at constant speed from its
sketch angle; masses, loads, gravity and pressure angle come from the model
file (``[masses]``, ``[[loads]]``, ``[mechanism] gravity, pressure_angle``).
``simulate``: starts at the sketch at ``--rpm`` and integrates the motion
under the constant input torque ``--torque`` for ``--time`` seconds.
Caps: ``--points`` at most :data:`gearlever.cli.mechanism.MAX_POINTS`,
``--time`` times the speed at most :data:`MAX_TURNS` input turns.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever.cli._common import emit, finite_float, positive_float, positive_int, to_json
from gearlever.errors import GearleverError

#: Largest number of input turns ``simulate`` integrates (``--time`` x ``--rpm`` / 60).
MAX_TURNS = 10_000


def register_dynamics(ms) -> None:
    f = ms.add_parser("forces", help="input torque and pin, guide and tooth forces over a turn at constant speed")
    f.add_argument("model", help="model file (TOML) with [masses], [[loads]], gravity")
    f.add_argument("--rpm", type=finite_float, required=True, help="speed of the rotary input (rev/min)")
    f.add_argument("--points", type=positive_int, default=360, help="input rows over the turn (default 360)")
    f.add_argument("--format", choices=("csv", "json"), default="csv")
    f.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    f.set_defaults(func=_forces)

    s = ms.add_parser("simulate", help="motion under a constant input torque (reduced-inertia equation)")
    s.add_argument("model", help="model file (TOML) with [masses]")
    s.add_argument("--rpm", type=finite_float, required=True, help="initial speed of the input (rev/min)")
    s.add_argument("--time", type=positive_float, required=True, help="simulated time (s)")
    s.add_argument("--torque", type=finite_float, default=0.0, help="constant input torque (default 0)")
    s.add_argument("--points", type=positive_int, default=201, help="output rows (default 201)")
    s.add_argument("--format", choices=("csv", "json"), default="csv")
    s.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    s.set_defaults(func=_simulate)


def _one_rotary(mech):
    m = mech.model
    if len(m.inputs) != 1 or m.inputs[0].kind != "link":
        raise GearleverError(f"--rpm needs a model with one rotary input; {m.name!r} has {len(m.inputs)} input(s)")


def _fmt(v) -> str:
    return "nan" if not math.isfinite(v) else f"{v + 0.0:.12g}"


def _table(cols: dict, fmt: str, meta: dict) -> str:
    names = list(cols)
    arr = np.column_stack([np.asarray(cols[k], dtype=float) for k in names])
    if fmt == "csv":
        lines = [",".join(names)] + [",".join(_fmt(v) for v in row) for row in arr.tolist()]
        return "\n".join(lines)
    return to_json({**meta, "rows": [dict(zip(names, row)) for row in arr.tolist()]})


def force_columns(d) -> dict:
    """CLI columns of an :class:`~gearlever.mechanism.dynamics.InverseDynamics` (input angle in degrees)."""
    cols = {"input_deg": np.degrees(d.q[:, 0]), "input_torque": d.input_force[:, 0]}
    for k, v in d.reaction.items():
        cols[f"pin_{k}_x"], cols[f"pin_{k}_y"] = v[:, 0], v[:, 1]
    for k, v in d.slider_force.items():
        cols[f"guide_{k}_normal"] = v
    for k, v in d.mesh_force.items():
        cols[f"mesh_{k}"] = v
    cols["ground_fx"], cols["ground_fy"] = d.ground_force[:, 0], d.ground_force[:, 1]
    return cols


def _write(text, out):
    try:
        emit(text, out)
    except OSError as exc:
        raise GearleverError(f"--out: cannot write the file: {exc.strerror or exc}") from None


def _forces(args) -> int:
    from gearlever.cli.mechanism import MAX_POINTS, _load

    if args.points > MAX_POINTS:
        raise GearleverError(f"--points must be at most {MAX_POINTS}, got {args.points}")
    mech = _load(args.model)
    _one_rotary(mech)
    w = args.rpm * math.pi / 30.0
    q = mech.sketch_inputs[0] + np.linspace(0.0, 2 * np.pi, args.points, endpoint=False)
    d = mech.inverse_dynamics(q, np.full_like(q, w), np.zeros_like(q))
    meta = {"mechanism": mech.model.name, "rpm": args.rpm, "indeterminate": list(d.indeterminate)}
    _write(_table(force_columns(d), args.format, meta), args.out)
    return 0


def _simulate(args) -> int:
    from gearlever.cli.mechanism import MAX_POINTS, _load

    if args.points > MAX_POINTS:
        raise GearleverError(f"--points must be at most {MAX_POINTS}, got {args.points}")
    turns = args.time * abs(args.rpm) / 60.0
    if turns > MAX_TURNS:
        raise GearleverError(f"--time: at --rpm {args.rpm:g} that is {turns:.6g} turns, at most {MAX_TURNS}")
    mech = _load(args.model)
    _one_rotary(mech)
    t = np.linspace(0.0, args.time, max(args.points, 2))
    s = mech.simulate(t, mech.sketch_inputs[0], args.rpm * math.pi / 30.0, torque=args.torque)
    cols = {
        "t": s.t,
        "input_deg": np.degrees(s.q),
        "rpm": s.qdot * 30.0 / math.pi,
        "alpha": s.qddot,
        "kinetic_energy": s.kinetic_energy,
    }
    meta = {"mechanism": mech.model.name, "torque": args.torque}
    _write(_table(cols, args.format, meta), args.out)
    return 0
