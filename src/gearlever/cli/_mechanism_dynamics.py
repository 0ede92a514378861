"""``gearlever mechanism forces|simulate``: input torques, pair forces and motion of a model file.

Sub-commands (added to ``gearlever mechanism`` by :func:`register_dynamics`)::

    gearlever mechanism forces MODEL [--rpm NAME=VALUE ...] [--speed NAME=VALUE ...] [--efficiency ETA]
                                     [--points K] [--format csv|json] [--out FILE]
    gearlever mechanism simulate MODEL --rpm NAME=VALUE ... [--speed NAME=VALUE ...] --time T [--efficiency ETA]
                                     [--torque NAME=VALUE ...] [--points K] [--format csv|json] [--out FILE]

Inputs are named as in the model's ``[[inputs]]`` (a link input by its link,
``link/relative_to`` for a relative one; a slider input by its slider):
``--rpm NAME=VALUE`` once per rotary input (rev/min), ``--speed NAME=VALUE``
once per slider input (model length unit per s).  With one input a bare
``--rpm 100`` is that input's.

``forces``: every input moves at its constant speed from its sketch
position; the rows span one turn of the first rotary input that turns
(end excluded, ``--points`` rows, default 360), every other input moving
at its own speed over that time.  When that input cannot turn fully (it
rocks between two dead points, :func:`gearlever.mechanism.limits.input_limits`)
the rows span one oscillation of it at that speed instead (to one limit,
back to the other, back to the sketch), with a ``direction`` column and its
speed signed by the motion (the reversals are instantaneous: the rows hold
no impulse), and one line on stderr says so.  Without ``--rpm``/``--speed`` every
input moves at 1 rad/s (slider inputs at 1 length unit/s): the torques are
then those at unit input speeds (the speed columns say so: ``NAME_rad_s``
is 1 on every row).  Masses, loads, gravity, pressure angle and mesh
efficiency come from the model file (``[masses]``, ``[[loads]]``,
``[mechanism] gravity, pressure_angle, mesh_efficiency``, ``[[meshes]]
efficiency``); ``--efficiency`` overrides the meshes' efficiency.

``simulate``: starts at the sketch with the speeds of ``--rpm``/``--speed``
(one rotary input that rocks between two dead points: the run is refused, in one line naming the limit and
the time, where the motion comes within :data:`LIMIT_MARGIN` of its range of a limit, since the reduced
inertia grows without bound there; a run that stays away from them says so on stderr and writes a
``direction`` column, the sign of the input's speed.  ``simulate`` integrates the motion the torques
make: a rocking input reverses only where the dynamics turn it back, never at a prescribed limit, since
arriving at a dead point with speed is an impact the rigid model cannot carry through)
(every input given) and integrates the equations of motion for ``--time``
seconds under constant driving torques ``--torque NAME=VALUE`` (force for
a slider input; inputs not named are free, torque 0), with the model's
mesh efficiency or ``--efficiency``; ``work``, ``load_work`` and
``mesh_loss_work`` (lossy meshes; ``loss_work``, meshes and joint friction,
for a model with ``[friction]``) balance the change of kinetic energy.

Joint friction (``[friction]``, :mod:`gearlever.mechanism.friction`):
``forces`` adds each pin's friction torque ``pin_K_friction``, each guide's
friction force ``guide_S_friction`` and the power they dissipate,
``friction_loss``: input power = power of the loads + rate of kinetic energy
+ ``friction_loss`` (+ the meshes' losses).

Units: lengths in the model's ``[mechanism] units``, masses in kg, time
in s; forces are in N and torques in N per length unit for a known unit (N mm with ``"mm"``)
(:func:`gearlever.mechanism.loads.force_units`).  Every column name ends
with its unit (``gear9_torque_N_mm``, ``pin_A_x_N``, ``mesh_z9-z8_N``);
JSON output repeats them under ``"units"``.

Caps: ``--points`` at most :data:`gearlever.mechanism.sweep.MAX_POINTS`;
``simulate`` at most :data:`MAX_TURNS` turns of the fastest input at its
starting speed, and at most :data:`gearlever.mechanism.dynamics.MAX_EVALS`
evaluations of the equations of motion (several inputs).
"""

from __future__ import annotations

import math
import sys

