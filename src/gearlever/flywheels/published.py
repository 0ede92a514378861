"""Published textbook problems of epicyclic torques, engine crank effort and flywheel sizing.

The problem data are read from the package data file ``textbook_dynamics.toml``
and the printed answers from ``textbook_dynamics.csv`` (worked examples of
Khurmi and Gupta's *Theory of Machines*, chapters 13, 15 and 16).  Nothing here
copies an answer: each epicyclic train is a gear network whose holding torques
come from :func:`~gearlever.gears.torques.network_torques`; each engine is built
as a :class:`~gearlever.mechanism.Mechanism` (an in-line slider-crank with its
masses, loads and gravity) and solved by
:meth:`~gearlever.mechanism.Mechanism.inverse_dynamics`; each turning moment is
sampled and integrated by :func:`~gearlever.flywheels.flywheel.flywheel`.
:func:`textbook_checks` sets every computed value beside the published one.
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass

import numpy as np

from gearlever._result import Result
from gearlever.data import read_records, read_text
from gearlever.errors import GearleverError
from gearlever.flywheels.flywheel import flywheel

__all__ = [
    "PROBLEMS",
    "ANSWERS",
    "SAMPLES",
    "TextbookCheck",
    "crank_effort",
    "engine_forces",
    "engine_mechanism",
    "epicyclic_problem",
    "flywheel_problem",
    "problems",
    "textbook_checks",
]

#: Package data files: problem data and published answers.
PROBLEMS = "textbook_dynamics.toml"
ANSWERS = "textbook_dynamics.csv"
#: Samples of one turn of a turning-moment diagram (every 0.01 deg).
SAMPLES = 36001
#: Scale from the SI value (N, N m, W) to the unit of the published answer.
_TO_UNIT = {
    "kN": 1e-3,
    "kN m": 1e-3,
    "kW": 1e-3,
    "N m": 1.0,
    "kg m^2": 1.0,
    "rad/s": 1.0,
    "rad/s^2": 1.0,
    "deg": 1.0,
    "%": 1.0,
}


@dataclass(frozen=True)
class TextbookCheck(Result):
    """Published answers beside the values the model computes, one row per printed answer.

    Attributes
    ----------
    example, quantity, unit, basis : (R,) str arrays: example number, quantity, its unit, why the tolerance.
    page : (R,) page of the example in the book.
    published, computed, tolerance : (R,) values in ``unit``; ``tolerance`` bounds ``|computed - published|``.

    Examples
    --------
    >>> c = textbook_checks()
    >>> len(c.example), str(c.quantity[0]), float(c.published[0]), float(c.computed[0])
    (22, 'holding_torque', 400.0, 400.0)
    """

    example: np.ndarray
    page: np.ndarray
    quantity: np.ndarray
    unit: np.ndarray
    published: np.ndarray
    computed: np.ndarray
    tolerance: np.ndarray
    basis: np.ndarray

    @property
    def deviation(self) -> np.ndarray:
        """``computed - published`` in the answer's unit."""
        return self.computed - self.published

    @property
    def within(self) -> np.ndarray:
        """Rows whose deviation is within their tolerance."""
        return np.abs(self.deviation) <= self.tolerance

    def value(self, example: str, quantity: str) -> tuple[float, float, float]:
        """``(published, computed, tolerance)`` of one answer."""
        hit = np.flatnonzero((self.example == example) & (self.quantity == quantity))
        if hit.size != 1:
            raise GearleverError(f"example {example!r} has no published {quantity!r}")
        i = int(hit[0])
        return float(self.published[i]), float(self.computed[i]), float(self.tolerance[i])


def problems() -> dict:
    """The problem data: ``{"engine": {example: spec}, "flywheel": {example: spec}}``."""
    return tomllib.loads(read_text(PROBLEMS))


def _spec(kind: str, example: str) -> dict:
    table = problems()[kind]
    if example not in table:
        raise GearleverError(f"example must be one of {sorted(table)} for {kind}, got {example!r}")
    return table[example]


