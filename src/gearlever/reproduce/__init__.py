"""Regenerate every file in tables/ and figures/.

Each module in this package defines ``run(tables_dir, figures_dir)``, which
writes its files (atomically, into folders that exist) and returns a list of
summary lines naming the files by the paths written.  They run in
alphabetical order of module name.  :func:`run` checks both folders before
anything is written (each must be a writable directory or creatable), then
creates them; a refused folder raises :class:`OSError` naming it, and no file
is written.  Every file is staged and renamed into place at the end
(:func:`gearlever._io.output_set`): a step that fails leaves no file written
and no folder created.  This package may import ``tables``
(pandas) and ``plotting`` (matplotlib); the numeric modules never do.

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import gearlever's ``_format``, ``_io``,
``_progress``, ``_result``, ``_validate``, ``cams``, ``curves``, ``data``,
``dynamics``, ``errors``, ``gears``, ``laws``, ``loops``, ``mechanism``,
``plotting``, ``synthesis``, ``tables``, ``trains``, ``zrdpm``.
"""

from __future__ import annotations

import importlib
import pkgutil
from pathlib import Path


def run(tables_dir, figures_dir) -> list[str]:
    """Run every reproduction step, writing all files or none; return all summary lines.

    The summary lines name the files by the paths written (``tables_dir``
    and ``figures_dir`` as given).
    """
    from gearlever._io import check_folder, output_set

    tables_dir, figures_dir = Path(tables_dir), Path(figures_dir)
    for folder in (tables_dir, figures_dir):  # both checked before either is created
        check_folder(folder)
    lines: list[str] = []
    with output_set() as outputs:  # every file renamed into place at the end, or none
        for folder in (tables_dir, figures_dir):
            outputs.declare_folder(folder)
        for info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
            if info.name.startswith("_"):
                continue
            module = importlib.import_module(f"{__name__}.{info.name}")
            lines.extend(module.run(tables_dir, figures_dir))
    return lines
