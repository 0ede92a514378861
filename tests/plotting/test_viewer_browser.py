"""The viewer page in a real browser (headless Chromium through selenium): the DOM against the solver.

One browser for the module.  Without chromium/chromedriver the module is skipped locally and
FAILS when the environment variable CI is set (a browser test never silently skips in CI).
"""

from __future__ import annotations

import io
import math
import os
from pathlib import Path

import numpy as np
import pytest

from gearlever.mechanism import Mechanism
from gearlever.mechanism.centres import instant_centres
from gearlever.plotting.viewer import GRID_STEPS, viewer_html

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
NAMES = ["fourbar", "slider_crank", "whitworth", "watt_sixbar", "geared_fivebar", "zrdpm_gear_contour"]
N = 360
#: Where a point circle must be: the solver's coordinates, rounded to 6 significant digits in the page.
REL = 1e-5

# A double rocker (not Grashof): the "crank" cannot turn fully, so part of the turn does not assemble.
DOUBLE_ROCKER = """
[mechanism]
name = "double rocker"
units = "mm"
[points]
O2 = [0.0, 0.0]
O4 = [30.0, 0.0]
A  = [20.0, 0.0]
B  = [28.0, 10.0]
[links]
ground  = ["O2", "O4"]
crank   = ["O2", "A"]
coupler = ["A", "B"]
rocker  = ["O4", "B"]
[[inputs]]
link = "crank"
"""


def _have_browser() -> bool:
    return all(Path(p).is_file() for p in (CHROMIUM, CHROMEDRIVER))


@pytest.fixture(scope="module")
def driver(tmp_path_factory):
    if not _have_browser():
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
    d = webdriver.Chrome(service=Service(CHROMEDRIVER), options=opts)
    d.set_page_load_timeout(60)
    yield d
    d.quit()


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    """Page files of the examples (and of a model that does not assemble everywhere), with their models."""
    folder = tmp_path_factory.mktemp("pages")
    out = {}
    for name in NAMES:
        mech = Mechanism.load(EXAMPLES / f"{name}.toml")
        path = folder / f"{name}.html"
        path.write_text(viewer_html(mech, frames=N), encoding="utf-8")
        out[name] = (mech, path)
    model = folder / "double_rocker.toml"
    model.write_text(DOUBLE_ROCKER, encoding="utf-8")
    mech = Mechanism.load(model)
    path = folder / "double_rocker.html"
    path.write_text(viewer_html(mech, frames=72), encoding="utf-8")
    out["double_rocker"] = (mech, path)
    return out


def _open(driver, pages, name, query=""):
    from selenium.webdriver.support.ui import WebDriverWait

    mech, path = pages[name]
    driver.get(path.as_uri() + query)
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready") == "1")
    return mech


def _frame(driver) -> int:
    return int(driver.find_element("id", "frame").get_attribute("value"))


_READ = """
const out = {};
document.querySelectorAll(arguments[0]).forEach((e) => {
  out[e.getAttribute(arguments[1])] = {
    cx: e.getAttribute('cx'), cy: e.getAttribute('cy'),
    x1: e.getAttribute('x1'), y1: e.getAttribute('y1'), x2: e.getAttribute('x2'), y2: e.getAttribute('y2'),
    hidden: e.style.display === 'none' || getComputedStyle(e).display === 'none',
  };
});
return out;
"""


def _read(driver, selector, attr):
    return driver.execute_script(_READ, selector, attr)


def _solve_frames(mech, frames, n=N, grid_index=None):
    """The solver's sweep of the page's ``n`` frames (the whole turn, so that every frame is reached
    continuously from the sketch), then the rows ``frames`` of it."""
    q0 = mech.sketch_inputs.astype(float)
    W = q0.size
    q = np.tile(q0, (n, 1))
    q[:, 0] = q0[0] + 2 * np.pi * np.arange(n) / n
    if grid_index is not None:
        q[:, 1] = q0[1] + 2 * np.pi * grid_index / GRID_STEPS
    rates = np.zeros(W)
    rates[0] = 1.0
    r = mech.solve(q, np.tile(rates, (n, 1)))
    rows = np.asarray(frames)
    return _Rows(
        {p: v[rows] for p, v in r.point.items()},
        {p: v[rows] for p, v in r.velocity.items()},
        r.closed[rows],
        instant_centres(r),
        rows,
    )


