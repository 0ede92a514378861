"""``gearlever gear mesh|interference|profile``: involute tooth geometry of a pair, interference limits, tooth outlines.

::

    gearlever gear mesh --module M --teeth Z1 Z2 [--internal | --rack] [--shift X1 X2 | --center-distance A]
            [--pressure-angle 20] [--helix BETA] [--face-width B] [--addendum 1] [--dedendum 1.25]
            [--no-tip-shortening] [--json]
    gearlever gear interference --teeth Z [--pressure-angle 20] [--addendum 1]
    gearlever gear profile --module M --teeth Z [--shift X] ... --out G.dxf|G.svg|G.csv

Library: :mod:`gearlever.gears.geometry`.  Angles in degrees here; lengths in
the unit of the module (mm).  Numbers are written with 10 significant digits
(:data:`gearlever._format.DIGITS_DESIGN`).  Bad input (teeth not positive
integers, a module or face width not above 0, a helix of 45 deg or more, a
shift that points a tooth, a contact ratio below 1, an internal pair whose
tips interfere, a centre distance the shifts cannot reach): exit 2, one line
naming the flag.
"""

from __future__ import annotations

import argparse
import math

from gearlever.cli._common import capped_float, capped_int, emit, finite_float, flagged, to_json

#: Largest module, face width and centre distance accepted (mm).
MAX_LENGTH = 1e6
#: Largest tooth number.
MAX_TEETH = 10000
#: Most points along one flank of a profile.
MAX_POINTS = 2000

_FLAGS = {
    "module": "--module",
    "teeth": "--teeth",
    "teeth1": "--teeth",
    "teeth2": "--teeth",
    "shift": "--shift",
    "shift1": "--shift",
    "shift2": "--shift",
    "center_distance": "--center-distance",
    "pressure_angle": "--pressure-angle",
    "helix": "--helix",
    "face_width": "--face-width",
    "addendum": "--addendum",
    "dedendum": "--dedendum",
    "root_radius": "--root-radius",
    "points": "--points",
    "split": "--split",
    "tip_diameter": "--tip-diameter",
}


def _flagged(exc):
    """The library's error with its parameter names as this command's flags (``shift1`` -> ``--shift``)."""
    import re

    from gearlever.errors import GearleverError

    text = str(flagged(exc, _FLAGS))
    text = re.sub(r"(?<![-\w])(shift|teeth)[12]\b", lambda m: "--" + m.group(1), text)
    text = re.sub(r"--(shift|teeth)[12]\b", lambda m: "--" + m.group(1), text)
    # the contact-ratio refusal names every flag that sets it
    text = re.sub(r"^(--teeth [^:]*) with shift (.*) and addendum ", r"\1 with --shift \2 and --addendum ", text)
    text = text.replace(
        "--teeth (the ring) must exceed --teeth,", "--teeth: the ring's (the second) must exceed the pinion's,"
    )
    return GearleverError(text)


def _teeth_arg(text: str) -> int:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if not math.isfinite(value) or value != int(value) or value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    if value > MAX_TEETH:
        raise argparse.ArgumentTypeError(f"must be at most {MAX_TEETH}, got {text!r}")
    return int(value)


def _common(p, *, pair: bool) -> None:
    length = capped_float(MAX_LENGTH)
    p.add_argument("--module", required=True, type=length, metavar="M", help="normal module (mm, > 0)")
    p.add_argument(
        "--teeth",
        required=True,
        nargs="+" if pair else None,
        type=_teeth_arg,
        metavar="Z",
        help="tooth numbers Z1 Z2 (one for --rack)" if pair else "tooth number",
    )
    p.add_argument("--pressure-angle", type=finite_float, default=20.0, metavar="DEG", help="normal, default 20")
    p.add_argument("--helix", type=finite_float, default=0.0, metavar="DEG", help="helix angle, below 45 (default 0)")
    p.add_argument("--addendum", type=finite_float, default=1.0, metavar="HA", help="basic rack addendum (modules)")
    p.add_argument("--dedendum", type=finite_float, default=1.25, metavar="HF", help="basic rack dedendum (modules)")
    p.add_argument(
        "--root-radius", type=finite_float, default=0.38, metavar="RHO", help="rack tip radius (modules, 0.38)"
    )


