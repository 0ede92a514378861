"""``gearlever fourbar``: positions and analogues of a four-bar over a full crank turn."""

from __future__ import annotations

import json
import math

import numpy as np

from gearlever.cli._common import emit, positive_float, positive_int

COLUMNS = (
    "theta2_deg",
    "theta3_deg",
    "theta4_deg",
    "dtheta3_dphi",
    "dtheta4_dphi",
    "d2theta3_dphi2",
    "d2theta4_dphi2",
    "transmission_deg",
    "valid",
)


def register(sub) -> None:
    p = sub.add_parser(
        "fourbar",
        help="four-bar coupler/rocker angles and their analogues over a crank turn",
        description="Coupler and rocker angles (deg) and their velocity and acceleration "
        "analogues (omega/omega2, alpha/omega2^2) of a four-bar over a full turn "
        "of the crank. Points where the linkage cannot close are nan, valid=0.",
    )
    p.add_argument("--ground", type=positive_float, required=True, help="ground link length")
    p.add_argument("--crank", type=positive_float, required=True, help="crank (input) length")
    p.add_argument("--coupler", type=positive_float, required=True, help="coupler length")
    p.add_argument("--rocker", type=positive_float, required=True, help="rocker (output) length")
    p.add_argument(
        "--points",
        type=positive_int,
        default=360,
        help="crank angles over a turn, 0 <= theta2 < 360 deg (default 360)",
    )
    p.add_argument("--branch", choices=("open", "crossed"), default="open", help="assembly branch")
    p.add_argument("--format", choices=("csv", "json"), default="csv", help="output format")
    p.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    p.set_defaults(func=_run)


def rows(ground, crank, coupler, rocker, points, branch):
    """Table rows (tuples in :data:`COLUMNS` order) for the CLI."""
    from gearlever.loops import fourbar, transmission_angle

    th2 = np.linspace(0.0, 2 * np.pi, points, endpoint=False)
    r = fourbar(ground, crank, coupler, rocker, th2, branch=branch)
    mu = transmission_angle(ground, crank, coupler, rocker, th2)
    cols = (
        np.degrees(th2),
        np.degrees(r.theta3),
        np.degrees(r.theta4),
        r.dtheta3_dphi,
        r.dtheta4_dphi,
        r.d2theta3_dphi2,
        r.d2theta4_dphi2,
        np.degrees(mu),
    )
    return [tuple(float(c[i]) for c in cols) + (bool(r.valid[i]),) for i in range(points)]


def _fmt(v) -> str:
    if isinstance(v, bool):
        return "1" if v else "0"
    return "nan" if math.isnan(v) else f"{v:.12g}"


def _run(args) -> int:
    table = rows(args.ground, args.crank, args.coupler, args.rocker, args.points, args.branch)
    if args.format == "csv":
        text = "\n".join([",".join(COLUMNS)] + [",".join(_fmt(v) for v in row) for row in table])
    else:
        recs = [
            {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in zip(COLUMNS, row)} for row in table
        ]
        text = json.dumps(recs, indent=1)
    emit(text, args.out)
    return 0
