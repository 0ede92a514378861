"""Test helpers of the workbench: the real server on a free loopback port, and a guarded headless Chromium.

``running_bench(workspace)`` starts the Starlette app of :func:`gearlever.workbench.app.create_app` under
uvicorn in a background thread, on a socket bound to ``127.0.0.1:0`` (the kernel picks a free port), and
yields a :class:`Bench` ``(base_url, token, workspace)``; leaving the block stops the server and joins the
thread.  The fixture ``bench`` does that for one test with a fresh temporary workspace (each test starts and
stops its own server).

``browser`` is the module's headless Chromium (``tests/plotting/_browser.py``: Debian's chromium and
chromedriver through selenium; skipped locally without them and FAILING under ``CI``), with two guards:

* every request to a host other than loopback goes to a dead proxy (``--proxy-server`` on a closed port;
  Chromium never proxies loopback), so nothing leaves the machine, and :func:`off_host_requests` lists
  every URL the page asked for that is not the bench's own (from the performance log's
  ``Network.requestWillBeSent`` events);
* :func:`console_errors` lists the browser console's SEVERE entries.

``guarded(browser, bench)`` runs a test body and then fails on any off-host request or console error.
"""

from __future__ import annotations

import contextlib
import inspect
import json
import os
import re
import secrets
import socket
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from tests.plotting import _browser

#: Requests the page may make without a host: inline data and object URLs, the browser's own pages.
LOCAL_SCHEMES = ("data", "blob", "about", "chrome", "devtools", "chrome-extension")


@dataclass(frozen=True)
class Bench:
    """A running workbench server: where it is, its token and its workspace folder."""

    base_url: str
    token: str
    workspace: Path

    @property
    def host(self) -> str:
        return urlsplit(self.base_url).netloc

    @property
    def page_url(self) -> str:
        return f"{self.base_url}/?token={self.token}"

    def __iter__(self):  # (base_url, token, workspace) = bench
        return iter((self.base_url, self.token, self.workspace))


#: The tests check behaviour, not speed: on a loaded 2-core machine a worker's first answer (its imports and
#: warm-up) can take longer than the server's default cap per solve, so the test server's caps are generous.
TEST_CAPS = {"solve_seconds": 120.0, "export_seconds": 120.0}


def _make_app(workspace: Path, token: str, port: int, **kwargs):
    from gearlever.workbench.app import create_app

    params = inspect.signature(create_app).parameters
    kwargs = {k: v for k, v in {**TEST_CAPS, **kwargs}.items() if k in params}
    if "host" in params:
        kwargs["host"] = "127.0.0.1"
    if "port" in params:
        kwargs["port"] = port
    return create_app(workspace, token, **kwargs)


@contextlib.contextmanager
def running_bench(workspace: Path, token: str | None = None, timeout: float = 30.0, **app_kwargs) -> Iterator[Bench]:
    """Start the real app under uvicorn in a thread on a free loopback port; stop it on exit.

    ``app_kwargs`` go to ``create_app`` (caps, workers...) over :data:`TEST_CAPS`.
    """
    import uvicorn

    workspace = Path(workspace)
    workspace.mkdir(parents=True, exist_ok=True)
    token = token or secrets.token_hex(16)
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind(("127.0.0.1", 0))
    port = sock.getsockname()[1]
    app = _make_app(workspace, token, port, **app_kwargs)
    config = uvicorn.Config(app, log_level="warning", lifespan="auto", access_log=False)
    server = uvicorn.Server(config)
    errors: list[BaseException] = []

    def run():
        try:
            server.run(sockets=[sock])
        except BaseException as exc:  # reported to the test below
            errors.append(exc)

    thread = threading.Thread(target=run, name=f"workbench-{port}", daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout
    while not server.started:
        if errors or not thread.is_alive():
            raise RuntimeError(f"the workbench server did not start: {errors!r}")
        if time.monotonic() > deadline:
            raise RuntimeError(f"the workbench server did not start in {timeout} s")
        time.sleep(0.01)
    try:
        yield Bench(f"http://127.0.0.1:{port}", token, workspace)
    finally:
        server.should_exit = True
        thread.join(timeout)
        sock.close()
        if thread.is_alive():
            raise RuntimeError("the workbench server did not stop")


@pytest.fixture
def bench(tmp_path) -> Iterator[Bench]:
    """The workbench on a free port with a fresh workspace ``tmp_path/workspace``, for one test."""
    with running_bench(tmp_path / "workspace") as b:
        yield b


@pytest.fixture(scope="module")
def browser(tmp_path_factory):
    """Headless Chromium (selenium) whose requests off loopback go nowhere and are logged."""
    if not _browser.have_browser():
        msg = f"chromium and chromedriver are needed ({_browser.CHROMIUM}, {_browser.CHROMEDRIVER})"
        if os.environ.get("CI"):
            pytest.fail(msg + ": the browser tests must run in CI")
        pytest.skip(msg)
    d = start_browser(tmp_path_factory.mktemp("chromium-profile"))
    try:
        yield d
    finally:
        d.quit()


def start_browser(profile: Path, size: tuple[int, int] = (1280, 860)):
    """A headless Chromium driver whose requests off loopback go to a dead proxy (see the module's doc)."""
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    # A closed loopback port as the proxy: every request to another host fails there (loopback is never
    # proxied), and DNS is refused for every name but localhost.
    dead = socket.socket()
    dead.bind(("127.0.0.1", 0))
    dead_port = dead.getsockname()[1]
    dead.close()
    opts = webdriver.ChromeOptions()
    opts.binary_location = _browser.CHROMIUM
    for a in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-extensions",
        "--disable-default-apps",
        "--no-first-run",
        "--no-default-browser-check",
        f"--window-size={size[0]},{size[1]}",
        "--force-device-scale-factor=1",
        f"--proxy-server=http://127.0.0.1:{dead_port}",
        "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE localhost, EXCLUDE 127.0.0.1",
        f"--user-data-dir={profile}",
    ):
        opts.add_argument(a)
    opts.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    d = webdriver.Chrome(service=Service(_browser.CHROMEDRIVER), options=opts)
    d.set_page_load_timeout(60)
    d.set_script_timeout(120)
    d.execute_cdp_cmd("Network.enable", {})
    return d


