"""The geometry of a mechanism's parts for CAD: outlines, pin holes, slider guides, whole gears.

:func:`mechanism_drawing` lays out every link of a model at one pose (the
sketch, or the inputs given) as a :class:`Part`:

- a link carrying two pins is a slot (two half circles joined by tangents),
  one carrying three or more the rounded convex hull of its pins (the hull
  offset by the link's half width), one carrying a single pin a round boss;
- every joint is a pin hole (a circle of the pin diameter) on each link it joins;
- a gear is its whole tooth outline (involute flanks and the trochoidal root
  fillet the ISO 53 rack cuts, :func:`gearlever.gears.geometry.tooth_outline`),
  phased so that meshing teeth interleave, with a bore at its centre; a ring
  gets a round rim outside its root circle; the link's slot is dropped when
  the gear's body already holds its pins;
- a slider is a block around its pin, lined up with its guide; the guide is
  two lines on the guiding link's part, one block height apart.

Each part keeps its closed outlines (``(N, 2)`` arrays, counter-clockwise),
holes (centre, radius) and open lines in world coordinates of the pose, and
its pose (:attr:`Part.origin`, :attr:`Part.angle`) so that
:meth:`Part.local` redraws it in its own body frame (one file per part).
Numeric core: numpy and the model; no drawing library.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from gearlever._result import Result
from gearlever.errors import GearleverError

__all__ = ["Part", "Drawing", "mechanism_drawing", "slot", "rounded_hull", "default_pin_diameter"]

#: Points on a half circle of a link's end (odd: the end's apex is one), per vertex arc of a hull in proportion.
ARC_POINTS = 25
#: Points on each tooth flank of a drawn gear.
TOOTH_POINTS = 12
#: Most teeth drawn as a whole outline (a bigger gear is drawn as its pitch, tip and root circles).
MAX_DRAWN_TEETH = 2000


@dataclass(frozen=True)
class Part:
    """One part of the drawing (a link, with its gears, holes and guides).

    Attributes
    ----------
    name : str
        The link's name (the DXF layer).
    outlines : tuple of ndarray
        Closed outlines ``(N, 2)`` (the last point joins the first).
    holes : tuple of tuple
        ``((x, y), radius)`` of each pin hole and bore.
    lines : tuple of ndarray
        Open polylines ``(N, 2)`` (slider guides).
    origin : tuple
        World position of the part's body frame (its first point).
    angle : float
        World angle (rad) of the body frame's x axis.

    Examples
    --------
    >>> p = Part("crank", (slot((10, 10), (10, 20), 1.0),), (((10.0, 10.0), 0.5), ((10.0, 20.0), 0.5)),
    ...          origin=(10.0, 10.0), angle=math.pi / 2)
    >>> [tuple(round(v, 9) + 0.0 for v in c) for c, r in p.local().holes]
    [(0.0, 0.0), (10.0, 0.0)]
    """

    name: str
    outlines: tuple
    holes: tuple
    lines: tuple = ()
    origin: tuple = (0.0, 0.0)
    angle: float = 0.0

    def local(self) -> Part:
        """The part in its own body frame (origin at its first point, x along its first two points)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        rot = np.array([[c, s], [-s, c]])
        o = np.asarray(self.origin, dtype=float)

        def to(p):
            return (np.asarray(p, dtype=float) - o) @ rot.T

        return Part(
            self.name,
            tuple(to(o_) for o_ in self.outlines),
            tuple((tuple(to(c_).tolist()), r) for c_, r in self.holes),
            tuple(to(ln) for ln in self.lines),
            (0.0, 0.0),
            0.0,
        )

    def extent(self) -> tuple:
        """``(xmin, ymin, xmax, ymax)`` of everything drawn."""
        pts = [np.asarray(o) for o in self.outlines] + [np.asarray(ln) for ln in self.lines]
        pts += [np.array([[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]]) for c, r in self.holes]
        allp = np.vstack(pts) if pts else np.zeros((1, 2))
        return (*allp.min(axis=0).tolist(), *allp.max(axis=0).tolist())


