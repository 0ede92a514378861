"""Fixtures of the workbench tests: the server of one test, the module's Chromium, and an opened page.

``bench`` starts the real server for one test on a free loopback port and stops it after
(:func:`tests.workbench._server.running_bench`); ``browser`` is the module's headless Chromium, which fails
under ``CI`` when chromium or chromedriver is missing and skips only outside it (``_server.browser``).

``page`` is the set-up every page test shared: the browser at the desktop size, the page of this test's
bench opened and ready, and the whole test ``guarded``: it fails on a console error or a request off the
bench's host made at any point of the test.  A test that causes a console error on purpose names it with
``@pytest.mark.console_allow(regex, ...)``.
"""

from __future__ import annotations

import pytest

from tests.workbench import _server

bench = _server.bench
browser = _server.browser


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "console_allow(*regex): console errors the page test causes on purpose (see tests/workbench)"
    )


@pytest.fixture
def page(request, browser, bench):
    """The module's Chromium with this test's bench opened at the desktop size, guarded for the whole test."""
    marker = request.node.get_closest_marker("console_allow")
    allow = tuple(marker.args) if marker else ()
    _server.desktop(browser)
    _server.reset_logs(browser)
    _server.open_bench(browser, bench)
    yield browser
    if request.node.stash.get(_FAILED, False):
        return  # the test's own failure says more than the logs it left
    _server.check_clean(browser, bench, allow)


_FAILED = pytest.StashKey[bool]()


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    report = yield
    if report.when == "call" and report.failed:
        item.stash[_FAILED] = True
    return report
