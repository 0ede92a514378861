"""Deterministic, atomic CSV output shared by every table."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from gearlever._frame import frame
from gearlever._io import write_text_atomic

__all__ = ["FLOAT_FORMAT", "frame", "write_csv"]

#: Significant digits written for floats: enough for a round trip of the
#: values to ~1e-12 relative, and byte-identical on every run.
FLOAT_FORMAT = "%.12g"


def write_csv(df: pd.DataFrame, path, float_format: str = FLOAT_FORMAT) -> Path:
    """Write ``df`` (without its index) to ``path`` atomically; return the path.

    Output is deterministic: fixed float format, ``\\n`` line ends.
    """
    text = df.to_csv(index=False, float_format=float_format, lineterminator="\n")
    return write_text_atomic(path, text)
