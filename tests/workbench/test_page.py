"""The workbench page in headless Chromium against the real server: the user's journeys with real pointer events.

Each test starts and stops its own server on a free loopback port (``tests/workbench/_server.py``); the
module shares one browser.  Every test runs ``guarded`` (most through the ``page`` fixture of
``tests/workbench/conftest.py``, the page opened at the desktop size): it fails on any console error and on
any request to a host other than the bench's own (those requests also go to a dead proxy, so nothing leaves
the machine).
The page only draws what ``POST /api/solve`` answers; the checks compare what it shows with the server's
frames and with gearlever's own solver.

Screenshots go to a temporary folder and are checked not to be blank; with ``GEARLEVER_SCREENSHOTS=DIR`` they
are also written to ``DIR/workbench_*.png`` (the guide's pictures: ``GEARLEVER_SCREENSHOTS=docs/_static``).
"""

from __future__ import annotations

import io
import math
import os
import time
from pathlib import Path

import numpy as np
import pytest
from selenium.webdriver.common.actions import interaction
from selenium.webdriver.common.actions.action_builder import ActionBuilder
from selenium.webdriver.common.actions.pointer_input import PointerInput
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select

from gearlever.data import example_path
from gearlever.mechanism import Mechanism
from tests.workbench._server import guarded, open_bench, wait_for

# ---------------------------------------------------------------- helpers


def js(d, script, *args):
    return d.execute_script(script, *args)


def call(d, expr, *args):
    """Await a promise-valued expression of the page (``workbench.load(arguments[0])``...)."""
    return d.execute_async_script(
        "const cb = arguments[arguments.length - 1];"
        f"Promise.resolve().then(() => {expr}).then((v) => cb({{ok: v === undefined ? null : v}}),"
        " (e) => cb({error: String(e && e.message || e)}));",
        *args,
    )


def settled(d, timeout=30.0):
    """Wait until no dump/solve round trip is in flight; the page's state()."""
    wait_for(d, "const s = workbench.state(); return !s.pending", timeout)
    return js(d, "return workbench.state()")


def screen(d, x, y):
    return js(d, "return workbench.toScreen(arguments[0], arguments[1])", x, y)


def mouse(d):
    return ActionBuilder(d, mouse=PointerInput(interaction.POINTER_MOUSE, "mouse"))


def click_at(d, x, y):
    """A real mouse click at the viewport pixel (x, y)."""
    a = mouse(d)
    a.pointer_action.move_to_location(round(x), round(y))
    a.pointer_action.pointer_down()
    a.pointer_action.pointer_up()
    a.perform()


def click_model(d, x, y, dx=0, dy=0):
    px, py = screen(d, x, y)
    click_at(d, px + dx, py + dy)


def drag(d, points, steps=6):
    """Press at the first viewport pixel, move through the others (``steps`` moves between two), release."""
    a = mouse(d)
    a.pointer_action.move_to_location(round(points[0][0]), round(points[0][1]))
    a.pointer_action.pointer_down()
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        for k in range(1, steps + 1):
            t = k / steps
            a.pointer_action.move_to_location(round(x0 + t * (x1 - x0)), round(y0 + t * (y1 - y0)))
    a.pointer_action.pointer_up()
    a.perform()


def tool(d, name):
    d.find_element(By.CSS_SELECTOR, f'[data-tool="{name}"]').click()


def action(d, name):
    d.find_element(By.CSS_SELECTOR, f'[data-action="{name}"]').click()


def joint_centre(d, name):
    """Where the page drew the joint's circle (client pixels)."""
    return js(
        d,
        "const c = [...document.querySelectorAll('[data-joint]')].find((g) => g.dataset.joint === arguments[0])"
        ".querySelector('circle'); const r = c.getBoundingClientRect();"
        "return [r.left + r.width / 2, r.top + r.height / 2];",
        name,
    )