@dataclass(frozen=True)
class Drawing(Result):
    """The parts of a mechanism at one pose.

    Attributes
    ----------
    name, units : str
        From the model.
    parts : tuple of Part
        One per link carrying something drawn, in the model's link order (ground first if drawn).
    pin_diameter : float
    inputs : dict
        Input label -> value at this pose (rad for a link, length for a slider).
    notes : tuple of str
        What was drawn in a simpler form (a gear with too many teeth, a gear with no module).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> d = mechanism_drawing(Mechanism.load(example_path("ferguson.toml")))
    >>> d.notes[0]
    "no module in the model: module 1 from the first mesh's centre distance"
    >>> [p.name for p in d.parts]
    ['ground', 'arm', 'planet', 'g99', 'g100', 'g101']
    """

    name: str
    units: str
    parts: tuple
    pin_diameter: float
    inputs: dict = field(default_factory=dict)
    notes: tuple = ()

    def extent(self) -> tuple:
        boxes = np.array([p.extent() for p in self.parts]) if self.parts else np.zeros((1, 4))
        return (*boxes[:, :2].min(axis=0).tolist(), *boxes[:, 2:].max(axis=0).tolist())


def _arc(c, r, a0, a1, n):
    t = np.linspace(a0, a1, n)
    return np.column_stack([c[0] + r * np.cos(t), c[1] + r * np.sin(t)])


def slot(p, q, half_width: float, n: int = ARC_POINTS) -> np.ndarray:
    """Closed outline of a slot (stadium) around points ``p`` and ``q``, counter-clockwise.

    >>> s = slot((0, 0), (10, 0), 2.0)
    >>> float(s[:, 0].min()), float(s[:, 0].max()), float(s[:, 1].max())
    (-2.0, 12.0, 2.0)
    """
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    d = q - p
    a = math.atan2(d[1], d[0])
    return np.vstack(
        [
            _arc(q, half_width, a - math.pi / 2, a + math.pi / 2, n),
            _arc(p, half_width, a + math.pi / 2, a + 3 * math.pi / 2, n),
        ]
    )


def _hull(pts: np.ndarray) -> np.ndarray:
    """Convex hull, counter-clockwise (Andrew's monotone chain), collinear points dropped."""
    pts = sorted(set(map(tuple, np.round(pts, 12).tolist())))
    if len(pts) <= 2:
        return np.array(pts)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


def rounded_hull(points, half_width: float, n: int = ARC_POINTS) -> np.ndarray:
    """Closed outline of the convex hull of ``points`` offset by ``half_width`` (counter-clockwise).

    Two points (or collinear ones) give a :func:`slot`; one point a circle.

    >>> h = rounded_hull([(0, 0), (10, 0), (5, 8)], 1.0)
    >>> round(float(h[:, 1].max()), 6), round(float(h[:, 1].min()), 6)
    (9.0, -1.0)
    """
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    hull = _hull(pts)
    if len(hull) == 1:
        return _arc(hull[0], half_width, 0.0, 2 * math.pi, 2 * n)[:-1]
    if len(hull) == 2:
        return slot(hull[0], hull[1], half_width, n)
    out = []
    k = len(hull)
    for i in range(k):
        prev, cur, nxt = hull[i - 1], hull[i], hull[(i + 1) % k]
        a_in = math.atan2(*(cur - prev)[::-1]) - math.pi / 2
        a_out = math.atan2(*(nxt - cur)[::-1]) - math.pi / 2
        while a_out < a_in:
            a_out += 2 * math.pi
        m = max(2, int(round(n * (a_out - a_in) / math.pi)) + 1)
        out.append(_arc(cur, half_width, a_in, a_out, m))
    return np.vstack(out)


def default_pin_diameter(model) -> float:
    """A fifth of the shortest distance between two pins of one link (or of the model's size).

    >>> from gearlever.mechanism.model import model_from_dict
    >>> m = model_from_dict({"points": {"O": [0, 0], "A": [10, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> default_pin_diameter(m)
    2.0
    """
    shortest = math.inf
    for link in model.links.values():
        for i, p in enumerate(link.points):
            for q in link.points[i + 1 :]:
                d = math.dist(model.points[p], model.points[q])
                if d > 0:
                    shortest = min(shortest, d)
    if not math.isfinite(shortest):
        shortest = model.length_scale
    return shortest / 5.0


def _rot(xy: np.ndarray, angle: float, centre) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return xy @ np.array([[c, s], [-s, c]]) + np.asarray(centre, dtype=float)


