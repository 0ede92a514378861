"""The workbench page in headless Chromium: a cam and its follower, motion poses in the model, load arrows.

Each journey is driven by real pointer events on its own server and runs ``guarded`` (no console error, no
request off the bench's host), as in ``test_page.py``:

- a cam placed with the cam tool on an empty bench, from a shipped law: what the page draws is what
  ``POST /api/cam`` answers (the library's :func:`gearlever.cams.design_cam`), it turns when played, and
  placing it is one undo step;
- three motion poses: each added pose one undo step, written in the model's ``[[poses]]``, undone and
  redone, saved into the workspace and reopened;
- a load entered in the panel: an arrow ending at its point, on the pin forces' scale, labelled.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select

from tests.workbench._server import open_bench, wait_for
from tests.workbench.test_page import (
    FOURBAR,
    call,
    click_at,
    drag,
    joint_centre,
    js,
    screen,
    settled,
    shot,
    tool,
)
from tests.workbench.test_page_design import set_field


def _attr_points(d, selector):
    text = js(d, "return document.querySelector(arguments[0]).getAttribute('points')", selector)
    return np.array([[float(v) for v in p.split(",")] for p in text.split()])


def _circle(d, selector):
    return js(
        d,
        "const c = document.querySelector(arguments[0]); const r = c.getBoundingClientRect();"
        "return [r.left + r.width / 2, r.top + r.height / 2, r.width / 2];",
        selector,
    )


def test_cam_drawn_on_an_empty_bench_is_the_librarys_and_turns_and_undoes(page, bench, tmp_path):
    from gearlever.cams import design_cam
    from gearlever.data import example_path
    from gearlever.laws import load_law

    d = page
    Select(d.find_element(By.ID, "cam-law")).select_by_value("example:law_lift")
    tool(d, "cam")
    click_at(d, *screen(d, 0.0, 0.0))
    wait_for(d, "return !!workbench.cam() && !!document.querySelector('[data-cam]')")
    settled(d)
    c = js(d, "return workbench.cam()")
    assert c["follower_kind"] == "translating-roller" and c["frames"] == 360
    assert js(d, "return workbench.state().undo") == 1
    assert "sized for a pressure angle of at most 30 deg" in d.find_element(By.ID, "status").text
    # the library's cam, computed here: the same base radius, stroke and follower travel
    law = load_law(example_path("law_lift.toml"))
    ref = design_cam(law, "translating-roller", base_radius=c["base_radius"], roller_radius=5.0, points=360)
    assert c["roller_radius"] == 5.0  # a quarter of the 20 mm stroke
    assert math.isclose(c["pressure_angle_max_deg"], math.degrees(ref.pressure_angle_max), rel_tol=1e-9)
    assert c["pressure_angle_max_deg"] <= 30.0 + 1e-6
    np.testing.assert_allclose(c["s"], ref.s, atol=1e-4)
    # the roller centre rides on the follower's axis at base + roller + s (offset 0), where the page draws it
    cx, cy = c["centre"]
    rc = np.array(c["roller_centre"])
    np.testing.assert_allclose(rc[:, 0], cx, atol=1e-4)
    np.testing.assert_allclose(rc[:, 1] - cy, c["base_radius"] + 5.0 + ref.s, atol=1e-4)
    for frame in (0, 120):
        js(d, "workbench.setFrame(arguments[0])", frame)
        x, y, r = _circle(d, ".follower-roller")
        sx, sy = screen(d, *rc[frame])
        scale = js(d, "return workbench.view().s")
        assert math.hypot(x - sx, y - sy) < 1.0 and math.isclose(r, 5.0 * scale, rel_tol=0.02)
    # the profile drawn at frame k is the served profile turned about the pivot by the cam's angle: it touches
    # the roller (its nearest point is one roller radius from the roller's centre)
    k = 120
    js(d, "workbench.setFrame(arguments[0])", k)
    drawn = _attr_points(d, ".cam-profile")
    v = js(d, "return workbench.view()")
    model = np.column_stack([(drawn[:, 0] - v["tx"]) / v["s"], (v["ty"] - drawn[:, 1]) / v["s"]])
    gap = np.min(np.hypot(*(model - rc[k]).T))
    assert abs(gap - 5.0) < 0.02 * c["base_radius"], gap
    shot(d, tmp_path, "cam")
    # playing turns the cam
    before = _attr_points(d, ".cam-profile")
    js(d, "workbench.play()")
    wait_for(d, "return workbench.state().frame > 130")
    js(d, "workbench.pause()")
    assert not np.allclose(before, _attr_points(d, ".cam-profile"))
    # one undo step: undo removes it, redo brings it back
    call(d, "workbench.undo()")
    assert js(d, "return document.querySelector('[data-cam]')") is None
    call(d, "workbench.redo()")
    wait_for(d, "return !!document.querySelector('[data-cam]')")
    # a new bench clears it, in one undo step with the model
    d.find_element(By.CSS_SELECTOR, '[data-action="new"]').click()
    wait_for(d, "return !document.querySelector('[data-cam]') && !workbench.cam()")
    call(d, "workbench.undo()")
    wait_for(d, "return !!document.querySelector('[data-cam]')")


def test_cam_of_an_angle_law_has_an_oscillating_follower_on_its_pivot(page):
    d = page
    Select(d.find_element(By.ID, "cam-law")).select_by_value("example:law_dwell_rocker")
    tool(d, "cam")
    click_at(d, *screen(d, 10.0, 10.0))
    wait_for(d, "return !!workbench.cam() && !!document.querySelector('.follower-roller')")
    c = js(d, "return workbench.cam()")
    assert c["follower_kind"] == "oscillating-roller" and c["pivot"] is not None
    # the arm keeps its length: pivot to roller centre is the arm at every frame
    rc, pv = np.array(c["roller_centre"]), np.array(c["pivot"])
    np.testing.assert_allclose(np.hypot(*(rc - pv).T), c["arm"], atol=1e-3)
    # the follower swings through the law's 45 deg
    assert math.isclose(max(c["s"]) - min(c["s"]), 45.0, abs_tol=1e-3)


def test_three_poses_are_undoable_steps_saved_with_the_model_and_reopened(page, bench, tmp_path):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    tool(d, "pose")
    want = [(0.0, 20.0, 0.0), (20.0, 30.0, 20.0), (40.0, 30.0, 45.0)]
    for n, (x, y, a) in enumerate(want, 1):
        px, py = screen(d, x, y)
        r = math.radians(a)
        drag(d, [(px, py), (px + 60 * math.cos(r), py - 60 * math.sin(r))])
        assert settled(d)["undo"] == 1 + n  # the load of the model, then one step a pose
    poses = tomllib.loads(js(d, "return workbench.model()"))["poses"]
    assert len(poses) == 3
    for (x, y, a), p in zip(want, poses):
        assert math.hypot(p["point"][0] - x, p["point"][1] - y) < 0.6 and abs(p["angle_deg"] - a) < 1.5, p
    assert "[[poses]]" in d.find_element(By.ID, "toml").get_property("value")
    shot(d, tmp_path, "poses_saved")
    call(d, "workbench.undo()")
    settled(d)
    assert len(tomllib.loads(js(d, "return workbench.model()"))["poses"]) == 2
    assert len(js(d, "return workbench.poses()")) == 2
    call(d, "workbench.redo()")
    settled(d)
    assert len(tomllib.loads(js(d, "return workbench.model()"))["poses"]) == 3
    # a pose selected and deleted with the Delete key is one step too, undone like the others
    steps = settled(d)["undo"]
    click_at(d, *screen(d, *[poses[2]["point"][0], poses[2]["point"][1]]))
    wait_for(d, "return !!document.querySelector('[data-field=\"pose-angle\"]')")
    d.find_element(By.TAG_NAME, "body").send_keys(Keys.DELETE)
    wait_for(d, "return workbench.poses().length === 2")
    assert settled(d)["undo"] == steps + 1
    call(d, "workbench.undo()")
    settled(d)
    assert len(js(d, "return workbench.poses()")) == 3
    call(d, "workbench.save('poses.toml')")
    wait_for(d, "return workbench.state().file.name === 'poses.toml'")
    saved = (bench.workspace / "poses.toml").read_text(encoding="utf-8")
    assert tomllib.loads(saved)["poses"] == poses
    # reopen in a fresh page: the poses come back with the model
    d.get("about:blank")
    open_bench(d, bench)
    call(d, "workbench.open('poses.toml')")
    settled(d)
    got = js(d, "return workbench.poses()")
    assert [[p["point"][0], p["point"][1], p["angle_deg"]] for p in poses] == got
    assert len(js(d, "return document.querySelectorAll('[data-pose]')")) == 3


def test_a_load_is_drawn_as_an_arrow_at_its_point_on_the_pin_forces_scale_and_labelled(page, tmp_path):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    tool(d, "select")
    click_at(d, *joint_centre(d, "P"))
    wait_for(d, "return !!document.querySelector('[data-field=\"load-fy\"]')")
    set_field(d, "load-fy", -10)
    arrow = js(
        d,
        "const a = document.querySelector('[data-load=\"0\"]');"
        "return ['x1', 'y1', 'x2', 'y2'].map((k) => Number(a.getAttribute(k)));",
    )
    x1, y1, x2, y2 = arrow
    # it ends at P where P is drawn, pointing down (the force is -y), 70 px long (the only force drawn)
    r = js(d, "const r = document.querySelector('#canvas').getBoundingClientRect(); return [r.left, r.top]")
    px, py = joint_centre(d, "P")
    assert math.hypot(x2 + r[0] - px, y2 + r[1] - py) < 1.0
    assert abs(x1 - x2) < 1e-6 and math.isclose(y2 - y1, 70.0, rel_tol=1e-6)
    assert js(d, "return document.querySelector('[data-load-label=\"0\"]').textContent") == "10 N"
    # with the pin forces shown, the load is on their scale: px per newton the same for both
    d.find_element(By.ID, "show-forces").click()
    wait_for(d, "return workbench.state().forces === 'ready'")
    js(d, "workbench.setFrame(90)")
    F = js(d, "return workbench.forces()")
    big = max(math.hypot(*v) for s in F["pin"].values() for v in s if v and v[0] is not None)
    scale = 70.0 / max(big, 10.0)
    x1, y1, x2, y2 = js(
        d,
        "const a = document.querySelector('[data-load=\"0\"]');"
        "return ['x1', 'y1', 'x2', 'y2'].map((k) => Number(a.getAttribute(k)));",
    )
    assert math.isclose(math.hypot(x2 - x1, y2 - y1), 10.0 * scale, rel_tol=1e-6)
    key, series = next((k, s) for k, s in F["pin"].items() if s[90] and math.hypot(*s[90]) > 0)
    fx = js(
        d,
        "const a = [...document.querySelectorAll('[data-force]')].find((g) => g.dataset.force === arguments[0]);"
        "const g = (k) => Number(a.getAttribute(k));"
        "return Math.hypot(g('x2') - g('x1'), g('y2') - g('y1'));",
        key,
    )
    assert math.isclose(fx, math.hypot(*series[90]) * scale, rel_tol=1e-6)
    assert d.find_element(By.ID, "torque").text.endswith("N·mm")
    shot(d, tmp_path, "load")


def test_cam_on_the_cranks_ground_pivot_turns_with_the_crank(page, tmp_path):
    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    Select(d.find_element(By.ID, "cam-law")).select_by_value("example:law_lift")
    tool(d, "cam")
    click_at(d, *joint_centre(d, "O2"))  # the crank's ground pivot: the cam is rigid on the crank
    wait_for(d, "return !!workbench.cam() && !!document.querySelector('[data-cam]')")
    settled(d)
    c = js(d, "return workbench.cam()")
    f = js(d, "return workbench.frames()")
    crank = np.array(f["angle_deg"]["crank"])
    assert c["frames"] == f["frames"] and c["centre"] == f["point"]["O2"][0]
    # the cam's angle at each frame is the crank's turn from the sketch, to the nearest 0.1 deg
    turn = np.mod(crank - crank[0], 360.0)
    diff = np.abs((np.array(c["cam_angle_deg"]) - turn + 180.0) % 360.0 - 180.0)
    assert diff.max() <= 0.05 + 1e-9, diff.max()
    assert "it turns with crank" in d.find_element(By.ID, "status").text
    js(d, "workbench.setFrame(100)")
    shot(d, tmp_path, "cam_on_crank")
    # moving the crank's pivot moves the cam with it (a new solve, a new cam)
    call(d, "workbench.undo()")
    assert js(d, "return document.querySelector('[data-cam]')") is None