import numpy as np

from gearlever._format import DIGITS_FORCES, DIGITS_SIMULATE
from gearlever._io import table_text
from gearlever.cli._common import capped_int, emit, finite_float, named_values, positive_float, progress
from gearlever.cli._shared import add_branch_argument, load_model, say_branch_points
from gearlever.errors import GearleverError
from gearlever.mechanism.sweep import MAX_POINTS

#: Largest number of input turns ``simulate`` integrates (``--time`` x fastest ``--rpm`` / 60); one input
#: that turns fully uses spline tables (about 0.1 ms a turn), several inputs stop at MAX_EVALS anyway.
MAX_TURNS = 10_000

_POWER = {"N_m": "W", "N_mm": "mW", "N_km": "kW"}


def register_dynamics(ms) -> None:
    f = ms.add_parser("forces", help="input torques and pin, guide and tooth forces at constant input speeds")
    f.add_argument("model", help="model file (TOML) with [masses], [[loads]], gravity")
    f.add_argument(
        "--rpm",
        action="append",
        metavar="NAME=VALUE",
        help="speed of a rotary input (rev/min), once per input; default every input at 1 rad/s",
    )
    f.add_argument("--speed", action="append", metavar="NAME=VALUE", help="speed of a slider input (length/s)")
    f.add_argument("--efficiency", type=finite_float, default=None, help="tooth efficiency of every mesh, (0, 1]")
    f.add_argument(
        "--points",
        type=capped_int(MAX_POINTS),
        default=360,
        help=f"rows over the turn (default 360, at most {MAX_POINTS})",
    )
    f.add_argument("--format", choices=("csv", "json"), default="csv")
    f.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    add_branch_argument(f)
    f.set_defaults(func=_forces)

    s = ms.add_parser("simulate", help="motion under constant input torques (equations of motion in the inputs)")
    s.add_argument("model", help="model file (TOML) with [masses]")
    s.add_argument("--rpm", action="append", metavar="NAME=VALUE", help="initial speed of a rotary input (rev/min)")
    s.add_argument("--speed", action="append", metavar="NAME=VALUE", help="initial speed of a slider input")
    s.add_argument("--time", type=positive_float, required=True, help="simulated time (s)")
    s.add_argument(
        "--torque",
        action="append",
        metavar="NAME=VALUE",
        help="constant driving torque (force, slider input) of an input; inputs not named are free",
    )
    s.add_argument("--efficiency", type=finite_float, default=None, help="tooth efficiency of every mesh, (0, 1]")
    s.add_argument(
        "--points", type=capped_int(MAX_POINTS), default=201, help=f"output rows (default 201, at most {MAX_POINTS})"
    )
    s.add_argument("--format", choices=("csv", "json"), default="csv")
    s.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    s.set_defaults(func=_simulate)


def _names(mech):
    """CLI names of the inputs (in order) and whether each is rotary."""
    out = []
    for spec in mech.model.inputs:
        out.append((spec.label if spec.kind == "link" else spec.name, spec.kind == "link"))
    return out


def _speeds(mech, args, required: bool):
    """Input speeds (W,) in rad/s or length/s from --rpm and --speed; None when neither is given (and allowed)."""
    names = _names(mech)
    rot = [n for n, r in names if r]
    lin = [n for n, r in names if not r]
    if not args.rpm and not args.speed and not required:
        return None
    if args.rpm and not rot:
        raise GearleverError(f"--rpm: model {mech.model.name!r} has no rotary input (slider inputs take --speed)")
    if args.speed and not lin:
        raise GearleverError(f"--speed: model {mech.model.name!r} has no slider input (rotary inputs take --rpm)")
    rpm = named_values(args.rpm, "--rpm", rot, bare_ok=len(names) == 1)
    spd = named_values(args.speed, "--speed", lin, bare_ok=len(names) == 1)
    missing = [n for n in rot if n not in rpm]
    if missing:
        raise GearleverError(f"--rpm: give every rotary input, NAME=VALUE once each (missing: {', '.join(missing)})")
    missing = [n for n in lin if n not in spd]
    if missing:
        raise GearleverError(f"--speed: give every slider input, NAME=VALUE once each (missing: {', '.join(missing)})")
    from gearlever._validate import MAX_SPEED

    for n, r in names:
        v = rpm[n] * math.pi / 30.0 if r else spd[n]
        if abs(v) > MAX_SPEED:
            flag, cap = ("--rpm", f"{MAX_SPEED * 30.0 / math.pi:.3g} rev/min") if r else ("--speed", f"{MAX_SPEED:g}")
            raise GearleverError(
                f"{flag} {n}: must be at most {cap} in size (its square enters the forces), got {rpm[n] if r else v:g}"
            )
    return np.array([rpm[n] * math.pi / 30.0 if r else spd[n] for n, r in names])