def engine_mechanism(spec: dict):
    """In-line horizontal slider-crank of an engine problem, drawn at its crank angle.

    The crank shaft O is at the origin, the line of stroke is the +x axis and the
    crank is at ``crank_angle_deg`` from the inner dead centre (crank along +x).

    Returns
    -------
    (Mechanism, float)
        The model and the crank angle (rad) to solve it at.

    Examples
    --------
    >>> m, th = engine_mechanism({"crank": 0.1, "rod": 0.4, "reciprocating_mass": 1.0, "crank_angle_deg": 90.0})
    >>> sorted(m.model.links), round(th, 6)
    (['crank', 'ground', 'piston', 'rod'], 1.570796)
    """
    from gearlever.mechanism import Mechanism

    r, l = float(spec["crank"]), float(spec["rod"])
    th = math.radians(float(spec["crank_angle_deg"]))
    A = np.array([r * math.cos(th), r * math.sin(th)])
    B = np.array([A[0] + math.sqrt(l * l - A[1] ** 2), 0.0])
    masses = {"piston": {"mass": float(spec["reciprocating_mass"]), "centre": "B"}}
    if "rod_mass" in spec:
        m = float(spec["rod_mass"])
        G = A + float(spec["rod_centre_from_crank_pin"]) / l * (B - A)
        masses["rod"] = {"mass": m, "centre": G.tolist(), "inertia": m * float(spec["rod_radius_of_gyration"]) ** 2}
    model = {
        "mechanism": {"name": "engine", "units": "m", "gravity": [0.0, -float(spec.get("gravity", 0.0))]},
        "points": {"O": [0.0, 0.0], "A": A.tolist(), "B": B.tolist()},
        "links": {"ground": ["O"], "crank": ["O", "A"], "rod": ["A", "B"], "piston": ["B"]},
        "sliders": [{"link": "piston", "on": "ground", "point": "B", "direction": [1.0, 0.0]}],
        "inputs": [{"link": "crank"}],
        "masses": masses,
    }
    return Mechanism.from_dict(model), th


def _omega(spec: dict) -> float:
    """Crank speed of a problem (rad/s) from its ``speed_rpm``."""
    return float(spec["speed_rpm"]) * math.pi / 30.0


def _gas_force(spec: dict) -> float:
    """Net gas force on the piston towards the crank shaft (N)."""
    if "bore" not in spec:
        return 0.0
    area = math.pi / 4.0 * float(spec["bore"]) ** 2
    if "net_pressure" in spec:
        return float(spec["net_pressure"]) * area
    annulus = area - math.pi / 4.0 * float(spec.get("piston_rod", 0.0)) ** 2
    return float(spec["cover_end_pressure"]) * area - float(spec["crank_end_pressure"]) * annulus


def engine_forces(spec: dict, piston_force: float) -> dict[str, float]:
    """Forces of the engine ``spec`` at its crank angle and constant speed under a piston force (SI units).

    ``piston_force`` pushes the piston towards the crank shaft.  ``crank_torque``
    is signed (positive driving the crank forward); the forces are magnitudes.
    See :func:`crank_effort` for the keys.

    Examples
    --------
    A light piston pushed with 1 kN, crank 0.1 m square to the stroke: the rod is
    inclined by ``asin(0.1/0.4)`` and the turning moment is ``F r = 100`` N m.

    >>> spec = {"crank": 0.1, "rod": 0.4, "reciprocating_mass": 1e-9, "crank_angle_deg": 90.0, "speed_rpm": 1e-9}
    >>> f = engine_forces(spec, 1000.0)
    >>> round(f["crank_torque"], 6), round(f["slide_bar_force"], 3)
    (100.0, 258.199)
    """
    mech, th = engine_mechanism(spec)
    omega = _omega(spec)
    loads = [{"link": "piston", "point": "B", "force": [-piston_force, 0.0]}] if piston_force else []
    d = mech.inverse_dynamics([th], [omega], [0.0], loads=loads)
    if not bool(d.ok[0]):
        raise GearleverError("the engine model could not be solved at its crank angle")
    e = np.array([math.cos(th), math.sin(th)])
    pin = d.reaction["A"][0]
    return {
        "crank_torque": -float(d.input_force[0, 0]),
        "slide_bar_force": abs(float(d.slider_force["piston"][0])),
        "rod_thrust": float(np.hypot(*d.reaction["B"][0])),
        "crank_pin_tangential_force": abs(float(pin[0] * -e[1] + pin[1] * e[0])),
        "bearing_thrust": abs(float(pin @ e)),
    }


