"""Regenerate every file in tables/ and figures/.

Each module in this package defines ``run(tables_dir, figures_dir)``, which
writes its files (atomically) and returns a list of summary lines.  They run
in alphabetical order of module name.  This package may import ``tables``
(pandas) and ``plotting`` (matplotlib); the numeric modules never do.
"""

from __future__ import annotations

import importlib
import pkgutil
from pathlib import Path


def run(tables_dir, figures_dir) -> list[str]:
    """Run every reproduction step; return all summary lines."""
    tables_dir, figures_dir = Path(tables_dir), Path(figures_dir)
    tables_dir.mkdir(parents=True, exist_ok=True)
    figures_dir.mkdir(parents=True, exist_ok=True)
    lines: list[str] = []
    for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        lines.extend(module.run(tables_dir, figures_dir))
    return lines
