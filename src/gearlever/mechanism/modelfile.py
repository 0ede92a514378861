"""The one writer of model files: a model dict (or a parsed model) as TOML text.

Every package that writes a model file (the synthesis kinds, the coupler-curve
synthesis :mod:`gearlever.synthesis.curve`, the command line, the animation of a
four-bar in :mod:`gearlever.plotting`) builds its dict (the builders of the
synthesized linkages are in :mod:`gearlever.synthesis.model`) and writes it
with :func:`model_toml`:

- :func:`model_toml`: the TOML text of a model dict, every table the loader
  accepts (``[lengths]`` included) in the order of
  :func:`gearlever.mechanism.schema.write_order`;
- :func:`model_dict`: the dict of a parsed
  :class:`~gearlever.mechanism.schema.MechanismModel`, which the loader reads
  back to the same model (``Mechanism.dumps`` and ``Mechanism.loads``);
- the pieces other writers share: :func:`mechanism_table` (the
  ``[mechanism]`` table) and :func:`xy_pair` (a checked point).

Written files settle the point coordinates at :data:`COORD_DIGITS` digits of
the model's size and other numbers at :data:`DIGITS` significant digits;
``exact=True`` writes every float in its shortest exact form (Python's
``repr``) instead, so that the text reads back to the same floats.

Imports only :mod:`gearlever.errors`, :mod:`gearlever._format` and
:mod:`gearlever.mechanism.schema`.
"""

from __future__ import annotations

import math

from gearlever._format import rounded
from gearlever.errors import GearleverError
from gearlever.mechanism import schema
from gearlever.mechanism.schema import MechanismModel

__all__ = ["COORD_DIGITS", "DIGITS", "mechanism_table", "model_dict", "model_toml", "xy_pair"]

#: Significant digits of other numbers written to a model file.
DIGITS = 15

#: Digits of the model's size at which point coordinates are written
#: (:mod:`gearlever._format`): exact to 1e-9 of the size, which every
#: synthesis meets, and a coordinate that is zero up to rounding is written 0.
COORD_DIGITS = 10


def xy_pair(where: str, p) -> list:
    """A point ``[x, y]`` of a model file: a pair of finite floats (``-0.0`` written ``0.0``).

    Parameters
    ----------
    where : str
        The point's name, in the message of a refusal.
    p : pair of float

    Raises
    ------
    GearleverError
        Naming ``where`` when ``p`` is not a pair of finite numbers.

    Examples
    --------
    >>> xy_pair("A", (1, -0.0))
    [1.0, 0.0]
    >>> try:
    ...     xy_pair("A", (1, float("nan")))
    ... except GearleverError as exc:
    ...     print(exc)
    A must be finite, got (1, nan)
    """
    try:
        x, y = (float(v) for v in p)
    except (TypeError, ValueError):
        raise GearleverError(f"{where} must be a pair of numbers (x, y), got {p!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise GearleverError(f"{where} must be finite, got {p!r}")
    return [x + 0.0, y + 0.0]


def mechanism_table(name: str, units: str) -> dict:
    """The ``[mechanism]`` table of a written model: its name, and its length unit when one is given.

    Examples
    --------
    >>> mechanism_table("crank", ""), mechanism_table("crank", "mm")
    ({'name': 'crank'}, {'name': 'crank', 'units': 'mm'})
    """
    return {"name": name, "units": units} if units else {"name": name}


def _value(v, exact: bool = False) -> str:
    if hasattr(v, "tolist") and not isinstance(v, (bool, int, float, str)):
        v = v.tolist()  # numpy arrays and scalars of the Python API's loads
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise GearleverError(f"a model value must be finite, got {v!r}")
        text = repr(v + 0.0) if exact else f"{v + 0.0:.{DIGITS}g}"
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x, exact) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x, exact)}" for k, x in v.items()) + " }"
    raise GearleverError(f"cannot write {type(v).__name__} into a model file")


def _key(k: str) -> str:
    k = str(k)
    return k if k and all(c.isalnum() or c in "_-" for c in k) and k.isascii() else _value(k)


def _settled(model: dict) -> dict:
    """The model with its point coordinates at :data:`COORD_DIGITS` of its size (largest coordinate)."""
    pts = model.get("points", {})
    coords = [abs(float(c)) for p in pts.values() for c in p if isinstance(c, (int, float))]
    coords = [c for c in coords if math.isfinite(c)]
    size = max(coords) if coords else 0.0
    if size == 0.0:
        return model
    out = dict(model)
    out["points"] = {k: rounded([float(c) for c in v], COORD_DIGITS, size) for k, v in pts.items()}
    return out