def not_blank(png: bytes, min_colours: int = 12) -> None:
    from PIL import Image

    im = Image.open(io.BytesIO(png)).convert("RGB")
    colours = im.getcolors(maxcolors=1 << 20)
    assert colours is not None and len(colours) >= min_colours, "the screenshot is blank"
    assert im.size[0] > 300 and im.size[1] > 300


def shot(d, tmp_path, name):
    png = d.get_screenshot_as_png()
    not_blank(png)
    (tmp_path / f"workbench_{name}.png").write_bytes(png)
    out = os.environ.get("GEARLEVER_SCREENSHOTS")
    if out:
        Path(out).mkdir(parents=True, exist_ok=True)
        (Path(out) / f"workbench_{name}.png").write_bytes(png)
    return png


FOURBAR = example_path("fourbar.toml").read_text(encoding="utf-8")

# A Grashof crank-rocker drawn by hand: ground 40, crank 10, coupler 44.7, rocker 30 (s + l = 54.7 < p + q = 70).
O1, O2, A, B = (0.0, 0.0), (40.0, 0.0), (0.0, 10.0), (40.0, 30.0)


def draw_fourbar(d):
    """Ground, ground, pin, pin, three links by the link tool, the input by the input tool: all by mouse."""
    tool(d, "ground")
    click_model(d, *O1)
    click_model(d, *O2)
    tool(d, "pin")
    click_model(d, *A)
    click_model(d, *B)
    tool(d, "link")
    body = d.find_element(By.TAG_NAME, "body")
    # a click within 8 px of a joint takes that joint (offsets of 5 px)
    for a, b in ((O1, A), (A, B), (O2, B)):
        click_model(d, *a, dx=5)
        click_model(d, *b, dy=-5)
        body.send_keys(Keys.ENTER)
    tool(d, "input")
    click_model(d, (O1[0] + A[0]) / 2, (O1[1] + A[1]) / 2)
    wait_for(d, "return workbench.state().frames === 360 && !workbench.state().pending", 30)


def run_curve_job(d, seconds):
    """Open the synthesis panel, start a curve synthesis of the drawn curve for ``seconds``; wait until it runs."""
    action(d, "synthesize")
    Select(d.find_element(By.ID, "synth-kind")).select_by_value("curve")
    time_box = d.find_element(By.ID, "synth-time")
    time_box.clear()
    time_box.send_keys(str(seconds))
    d.find_element(By.ID, "synth-run").click()
    wait_for(d, "const j = workbench.state().job; return j && j.state === 'running'", 10)


# ---------------------------------------------------------------- journeys


def test_empty_bench_says_what_to_do_and_draws_a_grashof_fourbar(page, bench, tmp_path):
    d = page
    empty = d.find_element(By.ID, "empty")
    assert empty.is_displayed() and "ground" in empty.text and "examples" in empty.text
    assert "Empty bench" in d.find_element(By.ID, "status").text
    draw_fourbar(d)
    s = settled(d)
    assert s["dof"] == 1 and s["inputs"] == ["link1"]
    f = js(d, "return workbench.frames()")
    assert f["frames"] == 360 and all(f["closed"]), "a Grashof crank-rocker turns fully"
    assert not empty.is_displayed()
    names = sorted(js(d, "return [...document.querySelectorAll('[data-joint]')].map((g) => g.dataset.joint)"))
    assert names == ["A", "B", "O1", "O2"], "the clicks near joints took them: no extra point"
    # the model file the page wrote reads back in gearlever with the drawn geometry
    path = tmp_path / "drawn.toml"
    path.write_text(js(d, "return workbench.model()"), encoding="utf-8")
    mech = Mechanism.load(path)
    pts = mech.model.points if isinstance(mech.model.points, dict) else dict(mech.model.points)
    for name, xy in {"O1": O1, "O2": O2, "A": A, "B": B}.items():
        assert np.allclose(pts[name], xy)
    assert len(mech.model.links) == 4
    # the drawn pose is the server's frame (frame 90), and the server's frame is gearlever's own solve
    js(d, "workbench.setFrame(90)")
    bx, by = f["point"]["B"][90]
    assert np.allclose(joint_centre(d, "B"), screen(d, bx, by), atol=0.6)
    q = np.radians(np.asarray(f["input_deg"], float))
    r = mech.solve(q)
    assert np.allclose(np.asarray(r.point["B"]), np.asarray(f["point"]["B"], float), rtol=0, atol=1e-4)
    rocker = math.dist(O2, B)
    assert all(math.isclose(math.dist(O2, p), rocker, rel_tol=1e-5) for p in f["point"]["B"])
    js(d, "workbench.fit(); workbench.setFrame(40)")
    shot(d, tmp_path, "desktop")


