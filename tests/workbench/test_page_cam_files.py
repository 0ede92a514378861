"""The workbench page in headless Chromium: the cam saved, reopened, shared and exported.

Each journey runs on its own server, ``guarded`` (no console error, no request off the bench's host):

- a cam placed on the crank's ground pivot of the four-bar, saved: the model file and ``NAME.cam.toml`` (a
  CAM.toml that :func:`gearlever.cams.load_cam` and :func:`gearlever.cams.cam_centre` read); reopened in a fresh
  page it has the same law, follower, base radius and pivot, and still turns with the crank; a cam file changed
  on disk is not overwritten (the conflict is shown); a CAM file opened alone puts the cam on an empty bench;
- the law list beside the cam tool is asked again when the tool is chosen: a law written since the page opened
  is listed.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

from tests.workbench._server import open_bench, wait_for
from tests.workbench.test_page import FOURBAR, call, click_at, joint_centre, js, screen, settled, shot, tool

_CAM_READY = "return !!workbench.cam() && !!document.querySelector('[data-cam]')"


@pytest.mark.console_allow("412")
def test_cam_saved_beside_the_model_reopens_in_a_fresh_page_the_same(page, bench, tmp_path):
    from gearlever.cams import cam_centre, load_cam

    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    Select(d.find_element(By.ID, "cam-law")).select_by_value("example:law_dwell_rocker")
    tool(d, "cam")
    click_at(d, *joint_centre(d, "O2"))  # the crank's ground pivot
    wait_for(d, _CAM_READY)
    settled(d)
    before = js(d, "return workbench.cam()")
    assert call(d, "workbench.save('bench.toml')")["ok"] == "bench.toml"
    path = bench.workspace / "bench.cam.toml"
    assert path.exists() and (bench.workspace / "bench.toml").exists()
    # the library reads the cam file: its follower, base radius and pivot
    design = load_cam(path)
    assert design.follower == before["follower_kind"] == "oscillating-roller"
    assert abs(design.base_radius - before["base_radius"]) <= 1e-11 * before["base_radius"]
    assert list(cam_centre(path)) == before["centre"]
    names = {f["name"]: f["kind"] for f in js(d, "return fetch('/api/files').then((r) => r.json())")["files"]}
    assert names == {"bench.toml": "model", "bench.cam.toml": "cam"}

    # a fresh page opens the model and its cam comes back: same law (s), follower, radius, pivot, turning
    open_bench(d, bench)
    assert js(d, "return workbench.cam()") is None
    call(d, "workbench.open('bench.toml')")
    wait_for(d, _CAM_READY)
    settled(d)
    after = js(d, "return workbench.cam()")
    assert after["follower_kind"] == before["follower_kind"] and after["centre"] == before["centre"]
    assert abs(after["base_radius"] - before["base_radius"]) <= 1e-11 * before["base_radius"]
    for key in ("roller_radius", "arm", "pivot_distance", "cam_angle_deg"):
        assert after[key] == before[key], key
    np.testing.assert_allclose(after["s"], before["s"], atol=1e-9)
    np.testing.assert_allclose(np.array(after["profile"], float), np.array(before["profile"], float), atol=1e-8)
    wait_for(d, "return document.getElementById('status').textContent.includes('it turns with crank')")
    assert js(d, "return workbench.state().undo") == 1  # model and cam: one step
    js(d, "workbench.setFrame(60)")
    shot(d, tmp_path, "cam_reopened")

    # the cam file changed on disk since it was opened: not clobbered, the conflict is shown
    theirs = path.read_text(encoding="utf-8").replace("Written by", "Edited after being written by")
    path.write_text(theirs, encoding="utf-8")
    assert call(d, "workbench.save('bench.toml')")["ok"] is None
    assert path.read_text(encoding="utf-8") == theirs
    assert not d.find_element(By.ID, "file-conflict").get_attribute("hidden")
    assert "bench.cam.toml changed" in d.find_element(By.ID, "file-conflict-text").text
    d.find_element(By.ID, "conflict-overwrite").click()  # the user chose theirs to be replaced: now written
    deadline = time.monotonic() + 30
    while path.read_text(encoding="utf-8") == theirs and time.monotonic() < deadline:
        time.sleep(0.05)
    assert path.read_text(encoding="utf-8") != theirs and list(cam_centre(path)) == before["centre"]

    # the CAM file alone: an empty bench with the cam at its pivot
    open_bench(d, bench)
    call(d, "workbench.open('bench.cam.toml')")
    wait_for(d, _CAM_READY)
    settled(d)
    alone = js(d, "return workbench.cam()")
    assert alone["centre"] == before["centre"] and alone["follower_kind"] == before["follower_kind"]
    assert js(d, "return Object.keys(workbench.frames()?.point || {}).length") == 0


def test_law_list_is_asked_again_when_the_cam_tool_is_chosen(page, bench):
    from tests.workbench._client import example_text

    d = page
    values = lambda: js(d, "return [...document.querySelectorAll('#cam-law option')].map((o) => o.value)")  # noqa: E731
    assert "file:my_law.toml" not in values()
    (bench.workspace / "my_law.toml").write_text(example_text("law_lift"), encoding="utf-8")
    tool(d, "cam")
    wait_for(d, "return [...document.querySelectorAll('#cam-law option')].some((o) => o.value === 'file:my_law.toml')")
    assert values().count("example:law_lift") == 1  # rebuilt, not appended


def test_share_link_carries_the_cam_and_a_fresh_page_finds_it(page, bench):
    import base64
    import zlib

    from gearlever.cams import cam_centre, load_cam

    d = page
    call(d, "workbench.load(arguments[0])", FOURBAR)
    settled(d)
    plain_dxf = call(d, "workbench.export('dxf')")["ok"]
    Select(d.find_element(By.ID, "cam-law")).select_by_value("example:law_lift")
    Select(d.find_element(By.ID, "cam-follower")).select_by_visible_text("translating-flat")
    tool(d, "cam")
    click_at(d, *screen(d, 20.0, -8.0))  # on no joint: a cam alone beside the linkage
    wait_for(d, _CAM_READY)
    settled(d)
    before = js(d, "return workbench.cam()")
    # the page's DXF carries the cam's profile: 360 more polyline vertices than the linkage alone
    assert call(d, "workbench.export('dxf')")["ok"] > plain_dxf + 360 * 2 * 10
    link = call(d, "workbench.share()")["ok"]
    frag = link.split("#", 1)[1]
    assert frag.startswith("m=") and "&c=" in frag and "token" not in link
    # the cam's part is the CAM.toml text, deflate-raw compressed and base64url encoded, as the model's
    packed = frag.split("&c=", 1)[1]
    text = zlib.decompress(base64.urlsafe_b64decode(packed + "=" * (-len(packed) % 4)), -15).decode()
    path = bench.workspace.parent / "shared.cam.toml"
    path.write_text(text, encoding="utf-8")
    assert list(cam_centre(path)) == before["centre"] and load_cam(path).follower == "translating-flat"
    model = js(d, "return workbench.model()")
    d.get("about:blank")
    open_bench(d, bench, fragment=frag)
    wait_for(d, _CAM_READY)
    settled(d)
    after = js(d, "return workbench.cam()")
    assert js(d, "return workbench.model()") == model
    assert after["follower_kind"] == "translating-flat" and after["centre"] == before["centre"]
    assert abs(after["base_radius"] - before["base_radius"]) <= 1e-11 * before["base_radius"]
    np.testing.assert_allclose(after["s"], before["s"], atol=1e-9)
    assert js(d, "return workbench.state().undo") == 1  # model and cam: one step
