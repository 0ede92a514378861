"""Masses, external loads, gravity and pressure angle of a mechanism model, validated.

Model file tables (kept raw by the model loader in ``MechanismModel.extra``)::

    [mechanism]
    gravity = [0.0, -9.81]          # optional, acceleration of gravity (length/s^2 of the model)
    pressure_angle = 20.0           # optional, degrees, of every gear pair (default 20)
    mesh_efficiency = 0.98          # optional, tooth efficiency of every gear pair (default 1);
                                    # a pair's own [[meshes]] efficiency = ... takes precedence
    [masses]
    crank = { mass = 0.5, centre = "O2", inertia = 0.001 }   # centre: a point of the link, or [x, y] in the sketch
    [[loads]]
    link = "piston"
    point = "B"                     # or [x, y] in the sketch, carried by the link
    force = [-500.0, 0.0]
    [[loads]]
    link = "rocker"
    torque = 5.0

The Python API takes the same loads as a list of dicts whose ``force`` may be
an array ``(N, 2)`` and ``torque`` an array ``(N,)`` over the input rows.

Units. Lengths, and so positions, velocities, accelerations and gravity,
are in the model's length unit ``u`` (``[mechanism] units``); masses are in
kg and moments of inertia in kg u^2.  For a known length unit (m, cm, mm,
km, in, ft) forces are in N and torques in N u, whatever ``u`` is: a model
drawn in mm gives N and N mm, and takes its ``[[loads]]`` in N and N mm
(gravity is then ``[0, -9810]`` mm/s^2).  This is done by giving each mass
and inertia the factor :func:`metres_per_unit` (a mass m in kg times an
acceleration in u/s^2 times metres per u is a force in N).  For a model
without a unit, or with another one, no factor is applied and forces are in
kg u/s^2.  :func:`force_units` names the units.

Imports numpy and :mod:`gearlever.mechanism.schema` only (the loader imports this module).
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from gearlever.errors import GearleverError
from gearlever.mechanism import schema
from gearlever.mechanism.schema import GROUND, MAX_LOAD, MechanismModel

__all__ = [
    "MassSpec",
    "LoadSpec",
    "parse_masses",
    "parse_loads",
    "gravity_of",
    "pressure_angle_of",
    "mesh_efficiency_of",
    "force_units",
    "metres_per_unit",
    "validate_extra",
]

#: Default pressure angle of the gear pairs (rad): 20 degrees.
DEFAULT_PRESSURE_ANGLE = math.radians(20.0)


@dataclass(frozen=True)
class MassSpec:
    """Mass ``mass`` with centre ``centre`` (body-fixed coordinates of the link) and inertia about it."""

    link: str
    mass: float
    centre: tuple
    inertia: float


@dataclass(frozen=True)
class LoadSpec:
    """A force at a body-fixed point and/or a torque on a link; arrays are ``(N, 2)`` and ``(N,)``."""

    label: str
    link: str
    point: tuple | None
    force: np.ndarray | None
    torque: np.ndarray | None


def _num(where, v, nonneg=False, cap=None) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v)):
        raise GearleverError(f"{where} must be a finite number, got {v!r}")
    if nonneg and float(v) < 0:
        raise GearleverError(f"{where} must be >= 0, got {v!r}")
    if cap is not None and abs(float(v)) > cap:
        raise GearleverError(f"{where} must be at most {cap:g} in size (the forces would overflow), got {float(v):g}")
    return float(v)


def _local(model: MechanismModel, link: str, where: str, spec) -> tuple:
    """Body-fixed coordinates of a point name of ``link`` or of a sketch location ``[x, y]``."""
    lk = model.links[link]
    if isinstance(spec, str):
        if spec not in lk.local:
            raise GearleverError(f"{where}: point {spec!r} is not on link {link!r} (its points: {list(lk.points)})")
        return tuple(lk.local[spec])
    if isinstance(spec, (list, tuple, np.ndarray)) and len(spec) == 2:
        x, y = _num(f"{where}[0]", spec[0]), _num(f"{where}[1]", spec[1])
        dx, dy = x - lk.origin[0], y - lk.origin[1]
        c, s = math.cos(lk.angle0), math.sin(lk.angle0)
        return (c * dx + s * dy, -s * dx + c * dy)
    raise GearleverError(f"{where} must be a point name of link {link!r} or a sketch location [x, y], got {spec!r}")


def _link(model: MechanismModel, where: str, name) -> str:
    if not isinstance(name, str) or name not in model.links:
        raise GearleverError(f"{where}: unknown link {name!r}")
    if name == GROUND:
        raise GearleverError(f"{where}: the frame {GROUND!r} does not move (give masses and loads of moving links)")
    return name


def parse_masses(model: MechanismModel, masses=None) -> dict:
    """``{link: MassSpec}`` from ``masses`` (default the model's ``[masses]``); links without one are massless.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [2, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> parse_masses(m, {"crank": {"mass": 3.0, "centre": [1.0, 0.0], "inertia": 0.5}})["crank"].centre
    (1.0, 0.0)

    Notes
    -----
    The returned mass and inertia carry the factor :func:`metres_per_unit`
    of the model's length unit, so that forces come out in N (see the module
    docstring); for a model in m (or without a unit) they are as given.
    """
    raw = model.extra.get("masses", {}) if masses is None else masses
    if not isinstance(raw, dict):
        raise GearleverError("masses must be a table {link = { mass, centre, inertia }}")
    out = {}
    for name, t in raw.items():
        where = f"masses.{name}"
        link = _link(model, where, name)
        if not isinstance(t, dict):
            raise GearleverError(f"{where} must be a table {{ mass, centre, inertia }}, got {t!r}")
        allowed = schema.allowed_keys("masses")
        for k in t:
            if k not in allowed:
                raise GearleverError(f"{where}: unknown key {k!r} (allowed: {', '.join(allowed)})")
        mass = _num(f"{where}.mass", t.get("mass", 0.0), nonneg=True, cap=MAX_LOAD)
        inertia = _num(f"{where}.inertia", t.get("inertia", 0.0), nonneg=True, cap=MAX_LOAD)
        if "centre" in t:
            centre = _local(model, link, f"{where}.centre", t["centre"])
        elif mass == 0.0:
            centre = (0.0, 0.0)
        else:
            raise GearleverError(f"{where}: missing key 'centre' (a point of the link or [x, y])")
        k = metres_per_unit(model)
        out[link] = MassSpec(link, mass * k, centre, inertia * k)
    return out


def _array(where, v, N, shape):
    try:
        a = np.asarray(v, dtype=float)
    except (TypeError, ValueError):
        raise GearleverError(f"{where} must be numbers, got {v!r}") from None
    if not np.all(np.isfinite(a)):
        raise GearleverError(f"{where} must be finite numbers")
    if a.size and float(np.max(np.abs(a))) > MAX_LOAD:
        worst = float(a.flat[int(np.argmax(np.abs(a)))])
        raise GearleverError(f"{where} must be at most {MAX_LOAD:g} in size (the forces would overflow), got {worst:g}")
    full = (N,) + shape
    if a.shape == shape:
        return np.broadcast_to(a, full).copy()
    if a.shape == full:
        return a.copy()
    want = f"{shape}" if not shape else f"{shape} or ({N}, {', '.join(map(str, shape))})"
    raise GearleverError(f"{where} must have shape {want if shape else f'() or ({N},)'}, got {a.shape}")


def parse_loads(model: MechanismModel, loads=None, N: int = 1) -> list:
    """``[LoadSpec]`` from ``loads`` (default the model's ``[[loads]]``), arrays broadcast to ``N`` rows."""
    raw = model.extra.get("loads", []) if loads is None else loads
    if isinstance(raw, dict):
        raw = [raw]
    if not isinstance(raw, (list, tuple)):
        raise GearleverError("loads must be a list of tables {link, point, force} or {link, torque}")
    out = []
    for i, t in enumerate(raw):
        where = f"loads[{i}]"
        if not isinstance(t, dict):
            raise GearleverError(f"{where} must be a table {{link, point, force}} or {{link, torque}}, got {t!r}")
        allowed = schema.allowed_keys("loads")
        for k in t:
            if k not in allowed:
                raise GearleverError(f"{where}: unknown key {k!r} (allowed: {', '.join(allowed)})")
        link = _link(model, f"{where}.link", t.get("link"))
        if "force" not in t and "torque" not in t:
            raise GearleverError(f"{where}: give a force (with its point) or a torque")
        force = point = torque = None
        if "force" in t:
            if "point" not in t:
                raise GearleverError(f"{where}: a force needs its point (a point of link {link!r} or [x, y])")
            point = _local(model, link, f"{where}.point", t["point"])
            force = _array(f"{where}.force", t["force"], N, (2,))
        elif "point" in t:
            raise GearleverError(f"{where}: a point is given but no force")
        if "torque" in t:
            torque = _array(f"{where}.torque", t["torque"], N, ())
        label = f"{link}" + (f"@{t['point']}" if isinstance(t.get("point"), str) else "")
        out.append(LoadSpec(label, link, point, force, torque))
    return out


def gravity_of(model: MechanismModel, gravity=None) -> np.ndarray:
    """Acceleration of gravity ``(2,)``: ``gravity`` or the model's ``[mechanism] gravity`` (default none)."""
    g = model.extra.get("gravity", (0.0, 0.0)) if gravity is None else gravity
    if not isinstance(g, (list, tuple, np.ndarray)) or len(g) != 2:
        raise GearleverError(f"gravity must be a pair of numbers [gx, gy], got {g!r}")
    return np.array([_num("gravity[0]", g[0], cap=MAX_LOAD), _num("gravity[1]", g[1], cap=MAX_LOAD)])


def pressure_angle_of(model: MechanismModel, pressure_angle=None) -> float:
    """Pressure angle (rad): ``pressure_angle`` (rad) or the model's ``pressure_angle`` (deg), default 20 deg."""
    if pressure_angle is None:
        if "pressure_angle" not in model.extra:
            return DEFAULT_PRESSURE_ANGLE
        a = math.radians(_num("mechanism.pressure_angle", model.extra["pressure_angle"]))
        where = "mechanism.pressure_angle (deg)"
    else:
        a = _num("pressure_angle", pressure_angle)
        where = "pressure_angle (rad)"
    if not 0.0 <= a < math.radians(60.0):
        raise GearleverError(f"{where} must be in [0, 60) degrees, got {math.degrees(a):g} deg")
    return a


def mesh_efficiency_of(model: MechanismModel, efficiency=None) -> dict:
    """Tooth efficiency of every mesh, ``{mesh name: eta}``, each in (0, 1].

    ``efficiency``: a number for every mesh, or ``{mesh name: number}`` (the
    others keep the model's value); default the model's: a mesh's own
    ``efficiency`` in ``[[meshes]]``, else ``[mechanism] mesh_efficiency``, else 1.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"mechanism": {"mesh_efficiency": 0.97},
    ...     "points": {"O": [0, 0], "C": [3, 0]}, "links": {"ground": ["O", "C"], "a": ["O"], "b": ["C"]},
    ...     "gears": {"ga": {"link": "a", "centre": "O", "teeth": 20}, "gb": {"link": "b", "centre": "C", "teeth": 40}},
    ...     "meshes": [{"gears": ["ga", "gb"]}], "inputs": [{"link": "a"}]})
    >>> mesh_efficiency_of(m), mesh_efficiency_of(m, {"ga-gb": 0.9})
    ({'ga-gb': 0.97}, {'ga-gb': 0.9})
    """

    def check(where, v):
        x = _num(where, v)
        if not 0.0 < x <= 1.0:
            raise GearleverError(f"{where} must be in (0, 1], got {v!r}")
        return x

    default = 1.0
    if "mesh_efficiency" in model.extra:
        default = check("mechanism.mesh_efficiency", model.extra["mesh_efficiency"])
    out = {}
    for mesh in model.meshes:
        eff = getattr(mesh, "efficiency", None)
        out[mesh.name] = default if eff is None else float(eff)
    if efficiency is None:
        return out
    if isinstance(efficiency, dict):
        for k, v in efficiency.items():
            if k not in out:
                raise GearleverError(f"efficiency: unknown mesh {k!r} (meshes: {', '.join(out) or 'none'})")
            out[k] = check(f"efficiency[{k!r}]", v)
        return out
    x = check("efficiency", efficiency)
    return dict.fromkeys(out, x)


#: Metres per length unit, for the units whose forces are given in N.
METRES_PER_UNIT = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "km": 1e3, "in": 0.0254, "ft": 0.3048}


