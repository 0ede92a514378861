"""Drawings of mechanism models: links, joints, sliders, gears, inputs, loads and point paths; GIF animation.

A drawing shows, in the model's sketch (or at one row of a sweep):

- every moving link in its own colour (a bar, or the convex hull of its
  points), its name near its middle, the names of the points;
- pin joints as open circles, ground pivots as triangles over hatching;
- sliders as blocks on their guides (hatched when the guide is on ground);
- gears as pitch circles (dash-dot for a ring) with their tooth counts
  ``z = ...`` and a radial mark that turns with the gear;
- each input as an arc arrow at its pivot (a double arrow for a slider)
  labelled ``input: NAME``;
- the model's ``[[loads]]``: forces as arrows at their points with their
  values, torques as arc arrows; gravity in the legend;
- the paths of the points over a sweep, dotted; a legend and a title.

Names that the font cannot draw (e.g. CJK without a CJK font) are written
with escapes instead of missing-glyph boxes.
"""

from __future__ import annotations

import functools
import io
import math
from pathlib import Path

import numpy as np
from matplotlib import patheffects
from matplotlib.collections import LineCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon

from gearlever._io import atomic_path
from gearlever._validate import positive_int
from gearlever.errors import GearleverError
from gearlever.plotting._common import axes, plt
from gearlever.plotting._limits import ANIMATION_DPI, ANIMATION_SIZE, DRAWING_SIZE, check_figure, check_frames

__all__ = ["draw_mechanism", "animate_mechanism"]

#: Link colours (matplotlib's tab10 without red, pink and grey: those mark loads, inputs and the frame).
LINK_COLORS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#bcbd22", "#17becf")
INPUT_COLOR = "#c51b7d"
LOAD_COLOR = "#d62728"
GROUND_COLOR = "0.25"
PATH_COLOR = "0.55"
FONT = 7.5
_HALO = [patheffects.withStroke(linewidth=2.5, foreground="white")]
#: Force units written after a load's value, by length unit of the model (consistent SI only).
_FORCE_UNIT = {"m": "N"}
_TORQUE_UNIT = {"m": "N·m"}


# --------------------------------------------------------------------------- text
@functools.lru_cache(maxsize=8)
def _font(path: str):
    from matplotlib.ft2font import FT2Font

    return FT2Font(path)


@functools.lru_cache(maxsize=4096)
def _has_glyph(c: str) -> bool:
    from matplotlib import font_manager

    path = font_manager.findfont(font_manager.FontProperties(family=plt.rcParams["font.family"]))
    return _font(path).get_char_index(ord(c)) != 0


def _fallback_label(name) -> str:
    """``name`` as text the default font can draw: other characters as ``\\uXXXX`` escapes, ``$`` escaped."""
    out = []
    for c in str(name):
        if c == "$":
            out.append(r"\$")
        elif c.isprintable() and _has_glyph(c):
            out.append(c)
        else:
            out.append(c.encode("unicode_escape").decode("ascii"))
    return "".join(out)


try:  # the shared helper, when the package has it
    from gearlever.plotting._text import safe_label as _label
except ImportError:
    _label = _fallback_label


# --------------------------------------------------------------------------- geometry
def _configuration(mech, result, row):
    """Point positions (dict) and link rotations from the sketch at ``row`` of ``result`` (the sketch when None)."""
    m = mech.model
    if result is None or row is None:
        return dict(m.points), {k: 0.0 for k in m.links}
    pts = {p: tuple(result.point[p][row]) for p in result.point}
    for p in m.links["ground"].points:  # the frame does not move (also where the rest cannot close)
        pts[p] = m.points[p]
    rot = {k: (float(result.angle[k][row]) - m.links[k].angle0) if k in result.angle else 0.0 for k in m.links}
    return pts, rot


def _rotate(v, th):
    c, s = math.cos(th), math.sin(th)
    return np.array([c * v[0] - s * v[1], s * v[0] + c * v[1]])


def _world(link, pts, rot, local):
    """Position of the body-fixed point ``local`` of ``link`` in the current configuration."""
    origin = np.asarray(pts[link.points[0]], dtype=float)
    return origin + _rotate(local, link.angle0 + rot[link.name])


def _hull(xy: np.ndarray) -> np.ndarray:
    """Convex hull (counter-clockwise, Andrew's monotone chain); two points when collinear."""
    P = sorted(set(map(tuple, np.round(xy, 12).tolist())))
    if len(P) <= 2:
        return np.array(P)

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in P:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(P):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return np.array(lower[:-1] + upper[:-1])