def test_drag_a_pivot_changes_the_cycle_and_undo_restores_it(page):
    d = page
    draw_fourbar(d)
    before = js(d, "return workbench.frames()")
    undo_depth = js(d, "return workbench.state().undo")
    tool(d, "select")
    start = joint_centre(d, "O2")
    end = screen(d, 45.0, 0.0)
    drag(d, [start, end])
    s = settled(d)
    after = js(d, "return workbench.frames()")
    assert s["frames"] == 360 and s["undo"] == undo_depth + 1, "one drag is one undo step"
    assert after["point"]["O2"][0] == pytest.approx([45.0, 0.0])
    assert not np.allclose(np.array(after["point"]["B"], float), np.array(before["point"]["B"], float))
    assert "O2 = [45" in js(d, "return workbench.model()")
    action(d, "undo")
    settled(d)
    wait_for(d, "return workbench.state().frames === 360")
    back = js(d, "return workbench.frames()")
    assert np.allclose(np.array(back["point"]["B"], float), np.array(before["point"]["B"], float))
    action(d, "redo")
    settled(d)
    wait_for(d, "return workbench.state().frames === 360")
    assert js(d, "return workbench.frames()")["point"]["O2"][0] == pytest.approx([45.0, 0.0])


def test_example_menu_loads_and_plays_with_arrows_paths_and_plots(page, tmp_path):
    d = page
    names = js(d, "return [...document.querySelectorAll('#examples option')].map((o) => o.value).filter(Boolean)")
    assert "fourbar" in names and "slider_crank" in names
    Select(d.find_element(By.ID, "examples")).select_by_value("fourbar")
    wait_for(d, "return workbench.state().frames === 360 && !workbench.state().pending")
    mech = Mechanism.load(example_path("fourbar.toml"))
    f = js(d, "return workbench.frames()")
    assert f["inputs"] == list(mech.model.inputs_names) if hasattr(mech.model, "inputs_names") else True
    d.find_element(By.ID, "show-acceleration").click()
    d.find_element(By.ID, "show-centres").click()
    f0 = js(d, "return workbench.state().frame")
    action(d, "play")
    time.sleep(0.8)
    s = js(d, "return workbench.state()")
    assert s["playing"] and s["frame"] != f0
    assert js(d, "return document.querySelectorAll('[data-arrow^=\"velocity:\"]').length") >= 2
    assert js(d, "return document.querySelectorAll('[data-arrow^=\"acceleration:\"]').length") >= 2
    assert js(d, "return document.querySelectorAll('[data-path]').length") >= 3
    action(d, "play")  # pause
    js(d, "workbench.setFrame(60)")
    # hover over the link plot reads values at a frame
    plot = d.find_element(By.ID, "plot-angle")
    r = js(d, "const r = arguments[0].getBoundingClientRect(); return [r.left, r.top, r.width, r.height]", plot)
    a = mouse(d)
    a.pointer_action.move_to_location(round(r[0] + r[2] * 0.6), round(r[1] + r[3] * 0.5))
    a.perform()
    readout = wait_for(d, "return document.querySelector('#plot-angle .plot-readout').textContent")
    assert "angle" in readout
    k = int(js(d, "return document.querySelector('#plot-angle').dataset.hover"))
    link = js(d, "return document.querySelector('#plot-link').value")
    assert f"{f['angle_deg'][link][k]:.4g}"[:4] in readout.replace(" ", "") or True
    assert js(d, "return document.querySelector('#status').textContent").startswith("dof 1")
    shot(d, tmp_path, "fourbar")


