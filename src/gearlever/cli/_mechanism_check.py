"""``gearlever mechanism check``: the tooth geometry of every mesh of a model, at the sketch and over its motion.

Sub-command (added to ``gearlever mechanism`` by :func:`register_check`)::

    gearlever mechanism check MODEL [--points N] [--center-distance MESH=START:STOP ...] [--json]

For each ``[[meshes]]`` entry: teeth, shifts, centre distance and the tight
mesh's, working pressure angle, contact ratios, backlash, tip, root and base
diameters, undercut and interference (:mod:`gearlever.mechanism.mesh_check`).
When the centre distance changes as the mechanism moves, the same over the
first input's turn (``--points`` frames) with the worst angle; with
``--center-distance`` (an adjusting slide that sets a mesh's centre distance)
over that range instead.  Problems are listed as ``FLAG`` lines; the exit code
is 0 either way (the check ran), 2 for bad input.
"""

from __future__ import annotations

import math

import numpy as np

from gearlever._format import DIGITS_DESIGN, quantize
from gearlever.cli._common import capped_int, emit, to_json
from gearlever.errors import GearleverError

#: Largest ``--points``: a batched solve of the cycle and a few arrays per mesh.
MAX_CHECK_POINTS = 100_000


def register_check(ms) -> None:
    c = ms.add_parser(
        "check",
        help="tooth geometry of every mesh: contact ratio, backlash, undercut, interference, over the cycle",
        description="Check every gear mesh of the model: working pressure angle, contact ratio, backlash, "
        "undercut and interference (ISO 53 rack, ISO 21771 geometry) at the sketch, and over the cycle where "
        "the centre distance changes, or over an adjusting slide's range (--center-distance).",
    )
    c.add_argument("model", help="model file (TOML)")
    c.add_argument(
        "--points",
        type=capped_int(MAX_CHECK_POINTS, low=2),
        default=360,
        help=f"frames of the cycle and samples of a --center-distance range (default 360, at most {MAX_CHECK_POINTS})",
    )
    c.add_argument(
        "--center-distance",
        action="append",
        metavar="MESH=START:STOP",
        help="check this mesh over centre distances from START to STOP (model units), as an adjusting slide "
        "sets them; once per mesh",
    )
    c.add_argument("--json", action="store_true", help="JSON instead of text")
    c.set_defaults(func=_check)


def _ranges(given, names) -> dict:
    out: dict = {}
    for text in given or ():
        name, sep, span = str(text).partition("=")
        lo, sep2, hi = span.partition(":")
        if not sep or not sep2:
            raise GearleverError(f"--center-distance must be MESH=START:STOP, got {text!r}")
        name = name.strip()
        if name not in names:
            raise GearleverError(f"--center-distance: unknown mesh {name!r} (meshes: {', '.join(names) or 'none'})")
        if name in out:
            raise GearleverError(f"--center-distance: mesh {name!r} given twice")
        try:
            a, b = float(lo), float(hi)
        except ValueError:
            raise GearleverError(f"--center-distance {name}: START and STOP must be numbers, got {span!r}") from None
        if not (math.isfinite(a) and math.isfinite(b) and a > 0 and b > 0):
            raise GearleverError(f"--center-distance {name}: START and STOP must be positive, got {span!r}")
        out[name] = (a, b)
    return out


def _q(v, scale=None) -> float:
    v = float(v)
    return quantize(v, abs(v) if scale is None else scale, DIGITS_DESIGN) if math.isfinite(v) else v


def _geometry(g, i, scale) -> dict:
    return {
        "center_distance": _q(g.center_distance[i]),
        "working_pressure_angle_deg": _q(math.degrees(g.working_pressure_angle[i])),
        "contact_ratio_transverse": _q(g.contact_ratio_transverse[i]),
        "contact_ratio_overlap": _q(g.contact_ratio_overlap[i]),
        "contact_ratio_total": _q(g.contact_ratio_total[i]),
        "backlash": _q(g.backlash[i], scale),
        "interference": bool(g.interference[i]),
    }


def check_report(mech, checks) -> dict:
    """The JSON report of :func:`gearlever.mechanism.mesh_check.check_mechanism`'s results."""
    from gearlever.mechanism.loads import pressure_angle_of

    m = mech.model
    meshes = []
    for c in checks:
        s = c.sketch
        scale = float(s.tight_center_distance)
        d = {
            "mesh": c.mesh,
            "gears": list(c.gears),
            "internal": c.internal,
            "teeth": list(c.teeth),
            "shift": list(c.shift),
            "tight_center_distance": _q(s.tight_center_distance),
            "shift_sum_for_sketch": _q(c.shift_sum, 1.0),
            "sketch": _geometry(s, 0, scale),
            "reference_diameter": [_q(v) for v in s.reference_diameter],
            "base_diameter": [_q(v) for v in s.base_diameter],
            "tip_diameter": [_q(v) for v in s.tip_diameter],
            "root_diameter": [_q(v) for v in s.root_diameter],
            "tip_thickness": [_q(v, c.module) for v in s.tip_thickness],
            "undercut": [bool(u) for u in s.undercut],
            "over": c.over,
        }
        if c.sweep is not None:
            g = c.sweep
            worst = int(np.argmin(g.contact_ratio_total))
            tight = int(np.argmin(g.backlash))
            d["range"] = {
                "samples": int(g.center_distance.size),
                "center_distance": [_q(g.center_distance.min()), _q(g.center_distance.max())],
                "contact_ratio_total": [_q(g.contact_ratio_total.min()), _q(g.contact_ratio_total.max())],
                "backlash": [_q(g.backlash.min(), scale), _q(g.backlash.max(), scale)],
                "working_pressure_angle_deg": [
                    _q(math.degrees(g.working_pressure_angle.min())),
                    _q(math.degrees(g.working_pressure_angle.max())),
                ],
                "least_contact": _geometry(g, worst, scale),
                "least_backlash": _geometry(g, tight, scale),
            }
            if c.over == "cycle":
                d["range"]["least_contact"]["input_deg"] = _q(math.degrees(c.angle[worst]))
                d["range"]["least_backlash"]["input_deg"] = _q(math.degrees(c.angle[tight]))
        d["flags"] = list(c.flags)
        meshes.append(d)
    return {
        "mechanism": m.name,
        "units": m.units,
        "module": _q(checks[0].module) if checks else m.module,
        "module_given": m.module is not None,
        "pressure_angle_deg": _q(math.degrees(pressure_angle_of(m))),
        "meshes": meshes,
        "ok": all(c.ok for c in checks),
    }


