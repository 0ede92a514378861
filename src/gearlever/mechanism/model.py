"""Mechanism model files: loading and validation.

The tables, keys, types and caps are declared once in
:mod:`gearlever.mechanism.schema`; this module reads a model against them
(the summary below is the schema's, in words).  The writer is
:mod:`gearlever.mechanism.modelfile`.

A planar mechanism is described as data (a TOML file, or the same structure
as a dict): named sketch points, rigid links carrying points, sliders, gears,
meshes and inputs.  :func:`load_model` and :func:`model_from_dict` check every
element and return a :class:`MechanismModel`, a frozen dataclass holding the
parsed data (links with their body-fixed coordinates, joints, sliders, gears,
meshes, inputs).  Every refusal is a :class:`~gearlever.errors.GearleverError`
whose message names the element (``links.crank``, ``meshes[2]``...) and what
is wrong.

Schema (top-level tables)::

    [mechanism]  name, units, module; gravity, pressure_angle, mesh_efficiency (kept in extra)
    [points]     NAME = [x, y]
    [links]      NAME = ["P1", "P2", ...]        (the link "ground" is the frame)
    [[sliders]]  link, on, point, direction [, name]
    [gears]      NAME = { link, centre, teeth [, internal] [, shift] [, face_width] [, helix] }
    [[meshes]]   gears = ["a", "b"] [, carrier] [, efficiency (0, 1], see mechanism.dynamics)]
    [[inputs]]   link [, relative_to]   or   slider
    [lengths]    LINK = length   or   "LINK.P-Q" = length   (see below)
    [masses], [[loads]]   kept raw in MechanismModel.extra, validated at load
                          (gearlever.mechanism.loads.validate_extra)

Names of points, links, sliders and gears (and the ``units`` label) must
match :data:`NAME_PATTERN`: a letter (any script: ``O2``, ``кривошип``,
``曲柄``) or ``_`` first, then letters, digits, ``_``, ``-`` or ``.``, at most
:data:`MAX_NAME` characters.  A name may not start with a digit, so that it
never reads as a number in a table, and holds no comma, quote, ``=``, space or
control character, so that it is safe in a CSV header, a ``NAME=VALUE``
flag, a JSON key and a figure label.  Two elements whose result columns
(``{link}_deg``, ``{point}_x_{units}``, ``{slider}_s_{units}``,
``in_{input}_deg``...) would share a name are refused, naming both.

Caps (a file beyond any real mechanism is refused naming the cap, before it
can make the analysis hang): file size :data:`MAX_MODEL_BYTES`, nesting depth
:data:`MAX_DEPTH`, :data:`MAX_LINKS` links, :data:`MAX_POINTS` points,
:data:`MAX_ELEMENTS` sliders, gears, meshes or inputs each, teeth at most
:data:`MAX_TEETH`, coordinates at most :data:`MAX_COORDINATE` in size, and
no link shorter than ``1 /`` :data:`MAX_SCALE_RATIO` of the model's size.

Tooth geometry (optional, read by :mod:`gearlever.mechanism.mesh_check` and
:mod:`gearlever.export`): ``[mechanism] module`` (the normal module of a
helical gear) and ``pressure_angle`` (deg, default 20); per gear ``shift``
(profile shift coefficient x, a number in [-:data:`MAX_SHIFT`,
:data:`MAX_SHIFT`], default 0), ``face_width`` (> 0, model units) and
``helix`` (helix angle, deg, in [0, 45), default 0; the two gears of a mesh
have the same).  With a module, a mesh's centre distance must be the tight
(zero-backlash) working centre distance of its teeth, shifts and helix
(ISO 21771:2007, eq. for the working pressure angle ``inv alpha_wt = inv
alpha_t + 2 tan alpha_n (x_1 + x_2) / (z_1 + z_2)``); without shifts and helix
that is ``m (z_1 +- z_2) / 2``.

``[lengths]`` (optional) gives exact link lengths for a rough sketch, read by
:func:`gearlever.mechanism.assemble.assemble`: ``crank = 10.0`` is the
distance between the first two points of link ``crank``; ``"coupler.A-P" =
30.0`` (or, unquoted, ``coupler.A-P = 30.0``) the distance between points
``A`` and ``P`` of link ``coupler``.
Values are positive numbers in the model's length unit; each pair of points
at most once.  The loader checks the names and values
(:func:`parse_lengths`) and keeps the table raw in ``MechanismModel.extra``;
solving uses the sketch as it is.

Standard library and numpy only.
"""

from __future__ import annotations

import math
import numbers
import tomllib
from pathlib import Path

from gearlever._io import read_text_capped
from gearlever.errors import GearleverError
from gearlever.mechanism import schema
from gearlever.mechanism.loads import validate_extra
from gearlever.mechanism.schema import (
    GROUND,
    MAX_COORDINATE,
    MAX_DEPTH,
    MAX_ELEMENTS,
    MAX_HELIX_DEG,
    MAX_LABEL,
    MAX_LINKS,
    MAX_MODEL_BYTES,
    MAX_NAME,
    MAX_POINTS,
    MAX_SCALE_RATIO,
    MAX_SHIFT,
    MAX_TEETH,
    NAME_PATTERN,
    GearSpec,
    InputSpec,
    Link,
    MechanismModel,
    MeshSpec,
    Slider,
)