def crank_effort(example: str) -> dict[str, float]:
    """Forces of an engine problem at its crank angle and constant speed (SI units).

    Returns
    -------
    dict
        ``crank_torque`` (N m, the turning moment gas and inertia give the shaft),
        ``slide_bar_force`` (guide's normal force), ``rod_thrust`` (force at the
        gudgeon pin), ``crank_pin_tangential_force`` and ``bearing_thrust``
        (the crank-pin force across and along the crank), all magnitudes in N;
        ``inertia_torque`` (N m) for a problem without gas force;
        ``flywheel_acceleration`` (rad/s^2) where the problem gives a flywheel
        and a constant resisting power.

    Examples
    --------
    >>> round(crank_effort("15.7")["crank_torque"], 1)
    14489.5

    Notes
    -----
    Inverse dynamics of the slider-crank (d'Alembert): piston effort
    ``F_P = F_L - m_R a_P``, rod thrust ``F_Q = F_P / cos(phi)``, guide force
    ``F_N = F_P tan(phi)``, crank-pin effort ``F_T = F_Q sin(theta + phi)``,
    turning moment ``T = F_T r``; R. S. Khurmi and J. K. Gupta, *Theory of
    Machines*, 14th ed., Eurasia (2009), chapter 15 (piston effort and crank
    effort).  The model's piston acceleration is exact, not the book's
    two-term series.
    """
    spec = _spec("engine", example)
    omega = _omega(spec)
    F = _gas_force(spec)
    out = engine_forces(spec, F)
    torque = out["crank_torque"]
    out["crank_torque"] = abs(torque)
    if not F:
        out["inertia_torque"] = abs(torque)
    if "flywheel" in spec:
        fw = spec["flywheel"]
        resisting = float(fw["power"]) / omega
        out["flywheel_acceleration"] = (torque - resisting) / (float(fw["mass"]) * float(fw["radius_of_gyration"]) ** 2)
    return out


def _series(coef: dict, theta: np.ndarray) -> np.ndarray:
    out = np.full_like(theta, float(coef.get("mean", 0.0)))
    for k, a in coef.get("sin", []):
        out += float(a) * np.sin(k * theta)
    for k, b in coef.get("cos", []):
        out += float(b) * np.cos(k * theta)
    return out


def flywheel_problem(example: str) -> dict[str, float]:
    """Turning-moment results of a flywheel problem over one turn.

    Returns
    -------
    dict
        ``power`` (W), ``energy_fluctuation`` (J), ``inertia`` (kg m^2),
        ``fluctuation_percent``; where an inertia is known the flywheel's
        acceleration ``(T - L)/I``: ``acceleration_at`` (at the problem's
        ``acceleration_at_deg``), and over the first half turn (the
        stationary points the book finds from its quadratic in ``cos theta``)
        ``max_acceleration``, ``max_retardation`` (rad/s^2) and the angles
        ``theta_max_acceleration``, ``theta_min_acceleration`` (deg).

    Examples
    --------
    >>> round(flywheel_problem("16.12")["energy_fluctuation"], 1)
    1204.2

    Notes
    -----
    ``dE = max E - min E`` of ``E = integral (T - L) d theta`` and
    ``I = dE / (omega^2 Cs)``; Khurmi and Gupta, *Theory of Machines*,
    chapter 16.  The diagram is sampled every 0.01 deg and integrated
    exactly for a torque linear between samples (see
    :func:`~gearlever.flywheels.flywheel.flywheel`).
    """
    spec = _spec("flywheel", example)
    theta = np.linspace(0.0, 2.0 * np.pi, SAMPLES)
    torque = _series(spec["torque"], theta)
    load = _series(spec["load"], theta) if "load" in spec else None
    inertia = spec.get("inertia")
    if inertia is None and "mass" in spec:
        inertia = float(spec["mass"]) * float(spec["radius_of_gyration"]) ** 2
    fw = flywheel(
        theta, torque, float(spec["speed_rpm"]), fluctuation=spec.get("fluctuation"), inertia=inertia, load=load
    )
    out = {
        "power": fw.power,
        "energy_fluctuation": fw.energy_fluctuation,
        "inertia": float(fw.inertia),
        "fluctuation_percent": 100.0 * float(fw.fluctuation),
    }
    acc = fw.angular_acceleration
    if "acceleration_at_deg" in spec:
        out["acceleration_at"] = float(np.interp(math.radians(float(spec["acceleration_at_deg"])), theta, acc))
    half = theta <= np.pi
    i_max, i_min = int(np.argmax(acc[half])), int(np.argmin(acc[half]))
    out.update(
        max_acceleration=float(acc[half][i_max]),
        max_retardation=-float(acc[half][i_min]),
        theta_max_acceleration=math.degrees(theta[half][i_max]),
        theta_min_acceleration=math.degrees(theta[half][i_min]),
    )
    return out


