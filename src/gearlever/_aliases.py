"""Old module paths kept importable after the move to subpackages.

``import gearlever.networks`` (a path of version 0.1) gives the module
:mod:`gearlever.gears.networks` itself, not a copy: the same objects, one
place of definition.  Imports only :mod:`importlib` and :mod:`sys`.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys

#: old path -> new path
ALIASES = {
    "gearlever.networks": "gearlever.gears.networks",
    "gearlever.chariot": "gearlever.gears.chariot",
    "gearlever.car": "gearlever.gears.car",
    "gearlever.differential": "gearlever.gears.willis",
    "gearlever.hooke": "gearlever.trains.hooke",
    "gearlever.structure": "gearlever.mechanism.mobility",
    "gearlever.mechanism.structure": "gearlever.mechanism.mobility",
    "gearlever.vector_loop": "gearlever.loops.vector_loop",
    "gearlever.synthesis._model": "gearlever.synthesis.model",
}


class _AliasFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    def find_spec(self, fullname, path=None, target=None):
        if fullname in ALIASES:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        return None  # a placeholder; exec_module swaps in the real module

    def exec_module(self, module):
        sys.modules[module.__name__] = importlib.import_module(ALIASES[module.__name__])


def install() -> None:
    """Put the alias finder on :data:`sys.meta_path` (once)."""
    if not any(isinstance(f, _AliasFinder) for f in sys.meta_path):
        sys.meta_path.append(_AliasFinder())