__all__ = [
    "GROUND",
    "parse_lengths",
    "parse_poses",
    "Link",
    "Slider",
    "GearSpec",
    "MeshSpec",
    "tight_centre_distance",
    "InputSpec",
    "MechanismModel",
    "load_model",
    "model_from_dict",
    "model_from_text",
    # the caps, declared in gearlever.mechanism.schema
    "MAX_COORDINATE",
    "MAX_DEPTH",
    "MAX_ELEMENTS",
    "MAX_LINKS",
    "MAX_MODEL_BYTES",
    "MAX_NAME",
    "MAX_POINTS",
    "MAX_SCALE_RATIO",
    "MAX_TEETH",
    "NAME_PATTERN",
]

NEWLINE = b"\n"


# --------------------------------------------------------------------------- helpers
def _is_num(v) -> bool:
    return isinstance(v, numbers.Real) and not isinstance(v, bool)


def _short(v) -> str:
    """``repr(v)``, cut to 60 characters (a 400-digit integer is not echoed whole)."""
    text = repr(v)
    return text if len(text) <= 60 else text[:57] + "..."


def _num(where: str, v) -> float:
    if not _is_num(v):
        raise GearleverError(f"{where} must be a number, got {_short(v)}")
    try:
        f = float(v)
    except OverflowError:
        f = math.inf
    if not math.isfinite(f):
        raise GearleverError(f"{where} must be a finite number, got {_short(v)}")
    return f


def _name(where: str, v) -> str:
    """``v`` if it is a safe element name (:data:`NAME_PATTERN`), else refuse naming ``where``."""
    if not isinstance(v, str):
        raise GearleverError(f"{where}: a name must be a string, got {_short(v)}")
    if len(v) > MAX_NAME or NAME_PATTERN.fullmatch(v) is None:
        raise GearleverError(
            f"{where}: name {_short(v)} must start with a letter or _ and hold only letters, digits, _ - . "
            f"(at most {MAX_NAME} characters; no spaces, commas, quotes, = or control characters)"
        )
    return v


def _count(where: str, n: int, cap: int) -> None:
    if n > cap:
        raise GearleverError(f"{where}: {n} entries, more than the cap of {cap}")


#: Tables of gearlever's other input files, each with the command that reads it.
_OTHER_FILES = {
    "cam": ": this is a CAM file, not a model: open it with gearlever cam view",
    "law": ": this is a LAW file, not a model: use it with gearlever cam design or gearlever synthesize law",
}


def depth(obj, cap: int = MAX_DEPTH) -> int:
    """Nesting depth of lists and dicts in ``obj`` (1 for a flat dict), refusing beyond ``cap``.

    Iterative (no recursion), so that any structure can be measured.

    >>> depth({"a": [1, {"b": [2]}]})
    4
    """
    deepest = 0
    stack = [(obj, 1)]
    while stack:
        o, d = stack.pop()
        if isinstance(o, (dict, list, tuple)):
            if d > cap:
                raise GearleverError(f"nested deeper than the cap of {cap} levels of arrays and tables")
            deepest = max(deepest, d)
            stack.extend((v, d + 1) for v in (o.values() if isinstance(o, dict) else o))
    return deepest


def _str(where: str, v) -> str:
    if not isinstance(v, str) or not v:
        raise GearleverError(f"{where} must be a non-empty string, got {_short(v)}")
    return v


def _label(where: str, v) -> str:
    """A free-text label (mechanism name): one line, no control characters, at most 200 characters."""
    v = _str(where, v)
    if len(v) > MAX_LABEL or any(ord(c) < 32 or 127 <= ord(c) < 160 for c in v):
        raise GearleverError(f"{where} must be one line of at most {MAX_LABEL} characters without control characters")
    return v


def _table(where: str, v, allowed, required=()) -> dict:
    if not isinstance(v, dict):
        raise GearleverError(f"{where} must be a table, got {type(v).__name__}")
    for k in v:
        if not isinstance(k, str):
            raise GearleverError(f"{where}: keys must be strings, got {_short(k)}")
        if k not in allowed:
            raise GearleverError(f"{where}: unknown key {k!r} (allowed: {', '.join(allowed)})")
    for k in required:
        if k not in v:
            raise GearleverError(f"{where}: missing key {k!r}")
    return v


def _array_of_tables(where: str, v) -> list:
    if isinstance(v, dict):
        v = [v]
    if not isinstance(v, list) or not all(isinstance(t, dict) for t in v):
        raise GearleverError(f"{where} must be an array of tables ([[{where}]])")
    return v


def _vec2(where: str, v) -> tuple:
    if not isinstance(v, (list, tuple)) or len(v) != 2:
        raise GearleverError(f"{where} must be a pair of numbers [x, y], got {_short(v)}")
    return (_num(f"{where}[0]", v[0]), _num(f"{where}[1]", v[1]))


def _coords(where: str, v) -> tuple:
    x, y = _vec2(where, v)
    if max(abs(x), abs(y)) > MAX_COORDINATE:
        raise GearleverError(f"{where}: coordinates must be at most {MAX_COORDINATE:g} in size, got {_short(v)}")
    return (x, y)