def register(sub) -> None:
    from gearlever.cli import OneLineParser

    p = sub.add_parser("gear", help="involute gear geometry: a mesh, interference limits, a tooth outline")
    inner = p.add_subparsers(dest="gear_command", metavar="ACTION", parser_class=OneLineParser)
    inner.required = True

    m = inner.add_parser("mesh", help="geometry of a pair: working pressure angle, centre distance, contact ratio")
    _common(m, pair=True)
    kind = m.add_mutually_exclusive_group()
    kind.add_argument("--internal", action="store_true", help="gear 2 is a ring (internal gear)")
    kind.add_argument("--rack", action="store_true", help="gear 1 meshes a rack")
    sh = m.add_mutually_exclusive_group()
    sh.add_argument("--shift", nargs="+", type=finite_float, metavar="X", help="profile shifts X1 X2 (normal)")
    sh.add_argument(
        "--center-distance", type=capped_float(MAX_LENGTH), metavar="A", help="wanted centre distance: find the shifts"
    )
    m.add_argument(
        "--split",
        choices=("inverse", "proportional", "equal", "pinion"),
        default="inverse",
        help="how --center-distance's sum of shifts is split (default inverse to the teeth)",
    )
    m.add_argument("--face-width", type=capped_float(MAX_LENGTH), metavar="B", help="face width (mm) for the overlap")
    m.add_argument("--no-tip-shortening", action="store_true", help="keep the tips at d + 2 (ha + x) m")
    m.add_argument("--json", action="store_true", help="JSON instead of text")
    m.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")
    m.set_defaults(func=_mesh)

    i = inner.add_parser("interference", help="the largest gear a standard pinion meshes, and whether a rack fits")
    i.add_argument("--teeth", required=True, type=_teeth_arg, metavar="Z", help="pinion tooth number")
    i.add_argument("--pressure-angle", type=finite_float, default=20.0, metavar="DEG", help="default 20")
    i.add_argument("--addendum", type=finite_float, default=1.0, metavar="HA", help="addendum (modules), default 1")
    i.add_argument("--json", action="store_true", help="JSON instead of text")
    i.set_defaults(func=_interference)

    f = inner.add_parser("profile", help="the whole gear's tooth outline (involute and root fillets)")
    _common(f, pair=False)
    f.add_argument("--shift", type=finite_float, default=0.0, metavar="X", help="profile shift (normal)")
    f.add_argument("--internal", action="store_true", help="an internal gear (ring)")
    f.add_argument("--tip-diameter", type=capped_float(MAX_LENGTH), metavar="DA", help="a shortened tip (mm)")
    f.add_argument(
        "--points", type=capped_int(MAX_POINTS, 4), default=24, metavar="N", help="points along each flank (24)"
    )
    f.add_argument("--out", required=True, metavar="FILE", help="G.dxf, G.svg or G.csv")
    f.set_defaults(func=_profile)


def _num(v) -> str:
    from gearlever._format import DIGITS_DESIGN, quantize

    v = float(v)
    if not math.isfinite(v):
        return "-"
    return f"{quantize(v, 0.0, DIGITS_DESIGN) + 0.0:.{DIGITS_DESIGN}g}"


