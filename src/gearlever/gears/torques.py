"""Torques, frame reactions and power flow of a gear network, exact in fractions.

A network (:class:`gearlever.gears.networks.Network`) ties its members'
rotations by linear constraints ``C rot = 0``.  Treat every constraint as a
massless device (a mesh of teeth, a set of planets on a carrier, a rigid
coupling) that exerts the torque ``-lambda_k * C[k, j]`` on member ``j``.  A
member with the external torque ``T_j`` is in equilibrium when

    ``T_j = sum_k lambda_k C[k, j]``,  i.e.  ``T = C^T lambda``:

the external torques are a combination of the constraint rows, which is the
principle of virtual work (``T . v = 0`` for every admissible motion ``v``,
``C v = 0``).  Given the applied torques, the unknown torques on as many load
members as the network has degrees of freedom follow uniquely; the
multipliers ``lambda`` give the torque each device passes and, for a
constraint that names the frame, the reaction of the frame.

Sign convention: a torque is positive in the positive rotation direction of
its member; power ``T * omega`` is positive when it flows *into* the network
from outside.  An ideal network conserves power exactly: the external powers
sum to zero.

Losses: with a mesh efficiency ``eta < 1``, each device passes on only part of
the power that enters it, charged in the direction the power actually flows
through it, measured in the frame of its carrier (the frame itself for fixed
axes).  See :func:`network_torques`.

Imports only the standard library and :mod:`gearlever.gears.networks`.
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction

from gearlever._result import Result
from gearlever.errors import GearleverError
from gearlever.gears.networks import FRAME, Differential, Mesh, Network, SameShaft

__all__ = ["NetworkTorques", "network_torques", "parse_assignments", "parse_number", "torque_report"]

#: Largest number of direction-fixing passes for a lossy network (each pass is one exact solve).
MAX_PASSES = 32


def _exact(name: str, value) -> Fraction:
    """An exact rational from an int, Fraction, or float (its shortest decimal: 0.98 -> 49/50)."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise GearleverError(f"{name} must be a finite number, got {value!r}")
    if isinstance(value, numbers.Rational):
        return Fraction(value)
    v = float(value)
    if not math.isfinite(v):
        raise GearleverError(f"{name} must be a finite number, got {value!r}")
    return Fraction(repr(v))


def _rref_solve(M: list[list[Fraction]], b: list[Fraction]):
    """Solve ``M z = b`` exactly: (particular solution with free unknowns 0, null-space basis) or None."""
    n_rows = len(M)
    n_cols = len(M[0]) if M else 0
    aug = [list(row) + [rhs] for row, rhs in zip(M, b)]
    pivots: list[int] = []
    r = 0
    for col in range(n_cols):
        p = next((i for i in range(r, n_rows) if aug[i][col]), None)
        if p is None:
            continue
        aug[r], aug[p] = aug[p], aug[r]
        f = aug[r][col]
        aug[r] = [x / f for x in aug[r]]
        for i in range(n_rows):
            if i != r and aug[i][col]:
                g = aug[i][col]
                aug[i] = [x - g * y for x, y in zip(aug[i], aug[r])]
        pivots.append(col)
        r += 1
        if r == n_rows:
            break
    if any(aug[i][n_cols] for i in range(r, n_rows)):
        return None
    z = [Fraction(0)] * n_cols
    for i, col in enumerate(pivots):
        z[col] = aug[i][n_cols]
    free = [j for j in range(n_cols) if j not in set(pivots)]
    null = []
    for f in free:
        v = [Fraction(0)] * n_cols
        v[f] = Fraction(1)
        for i, col in enumerate(pivots):
            v[col] = -aug[i][f]
        null.append(v)
    return z, null


@dataclass(frozen=True)
class _Device:
    """One constraint as a torque-passing device: its row, gear members and carrier."""

    label: str
    row: dict[str, Fraction]  # coefficients on the unknown members (frame dropped)
    gears: tuple[str, ...]  # members whose relative power is charged with losses
    carrier: str | None  # moving carrier (None: fixed axes or a frame carrier)
    touches_frame: bool
    eta: Fraction  # efficiency of the device in its carrier's frame