def requested_urls(driver) -> list[str]:
    """Every URL the browser asked for since the last call (performance log, Network.requestWillBeSent)."""
    urls = []
    for entry in driver.get_log("performance"):
        try:
            message = json.loads(entry["message"])["message"]
        except (KeyError, ValueError):
            continue
        if message.get("method") == "Network.requestWillBeSent":
            urls.append(message["params"]["request"]["url"])
    return urls


def off_host_requests(urls: list[str], bench: Bench) -> list[str]:
    """The URLs that are neither the bench's own nor local (data:, blob:...)."""
    bad = []
    for url in urls:
        parts = urlsplit(url)
        if parts.scheme in LOCAL_SCHEMES:
            continue
        if parts.scheme in ("http", "https", "ws", "wss") and parts.netloc == bench.host:
            continue
        bad.append(url)
    return bad


def console_errors(driver, allow: tuple[str, ...] = ()) -> list[str]:
    """The SEVERE console entries since the last call, but those matching a regular expression of ``allow``.

    Chromium logs every 4xx answer as a console error ("Failed to load resource"); a test that makes one on
    purpose (a TOML syntax error, a stale If-Match) names it in ``allow``, and nothing else passes.
    """
    out = []
    for e in driver.get_log("browser"):
        if e.get("level") == "SEVERE" and not any(re.search(a, e["message"]) for a in allow):
            out.append(e["message"])
    return out


def reset_logs(driver) -> None:
    driver.get_log("browser")
    driver.get_log("performance")


def check_clean(driver, bench: Bench, allow: tuple[str, ...] = ()) -> None:
    """Fail on any console error (but ``allow``) and on any request to another host since the last check."""
    errors = console_errors(driver, allow)
    bad = off_host_requests(requested_urls(driver), bench)
    assert not bad, f"requests to other hosts than {bench.host}: {bad}"
    assert not errors, f"console errors: {errors}"


@contextlib.contextmanager
def guarded(driver, bench: Bench, allow: tuple[str, ...] = ()) -> Iterator[None]:
    """Run the body, then fail on any console error (but ``allow``) or off-host request it caused."""
    reset_logs(driver)
    yield
    check_clean(driver, bench, allow)


def desktop(driver) -> None:
    """The browser as a desktop window, 1280 x 860, no touch (a test before may have emulated a phone)."""
    driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})
    driver.execute_cdp_cmd("Emulation.setTouchEmulationEnabled", {"enabled": False})
    driver.set_window_size(1280, 860)


def open_bench(driver, bench: Bench, fragment: str = "", timeout: float = 30.0) -> None:
    """Open the page with the token (and a URL fragment) and wait until ``workbench.state().ready``."""
    driver.get(bench.page_url + (f"#{fragment}" if fragment else ""))
    wait_for(driver, "return !!(window.workbench && window.workbench.state().ready)", timeout)


def wait_for(driver, script: str, timeout: float = 30.0, *args):
    """Poll a JavaScript expression (a ``return ...`` statement) until it is truthy; return its value."""
    deadline = time.monotonic() + timeout
    while True:
        value = driver.execute_script(script, *args)
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for: {script}")
        time.sleep(0.05)