# --------------------------------------------------------------------------- loading
def load_model(path) -> MechanismModel:
    """Read and validate a mechanism model file (TOML).

    Parameters
    ----------
    path : str or path-like

    Returns
    -------
    MechanismModel

    Raises
    ------
    GearleverError
        Unreadable file, TOML syntax error (with its line and column), or any
        element refused by :func:`model_from_dict`; the message starts with
        the file name.

    Notes
    -----
    The file is parsed with the standard library's ``tomllib`` (TOML 1.0,
    T. Preston-Werner, *TOML: Tom's Obvious Minimal Language*).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "m.toml"
    >>> _ = p.write_text('[points]\\nO = [0, 0]\\nA = [1, 0]\\n[links]\\nground = ["O"]\\n'
    ...                  'crank = ["O", "A"]\\n[[inputs]]\\nlink = "crank"\\n')
    >>> load_model(p).moving
    ('crank',)
    """
    p = Path(path)
    return model_from_text(read_text_capped(p, "model file", MAX_MODEL_BYTES), where=str(p))


def model_from_text(text: str, where: str | None = None) -> MechanismModel:
    """Parse and validate the TOML text of a model file.

    Parameters
    ----------
    text : str
        At most :data:`MAX_MODEL_BYTES` bytes in UTF-8.
    where : str, optional
        The text's origin (a file name), prefixed to every refusal.

    Returns
    -------
    MechanismModel

    Raises
    ------
    GearleverError
        Text beyond the size cap, TOML syntax error (with its line and
        column), or any element refused by :func:`model_from_dict`.

    Examples
    --------
    >>> model_from_text('[points]\\nO = [0, 0]\\nA = [1, 0]\\n[links]\\nground = ["O"]\\n'
    ...                 'crank = ["O", "A"]\\n[[inputs]]\\nlink = "crank"\\n').moving
    ('crank',)
    """
    prefix = f"{where}: " if where else ""
    if not isinstance(text, str):
        raise GearleverError(f"{prefix}a model's text must be a string, got {type(text).__name__}")
    raw = text.encode("utf-8", "surrogatepass")
    if len(raw) > MAX_MODEL_BYTES:
        raise GearleverError(f"{prefix}{len(raw)} bytes, more than the cap of {MAX_MODEL_BYTES} bytes of a model file")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        msg = str(exc).splitlines()[0] if str(exc) else "invalid TOML"
        if "line" not in msg:
            msg += f" (line {raw.count(NEWLINE) + 1})"
        raise GearleverError(f"{prefix}TOML syntax error: {msg}") from None
    except RecursionError:
        # tomllib parses nested arrays and inline tables recursively
        raise GearleverError(f"{prefix}nested deeper than the cap of {MAX_DEPTH} levels of arrays and tables") from None
    try:
        return model_from_dict(data)
    except GearleverError as exc:
        raise GearleverError(f"{prefix}{exc}") from None


def model_from_dict(d) -> MechanismModel:
    """Validate a model given as a dict (the TOML file's structure) and parse it.

    The steps, each a function: the top-level tables (:func:`_read_tables`),
    ``[mechanism]`` (:func:`_read_mechanism`), points, links and their
    joints, sliders, gears, meshes, inputs, then the kept tables (``[lengths]``
    here, masses and loads by :func:`gearlever.mechanism.loads.validate_extra`).
    The allowed tables and keys come from :mod:`gearlever.mechanism.schema`.

    Parameters
    ----------
    d : dict
        Top-level tables as in the module docstring.

    Returns
    -------
    MechanismModel

    Raises
    ------
    GearleverError
        Naming the element and what is wrong: unknown table or key, unknown
        point in a link, a link with no points, missing ground, a link not
        joined to ground, a gear centre not on its link, a mesh with no
        carrier or two, a centre distance that does not match the module, an
        input on ground, a slider whose point is not on its link or whose
        guide is on the sliding link itself, a zero direction, non-finite
        numbers.

    Notes
    -----
    A point carried by ``k >= 2`` links is a revolute joint, ``k - 1`` lower
    pairs (Artobolevsky's counting, as in the planar Chebyshev-Grubler
    formula).

    Examples
    --------
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...                      "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...                      "inputs": [{"link": "crank"}]})
    >>> m.joints
    (('O', 'ground', 'crank'),)
    """
    extra = _read_tables(d)
    name, units, module = _read_mechanism(d, extra)
    points = _read_points(d)
    links = _read_links(d, points)
    moving = tuple(n for n in links if n != GROUND)
    if not moving:
        raise GearleverError("[links]: the mechanism needs at least one moving link besides ground")
    joints = _joints(points, links)
    sliders = _read_sliders(d, points, links)
    _check_connected(links, joints, sliders)
    gears = _read_gears(d, points, links)
    meshes = _read_meshes(d, points, links, gears, module)
    inputs = _read_inputs(d, links, sliders)
    # [lengths]: checked here, used by gearlever.mechanism.assemble (kept raw in extra)
    if "lengths" in d:
        parse_lengths(d["lengths"], links)
    # [[poses]]: checked here, used by motion synthesis (kept raw in extra)
    if "poses" in d:
        parse_poses(d["poses"])
    _check_columns(points, links, sliders, inputs, units)
    model = MechanismModel(
        name=name,
        units=units,
        module=module,
        points=points,
        links=links,
        moving=moving,
        joints=tuple(joints),
        sliders=tuple(sliders),
        gears=gears,
        meshes=tuple(meshes),
        inputs=tuple(inputs),
        extra=extra,
    )
    validate_extra(model)
    return model


