"""The viewer page in a real browser (headless Chromium through selenium): the DOM against the solver.

One browser for the module (``tests/plotting/_browser.py``).  Without chromium/chromedriver the module
is skipped locally and FAILS when the environment variable CI is set (a browser test never silently
skips in CI).
"""

from __future__ import annotations

import io
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from gearlever.mechanism import Mechanism
from gearlever.mechanism.centres import instant_centres
from gearlever.mechanism.limits import input_limits
from gearlever.plotting.viewer import GRID_STEPS, viewer_html
from tests.plotting import _browser

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
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


# Free text that would break the page if embedded raw, and the oddest names a model file accepts.
HOSTILE = {
    "mechanism": {"name": '"<!--<script> </script><b>x</b> &amp; \u2028', "units": "µm", "module": 1.0},
    "points": {"Ø.2": [0, 0], "A-1.x": [10, 0], "B-2": [28, 20], "O.4": [40, 0]},
    "links": {
        "ground": ["Ø.2", "O.4"],
        "κρανκ-1": ["Ø.2", "A-1.x"],
        "cöupler": ["A-1.x", "B-2"],
        "名前.r": ["O.4", "B-2"],
    },
    "gears": {
        "ζ-gear.1": {"link": "κρανκ-1", "centre": "Ø.2", "teeth": 12},
        "fixé.0": {"link": "ground", "centre": "O.4", "teeth": 30, "internal": True},
    },
    "inputs": [{"link": "κρανκ-1"}],
}


driver = _browser.driver  # fixture


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
    for name in ("planetary", "ferguson"):
        mech = Mechanism.load(EXAMPLES / f"{name}.toml")
        path = folder / f"{name}.html"
        path.write_text(viewer_html(mech, frames=N), encoding="utf-8")
        out[name] = (mech, path)
    big = tomllib.loads((EXAMPLES / "fourbar.toml").read_text(encoding="utf-8"))
    big["points"] = {p: [1000 * v for v in xy] for p, xy in big["points"].items()}
    for name, mech in (("fourbar_big", Mechanism.from_dict(big)), ("hostile", Mechanism.from_dict(HOSTILE))):
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


def test_a_rocking_input_page_sweeps_one_oscillation_and_every_frame_assembles(driver, pages):
    """The double rocker's input cannot turn fully: the page sweeps one oscillation between its limits
    (issue 34), so every frame assembles and shows its points (no frame of NaN)."""
    mech, _ = pages["double_rocker"]
    lim = input_limits(mech)
    assert not lim.full_turn
    for frame in (0, 17, 36, 53):
        _open(driver, pages, "double_rocker", f"?frame={frame}")
        assert not any(e["hidden"] for e in _read(driver, "[data-point]", "data-point").values())
        assert "not assembled" not in driver.find_element("id", "readout").text


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


_DOWNLOAD = """
const done = arguments[arguments.length - 1];
HTMLAnchorElement.prototype.click = function () { fetch(this.href).then(r => r.text()).then(done); };
document.getElementById(arguments[0]).click();
"""


def _csv(driver):
    import csv

    rows = list(csv.reader(io.StringIO(driver.execute_async_script(_DOWNLOAD, "export-csv"))))
    return rows[0], rows[1:]


def test_csv_export_holds_the_whole_cycle_with_empty_cells_at_infinity(driver, pages):
    mech = _open(driver, pages, "slider_crank", "?frame=77")
    head, rows = _csv(driver)
    assert len(rows) == N and all(len(r) == len(head) for r in rows)
    col = {name: i for i, name in enumerate(head)}
    r = _solve_frames(mech, list(range(N)))
    ic = r.centres()
    for k in (0, 77, 200, 359):
        row = rows[k]
        assert int(row[col["frame"]]) == k and float(row[col["input_crank_deg"]]) == pytest.approx(k)
        for p in ("A", "B"):
            assert float(row[col[f"{p}_x_mm"]]) == pytest.approx(r.point[p][k, 0], rel=REL, abs=1e-9)
            assert float(row[col[f"{p}_y_mm"]]) == pytest.approx(r.point[p][k, 1], rel=REL, abs=1e-9)
            assert float(row[col[f"v_{p}_x_mm_per_crank"]]) == pytest.approx(r.velocity[p][k, 0], rel=REL, abs=1e-9)
        # the slider's centre is at infinity at every frame: empty, as analyze --centres documents, never "nan"
        assert row[col["ic_ground/piston_x_mm"]] == "" and row[col["ic_ground/piston_y_mm"]] == ""
        j = ic.pairs.index("crank/rod")
        assert float(row[col["ic_crank/rod_x_mm"]]) == pytest.approx(ic.xy[k, j, 0], rel=REL, abs=1e-9)
    assert not any(cell.lower() in ("nan", "null", "undefined") for row in rows for cell in row)
    svg = driver.execute_async_script(_DOWNLOAD, "export-svg")
    assert svg.startswith("<svg") and 'data-point="B"' in svg


