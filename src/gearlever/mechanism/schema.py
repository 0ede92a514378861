"""The model file's schema, declared once: every table, key, type, unit, cap and meaning.

One description serves three readers:

- the loader (:mod:`gearlever.mechanism.model` and :mod:`gearlever.mechanism.loads`)
  takes from it the allowed tables and keys, the required ones and the caps
  (a misspelt key is refused with the list of :func:`allowed_keys`);
- the writer (:mod:`gearlever.mechanism.modelfile`) writes the tables in
  :func:`write_order` (plain tables, then arrays of tables, as TOML needs);
- the guide's page *The model file* lists the same tables and keys (a test
  holds the page to :data:`TABLES`).

It also holds the parsed model's data types (:class:`MechanismModel`,
:class:`Link`, :class:`Slider`, :class:`GearSpec`, :class:`MeshSpec`,
:class:`InputSpec`), so that the loader and the masses-and-loads reader both
import this leaf and not each other.

Examples
--------
>>> [t.header for t in TABLES][:4]
['[mechanism]', '[points]', '[links]', '[[sliders]]']
>>> allowed_keys("meshes")
('gears', 'carrier', 'efficiency')
>>> required_keys("gears")
('link', 'centre', 'teeth')
>>> write_order()[-4:]
('meshes', 'inputs', 'loads', 'poses')

Notes
-----
The file is TOML 1.0 (T. Preston-Werner, *TOML: Tom's Obvious Minimal
Language*): plain tables ``[name]`` and arrays of tables ``[[name]]``.

Imports only the standard library.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

__all__ = [
    "GROUND",
    "GearSpec",
    "InputSpec",
    "Key",
    "Link",
    "MechanismModel",
    "MeshSpec",
    "Slider",
    "TABLES",
    "Table",
    "allowed_keys",
    "allowed_tables",
    "kept_tables",
    "required_keys",
    "table",
    "write_order",
]

#: Name of the frame link.
GROUND = "ground"

# --------------------------------------------------------------------------- caps
#: Names of points, links, sliders and gears: a letter of any script or ``_``
#: first, then letters, digits, ``_``, ``-``, ``.`` (Python's Unicode ``\w``).
NAME_PATTERN = re.compile(r"[^\W\d]+[\w.\-]*")
#: Longest name (characters).
MAX_NAME = 64
#: Longest ``[mechanism] name`` (characters, one line).
MAX_LABEL = 200
#: Largest model file (bytes): real models are a few kB; 4 MiB parses in about a second.
MAX_MODEL_BYTES = 4 * 2**20
#: Deepest nesting of arrays and tables (a model needs 3: ``[gears] g = { ... }``).
MAX_DEPTH = 16
#: Most links: the structure analysis is a dense rank decision of a
#: ``2 P5 + P4`` by ``3 n`` Jacobian (cubic in n).  Measured on a loaded 2-core
#: machine: a 1000-link chain 1.8 s (a 3000-link chain took 73 s and 0.9 GB);
#: the worst case, 1000 parallel levers on one bar (997 redundant constraints,
#: 3996 x 3000), 74 s.
MAX_LINKS = 1000
#: Most points.
MAX_POINTS = 5000
#: Most sliders, gears, meshes, inputs (each).
MAX_ELEMENTS = 1000
#: Most teeth of a gear.
MAX_TEETH = 100_000
#: Largest profile shift coefficient (in size): a shift beyond 2 points every real tooth.
MAX_SHIFT = 5.0
#: Helix angle limit (deg, excluded): the handbooks' bound for helical spur-type gears.
MAX_HELIX_DEG = 45.0
#: Largest coordinate size (model units): beyond it squared distances lose the
#: precision the rank decision needs next to lengths of order 1.
MAX_COORDINATE = 1e12
#: Largest ratio of the model's size to a link's length (its first two points):
#: the structure's rank decisions are relative (1e-9); a crank of 10 in a model
#: spanning 1e11 made a one-dof four-bar read as three dof.
MAX_SCALE_RATIO = 1e6
#: Most poses of ``[[poses]]``: motion synthesis takes three to five (Burmester).
MAX_POSES = 5
#: Largest mass, moment of inertia, force, torque or gravity component accepted (in the model's units).
#: Forces are products of these with lengths (at most 1e12) and speeds squared; a value beyond this
#: cap is far past any machine and would overflow floating point (inf, then NaN forces passed off as
#: results).  Products of values within the caps that still overflow are refused by the final check
#: of :func:`gearlever.mechanism.dynamics.inverse_dynamics`.
MAX_LOAD = 1e100


# --------------------------------------------------------------------------- the declaration
@dataclass(frozen=True)
class Key:
    """One key of a table: its name, type, unit, default, cap and meaning.

    Attributes
    ----------
    name : str
    type : str
        What the value is, in words (``"link name"``, ``"[x, y]"``, ``"number > 0"``).
    doc : str
        Its meaning, one line.
    required : bool
    unit : str
        ``"length"``, ``"deg"``, ``"kg"``... or ``""`` (no unit).
    default : str
        As written in the file (``""``: none).
    cap : str
        The bound checked at load (``""``: none).
    """

    name: str
    type: str
    doc: str
    required: bool = False
    unit: str = ""
    default: str = ""
    cap: str = ""


@dataclass(frozen=True)
class Table:
    """One top-level table of the model file.

    Attributes
    ----------
    name : str
    form : {"table", "map", "map of tables", "array"}
        ``table``: fixed keys (``[mechanism]``); ``map``: ``NAME = value``
        entries (``[points]``); ``map of tables``: ``NAME = { keys }``
        (``[gears]``); ``array``: an array of tables with fixed keys
        (``[[inputs]]``).
    doc : str
        Its meaning, one line.
    keys : tuple of Key
        The fixed keys (of the table, of each entry's table, or of each array
        element); for a ``map``, one :class:`Key` naming its entries' value.
    required : bool
        The file must hold it.
    kept : bool
        The loader keeps it raw in ``MechanismModel.extra``
        (read by :mod:`gearlever.mechanism.loads` or the assembly).
    cap : str
        The most entries (``""``: none).
    """

    name: str
    form: str
    doc: str
    keys: tuple = ()
    required: bool = False
    kept: bool = False
    cap: str = ""

    @property
    def header(self) -> str:
        """``[name]`` or ``[[name]]`` for an array of tables."""
        return f"[[{self.name}]]" if self.form == "array" else f"[{self.name}]"

    @property
    def is_array(self) -> bool:
        return self.form == "array"


_CAP_ELEMENTS = f"{MAX_ELEMENTS} entries"
_COORD = f"|x|, |y| <= {MAX_COORDINATE:g}"
_LOAD = f"<= {MAX_LOAD:g} in size"

#: Every table of the model file, in the order the loader lists them.
TABLES: tuple = (
    Table(
        "mechanism",
        "table",
        "the mechanism's name, length unit, gear module and force settings",
        (
            Key("name", "string", "title in drawings and JSON", default='"mechanism"', cap=f"{MAX_LABEL} chars"),
            Key("units", "name", "label of the length unit (column names)", default='""', cap=f"{MAX_NAME} chars"),
            Key("module", "number > 0", "gear module; checks every mesh's centre distance", unit="length"),
            Key("gravity", "[gx, gy]", "acceleration of gravity (forces only)", unit="length/s^2", cap=_LOAD),
            Key("pressure_angle", "number in [0, 60)", "pressure angle of every gear pair", unit="deg", default="20"),
            Key("mesh_efficiency", "number in (0, 1]", "tooth efficiency of every gear pair", default="1"),
        ),
    ),
    Table(
        "points",
        "map",
        "NAME = [x, y]: the sketch, one assembled position",
        (Key("NAME", "[x, y]", "sketch position of the point", required=True, unit="length", cap=_COORD),),
        required=True,
        cap=f"{MAX_POINTS} entries",
    ),
    Table(
        "links",
        "map",
        'NAME = ["P1", "P2", ...]: a rigid link and the points it carries ("ground" the frame)',
        (Key("NAME", "list of point names", "the points the link carries, first the origin", required=True),),
        required=True,
        cap=f"{MAX_LINKS} moving links",
    ),
    Table(
        "sliders",
        "array",
        "a prismatic pair: link slides along a straight guide fixed on the link on",
        (
            Key("name", "name", "the slider's name (default: the sliding link's name)", cap=f"{MAX_NAME} chars"),
            Key("link", "link name", "the sliding link", required=True),
            Key("on", "link name", "the link carrying the guide", required=True),
            Key("point", "point name", "a point of link: the guide passes through it", required=True),
            Key("direction", "[ux, uy]", "the guide's direction in the sketch (not zero)", required=True),
        ),
        cap=_CAP_ELEMENTS,
    ),
    Table(
        "gears",
        "map of tables",
        "NAME = { link, centre, teeth [, internal] }: a gear rigid on a link",
        (
            Key("link", "link name", "the link the gear is rigid on", required=True),
            Key("centre", "point name", "its centre, a point of link", required=True),
            Key("teeth", "integer >= 1", "number of teeth", required=True, cap=f"{MAX_TEETH}"),
            Key("internal", "true or false", "an internal gear (a ring)", default="false"),
            Key("shift", "number", "profile shift coefficient x", default="0", cap=f"{MAX_SHIFT:g} in size"),
            Key("face_width", "length > 0", "face width (model units)"),
            Key("helix", "number, deg", "helix angle", default="0", cap=f"below {MAX_HELIX_DEG:g}"),
        ),
        cap=_CAP_ELEMENTS,
    ),
    Table(
        "meshes",
        "array",
        "a gear mesh (higher pair) of two gears",
        (
            Key("gears", "pair of gear names", "the two gears in mesh", required=True),
            Key("carrier", "link name", "the link carrying both centres (default: the one that does)"),
            Key("efficiency", "number in (0, 1]", "tooth efficiency of this pair (default: mesh_efficiency)"),
        ),
        cap=_CAP_ELEMENTS,
    ),
    Table(
        "inputs",
        "array",
        "one input (degree of freedom): a link's angle or a slider's displacement",
        (
            Key("link", "link name", "input link (its absolute angle); not ground"),
            Key("relative_to", "link name", "measure the link's angle relative to this link"),
            Key("slider", "slider name", "input slider (its displacement); instead of link"),
        ),
        required=True,
        cap=_CAP_ELEMENTS,
    ),
    Table(
        "masses",
        "map of tables",
        "LINK = { mass, centre, inertia }: the mass of a moving link",
        (
            Key("mass", "number >= 0", "mass", unit="kg", default="0", cap=_LOAD),
            Key("centre", "point name or [x, y]", "centre of mass (required when mass > 0)", unit="length"),
            Key("inertia", "number >= 0", "moment of inertia about the centre", unit="kg length^2", default="0"),
        ),
        kept=True,
    ),
    Table(
        "loads",
        "array",
        "an external force at a point and/or a torque on a moving link",
        (
            Key("link", "link name", "the loaded link (not ground)", required=True),
            Key("point", "point name or [x, y]", "where the force acts (with force)", unit="length"),
            Key("force", "[fx, fy]", "the force", unit="N", cap=_LOAD),
            Key("torque", "number", "the torque", unit="N length", cap=_LOAD),
        ),
        kept=True,
    ),
    Table(
        "lengths",
        "map",
        'LINK = length or "LINK.P-Q" = length: exact lengths for a rough sketch (mechanism assemble)',
        (
            Key(
                "LINK or LINK.P-Q",
                "number > 0",
                "distance of the link's first two points, or of P and Q",
                unit="length",
                cap=f"<= {MAX_COORDINATE:g}",
            ),
        ),
        kept=True,
    ),
    Table(
        "friction",
        "table",
        "Coulomb friction at the pins and sliders (gearlever.mechanism.friction)",
        (
            Key("coefficient", "number from 0 to 1", "Coulomb coefficient of every pin and slider", default="none"),
            Key("pin_radius", "length > 0", "journal radius of every pin (pins need a radius)", unit="length"),
            Key("pins", "table of POINT = { coefficient, radius }", "a pin's own values"),
            Key("sliders", "table of SLIDER = { coefficient }", "a slider's own coefficient"),
        ),
        kept=True,
    ),
    Table(
        "poses",
        "array",
        "a pose of a coupler for motion synthesis: its point and its direction (the workbench's pose tool)",
        (
            Key("point", "[x, y]", "where the coupler point is", required=True, unit="length", cap=_COORD),
            Key("angle_deg", "number", "the coupler's direction, counter-clockwise from +x", required=True, unit="deg"),
        ),
        kept=True,
        cap=f"{MAX_POSES} entries",
    ),
)

_BY_NAME = {t.name: t for t in TABLES}


def table(name: str) -> Table:
    """The :class:`Table` named ``name`` (``"points"``, ``"inputs"``...)."""
    return _BY_NAME[name]


def allowed_tables() -> tuple:
    """Names of the top-level tables, in the loader's order."""
    return tuple(t.name for t in TABLES)