def _read_tables(d) -> dict:
    """Check the top-level tables against the schema; return the kept ones (``extra``)."""
    if not isinstance(d, dict):
        raise GearleverError(f"model must be a table (dict), got {type(d).__name__}")
    depth(d)
    allowed = schema.allowed_tables()
    for k in d:
        if not isinstance(k, str):
            raise GearleverError(f"table names must be strings, got {_short(k)}")
        if k not in allowed:
            raise GearleverError(f"unknown table [{k}] (allowed: {', '.join(allowed)}){_OTHER_FILES.get(k, '')}")
    return {k: d[k] for k in schema.kept_tables() if k in d}


def _read_mechanism(d, extra: dict) -> tuple:
    """``(name, units, module)`` of ``[mechanism]``; its force settings go into ``extra``."""
    mech = _table("[mechanism]", d.get("mechanism", {}), schema.allowed_keys("mechanism"))
    name = _label("mechanism.name", mech["name"]) if "name" in mech else "mechanism"
    units = _name("mechanism.units", mech["units"]) if "units" in mech else ""
    module = None
    if "module" in mech:
        module = _num("mechanism.module", mech["module"])
        if module <= 0:
            raise GearleverError(f"mechanism.module must be positive, got {mech['module']!r}")
    for k in schema.KEPT_MECHANISM_KEYS:
        if k in mech:
            extra[k] = mech[k]
    return name, units, module


def _read_points(d) -> dict:
    """Point name -> sketch position, from ``[points]``."""
    if "points" not in d:
        raise GearleverError("missing table [points]")
    pts = d["points"]
    if not isinstance(pts, dict) or not pts:
        raise GearleverError("[points] must be a non-empty table of NAME = [x, y]")
    _count("[points]", len(pts), MAX_POINTS)
    return {_name("[points]", k): _coords(f"points.{k}", v) for k, v in pts.items()}


def _read_links(d, points: dict) -> dict:
    """Link name -> :class:`Link`, from ``[links]`` (ground present, scale checked)."""
    if "links" not in d:
        raise GearleverError("missing table [links]")
    lk = d["links"]
    if not isinstance(lk, dict) or not lk:
        raise GearleverError("[links] must be a non-empty table of NAME = [points]")
    if len(lk) - (GROUND in lk) > MAX_LINKS:
        raise GearleverError(f"[links]: {len(lk) - (GROUND in lk)} moving links, more than the cap of {MAX_LINKS}")
    for k in lk:
        _name("[links]", k)
    if GROUND not in lk:
        raise GearleverError('[links]: missing the frame link "ground"')
    links = {}
    for lname, plist in lk.items():
        where = f"links.{lname}"
        if not isinstance(plist, list):
            raise GearleverError(f"{where} must be a list of point names, got {_short(plist)}")
        if not plist:
            raise GearleverError(f"{where}: a link must carry at least one point")
        seen = []
        for p in plist:
            if not isinstance(p, str):
                raise GearleverError(f"{where}: point names must be strings, got {_short(p)}")
            if p not in points:
                raise GearleverError(f"{where}: unknown point {p!r}")
            if p in seen:
                raise GearleverError(f"{where}: point {p!r} listed twice")
            seen.append(p)
        links[lname] = _make_link(lname, tuple(seen), points)
    _check_scale(points, links)
    return links


def _joints(points: dict, links: dict) -> list:
    """Revolute pairs ``(point, first carrier, other carrier)``; every point must be carried."""
    carried: dict = {p: [] for p in points}
    for n, link in links.items():
        for p in link.points:
            carried[p].append(n)
    joints = []
    for p, carriers in carried.items():
        if not carriers:
            raise GearleverError(f"points.{p}: no link carries this point (list it in a link of [links], or remove it)")
        for other in carriers[1:]:
            joints.append((p, carriers[0], other))
    return joints


