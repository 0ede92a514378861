"""The cam page in a real browser (headless Chromium through selenium): the DOM against the cam module.

One browser for the module (``tests/plotting/_browser.py``).  Without chromium/chromedriver the
module is skipped locally and FAILS when the environment variable CI is set.  With GEARLEVER_SCREENSHOTS
set to a folder, the screenshot test also writes ``viewer_cam.png`` there (the guide's picture:
``GEARLEVER_SCREENSHOTS=docs/_static``).
"""

from __future__ import annotations

import io
import math
import os
import re
from pathlib import Path

import numpy as np
import pytest

from gearlever.plotting.cam_viewer import cam_viewer_html
from tests.plotting import _browser
from tests.plotting._cam_designs import designs

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
N = 360
DESIGNS = {k: v for k, v in designs().items() if k != "offset-roller"}
HOSTILE = '"</script><!--<script>window.pwned=1</script>&amp; \u2028 ü'


driver = _browser.driver  # fixture


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cam-pages")
    out = {}
    for name, cam in DESIGNS.items():
        path = folder / f"{name}.html"
        path.write_text(cam_viewer_html(cam, frames=N, name=name), encoding="utf-8")
        out[name] = (cam, path)
    path = folder / "hostile.html"
    path.write_text(cam_viewer_html(DESIGNS["translating-flat"], frames=N, name=HOSTILE), encoding="utf-8")
    out["hostile"] = (DESIGNS["translating-flat"], path)
    return out


def _open(driver, pages, name, query=""):
    from selenium.webdriver.support.ui import WebDriverWait

    cam, path = pages[name]
    driver.get_log("browser")  # drop what earlier pages logged
    driver.get(path.as_uri() + query)
    WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready") == "1")
    return cam


def _frame(driver) -> int:
    return int(driver.find_element("id", "frame").get_attribute("value"))


def _cam_angle(driver) -> float:
    """The cam's rotation (deg) read from the transform of the data-cam group."""
    t = driver.execute_script("return document.querySelector('[data-cam]').getAttribute('transform')")
    return float(re.fullmatch(r"rotate\(([-+0-9.e]+)\)", t).group(1))


def _attrs(driver, selector, names):
    return driver.execute_script(
        "const e = document.querySelector(arguments[0]); return arguments[1].map((n) => e.getAttribute(n));",
        selector,
        names,
    )