def model_toml(model: dict, comment: str = "", *, exact: bool = False) -> str:
    """TOML text of a model dict: its tables in the schema's order, arrays of tables as ``[[...]]``.

    Parameters
    ----------
    model : dict
        The model file's structure (:func:`gearlever.mechanism.model_from_dict`
        reads it); tables the schema does not know are refused.
    comment : str
        Written first, each line as a ``#`` comment.
    exact : bool
        False (default): point coordinates settled at :data:`COORD_DIGITS`
        digits of the model's size, other floats at :data:`DIGITS`
        significant digits.  True: every float in its shortest exact form.

    Examples
    --------
    >>> import tomllib
    >>> d = {"points": {"O": [0.0, 0.0], "A": [1.0, 0.0]}, "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...      "inputs": [{"link": "crank"}], "lengths": {"crank": 2.0}}
    >>> text = model_toml(d)
    >>> print(text.splitlines()[-4:])
    ['crank = 2.0', '', '[[inputs]]', 'link = "crank"']
    >>> tomllib.loads(text) == d
    True
    """
    unknown = [k for k in model if k not in schema.allowed_tables()]
    if unknown:
        raise GearleverError(f"cannot write the table [{unknown[0]}] (allowed: {', '.join(schema.allowed_tables())})")
    lines = [f"# {c}" for c in comment.splitlines()] if comment else []
    if not exact:
        model = _settled(model)
    for name in schema.write_order():
        if name not in model:
            continue
        if schema.table(name).is_array:
            items = model[name]
            for item in [items] if isinstance(items, dict) else items:
                lines += ["", f"[[{name}]]"] + [f"{_key(k)} = {_value(v, exact)}" for k, v in item.items()]
        else:
            lines += ["", f"[{name}]"] + [f"{_key(k)} = {_value(v, exact)}" for k, v in model[name].items()]
    return "\n".join(lines).lstrip("\n") + "\n"


def model_dict(model: MechanismModel) -> dict:
    """The model file's structure of a parsed model: the loader reads it back to the same model.

    Every table the model holds is written: ``[mechanism]`` (name, units,
    module and the kept force settings), points, links, sliders (with their
    names and unit directions), gears, meshes (with their carriers), inputs,
    and the kept tables ``[masses]``, ``[[loads]]``, ``[lengths]`` as read.
    A slider's direction is written as the file gave it (the model holds it
    normalized; normalizing a unit vector again may change its last digit).

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> d = {"points": {"O": [0, 0], "A": [1, 0]}, "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...      "inputs": [{"link": "crank"}]}
    >>> model_dict(model_from_dict(d))["points"]
    {'O': [0.0, 0.0], 'A': [1.0, 0.0]}
    >>> model_from_dict(model_dict(model_from_dict(d))) == model_from_dict(d)
    True
    """
    mech: dict = {"name": model.name}
    if model.units:
        mech["units"] = model.units
    if model.module is not None:
        mech["module"] = model.module
    for k in schema.KEPT_MECHANISM_KEYS:
        if k in model.extra:
            mech[k] = model.extra[k]
    out: dict = {
        "mechanism": mech,
        "points": {k: [float(x), float(y)] for k, (x, y) in model.points.items()},
        "links": {k: list(link.points) for k, link in model.links.items()},
    }
    if model.sliders:
        out["sliders"] = [
            {"name": s.name, "link": s.link, "on": s.on, "point": s.point}
            | {"direction": list(s.direction if s.given is None else s.given)}
            for s in model.sliders
        ]
    if model.gears:
        out["gears"] = {
            k: {"link": g.link, "centre": g.centre, "teeth": g.teeth} | ({"internal": True} if g.internal else {})
            for k, g in model.gears.items()
        }
    if model.meshes:
        out["meshes"] = [
            {"gears": [m.a, m.b], "carrier": m.carrier} | ({} if m.efficiency is None else {"efficiency": m.efficiency})
            for m in model.meshes
        ]
    out["inputs"] = [
        {"slider": i.name}
        if i.kind == "slider"
        else {"link": i.name} | ({} if i.relative_to is None else {"relative_to": i.relative_to})
        for i in model.inputs
    ]
    for k in schema.kept_tables():
        if k in model.extra:
            out[k] = model.extra[k]
    return out
