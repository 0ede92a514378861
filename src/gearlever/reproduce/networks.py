"""Reproduce the gear-network results: tables/nuttall.csv, tables/car_differential.csv,
figures/chariot_path.png and figures/chariot_drift.png."""

from __future__ import annotations

from pathlib import Path

#: Design driven in the figures (n2, n5, n6, n7, n8, n9, n11) and the way-points of the path figure.
FIGURE_TEETH = (30, 24, 18, 36, 20, 25, 40)
FIGURE_WAYPOINTS = ((0, 0), (6, 0), (6, 4), (2, 6), (-1, 2), (3, 1), (0, 0))


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.gears.chariot import NuttallTeeth, design_nuttall, random_path, simulate, waypoint_path
    from gearlever.plotting._common import save
    from gearlever.plotting.chariot import plot_chariot_path, plot_drift
    from gearlever.tables._common import write_csv
    from gearlever.tables.chariot import car_cases_table, nuttall_designs_table

    lines = []
    nut = nuttall_designs_table()
    write_csv(nut, Path(tables_dir) / "nuttall.csv")
    lines.append(
        f"{Path(tables_dir) / 'nuttall.csv'}: {len(nut)} designs, solver = source closed form in "
        f"{int(nut['closed_form_agrees'].sum())}/{len(nut)}"
    )
    car = car_cases_table()
    write_csv(car, Path(tables_dir) / "car_differential.csv")
    imbalance = float((car["power_in_W"] - car["power_out_W"]).abs().max())
    lines.append(
        f"{Path(tables_dir) / 'car_differential.csv'}: {len(car)} cases, max |P_in - P_out| = {imbalance:.1e} W"
    )

    d = design_nuttall(NuttallTeeth(*FIGURE_TEETH))
    dl, dr, h0 = waypoint_path(FIGURE_WAYPOINTS, track=d.track, step=0.02)
    runs = {
        "exact wheels": simulate(d, dl, dr, heading0=h0),
        "d1 1 % too large": simulate(d, dl, dr, d1=1.01 * d.d1, heading0=h0),
    }
    ax = plot_chariot_path(runs)
    save(ax.figure, Path(figures_dir) / "chariot_path.png")
    lines.append(
        f"{Path(figures_dir) / 'chariot_path.png'}: way-point tour, "
        f"drift exact {runs['exact wheels'].max_drift:.1e} rad, "
        f"1 % wrong d1 {runs['d1 1 % too large'].max_drift:.3f} rad"
    )

    dl, dr = random_path(20, seed=7, steps_per_turn=500, track=d.track)
    runs = {
        "exact wheels": simulate(d, dl, dr),
        "d1 1 % too large": simulate(d, dl, dr, d1=1.01 * d.d1),
        "d12 1 % too large": simulate(d, dl, dr, d12=1.01 * d.d12),
    }
    ax = plot_drift(runs)
    save(ax.figure, Path(figures_dir) / "chariot_drift.png")
    lines.append(
        f"{Path(figures_dir) / 'chariot_drift.png'}: random path of 20 turns, max drift "
        + ", ".join(f"{k} {r.max_drift:.2e} rad" for k, r in runs.items())
    )
    return lines