class _Rows:
    def __init__(self, point, velocity, closed, ic, rows):
        self.point, self.velocity, self.closed = point, velocity, closed
        self._ic, self._rows = ic, rows

    def centres(self):
        ic = self._ic
        return type(ic)(
            ic.links,
            ic.pairs,
            ic.xy[self._rows],
            ic.at_infinity[self._rows],
            ic.direction[self._rows],
            ic.closed[self._rows],
        )


def _assert_points(dom, r, i, L):
    for p, xy in r.point.items():
        e = dom[p]
        assert not e["hidden"], p
        assert float(e["cx"]) == pytest.approx(xy[i, 0], rel=REL, abs=1e-9 * L), p
        assert float(e["cy"]) == pytest.approx(xy[i, 1], rel=REL, abs=1e-9 * L), p


@pytest.mark.parametrize("name", NAMES)
def test_point_circles_are_at_the_solver_positions_and_readout_gives_the_angle(driver, pages, name):
    frames = [0, 37, 123, 250, 359]
    mech = pages[name][0]
    r = _solve_frames(mech, frames)
    L = mech.model.length_scale
    for i, k in enumerate(frames):
        _open(driver, pages, name, f"?frame={k}")
        assert _frame(driver) == k
        _assert_points(_read(driver, "[data-point]", "data-point"), r, i, L)
        links = _read(driver, "[data-link]", "data-link")
        assert set(links) == set(mech.model.moving)
        theta = math.degrees(mech.sketch_inputs[0] + 2 * np.pi * k / N)
        assert f"θ = {theta:.2f}°" in driver.find_element("id", "readout").text


@pytest.mark.parametrize("name", ["fourbar", "slider_crank", "whitworth", "watt_sixbar", "geared_fivebar"])
def test_instant_centre_circles_match_the_solver_and_hide_at_infinity(driver, pages, name):
    frames = [0, 90, 201]
    mech = pages[name][0]
    ic = _solve_frames(mech, frames).centres()
    for i, k in enumerate(frames):
        _open(driver, pages, name, f"?frame={k}")
        dom = _read(driver, "[data-ic]", "data-ic")
        order = driver.execute_script("return Array.from(document.querySelectorAll('[data-ic]'), e => e.dataset.ic)")
        assert order == list(ic.pairs)  # ground first, then the links in model order
        for p, pair in enumerate(ic.pairs):
            e = dom[pair]
            if ic.at_infinity[i, p]:
                assert e["hidden"], pair
                continue
            assert float(e["cx"]) == pytest.approx(ic.xy[i, p, 0], rel=REL, abs=1e-9), pair
            assert float(e["cy"]) == pytest.approx(ic.xy[i, p, 1], rel=REL, abs=1e-9), pair
    if name == "slider_crank":
        assert ic.at_infinity[:, ic.pairs.index("ground/piston")].all()


def test_two_input_page_second_slider_selects_the_second_input(driver, pages):
    mech = _open(driver, pages, "zrdpm_gear_contour", "?frame=45&grid=6")
    r = _solve_frames(mech, [45], grid_index=6)
    _assert_points(_read(driver, "[data-point]", "data-point"), r, 0, mech.model.length_scale)
    assert driver.find_element("id", "grid").get_attribute("max") == str(GRID_STEPS - 1)
    assert "lever1 = 90.00°" in driver.find_element("id", "readout").text
    # move the second slider with the keyboard: the pose follows the solver at the new value
    assert not driver.find_elements("css selector", "[data-ic]")
    driver.execute_script(
        "const g = document.getElementById('grid'); g.value = 7; g.dispatchEvent(new Event('input'));"
    )
    r = _solve_frames(mech, [45], grid_index=7)
    _assert_points(_read(driver, "[data-point]", "data-point"), r, 0, mech.model.length_scale)


