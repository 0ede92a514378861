"""``gearlever flywheel --torque-file F --rpm N (--fluctuation CS | --inertia I) [--format table|json]``.

Integrate a turning-moment diagram over one cycle (see
:func:`gearlever.flywheels.flywheel.flywheel`) and size the flywheel that
holds a coefficient of fluctuation of speed, or give the fluctuation a
flywheel of known inertia allows.

The torque file is a CSV: crank angle in degrees, driving torque, and
optionally a third column, the resisting torque (default: constant, the mean
driving torque).  Lines starting with ``#`` are comments; a first line that
is not numeric is a header.  Caps: :data:`MAX_FILE_BYTES` bytes and
:data:`gearlever.flywheels.flywheel.MAX_SAMPLES` rows.  Bad input ends with
exit 2 and one line naming the flag or the CSV row and column.
"""

from __future__ import annotations

import math

from gearlever._io import read_csv_table
from gearlever.cli._common import capped_float, emit, flagged, positive_float, to_json
from gearlever.errors import GearleverError

#: Largest torque file read (bytes).
MAX_FILE_BYTES = 50_000_000


def register(sub) -> None:
    p = sub.add_parser("flywheel", help="turning-moment diagram over a cycle: energy fluctuation and flywheel size")
    p.add_argument(
        "--torque-file",
        required=True,
        metavar="F",
        help="CSV: crank angle (deg), driving torque[, resisting torque]; the last row closes the cycle",
    )
    p.add_argument("--rpm", type=positive_float, required=True, metavar="N", help="mean speed (rev/min)")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument(
        "--fluctuation", type=positive_float, metavar="CS", help="coefficient of fluctuation of speed allowed"
    )
    g.add_argument("--inertia", type=positive_float, metavar="I", help="flywheel moment of inertia (kg m^2)")
    p.add_argument(
        "--period-deg",
        type=capped_float(360_000.0),  # 1000 turns: gearlever.flywheels.flywheel.MAX_PERIOD
        default=None,
        metavar="DEG",
        help="cycle length (deg) when the last row does not close it, e.g. 720 for rows 0..710",
    )
    p.add_argument("--format", choices=("table", "json"), default="table")
    p.add_argument("--out", default=None, metavar="FILE", help="write to FILE instead of stdout")
    p.set_defaults(func=_run)


def read_torque_file(path: str, max_rows: int | None = None):
    """Crank angles (deg), driving torque and resisting torque (or None) from the CSV ``path``."""
    from gearlever.flywheels.flywheel import MAX_SAMPLES

    max_rows = MAX_SAMPLES if max_rows is None else max_rows
    where = f"--torque-file {path!r}"
    table = read_csv_table(path, "--torque-file", header=False, comments=True, cap=MAX_FILE_BYTES)
    rows: list[list[float]] = []
    width = None
    seen_data = False
    for k, record in zip(table.lines, table.rows):
        cells = [c.strip() for c in record]
        values = []
        for j, cell in enumerate(cells, start=1):
            try:
                v = float(cell)
            except ValueError:
                v = None
            if v is None or not math.isfinite(v):
                if not seen_data and not rows and v is None:
                    values = None  # a header line
                    break
                raise GearleverError(f"{where} row {k}, column {j}: must be a finite number, got {cell!r}")
            values.append(v)
        if values is None:
            names = [c for c in cells if c]
            dup = next((c for i, c in enumerate(names) if c in names[:i]), None)
            if dup is not None:
                raise GearleverError(f"{where} row {k}: column {dup!r} appears twice in the header")
            seen_data = True
            continue
        seen_data = True
        if len(values) not in (2, 3):
            raise GearleverError(
                f"{where} row {k}: must have 2 or 3 columns (angle_deg, torque[, load]), got {len(values)}"
            )
        if width is None:
            width = len(values)
        elif len(values) != width:
            raise GearleverError(f"{where} row {k}: has {len(values)} columns, earlier rows have {width}")
        if rows and values[0] <= rows[-1][0]:
            raise GearleverError(f"{where} row {k}, column 1: crank angle must increase, got {cells[0]!r}")
        rows.append(values)
        if len(rows) > max_rows:
            raise GearleverError(f"{where}: more than {max_rows} rows")
    if len(rows) < 2:
        raise GearleverError(f"{where}: needs at least 2 rows of crank angle and torque, got {len(rows)}")
    theta = [r[0] for r in rows]
    torque = [r[1] for r in rows]
    load = [r[2] for r in rows] if width == 3 else None
    return theta, torque, load


def _run(args) -> int:
    import numpy as np

    from gearlever.flywheels.flywheel import flywheel

    theta_deg, torque, load = read_torque_file(args.torque_file)
    try:
        res = flywheel(
            np.radians(theta_deg),
            torque,
            args.rpm,
            fluctuation=args.fluctuation,
            inertia=args.inertia,
            load=load,
            period=None if args.period_deg is None else math.radians(args.period_deg),
        )
    except GearleverError as exc:
        msg = str(exc)
        flags = {
            "period": "--period-deg",
            "mean_speed_rpm": "--rpm",
            "fluctuation": "--fluctuation",
            "inertia": "--inertia",
        }
        lead = msg.split(":")[0].split(" ")[0]
        if lead in flags:
            raise flagged(exc, flags) from None
        raise GearleverError(f"--torque-file {args.torque_file!r}: {msg}") from None
    s = res.summary()
    if args.format == "json":
        emit(to_json(s), args.out)
        return 0
    lines = [
        f"cycle {s['period_deg']:.6g} deg, {s['samples']} samples, mean speed {s['mean_speed_rpm']:.6g} rpm",
        f"mean torque          {s['mean_torque']:.6g}",
        f"power                {s['power']:.6g}",
        f"work per cycle       {s['work_per_cycle']:.6g}",
        f"energy fluctuation   {s['energy_fluctuation']:.6g}",
        f"max speed at         {s['theta_max_speed_deg']:.6g} deg",
        f"min speed at         {s['theta_min_speed_deg']:.6g} deg",
        f"inertia              {s['inertia']:.6g}",
        f"fluctuation Cs       {s['fluctuation']:.6g}",
    ]
    if s["load_shift"]:
        lines.append(f"load shifted by      {s['load_shift']:.6g} (its mean made equal to the driving one)")
    emit("\n".join(lines), args.out)
    return 0
