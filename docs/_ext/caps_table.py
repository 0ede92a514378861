"""Sphinx directive ``.. gearlever-caps::``: every size cap of gearlever, found in the code.

A cap is a module-level constant named ``MAX_*`` (or ``*_CAP``) in any module
of gearlever, documented by a ``#:`` comment above it.  The directive imports
every module, reads the constants and their comments (Sphinx's own source
analyser), and emits one table row per cap: where it lives, its value and what
it limits.  A cap added to the code appears at the next build.
"""

from __future__ import annotations

import importlib
import numbers
import pkgutil
import re

from docutils import nodes
from docutils.parsers.rst import Directive
from sphinx.pycode import ModuleAnalyzer

NAME = re.compile(r"^(MAX_[A-Z0-9_]+|[A-Z0-9_]+_CAP)$")


def _value_text(v) -> str:
    if isinstance(v, dict):
        return ", ".join(f"{k}: {_value_text(x)}" for k, x in v.items())
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        return repr(v)
    if isinstance(v, int) and v >= 10_000:
        if str(v).rstrip("0") == "1":
            return f"10^{len(str(v)) - 1}"
        if v % 2**20 == 0:
            return f"{v // 2**20} MiB ({v:,})"
        return f"{v:,}"
    return f"{v:g}" if isinstance(v, float) else str(v)


def collect_caps():
    """``[(module, name, value, comment)]`` for every cap constant, sorted by module and name."""
    import gearlever

    names = ["gearlever"] + [m.name for m in pkgutil.walk_packages(gearlever.__path__, "gearlever.")]
    rows = []
    for modname in sorted(set(names)):
        if modname.endswith("__main__"):
            continue
        module = importlib.import_module(modname)
        caps = {k: v for k, v in vars(module).items() if NAME.match(k)}
        if not caps:
            continue
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:  # noqa: BLE001 - a module without source: no comments
            docs = {}
        for k, v in sorted(caps.items()):
            comment = docs.get(("", k))
            if comment is None:
                continue  # imported from its home module, where it is listed
            rows.append((modname, k, v, " ".join(" ".join(comment).split())))
    return rows


class CapsTable(Directive):
    has_content = False

    def run(self):
        rows = collect_caps()
        table = nodes.table()
        group = nodes.tgroup(cols=4)
        table += group
        for width in (22, 18, 14, 46):
            group += nodes.colspec(colwidth=width)
        head = nodes.thead()
        body = nodes.tbody()
        group += head
        group += body

        def row(cells, literal=(False, False, False, False), rst=False):
            r = nodes.row()
            for i, (text, lit) in enumerate(zip(cells, literal)):
                entry = nodes.entry()
                if lit:
                    inline = [nodes.literal(text, text)]
                elif rst and i == len(cells) - 1:  # the comment: inline reST (roles, literals)
                    inline, _messages = self.state.inline_text(text, self.lineno)
                else:
                    inline = [nodes.Text(text)]
                entry += nodes.paragraph("", "", *inline)
                r += entry
            return r

        head += row(("module", "constant", "value", "what it limits"))
        for modname, k, v, comment in rows:
            body += row((modname, k, _value_text(v), comment), (True, True, False, False), rst=True)
        return [table]


def setup(app):
    app.add_directive("gearlever-caps", CapsTable)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
