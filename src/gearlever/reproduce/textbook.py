"""Published textbook problems of epicyclic torques, engine crank effort and flywheel sizing, solved by the model."""

from __future__ import annotations

from pathlib import Path

#: Significant digits written: the answers are printed with at most five.
FLOAT_FORMAT = "%.6g"


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.tables._common import write_csv
    from gearlever.tables.dynamics import textbook_table

    df = textbook_table()
    write_csv(df, Path(tables_dir) / "textbook_checks.csv", float_format=FLOAT_FORMAT)
    worst = (df.deviation.abs() / df.tolerance).max()
    return [
        f"textbook: {Path(tables_dir) / 'textbook_checks.csv'}: {int(df.within.sum())}/{len(df)} published answers "
        f"({df.example.nunique()} worked examples: epicyclic torques, crank effort, flywheels) within tolerance; "
        f"worst at {worst:.2f} of its tolerance"
    ]
