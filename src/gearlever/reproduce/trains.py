"""Reproduce the trains-of-wheels and Hooke's-coupling tables and figures."""

from __future__ import annotations

from pathlib import Path


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.plotting import hooke as hplot
    from gearlever.plotting._common import save
    from gearlever.tables import trains as ttab
    from gearlever.tables._common import write_csv

    tables_dir, figures_dir = Path(tables_dir), Path(figures_dir)
    lines = []
    hooke_df = ttab.hooke_table()
    write_csv(hooke_df, tables_dir / "hooke.csv")
    ext = ttab.hooke_extremes_table()
    write_csv(ext, tables_dir / "hooke_extremes.csv")
    lines.append(
        f"trains: {tables_dir / 'hooke.csv'} ({len(hooke_df)} input angles), {tables_dir / 'hooke_extremes.csv'}"
    )
    designs = ttab.design_table()
    write_csv(designs, tables_dir / "train_designs.csv")
    lines.append(f"trains: {tables_dir / 'train_designs.csv'} ({len(designs)} worked syntheses by the text's rules)")
    sand = ttab.sandgren_table()
    write_csv(sand, tables_dir / "sandgren.csv")
    k2 = sand[sand.pairs == 2].iloc[0]
    lines.append(
        f"trains: {tables_dir / 'sandgren.csv'}: K=2 optimum {k2.drivers} / {k2.followers}, "
        f"squared error {k2.squared_error:.6e}, {k2.n_solutions} set(s), {k2.n_ordered} ordered"
    )
    ax = hplot.plot_single_ratio()
    save(ax.figure, figures_dir / "hooke_single.png")
    ax = hplot.plot_double_ratio()
    save(ax.figure, figures_dir / "hooke_double.png")
    lines.append(f"trains: {figures_dir / 'hooke_single.png'}, {figures_dir / 'hooke_double.png'}")
    return lines