def test_frames_that_do_not_assemble_hide_the_points_and_keep_the_angle(driver, pages):
    mech, _ = pages["double_rocker"]
    r = mech.solve(mech.sketch_inputs[0] + 2 * np.pi * np.arange(72) / 72)
    bad = int(np.flatnonzero(~r.closed)[0])
    good = int(np.flatnonzero(r.closed)[0])
    _open(driver, pages, "double_rocker", f"?frame={bad}")
    dom = _read(driver, "[data-point]", "data-point")
    assert all(e["hidden"] for e in dom.values())
    text = driver.find_element("id", "readout").text
    assert f"θ = {math.degrees(2 * np.pi * bad / 72):.2f}°" in text and "not assembled" in text
    _open(driver, pages, "double_rocker", f"?frame={good}")
    assert not any(e["hidden"] for e in _read(driver, "[data-point]", "data-point").values())


def test_play_advances_the_frame_and_pause_stops_it(driver, pages):
    from selenium.webdriver.support.ui import WebDriverWait

    _open(driver, pages, "fourbar", "?frame=5&play=1")
    WebDriverWait(driver, 20, poll_frequency=0.05).until(lambda d: _frame(d) != 5)
    driver.find_element("id", "play").click()  # pause
    k = _frame(driver)
    WebDriverWait(driver, 5).until(lambda d: "frame=" in d.execute_script("return location.search"))
    assert _frame(driver) == k
    # the play button starts it again
    driver.find_element("id", "play").click()
    WebDriverWait(driver, 20, poll_frequency=0.05).until(lambda d: _frame(d) != k)
    driver.find_element("id", "play").click()


def test_url_keeps_the_frame_so_a_view_can_be_shared(driver, pages):
    from selenium.webdriver.support.ui import WebDriverWait

    _open(driver, pages, "watt_sixbar", "?frame=10")
    driver.find_element("id", "step").click()
    WebDriverWait(driver, 10).until(lambda d: "frame=11" in d.execute_script("return location.search"))
    assert _frame(driver) == 11


def test_keyboard_space_plays_and_arrows_step(driver, pages):
    from selenium.webdriver.common.keys import Keys
    from selenium.webdriver.support.ui import WebDriverWait

    _open(driver, pages, "slider_crank", "?frame=20")
    body = driver.find_element("tag name", "body")
    body.send_keys(Keys.ARROW_RIGHT)
    body.send_keys(Keys.ARROW_RIGHT)
    assert _frame(driver) == 22
    body.send_keys(Keys.ARROW_LEFT)
    assert _frame(driver) == 21
    body.send_keys(Keys.SPACE)
    WebDriverWait(driver, 20, poll_frequency=0.05).until(lambda d: _frame(d) != 21)
    body.send_keys(Keys.SPACE)
    assert "play" in driver.find_element("id", "play").text


@pytest.mark.parametrize("name, pin", [("fourbar", "A"), ("geared_fivebar", "A")])
def test_dragging_the_input_pin_moves_the_mechanism_to_the_solver_pose(driver, pages, name, pin):
    from selenium.webdriver.common.action_chains import ActionChains

    mech = _open(driver, pages, name, "?frame=0")
    pivot = mech.model.links[mech.model.inputs[0].name].points[0]
    js = (
        "const r = document.querySelector(`[data-point='${arguments[0]}']`).getBoundingClientRect();"
        "return [r.left + r.width / 2, r.top + r.height / 2];"
    )
    px, py = driver.execute_script(js, pivot)
    ax, ay = driver.execute_script(js, pin)
    # turn the pin a quarter turn counter-clockwise about the pivot (screen y points down)
    dx, dy = ax - px, ay - py
    tx, ty = px + dy, py - dx
    pin_el = driver.find_element("css selector", f"[data-point='{pin}']")
    chain = ActionChains(driver).move_to_element(pin_el).click_and_hold()
    steps = 6
    cx, cy = ax, ay
    for s in range(1, steps + 1):
        # along the arc, so that the pointer stays on a circle about the pivot
        a = s * (math.pi / 2) / steps
        nx = px + dx * math.cos(a) + dy * math.sin(a)
        ny = py - dx * math.sin(a) + dy * math.cos(a)
        chain.move_by_offset(round(nx - cx), round(ny - cy))
        cx, cy = cx + round(nx - cx), cy + round(ny - cy)
    chain.release().perform()
    k = _frame(driver)
    assert abs(k - 90) <= 3, k
    assert (tx, ty) != (ax, ay)
    r = _solve_frames(mech, [k])
    _assert_points(_read(driver, "[data-point]", "data-point"), r, 0, mech.model.length_scale)


