"""Tables of trains of wheels and Hooke's couplings (pandas)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from gearlever.trains import hooke
from gearlever.trains.design import design_train
from gearlever.trains.search import search_best

#: Shaft angles (deg) of the single-joint columns of :func:`hooke_table`.
SINGLE_ANGLES_DEG = (10.0, 20.0, 30.0, 45.0)
#: Double couplings (beta1 deg, beta2 deg, phase deg) of :func:`hooke_table`.
DOUBLE_CASES_DEG = ((30.0, 30.0, 0.0), (30.0, 20.0, 0.0), (30.0, 30.0, 30.0), (30.0, 30.0, 90.0))
#: Worked syntheses by the text's rules: (ratio, keyword arguments of design_train).
WORKED_DESIGNS = (
    ("12", dict(tooth_form="epicycloidal")),
    ("100", dict(tooth_form="involute")),
    ("100", dict(tooth_form="involute", prefer="wear")),
    ("355/113", dict(tooth_form="epicycloidal")),
    ("1/6.931", dict(min_teeth=12, max_teeth=60)),
)


def _join(values) -> str:
    return " ".join(str(v) for v in values)


def hooke_table(step_deg: float = 5.0) -> pd.DataFrame:
    """Velocity ratio over a turn, single joints and double couplings.

    Columns: input_deg; ``ratio_single_b<beta>deg`` and
    ``output_deg_single_b<beta>deg`` per shaft angle; ``ratio_double_b<b1>_<b2>_p<phase>deg``
    per double coupling.
    """
    phi_deg = np.arange(0.0, 360.0 + step_deg / 2, step_deg)
    phi = np.radians(phi_deg)
    cols = {"input_deg": phi_deg}
    for b in SINGLE_ANGLES_DEG:
        cols[f"output_deg_single_b{b:g}deg"] = np.degrees(hooke.output_angle(phi, math.radians(b)))
        cols[f"ratio_single_b{b:g}deg"] = hooke.velocity_ratio(phi, math.radians(b))
        cols[f"accel_ratio_single_b{b:g}deg"] = hooke.acceleration_ratio(phi, math.radians(b)) + 0.0  # no -0
    for b1, b2, p in DOUBLE_CASES_DEG:
        cols[f"ratio_double_b{b1:g}_{b2:g}_p{p:g}deg"] = hooke.double_velocity_ratio(
            phi, math.radians(b1), math.radians(b2), math.radians(p)
        )
    return pd.DataFrame(cols)


def hooke_extremes_table() -> pd.DataFrame:
    """Least and greatest velocity ratio: single joints (cos, 1/cos) and the double cases."""
    rows = []
    for b in SINGLE_ANGLES_DEG:
        lo, hi = hooke.ratio_extremes(math.radians(b))
        rows.append(
            {
                "coupling": "single",
                "beta1_deg": b,
                "beta2_deg": np.nan,
                "phase_deg": np.nan,
                "min_ratio": lo,
                "max_ratio": hi,
                "fluctuation": hi - lo,
            }
        )
    for b1, b2, p in DOUBLE_CASES_DEG:
        f = hooke.double_fluctuation(math.radians(b1), math.radians(b2), math.radians(p))
        rows.append(
            {
                "coupling": "double",
                "beta1_deg": b1,
                "beta2_deg": b2,
                "phase_deg": p,
                "min_ratio": f.min_ratio,
                "max_ratio": f.max_ratio,
                "fluctuation": f.fluctuation,
            }
        )
    return pd.DataFrame(rows)


def design_table() -> pd.DataFrame:
    """Worked syntheses by the text's rules (best design of each of :data:`WORKED_DESIGNS`)."""
    rows = []
    for ratio, kwargs in WORKED_DESIGNS:
        res = design_train(ratio, **kwargs)
        d = res.designs[0]
        rows.append(
            {
                "target": ratio,
                "target_float": float(res.target),
                "min_teeth": res.min_teeth,
                "max_teeth": res.max_teeth,
                "pairs_lower": res.bounds.lower,
                "pairs_upper": res.bounds.upper,
                "prefer": kwargs.get("prefer", "teeth"),
                "method": res.method,
                "approximation": str(res.approximation),
                "drivers": _join(d.drivers),
                "followers": _join(d.followers),
                "ratio": str(d.ratio),
                "ratio_float": float(d.ratio),
                "error": d.error,
                "gcd": _join(d.gcds),
                "total_teeth": d.total_teeth,
            }
        )
    return pd.DataFrame(rows)


def sandgren_table(pairs=(1, 2, 3, 4, 5), min_teeth: int = 12, max_teeth: int = 60) -> pd.DataFrame:
    """Every optimal train for 1/6.931 with K = 1..5 pairs, teeth 12-60 (exhaustive search)."""
    rows = []
    for k in pairs:
        res = search_best("1/6.931", k, min_teeth, max_teeth)
        for i, s in enumerate(res.solutions, start=1):
            rows.append(
                {
                    "pairs": k,
                    "solution": i,
                    "n_solutions": res.n_solutions,
                    "n_ordered": res.n_ordered,
                    "drivers": _join(s.drivers),
                    "followers": _join(s.followers),
                    "ratio": str(s.ratio),
                    "ratio_float": float(s.ratio),
                    "abs_error": float(res.best_error),
                    "squared_error": float(res.best_error) ** 2,
                    "n_products": res.n_products,
                }
            )
    return pd.DataFrame(rows)
