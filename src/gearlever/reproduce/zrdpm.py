"""Reproduce the ZRDPM paper: Tables I and II, identified constants, mobility, figures."""

from __future__ import annotations

from pathlib import Path

#: Files this step writes (relative to the tables and figures folders).
TABLE_FILES = ("table1.csv", "table2.csv", "identified_constants.csv", "mobility.csv")
FIGURE_FILES = ("zrdpm_fig3_u1.png", "zrdpm_analogues.png", "zrdpm_tables_comparison.png")


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    """Write the ZRDPM tables and figures; return one summary line per table."""
    from gearlever.plotting import zrdpm as plots
    from gearlever.plotting._common import save
    from gearlever.tables import zrdpm as tabs
    from gearlever.tables._common import write_csv

    tables_dir, figures_dir = Path(tables_dir), Path(figures_dir)
    reps = [tabs.reproduce("I"), tabs.reproduce("II")]
    lines = []
    for rep, fname in zip(reps, ("table1.csv", "table2.csv")):
        write_csv(tabs.comparison_frame(rep), tables_dir / fname)
        k, sc = rep.fit.constants, rep.self_consistent
        lines.append(
            f"zrdpm: {fname}: {rep.table.size} values, max |deviation| {rep.fit.max_abs:.4f} cm "
            f"(rms {rep.fit.rms:.4f}); identified l*u^2 = {k.l_u2:.4f} cm, l*e = {k.l_e:.4f} cm "
            f"(A = {k.A:.4f}, B = {k.B:.4f}); self-consistent model best fit misses by up to "
            f"{sc.max_abs:.2f} cm"
        )
    write_csv(tabs.constants_frame(reps), tables_dir / "identified_constants.csv")
    mob = tabs.mobility_frame()
    write_csv(mob, tables_dir / "mobility.csv")
    lines.append(f"zrdpm: mobility.csv: {len(mob)} cases, {int(mob['agrees'].sum())} agree with the paper")
    save(plots.plot_u1_turn().figure, figures_dir / "zrdpm_fig3_u1.png")
    save(plots.plot_analogues(), figures_dir / "zrdpm_analogues.png")
    save(plots.plot_table_comparison(reps), figures_dir / "zrdpm_tables_comparison.png")
    return lines
