"""Tables of epicyclic trains: each member's rotation per input, with the tabular method's columns."""

from __future__ import annotations

from fractions import Fraction

import pandas as pd

from gearlever.gears.epicyclic import tabular_method
from gearlever.gears.networks import Network
from gearlever.tables._common import frame


def _frac(f: Fraction | None) -> str:
    if f is None:
        return ""
    return str(f.numerator) if f.denominator == 1 else f"{f.numerator}/{f.denominator}"


def epicyclic_table(network: Network, inputs, carrier: str | None = None, turned: str | None = None) -> pd.DataFrame:
    """One row per member: teeth, rotation per unit of each input (exact ``p/q`` and float).

    With ``carrier``, the tabular method's columns too: ``relative`` (turns
    with the carrier fixed and ``turned`` turned +1; empty where the
    epicyclic does not determine the member) and ``x_per_<input>``,
    ``y_per_<input>`` (the multiplier and the whole-train turn), so that
    ``total = y + x * relative`` can be checked row by row.

    >>> from gearlever.gears.planetary import planetary_network
    >>> epicyclic_table(planetary_network(24, 60, planet=18), ["sun"], "carrier")["per_sun"].tolist()
    ['1', '0', '2/7', '-2/3']
    """
    sol = network.solve(inputs)
    names = list(network.names)
    cols: dict = {
        "member": names,
        "teeth": ["" if network.teeth[n] is None else str(network.teeth[n]) for n in names],
    }
    tab = tabular_method(network, carrier, sol.inputs, turned) if carrier is not None else None
    if tab is not None:
        rel = {r.member: r.relative for r in tab.rows}
        cols["turned"] = [tab.turned] * len(names)
        cols["relative"] = [_frac(rel[n]) for n in names]
    for k, name in enumerate(sol.inputs):
        cols[f"per_{name}"] = [_frac(sol.coefficients[n][k]) for n in names]
        cols[f"per_{name}_float"] = [float(sol.coefficients[n][k]) for n in names]
        if tab is not None:
            cols[f"x_per_{name}"] = [_frac(tab.x[k])] * len(names)
            cols[f"y_per_{name}"] = [_frac(tab.y[k])] * len(names)
    return frame(cols)
