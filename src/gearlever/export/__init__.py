"""Mechanisms out to CAD: each link's outline, pin holes, slider guides and whole gears, as DXF or SVG.

- :mod:`~gearlever.export.outline`: the geometry (:func:`mechanism_drawing`), no file format;
- :mod:`~gearlever.export.dxf`: DXF (ezdxf), one layer per link, ``$INSUNITS`` from the model's units;
- :mod:`~gearlever.export.svg`: plain SVG (XML), one group per link.

:data:`FORMATS` maps a file suffix to its writer ``write(drawing, path)``;
:func:`export` picks the writer from the path's suffix and writes atomically
(:func:`gearlever._io.atomic_path`).  STEP and STL are not written: see the
guide's "Export to CAD" page for why.

Examples
--------
>>> import tempfile, pathlib
>>> from gearlever.mechanism import Mechanism
>>> from gearlever.data import example_path
>>> out = pathlib.Path(tempfile.mkdtemp()) / "fourbar.svg"
>>> d = export(Mechanism.load(example_path("fourbar.toml")), out)
>>> out.read_text().startswith("<?xml"), [p.name for p in d.parts]
(True, ['ground', 'crank', 'coupler', 'rocker'])
"""

from __future__ import annotations

from pathlib import Path

from gearlever.errors import GearleverError
from gearlever.export import dxf, svg
from gearlever.export.outline import Drawing, Part, mechanism_drawing

__all__ = ["FORMATS", "Drawing", "Part", "mechanism_drawing", "export", "export_parts"]

#: File suffix -> writer ``write(drawing, path)``.
FORMATS = {"dxf": dxf.write, "svg": svg.write}


def export(mech, path, inputs=None, pin_diameter=None) -> Drawing:
    """Write ``mech`` at the sketch (or at ``inputs``) to ``path`` (.dxf or .svg); return the drawing.

    Parameters as for :func:`~gearlever.export.outline.mechanism_drawing`.

    Examples
    --------
    >>> import tempfile, pathlib, ezdxf
    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> out = pathlib.Path(tempfile.mkdtemp()) / "zrdpm.dxf"
    >>> _ = export(Mechanism.load(example_path("zrdpm_gear_contour.toml")), out, inputs={"gear9": 0.5})
    >>> doc = ezdxf.readfile(out)
    >>> sorted(layer.dxf.name for layer in doc.layers if layer.dxf.name[0].islower()), doc.audit().has_errors
    (['gear8', 'gear9', 'ground', 'lever1'], False)
    """
    fmt = Path(path).suffix.lower().lstrip(".")
    if fmt not in FORMATS:
        raise GearleverError(f"path must end with {' or '.join('.' + k for k in FORMATS)}, got {str(path)!r}")
    drawing = mechanism_drawing(mech, inputs, pin_diameter)
    FORMATS[fmt](drawing, path)
    return drawing


def export_parts(drawing: Drawing, folder) -> list:
    """One DXF per part in ``folder`` (``<link>.dxf``), each in its own body frame; return the paths.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from gearlever.mechanism import Mechanism
    >>> from gearlever.data import example_path
    >>> d = mechanism_drawing(Mechanism.load(example_path("slider_crank.toml")))
    >>> [p.name for p in export_parts(d, tempfile.mkdtemp())]
    ['ground.dxf', 'crank.dxf', 'rod.dxf', 'piston.dxf']
    """
    paths = []
    for part in drawing.parts:
        one = Drawing(drawing.name, drawing.units, (part.local(),), drawing.pin_diameter, drawing.inputs)
        path = Path(folder) / f"{part.name}.dxf"
        dxf.write(one, path)
        paths.append(path)
    return paths