def _mesh(args) -> int:
    from gearlever._format import DIGITS_DESIGN, rounded
    from gearlever.errors import GearleverError
    from gearlever.gears.geometry import mesh

    teeth = args.teeth
    if args.rack:
        if len(teeth) != 1:
            raise GearleverError(f"--teeth takes one tooth number with --rack, got {len(teeth)}")
        z1, z2 = teeth[0], None
    elif len(teeth) != 2:
        raise GearleverError(f"--teeth takes two tooth numbers Z1 Z2, got {len(teeth)}")
    else:
        z1, z2 = teeth
    x1 = x2 = 0.0
    if args.shift is not None:
        want = 1 if args.rack else 2
        if len(args.shift) != want:
            raise GearleverError(f"--shift takes {want} number(s), got {len(args.shift)}")
        x1 = args.shift[0]
        x2 = args.shift[1] if want == 2 else 0.0
    kind = "rack" if args.rack else ("internal" if args.internal else "external")
    try:
        g = mesh(
            args.module,
            z1,
            z2,
            x1,
            x2,
            kind=kind,
            center_distance=args.center_distance,
            split=args.split,
            pressure_angle=math.radians(args.pressure_angle),
            helix=math.radians(args.helix),
            face_width=args.face_width,
            addendum=args.addendum,
            dedendum=args.dedendum,
            root_radius=args.root_radius,
            tip_shortening=not args.no_tip_shortening,
        )
    except GearleverError as exc:
        raise _flagged(exc) from None
    rec = rounded(g.record(), DIGITS_DESIGN)
    if args.json:
        emit(to_json(rec), args.out)
        return 0
    spur = "helical" if g.helix else "spur"
    names = "pinion / rack" if kind == "rack" else ("pinion / ring" if kind == "internal" else "gear 1 / gear 2")
    teeth_text = f"{z1}" + ("" if z2 is None else f" / {z2}")

    def pair(key, unit=""):
        vals = rec[key]
        text = " / ".join("-" if v is None else (_num(v) if not isinstance(v, bool) else str(v).lower()) for v in vals)
        return text + (f" {unit}" if unit else "")

    lines = [
        f"{kind} {spur} mesh, module {_num(g.module)} mm, teeth {teeth_text}, pressure angle "
        f"{_num(math.degrees(g.pressure_angle))} deg"
        + (f", helix {_num(math.degrees(g.helix))} deg" if g.helix else ""),
        f"values per gear: {names}",
        f"working pressure angle (transverse)   {_num(rec['working_pressure_angle_deg'])} deg",
        f"center distance                       {_num(rec['center_distance'])} mm"
        + (" (gear centre to the rack's reference line)" if kind == "rack" else ""),
        f"center distance modification y       {_num(rec['center_distance_modification'])} module",
        f"tip shortening k                      {_num(rec['tip_shortening'])} module",
        f"profile shift x                       {pair('shift', 'module')}",
        f"reference diameter                    {pair('reference_diameter', 'mm')}",
        f"base diameter                         {pair('base_diameter', 'mm')}",
        f"tip diameter                          {pair('tip_diameter', 'mm')}",
        f"root diameter                         {pair('root_diameter', 'mm')}",
        f"tip thickness (normal)                {pair('tip_thickness', 'mm')}",
        f"contact ratio transverse              {_num(rec['contact_ratio_transverse'])}",
        "contact ratio overlap                 "
        + (_num(rec["contact_ratio_overlap"]) if rec["contact_ratio_overlap"] is not None else "- (give --face-width)"),
        "contact ratio total                   "
        + (_num(rec["contact_ratio_total"]) if rec["contact_ratio_total"] is not None else "-"),
        f"undercut                              {pair('undercut')}",
        "fewest teeth without undercut         "
        + " / ".join("-" if v is None else str(v) for v in rec["min_teeth_no_undercut"]),
        f"interference                          {pair('interference')}",
    ]
    emit("\n".join(lines), args.out)
    return 0


