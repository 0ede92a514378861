"""DXF of a :class:`~gearlever.export.outline.Drawing` (ezdxf, R2010): one layer per link.

Closed outlines are closed LWPOLYLINEs, holes CIRCLEs, guides LWPOLYLINEs, on
the layer named after the link; ``$INSUNITS`` is set from the model's units
(mm, cm, m, in, ft, um; 0, unitless, for any other label).  The bytes are the
same on every run (ezdxf's fixed dates and handles, classes in a fixed order).
"""

from __future__ import annotations

from gearlever._io import atomic_path

__all__ = ["INSUNITS", "write"]

#: ``$INSUNITS`` codes of the DXF reference (AutoCAD DXF Reference, HEADER section).
INSUNITS = {"in": 1, "ft": 2, "mm": 4, "cm": 5, "m": 6, "um": 13}


def _fix_class_order(doc) -> None:
    """The CLASSES section in a fixed order (ezdxf fills it from a set, in hash-seed order)."""
    from ezdxf.sections.classes import REQ_R2004, REQUIRED_CLASSES

    doc.classes.add_required_classes(doc.dxfversion)
    required = REQUIRED_CLASSES.get(doc.dxfversion, REQ_R2004)
    items = doc.classes.classes
    first = [k for k in items if k[0] in required]
    rest = sorted(k for k in items if k[0] not in required)
    doc.classes.classes = {k: items[k] for k in first + rest}


def document(drawing):
    """The ezdxf document of ``drawing`` (not saved)."""
    import ezdxf

    doc = ezdxf.new("R2010", units=INSUNITS.get(drawing.units, 0))
    msp = doc.modelspace()
    for i, part in enumerate(drawing.parts):
        if part.name not in doc.layers:
            doc.layers.add(part.name, color=1 + i % 7)
        attribs = {"layer": part.name}
        for outline in part.outlines:
            msp.add_lwpolyline([(float(x), float(y)) for x, y in outline], close=True, dxfattribs=attribs)
        for (cx, cy), r in part.holes:
            msp.add_circle((float(cx), float(cy)), float(r), dxfattribs=attribs)
        for line in part.lines:
            msp.add_lwpolyline([(float(x), float(y)) for x, y in line], dxfattribs=attribs)
    _fix_class_order(doc)
    return doc


def write(drawing, path) -> None:
    """Write ``drawing`` to the DXF file ``path`` atomically."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = document(drawing)
        with atomic_path(path) as tmp:
            doc.saveas(tmp)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
