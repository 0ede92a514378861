"""Published reference data, each file with its source, page and units in a header.

Files are read on demand with :mod:`importlib.resources`, never at import time.
"""

from __future__ import annotations

from importlib import resources


def read_text(name: str) -> str:
    """Return the text of the data file ``name`` shipped in this package."""
    return resources.files(__name__).joinpath(name).read_text(encoding="utf-8")
