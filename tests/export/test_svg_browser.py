"""SVG export (gearlever.export.svg) opened in headless Chromium: it parses, holds every part, and draws.

One browser for the module (``tests/plotting/_browser.py``); skipped locally without chromium, failed in CI.
"""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET

import numpy as np
import pytest

from gearlever.data import example_path
from gearlever.export import export
from gearlever.mechanism import Mechanism
from tests.plotting import _browser

driver = _browser.driver  # fixture


@pytest.mark.parametrize("name", ["fourbar", "geared_fivebar", "planetary", "slider_crank"])
def test_svg_opens_in_chromium_with_every_part(name, tmp_path, driver):
    mech = Mechanism.load(example_path(f"{name}.toml"))
    out = tmp_path / f"{name}.svg"
    drawing = export(mech, out)
    ET.parse(out)  # well-formed XML
    driver.get(out.as_uri())
    assert driver.execute_script("return document.documentElement.tagName") == "svg"
    ids = driver.execute_script("return Array.from(document.querySelectorAll('g')).map(g => g.id)")
    assert ids == [f"link-{p.name}" for p in drawing.parts]
    circles = driver.execute_script("return document.querySelectorAll('circle').length")
    assert circles == sum(len(p.holes) for p in drawing.parts)
    # the browser lays the drawing out: the bounding box of the parts is the drawing's extent
    box = driver.execute_script("const b = document.documentElement.getBBox(); return [b.x, b.y, b.width, b.height]")
    x0, y0, x1, y1 = drawing.extent()
    assert box[2] >= (x1 - x0) * 0.99 and box[3] >= (y1 - y0) * 0.99
    # and draws strokes: the screenshot is not blank
    from PIL import Image

    png = Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("L")
    assert (np.asarray(png) < 250).sum() > 500
    errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
    assert not errors