def _interference(args) -> int:
    from gearlever.errors import GearleverError
    from gearlever.gears.geometry import max_mating_teeth, min_pinion_teeth

    try:
        largest = max_mating_teeth(args.teeth, pressure_angle=math.radians(args.pressure_angle), addendum=args.addendum)
        rack_min = min_pinion_teeth(math.inf, pressure_angle=math.radians(args.pressure_angle), addendum=args.addendum)
    except GearleverError as exc:
        raise flagged(
            exc, {"teeth": "--teeth", "pressure_angle": "--pressure-angle", "addendum": "--addendum"}
        ) from None
    rack_fits = largest is None
    if args.json:
        emit(
            to_json(
                {
                    "teeth": args.teeth,
                    "max_mating_teeth": largest,
                    "rack_fits": rack_fits,
                    "min_pinion_teeth_rack": rack_min,
                }
            )
        )
        return 0
    head = (
        f"pinion of {args.teeth} teeth, pressure angle {_num(args.pressure_angle)} deg, "
        f"addendum {_num(args.addendum)} module"
    )
    if rack_fits:
        body = "meshes any gear and a rack without interference"
    elif largest < args.teeth:
        body = f"interferes even with a gear of its own size (largest mating gear {largest} teeth); a rack does not fit"
    else:
        body = f"largest mating gear without interference: {largest} teeth; a rack does not fit"
    emit(f"{head}\n{body}\nfewest pinion teeth that mesh a rack: {rack_min}")
    return 0


def _profile(args) -> int:
    from pathlib import Path

    from gearlever.cli._common import check_output
    from gearlever.errors import GearleverError
    from gearlever.gears.geometry import tooth_outline

    suffix = Path(args.out).suffix.lower()
    if suffix not in (".dxf", ".svg", ".csv"):
        raise GearleverError(f"--out must end with .dxf, .svg or .csv, got {args.out!r}")
    check_output(args.out)
    try:
        xy = tooth_outline(
            args.module,
            args.teeth,
            args.shift,
            pressure_angle=math.radians(args.pressure_angle),
            helix=math.radians(args.helix),
            addendum=args.addendum,
            dedendum=args.dedendum,
            root_radius=args.root_radius,
            internal=args.internal,
            tip_diameter=args.tip_diameter,
            points=args.points,
        )
    except GearleverError as exc:
        raise _flagged(exc) from None
    if suffix == ".csv":
        from gearlever._format import format_number

        rows = ["x_mm,y_mm"] + [f"{format_number(x, 12)},{format_number(y, 12)}" for x, y in xy]
        emit("\n".join(rows), args.out)
    elif suffix == ".svg":
        emit(_svg(xy), args.out)
    else:
        _dxf(xy, args.out, f"gear_z{args.teeth}")
    return 0


def _svg(xy) -> str:
    r = float(max(abs(xy).max(), 1e-9)) * 1.05
    pts = " ".join(f"{x:.6f},{-y:.6f}" for x, y in xy)
    return (
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * r:.6f}mm" height="{2 * r:.6f}mm" '
        f'viewBox="{-r:.6f} {-r:.6f} {2 * r:.6f} {2 * r:.6f}">\n'
        f'<polygon points="{pts}" fill="none" stroke="black" stroke-width="{r / 500:.6f}"/>\n'
        f'<circle cx="0" cy="0" r="{r / 200:.6f}" fill="black"/>\n</svg>'
    )


def _dxf(xy, path, layer: str) -> None:
    import ezdxf
    import numpy as np

    from gearlever._io import atomic_path

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc = ezdxf.new("R2010", units=4)  # $INSUNITS 4: millimetres
        doc.layers.add(layer, color=1)
        poly = doc.modelspace().add_lwpolyline([], close=True, dxfattribs={"layer": layer})
        # one extend of (x, y, start width, end width, bulge) rows: ezdxf's per-point append copies the array
        # each time (quadratic: 13 s for 26k points)
        rows = np.zeros((len(xy), 5))
        rows[:, :2] = xy
        poly.lwpoints.extend(rows)
        with atomic_path(path) as tmp:
            doc.saveas(tmp)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