def _devices(network: Network, eta: Fraction) -> list[_Device]:
    teeth = {g.name: g.teeth for g in network.gears}
    out = []
    for c in network.constraints:
        row = c.terms(teeth)
        members = c.members()
        if isinstance(c, SameShaft):
            out.append(_Device(c.label, row, (), None, FRAME in members, Fraction(1)))
            continue
        if isinstance(c, Differential):
            carrier, gears, k = c.carrier, (c.a, c.b), 2  # two meshes: side gear-planet-side gear
        elif isinstance(c, Mesh):
            carrier, gears, k = getattr(c, "carrier", None), (c.p, c.q), 1
        else:  # a constraint kind this module does not know: ideal, no losses charged
            out.append(_Device(c.label, row, (), None, FRAME in members, Fraction(1)))
            continue
        if carrier == FRAME:
            carrier = None
        gears = tuple(g for g in gears if g != FRAME and g in row)
        out.append(_Device(c.label, row, gears, carrier, FRAME in members, eta**k))
    return out


def _lossy_row(dev: _Device, driven: frozenset[str]) -> dict[str, Fraction]:
    """The device's row with the driven gears' coefficients times its efficiency.

    The carrier's coefficient becomes minus the sum of the gears' ones, so the
    device's torques still balance about the common axis and the power it
    loses is the same in every frame.
    """
    if not driven or dev.eta == 1:
        return dict(dev.row)
    row = dict(dev.row)
    for g in driven:
        row[g] = row[g] * dev.eta
    if dev.carrier is not None:
        row[dev.carrier] = -sum((row[g] for g in dev.gears), Fraction(0))
    return row


@dataclass(frozen=True)
class NetworkTorques(Result):
    """Equilibrium torques and power flow of a network (exact fractions).

    Attributes
    ----------
    torques : {member: torque applied on it from outside}, the applied ones and
        the loads found, in that order.
    frame_reactions : {label: torque of the frame} for every constraint that
        names the frame: the torque the frame exerts on the moving members it
        holds through that constraint (about their axis); None where it is
        statically indeterminate (redundant constraints share it).
    multipliers : {label: lambda} (None where indeterminate); the device exerts
        ``-lambda * row[j]`` on member ``j``.
    speeds : {member: speed} of every member, or None when no speeds were given.
    power : {member: external torque x speed} (power fed in from outside), or None.
    flows : {label: {member: power the device delivers to it}}; None for an
        indeterminate device; empty without speeds.
    rolling_power : {label: power through the device's teeth in its carrier's frame}.
    losses : {label: power lost in the device}, ``(1 - eta_k) * rolling power``.
    throughput : {label: power the device delivers to the members it drives}.
    input_power : sum of the positive external powers.
    circulating : labels whose throughput exceeds the input power (power circulates through them).
    efficiency : the mesh efficiency used.
    """

    torques: Mapping[str, Fraction]
    frame_reactions: Mapping[str, Fraction | None]
    multipliers: Mapping[str, Fraction | None]
    speeds: Mapping[str, Fraction] | None
    power: Mapping[str, Fraction] | None
    flows: Mapping[str, Mapping[str, Fraction] | None]
    rolling_power: Mapping[str, Fraction | None]
    losses: Mapping[str, Fraction]
    throughput: Mapping[str, Fraction | None]
    input_power: Fraction | None
    circulating: tuple[str, ...]
    efficiency: Fraction

    @property
    def total_loss(self) -> Fraction:
        """Sum of the devices' losses (equals the sum of the external powers)."""
        return sum(self.losses.values(), Fraction(0))


def _equilibrium(network, devices, rows, applied, loads):
    """Solve ``T = C'^T lambda`` for lambda and the load torques; flag what is indeterminate."""
    names = network.names
    m = len(devices)
    n_unk = m + len(loads)
    M = []
    rhs = []
    for name in names:
        line = [rows[k].get(name, Fraction(0)) for k in range(m)]
        line += [Fraction(-1) if name == ld else Fraction(0) for ld in loads]
        M.append(line)
        rhs.append(applied.get(name, Fraction(0)))
    if n_unk == 0:
        return [], [], [], []
    sol = _rref_solve(M, rhs)
    if sol is None:
        return None
    z, null = sol
    lam, L = z[:m], z[m:]
    lam_free = [any(v[k] for v in null) for k in range(m)]
    load_free = [any(v[m + i] for v in null) for i in range(len(loads))]
    return lam, L, lam_free, load_free