def _read_sliders(d, points: dict, links: dict) -> list:
    """The :class:`Slider` of each ``[[sliders]]``."""
    sliders = []
    stab = _array_of_tables("sliders", d.get("sliders", []))
    _count("[[sliders]]", len(stab), MAX_ELEMENTS)
    for i, t in enumerate(stab):
        where = f"sliders[{i}]"
        _table(where, t, schema.allowed_keys("sliders"), schema.required_keys("sliders"))
        link = _str(f"{where}.link", t["link"])
        on = _str(f"{where}.on", t["on"])
        for k, v in (("link", link), ("on", on)):
            if v not in links:
                raise GearleverError(f"{where}.{k}: unknown link {v!r}")
        sname = _name(f"{where}.name", t["name"]) if "name" in t else link
        where = f"sliders[{i}] ({sname})"
        if on == link:
            raise GearleverError(f"{where}: the guide must be on another link than the sliding link {link!r}")
        point = _str(f"{where}.point", t["point"])
        if point not in points:
            raise GearleverError(f"{where}.point: unknown point {point!r}")
        if point not in links[link].local:
            raise GearleverError(f"{where}.point: point {point!r} is not on the sliding link {link!r}")
        ux, uy = _vec2(f"{where}.direction", t["direction"])
        norm = math.hypot(ux, uy)
        if not norm > 0 or not math.isfinite(norm):
            raise GearleverError(f"{where}.direction must be a non-zero vector, got {t['direction']!r}")
        if any(s.name == sname for s in sliders):
            raise GearleverError(f"{where}: slider name {sname!r} used twice (give each a name)")
        sliders.append(Slider(sname, link, on, point, (ux / norm, uy / norm), (ux, uy)))
    return sliders


def _read_gears(d, points: dict, links: dict) -> dict:
    """Gear name -> :class:`GearSpec`, from ``[gears]``."""
    gtab = d.get("gears", {})
    if not isinstance(gtab, dict):
        raise GearleverError("[gears] must be a table of NAME = { link, centre, teeth }")
    _count("[gears]", len(gtab), MAX_ELEMENTS)
    gears = {}
    for gname, t in gtab.items():
        _name("[gears]", gname)
        where = f"gears.{gname}"
        _table(where, t, schema.allowed_keys("gears"), schema.required_keys("gears"))
        link = _str(f"{where}.link", t["link"])
        if link not in links:
            raise GearleverError(f"{where}.link: unknown link {link!r}")
        centre = _str(f"{where}.centre", t["centre"])
        if centre not in points:
            raise GearleverError(f"{where}.centre: unknown point {centre!r}")
        if centre not in links[link].local:
            raise GearleverError(f"{where}.centre: point {centre!r} is not on the gear's link {link!r}")
        z = t["teeth"]
        if isinstance(z, bool) or not isinstance(z, int) or z < 1 or z > MAX_TEETH:
            raise GearleverError(f"{where}.teeth must be a positive integer at most {MAX_TEETH}, got {_short(z)}")
        internal = t.get("internal", False)
        if not isinstance(internal, bool):
            raise GearleverError(f"{where}.internal must be true or false, got {internal!r}")
        shift = _num(f"{where}.shift", t["shift"]) if "shift" in t else 0.0
        if abs(shift) > MAX_SHIFT:
            raise GearleverError(f"{where}.shift must be in [-{MAX_SHIFT:g}, {MAX_SHIFT:g}], got {_short(t['shift'])}")
        width = None
        if "face_width" in t:
            width = _num(f"{where}.face_width", t["face_width"])
            if not 0.0 < width <= MAX_COORDINATE:
                raise GearleverError(f"{where}.face_width must be positive, got {_short(t['face_width'])}")
        helix = _num(f"{where}.helix", t["helix"]) if "helix" in t else 0.0
        if not 0.0 <= helix < MAX_HELIX_DEG:
            raise GearleverError(f"{where}.helix must be in [0, {MAX_HELIX_DEG:g}) deg, got {_short(t['helix'])}")
        gears[gname] = GearSpec(gname, link, centre, int(z), internal, shift, width, math.radians(helix))
    return gears


def _read_meshes(d, points: dict, links: dict, gears: dict, module) -> list:
    """The :class:`MeshSpec` of each ``[[meshes]]`` (carrier found, centre distance checked against the module)."""
    meshes = []
    mech = d.get("mechanism") if isinstance(d.get("mechanism"), dict) else {}
    pa = mech.get("pressure_angle", 20.0)  # validated later (loads.validate_extra); 20 deg meanwhile if out of range
    alpha = math.radians(float(pa)) if _is_num(pa) and 0.0 < pa < 60.0 else math.radians(20.0)
    mtab = _array_of_tables("meshes", d.get("meshes", []))
    _count("[[meshes]]", len(mtab), MAX_ELEMENTS)
    for i, t in enumerate(mtab):
        where = f"meshes[{i}]"
        _table(where, t, schema.allowed_keys("meshes"), schema.required_keys("meshes"))
        pair = t["gears"]
        if not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(g, str) for g in pair):
            raise GearleverError(f"{where}.gears must be a pair of gear names, got {pair!r}")
        a, b = pair
        where = f"meshes[{i}] ({a}-{b})"
        for g in (a, b):
            if g not in gears:
                raise GearleverError(f"{where}: unknown gear {g!r}")
        if a == b:
            raise GearleverError(f"{where}: a gear cannot mesh with itself")
        ga, gb = gears[a], gears[b]
        if ga.internal and gb.internal:
            raise GearleverError(f"{where}: two internal gears cannot mesh")
        if ga.link == gb.link:
            raise GearleverError(f"{where}: both gears are on the same link {ga.link!r}")
        carrier = _mesh_carrier(where, t, links, ga, gb)
        if ga.helix != gb.helix:
            raise GearleverError(
                f"{where}: the helix angles differ ({math.degrees(ga.helix):g} and {math.degrees(gb.helix):g} deg)"
            )
        if module is not None:
            _check_module(where, points, module, ga, gb, alpha)
        eff = None
        if "efficiency" in t:
            eff = _num(f"{where}.efficiency", t["efficiency"])
            if not 0.0 < eff <= 1.0:
                raise GearleverError(f"{where}.efficiency must be in (0, 1], got {t['efficiency']!r}")
        meshes.append(MeshSpec(f"{a}-{b}", a, b, carrier, eff))
    return meshes


