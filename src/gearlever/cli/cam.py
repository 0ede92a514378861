"""``gearlever cam design``: the disc cam that gives a motion law.

::

    gearlever cam design LAW.toml --follower translating-roller|translating-flat|oscillating-roller|oscillating-flat
        [--base-radius R] [--roller-radius r] [--offset e] [--arm L --pivot-distance D]
        [--max-pressure-angle DEG] [--min-curvature-radius RHO] [--rpm N] [--points N]
        --out CAM.toml [--profile P.csv|P.svg|P.dxf] [--report R.json] [--figure F.png]
    gearlever cam view CAM.toml --out PAGE.html [--frames N]

Without ``--base-radius`` the base circle is sized: the smallest meeting
``--max-pressure-angle`` and/or ``--min-curvature-radius``.  With both, the
design at ``--base-radius`` is checked against the bounds and refused when it
breaks one (the line gives the smallest base radius meeting it).  The search
samples at most :data:`SIZING_POINTS` cam angles, so a design at a finer
``--points`` may show the bound passed by its sampling (1e-6 deg on the lift law).  Every file
is written atomically; every refusal is one line naming the file, segment or flag.

``cam view`` writes the interactive page of the cam turning with its follower
(:func:`gearlever.plotting.cam_viewer.cam_viewer_html`); ``gearlever mechanism
view CAM.toml`` does the same.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from gearlever.cli._common import (
    capped_int,
    check_output,
    emit,
    finite_float,
    positive_float,
    to_json,
)
from gearlever.cli._shared import add_page_arguments, cam_page, check_page_out
from gearlever.errors import GearleverError, a

#: Most profile points.
MAX_POINTS = 1_000_000
#: Most points the base-circle search evaluates per candidate radius (it tries about 130 radii).
SIZING_POINTS = 36_000


def register(sub) -> None:
    from gearlever.cams.followers import FOLLOWERS

    p = sub.add_parser("cam", help="disc cams for a motion law (LAW.toml)")
    ss = p.add_subparsers(dest="cam_command", metavar="SUBCOMMAND")
    ss.required = True
    d = ss.add_parser(
        "design",
        help="profile, pressure angle, curvature and undercut of the disc cam giving a law",
        description="Design the disc cam that gives LAW.toml's output to a follower; the cam turns "
        "counterclockwise, the follower touches the base circle at the law's lowest output.",
    )
    d.add_argument("law", metavar="LAW.toml", help="the motion law (segments or samples)")
    d.add_argument("--follower", required=True, choices=list(FOLLOWERS), help="follower kind")
    d.add_argument("--base-radius", type=positive_float, default=None, help="base circle radius (length)")
    d.add_argument("--roller-radius", type=positive_float, default=None, help="roller radius (roller followers)")
    d.add_argument(
        "--offset",
        type=finite_float,
        default=0.0,
        help="translating: follower axis offset from the cam centre; oscillating flat: face offset from the pivot",
    )
    d.add_argument("--arm", type=positive_float, default=None, help="oscillating roller: pivot to roller centre")
    d.add_argument("--pivot-distance", type=positive_float, default=None, help="oscillating: cam centre to pivot")
    d.add_argument("--max-pressure-angle", type=positive_float, default=None, metavar="DEG", help="bound, degrees")
    d.add_argument(
        "--min-curvature-radius", type=finite_float, default=None, metavar="RHO", help="bound on the convex surface"
    )
    d.add_argument("--rpm", type=positive_float, default=None, help="cam speed: adds per-second peaks to the report")
    d.add_argument(
        "--points",
        type=capped_int(MAX_POINTS, 8),
        default=3600,
        help=f"profile points (default 3600, at most {MAX_POINTS:,})",
    )
    d.add_argument("--out", required=True, metavar="CAM.toml", help="cam data file to write")
    d.add_argument("--profile", default=None, metavar="P.csv|P.svg|P.dxf", help="cam surface in the cam's frame")
    d.add_argument("--report", default=None, metavar="R.json", help="JSON report")
    d.add_argument("--figure", default=None, metavar="F.png", help="SVAJ diagrams and the profile")
    d.set_defaults(func=_design)
    v = ss.add_parser(
        "view",
        help="interactive HTML page (one self-contained file) of the cam turning with its follower",
        description="Write one HTML page that animates CAM.toml (written by gearlever cam design): the cam "
        "turning counterclockwise, the follower at the law's output, the output and pressure angle plotted.",
    )
    v.add_argument("cam", metavar="CAM.toml", help="cam file written by gearlever cam design")
    add_page_arguments(v, "the cam")
    v.set_defaults(func=_view)


def _design(args) -> int:
    import numpy as np

    from gearlever._format import rounded
    from gearlever.cams import FOLLOWERS, design_cam, size_base_radius
    from gearlever.cams.camfile import CAM_DIGITS, cam_toml
    from gearlever.cams.export import EXPORTS, export_profile
    from gearlever.laws import load_law

    kind = FOLLOWERS[args.follower]
    for flag, path in (("--profile", args.profile), ("--report", args.report), ("--figure", args.figure)):
        check_output(path, flag)
    if args.profile is not None and not args.profile.lower().endswith(tuple(EXPORTS)):
        raise GearleverError(f"--profile must end with .csv, .svg or .dxf, got {args.profile!r}")
    if args.figure is not None and not args.figure.lower().endswith(".png"):
        raise GearleverError(f"--figure must end with .png, got {args.figure!r}")
    if args.max_pressure_angle is not None and not args.max_pressure_angle < 90:
        raise GearleverError(f"--max-pressure-angle must be below 90 deg, got {args.max_pressure_angle:g}")
    if args.min_curvature_radius is not None and args.min_curvature_radius < 0:
        raise GearleverError(f"--min-curvature-radius must be >= 0, got {args.min_curvature_radius:g}")
    given = {"roller_radius": args.roller_radius, "arm": args.arm, "pivot_distance": args.pivot_distance}
    flags = {"roller_radius": "--roller-radius", "arm": "--arm", "pivot_distance": "--pivot-distance"}
    for name, value in given.items():
        if name in kind.needs and value is None:
            raise GearleverError(f"{flags[name]} is required for {a(kind.name)} follower")
        if name not in kind.needs and value is not None:
            raise GearleverError(f"{flags[name]} does not apply to {a(kind.name)} follower")
    if args.offset != 0 and "offset" not in kind.needs:
        raise GearleverError(f"--offset does not apply to {a(kind.name)} follower")
    dims = {
        "roller_radius": args.roller_radius or 0.0,
        "offset": args.offset,
        "arm": args.arm,
        "pivot_distance": args.pivot_distance,
    }
    law = load_law(args.law)
    sizing = args.max_pressure_angle is not None or args.min_curvature_radius is not None
    bound_phi = None if args.max_pressure_angle is None else math.radians(args.max_pressure_angle)
    sized = None
    if sizing:
        try:
            sized = size_base_radius(
                law,
                kind.name,
                **dims,
                max_pressure_angle=bound_phi,
                min_curvature_radius=args.min_curvature_radius,
                points=min(args.points, SIZING_POINTS),
            )
        except GearleverError as exc:
            raise GearleverError(_points_flag(_flagged(exc), min(args.points, SIZING_POINTS))) from None
    if args.base_radius is None and sized is None:
        raise GearleverError(
            "--base-radius is required (or give --max-pressure-angle or --min-curvature-radius to size it)"
        )
    rb = args.base_radius if args.base_radius is not None else sized
    try:
        cam = design_cam(law, kind.name, base_radius=rb, **dims, points=args.points)
    except GearleverError as exc:
        text = _points_flag(_flagged(exc), args.points)
        if text.startswith(("undercut", "base radius")):
            who = "--base-radius" if args.base_radius is not None else "the sized base radius"
            roller = f" with --roller-radius {args.roller_radius:g}" if args.roller_radius else ""
            raise GearleverError(f"{who} {rb:.6g}{roller}: {text}") from None
        raise GearleverError(text) from None
    if args.base_radius is not None and sizing:
        if bound_phi is not None and cam.pressure_angle_max > bound_phi * (1 + 1e-12):
            raise GearleverError(
                f"--max-pressure-angle {args.max_pressure_angle:g}: the pressure angle reaches "
                f"{math.degrees(cam.pressure_angle_max):.4g} deg with --base-radius {rb:g}; "
                f"the smallest base radius meeting the bounds is {sized:.6g}"
            )
        if args.min_curvature_radius is not None and cam.curvature_radius_min < args.min_curvature_radius:
            raise GearleverError(
                f"--min-curvature-radius {args.min_curvature_radius:g}: the convex surface's radius of curvature "
                f"falls to {cam.curvature_radius_min:.6g} with --base-radius {rb:g}; "
                f"the smallest base radius meeting the bounds is {sized:.6g}"
            )
    report = cam.summary()
    report["law"] = args.law
    report["base_radius_from"] = "--base-radius" if args.base_radius is not None else "sized"
    report["base_radius_sized"] = sized
    cont = law.continuity()
    report["law_continuous"] = cont.ok
    report["law_discontinuities"] = cont.problems()
    vals = law.evaluate(cam.theta)
    scale = 180 / math.pi if law.output == "angle" else 1.0
    unit = "deg" if law.output == "angle" else law.units
    for field in ("v", "a", "j"):
        report[f"{field}_max_{unit}_per_rad" + ("" if field == "v" else ("2" if field == "a" else "3"))] = (
            float(np.max(np.abs(getattr(vals, field)))) * scale
        )
    if args.rpm is not None:
        ps = vals.per_second(args.rpm)
        report["rpm"] = args.rpm
        report[f"v_max_{unit}_per_s"] = float(np.max(np.abs(ps.v))) * scale
        report[f"a_max_{unit}_per_s2"] = float(np.max(np.abs(ps.a))) * scale
        report[f"j_max_{unit}_per_s3"] = float(np.max(np.abs(ps.j))) * scale
    report = rounded(report, CAM_DIGITS)
    law_table = law.to_dict()
    if law_table.get("samples", 1) is None:
        src = Path(args.law).parent / _samples_name(args.law)
        law_table["samples"] = os.path.relpath(src, Path(args.out).resolve().parent)
    emit(cam_toml(cam, law_table, report, f"Written by gearlever cam design from {Path(args.law).name}"), args.out)
    if args.profile is not None:
        content = export_profile(cam, args.profile)
        if isinstance(content, bytes):
            from gearlever._io import atomic_path

            with atomic_path(args.profile) as tmp:
                Path(tmp).write_bytes(content)
        else:
            emit(content, args.profile, "--profile")
    if args.report is not None:
        emit(to_json(report), args.report, "--report")
    if args.figure is not None:
        from gearlever.plotting._common import save
        from gearlever.plotting.cam import cam_design_figure

        save(cam_design_figure(cam, vals if args.rpm is None else vals.per_second(args.rpm)), args.figure)
    u = "" if cam.units == "length" else f" {cam.units}"
    lines = [
        f"follower          {cam.follower}",
        f"base radius       {cam.base_radius:.6g}{u}" + (" (sized)" if args.base_radius is None else ""),
        f"pressure angle    max {report['pressure_angle_max_deg']:.4g} deg "
        f"at {report['pressure_angle_max_at_deg']:.4g} deg",
        f"curvature radius  min {cam.curvature_radius_min:.4g}{u} (convex surface)",
        f"undercut          {'yes' if cam.undercut else 'no'}",
    ]
    if kind.contact == "flat":
        lines.append(f"face width        {cam.face_width:.4g}{u}")
    if not cont.ok:
        lines.append(f"law               not continuous: {cont.problems()[0]}")
    lines.append(f"cam               {args.out}")
    emit("\n".join(lines))
    return 0


def _flagged(exc: GearleverError) -> str:
    """The library's refusal with the dimensions it names called by their flags."""
    from gearlever.cams.followers._base import Unbuildable

    if isinstance(exc, Unbuildable):
        return exc.named({n: "--" + n.replace("_", "-") for n in exc.names})
    return str(exc)


def _points_flag(text: str, points: int) -> str:
    """The library's "give more points" as the flag that gives them."""
    return text.replace("give more points", f"give more --points than {points}")


def _samples_name(law_path: str) -> str:
    import tomllib

    from gearlever._io import read_text_capped

    return tomllib.loads(read_text_capped(law_path, "LAW"))["law"]["samples"]


def _view(args) -> int:
    check_page_out(args.out)
    check_output(args.out)
    emit(cam_page(args.cam, args.frames), args.out)
    return 0