def network_torques(
    network: Network,
    applied: Mapping[str, object],
    loads: Sequence[str],
    speeds: Mapping[str, object] | None = None,
    efficiency=1,
) -> NetworkTorques:
    """Load torques that hold a gear network in equilibrium, frame reactions and power flow.

    Parameters
    ----------
    network : Network
        The gear network.
    applied : mapping of member name to torque
        Torques applied from outside (e.g. the motor's), positive in the
        member's positive rotation direction.
    loads : sequence of member names
        Members whose torques are unknown, as many as the network's degrees of
        freedom and independent (a set of inputs :meth:`Network.solve` accepts).
    speeds : mapping of member name to speed, optional
        Speeds of as many independent members as the degrees of freedom; every
        member's speed and power follow.  Needed when ``efficiency < 1``
        (the direction of the power flow decides where losses are charged).
    efficiency : number in (0, 1]
        Efficiency of one tooth mesh.  A fixed-axis mesh passes on ``eta`` of
        the power entering it; a differential (side gear, planet, side gear:
        two meshes) passes on ``eta**2`` of the power through its teeth in its
        carrier's frame.  Rigid couplings lose nothing.

    Ints and Fractions are used exactly; a float is read as its shortest
    decimal (``0.98`` as ``49/50``), so results are exact fractions.

    Returns
    -------
    NetworkTorques

    Raises
    ------
    GearleverError
        Unknown members, a torque applied to a load member or the frame, loads
        not independent, efficiency outside (0, 1], efficiency < 1 without
        speeds or in a network with redundant constraints (its internal
        torques are statically indeterminate), or power-flow directions that
        do not settle (a self-locking train).

    Examples
    --------
    A planetary train, sun 20 teeth, ring 80 held by the frame, carrier out:
    the carrier must be held by ``-(1 + 80/20) = -5`` times the sun torque and
    the frame takes the ring's reaction ``80/20 = 4`` times it.

    >>> from gearlever.gears.networks import Differential, Gear, Network, SameShaft
    >>> net = Network([Gear("sun", 20), Gear("ring", 80), Gear("carrier")],
    ...               [Differential("planets", "sun", "ring", "carrier"), SameShaft("held", "ring", "frame")])
    >>> r = network_torques(net, {"sun": 10}, ["carrier"], speeds={"sun": 100})
    >>> r.torques["carrier"], r.frame_reactions["held"], r.speeds["carrier"]
    (Fraction(-50, 1), Fraction(40, 1), Fraction(20, 1))
    >>> sum(r.power.values())
    Fraction(0, 1)

    Notes
    -----
    Equilibrium is the principle of virtual work: ``T . v = 0`` for every
    ``v`` with ``C v = 0``, i.e. ``T = C^T lambda`` (Lagrange multipliers of
    the constraints), solved exactly by Gauss-Jordan elimination over the
    rationals.  The frame's reaction through constraint ``k`` is
    ``-lambda_k * sum_j C'[k, j]``.

    Losses follow the carrier-frame ("relative", or rolling) power method of
    R. H. Macmillan, "Power flow and loss in differential mechanisms",
    Journal of Mechanical Engineering Science 3(1), 1961, pp. 37-41, and
    E. Pennestri and F. Freudenstein, "The mechanical efficiency of epicyclic
    gear trains", ASME Journal of Mechanical Design 115(3), 1993,
    pp. 645-651: seen from its carrier, a device is an ordinary fixed-axis
    train; the member delivering power into its teeth in that frame
    (``lambda_k C[k, j] (omega_j - omega_carrier) > 0``) drives, and the
    driven member's coefficient is multiplied by the device's efficiency;
    the carrier takes minus the sum of the gear coefficients (torque balance
    about the axis).  The loss is then ``(1 - eta_k)`` times the rolling
    power, and the sum of the external powers equals the sum of the losses.
    With a fixed ring, sun in and carrier out, this gives the classical
    ``eta = (1 + eta_0 z_r/z_s) / (1 + z_r/z_s)``.  The directions depend on
    the torques; they are found by repeated exact solves until they settle.
    A device whose gears do not move relative to its carrier loses nothing.
    """
    app, loads, eta, analysis = _checked_torques(network, applied, loads, efficiency)
    spd = _member_speeds(network, speeds, eta, analysis)
    devices = _devices(network, eta)
    rows, lam, L, lam_free = _settled_equilibrium(network, devices, app, loads, spd, eta)
    torques = dict(app)
    torques.update({name: L[i] for i, name in enumerate(loads)})
    multipliers = {d.label: (None if lam_free[k] else lam[k]) for k, d in enumerate(devices)}
    flow = _power_flow(network, devices, rows, lam, lam_free, torques, spd, eta)
    return NetworkTorques(
        torques=torques,
        frame_reactions=_frame_reactions(devices, rows, lam, lam_free),
        multipliers=multipliers,
        speeds=spd,
        **flow,
        efficiency=eta,
    )