def _units(mech):
    from gearlever.mechanism.loads import force_units

    F, T = force_units(mech.model)
    L = T[len(F) + 1 :]
    return L, F, T, _POWER.get(T, f"{T}_per_s"), {"N_m": "J", "N_mm": "mJ", "N_km": "kJ"}.get(T, T)


def force_columns(d, mech, t) -> dict:
    """CLI columns of an :class:`~gearlever.mechanism.dynamics.InverseDynamics` (angles in degrees, units named)."""
    L, F, T, P, _ = _units(mech)
    cols = {"t_s": t}
    for i, (name, rot) in enumerate(_names(mech)):
        if rot:
            cols[f"{name}_deg"] = np.degrees(d.q[:, i])
            cols[f"{name}_rad_s"] = d.qdot[:, i]
        else:
            cols[f"{name}_{L}"] = d.q[:, i]
            cols[f"{name}_{L}_s"] = d.qdot[:, i]
    for i, (name, rot) in enumerate(_names(mech)):
        cols[f"{name}_torque_{T}" if rot else f"{name}_force_{F}"] = d.input_force[:, i]
    for k, v in d.reaction.items():
        cols[f"pin_{k}_x_{F}"], cols[f"pin_{k}_y_{F}"] = v[:, 0], v[:, 1]
    for k, v in d.slider_force.items():
        cols[f"guide_{k}_normal_{F}"] = v
    for k, v in d.mesh_force.items():
        cols[f"mesh_{k}_{F}"] = v
    for k, v in d.mesh_loss.items():
        if np.any(v != 0):
            cols[f"mesh_{k}_loss_{P}"] = v
    for k, v in d.friction_torque.items():
        cols[f"pin_{k}_friction_{T}"] = v
    for k, v in d.friction_force.items():
        cols[f"guide_{k}_friction_{F}"] = v
    if d.friction_loss:
        cols[f"friction_loss_{P}"] = sum(d.friction_loss.values())
    cols[f"ground_fx_{F}"], cols[f"ground_fy_{F}"] = d.ground_force[:, 0], d.ground_force[:, 1]
    return cols


def _write(text, out):
    try:
        emit(text, out)
    except OSError as exc:
        raise GearleverError(f"--out: cannot write the file: {exc.strerror or exc}") from None


def _efficiency(args):
    eff = args.efficiency
    if eff is not None and not 0.0 < eff <= 1.0:
        raise GearleverError(f"--efficiency must be in (0, 1], got {eff:g}")
    return eff