class _Placer:
    """Greedy label placement: the first candidate whose text box overlaps no box placed so far.

    Boxes are estimated in data units from the font size (``pt``: data units
    per typographic point); when every candidate overlaps, the least overlap wins.
    """

    def __init__(self, pt: float):
        self.pt = pt
        self.boxes: list = []

    def add_point(self, xy, r: float):
        self.boxes.append((xy[0] - r, xy[1] - r, xy[0] + r, xy[1] + r))

    def box(self, c, text: str, size: float = FONT, ha: str = "center", va: str = "center"):
        lines = text.split("\n")
        w = 0.62 * size * max(len(t) for t in lines) * self.pt
        h = 1.3 * size * len(lines) * self.pt
        x0 = {"center": c[0] - w / 2, "left": c[0], "right": c[0] - w}[ha]
        y0 = {"center": c[1] - h / 2, "bottom": c[1], "top": c[1] - h}[va]
        return (x0, y0, x0 + w, y0 + h)

    def _overlap(self, b) -> float:
        total = 0.0
        for o in self.boxes:
            dx = min(b[2], o[2]) - max(b[0], o[0])
            dy = min(b[3], o[3]) - max(b[1], o[1])
            if dx > 0 and dy > 0:
                total += dx * dy
        return total

    def place(self, candidates, text: str, size: float = FONT):
        best, best_box, best_cost = None, None, np.inf
        for c in candidates:
            c = np.asarray(c, dtype=float)
            b = self.box(c, text, size)
            cost = self._overlap(b)
            if cost < best_cost:
                best, best_box, best_cost = c, b, cost
            if cost == 0.0:
                break
        self.boxes.append(best_box)
        return best


class _Scene:
    """What every frame of one drawing shares: extent, symbol size, colours, guide spans, loads, gravity."""

    def __init__(self, mech, result, axes_in=(5.5, 4.5), paths=None):
        from gearlever.mechanism.loads import gravity_of, parse_loads

        m = mech.model
        self.mech, self.model, self.result = mech, m, result
        self.axes_in = axes_in
        xy = [np.array(list(m.points.values()), dtype=float)]
        for res in (result, paths):
            if res is not None:
                xy += [np.asarray(v, dtype=float) for v in res.point.values()]
        for g in m.gears.values():
            r = m.pitch_radius(g.name)
            if r is None:
                continue
            c = [np.array([m.points[g.centre]], dtype=float)]
            if result is not None and g.centre in result.point:
                c.append(np.asarray(result.point[g.centre], dtype=float))
            c = np.concatenate(c)
            xy += [c + [r, r], c - [r, r]]
        allxy = np.concatenate(xy)
        allxy = allxy[np.all(np.isfinite(allxy), axis=1)]
        self.lo, self.hi = allxy.min(axis=0), allxy.max(axis=0)
        span = float(max(self.hi - self.lo))
        if not span > 0:
            span = 2.0 * m.length_scale if m.length_scale > 1e-300 else 1.0
        #: symbol size (data units): 3 % of the drawing
        self.u = 0.03 * span
        self.colors = {}
        for i, name in enumerate(m.moving):
            self.colors[name] = LINK_COLORS[i % len(LINK_COLORS)]
        self.colors["ground"] = GROUND_COLOR
        # slider displacement range over the sweep (for the guide length)
        self.disp = {}
        for s in m.sliders:
            d = None
            if result is not None and s.name in getattr(result, "displacement", {}):
                d = np.asarray(result.displacement[s.name], dtype=float)
                d = d[np.isfinite(d)]
            self.disp[s.name] = (float(d.min()), float(d.max())) if d is not None and d.size else (0.0, 0.0)
        self.loads = parse_loads(m)
        g = gravity_of(m)
        self.gravity = g if np.any(g != 0.0) else None
        fmax = [float(np.hypot(*ld.force[0])) for ld in self.loads if ld.force is not None]
        self.fmax = max(fmax, default=0.0)
        # data units per typographic point, for the label boxes (equal aspect: the tighter direction)
        (x0, x1), (y0, y1) = self.limits()
        self.pt = max((x1 - x0) / axes_in[0], (y1 - y0) / axes_in[1]) / 72.0

    def limits(self):
        """Axis limits: the drawing with a margin, widened to the aspect of the axes box (equal scales)."""
        pad = 6.0 * self.u
        (x0, y0), (x1, y1) = self.lo - pad, self.hi + pad
        want = self.axes_in[0] / self.axes_in[1]
        w, h = x1 - x0, y1 - y0
        if w / h < want:
            x0, x1 = (x0 + x1) / 2 - h * want / 2, (x0 + x1) / 2 + h * want / 2
        else:
            y0, y1 = (y0 + y1) / 2 - w / want / 2, (y0 + y1) / 2 + w / want / 2
        return (float(x0), float(x1)), (float(y0), float(y1))


