"""Helpers shared by the CLI sub-commands: number parsing and output."""

from __future__ import annotations

import argparse
import math

from gearlever import _io
from gearlever._io import write_text_atomic


def finite_float(text: str) -> float:
    """argparse type: a finite float (argparse reports the parameter name on failure)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text!r}")
    return value


def positive_float(text: str) -> float:
    """argparse type: a finite float > 0."""
    value = finite_float(text)
    if value <= 0:
        raise argparse.ArgumentTypeError(f"must be a positive number, got {text!r}")
    return value


def nonnegative_int(text: str) -> int:
    """argparse type: an integer >= 0."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a non-negative integer, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be a non-negative integer, got {text!r}")
    return value


def positive_int(text: str) -> int:
    """argparse type: an integer >= 1."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be a positive integer, got {text!r}")
    return value


def emit(text: str, out: str | None = None) -> None:
    """Print ``text`` to stdout, or write it atomically to the file ``out``."""
    if out:
        write_text_atomic(out, text if text.endswith("\n") else text + "\n")
    else:
        print(text)


def to_json(obj) -> str:
    """Strict JSON (NaN and infinities as null), keys in the order given; see :func:`gearlever._io.to_json`."""
    return _io.to_json(obj, indent=2)