def kept_tables() -> tuple:
    """Tables the loader keeps raw in ``MechanismModel.extra``."""
    return tuple(t.name for t in TABLES if t.kept)


def allowed_keys(name: str) -> tuple:
    """Keys of table ``name`` (of each entry for a map of tables, of each element for an array)."""
    return tuple(k.name for k in _BY_NAME[name].keys)


def required_keys(name: str) -> tuple:
    """Keys table ``name`` must hold (each entry, each element)."""
    return tuple(k.name for k in _BY_NAME[name].keys if k.required)


#: Keys of ``[mechanism]`` the loader keeps raw in ``MechanismModel.extra`` (read by the forces).
KEPT_MECHANISM_KEYS = ("gravity", "pressure_angle", "mesh_efficiency")


def write_order() -> tuple:
    """Order in which a written file holds its tables: plain tables first, then arrays of tables.

    TOML puts every key after an array-of-tables header ``[[x]]`` into that
    element, so the plain tables must all come first.
    """
    return tuple(t.name for t in TABLES if not t.is_array) + tuple(t.name for t in TABLES if t.is_array)


# --------------------------------------------------------------------------- the parsed model's types
@dataclass(frozen=True)
class Link:
    """A rigid link: the points it carries and their body-fixed coordinates.

    Attributes
    ----------
    name : str
    points : tuple of str
        In the order listed; the first is the origin of the body frame.
    origin : tuple of float
        Sketch position of the first point.
    angle0 : float
        Sketch angle (rad) of the line from the first point to the second;
        0 for a one-point link (its angle is its rotation from the sketch).
    local : dict
        Point name -> body-fixed coordinates ``(xi, eta)``: the sketch offset
        from ``origin`` turned back by ``angle0``.
    """

    name: str
    points: tuple
    origin: tuple
    angle0: float
    local: dict = field(repr=False)


