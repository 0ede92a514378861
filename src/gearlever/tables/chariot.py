"""Tables for the Nuttall chariot (worked designs) and the car differential (worked cases)."""

from __future__ import annotations

import pandas as pd

from gearlever.gears.car import car_differential
from gearlever.gears.chariot import NuttallTeeth, design_nuttall, nuttall_closed_form

#: Worked designs: (name, (n2, n5, n6, n7, n8, n9, n11)).
NUTTALL_DESIGNS = (
    ("all teeth equal (20)", (20, 20, 20, 20, 20, 20, 20)),
    ("geared up by two: n7 = 2 n6 = 2 n8", (20, 20, 20, 40, 20, 20, 20)),
    ("geared down by two: n6 = n8 = 2 n7", (20, 20, 40, 20, 40, 20, 20)),
    ("unequal side differentials", (30, 24, 18, 36, 20, 25, 40)),
    ("small wheel 1 side", (12, 36, 15, 45, 20, 16, 48)),
)

#: Worked car-differential cases: (name, keyword arguments after the drive).
CAR_CASES = (
    ("straight run", {}),
    ("left turn R = 5 m, track 1.5 m", {"turn_radius": 5.0, "track": 1.5}),
    ("right turn R = -5 m, track 1.5 m", {"turn_radius": -5.0, "track": 1.5}),
    ("left wheel held", {"left_speed": 0.0}),
    ("right wheel held (inner wheel at R = T/2)", {"turn_radius": -0.75, "track": 1.5}),
)


def _frac(f) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


def nuttall_designs_table(designs=NUTTALL_DESIGNS) -> pd.DataFrame:
    """One row per design: network counts, relation (l) coefficients, rotations per pointer turn, d1/t, d12/t.

    Diameters are in units of the track width t, rotations in turns.  The
    column ``closed_form_agrees`` compares the solver with the source's hand
    formulas exactly (Fractions).
    """
    rows = []
    for name, teeth in designs:
        t = NuttallTeeth(*teeth)
        d = design_nuttall(t)
        a = d.solution.analysis
        cf = nuttall_closed_form(t)
        rows.append(
            {
                "design": name,
                **t.as_dict(),
                "unknowns": a.unknowns,
                "rank": a.rank,
                "dof": a.dof,
                "redundant": " ".join(a.redundant),
                "rot7_per_rot1": _frac(d.pointer_per_right),
                "rot7_per_rot12": _frac(d.pointer_per_left),
                "rot1_turns_per_pointer_turn": _frac(d.rot1_per_pointer_turn),
                "rot12_turns_per_pointer_turn": _frac(d.rot12_per_pointer_turn),
                "d1_per_t_fraction": _frac(d.d1_over_t),
                "d12_per_t_fraction": _frac(d.d12_over_t),
                "d1_per_t": float(d.d1_over_t),
                "d12_per_t": float(d.d12_over_t),
                "closed_form_agrees": bool(
                    cf["d1_over_t"] == d.d1_over_t
                    and cf["d12_over_t"] == d.d12_over_t
                    and cf["rot1"] == d.rot1_per_pointer_turn
                    and cf["rot12"] == d.rot12_per_pointer_turn
                ),
            }
        )
    return pd.DataFrame(rows)


def car_cases_table(
    pinion_teeth: int = 11,
    ring_teeth: int = 41,
    pinion_speed_rad_s: float = 300.0,
    pinion_torque_N_m: float = 100.0,
    cases=CAR_CASES,
) -> pd.DataFrame:
    """Worked car-differential cases (speeds rad/s, torques N m, power W)."""
    rows = []
    for name, kw in cases:
        s = car_differential(pinion_teeth, ring_teeth, pinion_speed_rad_s, pinion_torque_N_m, **kw)
        d = s.summary()
        rows.append(
            {
                "case": name,
                "pinion_teeth": pinion_teeth,
                "ring_teeth": ring_teeth,
                "turn_radius_m": kw.get("turn_radius", float("nan")),
                "track_m": kw.get("track", float("nan")),
                "pinion_speed_rad_s": pinion_speed_rad_s,
                "pinion_torque_N_m": pinion_torque_N_m,
                "carrier_speed_rad_s": d["carrier_speed"],
                "left_speed_rad_s": d["left_speed"],
                "right_speed_rad_s": d["right_speed"],
                "ring_torque_N_m": d["ring_torque"],
                "left_torque_N_m": d["left_torque"],
                "right_torque_N_m": d["right_torque"],
                "power_in_W": d["power_in"],
                "power_out_W": d["power_out"],
            }
        )
    return pd.DataFrame(rows)
