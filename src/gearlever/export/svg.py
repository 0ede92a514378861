"""SVG of a :class:`~gearlever.export.outline.Drawing`: plain XML, one group per link, y up as in the model.

Each part is a ``<g id="link-NAME">`` holding its outlines (closed paths),
holes (circles) and guides (open paths), stroked, unfilled, in a colour of its
own; the document's width and height carry the model's units when they are
SVG units (mm, cm, in), so that it prints to scale.
"""

from __future__ import annotations

from xml.sax.saxutils import escape, quoteattr

from gearlever._io import write_text_atomic

__all__ = ["text", "write"]

#: Stroke colours of the parts, in turn.
COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#7f7f7f")


def _n(v: float) -> str:
    return f"{float(v) + 0.0:.6g}"


def _path(xy, close: bool) -> str:
    pts = [f"{_n(x)},{_n(-y)}" for x, y in xy]
    return "M" + " L".join(pts) + (" Z" if close else "")


def text(drawing) -> str:
    """The SVG document of ``drawing``."""
    x0, y0, x1, y1 = drawing.extent()
    pad = 0.05 * max(x1 - x0, y1 - y0, 1e-300)
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    w, h = x1 - x0, y1 - y0
    unit = drawing.units if drawing.units in ("mm", "cm", "in") else ""
    stroke = _n(max(w, h) / 600)
    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{_n(x0)} {_n(-y1)} {_n(w)} {_n(h)}" '
        f'width="{_n(w)}{unit}" height="{_n(h)}{unit}">',
        f"  <title>{escape(drawing.name)}</title>",
        f'  <rect x="{_n(x0)}" y="{_n(-y1)}" width="{_n(w)}" height="{_n(h)}" fill="white"/>',
    ]
    for i, part in enumerate(drawing.parts):
        colour = COLOURS[i % len(COLOURS)]
        lines.append(
            f'  <g id={quoteattr("link-" + part.name)} fill="none" stroke="{colour}" stroke-width="{stroke}" '
            'stroke-linejoin="round">'
        )
        lines.append(f"    <title>{escape(part.name)}</title>")
        for outline in part.outlines:
            lines.append(f'    <path d="{_path(outline, True)}"/>')
        for (cx, cy), r in part.holes:
            lines.append(f'    <circle cx="{_n(cx)}" cy="{_n(-cy)}" r="{_n(r)}"/>')
        for line in part.lines:
            lines.append(f'    <path d="{_path(line, False)}" stroke-dasharray="{_n(4 * float(stroke))}"/>')
        lines.append("  </g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write(drawing, path) -> None:
    """Write ``drawing`` to the SVG file ``path`` atomically."""
    write_text_atomic(path, text(drawing))
