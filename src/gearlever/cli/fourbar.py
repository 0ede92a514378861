"""``gearlever fourbar``: positions and analogues of a four-bar over a full crank turn."""

from __future__ import annotations

import math
import sys

import numpy as np

from gearlever._io import table_text
from gearlever.cli._common import capped_int, emit, positive_float, progress, to_json

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
    "change_point",
)

#: Most crank angles: a row is ~150 bytes of CSV (~300 of JSON) and ~1 kB of
#: Python objects while the text is built, so 10^5 rows take ~130 MB and about
#: a second; 10^5 points is a point every 0.0036 degrees.
MAX_POINTS = 10**5


def register(sub) -> None:
    p = sub.add_parser(
        "fourbar",
        help="four-bar coupler/rocker angles and their analogues over a crank turn",
        description="Coupler and rocker angles (deg) and their velocity and acceleration "
        "analogues (omega/omega2, alpha/omega2^2) of a four-bar over a full turn "
        "of the crank. Points where the linkage cannot close are nan, valid=0. "
        "A change-point linkage (s + l = p + q) folds flat at some crank angles, where it "
        "can switch assembly (parallelogram to antiparallelogram): those rows have "
        "change_point=1 and a note on stderr names the angles.",
    )
    p.add_argument("--ground", type=positive_float, required=True, help="ground link length")
    p.add_argument("--crank", type=positive_float, required=True, help="crank (input) length")
    p.add_argument("--coupler", type=positive_float, required=True, help="coupler length")
    p.add_argument("--rocker", type=positive_float, required=True, help="rocker (output) length")
    p.add_argument(
        "--points",
        type=capped_int(MAX_POINTS),
        default=360,
        help=f"crank angles over a turn, 0 <= theta2 < 360 deg (default 360, at most {MAX_POINTS:,})",
    )
    p.add_argument("--branch", choices=("open", "crossed"), default="open", help="assembly branch")
    p.add_argument("--format", choices=("csv", "json"), default="csv", help="output format")
    p.add_argument("--out", default=None, help="write to this file (atomically) instead of stdout")
    p.set_defaults(func=_run)


def rows(ground, crank, coupler, rocker, points, branch):
    """Table rows (tuples in :data:`COLUMNS` order) for the CLI."""
    from gearlever.loops import fourbar, transmission_angle

    phi = np.linspace(0.0, 2 * np.pi, points, endpoint=False)
    r = fourbar(ground, crank, coupler, rocker, phi, branch=branch)
    mu = transmission_angle(ground, crank, coupler, rocker, phi)
    cols = (
        np.degrees(phi),
        np.degrees(r.theta3),
        np.degrees(r.theta4),
        r.dtheta3_dphi,
        r.dtheta4_dphi,
        r.d2theta3_dphi2,
        r.d2theta4_dphi2,
        np.degrees(mu),
    )
    floats = zip(*(c.tolist() for c in cols))
    return [(*f, bool(v), bool(cp)) for f, v, cp in zip(floats, r.valid.tolist(), r.change_point.tolist())]


def change_point_note(ground, crank, coupler, rocker, branch) -> str | None:
    """One line naming the crank angles where the linkage folds flat, or None if it never does."""
    from gearlever.loops import change_points

    cps = change_points(ground, crank, coupler, rocker)
    if cps.size == 0:
        return None
    where = ", ".join(f"{math.degrees(t):g}" for t in cps)
    return (
        f"gearlever fourbar: note: change point at theta2 = {where} deg (the linkage folds flat and can "
        f"switch assembly, e.g. parallelogram to antiparallelogram); the {branch} branch is followed "
        "through it, rows there have change_point=1"
    )


def _run(args) -> int:
    links = (args.ground, args.crank, args.coupler, args.rocker)
    with progress("solving the four-bar"):
        table = rows(*links, args.points, args.branch)
        if args.format == "csv":
            text = table_text({c: [row[i] for row in table] for i, c in enumerate(COLUMNS)}, "csv")
        else:
            text = to_json([dict(zip(COLUMNS, row)) for row in table])
    emit(text, args.out)
    note = change_point_note(*links, args.branch)
    if note:
        print(note, file=sys.stderr)
    return 0