# --------------------------------------------------------------------------- symbols
def _text(ax, xy, s, color="k", size=FONT, **kw):
    kw.setdefault("ha", "center")
    kw.setdefault("va", "center")
    return ax.text(xy[0], xy[1], s, color=color, fontsize=size, path_effects=_HALO, zorder=8, **kw)


def _arrow(ax, tail, head, color, lw=1.4, style="-|>"):
    return ax.annotate(
        "",
        xy=tuple(head),
        xytext=tuple(tail),
        arrowprops=dict(arrowstyle=style, color=color, lw=lw, shrinkA=0, shrinkB=0, mutation_scale=11),
        zorder=7,
    )


def _arc_arrow(ax, centre, r, a0, a1, color, lw=1.4):
    """Arc of radius ``r`` from angle ``a0`` to ``a1`` (rad) with an arrow head at ``a1``."""
    t = np.linspace(a0, a1, 40)
    x, y = centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)
    artists = ax.plot(x[:-3], y[:-3], "-", color=color, lw=lw, zorder=7, solid_capstyle="butt")
    artists.append(_arrow(ax, (x[-4], y[-4]), (x[-1], y[-1]), color, lw=lw))
    return artists


def _ground_symbol(ax, xy, u):
    """A pivot triangle over a hatched base at ``xy``."""
    x, y = xy
    tri = Polygon([(x, y), (x - u, y - 1.7 * u), (x + u, y - 1.7 * u)], closed=True, fc="white", ec="k", lw=1, zorder=3)
    ax.add_patch(tri)
    base = y - 1.7 * u
    segs = [[(x - 1.6 * u, base), (x + 1.6 * u, base)]]
    for k in range(5):
        xs = x - 1.2 * u + 0.7 * k * u
        segs.append([(xs, base), (xs - 0.6 * u, base - 0.6 * u)])
    lc = LineCollection(segs, colors="k", linewidths=0.8, zorder=3)
    ax.add_collection(lc)
    return [tri, lc]


def _hatched_line(ax, a, b, normal, u, color):
    """A guide from ``a`` to ``b`` with hatching on the ``normal`` side (a guide on the frame)."""
    a, b, n = np.asarray(a), np.asarray(b), np.asarray(normal)
    segs = [[tuple(a), tuple(b)]]
    length = float(np.hypot(*(b - a)))
    t = (b - a) / length if length > 0 else np.array([1.0, 0.0])
    k = max(int(length / (0.8 * u)), 1)
    for i in range(k + 1):
        p = a + t * (i * length / k)
        segs.append([tuple(p), tuple(p + 0.6 * u * (n - t))])
    lc = LineCollection(segs, colors=color, linewidths=0.9, zorder=1)
    ax.add_collection(lc)
    return [lc]


# --------------------------------------------------------------------------- one configuration
def _pivot_of(m, spec):
    """The point an input turns about: the input link's point shared with ground (or its reference link)."""
    link = m.links[spec.name]
    other = m.links[spec.relative_to or "ground"]
    for p in link.points:
        if p in other.local:
            return p
    return link.points[0]


