"""The one home for writing model files: a synthesized linkage as a model dict and its TOML text.

Every package that writes a model file (the synthesis kinds, the coupler-curve
library :mod:`gearlever.curves`, the command line, the animation of a
four-bar in :mod:`gearlever.plotting`) builds its dict with the helpers here
and writes it with :func:`model_toml`:

- :func:`model_toml`: the TOML text of a model dict (tables in the schema's
  order, coordinates settled at :data:`COORD_DIGITS` digits of the size);
- the builders of the synthesized linkages: :func:`fourbar_model`,
  :func:`slider_crank_model`, :func:`geared_fivebar_model`,
  :func:`stephenson_sixbar_model`;
- the pieces other writers share: :func:`mechanism_table` (the
  ``[mechanism]`` table) and :func:`xy_pair` (a checked point).

The point and link names follow one convention for every synthesized
four-bar: ``O2`` input (crank) pivot, ``O4`` output (rocker) ground pivot,
``A`` crank pin, ``B`` rocker pin, ``P`` traced point; links ``ground``,
``crank``, ``coupler``, ``rocker``; the crank is the input.  The schema is
that of :mod:`gearlever.mechanism.model`.

Imports only :mod:`gearlever.errors` and :mod:`gearlever._format`.
"""

from __future__ import annotations

import math

from gearlever.errors import GearleverError

__all__ = [
    "fourbar_model",
    "geared_fivebar_model",
    "mechanism_table",
    "model_toml",
    "slider_crank_model",
    "stephenson_sixbar_model",
    "xy_pair",
]

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


def fourbar_model(O2, O4, A, B, P=None, *, name: str = "synthesized four-bar", units: str = "") -> dict:
    """Model dict of a four-bar with the crank as input, in the pose given.

    Parameters
    ----------
    O2, O4, A, B : pair of float
        Crank pivot, rocker pivot, crank pin, rocker pin (sketch positions).
    P : pair of float, optional
        Coupler point (traced point).
    name, units : str
        ``[mechanism]`` name and length unit label.

    Returns
    -------
    dict
        Accepted by :func:`gearlever.mechanism.model_from_dict`.

    Examples
    --------
    >>> from gearlever.mechanism import model_from_dict
    >>> m = model_from_dict(fourbar_model((0, 0), (4, 0), (1, 0), (4.5, 2.8), (3, 4.5)))
    >>> m.moving
    ('crank', 'coupler', 'rocker')
    """
    pts = {"O2": xy_pair("O2", O2), "O4": xy_pair("O4", O4), "A": xy_pair("A", A), "B": xy_pair("B", B)}
    coupler = ["A", "B"]
    if P is not None:
        pts["P"] = xy_pair("P", P)
        coupler.append("P")
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {"ground": ["O2", "O4"], "crank": ["O2", "A"], "coupler": coupler, "rocker": ["O4", "B"]},
        "inputs": [{"link": "crank"}],
    }


def slider_crank_model(
    O2, A, B, direction=(1.0, 0.0), *, name: str = "synthesized slider-crank", units: str = ""
) -> dict:
    """Model dict of a slider-crank with the crank as input, in the pose given.

    Point names: ``O2`` crank pivot, ``A`` crank pin, ``B`` slider pin (wrist
    pin); links ``ground``, ``crank``, ``rod``, ``slider``; the slider moves
    on the ground along ``direction`` through B.

    Parameters
    ----------
    O2, A, B : pair of float
        Sketch positions.
    direction : pair of float
        Direction of the slider line (not zero).
    name, units : str
        ``[mechanism]`` name and length unit label.

    Returns
    -------
    dict
        Accepted by :func:`gearlever.mechanism.model_from_dict`.

    Examples
    --------
    >>> from gearlever.mechanism import model_from_dict
    >>> m = model_from_dict(slider_crank_model((0, 0), (10, 0), (44.641016151378, 5.0)))
    >>> m.moving
    ('crank', 'rod', 'slider')
    """
    u = xy_pair("direction", direction)
    if math.hypot(*u) == 0.0:
        raise GearleverError("direction must not be zero")
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": {"O2": xy_pair("O2", O2), "A": xy_pair("A", A), "B": xy_pair("B", B)},
        "links": {"ground": ["O2"], "crank": ["O2", "A"], "rod": ["A", "B"], "slider": ["B"]},
        "sliders": [{"link": "slider", "on": "ground", "point": "B", "direction": u}],
        "inputs": [{"link": "crank"}],
    }


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise GearleverError(f"a model value must be finite, got {v!r}")
        text = f"{v + 0.0:.{DIGITS}g}"
        return text if any(c in text for c in ".en") else text + ".0"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    raise GearleverError(f"cannot write {type(v).__name__} into a model file")


def _key(k: str) -> str:
    k = str(k)
    return k if k and all(c.isalnum() or c in "_-" for c in k) and k.isascii() else _value(k)