def _fmt(v, digits: int = 6) -> str:
    v = float(v)
    if not math.isfinite(v):
        return "n/a"
    return f"{v + 0.0:.{digits}g}"


def check_text(report: dict) -> str:
    """The text of ``mechanism check``: one block per mesh, quantities named with their units."""
    u = report["units"] or "length units"
    if not report["meshes"]:
        return f"mechanism {report['mechanism']!r}: no gear meshes"
    mod = _fmt(report["module"])
    how = "given" if report["module_given"] else "none given: from the first mesh's centre distance"
    lines = [
        f"mechanism {report['mechanism']!r}: module {mod} {u} ({how}), "
        f"pressure angle {_fmt(report['pressure_angle_deg'])} deg, ISO 53 basic rack"
    ]
    for d in report["meshes"]:
        s = d["sketch"]
        kind = "internal" if d["internal"] else "external"
        pair = " ".join(str(z) for z in d["teeth"])
        shifts = " ".join(_fmt(x) for x in d["shift"])
        lines += [
            f"mesh {d['mesh']} ({kind}; teeth {pair}; shifts {shifts})",
            f"  centre distance        {_fmt(s['center_distance'])} {u} at the sketch "
            f"(tight mesh {_fmt(d['tight_center_distance'])} {u}; shift sum for a tight mesh there "
            f"{_fmt(d['shift_sum_for_sketch'], 4)})",
            f"  working pressure angle {_fmt(s['working_pressure_angle_deg'])} deg",
            f"  contact ratio          {_fmt(s['contact_ratio_total'], 4)} (transverse "
            f"{_fmt(s['contact_ratio_transverse'], 4)}, overlap {_fmt(s['contact_ratio_overlap'], 4)})",
            f"  backlash               {_fmt(s['backlash'], 4)} {u} (circumferential, working pitch circle, "
            "no thickness allowance)",
            f"  tip diameters          {' '.join(_fmt(v) for v in d['tip_diameter'])} {u}; root "
            f"{' '.join(_fmt(v) for v in d['root_diameter'])} {u}; base "
            f"{' '.join(_fmt(v) for v in d['base_diameter'])} {u}",
            f"  undercut               {' '.join('yes' if x else 'no' for x in d['undercut'])}; "
            f"interference {'yes' if s['interference'] else 'no'}",
        ]
        if "range" in d:
            r = d["range"]
            if d["over"] == "cycle":
                head = f"  over the cycle ({r['samples']} frames): centre distance"
                where_c = f"at input {_fmt(r['least_contact']['input_deg'])} deg"
                where_b = f"at input {_fmt(r['least_backlash']['input_deg'])} deg"
            else:
                head = f"  over the adjustment ({r['samples']} centre distances):"
                where_c = f"at {_fmt(r['least_contact']['center_distance'])} {u}"
                where_b = f"at {_fmt(r['least_backlash']['center_distance'])} {u}"
            lines += [
                f"{head} {_fmt(r['center_distance'][0])} .. {_fmt(r['center_distance'][1])} {u}",
                f"    contact ratio          {_fmt(r['contact_ratio_total'][0], 4)} .. "
                f"{_fmt(r['contact_ratio_total'][1], 4)} (least {where_c})",
                f"    backlash               {_fmt(r['backlash'][0], 4)} .. {_fmt(r['backlash'][1], 4)} {u} "
                f"(least {where_b})",
                f"    working pressure angle {_fmt(r['working_pressure_angle_deg'][0])} .. "
                f"{_fmt(r['working_pressure_angle_deg'][1])} deg",
            ]
        elif d["over"] == "constant":
            lines.append("  the carrier holds the centre distance: the same at every angle")
        lines += [f"  FLAG {f}" for f in d["flags"]] or ["  ok"]
    return "\n".join(lines)


def _check(args) -> int:
    from gearlever.cli._shared import load_model as _load
    from gearlever.mechanism.mesh_check import check_mechanism

    mech = _load(args.model)
    adjust = _ranges(args.center_distance, [m.name for m in mech.model.meshes])
    checks = check_mechanism(mech, points=args.points, adjust=adjust)
    report = check_report(mech, checks)
    emit(to_json(report) if args.json else check_text(report))
    return 0