def _mesh_carrier(where: str, t: dict, links: dict, ga: GearSpec, gb: GearSpec) -> str:
    """The mesh's carrier: the one given, or the one link carrying both centres."""
    centres = {ga.centre, gb.centre}
    if "carrier" in t:
        carrier = _str(f"{where}.carrier", t["carrier"])
        if carrier not in links:
            raise GearleverError(f"{where}.carrier: unknown link {carrier!r}")
        if not centres <= set(links[carrier].local):
            raise GearleverError(f"{where}.carrier: link {carrier!r} does not carry both gear centres")
        return carrier
    cands = [n for n in links if centres <= set(links[n].local)]
    if not cands:
        raise GearleverError(f"{where}: no carrier (no link carries both centres {ga.centre}, {gb.centre})")
    if len(cands) > 1:
        raise GearleverError(f"{where}: two or more carriers {cands}; name one with carrier = ...")
    return cands[0]


def _check_module(where: str, points: dict, module: float, ga: GearSpec, gb: GearSpec, alpha: float) -> None:
    """Refuse a centre distance that is not the pair's tight one to 1e-6 relative.

    Unshifted spur gears: ``m (z_a +- z_b) / 2``; with shifts or a helix, the
    working centre distance (:func:`tight_centre_distance`).
    """
    dist = math.dist(points[ga.centre], points[gb.centre])
    internal = ga.internal or gb.internal
    try:
        want = tight_centre_distance(module, ga, gb, alpha)
    except GearleverError as exc:
        raise GearleverError(f"{where}: {exc}") from None
    if abs(dist - want) > 1e-6 * max(want, 1.0):
        shifted = ga.shift != 0 or gb.shift != 0 or ga.helix != 0
        plain = f"m (z_a {'-' if internal else '+'} z_b) / 2"
        rule = "the working centre distance of its shifts and helix" if shifted else plain
        raise GearleverError(
            f"{where}: centre distance {dist:.9g} does not match module {module:g}: {rule} = {want:.9g}"
        )


def _read_inputs(d, links: dict, sliders: list) -> list:
    """The :class:`InputSpec` of each ``[[inputs]]`` (at least one)."""
    inputs = []
    itab = _array_of_tables("inputs", d.get("inputs", []))
    _count("[[inputs]]", len(itab), MAX_ELEMENTS)
    for i, t in enumerate(itab):
        where = f"inputs[{i}]"
        _table(where, t, schema.allowed_keys("inputs"))
        if ("link" in t) == ("slider" in t):
            raise GearleverError(f"{where}: give exactly one of link = ... or slider = ...")
        spec = _slider_input(where, t, sliders) if "slider" in t else _link_input(where, t, links)
        if spec in inputs:
            raise GearleverError(f"{where}: input {spec.label!r} given twice")
        inputs.append(spec)
    if not inputs:
        raise GearleverError("missing [[inputs]]: give one per degree of freedom")
    return inputs


def _slider_input(where: str, t: dict, sliders: list) -> InputSpec:
    if "relative_to" in t:
        raise GearleverError(f"{where}: relative_to applies to a link input only")
    s = _str(f"{where}.slider", t["slider"])
    if not any(sl.name == s for sl in sliders):
        raise GearleverError(f"{where}.slider: unknown slider {s!r}")
    return InputSpec("slider", s)


def _link_input(where: str, t: dict, links: dict) -> InputSpec:
    lname = _str(f"{where}.link", t["link"])
    if lname not in links:
        raise GearleverError(f"{where}.link: unknown link {lname!r}")
    if lname == GROUND:
        raise GearleverError(f"{where}.link: an input cannot be on ground")
    rel = None
    if "relative_to" in t:
        rel = _str(f"{where}.relative_to", t["relative_to"])
        if rel not in links:
            raise GearleverError(f"{where}.relative_to: unknown link {rel!r}")
        if rel == lname:
            raise GearleverError(f"{where}.relative_to: must be another link than {lname!r}")
    return InputSpec("link", lname, rel)