def _forces(args) -> int:
    mech = load_model(args.model)
    names = _names(mech)
    w = _speeds(mech, args, required=False)
    analogue = w is None
    if analogue:
        w = np.ones(len(names))
    if not any(rot for _, rot in names):
        raise GearleverError(
            f"{args.model}: forces needs a rotary input (the rows span one turn of it); this model's inputs are "
            "slider inputs only (use Mechanism.inverse_dynamics)"
        )
    turning = [i for i, (_, rot) in enumerate(names) if rot and w[i] != 0]
    if not turning:
        raise GearleverError("--rpm: no rotary input turns (give one a non-zero speed): the rows span one turn of it")
    i0 = turning[0]
    period = 2 * math.pi / abs(w[i0])
    from gearlever.mechanism.limits import input_limits
    from gearlever.mechanism.sweep import oscillation, sweep_rows

    lim = input_limits(mech, i0, branch=args.branch)
    direction = None
    if lim.full_turn:
        t = np.linspace(0.0, period, args.points, endpoint=False)
        q = mech.sketch_inputs[None, :] + t[:, None] * w[None, :]
        qdot = np.broadcast_to(w, q.shape)
    else:  # one oscillation of the rocking input at its speed, the others at theirs
        if i0 == 0:
            sweep_rows(mech, 2, first=1)  # refuses a locked input, naming the links
        t = 2.0 * (lim.upper - lim.lower) / abs(w[i0]) * np.arange(args.points) / args.points
        q = mech.sketch_inputs[None, :] + t[:, None] * w[None, :]
        v, direction = oscillation(lim.start, lim.lower, lim.upper, args.points, 1 if w[i0] > 0 else -1)
        q[:, i0] = v
        qdot = np.broadcast_to(w, q.shape).copy()
        qdot[:, i0] = abs(w[i0]) * direction
        print(f"{lim.input} rocks between {lim.text()}: sweeping one oscillation", file=sys.stderr)
    eff = _efficiency(args)
    with progress("mechanism forces"):
        try:
            d = mech.inverse_dynamics(q, qdot, np.zeros_like(q), efficiency=eff, branch=args.branch)
        except GearleverError as exc:
            raise _model_element(exc, args.model) from None
    say_branch_points(mech, d.kinematics)
    L, F, T, P, _ = _units(mech)
    meta = {
        "mechanism": mech.model.name,
        "units": {"length": L, "mass": "kg", "time": "s", "force": F, "torque": T, "power": P},
        "speeds": {n: float(w[i]) for i, (n, _) in enumerate(names)},
        "speeds_note": (
            "no --rpm/--speed given: every input at 1 rad/s (slider inputs 1 length unit/s)"
            if analogue
            else "rad/s (rotary), length unit/s (slider), from --rpm/--speed"
        ),
        "turn_of": names[turning[0]][0],
        "indeterminate": list(d.indeterminate),
    }
    cols = force_columns(d, mech, t)
    if direction is not None:
        cols = {"t_s": cols.pop("t_s"), "direction": direction, **cols}
        meta["oscillation"] = {"input": lim.input, "lower": lim.lower, "upper": lim.upper, "unit": "rad"}
    _write(table_text(cols, args.format, meta, digits=DIGITS_FORCES), args.out)
    return 0


def _work_message(exc, args) -> str:
    """The one line for a simulation refused for its work (estimated or capped), naming --time and the cause."""
    from gearlever.mechanism.dynamics import MAX_EVALS

    cause = "at these --rpm" + (" and --torque" if args.torque else "") + " with the model's masses and loads"
    if exc.need == math.inf and exc.count < exc.cap:  # the integrator gave up: steps below the float spacing
        return (
            f"--time {args.time:g}: {cause} the motion cannot be integrated past t = {exc.reached:.3g} s "
            "(its accelerations are out of scale for floating-point time steps): give smaller torques, "
            "loads or speeds"
        )
    if exc.need == math.inf:
        return (
            f"--time {args.time:g}: the motion needs more than {MAX_EVALS} evaluations of its equations "
            f"(the cap on the work of one run; it reached t = {exc.reached:.3g} s): simulate a shorter --time"
        )
    return (
        f"--time {args.time:g}: {cause} the motion needs about {exc.need:.2g} evaluations of its equations, "
        f"more than the cap on the work of one run ({MAX_EVALS}; it reached t = {exc.reached:.3g} s in "
        f"{exc.count}): simulate a shorter --time"
    )


#: Model-file elements that the library's messages start with (the CLI names the file in front).
_ELEMENTS = ("masses.", "loads[", "mechanism.", "gravity")


def _model_element(exc, model: str) -> GearleverError:
    """``exc`` with the model file named in front when it names one of the file's elements."""
    text = str(exc)
    return GearleverError(f"{model}: {text}") if text.startswith(_ELEMENTS) else exc


#: How near (a fraction of its range) a rocking input may come to a limit before ``simulate`` stops: at a dead
#: point of the input its reduced inertia grows without bound and the integration would crawl.
LIMIT_MARGIN = 0.01


