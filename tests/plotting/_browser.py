"""The headless Chromium of the browser tests (selenium), one per test module that asks for ``driver``.

Without chromium/chromedriver a module using ``driver`` is skipped locally and FAILS when the
environment variable CI is set (a browser test never silently skips in CI).  The browser keeps its
console log (``driver.get_log("browser")``).  A test module takes the fixture with
``driver = _browser.driver``.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def have_browser() -> bool:
    return all(Path(p).is_file() for p in (CHROMIUM, CHROMEDRIVER))


@pytest.fixture(scope="module")
def driver(tmp_path_factory):
    if not have_browser():
        msg = f"chromium and chromedriver are needed ({CHROMIUM}, {CHROMEDRIVER})"
        if os.environ.get("CI"):
            pytest.fail(msg + ": the browser tests must run in CI")
        pytest.skip(msg)
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    opts = webdriver.ChromeOptions()
    opts.binary_location = CHROMIUM
    for a in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--no-first-run",
        "--window-size=1000,800",
        f"--user-data-dir={tmp_path_factory.mktemp('chromium-profile')}",
    ):
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    d = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    d.set_page_load_timeout(60)
    yield d
    d.quit()