def _unit(model: MechanismModel) -> str:
    return "".join(c if c.isalnum() else "_" for c in (model.units or "").strip())


def metres_per_unit(model: MechanismModel) -> float:
    """Metres per length unit of the model (1 for a model without a known unit).

    >>> from gearlever.mechanism.model import model_from_dict
    >>> metres_per_unit(model_from_dict({"mechanism": {"units": "mm"}, "points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]}))
    0.001
    """
    return METRES_PER_UNIT.get(_unit(model), 1.0)


def force_units(model: MechanismModel) -> tuple:
    """Names of the force and torque units, ``(force, torque)``, from ``[mechanism] units``.

    For a known length unit ``u`` (see :data:`METRES_PER_UNIT`) forces are in
    N and torques in N u: ``m`` gives ``("N", "N_m")``, ``mm`` gives
    ``("N", "N_mm")``.  Another unit ``u`` gives ``("kg_u_s2", "kg_u_s2_u")``
    (masses in kg, lengths in u), no unit ``("kg_L_s2", "kg_L_s2_L")``.

    >>> from gearlever.mechanism.model import model_from_dict
    >>> force_units(model_from_dict({"mechanism": {"units": "mm"}, "points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]}))
    ('N', 'N_mm')
    """
    u = _unit(model) or "L"
    f = "N" if u in METRES_PER_UNIT else f"kg_{u}_s2"
    return f, f"{f}_{u}"