def _settled(model: dict) -> dict:
    """The model with its point coordinates at :data:`COORD_DIGITS` of its size (largest coordinate)."""
    from gearlever._format import rounded

    pts = model.get("points", {})
    coords = [abs(float(c)) for p in pts.values() for c in p if isinstance(c, (int, float))]
    coords = [c for c in coords if math.isfinite(c)]
    size = max(coords) if coords else 0.0
    if size == 0.0:
        return model
    out = dict(model)
    out["points"] = {k: rounded([float(c) for c in v], COORD_DIGITS, size) for k, v in pts.items()}
    return out


def model_toml(model: dict, comment: str = "") -> str:
    """TOML text of a model dict (tables in the order of the schema; arrays of tables as ``[[...]]``).

    Examples
    --------
    >>> import tomllib
    >>> d = fourbar_model((0, 0), (4, 0), (1, 0), (4.5, 2.8))
    >>> tomllib.loads(model_toml(d)) == d
    True
    """
    lines = [f"# {c}" for c in comment.splitlines()] if comment else []
    model = _settled(model)
    for table in ("mechanism", "points", "links", "gears", "masses"):
        if table in model:
            lines += ["", f"[{table}]"] + [f"{_key(k)} = {_value(v)}" for k, v in model[table].items()]
    for array in ("sliders", "meshes", "inputs", "loads"):
        for item in model.get(array, []):
            lines += ["", f"[[{array}]]"] + [f"{_key(k)} = {_value(v)}" for k, v in item.items()]
    return "\n".join(lines).lstrip("\n") + "\n"


def geared_fivebar_model(
    O2, O4, A, B, C, P, teeth, *, name: str = "synthesized geared five-bar", units: str = ""
) -> dict:
    """Model dict of a geared five-bar: two cranks on O2 and O4 coupled by an external gear pair.

    Points ``O2`` input pivot, ``O4`` second crank pivot, ``A`` crank pin,
    ``B`` second crank pin, ``C`` joint of the two couplers, ``P`` traced
    point on the coupler A-C; links ``ground``, ``crank``, ``crank2``,
    ``coupler`` (A, C, P), ``link5`` (B, C); gears ``g1`` on the crank and
    ``g2`` on crank2 with ``teeth = (z1, z2)``, one mesh (the ground carries
    both centres; no module, so the pitch radii follow from the centre
    distance); the crank is the input.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> d = geared_fivebar_model((0, 0), (5, 0), (1, 0), (5, 1.5), (3, 4), (2, 3), (20, 40))
    >>> Mechanism.from_dict(d).structure().dof
    1
    """
    z = [int(t) for t in teeth]
    if len(z) != 2 or min(z) < 1 or any(int(t) != t for t in teeth):
        raise GearleverError(f"teeth must be two positive integers (z1, z2), got {teeth!r}")
    pts = {
        "O2": xy_pair("O2", O2),
        "O4": xy_pair("O4", O4),
        "A": xy_pair("A", A),
        "B": xy_pair("B", B),
        "C": xy_pair("C", C),
        "P": xy_pair("P", P),
    }
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {
            "ground": ["O2", "O4"],
            "crank": ["O2", "A"],
            "crank2": ["O4", "B"],
            "coupler": ["A", "C", "P"],
            "link5": ["B", "C"],
        },
        "gears": {
            "g1": {"link": "crank", "centre": "O2", "teeth": z[0]},
            "g2": {"link": "crank2", "centre": "O4", "teeth": z[1]},
        },
        "meshes": [{"gears": ["g1", "g2"]}],
        "inputs": [{"link": "crank"}],
    }


def stephenson_sixbar_model(
    O2, O4, O6, A, B, C, D, P, *, name: str = "synthesized Stephenson six-bar", units: str = ""
) -> dict:
    """Model dict of a Stephenson III six-bar: a four-bar whose coupler point C drives a dyad C-D-O6.

    Points ``O2, O4, O6`` ground pivots, ``A`` crank pin, ``B`` rocker pin,
    ``C`` on the coupler, ``D`` the dyad's joint, ``P`` traced point on
    ``C-D``; links ``ground`` (O2, O4, O6), ``crank``, ``coupler`` (A, B, C),
    ``rocker``, ``link5`` (C, D, P), ``output`` (O6, D); the crank is the input.

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> d = stephenson_sixbar_model((0, 0), (4, 0), (6, 3), (1, 0), (4.5, 2.8), (2, 3), (5, 5), (3, 5))
    >>> Mechanism.from_dict(d).structure().dof
    1
    """
    names = ("O2", "O4", "O6", "A", "B", "C", "D", "P")
    pts = {n: xy_pair(n, v) for n, v in zip(names, (O2, O4, O6, A, B, C, D, P))}
    mech = mechanism_table(name, units)
    return {
        "mechanism": mech,
        "points": pts,
        "links": {
            "ground": ["O2", "O4", "O6"],
            "crank": ["O2", "A"],
            "coupler": ["A", "B", "C"],
            "rocker": ["O4", "B"],
            "link5": ["C", "D", "P"],
            "output": ["O6", "D"],
        },
        "inputs": [{"link": "crank"}],
    }
