"""Sphinx directive ``.. gearlever-toplevel::``: the names ``import gearlever`` gives, linked to their homes.

:mod:`gearlever` re-exports the most used names of its subpackages
(``gearlever.__all__``).  Each is documented once, in the module that defines
it; this directive lists every name of ``__all__`` (or of the package given as
argument) with a link to that page and the first line of its docstring, so the
list cannot go stale.
"""

from __future__ import annotations

import importlib
import inspect

from docutils import nodes
from docutils.parsers.rst import Directive


def _home(obj, fallback: str) -> str:
    module = getattr(obj, "__module__", None)
    qual = getattr(obj, "__qualname__", None)
    if module and qual and not inspect.ismodule(obj):
        return f"{module}.{qual}"
    return fallback


class TopLevel(Directive):
    required_arguments = 0
    optional_arguments = 1

    def run(self):
        package = self.arguments[0] if self.arguments else "gearlever"
        mod = importlib.import_module(package)
        dl = nodes.definition_list()
        for name in mod.__all__:
            obj = getattr(mod, name)
            item = nodes.definition_list_item()
            if isinstance(obj, str):  # __version__
                term, _ = self.state.inline_text(f"``{package}.{name}``", self.lineno)
                summary = f"the version, {obj!r}"
            else:
                home = _home(obj, f"{package}.{name}")
                role = "py:class" if inspect.isclass(obj) else "py:func" if callable(obj) else "py:obj"
                term, _ = self.state.inline_text(f":{role}:`{package}.{name} <{home}>`", self.lineno)
                doc = inspect.getdoc(obj) or ""
                summary = doc.split("\n\n")[0].replace("\n", " ") if doc else ""
                summary = f"{summary} (defined in ``{getattr(obj, '__module__', package)}``)"
            item += nodes.term("", "", *term)
            text, _ = self.state.inline_text(summary, self.lineno)
            definition = nodes.definition()
            definition += nodes.paragraph("", "", *text)
            item += definition
            dl += item
        return [dl]


def setup(app):
    app.add_directive("gearlever-toplevel", TopLevel)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