def _gear_phases(model, centres: dict) -> dict:
    """Gear -> world angle of its reference tooth (external) or space (internal) so that meshing teeth interleave.

    A breadth-first walk over the meshes from each gear not yet phased (at
    angle 0): an external pair puts a space of the second gear against a
    tooth of the first on the line of centres (rolling the first's offset
    over with the tooth ratio); a ring puts a space against a pinion's tooth.
    """
    phase: dict = {}
    adj: dict = {g: [] for g in model.gears}
    for m in model.meshes:
        adj[m.a].append(m.b)
        adj[m.b].append(m.a)
    for start in model.gears:
        if start in phase:
            continue
        phase[start] = 0.0
        todo = [start]
        while todo:
            a = todo.pop(0)
            for b in adj[a]:
                if b in phase:
                    continue
                ga, gb = model.gears[a], model.gears[b]
                ca, cb = np.asarray(centres[ga.centre]), np.asarray(centres[gb.centre])
                if not ga.internal and not gb.internal:
                    theta = math.atan2(*(cb - ca)[::-1])
                    delta = phase[a] - theta
                    phase[b] = theta + math.pi - delta * ga.teeth / gb.teeth - math.pi / gb.teeth
                else:
                    # contact on the side of the pinion away from the ring's centre
                    ring_c, pin_c = (cb, ca) if gb.internal else (ca, cb)
                    theta = math.atan2(*(pin_c - ring_c)[::-1]) if np.any(pin_c != ring_c) else 0.0
                    phase[b] = theta + (phase[a] - theta) * ga.teeth / gb.teeth
                todo.append(b)
    return phase


def model_module(model) -> float | None:
    """The model's module, or (none given) the first mesh's: ``2 a cos(beta) / (z_1 +- z_2)``, or None."""
    if model.module is not None:
        return model.module
    if not model.meshes:
        return None
    first = model.gears[model.meshes[0].a]
    return 2.0 * model.pitch_radius(first.name) * math.cos(first.helix) / first.teeth


def _gear_outline(model, gear, alpha: float, module) -> tuple:
    """``(outline, rim or None, note)`` of ``gear`` at the origin, reference tooth (space) on +x."""
    g = model.gears[gear]
    note = None
    if module is None:
        return None, None, f"gear {gear}: no module and no mesh: not drawn"
    if g.teeth > MAX_DRAWN_TEETH or g.teeth < 3:
        r = module * g.teeth / (2 * math.cos(g.helix))
        return (
            _arc((0.0, 0.0), r, 0.0, 2 * math.pi, 4 * ARC_POINTS)[:-1],
            None,
            (f"gear {gear}: {g.teeth} teeth drawn as its pitch circle"),
        )
    from gearlever.gears.geometry import tooth_outline

    xy = tooth_outline(
        module,
        g.teeth,
        g.shift,
        pressure_angle=alpha,
        helix=g.helix,
        internal=g.internal,
        points=TOOTH_POINTS,
    )
    rim = None
    if g.internal:
        r_root = float(np.hypot(xy[:, 0], xy[:, 1]).max())
        rim = _arc((0.0, 0.0), r_root + 2.5 * module, 0.0, 2 * math.pi, 8 * ARC_POINTS)[:-1]
    return np.asarray(xy, dtype=float), rim, note