def test_csv_export_of_a_rocking_input_has_every_frame_closed(driver, pages):
    """One oscillation of the double rocker: every exported row is closed, with its points and its input."""
    mech = _open(driver, pages, "double_rocker")
    head, rows = _csv(driver)
    col = {name: i for i, name in enumerate(head)}
    assert rows and all(int(r[col["closed"]]) == 1 for r in rows)
    assert all(r[col["B_x_mm"]] != "" and r[col["input_crank_deg"]] != "" for r in rows)
    lim = input_limits(mech)
    angles = [float(r[col["input_crank_deg"]]) for r in rows]
    assert math.degrees(lim.lower) - 1e-6 <= min(angles) and max(angles) <= math.degrees(lim.upper) + 1e-6


def test_number_formatter_keeps_the_zeros_of_whole_numbers(driver, pages):
    _open(driver, pages, "fourbar")
    table = [
        (1000, 4, "1000"),
        (120000, None, "120000"),
        (100, 4, "100"),
        (10, None, "10"),
        (0, None, "0"),
        (-0.0, None, "0"),
        (1.5, None, "1.5"),
        (-2.5, 4, "-2.5"),
        (0.1 + 0.2, None, "0.3"),
        (12.5, 4, "12.5"),
        (6.854, 4, "6.854"),
        (1e-7, None, "1e-7"),
        (1.5e-7, None, "1.5e-7"),
        (123456789, None, "1.23457e+8"),
        (1.23456789e10, 4, "1.235e+10"),
        (None, None, "–"),
    ]
    got = driver.execute_script(
        "return arguments[0].map(([v, d]) => window.gearlever.fmt(v, d === null ? undefined : d));",
        [[v, d] for v, d, _ in table],
    )
    assert got == [want for _, _, want in table]
    ticks = [(1000, 250, "1000"), (2.5, 2.5, "2.5"), (120000, 20000, "120000"), (0.3, 0.1, "0.3"), (-50, 50, "-50")]
    got = driver.execute_script(
        "return arguments[0].map(([v, s]) => window.gearlever.tickLabel(v, s));", [[v, st] for v, st, _ in ticks]
    )
    assert got == [want for _, _, want in ticks]


def test_plot_ticks_and_hover_show_large_values_in_full(driver, pages):
    """A four-bar 1000 times larger: x of A runs over +-10000 mm; every tick and the hover read as numbers."""
    mech = _open(driver, pages, "fourbar_big")
    driver.execute_script(
        "const s = document.getElementById('quantity'); s.value = 'x:A'; s.dispatchEvent(new Event('change'));"
    )
    ticks = driver.execute_script(
        "return Array.from(document.querySelectorAll('#plot text.ytick'), t => [t.textContent, +t.dataset.value]);"
    )
    assert len(ticks) >= 3
    for text, value in ticks:
        assert float(text) == pytest.approx(value, abs=1e-9 * 10000), ticks
    assert {t for t, _ in ticks} >= {"-10000", "0", "10000"} or {t for t, _ in ticks} >= {"-5000", "0", "5000"}
    xt = driver.execute_script("return Array.from(document.querySelectorAll('#plot text.xtick'), t => t.textContent);")
    assert xt[:4] == ["0", "50", "100", "150"]
    # hover at frame 0: x of A = 10000 mm exactly
    driver.execute_script(
        """
        const p = document.getElementById('plot'), r = p.getBoundingClientRect();
        p.dispatchEvent(new MouseEvent('mousemove', {clientX: r.left + 62, clientY: r.top + 40, bubbles: true}));
        """
    )
    text = driver.find_element("css selector", "#plot .hover-text").text
    assert text.endswith(": 10000"), text
    assert mech.model.points["A"][0] == pytest.approx(10000)


