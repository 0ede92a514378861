"""Coulomb friction at the pins and sliders of a mechanism model: the ``[friction]`` table, validated.

Model file (kept raw by the model loader in ``MechanismModel.extra``)::

    [friction]
    coefficient = 0.15        # Coulomb coefficient of every pin and slider (default: no friction)
    pin_radius = 4.0          # journal radius of every pin (model length unit); pins need a radius
    [friction.pins]           # a pin's own values (by point name), over the defaults above
    B = { coefficient = 0.1, radius = 3.0 }
    [friction.sliders]        # a slider's own coefficient (by slider name)
    guide = { coefficient = 0.2 }

A pin of coefficient ``mu`` and journal radius ``r`` resists the relative
turning of its two links with the torque ``rho |R|``, ``R`` the pin's
reaction and ``rho = r sin(atan mu)`` the radius of its friction circle (the
reaction is tangent to that circle, offset so that its moment opposes the
relative rotation).  A slider resists the relative sliding with the force
``mu |N|`` along the guide, ``N`` the guide's normal force (its moment, from
a block of finite length, is not counted).  Both oppose the relative
motion; at a row where the relative motion stops they are zero (the
friction of rest is not modelled).

Notes
-----
The friction circle: J. J. Uicker, G. R. Pennock and J. E. Shigley, *Theory
of Machines and Mechanisms*, 4th ed., Oxford University Press, 2011,
section 13.8 ("Friction-force models", the friction circle of a pin
joint, ``r_f = r sin phi``, ``tan phi = mu``).

Imports the model schema only.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

from gearlever.errors import GearleverError
from gearlever.mechanism import schema

__all__ = ["FrictionSpec", "parse_friction", "MAX_COEFFICIENT"]

#: Largest Coulomb coefficient accepted: dry metal pairs lie below 1; a larger value is a typing error.
MAX_COEFFICIENT = 1.0
_KEYS = schema.allowed_keys("friction")


@dataclass(frozen=True)
class FrictionSpec:
    """Friction of a model: per pin point its friction-circle radius, per slider its coefficient.

    Attributes
    ----------
    pins : dict
        Point name -> ``(coefficient, journal radius, friction-circle radius)``; pins without friction absent.
    sliders : dict
        Slider name -> coefficient; sliders without friction absent.
    """

    pins: dict
    sliders: dict

    def __bool__(self) -> bool:
        return bool(self.pins or self.sliders)


def _coefficient(where: str, v) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v)):
        raise GearleverError(f"{where} must be a number, got {v!r}")
    if not 0.0 <= float(v) <= MAX_COEFFICIENT:
        raise GearleverError(
            f"{where} must be from 0 to {MAX_COEFFICIENT:g} (a Coulomb coefficient; dry metal pairs lie below 1), "
            f"got {float(v):g}"
        )
    return float(v)


def _radius(where: str, v, cap: float) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not math.isfinite(float(v)):
        raise GearleverError(f"{where} must be a number, got {v!r}")
    if not 0.0 < float(v) <= cap:
        raise GearleverError(f"{where} must be a positive length of at most {cap:g}, got {float(v):g}")
    return float(v)


def _table(where: str, v) -> dict:
    if not isinstance(v, dict):
        raise GearleverError(f"{where} must be a table, got {type(v).__name__}")
    return v


def parse_friction(model, friction=None) -> FrictionSpec:
    """The model's friction (``friction`` given: that table instead of the model's ``[friction]``).

    Refused, naming the element (``friction.pins.B.radius``): an unknown key,
    a pin or slider the model does not have, a coefficient outside
    ``[0, MAX_COEFFICIENT]``, a radius that is not a positive length, a pin
    with a coefficient but no radius.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> spec = parse_friction(m, {"coefficient": 0.2, "pin_radius": 0.05})
    >>> round(spec.pins["O"][2], 9)  # r sin(atan(mu))
    0.009805807
    """
    from gearlever.mechanism.schema import MAX_COORDINATE

    raw = model.extra.get("friction") if friction is None else friction
    if raw is None:
        return FrictionSpec({}, {})
    raw = _table("friction", raw)
    for key in raw:
        if key not in _KEYS:
            from gearlever._io import did_you_mean

            raise GearleverError(
                f"friction: unknown key {key!r}{did_you_mean(key, _KEYS)} (allowed: {', '.join(_KEYS)})"
            )
    mu0 = _coefficient("friction.coefficient", raw["coefficient"]) if "coefficient" in raw else None
    r0 = _radius("friction.pin_radius", raw["pin_radius"], MAX_COORDINATE) if "pin_radius" in raw else None
    joints = sorted({p for p, _a, _b in model.joints})
    own_pins = _table("friction.pins", raw.get("pins", {}))
    for name in own_pins:
        if name not in joints:
            raise GearleverError(f"friction.pins: {name!r} is not a pin of the model (pins: {', '.join(joints)})")
    pins = {}
    for p in joints:
        own = _table(f"friction.pins.{p}", own_pins.get(p, {}))
        for key in own:
            if key not in ("coefficient", "radius"):
                raise GearleverError(f"friction.pins.{p}: unknown key {key!r} (keys: coefficient, radius)")
        mu = _coefficient(f"friction.pins.{p}.coefficient", own["coefficient"]) if "coefficient" in own else mu0
        r = _radius(f"friction.pins.{p}.radius", own["radius"], MAX_COORDINATE) if "radius" in own else r0
        if mu is None or mu == 0.0:
            continue
        if r is None:
            raise GearleverError(
                f"friction.pins.{p}: a coefficient without a journal radius: give friction.pin_radius or "
                f"friction.pins.{p}.radius (or coefficient = 0 for this pin)"
            )
        pins[p] = (mu, r, r * math.sin(math.atan(mu)))
    names = [s.name for s in model.sliders]
    own_sliders = _table("friction.sliders", raw.get("sliders", {}))
    for name in own_sliders:
        if name not in names:
            raise GearleverError(
                f"friction.sliders: {name!r} is not a slider of the model (sliders: {', '.join(names) or 'none'})"
            )
    sliders = {}
    for s in names:
        own = _table(f"friction.sliders.{s}", own_sliders.get(s, {}))
        for key in own:
            if key != "coefficient":
                raise GearleverError(f"friction.sliders.{s}: unknown key {key!r} (key: coefficient)")
        mu = _coefficient(f"friction.sliders.{s}.coefficient", own["coefficient"]) if "coefficient" in own else mu0
        if mu:
            sliders[s] = mu
    return FrictionSpec(pins, sliders)