def _severe(driver):
    return [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_page_loads_without_console_errors_and_draws_the_cam_module_pose(driver, pages, name):
    for k in (0, 77, 130, 245):
        cam = _open(driver, pages, name, f"?frame={k}")
        assert _severe(driver) == []
        assert _frame(driver) == k
        i = k * cam.theta.size // N
        assert _cam_angle(driver) == pytest.approx(math.degrees(cam.theta[i]), abs=1e-6)
        cx, cy = (float(v) for v in _attrs(driver, "[data-contact]", ["cx", "cy"]))
        np.testing.assert_allclose([cx, cy], cam.contact[i], atol=1e-7 * cam.base_radius)
        if "roller" in name:
            rx, ry, r = (float(v) for v in _attrs(driver, "[data-roller]", ["cx", "cy", "r"]))
            c, s = math.cos(cam.theta[i]), math.sin(cam.theta[i])
            px, py = cam.pitch[i]
            np.testing.assert_allclose([rx, ry], [c * px - s * py, s * px + c * py], atol=1e-7 * cam.base_radius)
            assert r == pytest.approx(cam.roller_radius)
        else:
            x0, y0, x1, y1 = (float(v) for v in _attrs(driver, "[data-face]", ["x1", "y1", "x2", "y2"]))
            # the contact lies on the face line
            u = np.array([x1 - x0, y1 - y0])
            w = cam.contact[i] - [x0, y0]
            assert abs(u[0] * w[1] - u[1] * w[0]) / np.hypot(*u) < 1e-6 * cam.base_radius
        text = driver.find_element("id", "readout").text
        assert f"θ = {math.degrees(cam.theta[i]):.2f}°" in text and "pressure angle" in text
        # the plot's cursor marks the frame
        curve = driver.execute_script("return document.querySelector('[data-curve]').getAttribute('data-curve')")
        assert curve == "s"


def test_play_turns_the_cam_counterclockwise_and_pause_stops_it(driver, pages):
    from selenium.webdriver.support.ui import WebDriverWait

    _open(driver, pages, "translating-roller", "?frame=5")
    a0 = _cam_angle(driver)
    ry0 = float(_attrs(driver, "[data-roller]", ["cy"])[0])
    driver.find_element("id", "play").click()
    WebDriverWait(driver, 20, poll_frequency=0.05).until(lambda d: _frame(d) > 70)
    driver.find_element("id", "play").click()  # pause
    k = _frame(driver)
    assert _cam_angle(driver) > a0  # counterclockwise
    assert float(_attrs(driver, "[data-roller]", ["cy"])[0]) > ry0  # the follower rises after the dwell
    WebDriverWait(driver, 5).until(lambda d: "frame=" in d.execute_script("return location.search"))
    assert _frame(driver) == k
    assert _severe(driver) == []


def test_step_buttons_keys_and_slider_move_the_frame(driver, pages):
    from selenium.webdriver.common.keys import Keys

    _open(driver, pages, "oscillating-roller", "?frame=10")
    driver.find_element("id", "step").click()
    assert _frame(driver) == 11
    driver.find_element("id", "step-back").click()
    driver.find_element("id", "step-back").click()
    assert _frame(driver) == 9
    driver.find_element("tag name", "body").send_keys(Keys.ARROW_RIGHT)
    assert _frame(driver) == 10
    driver.execute_script(
        "const f = document.getElementById('frame'); f.value = 200; f.dispatchEvent(new Event('input'));"
    )
    assert _frame(driver) == 200
    assert _cam_angle(driver) == pytest.approx(200.0, abs=1e-6)


def _drag(driver, pivot, radius, start_deg, turn_deg, steps=12):
    """Press on the cam at ``radius`` px from its centre, turn the pointer ``turn_deg`` counterclockwise."""
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    px, py = pivot
    pts = []
    for s in range(steps + 1):
        a = math.radians(start_deg + turn_deg * s / steps)
        pts.append((px + radius * math.cos(a), py - radius * math.sin(a)))
    builder = ActionBuilder(driver, duration=10)
    builder.pointer_action.move_to_location(round(pts[0][0]), round(pts[0][1]))
    builder.pointer_action.pointer_down()
    for x, y in pts[1:]:
        builder.pointer_action.move_to_location(round(x), round(y))
    builder.pointer_action.pointer_up()
    builder.perform()


@pytest.mark.parametrize(("name", "turn"), [("translating-flat", 60), ("oscillating-flat", -45)])
def test_dragging_the_cam_turns_it_by_the_pointer_turn(driver, pages, name, turn):
    cam = _open(driver, pages, name, "?frame=100")
    pivot = driver.execute_script(
        "const r = document.querySelector('[data-hub]').getBoundingClientRect();"
        "return [r.left + r.width / 2, r.top + r.height / 2];"
    )
    _drag(driver, pivot, 40, 200, turn)
    k = _frame(driver)
    assert abs(k - (100 + turn)) <= 2, k
    assert _cam_angle(driver) == pytest.approx(math.degrees(cam.theta[k * cam.theta.size // N]), abs=1e-6)
    assert _severe(driver) == []


def test_plot_quantity_choice_and_click_sets_the_frame(driver, pages):
    from selenium.webdriver.support.ui import Select

    _open(driver, pages, "translating-roller", "?frame=0")
    Select(driver.find_element("id", "quantity")).select_by_value("phi")
    assert driver.execute_script("return document.querySelector('[data-curve]').getAttribute('data-curve')") == "phi"
    assert _frame(driver) == 0
    cursor0 = float(_attrs(driver, "[data-cursor]", ["x1"])[0])
    driver.find_element("id", "step").click()
    assert float(_attrs(driver, "[data-cursor]", ["x1"])[0]) > cursor0


def test_hostile_name_is_shown_literally_and_runs_nothing(driver, pages):
    _open(driver, pages, "hostile")
    assert _severe(driver) == []
    assert driver.execute_script("return window.pwned === undefined")
    assert driver.execute_script("return document.querySelector('h1').textContent") == HOSTILE
    assert driver.execute_script("return document.title").startswith('"</script><!--<script>window.pwned=1')
    assert driver.execute_script("return window.gearlever.data.name") == HOSTILE
    # the console check sees an error when there is one
    driver.execute_script("console.error('x')")
    assert len(_severe(driver)) == 1


@pytest.mark.parametrize("name", sorted(DESIGNS))
def test_screenshot_is_not_blank(driver, pages, name, tmp_path):
    from PIL import Image

    _open(driver, pages, name, "?frame=100")
    png = driver.get_screenshot_as_png()
    a = np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=float)
    assert a.std() > 10
    assert (a < 200).mean() > 0.01
    folder = os.environ.get("GEARLEVER_SCREENSHOTS")
    if folder and name == "translating-roller":
        Path(folder, "viewer_cam.png").write_bytes(png)
