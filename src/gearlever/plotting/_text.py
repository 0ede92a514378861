"""Labels from user names that every font in use can draw.

Model element names may be in any script (``曲柄``, ``кривошип``); a name
whose characters the current matplotlib font lacks would be drawn as empty
boxes, with a "Glyph ... missing from font" warning per character.
:func:`safe_label` returns the name itself when the font has every glyph,
else an ASCII form with the missing characters escaped (``\\u66f2``), which
still tells the elements apart.
"""

from __future__ import annotations

import functools

__all__ = ["safe_label", "font_has"]


@functools.lru_cache(maxsize=8)
def _font(path: str):
    from matplotlib import ft2font

    return ft2font.FT2Font(path)


def _font_paths() -> tuple:
    """Files of the fonts matplotlib uses for plain text now (the family list, with its fallbacks)."""
    from matplotlib import font_manager, rcParams

    prop = font_manager.FontProperties(family=rcParams["font.family"])
    try:  # matplotlib >= 3.6 falls back along the family list
        found = font_manager.fontManager._find_fonts_by_props(prop)
    except AttributeError:  # pragma: no cover - older matplotlib
        found = [font_manager.findfont(prop)]
    return tuple(str(p) for p in found)


def font_has(char: str, paths: tuple | None = None) -> bool:
    """True when one of the fonts in use (or of ``paths``) has a glyph for the character ``char``."""
    paths = _font_paths() if paths is None else paths
    code = ord(char)
    return any(_font(p).get_char_index(code) != 0 for p in paths)


def safe_label(name: str) -> str:
    """``name`` if the current font can draw all of it, else with the missing characters escaped.

    Whitespace and ASCII pass unchanged; a character no font in use has
    becomes ``\\uXXXX`` (``\\UXXXXXXXX`` beyond the basic plane).  Dollar
    signs are escaped so that a name is never read as mathtext.

    >>> safe_label("crank")
    'crank'
    >>> safe_label("A$1")
    'A\\\\$1'
    """
    paths = _font_paths()
    out = []
    for ch in str(name):
        if ch == "$":
            out.append("\\$")
        elif ch.isascii() or font_has(ch, paths):
            out.append(ch)
        else:
            code = ord(ch)
            out.append(f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}")
    return "".join(out)
