"""Published reference data, each file with its source, page and units in a header.

Files are read on demand with :mod:`importlib.resources`, never at import time.
Every data file is a CSV whose leading ``#`` lines name its source; the one
reader :func:`read_records` skips them and returns the rows as dicts.

The example models (``examples/*.toml`` mechanisms, ``examples/*.csv`` gear
networks) ship here too: :func:`list_examples` names them and
:func:`example_path` finds one, from a source checkout or an installed wheel.

Within the layering of the guide's architecture page (held by
``tests/test_imports.py``) it may import the standard library and gearlever's
``_io`` (the one CSV reader) and ``errors``.
"""

from __future__ import annotations

from importlib import resources

from gearlever.data._examples import example_path, list_examples

__all__ = ["read_records", "read_text", "list_examples", "example_path"]


def read_text(name: str) -> str:
    """Return the text of the data file ``name`` shipped in this package.

    Examples
    --------
    >>> read_text("zrdpm_mobility.csv").startswith("#")
    True
    """
    return resources.files(__name__).joinpath(name).read_text(encoding="utf-8")


def read_records(name: str) -> list[dict[str, str]]:
    """Rows of the data file ``name`` as dicts keyed by its header, ``#`` lines skipped.

    Examples
    --------
    >>> rows = read_records("zrdpm_mobility.csv")
    >>> sorted(rows[0])[:3]
    ['case', 'n', 'p4']
    """
    from gearlever._io import csv_table

    table = csv_table(read_text(name), name, comments=True)
    return [dict(zip(table.header, row)) for row in table.rows]