def test_hostile_names_load_and_display_literally(driver, pages):
    _open(driver, pages, "hostile")
    title = HOSTILE["mechanism"]["name"]
    assert driver.execute_script("return document.querySelector('h1').textContent") == title
    assert driver.execute_script("return document.title") == title + " - gearlever viewer"
    # nothing was injected: the page's own two scripts, no element from the names
    assert driver.execute_script("return document.scripts.length") == 2
    assert driver.execute_script("return document.querySelectorAll('b, i, img').length") == 0
    labels = driver.execute_script("return Array.from(document.querySelectorAll('#labels text'), t => t.textContent)")
    for name in ("κρανκ-1", "名前.r", "Ø.2", "A-1.x", "ζ-gear.1: z = 12", "fixé.0: z = 30 (internal)"):
        assert name in labels
    gears = driver.execute_script("return Array.from(document.querySelectorAll('[data-gear]'), e => e.dataset.gear)")
    assert sorted(gears) == sorted(["ζ-gear.1", "fixé.0"])
    options = driver.execute_script("return Array.from(document.querySelectorAll('#quantity option'), o => o.text)")
    assert "angle of 名前.r (deg)" in options and "x of B-2 (µm)" in options
    assert "κρανκ-1: θ = " in driver.find_element("id", "readout").text
    assert "input: κρανκ-1" in driver.find_element("id", "legend").text
    head, _ = _csv(driver)
    assert "Ø.2_x_µm" in head and "input_κρανκ-1_deg" in head


@pytest.mark.parametrize(
    "name, gear, centre, radius", [("planetary", "ring", "O", 60.0), ("ferguson", "fixed", "O", None)]
)
def test_ground_gears_are_drawn(driver, pages, name, gear, centre, radius):
    mech = _open(driver, pages, name, "?frame=17")
    r = mech.model.pitch_radius(gear)
    if radius is not None:
        assert r == pytest.approx(radius)
    e = driver.execute_script(
        "const e = document.querySelector(`[data-gear='${arguments[0]}']`);"
        "return e && [e.getAttribute('cx'), e.getAttribute('cy'), e.getAttribute('r'),"
        " e.getBoundingClientRect().width];",
        gear,
    )
    assert e is not None, f"gear {gear} not drawn"
    x, y = mech.model.points[centre]
    assert float(e[0]) == pytest.approx(x, abs=1e-9) and float(e[1]) == pytest.approx(y, abs=1e-9)
    assert float(e[2]) == pytest.approx(r, rel=1e-6) and e[3] > 50  # drawn, and large on the screen
    drawn = driver.execute_script("return Array.from(document.querySelectorAll('[data-gear]'), e => e.dataset.gear)")
    assert set(drawn) == {g for g in mech.model.gears if mech.model.pitch_radius(g) is not None}


_CENTRE = (
    "const r = document.querySelector(arguments[0]).getBoundingClientRect();"
    "return [r.left + r.width / 2, r.top + r.height / 2];"
)


def _drag(driver, start, pivot, turn_deg, lead=None, steps=12):
    """Press at ``start`` (screen px), optionally move to ``lead`` first, then turn the pointer ``turn_deg``
    counter-clockwise about ``pivot`` along an arc, and release."""
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.actions.action_builder import ActionBuilder

    px, py = pivot
    path = [start]
    if lead is not None:
        path.append(lead)
    sx, sy = path[-1]
    dx, dy = sx - px, sy - py
    for s in range(1, steps + 1):
        a = math.radians(turn_deg) * s / steps
        path.append((px + dx * math.cos(a) + dy * math.sin(a), py - dx * math.sin(a) + dy * math.cos(a)))
    chain = ActionChains(driver, duration=10)
    builder = ActionBuilder(driver, duration=10)
    builder.pointer_action.move_to_location(round(start[0]), round(start[1]))
    builder.pointer_action.pointer_down()
    for x, y in path[1:]:
        builder.pointer_action.move_to_location(round(x), round(y))
    builder.pointer_action.pointer_up()
    builder.perform()
    del chain


