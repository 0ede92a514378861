"""Sphinx directive ``.. gearlever-cli::``: the command-line reference, generated from the parser.

Walks :func:`gearlever.cli.build_parser` (every sub-command registered by the
modules of :mod:`gearlever.cli`) and emits one section per command and
sub-command with its help line, usage, description and every argument (flags,
metavar, help with defaults expanded, choices).  Nothing is written by hand,
so the page cannot go stale: a new option appears at the next build.

Options: ``:command: NAME`` documents one top-level command only.
"""

from __future__ import annotations

import argparse
import os
from contextlib import contextmanager

from docutils import nodes
from docutils.parsers.rst import Directive, directives

#: Width the usage lines are wrapped at (fixed, so the page is the same on any terminal).
USAGE_COLUMNS = "88"


@contextmanager
def _columns(width: str):
    old = os.environ.get("COLUMNS")
    os.environ["COLUMNS"] = width
    try:
        yield
    finally:
        if old is None:
            os.environ.pop("COLUMNS", None)
        else:
            os.environ["COLUMNS"] = old


def _subparsers(parser: argparse.ArgumentParser):
    """``[(name, help, child parser)]`` of the parser's sub-commands (aliases once)."""
    acts = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    if not acts:
        return []
    helps = {c.dest: c.help for c in acts[0]._choices_actions}
    seen, out = set(), []
    for name, child in acts[0].choices.items():
        if id(child) in seen:
            continue
        seen.add(id(child))
        out.append((name, helps.get(name) or "", child))
    return out


def _expanded_help(parser: argparse.ArgumentParser, action: argparse.Action) -> str:
    if not action.help or action.help == argparse.SUPPRESS:
        return ""
    return parser._get_formatter()._expand_help(action)


def _argument_items(parser: argparse.ArgumentParser) -> nodes.definition_list | None:
    dl = nodes.definition_list()
    for action in parser._actions:
        if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
            continue
        if action.help == argparse.SUPPRESS:
            continue
        formatter = parser._get_formatter()
        if action.option_strings:
            if action.nargs == 0:
                term_text = ", ".join(action.option_strings)
            else:  # argparse's own rendering of the metavar (choices as {a,b}, tuples, nargs)
                args = formatter._format_args(action, formatter._get_default_metavar_for_optional(action))
                term_text = ", ".join(action.option_strings) + " " + args
        else:
            term_text = formatter._format_args(action, formatter._get_default_metavar_for_positional(action))
        body = []
        help_text = _expanded_help(parser, action)
        if help_text:
            body.append(help_text)
        if action.choices is not None and not action.option_strings:
            body.append("choices: " + ", ".join(str(c) for c in action.choices))
        if action.required and action.option_strings:
            body.append("required")
        default = action.default
        if (
            action.option_strings
            and action.nargs != 0
            and default not in (None, argparse.SUPPRESS)
            and "default" not in help_text
        ):
            body.append(f"default: {default}")
        item = nodes.definition_list_item()
        item += nodes.term("", "", nodes.literal(term_text, term_text))
        definition = nodes.definition()
        definition += nodes.paragraph("", "; ".join(body) if body else "")
        item += definition
        dl += item
    return dl if len(dl.children) else None


class CliReference(Directive):
    has_content = False
    option_spec = {"command": directives.unchanged}

    def run(self):
        from gearlever.cli import build_parser

        env = self.state.document.settings.env
        env.note_dependency(__file__)
        top = build_parser()
        wanted = self.options.get("command")
        out = []
        for name, help_line, child in _subparsers(top):
            if wanted and name != wanted:
                continue
            out.append(self._section(("gearlever", name), help_line, child))
        if wanted and not out:
            raise self.error(f"no gearlever command {wanted!r}")
        return out

    def _section(self, path, help_line, parser):
        title = " ".join(path)
        section = nodes.section(ids=[nodes.make_id("cli " + title)], names=[nodes.fully_normalize_name(title)])
        section += nodes.title(title, "", nodes.literal(title, title))
        if help_line:
            section += nodes.paragraph(help_line, help_line[:1].upper() + help_line[1:] + ".")
        with _columns(USAGE_COLUMNS):
            usage = parser.format_usage().strip()
        section += nodes.literal_block(usage, usage, language="text")
        if parser.description and parser.description.rstrip(".") != help_line.rstrip("."):
            for para in parser.description.split("\n\n"):
                text = " ".join(para.split())
                section += nodes.paragraph(text, text)
        args = _argument_items(parser)
        if args is not None:
            section += args
        for name, sub_help, child in _subparsers(parser):
            section += self._section((*path, name), sub_help, child)
        self.state.document.note_implicit_target(section)
        return section


def setup(app):
    app.add_directive("gearlever-cli", CliReference)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