def tight_centre_distance(module: float, ga: GearSpec, gb: GearSpec, alpha: float = math.radians(20.0)) -> float:
    """The zero-backlash working centre distance of gears ``ga``, ``gb`` (shifts, helix) at normal module ``module``.

    Notes
    -----
    ISO 21771:2007; KHK, *Gear Technical Reference*, "Calculation of profile
    shifted spur gears" (m 3, z 12 and 24, x 0.6 and 0.36: alpha_w 26.0886 deg, a 56.4999 mm):
    ``alpha_t = atan(tan alpha_n / cos beta)``, ``inv alpha_wt = inv alpha_t + 2 tan
    alpha_n (x_1 + x_2) / (z_1 + z_2)`` (an internal pair: differences, ring
    second), ``a_w = m_n (z_1 + z_2) cos alpha_t / (2 cos beta cos alpha_wt)``.

    Examples
    --------
    >>> g1, g2 = GearSpec("a", "l1", "O", 12, shift=0.6), GearSpec("b", "l2", "C", 24, shift=0.36)
    >>> round(tight_centre_distance(3.0, g1, g2), 4)      # KHK's shifted spur example prints 56.4999 mm
    56.4999
    """
    internal = ga.internal or gb.internal
    if internal:
        ring, pin = (ga, gb) if ga.internal else (gb, ga)
        zsum, xsum = ring.teeth - pin.teeth, ring.shift - pin.shift
    else:
        zsum, xsum = ga.teeth + gb.teeth, ga.shift + gb.shift
    cb = math.cos(ga.helix)
    at = math.atan(math.tan(alpha) / cb)
    if zsum == 0:
        return 0.0
    inv_w = math.tan(at) - at + 2.0 * math.tan(alpha) * xsum / zsum
    if inv_w < 0:
        raise GearleverError(f"the shifts {ga.shift:g}, {gb.shift:g} leave no working pressure angle (inv < 0)")
    from gearlever.gears.geometry import inverse_involute

    aw = inverse_involute(max(inv_w, 0.0))
    return module * zsum * math.cos(at) / (2.0 * cb * math.cos(aw))


def _check_scale(points, links) -> None:
    """Refuse a link whose length (first two points) is below ``1 / MAX_SCALE_RATIO`` of the model's size."""
    xs = [p[0] for p in points.values()]
    ys = [p[1] for p in points.values()]
    cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
    size = max(math.hypot(x - cx, y - cy) for x, y in zip(xs, ys))
    for name, link in links.items():
        if len(link.points) >= 2:
            length = math.dist(points[link.points[0]], points[link.points[1]])
            if length * MAX_SCALE_RATIO < size:
                raise GearleverError(
                    f"links.{name}: its length {length:.6g} is less than 1/{MAX_SCALE_RATIO:g} of the model's size "
                    f"{size:.6g}; the structure analysis cannot resolve it (draw the model to one scale)"
                )


def _check_columns(points, links, sliders, inputs, units) -> None:
    """Refuse two elements whose result columns would share a name, naming both.

    The names mirror :meth:`gearlever.mechanism.solve.MechanismResult.columns`
    (angles in rad and in deg; rates named as velocities and as analogues per
    each input), plus the ``closed`` and ``reason`` columns of the command line.
    """
    u = units or "len"
    owner: dict = {}

    def add(col, who):
        if col in owner and owner[col] != who:
            raise GearleverError(f"{who}: its result column {col!r} is also a column of {owner[col]}; rename one")
        owner[col] = who

    names = []
    for spec in inputs:
        if spec.kind == "slider":
            names.append(spec.name)
        else:
            names.append(spec.name if spec.relative_to is None else f"{spec.name}_rel_{spec.relative_to}")
    rates = [("rad_s", "rad_s2", f"{u}_s", f"{u}_s2")]
    for per in names + ["unit_rates"]:
        rates.append((f"per_{per}", f"per_{per}_sq", f"{u}_per_{per}", f"{u}_per_{per}_sq"))
    for r1, r2, l1, l2 in rates:
        for i, (spec, n) in enumerate(zip(inputs, names)):
            slider = spec.kind == "slider"
            for ang in ("rad", "deg"):
                add(f"input_{n}_{u if slider else ang}", f"inputs[{i}]")
            add(f"qdot_{n}_{l1 if slider else r1}", f"inputs[{i}]")
            add(f"qddot_{n}_{l2 if slider else r2}", f"inputs[{i}]")
        for k in links:
            if k != GROUND:
                for col in (f"{k}_angle_rad", f"{k}_angle_deg", f"omega_{k}_{r1}", f"alpha_{k}_{r2}"):
                    add(col, f"links.{k}")
        for sl in sliders:
            for col in (f"{sl.name}_s_{u}", f"v_{sl.name}_{l1}", f"a_{sl.name}_{l2}"):
                add(col, f"sliders ({sl.name})")
        for p in points:
            for col in (f"{p}_x_{u}", f"{p}_y_{u}", f"v_{p}_x_{l1}", f"v_{p}_y_{l1}", f"a_{p}_x_{l2}", f"a_{p}_y_{l2}"):
                add(col, f"points.{p}")
    for col in ("closed", "reason"):
        if col in owner:
            raise GearleverError(f"{owner[col]}: its result column {col!r} is a reserved column name; rename it")


def _make_link(name: str, pts: tuple, points: dict) -> Link:
    ox, oy = points[pts[0]]
    angle0 = 0.0
    if len(pts) >= 2:
        bx, by = points[pts[1]]
        if bx == ox and by == oy:
            raise GearleverError(f"links.{name}: its first two points {pts[0]!r}, {pts[1]!r} coincide in the sketch")
        angle0 = math.atan2(by - oy, bx - ox)
    c, s = math.cos(angle0), math.sin(angle0)
    local = {}
    for p in pts:
        dx, dy = points[p][0] - ox, points[p][1] - oy
        local[p] = (c * dx + s * dy, -s * dx + c * dy)
    return Link(name, pts, (ox, oy), angle0, local)