def _limit_guard(mech, torque: dict, args):
    """``torque`` as a function that stops the run where a rocking input nears a limit (one rotary input), else as is.

    The input's reduced inertia grows without bound at its dead point, so the integration would crawl
    towards it (a hang); the run is refused in one line naming the limit and the time instead.
    """
    m = mech.model
    if len(m.inputs) != 1 or m.inputs[0].kind != "link":
        return torque
    from gearlever.mechanism.dynamics import _capped_torque
    from gearlever.mechanism.limits import input_limits

    lim = input_limits(mech)
    if not lim.rocks:
        return torque
    label = m.inputs[0].label
    value = _capped_torque(f"torque[{label!r}]", torque.get(label, 0.0))
    margin = LIMIT_MARGIN * (lim.upper - lim.lower)

    def f(t, q, qd):
        if not lim.lower + margin < q < lim.upper - margin:
            edge = lim.upper if q >= lim.upper - margin else lim.lower
            raise GearleverError(
                f"--time {args.time:g}: at t = {t:.4g} s the motion comes within {LIMIT_MARGIN:.0%} of its range "
                f"of the limit {math.degrees(edge):.3f} deg of {lim.input} (a dead point of the input: it rocks "
                f"between {lim.text()}), where it cannot go on; simulate a shorter --time (or other --rpm/--torque)"
            )
        return value

    f.note = f"{lim.input} rocks between {lim.text()}: the run stops short of them ({LIMIT_MARGIN:.0%} of the range)"
    return {label: f}


def _simulate(args) -> int:
    mech = load_model(args.model)
    names = _names(mech)
    w = _speeds(mech, args, required=True)
    turns = args.time * float(np.max(np.abs([w[i] for i, (_, r) in enumerate(names) if r] or [0.0]))) / (2 * math.pi)
    if turns > MAX_TURNS:
        raise GearleverError(f"--time: at these --rpm that is {turns:.6g} turns, at most {MAX_TURNS}")
    labels = [spec.label for spec in mech.model.inputs]
    given = named_values(args.torque, "--torque", [n for n, _ in names])
    torque = {labels[[n for n, _ in names].index(k)]: v for k, v in given.items()}
    t = np.linspace(0.0, args.time, max(args.points, 2))
    eff = _efficiency(args)
    from gearlever.mechanism.dynamics import WorkCapError

    torque = _limit_guard(mech, torque, args)
    with progress("mechanism simulate"):
        try:
            s = mech.simulate(t, mech.sketch_inputs, w, torque=torque, efficiency=eff)
        except WorkCapError as exc:
            raise GearleverError(_work_message(exc, args)) from None
        except GearleverError as exc:
            raise _model_element(exc, args.model) from None
    notes = [getattr(v, "note", None) for v in torque.values()] if isinstance(torque, dict) else []
    for note in filter(None, notes):
        print(note, file=sys.stderr)
    L, F, T, P, E = _units(mech)
    cols = {"t_s": s.t}
    if any(notes):  # a rocking input: the sign of its motion, as the sweeps of a rocking input write it
        cols["direction"] = np.sign(s.qdot[:, 0]).astype(int)
    for i, (name, rot) in enumerate(names):
        if rot:
            cols[f"{name}_deg"] = np.degrees(s.q[:, i])
            cols[f"{name}_rpm"] = s.qdot[:, i] * 30.0 / math.pi
            cols[f"{name}_rad_s2"] = s.qddot[:, i]
            cols[f"{name}_torque_{T}"] = s.torque[:, i]
        else:
            cols[f"{name}_{L}"] = s.q[:, i]
            cols[f"{name}_{L}_s"] = s.qdot[:, i]
            cols[f"{name}_{L}_s2"] = s.qddot[:, i]
            cols[f"{name}_force_{F}"] = s.torque[:, i]
    cols[f"kinetic_energy_{E}"] = s.kinetic_energy
    cols[f"work_{E}"] = s.work
    cols[f"load_work_{E}"] = s.load_work
    if mech.model.extra.get("friction") and np.any(s.loss_work != 0):
        cols[f"loss_work_{E}"] = s.loss_work  # the meshes' and the joints' friction
    elif np.any(s.loss_work != 0):
        cols[f"mesh_loss_work_{E}"] = s.loss_work
    meta = {
        "mechanism": mech.model.name,
        "units": {"length": L, "mass": "kg", "time": "s", "force": F, "torque": T, "energy": E},
        "torque": {n: given.get(n, 0.0) for n, _ in names},
    }
    _write(table_text(cols, args.format, meta, digits=DIGITS_SIMULATE), args.out)
    return 0
