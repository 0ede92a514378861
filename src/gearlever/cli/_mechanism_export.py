"""``gearlever mechanism export``: the mechanism's parts as a DXF or SVG drawing, and one DXF per part.

Sub-command (added to ``gearlever mechanism`` by :func:`register_export`)::

    gearlever mechanism export MODEL --out M.dxf|M.svg [--at INPUT=VALUE ...] [--pin-diameter D] [--parts DIR]

Every link is a closed outline around its pins (a slot for two pins, the
rounded hull for three or more) on a layer (DXF) or group (SVG) named after
it, with a pin hole at each joint, slider blocks and guides, and every gear as
its whole tooth outline with a bore (:mod:`gearlever.export`).  The pose is
the sketch, or the inputs given with ``--at`` (degrees for a link, length for
a slider; inputs not given stay at the sketch).  ``--parts DIR`` writes one
DXF per part, each in its own body frame, into ``DIR`` (made if missing).
All files are written or none.
"""

from __future__ import annotations

import math

from gearlever.cli._common import check_output, check_output_folder, commit_outputs, named_values, positive_float
from gearlever.errors import GearleverError


def register_export(ms) -> None:
    e = ms.add_parser(
        "export",
        help="DXF or SVG of the mechanism's parts: link outlines, pin holes, guides, whole gears",
        description="Draw every part of the model for the workshop: each link a closed outline around its pins "
        "on a layer named after it, pin holes at the joints, slider blocks and guides, gears as their whole "
        "tooth outline (involute and root fillet) with a bore. DXF (units in the header) or SVG.",
    )
    e.add_argument("model", help="model file (TOML, or a linkage .links.json)")
    e.add_argument("--out", default=None, help="drawing of the whole mechanism (.dxf or .svg)")
    e.add_argument(
        "--at",
        action="append",
        metavar="INPUT=VALUE",
        help="pose: the value of an input (deg for a link, length for a slider), once per input given "
        "(default: the sketch)",
    )
    e.add_argument(
        "--pin-diameter",
        type=positive_float,
        default=None,
        help="diameter of the pin holes and bores (model units; default a fifth of the shortest link)",
    )
    e.add_argument("--parts", default=None, metavar="DIR", help="also write one DXF per part into this folder")
    e.set_defaults(func=_export)


def _export(args) -> int:
    from gearlever.cli._shared import load_model as _load
    from gearlever.export import FORMATS, export_parts, mechanism_drawing
    from gearlever.mechanism.sweep import input_labels

    if args.out is None and args.parts is None:
        raise GearleverError("give --out M.dxf|M.svg, --parts DIR, or both")
    check_output(args.out, "--out", tuple(FORMATS))
    if args.parts is not None:
        check_output_folder(args.parts, "--parts", create=True)
    mech = _load(args.model)
    specs = mech.model.inputs
    labels = input_labels(mech)
    given = named_values(args.at, "--at", labels)
    inputs = {
        name: value * (math.pi / 180.0 if specs[labels.index(name)].kind == "link" else 1.0)
        for name, value in given.items()
    }
    try:
        drawing = mechanism_drawing(mech, inputs or None, args.pin_diameter)
    except GearleverError as exc:
        text = str(exc)
        for lib, flag in (("inputs:", "--at:"), ("pin_diameter", "--pin-diameter")):
            if text.startswith(lib):
                text = flag + text[len(lib) :]
        raise GearleverError(text) from None
    if args.out is not None:
        FORMATS[args.out.rsplit(".", 1)[-1].lower()](drawing, args.out)
    if args.parts is not None:
        export_parts(drawing, args.parts)
    written = commit_outputs()
    for note in drawing.notes:
        print(f"note: {note}")
    for path in written:
        print(f"wrote {path}")
    return 0
