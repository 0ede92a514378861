"""safe_label: element names in any script drawn without missing-glyph warnings."""

from __future__ import annotations

import warnings

import matplotlib

matplotlib.use("Agg")  # tests choose the backend; the library never does

import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from gearlever.plotting._text import font_has, safe_label  # noqa: E402


def _draw(text: str) -> list:
    """Warnings raised while drawing ``text``."""
    fig, ax = plt.subplots()
    ax.text(0.5, 0.5, text)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fig.canvas.draw()
    plt.close(fig)
    return [str(w.message) for w in caught]


@pytest.mark.parametrize("name", ["crank", "O2", "кривошип", "rod_2.b-3", "曲柄", "クランク", "𝔸x"])
def test_safe_label_draws_without_missing_glyph_warnings(name):
    assert not [w for w in _draw(safe_label(name)) if "missing" in w.lower()]


def test_safe_label_keeps_names_the_font_can_draw():
    assert safe_label("crank") == "crank"
    if all(font_has(c) for c in "кривошип"):
        assert safe_label("кривошип") == "кривошип"


def test_safe_label_escapes_what_the_font_lacks_and_the_raw_name_would_warn():
    name = "曲柄"
    if all(font_has(c) for c in name):
        pytest.skip("this machine's default font has CJK glyphs")
    assert [w for w in _draw(name) if "missing" in w.lower()], "the raw name should warn (else the test proves nothing)"
    assert safe_label(name) == "\\u66f2\\u67c4"
    assert safe_label("a曲") == "a\\u66f2"


def test_safe_label_escapes_dollars_so_names_are_not_mathtext():
    assert safe_label("$x$") == "\\$x\\$"
    assert not _draw(safe_label("a$b"))