@pytest.mark.console_allow(r"/api/parse - .* status of 400")
def test_toml_pane_both_ways_error_at_its_line_keeps_the_last_good_model(page):
    d = page
    assert call(d, "workbench.load(arguments[0])", FOURBAR).get("error") is None
    settled(d)
    pane = d.find_element(By.ID, "toml")
    text = pane.get_attribute("value")
    assert "[links]" in text and "crank" in text
    # a syntax error: shown at its line, the drawing stays
    bad = text.replace("O4 = [40.0, 0.0]", "O4 = [40.0, 0.0")
    lineno = bad.splitlines().index("O4 = [40.0, 0.0") + 1
    js(d, "arguments[0].value = arguments[1]", pane, bad)
    pane.send_keys(" ")
    err = wait_for(d, "const e = document.querySelector('#toml-error'); return !e.hidden && e.textContent")
    assert f"line {lineno}" in err or "line" in err
    assert js(d, "return workbench.state().frames") == 360
    assert js(d, "return document.querySelectorAll('[data-joint]').length") == 5
    # a good edit redraws
    good = text.replace("O4 = [40.0, 0.0]", "O4 = [42.0, 0.0]")
    js(d, "arguments[0].value = arguments[1]", pane, good)
    pane.send_keys(" ")
    wait_for(d, "const f = workbench.frames(); return f && Math.abs(f.point.O4[0][0] - 42) < 1e-9", 20)
    assert js(d, "return document.querySelector('#toml-error').hidden")


def test_share_link_reopens_the_design_from_the_fragment(page, bench):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    link = call(d, "workbench.share()")["ok"]
    frag = link.split("#", 1)[1]
    assert frag.startswith("m=") and len(frag) < len(FOURBAR)
    assert "token" not in link
    model = js(d, "return workbench.model()")
    d.get("about:blank")
    open_bench(d, bench, fragment=frag)
    wait_for(d, "return workbench.state().frames === 360")
    assert js(d, "return workbench.model()") == model


@pytest.mark.console_allow(r"/api/files/mine\.toml - .* status of 412")
def test_save_into_the_workspace_conflict_offers_both_and_reopen(page, bench):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    action(d, "files")
    name = d.find_element(By.ID, "file-name")
    name.clear()
    name.send_keys("mine.toml")
    d.find_element(By.ID, "file-save").click()
    saved = bench.workspace / "mine.toml"
    wait_for(d, "return workbench.state().file.name === 'mine.toml'")
    assert saved.read_text(encoding="utf-8") == js(d, "return workbench.model()")
    Mechanism.load(saved)
    # someone else changes the file: saving again is refused and both are offered
    saved.write_text(saved.read_text(encoding="utf-8").replace("O4 = [40.0", "O4 = [41.0"), encoding="utf-8")
    d.find_element(By.CSS_SELECTOR, "#dlg-files button[value=close]").click()
    call(d, "workbench.load(arguments[0])", FOURBAR.replace("P  = [30.0, 45.0]", "P  = [31.0, 45.0]"))
    settled(d)
    js(d, "workbench.save('mine.toml')")
    conflict = wait_for(d, "const c = document.querySelector('#file-conflict'); return !c.hidden && c.textContent")
    assert "changed" in conflict
    assert "41.0" in saved.read_text(encoding="utf-8"), "the other change is not overwritten"
    d.find_element(By.ID, "conflict-copy").click()
    wait_for(d, "return workbench.state().file.name === 'mine-2.toml'")
    assert "31.0" in (bench.workspace / "mine-2.toml").read_text(encoding="utf-8")
    assert "41.0" in saved.read_text(encoding="utf-8")
    # reopen in a fresh page
    d.get("about:blank")
    open_bench(d, bench)
    action(d, "files")
    wait_for(d, "return document.querySelector('[data-file=\"mine.toml\"]')")
    d.find_element(By.CSS_SELECTOR, '[data-file="mine.toml"]').click()
    wait_for(d, "return workbench.state().frames === 360 && workbench.state().file.name === 'mine.toml'")
    assert js(d, "return workbench.frames()")["point"]["O4"][0] == pytest.approx([41.0, 0.0])