def _draw_frame(ax, scene: _Scene, pts, rot, row=None):
    """Draw one configuration; return the artists (removed between the frames of an animation)."""
    m, u = scene.model, scene.u
    art = []
    finite = {p: np.asarray(xy, dtype=float) for p, xy in pts.items() if np.all(np.isfinite(xy))}
    placer = _Placer(scene.pt)
    for xy in finite.values():
        placer.add_point(xy, 0.6 * u)
    named = set()

    def label(cands, text, color, size=FONT, **kw):
        art.append(_text(ax, placer.place(cands, text, size), text, color=color, size=size, **kw))

    # ground pivots, and the name of the frame under the first one
    ground_pts = [p for p in m.links["ground"].points if p in finite]
    for p in ground_pts:
        art += _ground_symbol(ax, finite[p], u)
        placer.boxes.append((finite[p][0] - 1.6 * u, finite[p][1] - 2.3 * u, finite[p][0] + 1.6 * u, finite[p][1]))
    if ground_pts:
        g0 = finite[ground_pts[0]]
        cands = [g0 + d * u for d in np.array([[0.0, -3.0], [-4.2, -1.2], [4.2, -1.2], [0.0, -4.4]])]
        label(cands, "ground", GROUND_COLOR, size=FONT - 1)

    # point names, up and right of each point
    jointed = {p for p, _, _ in m.joints}
    for p, xy in finite.items():
        if p in jointed:
            art += ax.plot([xy[0]], [xy[1]], "o", mfc="white", mec="k", ms=5.5, mew=1.1, zorder=6)
        else:
            carriers = [c for c in m.carriers(p) if c != "ground"]
            color = scene.colors[carriers[0]] if carriers else GROUND_COLOR
            art += ax.plot([xy[0]], [xy[1]], "o", color=color, mec="k", ms=4, mew=0.6, zorder=6)
        text = _label(p)
        art.append(
            ax.annotate(
                text,
                tuple(xy),
                textcoords="offset points",
                xytext=(4, 3),
                fontsize=FONT - 0.5,
                path_effects=_HALO,
                zorder=8,
            )
        )
        placer.boxes.append(placer.box(xy + np.array([4, 3]) * scene.pt, text, FONT - 0.5, "left", "bottom"))

    art += _draw_inputs(ax, scene, finite, rot, placer, label)

    # links: a bar, or the convex hull of the points; the name by the middle
    for name in m.moving:
        link = m.links[name]
        if len(link.points) < 2 or not all(p in finite for p in link.points):
            continue
        color = scene.colors[name]
        xy = np.array([finite[p] for p in link.points])
        hull = _hull(xy)
        if len(hull) >= 3:
            art += ax.fill(hull[:, 0], hull[:, 1], color=color, alpha=0.22, zorder=1)
            closed = np.vstack([hull, hull[:1]])
            art += ax.plot(closed[:, 0], closed[:, 1], "-", color=color, lw=2, zorder=2)
            for p in link.points:  # interior points joined to the first
                if not any(np.allclose(finite[p], q) for q in hull):
                    art += ax.plot(*zip(xy[0], finite[p]), "-", color=color, lw=1.2, zorder=2)
            edges = [(hull[i], hull[(i + 1) % len(hull)]) for i in range(len(hull))]
            centre = hull.mean(axis=0)
            cands = [centre] + [(a + b) / 2 + _perp(a, b, s * 1.5 * u) for a, b in edges for s in (-1, 1)]
        else:
            art += ax.plot(hull[:, 0], hull[:, 1], "-", color=color, lw=2.5, zorder=2, solid_capstyle="round")
            a, b = hull[0], hull[-1]
            cands = [a + t * (b - a) + _perp(a, b, s * 1.5 * u) for t in (0.5, 0.35, 0.65, 0.2, 0.8) for s in (1, -1)]
        label(cands, _label(name), _dark(color), weight="bold")
        named.add(name)

    art += _draw_sliders(ax, scene, finite, rot, row, placer, named, label)
    art += _draw_gears(ax, scene, finite, rot, named, label)

    # other one-point links (no gear, no slider): the name by the point
    for name in m.moving:
        p = m.links[name].points[0]
        if name in named or len(m.links[name].points) > 1 or p not in finite or not np.isfinite(rot[name]):
            continue
        xy = finite[p]
        label(
            [xy + d * u for d in np.array([[0, -2.2], [0, 2.2], [3, 0], [-3, 0]])],
            _label(name),
            _dark(scene.colors[name]),
            weight="bold",
        )

    art += _draw_loads(ax, scene, finite, rot, label)
    return art