def _check_connected(links, joints, sliders) -> None:
    adj = {n: set() for n in links}
    for _, a, b in joints:
        adj[a].add(b)
        adj[b].add(a)
    for s in sliders:
        adj[s.link].add(s.on)
        adj[s.on].add(s.link)
    seen, stack = {GROUND}, [GROUND]
    while stack:
        for m in adj[stack.pop()]:
            if m not in seen:
                seen.add(m)
                stack.append(m)
    for n in links:
        if n not in seen:
            raise GearleverError(f"links.{n}: not joined to ground by pins or sliders")


# --------------------------------------------------------------------------- [[poses]]
def parse_poses(raw) -> list:
    """Check a ``[[poses]]`` array: ``[(x, y, angle in rad), ...]``.

    Each pose is a coupler point ``point = [x, y]`` and the coupler's
    direction ``angle_deg`` (degrees in the file, radians returned), as
    :func:`gearlever.synthesis.motion.synthesize_motion` takes them.

    Raises
    ------
    GearleverError
        Naming the pose (``poses[2].point``): not an array of tables, more
        than :data:`~gearlever.mechanism.schema.MAX_POSES`, an unknown or
        missing key, a coordinate or angle not a finite number.

    Examples
    --------
    >>> parse_poses([{"point": [1, 2], "angle_deg": 90}])
    [(1.0, 2.0, 1.5707963267948966)]
    """
    raw = _array_of_tables("poses", raw)
    _count("[[poses]]", len(raw), schema.MAX_POSES)
    out = []
    for i, pose in enumerate(raw):
        where = f"poses[{i}]"
        _table(where, pose, schema.allowed_keys("poses"), schema.required_keys("poses"))
        x, y = _coords(f"{where}.point", pose["point"])
        a = _num(f"{where}.angle_deg", pose["angle_deg"])
        out.append((float(x), float(y), math.radians(a)))
    return out


# --------------------------------------------------------------------------- [lengths]
def parse_lengths(raw, links: dict) -> dict:
    """Check a ``[lengths]`` table and resolve its keys to point pairs.

    Parameters
    ----------
    raw : dict
        ``{key: length}``: ``LINK`` (its first two points) or ``"LINK.P-Q"``.
    links : dict
        Link name -> :class:`Link` (or list of point names).

    Returns
    -------
    dict
        Key -> ``(link, P, Q, length)``, in the order given.

    Raises
    ------
    GearleverError
        Naming the entry (``lengths.crank``): not a table, unknown link, a
        link with fewer than two points, points not on the link or equal, a
        value that is not a positive finite number or exceeds
        :data:`MAX_COORDINATE`, a pair given twice.

    Examples
    --------
    >>> parse_lengths({"crank": 10, "coupler.A-P": 30.5}, {"crank": ["O2", "A"], "coupler": ["A", "B", "P"]})
    {'crank': ('crank', 'O2', 'A', 10.0), 'coupler.A-P': ('coupler', 'A', 'P', 30.5)}
    """
    if not isinstance(raw, dict):
        raise GearleverError('[lengths] must be a table of LINK = length or "LINK.P-Q" = length')
    flat = []
    for key, value in raw.items():
        if isinstance(value, dict):  # coupler.A-P = 30 unquoted is the table coupler = { A-P = 30 }
            flat += [(f"{key}.{k}", v) for k, v in value.items()]
        else:
            flat.append((str(key), value))
    out: dict = {}
    seen: dict = {}
    for key, value in flat:
        where = f"lengths.{key}" if "." not in key else f'lengths."{key}"'
        lname, _, pair = str(key).partition(".")
        if lname not in links:
            raise GearleverError(f"{where}: unknown link {lname!r}")
        pts = links[lname].points if hasattr(links[lname], "points") else tuple(links[lname])
        if not pair:
            if len(pts) < 2:
                raise GearleverError(f"{where}: link {lname!r} has one point; a length needs two")
            p, q = pts[0], pts[1]
        else:
            cands = [
                (pair[:i], pair[i + 1 :])
                for i, c in enumerate(pair)
                if c == "-" and pair[:i] in pts and pair[i + 1 :] in pts
            ]
            if len(cands) != 1:
                raise GearleverError(
                    f'{where}: must name two points of link {lname!r} as "{lname}.P-Q" (points: {", ".join(pts)})'
                )
            p, q = cands[0]
            if p == q:
                raise GearleverError(f"{where}: the two points must differ")
        length = _num(where, value)
        if length <= 0:
            raise GearleverError(f"{where} must be a positive length, got {value!r}")
        if length > MAX_COORDINATE:  # the assembled points could not be written (nor squared: 1e308**2 is inf)
            raise GearleverError(f"{where} must be at most {MAX_COORDINATE:g} (the cap on coordinates), got {value!r}")
        ident = (lname, frozenset((p, q)))
        if ident in seen:
            raise GearleverError(f"{where}: the pair {p}-{q} of link {lname!r} is already given as {seen[ident]!r}")
        seen[ident] = key
        out[key] = (lname, p, q, length)
    return out
