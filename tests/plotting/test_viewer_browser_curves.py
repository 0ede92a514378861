"""The page of a synthesized linkage (``mechanism view`` of a ``synthesize curve`` design) opens on its traced point."""

from __future__ import annotations

import json

from gearlever.mechanism import Mechanism
from gearlever.mechanism.linkage import linkage_from_dict
from gearlever.plotting.viewer import viewer_html
from gearlever.synthesis.curve.model import linkage_toml
from tests.plotting import _browser
from tests.synthesis.curve._designs import SIXBAR

driver = _browser.driver  # fixture


def _quantity(driver, mech, path):
    from selenium.webdriver.support.ui import WebDriverWait

    path.write_text(viewer_html(mech, frames=24), encoding="utf-8")
    driver.get(path.as_uri())
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready") == "1")
    return driver.execute_script("return document.getElementById('quantity').value")


def test_a_synthesized_linkage_page_opens_on_the_traced_point_and_others_on_the_last_link(driver, tmp_path):
    links = tmp_path / "0001.links.json"
    links.write_text(json.dumps(SIXBAR))
    assert _quantity(driver, Mechanism.load(links), tmp_path / "0001.html") == "y:P"  # not the angle of L6
    # the same linkage with its traced point renamed: the angle of the last link, as before
    model = tmp_path / "q.toml"
    model.write_text(linkage_toml(linkage_from_dict(SIXBAR)).replace('"P"', '"Q"').replace("\nP = ", "\nQ = "))
    assert _quantity(driver, Mechanism.load(model), tmp_path / "q.html") == "phi:L6"