def _draw_sliders(ax, scene, finite, rot, row, placer, named, label):
    m, u = scene.model, scene.u
    art = []
    for s in m.sliders:
        t, n = _guide_axes(s, rot)
        dmin, dmax = scene.disp[s.name]
        margin = 2.5 * u if dmax > dmin else 0.25 * m.length_scale
        block_h = 0.8 * u
        if s.on == "ground":  # a fixed guide through the sketch position, drawn in every frame
            xy0 = np.asarray(m.points[s.point], dtype=float)
            a, b = xy0 + t * (dmin - margin), xy0 + t * (dmax + margin)
            art += _hatched_line(ax, a - n * block_h, b - n * block_h, -n, u, GROUND_COLOR)
        if s.point not in finite:
            continue
        xy = finite[s.point]
        if s.on != "ground":
            d_now = 0.0
            if row is not None and scene.result is not None:
                d_now = float(scene.result.displacement[s.name][row])
                d_now = d_now if np.isfinite(d_now) else 0.0
            a, b = xy + t * (dmin - d_now - margin), xy + t * (dmax - d_now + margin)
            art += ax.plot(*zip(a, b), "--", color=scene.colors[s.on], lw=1.2, zorder=1)
        corners = [xy + sx * 1.4 * u * t + sy * block_h * n for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        color = scene.colors.get(s.link, "0.8")
        blk = Polygon(corners, closed=True, fc=_light(color), ec=_dark(color), lw=1.2, zorder=4)
        ax.add_patch(blk)
        art.append(blk)
        placer.add_point(xy, 1.2 * u)
        if s.link not in named:
            cands = [xy + sy * 2.6 * u * n for sy in (1, -1)] + [xy + sx * 3.5 * u * t for sx in (1, -1)]
            label(cands, _label(s.link), _dark(color), weight="bold")
            named.add(s.link)
    return art


def _guide_axes(s, rot):
    """Unit vectors along and across a slider's guide in the current configuration."""
    th = rot[s.on] if np.isfinite(rot[s.on]) else 0.0
    t = _rotate(s.direction, th)
    t = t / np.hypot(*t)
    return t, np.array([-t[1], t[0]])


def _draw_gears(ax, scene, finite, rot, named, label):
    m, u = scene.model, scene.u
    art = []
    circle = np.linspace(0.0, 2 * np.pi, 145)
    for g in m.gears.values():
        r = m.pitch_radius(g.name)
        if r is None or g.centre not in finite:
            continue
        x, y = finite[g.centre]
        color = scene.colors.get(g.link, GROUND_COLOR)
        art += ax.plot(x + r * np.cos(circle), y + r * np.sin(circle), "-." if g.internal else "-", color=color, lw=1.3)
        th = rot[g.link]
        if np.isfinite(th):  # the rotation mark, where the gear's angle is known
            tip = (x + r * math.cos(th), y + r * math.sin(th))
            art += ax.plot([x, tip[0]], [y, tip[1]], "-", color=color, lw=1.0, zorder=2)
            art += ax.plot([tip[0]], [tip[1]], "o", color=color, ms=3.5, zorder=5)
        if len(m.links[g.link].points) == 1 and g.link != "ground" and g.link not in named:
            name = _label(g.link) if g.name == g.link else f"{_label(g.link)} ({_label(g.name)})"
            named.add(g.link)
        else:
            name = _label(g.name)
        text = f"{name}: z = {g.teeth}"
        rr = r + 1.3 * u
        angles = [70, 110, 45, 135, 90, 20, 160, -20, -160, -45, -135, -70, -110]
        cands = [(x + rr * math.cos(a), y + rr * math.sin(a)) for a in np.radians(angles)]
        if g.internal:
            rr = r - 1.3 * u
            cands += [(x + rr * math.cos(a), y + rr * math.sin(a)) for a in np.radians(angles)]
        label(cands, text, _dark(color))
    return art


def _perp(a, b, length):
    d = np.asarray(b, dtype=float) - np.asarray(a, dtype=float)
    n = np.hypot(*d)
    return np.array([-d[1], d[0]]) / n * length if n > 0 else np.array([0.0, length])


def _dark(color):
    from matplotlib.colors import to_rgb

    r, g, b = to_rgb(color)
    return (0.7 * r, 0.7 * g, 0.7 * b)


def _light(color):
    from matplotlib.colors import to_rgb

    r, g, b = to_rgb(color)
    return (0.55 + 0.45 * r, 0.55 + 0.45 * g, 0.55 + 0.45 * b)


def _draw_inputs(ax, scene, finite, rot, placer, label):
    m, u = scene.model, scene.u
    art = []
    at_pivot: dict = {}
    for spec in m.inputs:
        if spec.kind == "slider":
            s = next(sl for sl in m.sliders if sl.name == spec.name)
            if s.point not in finite:
                continue
            t, n = _guide_axes(s, rot)
            c = finite[s.point] + 2.6 * u * n
            art.append(_arrow(ax, c - 1.8 * u * t, c + 1.8 * u * t, INPUT_COLOR, style="<|-|>"))
            ends = np.array([c + 1.8 * u * t + 0.5 * u * n, c - 1.8 * u * t - 0.5 * u * n])
            placer.boxes.append((*ends.min(axis=0), *ends.max(axis=0)))
            cands = [c + 1.4 * u * n, c - 5.2 * u * n, c + 4.5 * u * t, c - 4.5 * u * t]
            label(cands, f"input: {_label(spec.name)}", INPUT_COLOR)
            continue
        p = _pivot_of(m, spec)
        if p not in finite:
            continue
        xy = finite[p]
        k = at_pivot.get(p, 0)
        at_pivot[p] = k + 1
        # several inputs at one pivot: arcs above, then below, farther out
        r = (2.2 + 1.4 * (k // 2) + 1.4 * (k % 2)) * u
        up = 1.0 if k % 2 == 0 else -1.0
        a0, a1 = (30.0, 150.0) if up > 0 else (210.0, 330.0)
        art += _arc_arrow(ax, xy, r, math.radians(a0), math.radians(a1), INPUT_COLOR)
        placer.boxes.append((xy[0] - r, min(xy[1], xy[1] + up * r), xy[0] + r, max(xy[1], xy[1] + up * r)))
        cands = [
            xy + np.array([0.0, up * (r + 1.2 * u)]),
            xy + np.array([-r - 4.0 * u, up * 0.6 * r]),
            xy + np.array([r + 4.0 * u, up * 0.6 * r]),
            xy + np.array([0.0, up * (r + 2.6 * u)]),
        ]
        label(cands, f"input: {_label(spec.label)}", INPUT_COLOR)
    return art


def _fmt_value(v: float) -> str:
    return f"{v:.4g}"


def _draw_loads(ax, scene, finite, rot, label):
    m, u = scene.model, scene.u
    fu, tu = _FORCE_UNIT.get(m.units, ""), _TORQUE_UNIT.get(m.units, "")
    art = []
    for ld in scene.loads:
        link = m.links[ld.link]
        if not all(p in finite for p in link.points) or not np.isfinite(rot[ld.link]):
            continue
        if ld.force is not None:
            f = np.asarray(ld.force[0], dtype=float)
            mag = float(np.hypot(*f))
            if mag > 0:
                at = _world(link, finite, rot, ld.point)
                e = f / mag
                length = (3.0 + 3.0 * mag / scene.fmax) * u
                tail = at - e * length
                art.append(_arrow(ax, tail, at, LOAD_COLOR, lw=2.0))
                text = f"{_fmt_value(mag)} {fu}" if fu else f"F = {_fmt_value(mag)}"
                w = 0.62 * FONT * len(text) * scene.pt / 2 + 0.6 * u
                n = np.array([-e[1], e[0]])
                cands = [tail - e * w, at - e * length / 2 + n * 1.6 * u, at - e * length / 2 - n * 1.6 * u]
                label(cands, text, LOAD_COLOR, weight="bold")
        if ld.torque is not None:
            T = float(ld.torque[0])
            if T != 0:
                c = finite[link.points[0]]
                r = 1.8 * u
                a0, a1 = (math.radians(-60), math.radians(60)) if T > 0 else (math.radians(60), math.radians(-60))
                art += _arc_arrow(ax, c, r, a0, a1, LOAD_COLOR, lw=1.8)
                text = f"{_fmt_value(T)} {tu}" if tu else f"T = {_fmt_value(T)}"
                cands = [c + np.array([r + 3.5 * u, 0.0]), c + np.array([r + 3.5 * u, -1.6 * u])]
                label(cands, text, LOAD_COLOR, weight="bold")
    return art


def _legend(ax, scene, paths: bool, loc="upper left", anchor=(1.02, 1.0)):
    m = scene.model
    h = [Line2D([], [], color=scene.colors[k], lw=2.5, label=_label(k)) for k in m.moving]
    h.append(Line2D([], [], ls="none", marker="^", mfc="white", mec="k", label="ground pivot"))
    if m.joints:
        h.append(Line2D([], [], ls="none", marker="o", mfc="white", mec="k", label="pin joint"))
    if m.sliders:
        h.append(Line2D([], [], ls="none", marker="s", mfc="0.8", mec="k", ms=8, label="slider on its guide"))
    if m.gears:
        h.append(Line2D([], [], color=GROUND_COLOR, lw=1.3, label="gear pitch circle (z teeth)"))
    if paths:
        h.append(Line2D([], [], color=PATH_COLOR, ls=":", lw=1.2, label="point paths"))
    if m.inputs:
        h.append(Line2D([], [], color=INPUT_COLOR, lw=1.4, marker=">", ms=5, label="input"))
    if scene.loads:
        unit = _FORCE_UNIT.get(m.units)
        h.append(Line2D([], [], color=LOAD_COLOR, lw=2, marker=">", ms=5, label=f"load{f' ({unit})' if unit else ''}"))
    if scene.gravity is not None:
        gx, gy = (v + 0.0 for v in scene.gravity)
        unit = f" {_label(m.units)}/s²" if m.units else ""
        turn = math.degrees(math.atan2(gy, gx)) - 90.0  # a triangle marker turned to point along g
        marker = (3, 0, turn)
        h.append(Line2D([], [], ls="none", marker=marker, color="k", ms=6, label=f"gravity ({gx:g}, {gy:g}){unit}"))
    return ax.legend(
        handles=h,
        loc=loc,
        bbox_to_anchor=anchor,
        fontsize=FONT,
        frameon=False,
        borderaxespad=0.0,
        handlelength=2.2,
    )


def _style_axes(ax, scene):
    m = scene.model
    (x0, x1), (y0, y1) = scene.limits()
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal", adjustable="box")  # the box shrinks to the drawing (the limits stay)
    unit = f" ({_label(m.units)})" if m.units else ""
    ax.set_xlabel(f"x{unit}", fontsize=8)
    ax.set_ylabel(f"y{unit}", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.grid(True, color="0.92", lw=0.6, zorder=0)


def _paths(ax, scene, result=None):
    """Dotted paths of the points off the frame; a path that comes back to its start is closed."""
    res = scene.result if result is None else result
    if res is None:
        return
    ground = set(scene.model.links["ground"].points)
    for p, xy in res.point.items():
        if p in ground:
            continue
        xy = np.asarray(xy, dtype=float)
        steps = np.hypot(*np.diff(xy, axis=0).T)
        steps = steps[np.isfinite(steps)]
        if len(xy) > 2 and steps.size and np.all(np.isfinite(xy[[0, -1]])):
            if np.hypot(*(xy[0] - xy[-1])) <= 1.5 * steps.max():
                xy = np.vstack([xy, xy[:1]])
        ax.plot(xy[:, 0], xy[:, 1], ":", lw=1.1, color=PATH_COLOR, zorder=0.5)


def _inputs_text(scene, row) -> str:
    m, res = scene.model, scene.result
    parts = []
    for k, spec in enumerate(m.inputs):
        v = float(res.q[row, k])
        if spec.kind == "slider":
            parts.append(f"{_label(spec.name)} = {v:.4g}" + (f" {_label(m.units)}" if m.units else ""))
        else:
            parts.append(f"{_label(spec.label)} = {math.degrees(v) % 360.0:.0f}°")
    return ", ".join(parts) + ("" if res.closed[row] else " (does not close)")


def _check_figsize(figsize):
    try:
        w, h = (float(v) for v in figsize)
    except (TypeError, ValueError):
        raise GearleverError(f"figsize must be a pair of numbers (width, height) in inches, got {figsize!r}") from None
    check_figure("figsize", w, h)
    return w, h


# --------------------------------------------------------------------------- public
def draw_mechanism(
    mech, result=None, row=None, ax=None, *, figsize=DRAWING_SIZE, legend: bool = True, note: str | None = None
):
    """Draw a mechanism at the sketch (or at ``row`` of ``result``) with the point paths of ``result``.

    Parameters
    ----------
    mech : gearlever.Mechanism
    result : MechanismResult, optional
        A sweep; the path of every point not on ground is drawn dotted.
    row : int, optional
        Row of ``result`` to draw; the sketch when None.
    ax : matplotlib Axes, optional
        Drawn into; a new figure of ``figsize`` inches (constrained layout) when None.
    figsize : pair of float
        Width and height (inches) of the new figure.
    legend : bool
        Draw the legend (links, symbols, loads, gravity) right of the axes.
    note : str, optional
        A line under the title (how the paths were swept, e.g. which inputs
        were held).

    Returns
    -------
    matplotlib.axes.Axes

    Notes
    -----
    Symbols follow the usual kinematic-diagram conventions (pivots hatched on
    the frame, pins as circles, sliders as blocks on guides, gears as pitch
    circles): J. J. Uicker, G. R. Pennock and J. E. Shigley, *Theory of
    Machines and Mechanisms*, 5th ed., Oxford University Press, 2017, ch. 1
    (kinematic diagrams).  A force arrow ends at its point; its length grows
    with the magnitude (relative to the largest load).

    Examples
    --------
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"mechanism": {"name": "crank"}, "points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> ax = draw_mechanism(m)
    >>> ax.get_title(), "input: crank" in [t.get_text() for t in ax.texts]
    ('crank', True)
    >>> plt.close(ax.figure)
    """
    if ax is None:
        ax = axes(None, figsize=_check_figsize(figsize))
    fig_w, fig_h = ax.figure.get_size_inches()
    pos = ax.get_position()
    scene = _Scene(mech, result, axes_in=(fig_w * pos.width * (0.8 if legend else 1.0), fig_h * pos.height))
    if row is not None:
        if result is None:
            raise GearleverError("row needs a result (a sweep) to draw from")
        row = int(row)
        if not -len(result.closed) <= row < len(result.closed):
            raise GearleverError(f"row must be in [0, {len(result.closed)}), got {row}")
        row %= len(result.closed)
    _paths(ax, scene)
    pts, rot = _configuration(mech, result, row)
    _draw_frame(ax, scene, pts, rot, row)
    _style_axes(ax, scene)
    title = _label(mech.model.name)
    if row is not None:
        title += f"\n{_inputs_text(scene, row)}"
    if note:
        title += f"\n{_label(note)}"
    ax.set_title(title, fontsize=10)
    if legend:
        _legend(ax, scene, paths=result is not None)
    return ax


def animate_mechanism(
    mech,
    result,
    path,
    fps: int = 12,
    dpi: int = ANIMATION_DPI,
    figsize=ANIMATION_SIZE,
    title: str | None = None,
    paths=None,
) -> Path:
    """Write a GIF with one frame per row of ``result`` to ``path`` (atomically); return the path.

    Every frame is the drawing of :func:`draw_mechanism` at that row (names,
    inputs, loads, legend), over the dotted paths of the whole sweep; the
    title gives the input values of the frame.

    Parameters
    ----------
    mech : gearlever.Mechanism
    result : MechanismResult
        The sweep: one frame per row.
    path : str or Path
        Output GIF (written atomically).
    fps : int
        Frames per second.
    dpi : int
        Pixels per inch; the default figure is 8 x 6 in at 100 dpi (800 x 600 px).
    figsize : pair of float
        Width and height (inches).
    title : str, optional
        First title line (the model's name by default).
    paths : MechanismResult, optional
        A finer sweep whose point paths are drawn dotted (default ``result``).

    Returns
    -------
    Path

    Notes
    -----
    Each frame is drawn with Agg and kept as a 256-colour palette image, one
    byte a pixel (GIF, CompuServe, *Graphics Interchange Format* 89a), so the
    memory is ``frames * width * height`` bytes; sizes are capped
    (:func:`gearlever.plotting._common.check_frames`).

    Examples
    --------
    >>> import tempfile, numpy as np
    >>> from gearlever.mechanism import Mechanism
    >>> m = Mechanism.from_dict({"points": {"O": [0, 0], "A": [1, 0]},
    ...     "links": {"ground": ["O"], "crank": ["O", "A"]}, "inputs": [{"link": "crank"}]})
    >>> r = m.solve(np.linspace(0, 2 * np.pi, 3, endpoint=False))
    >>> with tempfile.TemporaryDirectory() as d:
    ...     p = animate_mechanism(m, r, Path(d) / "crank.gif", figsize=(4, 3), dpi=50)
    ...     from PIL import Image
    ...     with Image.open(p) as im:
    ...         (im.size, im.n_frames)
    ((200, 150), 3)
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from PIL import Image

    frames = positive_int("frames", len(result.closed))
    fps = positive_int("fps", fps)
    dpi = positive_int("dpi", dpi)
    w, h = _check_figsize(figsize)
    check_figure("figsize", w, h, dpi)
    check_frames("frames", frames, w, h, dpi)
    fig = Figure(figsize=(w, h), dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    # fixed axes box (no layout engine): the legend has the right quarter
    box = (0.09, 0.09, 0.64, 0.8)
    ax = fig.add_axes(box)
    scene = _Scene(mech, result, axes_in=(w * box[2], h * box[3]), paths=paths)
    _paths(ax, scene, paths)
    _style_axes(ax, scene)
    _legend(ax, scene, paths=True, anchor=(1.03, 1.0))
    name = _label(mech.model.name) if title is None else _label(title)
    images = []
    current: list = []
    for i in range(frames):
        for a in current:
            a.remove()
        pts, rot = _configuration(mech, result, i)
        current = _draw_frame(ax, scene, pts, rot, i)
        ax.set_title(f"{name}\n{_inputs_text(scene, i)}", fontsize=9)
        canvas.draw()
        rgba = np.asarray(canvas.buffer_rgba())
        im = Image.fromarray(np.ascontiguousarray(rgba[..., :3]))
        images.append(im.quantize(colors=255, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE))
    path = Path(path)
    buf = io.BytesIO()
    images[0].save(buf, format="GIF", save_all=True, append_images=images[1:], duration=round(1000 / fps), loop=0)
    with atomic_path(path, suffix=".gif") as tmp:
        Path(tmp).write_bytes(buf.getvalue())
    return path