def test_toggles_show_arrows_along_the_velocity_paths_and_kennedy_lines(driver, pages):
    mech = _open(driver, pages, "fourbar", "?frame=30")
    r = _solve_frames(mech, [30])
    assert all(e["hidden"] for e in _read(driver, "[data-vel]", "data-vel").values())
    driver.find_element("id", "show-velocity").click()
    vel = _read(driver, "[data-vel]", "data-vel")
    scale = float(driver.find_element("id", "arrows").get_attribute("data-vscale"))
    for p in ("A", "B", "P"):
        e = vel[p]
        assert not e["hidden"]
        x1, y1, x2, y2 = (float(e[k]) for k in ("x1", "y1", "x2", "y2"))
        assert (x1, y1) == (pytest.approx(r.point[p][0, 0], rel=REL), pytest.approx(r.point[p][0, 1], rel=REL))
        assert x2 - x1 == pytest.approx(scale * r.velocity[p][0, 0], rel=1e-4, abs=1e-6)
        assert y2 - y1 == pytest.approx(scale * r.velocity[p][0, 1], rel=1e-4, abs=1e-6)
    assert "mm/rad" in driver.find_element("id", "legend").text
    paths = _read(driver, "[data-path]", "data-path")
    assert set(paths) == {"A", "B", "P"} and not any(e["hidden"] for e in paths.values())
    driver.find_element("id", "show-paths").click()
    assert all(e["hidden"] for e in _read(driver, "[data-path]", "data-path").values())
    driver.find_element("id", "show-centres").click()
    assert "instant centres" in driver.find_element("id", "legend").text
    assert driver.execute_script("return getComputedStyle(document.getElementById('centres')).display") != "none"
    driver.find_element("id", "show-kennedy").click()
    n = driver.execute_script("return document.querySelectorAll('#kennedy line').length")
    assert n == 1
    driver.execute_script(
        "const s = document.getElementById('kennedy-triple'); s.value = 'all'; s.dispatchEvent(new Event('change'));"
    )
    assert driver.execute_script("return document.querySelectorAll('#kennedy line').length") == 4


def test_plot_lists_quantities_and_its_cursor_follows_the_frame(driver, pages):
    _open(driver, pages, "watt_sixbar", "?frame=0")
    options = driver.execute_script("return Array.from(document.querySelectorAll('#quantity option'), o => o.value)")
    assert "phi:output" in options and "w:coupler" in options and "v:D" in options
    x0 = float(driver.find_element("css selector", "#plot .cursor").get_attribute("x1"))
    driver.find_element("id", "step").click()
    x1 = float(driver.find_element("css selector", "#plot .cursor").get_attribute("x1"))
    assert x1 > x0
    assert driver.execute_script("return document.querySelector('#plot .curve').getAttribute('d').length") > 100


def test_csv_export_holds_the_frame_data(driver, pages):
    mech = _open(driver, pages, "slider_crank", "?frame=77")
    text = driver.execute_async_script(
        """
        const done = arguments[0];
        HTMLAnchorElement.prototype.click = function () { fetch(this.href).then(r => r.text()).then(done); };
        document.getElementById('export-csv').click();
        """
    )
    rows = dict(line.split(",", 2)[:2] for line in text.splitlines()[1:])
    r = _solve_frames(mech, [77])
    assert float(rows["B x"]) == pytest.approx(r.point["B"][0, 0], rel=REL)
    assert float(rows["input crank"]) == pytest.approx(77.0)
    svg = driver.execute_async_script(
        """
        const done = arguments[0];
        HTMLAnchorElement.prototype.click = function () { fetch(this.href).then(r => r.text()).then(done); };
        document.getElementById('export-svg').click();
        """
    )
    assert svg.startswith("<svg") and 'data-point="B"' in svg


@pytest.mark.parametrize("name", NAMES)
def test_screenshot_is_not_blank(driver, pages, name):
    from PIL import Image

    _open(driver, pages, name, "?frame=30")
    img = Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("L")
    a = np.asarray(img, dtype=float)
    assert a.std() > 10
    assert (a < 200).mean() > 0.01  # ink on at least 1 % of the window