def test_dragging_from_the_pivot_turns_the_crank_by_the_pointer_turn(driver, pages):
    """Grab at the pivot itself (where the old page jumped from 0 to 241 deg), move out along 45 deg, then
    turn the pointer 45 deg about the pivot: the crank turns 45 deg (frame 45 of 360), no jump."""
    mech = _open(driver, pages, "fourbar", "?frame=0")
    px, py = driver.execute_script(_CENTRE, "[data-point='O2']")
    lead = (px + 80 * math.cos(math.radians(45)), py - 80 * math.sin(math.radians(45)))
    _drag(driver, (px, py), (px, py), 45, lead=lead)
    k = _frame(driver)
    assert abs(k - 45) <= 2, k
    r = _solve_frames(mech, [k])
    _assert_points(_read(driver, "[data-point]", "data-point"), r, 0, mech.model.length_scale)


def test_dragging_relative_from_the_link_body_and_from_the_dashed_ring(driver, pages):
    _open(driver, pages, "fourbar", "?frame=100")
    px, py = driver.execute_script(_CENTRE, "[data-point='O2']")
    ax, ay = driver.execute_script(_CENTRE, "[data-point='A']")
    # on the crank's body, a quarter of the way out: no jump at the press, then -30 deg
    start = (px + 0.3 * (ax - px), py + 0.3 * (ay - py))
    hit = driver.execute_script(
        "return document.elementFromPoint(arguments[0], arguments[1]).closest('.grab') !== null", *start
    )
    assert hit
    _drag(driver, start, (px, py), -30)
    assert abs(_frame(driver) - 70) <= 2, _frame(driver)
    # on the dashed ring, opposite the crank
    ring_r = driver.execute_script("return document.querySelector('.input-hit').getBoundingClientRect().width / 2")
    ux, uy = (px - ax) / math.hypot(ax - px, ay - py), (py - ay) / math.hypot(ax - px, ay - py)
    start = (px + ring_r * ux, py + ring_r * uy)
    hit = driver.execute_script(
        "return document.elementFromPoint(arguments[0], arguments[1]).classList.contains('input-hit')", *start
    )
    assert hit
    _drag(driver, start, (px, py), 60)
    assert abs(_frame(driver) - 130) <= 2, _frame(driver)


def test_dragging_the_input_gear_turns_it(driver, pages):
    mech = _open(driver, pages, "planetary", "?frame=0")
    px, py = driver.execute_script(_CENTRE, "[data-point='O']")
    s = driver.execute_script(
        "const e = document.querySelector('[data-gear=sun]').getBoundingClientRect(); return e.width / 2;"
    )
    # inside the sun's pitch circle, left of the arm's triangle (its side P2 P3 is at x = -21 mm of r = 24 mm)
    start = (px - 0.94 * s, py)
    on = driver.execute_script(
        "const e = document.elementFromPoint(arguments[0], arguments[1]); return e.dataset.gear || e.tagName;", *start
    )
    assert on == "sun"
    _drag(driver, start, (px, py), 30)
    k = _frame(driver)
    assert abs(k - 30) <= 2, k
    r = _solve_frames(mech, [k])
    _assert_points(_read(driver, "[data-point]", "data-point"), r, 0, mech.model.length_scale)