def _checked_torques(network, applied, loads, efficiency) -> tuple:
    """``(applied torques, load names, efficiency, the network's analysis)`` of :func:`network_torques`, checked."""
    if not isinstance(network, Network):
        raise GearleverError(f"network must be a Network, got {type(network).__name__}")
    known = set(network.names)
    if not isinstance(applied, Mapping):
        raise GearleverError("applied must be a mapping {member: torque}")
    app: dict[str, Fraction] = {}
    for name, value in applied.items():
        if name == FRAME:
            raise GearleverError(f"applied: a torque on {FRAME!r} is a reaction, not an applied torque")
        if name not in known:
            raise GearleverError(f"applied: unknown member {name!r}")
        app[name] = _exact(f"applied torque on {name!r}", value)
    if isinstance(loads, str):
        loads = [loads]
    loads = tuple(loads)
    analysis = network.analyse()
    for name in loads:
        if name in app:
            raise GearleverError(f"loads: member {name!r} has an applied torque; a load's torque is the unknown")
    _solve_as(network, list(loads), "loads")  # checks names, count (= dof) and independence, naming the constraints
    eta = _exact("efficiency", efficiency)
    if not 0 < eta <= 1:
        raise GearleverError(f"efficiency must be in (0, 1], got {efficiency}")
    return app, loads, eta, analysis


def _member_speeds(network, speeds, eta, analysis) -> dict[str, Fraction] | None:
    """Every member's exact speed from ``speeds`` (None without them); refuses losses that cannot be charged."""
    spd: dict[str, Fraction] | None = None
    if speeds is not None:
        if not isinstance(speeds, Mapping):
            raise GearleverError("speeds must be a mapping {member: speed}")
        given = {str(k): _exact(f"speed of {k!r}", v) for k, v in speeds.items()}
        sol = _solve_as(network, list(given), "speeds")
        spd = {name: Fraction(sol.rotation(name, given)) for name in network.names}
    if eta < 1:
        if spd is None:
            raise GearleverError("speeds must be given when efficiency < 1 (losses follow the power flow)")
        if analysis.redundant:
            raise GearleverError(
                f"efficiency < 1 needs a network without redundant constraints: the torques shared by "
                f"({'), ('.join(analysis.redundant)}) and the constraints they follow from are statically "
                "indeterminate, so the power flow through them is not defined"
            )
    return spd


def _driven_gears(devices, lam, spd) -> list:
    """Per device, the gears driven in its carrier's frame (power out of the teeth) for the multipliers ``lam``."""
    out = []
    for k, d in enumerate(devices):
        if d.eta == 1 or not d.gears or spd is None:
            out.append(frozenset())
            continue
        wc = spd[d.carrier] if d.carrier is not None else Fraction(0)
        rel = {g: lam[k] * d.row[g] * (spd[g] - wc) for g in d.gears}
        if all(p == 0 for p in rel.values()):
            out.append(frozenset())
        else:
            out.append(frozenset(g for g, p in rel.items() if p < 0))
    return out


def _settled_equilibrium(network, devices, app, loads, spd, eta) -> tuple:
    """``(rows, lam, load torques, lam_free)``: the exact equilibrium, re-solved until the power flow settles."""

    def solve_with(driven):
        rows = [_lossy_row(d, driven[k]) for k, d in enumerate(devices)]
        res = _equilibrium(network, devices, rows, app, loads)
        if res is None:
            raise GearleverError("network: no equilibrium with these losses (the train self-locks)")
        return rows, res

    driven = [frozenset()] * len(devices)
    rows, (lam, L, lam_free, load_free) = solve_with(driven)
    if eta < 1:
        seen = {tuple(driven)}
        for _ in range(MAX_PASSES):
            new = _driven_gears(devices, lam, spd)
            if new == driven:
                break
            if tuple(new) in seen:
                raise GearleverError(
                    "efficiency: the power-flow directions do not settle (the train self-locks at this efficiency)"
                )
            seen.add(tuple(new))
            driven = new
            rows, (lam, L, lam_free, load_free) = solve_with(driven)
        else:  # pragma: no cover - bounded by the finite number of direction sets seen
            raise GearleverError("efficiency: the power-flow directions do not settle")
        if _driven_gears(devices, lam, spd) != driven:
            raise GearleverError(
                "efficiency: the power-flow directions do not settle (the train self-locks at this efficiency)"
            )
    if any(load_free):  # pragma: no cover - excluded by network.solve(loads) above
        raise GearleverError(f"loads {list(loads)} are not independent")
    return rows, lam, L, lam_free