def validate_extra(model: MechanismModel) -> None:
    """Check the model's ``[masses]``, ``[[loads]]``, ``gravity`` and ``pressure_angle`` (called at load).

    Every sub-command that reads a model file refuses a bad mass or load,
    not only the ones that use them; the messages name the file element
    (``masses.crank.mass``, ``loads[0].link``, ``mechanism.pressure_angle``).
    """
    for key, where in (
        ("masses", "masses"),
        ("loads", "loads"),
        ("gravity", "mechanism.gravity"),
        ("friction", "friction"),
    ):
        if key in model.extra:
            _no_huge_ints(where, model.extra[key])
    _no_huge_ints("mechanism.pressure_angle", model.extra.get("pressure_angle"))
    parse_masses(model)
    parse_loads(model)
    if "gravity" in model.extra:
        g = model.extra["gravity"]
        if not isinstance(g, (list, tuple)) or len(g) != 2:
            raise GearleverError(f"mechanism.gravity must be a pair of numbers [gx, gy], got {g!r}")
        _num("mechanism.gravity[0]", g[0], cap=MAX_LOAD)
        _num("mechanism.gravity[1]", g[1], cap=MAX_LOAD)
    pressure_angle_of(model)
    from gearlever.mechanism.friction import parse_friction

    parse_friction(model)


def _no_huge_ints(where: str, obj) -> None:
    """Refuse an integer too large for a float (``10**400``) anywhere in ``obj``, naming its place."""
    stack = [(where, obj)]
    while stack:
        w, o = stack.pop()
        if isinstance(o, dict):
            stack.extend((f"{w}.{k}", v) for k, v in o.items())
        elif isinstance(o, (list, tuple)):
            stack.extend((f"{w}[{i}]", v) for i, v in enumerate(o))
        elif isinstance(o, int) and not isinstance(o, bool) and abs(o) > 2**1023:
            raise GearleverError(f"{w} must be a finite number, got an integer of {len(str(abs(o)))} digits")