_LAYOUT = """
const v = document.getElementById("view").getBoundingClientRect();
const W = window.innerWidth, H = window.innerHeight;
const vis = (e) => e.checkVisibility({contentVisibilityAuto: true, visibilityProperty: true});
const boxes = Array.from(document.querySelectorAll("#labels text")).filter(vis).map((t) => {
  const r = t.getBoundingClientRect(); return {t: t.textContent, l: r.left, r: r.right, top: r.top, b: r.bottom}; });
const outside = boxes.filter((b) => b.l < Math.max(0, v.left) - 0.5 || b.r > Math.min(W, v.right) + 0.5
  || b.top < v.top - 0.5 || b.b > v.bottom + 0.5).map((b) => b.t);
const overlaps = [];
for (let i = 0; i < boxes.length; i++) for (let j = i + 1; j < boxes.length; j++) {
  const a = boxes[i], b = boxes[j];
  const x = Math.min(a.r, b.r) - Math.max(a.l, b.l), y = Math.min(a.b, b.b) - Math.max(a.top, b.top);
  if (x > 1 && y > 1) overlaps.push(a.t + "|" + b.t);
}
const controls = document.querySelectorAll("#toolbar button, #toolbar select, #toolbar input, #toolbar summary");
const centres = Array.from(controls)
  .filter(vis).map((e) => { const r = e.getBoundingClientRect(); return r.top + r.height / 2; }).sort((a, b) => a - b);
let rows = 0, last = -1e9;
centres.forEach((c) => { if (c - last > 12) rows++; last = c; });
return {height: v.height, H: H, W: W, rows: rows, labels: boxes.length, outside: outside, overlaps: overlaps,
  plotBottom: document.getElementById("plot").getBoundingClientRect().bottom,
  scrollW: document.documentElement.scrollWidth};
"""


@pytest.fixture
def window(driver):
    """Set the viewport to (width, height) CSS pixels for one test; back to 1000 x 800 after it."""

    def size(w, h):
        driver.execute_cdp_cmd(
            "Emulation.setDeviceMetricsOverride", {"width": w, "height": h, "deviceScaleFactor": 1, "mobile": w < 600}
        )

    yield size
    driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


@pytest.mark.parametrize("w, h, fraction", [(1000, 800, 0.5), (390, 844, 0.45)])
@pytest.mark.parametrize(
    "name, query",
    [("whitworth", "?frame=40"), ("whitworth", "?frame=250"), ("watt_sixbar", ""), ("zrdpm_gear_contour", "")]
    + [("planetary", "?frame=20"), ("fourbar", "?frame=300")],
)
def test_layout_fits_the_window_with_labels_inside_and_apart(driver, pages, window, w, h, fraction, name, query):
    window(w, h)
    _open(driver, pages, name, query)
    m = driver.execute_script(_LAYOUT)
    assert m["W"] == w and m["H"] == h
    assert m["height"] >= fraction * h, m  # the drawing takes the height left by the controls and the plot
    assert m["plotBottom"] <= h + 0.5, m  # the plot is above the fold
    assert m["rows"] <= 2, m  # a compact toolbar
    assert m["scrollW"] <= w, m  # nothing sticks out sideways
    assert m["labels"] >= 4 and not m["outside"], m
    assert not m["overlaps"], m


def test_coincident_instant_centres_fan_out(driver, pages, window):
    """With the centres shown, labels that share an anchor (a pin is two centres' place) do not stack."""
    for w, h in ((1000, 800), (390, 844)):
        window(w, h)
        _open(driver, pages, "whitworth", "?frame=40")
        driver.find_element("id", "options-button").click() if w < 600 else None
        driver.find_element("id", "show-centres").click()
        m = driver.execute_script(_LAYOUT)
        assert m["labels"] >= 15 and not m["outside"], m
        assert not m["overlaps"], m


def test_phone_options_menu_opens_and_its_check_boxes_work(driver, pages, window):
    window(390, 844)
    _open(driver, pages, "fourbar", "?frame=30")
    assert not driver.find_element("id", "show-velocity").is_displayed()
    driver.find_element("id", "options-button").click()
    driver.find_element("id", "show-velocity").click()
    assert not _read(driver, "[data-vel]", "data-vel")["A"]["hidden"]


@pytest.mark.parametrize("name", NAMES)
def test_screenshot_is_not_blank(driver, pages, name):
    from PIL import Image

    _open(driver, pages, name, "?frame=30")
    img = Image.open(io.BytesIO(driver.get_screenshot_as_png())).convert("L")
    a = np.asarray(img, dtype=float)
    assert a.std() > 10
    assert (a < 200).mean() > 0.01  # ink on at least 1 % of the window