def mechanism_drawing(mech, inputs=None, pin_diameter: float | None = None) -> Drawing:
    """Every link of ``mech`` as a :class:`Part` at the sketch or at ``inputs``.

    Parameters
    ----------
    mech : gearlever.mechanism.Mechanism
    inputs : dict, optional
        Input label -> value (rad for a link, length for a slider); inputs not
        given stay at their sketch values.  Default: the sketch itself.
    pin_diameter : float, optional
        Diameter of every pin hole and bore (model units); default
        :func:`default_pin_diameter`.  Links are twice as wide.

    Returns
    -------
    Drawing

    Raises
    ------
    GearleverError
        ``inputs`` naming an unknown input; a pin diameter not positive and
        finite; a pose at which the mechanism does not close.

    Notes
    -----
    The involute teeth, their root fillets and the ring's inner outline are
    :func:`gearlever.gears.geometry.tooth_outline` (ISO 53 rack); meshing
    gears are phased by the rolling of their pitch circles (the arc one gear
    turns off the line of centres is the arc its mate turns the other way,
    ``delta_b = -delta_a z_a / z_b`` for an external pair, the same sense for a ring).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> d = mechanism_drawing(Mechanism.load(example_path("fourbar.toml")))
    >>> [p.name for p in d.parts], len(d.parts[1].holes)
    (['ground', 'crank', 'coupler', 'rocker'], 2)
    """
    from gearlever.mechanism.loads import pressure_angle_of

    m = mech.model
    d_pin = default_pin_diameter(m) if pin_diameter is None else float(pin_diameter)
    if not (math.isfinite(d_pin) and d_pin > 0):
        raise GearleverError(f"pin_diameter must be a positive number, got {pin_diameter!r}")
    if d_pin > 1e3 * m.length_scale:
        raise GearleverError(f"pin_diameter {d_pin:g} is more than 1000 times the model's size {m.length_scale:g}")
    r_pin = d_pin / 2
    half = d_pin  # a link is twice the pin's diameter wide
    from gearlever.mechanism.solve import input_name

    labels = [input_name(s) for s in m.inputs]
    q0 = mech.sketch_inputs
    # world positions and rotations from the sketch
    if not inputs:
        pos = {p: np.asarray(xy, dtype=float) for p, xy in m.points.items()}
        rotation = {k: 0.0 for k in m.links}
        slider_shift = {s.name: 0.0 for s in m.sliders}
        at = dict(zip(labels, q0.tolist()))
    else:
        q = q0.copy()
        for name, v in inputs.items():
            if name not in labels:
                raise GearleverError(f"inputs: unknown input {name!r} (inputs: {', '.join(labels)})")
            q[labels.index(name)] = float(v)
        r = mech.solve(q[None, :])
        if not bool(r.closed[0]):
            why = str(r.reason[0]) or "it does not assemble"
            raise GearleverError(f"inputs: the mechanism does not close at this pose ({why})")
        pos = {p: np.asarray(r.point[p][0], dtype=float) for p in m.points}
        rotation = {k: 0.0 for k in m.links}
        for k in m.moving:
            rotation[k] = float(r.angle[k][0]) - m.links[k].angle0
        slider_shift = {s.name: float(r.displacement[s.name][0]) for s in m.sliders}
        at = dict(zip(labels, q.tolist()))
    alpha = pressure_angle_of(m)
    phases = _gear_phases(m, m.points)
    module = model_module(m)
    notes = []
    if m.module is None and module is not None:
        notes.append(f"no module in the model: module {module:.6g} from the first mesh's centre distance")
    extras: dict = {k: {"outlines": [], "holes": [], "lines": []} for k in m.links}
    gear_bodies: dict = {k: [] for k in m.links}
    for gname, g in m.gears.items():
        xy, rim, note = _gear_outline(m, gname, alpha, module)
        if note:
            notes.append(note)
        if xy is None:
            continue
        c = pos[g.centre]
        turn = phases[gname] + rotation[g.link]
        e = extras[g.link]
        e["outlines"].append(_rot(xy, turn, c))
        radii = np.hypot(xy[:, 0], xy[:, 1])
        if rim is not None:
            e["outlines"].append(_rot(rim, turn, c))
            gear_bodies[g.link].append((c, float(np.hypot(rim[:, 0], rim[:, 1]).max()), True))
        else:
            bore = min(r_pin, 0.5 * float(radii.min()))
            e["holes"].append((tuple(c.tolist()), bore))
            gear_bodies[g.link].append((c, float(radii.min()) - half, False))
    for s in m.sliders:
        p = pos[s.point]
        u = np.array(s.direction)
        c, sn = math.cos(rotation[s.on]), math.sin(rotation[s.on])
        u = np.array([c * u[0] - sn * u[1], sn * u[0] + c * u[1]])
        v = np.array([-u[1], u[0]])
        # the block around the pin, 3 pin diameters long, 2 wide
        corners = [p + a * 1.5 * d_pin * u + b * half * v for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        extras[s.link]["outlines"].append(np.array(corners))
        # the guide: two lines one block height apart, over the model's size either side of the sketch point
        base = p - slider_shift[s.name] * u
        span = 2.0 * m.length_scale
        for side in (-1, 1):
            a = base - span * u + side * half * v
            b = base + span * u + side * half * v
            extras[s.on]["lines"].append(np.array([a, b]))
    parts = []
    for k, link in m.links.items():
        e = extras[k]
        pins = [pos[p] for p in link.points]
        inside = [
            any(
                (ring and np.hypot(*(pp - c)) >= rr) or (not ring and np.hypot(*(pp - c)) <= rr)
                for c, rr, ring in gear_bodies[k]
            )
            for pp in pins
        ]
        outlines = list(e["outlines"])
        if not all(inside):
            body = [pp for pp, ok in zip(pins, inside) if not ok]
            body += [pp for pp, ok in zip(pins, inside) if ok and len(body) > 0]
            if not (k == "ground" and len(link.points) == 1 and gear_bodies[k]):
                outlines.insert(0, rounded_hull(np.array(body), half))
        holes = [(tuple(pp.tolist()), r_pin) for pp in pins]
        holes += [h for h in e["holes"] if not any(np.allclose(h[0], hh[0]) for hh in holes)]
        if not outlines and not e["lines"]:
            continue
        origin = tuple(pos[link.points[0]].tolist())
        parts.append(Part(k, tuple(outlines), tuple(holes), tuple(e["lines"]), origin, link.angle0 + rotation[k]))
    return Drawing(m.name, m.units, tuple(parts), d_pin, at, tuple(notes))