def epicyclic_problem(example: str) -> dict[str, float]:
    """Holding torque and output speed of an epicyclic-train problem.

    Returns
    -------
    dict
        ``holding_torque`` (N m, magnitude of the frame's torque on the held
        member), ``output_torque`` (N m, magnitude of the load member's torque)
        and ``output_speed`` (the load member's speed, in the unit of the
        input speed).

    Examples
    --------
    >>> epicyclic_problem("13.20")["holding_torque"]
    400.0

    Notes
    -----
    Equilibrium of the train by virtual work on the network's exact
    constraints (:func:`~gearlever.gears.torques.network_torques`): the
    external torques sum to zero and their power does too; Khurmi and Gupta,
    *Theory of Machines*, chapter 13 (torques in epicyclic gear trains).
    """
    from gearlever.gears.networks import parse_network
    from gearlever.gears.torques import network_torques

    spec = _spec("epicyclic", example)
    net = parse_network(spec["network"])
    w = float(spec["input_speed"])
    torque = float(spec["input_torque"]) if "input_torque" in spec else float(spec["power"]) / w
    t = network_torques(net, {spec["input"]: torque}, [spec["load"]], speeds={spec["input"]: w})
    return {
        "holding_torque": abs(float(t.frame_reactions[spec["held"]])),
        "output_torque": abs(float(t.torques[spec["load"]])),
        "output_speed": float(t.speeds[spec["load"]]),
    }


_SOLVERS = {"engine": crank_effort, "flywheel": flywheel_problem, "epicyclic": epicyclic_problem}


def textbook_checks() -> TextbookCheck:
    """Every published answer of ``textbook_dynamics.csv`` beside the model's value.

    Examples
    --------
    >>> c = textbook_checks()
    >>> bool(c.within.all()), sorted(set(c.example))[:3]
    (True, ['13.20', '13.22', '15.12'])
    """
    rows = read_records(ANSWERS)
    kind_of = {ex: kind for kind, table in problems().items() for ex in table}
    cache: dict[str, dict] = {}
    computed = []
    for row in rows:
        ex = row["example"]
        if ex not in kind_of:
            raise GearleverError(f"example {ex} has published answers but no problem data")
        if ex not in cache:
            cache[ex] = _SOLVERS[kind_of[ex]](ex)
        if row["quantity"] not in cache[ex]:
            raise GearleverError(f"example {ex}: the model gives no {row['quantity']!r}")
        computed.append(cache[ex][row["quantity"]] * _TO_UNIT[row["unit"]])

    def col(key, kind=object):
        return np.array([r[key] for r in rows], dtype=kind)

    return TextbookCheck(
        example=col("example"),
        page=col("page", int),
        quantity=col("quantity"),
        unit=col("unit"),
        published=col("published", float),
        computed=np.array(computed),
        tolerance=col("tolerance", float),
        basis=col("basis"),
    )
