"""A cam's profile as a drawing or a table: CSV, SVG and DXF, behind one registry of export formats.

:data:`EXPORTS` maps a file suffix to its :class:`ExportFormat`: a function
from the design to the file's text (CSV, SVG) or bytes (DXF), so that a front
end writes it atomically wherever it wants.  :func:`export_profile` picks the
format from the file name.  Another drawing (a mechanism's) can join the
registry with its own writers.  The profile is the cam surface in the cam's
frame (:attr:`~gearlever.cams.CamDesign.surface`), in the design's units.

The DXF is written by ezdxf (an optional dependency, imported only for a
DXF) with its fixed dates and handles, so the same design gives the same
bytes on every run.  Imports the standard library, :mod:`gearlever._format`
and :mod:`gearlever.errors` (ezdxf lazily); never pandas or matplotlib.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from gearlever._format import format_number
from gearlever.errors import GearleverError

__all__ = ["EXPORTS", "ExportFormat", "export_profile", "profile_csv", "profile_dxf", "profile_svg"]


@dataclass(frozen=True)
class ExportFormat:
    """One export format: its suffix, what it holds, and the function giving the file's content."""

    suffix: str
    description: str
    #: design -> str (text) or bytes
    write: Callable


def profile_csv(design) -> str:
    """The profile as CSV: a header ``x,y`` and one row per point, 12 significant digits.

    >>> from gearlever.cams import design_cam
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...     {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> print(profile_csv(design_cam(law, "translating-flat", base_radius=30.0, points=8)).splitlines()[1])
    0,30
    """
    rows = ["x,y"] + [f"{format_number(x)},{format_number(y)}" for x, y in design.surface]
    return "\n".join(rows) + "\n"


def _svg_unit(units: str) -> str:
    return units if units in ("mm", "cm", "in") else ""


def profile_svg(design) -> str:
    """The profile as an SVG polygon (y up, as drawn), with a dot at the cam centre.

    >>> from gearlever.cams import design_cam
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...     {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> profile_svg(design_cam(law, "translating-flat", base_radius=30.0, points=8)).count("<polygon")
    1
    """
    pts = design.surface
    r = float(max(abs(pts).max(), design.base_radius)) * 1.05
    path = " ".join(f"{format_number(x, 9)},{format_number(-y, 9)}" for x, y in pts)
    w = format_number(2 * r, 9)
    return (
        '<?xml version="1.0" encoding="UTF-8"?>\n'
        f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="{format_number(-r, 9)} {format_number(-r, 9)} {w} {w}" '
        f'width="{w}{_svg_unit(design.units)}" height="{w}{_svg_unit(design.units)}">\n'
        f"  <title>{design.follower} cam, base radius {format_number(design.base_radius, 9)} {design.units}</title>\n"
        f'  <polygon points="{path}" fill="none" stroke="black" stroke-width="{format_number(r / 500, 6)}"/>\n'
        f'  <circle cx="0" cy="0" r="{format_number(r / 100, 6)}" fill="black"/>\n'
        "</svg>\n"
    )


def _fix_class_order(doc) -> None:
    """The CLASSES section in a fixed order: ezdxf adds the classes of the entity types in use from a set,
    whose order changes with Python's hash seed; the required ones are kept first, in ezdxf's order."""
    from ezdxf.sections.classes import REQ_R2004, REQUIRED_CLASSES

    doc.classes.add_required_classes(doc.dxfversion)
    required = REQUIRED_CLASSES.get(doc.dxfversion, REQ_R2004)
    items = doc.classes.classes
    first = [k for k in items if k[0] in required]
    rest = sorted(k for k in items if k[0] not in required)
    doc.classes.classes = {k: items[k] for k in first + rest}


#: DXF ``$INSUNITS`` codes of the length units (0: unitless).
DXF_UNITS = {"mm": 4, "cm": 5, "m": 6, "in": 1, "ft": 2, "um": 13}


def profile_dxf(design) -> bytes:
    """The profile as a DXF (R2010): a closed polyline on layer ``CAM``, a small circle on ``CENTRE``.

    The bytes are those ezdxf writes to a file (its encoding of the
    document), with its fixed dates and handles: the same on every run.
    """
    import io

    import ezdxf

    # ezdxf's own switch for fixed dates and GUIDs: the same bytes on every run
    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = ezdxf.new("R2010", units=DXF_UNITS.get(design.units, 0))
        msp = doc.modelspace()
        pts = [(float(x), float(y)) for x, y in design.surface]
        msp.add_lwpolyline(pts, close=True, dxfattribs={"layer": "CAM"})
        msp.add_circle((0.0, 0.0), design.base_radius / 50, dxfattribs={"layer": "CENTRE"})
        _fix_class_order(doc)
        buf = io.StringIO(newline="")
        doc.write(buf)
        return doc.encode(buf.getvalue())
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed


#: Export formats of a cam profile by file suffix (lower case, with the dot).
EXPORTS: dict[str, ExportFormat] = {
    ".csv": ExportFormat(".csv", "points of the cam surface, x,y", profile_csv),
    ".svg": ExportFormat(".svg", "the cam surface as an SVG polygon", profile_svg),
    ".dxf": ExportFormat(".dxf", "the cam surface as a DXF polyline", profile_dxf),
}


def export_profile(design, name: str) -> str | bytes:
    """The content of the profile file ``name`` (its format from the suffix, :data:`EXPORTS`).

    Raises
    ------
    GearleverError
        An unknown suffix, naming the known ones.

    Examples
    --------
    >>> from gearlever.cams import design_cam
    >>> from gearlever.laws import law_from_segments
    >>> law = law_from_segments("displacement", "mm", [{"to": 180, "motion": "cycloidal", "rise": 10},
    ...     {"to": 360, "motion": "cycloidal", "rise": -10}])
    >>> cam = design_cam(law, "translating-flat", base_radius=30.0, points=8)
    >>> export_profile(cam, "cam.csv").splitlines()[0], sorted(EXPORTS)
    ('x,y', ['.csv', '.dxf', '.svg'])
    """
    suffix = "." + str(name).lower().rsplit(".", 1)[-1] if "." in str(name) else ""
    fmt = EXPORTS.get(suffix)
    if fmt is None:
        known = ", ".join(EXPORTS)
        raise GearleverError(f"profile must end with {known}, got {name!r}")
    return fmt.write(design)