@dataclass(frozen=True)
class Slider:
    """A prismatic pair: ``link`` slides along a straight guide fixed on ``on``.

    The guide passes through the sketch position of ``point`` (a point of
    ``link``) along the unit vector ``direction`` (sketch orientation), and
    turns with ``on``; ``link`` does not turn relative to ``on``.  Its
    displacement is measured along ``direction`` from the sketch.
    ``given`` is the direction as the file gives it (any length; None when
    built in code), written back by :func:`gearlever.mechanism.modelfile.model_dict`
    so that a written model reads back to the same unit vector.
    """

    name: str
    link: str
    on: str
    point: str
    direction: tuple
    given: tuple | None = field(default=None, compare=False, repr=False)


@dataclass(frozen=True)
class GearSpec:
    """A gear of the model file: rigid on ``link``, centred at ``centre``; ``internal`` for a ring.

    (The gear of a gear network, by tooth numbers alone, is :class:`gearlever.gears.networks.Gear`.)

    ``shift`` is the profile shift coefficient x, ``face_width`` the face
    width (model units, None when not given), ``helix`` the helix angle (rad).
    """

    name: str
    link: str
    centre: str
    teeth: int
    internal: bool = False
    shift: float = 0.0
    face_width: float | None = None
    helix: float = 0.0


