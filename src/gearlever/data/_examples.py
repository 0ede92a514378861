"""The example model files shipped with the package (``gearlever/data/examples``).

Mechanism models (``*.toml``) and gear networks (``*.csv``) that the guide,
the tests and ``gearlever reproduce`` use.  They are package data, so they are
found the same way from a source checkout and from an installed wheel
(:mod:`importlib.resources`).  Imports only the standard library and
:mod:`gearlever.errors`.
"""

from __future__ import annotations

import atexit
import contextlib
from importlib import resources
from pathlib import Path

from gearlever.errors import GearleverError

#: Suffixes of the files that are examples (anything else in the folder is not listed).
EXAMPLE_SUFFIXES = (".toml", ".csv")

_extracted = contextlib.ExitStack()
atexit.register(_extracted.close)


def _folder():
    return resources.files("gearlever.data").joinpath("examples")


def list_examples() -> list[str]:
    """Names (with suffix) of the shipped example files, sorted.

    Returns
    -------
    list of str
        File names such as ``"fourbar.toml"`` (mechanism models) and
        ``"car_differential.csv"`` (gear networks).

    Examples
    --------
    >>> names = list_examples()
    >>> "fourbar.toml" in names and "car_differential.csv" in names
    True
    """
    return sorted(p.name for p in _folder().iterdir() if p.is_file() and p.name.endswith(EXAMPLE_SUFFIXES))


def example_path(name: str) -> Path:
    """Path of the shipped example file ``name`` (``"fourbar.toml"``, or ``"fourbar"`` without suffix).

    Parameters
    ----------
    name : str
        A name from :func:`list_examples`; the suffix may be left out when
        only one example has that stem.

    Returns
    -------
    pathlib.Path
        A readable file.  From a zipped install the file is extracted to a
        temporary folder that lives until the interpreter exits.

    Raises
    ------
    GearleverError
        ``name`` is not a shipped example (the message lists the valid names).

    Examples
    --------
    >>> example_path("fourbar").name
    'fourbar.toml'
    >>> example_path("fourbar.toml").read_text().startswith("#")
    True
    >>> example_path("nosuch")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    gearlever.errors.GearleverError: name: no example 'nosuch'; the examples are ...
    """
    names = list_examples()
    chosen = [name] if name in names else [n for n in names if n.rsplit(".", 1)[0] == name]
    if len(chosen) != 1:
        why = f"{name!r} is ambiguous (give the suffix)" if chosen else f"no example {name!r}"
        raise GearleverError(f"name: {why}; the examples are {', '.join(names)}")
    ref = _folder().joinpath(chosen[0])
    if isinstance(ref, Path):
        return ref
    return _extracted.enter_context(resources.as_file(ref))  # pragma: no cover - zipped installs only