def _frame_reactions(devices, rows, lam, lam_free) -> dict:
    """The frame's reaction through each constraint that touches it (None where indeterminate)."""
    frame_reactions = {}
    for k, d in enumerate(devices):
        if d.touches_frame:
            s = sum(rows[k].values(), Fraction(0))
            frame_reactions[d.label] = None if (lam_free[k] and s != 0) else -lam[k] * s
    return frame_reactions


def _power_flow(network, devices, rows, lam, lam_free, torques, spd, eta) -> dict:
    """The power fields of :class:`NetworkTorques` (members' power, flows, rolling power, losses, throughput)."""
    power = flows = None
    rolling: dict[str, Fraction | None] = {}
    losses: dict[str, Fraction] = {}
    throughput: dict[str, Fraction | None] = {}
    input_power = None
    circulating: tuple[str, ...] = ()
    if spd is not None:
        power = {name: torques.get(name, Fraction(0)) * spd[name] for name in network.names}
        input_power = sum((p for p in power.values() if p > 0), Fraction(0))
        fed = [name for name, p in power.items() if p > 0]
        if eta < 1 and len(fed) >= 2 and not any(p < 0 for p in power.values()):
            # every loaded member takes power in: friction holds the train, nothing is driven
            raise GearleverError(
                f"efficiency: the train is self-locking when driven this way: power flows in at every "
                f"loaded member ({', '.join(fed)}) and out at none (at efficiency {float(eta):g})"
            )
        flows = {}
        for k, d in enumerate(devices):
            if lam_free[k]:
                flows[d.label] = rolling[d.label] = throughput[d.label] = None
                losses[d.label] = Fraction(0)
                continue
            f = {name: -lam[k] * c * spd[name] for name, c in rows[k].items()}
            flows[d.label] = f
            throughput[d.label] = sum((p for p in f.values() if p > 0), Fraction(0))
            wc = spd[d.carrier] if d.carrier is not None else Fraction(0)
            rel = [lam[k] * d.row[g] * (spd[g] - wc) for g in d.gears]
            rolling[d.label] = sum((p for p in rel if p > 0), Fraction(0))
            losses[d.label] = -sum(f.values(), Fraction(0)) if d.gears else Fraction(0)
        circulating = tuple(lbl for lbl, t in throughput.items() if t is not None and t > input_power)
    return {
        "power": power,
        "flows": flows if flows is not None else {},
        "rolling_power": rolling,
        "losses": losses,
        "throughput": throughput,
        "input_power": input_power,
        "circulating": circulating,
    }


def _num(x, what: str = "a result"):
    return None if x is None else _float(x, what)


#: Largest finite float: an exact result beyond it cannot be reported as a number.
_FLOAT_MAX = 1.7976931348623157e308


def _magnitude(x: Fraction) -> str:
    """``x`` written as ``3.5e+308`` even beyond the float range (from the exact fraction)."""
    if x == 0:
        return "0"
    e = len(str(abs(x.numerator))) - len(str(x.denominator))
    m = abs(x) / Fraction(10) ** e
    while m >= 10:
        m, e = m / 10, e + 1
    while m < 1:
        m, e = m * 10, e - 1
    return f"{'-' if x < 0 else ''}{float(m):.3g}e{e:+d}"