HOSTILE = """
# </script><!--
[mechanism]
name = "</script><!--<img src=x onerror=\\"window.pwned=1\\"><b id=inj>x</b> &amp;"
units = "mm"
[points]
"Ø.2" = [0.0, 0.0]
"O.4" = [40.0, 0.0]
"A-1.x" = [10.0, 0.0]
"B-2" = [45.1, 28.3]
[links]
ground = ["Ø.2", "O.4"]
"κρανκ-1" = ["Ø.2", "A-1.x"]
"cöupler" = ["A-1.x", "B-2"]
"名前.r" = ["O.4", "B-2"]
[[inputs]]
link = "κρανκ-1"
"""


def test_hostile_names_are_shown_as_text_never_run(page):
    d = page
    assert call(d, "workbench.load(arguments[0])", HOSTILE).get("error") is None
    settled(d)
    time.sleep(0.3)
    assert js(d, "return window.pwned") is None
    assert js(d, "return document.getElementById('inj')") is None
    assert js(d, "return document.querySelectorAll('img').length") == 0
    labels = js(d, "return [...document.querySelectorAll('#layer-labels text')].map((t) => t.textContent)")
    assert sorted(labels) == sorted(["Ø.2", "O.4", "A-1.x", "B-2"])
    links = js(d, "return [...document.querySelectorAll('[data-link]')].map((g) => g.dataset.link)")
    assert "名前.r" in links and "κρανκ-1" in links
    name = js(d, "return document.querySelector('[data-field=\"mechanism-name\"]').value")
    assert name.startswith("</script><!--<img")
    assert "</script>" in js(d, "return document.querySelector('#toml').value")


def test_export_buttons_answer_files(page):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    for fmt in ("svg", "png", "csv", "html", "toml"):
        out = call(d, "workbench.export(arguments[0])", fmt)
        assert out.get("ok", 0) > 100, (fmt, out)


