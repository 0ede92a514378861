"""Reproduce the epicyclic examples: tables/epicyclic_<name>.csv from the shipped network files (package data)."""

from __future__ import annotations

from pathlib import Path

#: Example network files (shipped examples, :func:`gearlever.data.example_path`) with their inputs, carrier
#: and turned member.
EXAMPLES = {
    "ferguson_paradox": {"inputs": ["arm"], "carrier": "arm", "turned": None},
    "simple_planetary": {"inputs": ["sun"], "carrier": "carrier", "turned": None},
    "compound_planetary": {"inputs": ["sun"], "carrier": "carrier", "turned": None},
    "car_differential": {"inputs": ["pinion", "left"], "carrier": "carrier", "turned": "left"},
    "reverted_train": {"inputs": ["A"], "carrier": None, "turned": None},
}


def run(tables_dir: Path, figures_dir: Path) -> list[str]:
    from gearlever.data import example_path
    from gearlever.gears.networks import parse_network
    from gearlever.tables._common import write_csv
    from gearlever.tables.epicyclic import epicyclic_table

    lines = []
    for name, spec in EXAMPLES.items():
        net = parse_network(example_path(f"{name}.csv").read_text(encoding="utf-8"))
        df = epicyclic_table(net, spec["inputs"], spec["carrier"], spec["turned"])
        write_csv(df, Path(tables_dir) / f"epicyclic_{name}.csv")
        first = spec["inputs"][0]
        lines.append(
            f"{Path(tables_dir) / f'epicyclic_{name}.csv'}: {len(df)} members, per {first}: "
            + ", ".join(f"{m} {v}" for m, v in zip(df["member"], df[f"per_{first}"]))
        )
    return lines