def _float(x, what: str, cause: str = "applied", whom: str | None = None) -> float:
    """``float(x)`` of an exact result, refusing one beyond the float range and naming it (``what``).

    The message starts with ``cause``, the parameter to make smaller
    (``applied``: the torques; ``speeds``), which the command line turns
    into its flag; ``whom`` says what must be smaller.

    >>> try:
    ...     _float(Fraction(10) ** 309, "the torque on sun")
    ... except GearleverError as exc:
    ...     print(str(exc)[:50])
    applied: the torque on sun comes to 1e+309, beyond
    """
    try:
        v = float(x)
    except OverflowError:
        v = math.inf
    if not math.isfinite(v):
        whom = whom or {"applied": "the applied torques", "speeds": "the speeds"}.get(cause, cause)
        raise GearleverError(
            f"{cause}: {what} comes to {_magnitude(Fraction(x))}, beyond the largest number that can be "
            f"reported ({_FLOAT_MAX:.4g}): {whom} must be smaller"
        )
    return v


def _solve_as(network: Network, names: list, param: str):
    """``network.solve(names)``, its refusals naming ``param`` (``loads``, ``speeds``) instead of "inputs"."""
    try:
        return network.solve(names)
    except GearleverError as exc:
        text = re.sub(r"\binputs\b", param, str(exc))
        raise GearleverError(text if text.startswith(param) else f"{param}: {text}") from None


def torque_report(
    network: Network,
    applied: Mapping[str, object],
    loads: Sequence[str],
    speeds: Mapping[str, object] | None = None,
    efficiency=1,
) -> dict:
    """The JSON-ready dict of ``gearlever network --torque --loads`` (floats, None for indeterminate).

    Keys: ``torques`` (member: torque from outside), ``frame_reactions``
    (constraint label: torque of the frame), ``power`` (member: power fed in
    from outside), and ``speeds``, ``losses``, ``throughput``,
    ``input_power``, ``total_loss``, ``circulating``, ``efficiency``,
    ``indeterminate`` (constraints whose share of torque is not determined).

    >>> from gearlever.gears.networks import Gear, Mesh, Network
    >>> net = Network([Gear("p", 20), Gear("q", 40)], [Mesh("pq", "p", "q")])
    >>> torque_report(net, {"p": 10}, ["q"], speeds={"p": 30})["torques"]
    {'p': 10.0, 'q': 20.0}
    """
    r = network_torques(network, applied, loads, speeds=speeds, efficiency=efficiency)
    out = {
        "torques": {k: _float(v, f"the torque on {k}") for k, v in r.torques.items()},
        "frame_reactions": {k: _num(v, f"the frame reaction ({k})") for k, v in r.frame_reactions.items()},
        "power": None
        if r.power is None
        else {
            k: _float(v, f"the power of {k} (torque x speed)", "applied", "the applied torques or the speeds")
            for k, v in r.power.items()
        },
        "speeds": None
        if r.speeds is None
        else {k: _float(v, f"the speed of {k}", "speeds") for k, v in r.speeds.items()},
        "losses": {k: _float(v, f"the loss of {k}") for k, v in r.losses.items()},
        "throughput": {k: _num(v, f"the throughput of {k}") for k, v in r.throughput.items()},
        "input_power": _num(r.input_power, "the input power"),
        "total_loss": _float(r.total_loss, "the total loss"),
        "circulating": list(r.circulating),
        "efficiency": float(r.efficiency),
        "indeterminate": [k for k, v in r.multipliers.items() if v is None],
    }
    return out


def parse_number(text: str, flag: str) -> Fraction:
    """An exact number from command-line text (``100``, ``2.5``, ``3/4``), the error naming ``flag``.

    >>> parse_number("0.98", "--efficiency")
    Fraction(49, 50)
    """
    try:
        value = Fraction(str(text).strip())
    except (ValueError, ZeroDivisionError):
        raise GearleverError(f"{flag} must be a number (e.g. 100, 2.5 or 3/4), got {text!r}") from None
    return value


def parse_assignments(text: str, flag: str) -> dict[str, Fraction]:
    """``"S=100,C=-2.5"`` as ``{member: exact value}``, the error naming ``flag``.

    >>> parse_assignments("sun=10, ring=1/2", "--torque")
    {'sun': Fraction(10, 1), 'ring': Fraction(1, 2)}
    """
    out: dict[str, Fraction] = {}
    for item in filter(None, (x.strip() for x in str(text).split(","))):
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise GearleverError(f"{flag} must be MEMBER=VALUE pairs separated by commas, got {item!r}")
        if name in out:
            raise GearleverError(f"{flag}: member {name!r} is given twice")
        out[name] = parse_number(value, f"{flag} {name}")
    return out