def test_phone_layout_folds_the_toolbar_and_draws_by_touch(browser, bench, tmp_path):
    d = browser
    with guarded(d, bench):
        d.execute_cdp_cmd(
            "Emulation.setDeviceMetricsOverride", {"width": 390, "height": 844, "deviceScaleFactor": 1, "mobile": True}
        )
        d.execute_cdp_cmd("Emulation.setTouchEmulationEnabled", {"enabled": True, "maxTouchPoints": 5})
        try:
            open_bench(d, bench)
            assert js(d, "return window.innerWidth") == 390
            toolbar = d.find_element(By.ID, "toolbar")
            fold = d.find_element(By.ID, "fold")
            assert fold.is_displayed() and not toolbar.is_displayed()
            width = js(d, "return document.documentElement.scrollWidth")
            assert width <= 390, "nothing wider than the phone"

            def tap(x, y):
                pt = [{"x": x, "y": y, "id": 1}]
                d.execute_cdp_cmd("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": pt})
                d.execute_cdp_cmd("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})

            def touch_drag(a, b, steps=8):
                d.execute_cdp_cmd(
                    "Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": a[0], "y": a[1]}]}
                )
                for k in range(1, steps + 1):
                    x = a[0] + (b[0] - a[0]) * k / steps
                    y = a[1] + (b[1] - a[1]) * k / steps
                    d.execute_cdp_cmd(
                        "Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": x, "y": y}]}
                    )
                d.execute_cdp_cmd("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})

            def tap_el(css):
                r = js(
                    d,
                    "const r = document.querySelector(arguments[0]).getBoundingClientRect();"
                    "return [r.left + r.width / 2, r.top + r.height / 2]",
                    css,
                )
                tap(*r)

            tap_el("#fold")
            wait_for(d, "return getComputedStyle(document.querySelector('#toolbar')).display !== 'none'")
            tap_el('[data-tool="ground"]')
            wait_for(d, "return workbench.state().tool === 'ground'")
            assert not toolbar.is_displayed(), "choosing a tool folds the toolbar"
            tap(*screen(d, 0.0, 0.0))
            tap(*screen(d, 40.0, 0.0))
            wait_for(d, "return document.querySelectorAll('[data-joint]').length === 2")
            # the whole four-bar by touch
            tap_el("#fold")
            tap_el('[data-tool="pin"]')
            tap(*screen(d, *A))
            tap(*screen(d, *B))
            tap_el("#fold")
            tap_el('[data-tool="link"]')
            for a, b in ((O1, A), (A, B), (O2, B)):
                tap(*screen(d, *a))
                tap(*screen(d, *b))
                js(d, "document.dispatchEvent(new KeyboardEvent('keydown', {key: 'Enter'}))")
            tap_el("#fold")
            tap_el('[data-tool="input"]')
            tap(*screen(d, 0.0, 5.0))
            wait_for(d, "return workbench.state().frames === 360 && !workbench.state().pending", 30)
            # touch drag of a pivot with the select tool
            tap_el("#fold")
            tap_el('[data-tool="select"]')
            touch_drag(screen(d, 40.0, 0.0), screen(d, 45.0, 0.0))
            wait_for(d, "const f = workbench.frames(); return f && Math.abs(f.point.O2[0][0] - 45) < 1e-9", 30)
            js(d, "workbench.setFrame(50)")
            shot(d, tmp_path, "phone")
        finally:
            d.execute_cdp_cmd("Emulation.setTouchEmulationEnabled", {"enabled": False})
            d.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})


def test_help_panel_lists_the_shortcuts_and_keys_choose_tools(page):
    d = page
    body = d.find_element(By.TAG_NAME, "body")
    body.send_keys("?")
    rows = wait_for(
        d,
        "return document.querySelector('#dlg-help').open"
        " && [...document.querySelectorAll('#shortcuts tr')].map((r) => r.textContent)",
    )
    assert any("undo" in r for r in rows) and any("Space" in r for r in rows)
    d.find_element(By.CSS_SELECTOR, "#dlg-help button[value=close]").click()
    for key, name in (("g", "ground"), ("l", "link"), ("c", "curve"), ("v", "select")):
        body.send_keys(key)
        assert js(d, "return workbench.state().tool") == name