@dataclass(frozen=True)
class MeshSpec:
    """A gear mesh (higher pair) of the model file: gears ``a`` and ``b`` whose centres ``carrier`` carries.

    (The mesh of a gear network is :class:`gearlever.gears.networks.Mesh`.)
    """

    name: str
    a: str
    b: str
    carrier: str
    efficiency: float | None = None  # tooth efficiency of this pair (None: [mechanism] mesh_efficiency or 1)


@dataclass(frozen=True)
class InputSpec:
    """One input (degree of freedom).

    ``kind`` is ``"link"`` (absolute angle of ``name``, or relative to the
    link ``relative_to``) or ``"slider"`` (displacement of slider ``name``).
    """

    kind: str
    name: str
    relative_to: str | None = None

    @property
    def label(self) -> str:
        """``"crank"``, ``"crank/ground2"`` or ``"slider:piston"``."""
        if self.kind == "slider":
            return f"slider:{self.name}"
        return self.name if self.relative_to is None else f"{self.name}/{self.relative_to}"


@dataclass(frozen=True)
class MechanismModel:
    """The parsed, validated data of a mechanism model file.

    Attributes
    ----------
    name, units : str
        From ``[mechanism]`` (``units`` is only a label for lengths).
    module : float or None
        Gear module; when given every mesh's centre distance was checked.
    points : dict
        Point name -> sketch position ``(x, y)``.
    links : dict
        Link name -> :class:`Link`; ``"ground"`` is the frame.
    moving : tuple of str
        The moving links (all but ground), in file order: the column order of
        the absolute-coordinate Jacobian (columns ``x, y, theta`` of each).
    joints : tuple of tuple
        Revolute pairs ``(point, link_i, link_j)``: a point carried by ``k``
        links gives ``k - 1`` pairs, all with its first carrier.
    sliders : tuple of Slider
    gears : dict
        Gear name -> :class:`GearSpec`.
    meshes : tuple of MeshSpec
    inputs : tuple of InputSpec
    extra : dict
        Raw values of the tables and keys this loader keeps but does not
        read: ``masses``, ``loads``, ``lengths`` (top level), ``gravity``,
        ``pressure_angle``, ``mesh_efficiency`` (of ``[mechanism]``); only
        those present.

    Examples
    --------
    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...                      "links": {"ground": ["O"], "crank": ["O", "A"]},
    ...                      "inputs": [{"link": "crank"}]})
    >>> m.moving, [i.label for i in m.inputs]
    (('crank',), ['crank'])
    """

    name: str
    units: str
    module: float | None
    points: dict
    links: dict
    moving: tuple
    joints: tuple
    sliders: tuple
    gears: dict
    meshes: tuple
    inputs: tuple
    extra: dict = field(default_factory=dict, repr=False)

    def carriers(self, point: str) -> tuple:
        """Links carrying ``point``, in file order."""
        return tuple(name for name, link in self.links.items() if point in link.local)

    def mesh_internal(self, mesh: MeshSpec) -> bool:
        """True when one gear of ``mesh`` is internal (a ring)."""
        return self.gears[mesh.a].internal or self.gears[mesh.b].internal

    def pitch_radius(self, gear: str) -> float | None:
        """Pitch radius of ``gear``: ``module * teeth / 2``, or from its first mesh's centre distance.

        Returns None for a gear in no mesh when no module is given.
        """
        g = self.gears[gear]
        if self.module is not None:
            return self.module * g.teeth / (2.0 * math.cos(g.helix))
        for m in self.meshes:
            if gear in (m.a, m.b):
                ga, gb = self.gears[m.a], self.gears[m.b]
                d = math.dist(self.points[ga.centre], self.points[gb.centre])
                zsum = abs(ga.teeth - gb.teeth) if self.mesh_internal(m) else ga.teeth + gb.teeth
                if zsum > 0 and d > 0:
                    return d * g.teeth / zsum
        return None

    @property
    def length_scale(self) -> float:
        """Largest distance of a sketch point from the centroid of all points (>= 1e-300)."""
        xs = [p[0] for p in self.points.values()]
        ys = [p[1] for p in self.points.values()]
        cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
        return max(max(math.hypot(x - cx, y - cy) for x, y in zip(xs, ys)), 1e-300)