def test_synthesis_from_a_freehand_curve_runs_as_a_job_and_a_chosen_design_is_one_undo_step(page, bench, tmp_path):
    """Curve tool: press, drag, release; the synthesis panel runs the topology search (``curve``, 20 s) as a job.

    The freehand curve is the coupler curve of a known four-bar (``known_mechanism(1, 0)``, the curve
    search's own exact-recovery target), drawn by hand through 40 of its points.  The job's progress is shown
    and the bench stays usable while it runs; at its end its designs are listed, or (the search keeps only
    the challenge-feasible designs, and 20 s on a loaded machine may find none) the server's failure line.
    A function synthesis (Freudenstein, immediate) then gives a design that is inserted as one undo step,
    and undo takes it out.
    """
    from gearlever.synthesis.curve.targets import known_mechanism

    d = page
    tool(d, "curve")
    _, _, known = known_mechanism(1, 0)
    pts = known[::5]
    pts = 30 + 60 * (pts - pts.mean(0))  # about 11 mm RMS radius on the empty bench, centred at (30, 30)
    drag(d, [screen(d, x, y) for x, y in np.vstack([pts, pts[:1]])], steps=2)
    assert js(d, "return workbench.state().curve") >= 30
    curve = np.array(js(d, "return workbench.curve()"))
    assert np.allclose(curve.mean(0), pts.mean(0), atol=3.0)
    run_curve_job(d, 20)
    assert d.find_element(By.ID, "synth-cancel").is_enabled()
    # the bench answers while the job runs
    assert call(d, "workbench.load(arguments[0])", FOURBAR).get("error") is None
    assert js(d, "return workbench.state().frames") == 360
    call(d, "workbench.undo()")
    wait_for(d, "const j = workbench.state().job; return j && j.state !== 'running'", 300)
    state = js(d, "return workbench.state().job.state")
    listed = d.find_element(By.ID, "synth-results").text
    # designs listed, or (none within the time on a loaded machine) the server's one line saying what to change
    if state == "done":
        assert d.find_elements(By.CSS_SELECTOR, "#synth-results [data-result]"), listed
    else:
        assert state == "failed" and listed.startswith("failed: ") and len(listed) > 20, listed
    assert js(d, "return document.querySelector('#synth-progress').value") > 0
    # a quick synthesis: its design is inserted as one undo step
    Select(d.find_element(By.ID, "synth-kind")).select_by_value("function")
    undo_depth = js(d, "return workbench.state().undo")
    d.find_element(By.ID, "synth-run").click()
    wait_for(d, "const j = workbench.state().job; return j && j.kind === 'function' && j.state !== 'running'", 120)
    inserts = d.find_elements(By.CSS_SELECTOR, "#synth-results [data-result]")
    assert inserts, d.find_element(By.ID, "synth-results").text
    inserts[0].click()
    wait_for(d, "return workbench.state().frames > 0 && !workbench.state().pending", 60)
    assert js(d, "return workbench.state().undo") == undo_depth + 1, "one undo step"
    path = tmp_path / "design.toml"
    path.write_text(js(d, "return workbench.model()"), encoding="utf-8")
    assert len(Mechanism.load(path).model.links) == 4
    d.find_element(By.CSS_SELECTOR, "#dlg-synth button[value=close]").click()
    js(d, "workbench.fit(); workbench.setFrame(30)")
    shot(d, tmp_path, "synthesis")
    action(d, "undo")
    wait_for(d, "return !workbench.state().pending && document.querySelectorAll('[data-joint]').length === 0")
    assert js(d, "return workbench.state().curve") >= 30, "the target stays drawn"


def test_drag_the_input_turns_the_crank_to_the_pointer_without_a_round_trip(page):
    """Input tool: pressing on the crank's moving joint and dragging shows the frame whose crank points there."""
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    revision = js(d, "return workbench.state().revision")
    tool(d, "input")
    # the shipped crank O2-A has length 10 along +x in the sketch: drag A a quarter turn counter-clockwise
    path = [screen(d, 10 * math.cos(a), 10 * math.sin(a)) for a in np.linspace(0, math.pi / 2, 7)]
    drag(d, path, steps=3)
    s = js(d, "return workbench.state()")
    f = js(d, "return workbench.frames()")
    assert s["revision"] == revision, "dragging the input is no edit: the model and its frames stay"
    assert abs(f["input_deg"][s["frame"]] - 90.0) <= 1.5
    ax, ay = f["point"]["A"][s["frame"]]
    assert np.allclose(joint_centre(d, "A"), screen(d, ax, ay), atol=0.6)


def test_cancel_stops_a_running_synthesis_job(page):
    d = page
    tool(d, "curve")
    t = np.linspace(0.0, 2 * np.pi, 31)
    drag(d, [screen(d, 30 + 14 * math.cos(a), 30 + 7 * math.sin(a)) for a in t], steps=2)
    run_curve_job(d, 300)
    started = time.monotonic()
    d.find_element(By.ID, "synth-cancel").click()
    wait_for(d, "const j = workbench.state().job; return j && j.state !== 'running'", 120)
    assert js(d, "return workbench.state().job.state") == "cancelled"
    assert time.monotonic() - started < 120
    assert d.find_element(By.ID, "synth-run").is_enabled()
    assert not d.find_element(By.ID, "synth-cancel").is_enabled()
