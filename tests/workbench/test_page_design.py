"""The workbench page's design aids in headless Chromium, each control driven by real pointer events.

Kennedy's lines (through the instant centres the server answers), force arrows and the input torque from a
load entered in the panel (checked against virtual work), the assembly-branch control, the DXF and outline
SVG export of the frame shown, ``&open=NAME``, a target imported from a CSV file for path synthesis, and
motion poses placed and turned on the canvas for motion synthesis.  As in ``test_page.py`` every test runs
``guarded`` (no console error, no request off the bench's host) on its own server.
"""

from __future__ import annotations

import math
import tomllib

import numpy as np
from selenium.webdriver.common.by import By
from selenium.webdriver.common.keys import Keys
from selenium.webdriver.support.ui import Select

from tests.workbench._server import desktop, guarded, wait_for
from tests.workbench.test_page import (
    FOURBAR,
    action,
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


def loaded(d, text=FOURBAR):
    """Load a model into the opened page (the ``page`` fixture) and wait for its frames."""
    call(d, "workbench.load(arguments[0])", text)
    return settled(d)


def set_field(d, name, value):
    """Type a value into a panel field and commit it (the change event), as a user does."""
    box = d.find_element(By.CSS_SELECTOR, f'[data-field="{name}"]')
    box.click()
    box.send_keys(Keys.CONTROL, "a")
    box.send_keys(str(value), Keys.TAB)
    return settled(d)


def test_kennedy_lines_pass_through_the_served_centres(page, tmp_path):
    d = page
    loaded(d)
    d.find_element(By.ID, "show-centres").click()
    d.find_element(By.ID, "show-kennedy").click()
    js(d, "workbench.setFrame(40)")
    lines = js(
        d,
        "return [...document.querySelectorAll('[data-kennedy]')].map((l) => [l.dataset.kennedy,"
        " ['x1', 'y1', 'x2', 'y2'].map((a) => Number(l.getAttribute(a)))])",
    )
    assert len(lines) == 4  # four bodies: four triples
    canvas = js(d, "const r = document.querySelector('#canvas').getBoundingClientRect(); return [r.left, r.top]")
    f = js(d, "return workbench.frames()")
    near = 0
    for keys, (x1, y1, x2, y2) in lines:
        for key in keys.split(" "):
            c = f["centres"][key][40]
            if c is None:
                continue
            px, py = (v - o for v, o in zip(screen(d, *c), canvas))
            dist = abs((x2 - x1) * (y1 - py) - (x1 - px) * (y2 - y1)) / math.hypot(x2 - x1, y2 - y1)
            assert dist < 1.0, (keys, key, dist)
            near += 1
    assert near >= 10
    shot(d, tmp_path, "kennedy")
    # one triple chosen in the menu: one line
    Select(d.find_element(By.ID, "kennedy-triple")).select_by_visible_text("ground, crank, coupler")
    assert js(d, "return document.querySelectorAll('[data-kennedy]').length") == 1


def test_force_arrows_and_input_torque_from_a_load_entered_in_the_panel_match_virtual_work(page, tmp_path):
    d = page
    loaded(d)
    tool(d, "select")
    click_at(d, *joint_centre(d, "P"))
    wait_for(d, "return !!document.querySelector('[data-field=\"load-fy\"]')")
    set_field(d, "load-fy", -10)
    model = tomllib.loads(js(d, "return workbench.model()"))
    assert model["loads"] == [{"link": "coupler", "point": "P", "force": [0.0, -10.0]}]
    d.find_element(By.ID, "show-forces").click()
    wait_for(d, "return workbench.state().forces === 'ready'")
    js(d, "workbench.setFrame(90)")
    keys = js(d, "return [...document.querySelectorAll('[data-force]')].map((a) => a.dataset.force)")
    assert {"A", "B", "O2", "O4"} <= set(keys)
    shot(d, tmp_path, "forces")
    text = d.find_element(By.ID, "torque").text
    assert text.startswith("T crank ") and text.endswith("N·mm")
    # virtual work: no mass, so the torque times the crank rate balances the load's power, T = -F . dP/dtheta
    f = js(d, "return workbench.frames()")
    T = float(text.split()[2])
    expected = 10.0 * f["velocity"]["P"][90][1]
    assert math.isclose(T, expected, rel_tol=1e-3), (T, expected)
    # a mass on the coupler changes the torque: centred at A (the page's default centre) it only adds a
    # radial force at the crank pin, no torque; its moment of inertia with the coupler's angular acceleration does
    a, b = np.array(f["point"]["A"][90]), np.array(f["point"]["B"][90])
    click_at(d, *screen(d, *(a + b) / 2))  # the coupler's middle where it is drawn: the link's panel
    wait_for(d, "return !!document.querySelector('[data-field=\"mass\"]')")
    set_field(d, "mass", 2)
    wait_for(d, "return workbench.state().forces === 'ready'")
    assert d.find_element(By.ID, "torque").text == text
    set_field(d, "inertia", 500)
    wait_for(d, "return workbench.state().forces === 'ready'")
    assert tomllib.loads(js(d, "return workbench.model()"))["masses"]["coupler"] == {
        "mass": 2.0,
        "centre": "A",
        "inertia": 500.0,
    }
    assert d.find_element(By.ID, "torque").text != text


def test_branch_control_puts_the_joint_on_its_other_branch_and_undo_restores(page):
    d = page
    loaded(d)
    tool(d, "select")
    sel = d.find_element(By.CSS_SELECTOR, '[data-branch="B"]')
    assert Select(sel).first_selected_option.text == "left of A→O4"
    Select(sel).select_by_value("-1")
    wait_for(d, "return workbench.state().undo === 2 && !workbench.state().pending")
    s = settled(d)
    assert s["frames"] == 360 and not s["message"]
    B = tomllib.loads(js(d, "return workbench.model()"))["points"]["B"]
    assert B[1] < 0  # mirrored below the line A-O4 (the ground line at the sketch)
    assert Select(d.find_element(By.CSS_SELECTOR, '[data-branch="B"]')).first_selected_option.text == ("right of A→O4")
    action(d, "undo")
    settled(d)
    assert tomllib.loads(js(d, "return workbench.model()"))["points"]["B"] == [45.1, 28.3]


def test_export_dialog_gives_dxf_and_outline_svg_of_the_frame_shown(page):
    d = page
    loaded(d)
    js(d, "workbench.setFrame(90)")
    action(d, "export")
    for fmt in ("dxf", "svg-outline", "csv"):
        d.find_element(By.CSS_SELECTOR, f'[data-export="{fmt}"]').click()
        note = wait_for(
            d, "const t = document.querySelector('#export-note').textContent; return /bytes$/.test(t) && t", 60
        )
        assert note.startswith(f"{fmt}: ") and int(note.split()[1]) > 500, note
        js(d, "document.querySelector('#export-note').textContent = ''")


def test_open_in_the_url_opens_a_workspace_file(browser, bench):
    d = browser
    (bench.workspace / "mine.toml").write_text(FOURBAR.replace("crank-rocker", "opened from the URL"))
    with guarded(d, bench):
        desktop(d)
        d.get(bench.page_url + "&open=mine.toml")
        wait_for(d, "return !!(window.workbench && window.workbench.state().ready)")
        s = settled(d)
        assert s["file"]["name"] == "mine.toml" and s["frames"] == 360
        assert "opened from the URL" in js(d, "return workbench.model()")


def test_csv_target_imported_in_the_synthesis_panel_drives_a_path_synthesis(page, tmp_path):
    d = page
    t = np.linspace(0, 2 * np.pi, 24, endpoint=False)
    csv = tmp_path / "target.csv"
    csv.write_text("x,y\n" + "".join(f"{20 + 6 * math.cos(a):.6f},{30 + 3 * math.sin(a):.6f}\n" for a in t))
    loaded(d)
    action(d, "synthesize")
    Select(d.find_element(By.ID, "synth-kind")).select_by_value("path")
    d.find_element(By.ID, "synth-csv").send_keys(str(csv))
    wait_for(d, "return workbench.state().curve === 24")
    assert np.allclose(js(d, "return workbench.curve()")[0], [26.0, 30.0])
    budget = d.find_element(By.ID, "synth-budget")
    budget.clear()
    budget.send_keys("480")
    d.find_element(By.ID, "synth-run").click()
    wait_for(d, "return document.querySelectorAll('[data-result]').length > 0", 300)
    d.find_element(By.CSS_SELECTOR, '[data-result="1"]').click()
    wait_for(d, "return workbench.state().undo === 2 && !workbench.state().pending", 60)
    assert "path synthesis" in js(d, "return workbench.model()")


def test_motion_poses_placed_and_turned_on_the_canvas_give_a_fourbar_through_them(page, tmp_path):
    d = page
    loaded(d)
    tool(d, "pose")
    want = [(0.0, 20.0, 0.0), (20.0, 30.0, 20.0), (40.0, 30.0, 45.0)]
    for x, y, a in want:
        px, py = screen(d, x, y)
        r = math.radians(a)
        drag(d, [(px, py), (px + 60 * math.cos(r), py - 60 * math.sin(r))])
    poses = js(d, "return workbench.poses()")
    assert len(poses) == 3
    for (x, y, a), p in zip(want, poses):
        assert math.hypot(p[0] - x, p[1] - y) < 0.6 and abs(p[2] - a) < 1.5, (p, (x, y, a))
    # drag the third pose's point to another place, turn the first pose by its tip
    drag(d, [screen(d, *poses[2][:2]), screen(d, 45.0, 25.0)])
    tip = [v + 36 * k for v, k in zip(screen(d, *poses[0][:2]), (1, 0))]
    drag(d, [tip, [tip[0] - 10, tip[1] - 20]])
    poses = js(d, "return workbench.poses()")
    assert math.hypot(poses[2][0] - 45, poses[2][1] - 25) < 0.6 and poses[0][2] > 10
    shot(d, tmp_path, "poses")
    steps = settled(d)["undo"]  # the load, and each pose added, moved or turned: one step each
    assert steps == 1 + 3 + 2, steps
    action(d, "synthesize")
    Select(d.find_element(By.ID, "synth-kind")).select_by_value("motion")
    d.find_element(By.ID, "synth-run").click()
    wait_for(d, "return document.querySelectorAll('[data-result]').length > 0", 120)
    d.find_element(By.CSS_SELECTOR, '[data-result="1"]').click()
    wait_for(d, f"return workbench.state().undo === {steps + 1} && !workbench.state().pending", 60)
    text = js(d, "return workbench.model()")
    assert "motion synthesis" in text
    # the coupler passes through every pose: the library solves the inserted model
    from gearlever.mechanism import Mechanism

    m = Mechanism.from_dict(tomllib.loads(text))
    turn = np.linspace(0, 2 * np.pi, 3600)
    # both ways from the sketch: a rocking crank reaches the poses on one side of it or the other
    rs = [m.solve(m.sketch_inputs[0] + k * turn) for k in (1, -1)]
    path = {n: np.concatenate([r.point[n] for r in rs]) for n in m.model.points}
    best = min(max(np.nanmin(np.hypot(*(path[n] - np.array(p[:2])).T)) for p in poses) for n in path)
    assert best < 0.05, best


def test_forces_of_two_inputs_hold_the_second_as_the_cycle_drawn_does(page):
    from tests.workbench._client import example_text

    d = page
    loaded(d, example_text("fivebar_two_inputs"))
    d.find_element(By.ID, "show-forces").click()
    wait_for(d, "return workbench.state().forces === 'ready'")
    text = d.find_element(By.ID, "torque").text
    assert "T left " in text and "T right " in text
    # the forces' frames are the drawn frames: the first input turns (60 rpm), the second is held
    f = js(d, "return workbench.forces()")
    assert math.isclose(f["speeds"]["left"], 2 * math.pi) and f["speeds"]["right"] == 0
    assert np.allclose(f["input_deg"], js(d, "return workbench.frames().input_deg"))


def chain(stages: int) -> str:
    """A crank and ``stages`` ternary rockers in series, each driven by a coupler from the previous one."""
    lines = ['[mechanism]\nname = "chain"\nunits = "mm"\n\n[points]', "O2 = [0.0, 0.0]", "A = [10.0, 0.0]"]
    links, ground, prev = ['crank = ["O2", "A"]'], ['"O2"'], "A"
    for k in range(1, stages + 1):
        x = 40.0 * k
        lines += [f"O{2 * k + 2} = [{x}, 0.0]", f"P{k} = [{x + 5.1}, 28.3]", f"Q{k} = [{x + 8.0}, 20.0]"]
        ground.append(f'"O{2 * k + 2}"')
        links += [f'coupler{k} = ["{prev}", "P{k}"]', f'rocker{k} = ["O{2 * k + 2}", "P{k}", "Q{k}"]']
        prev = f"Q{k}"
    lines += ["", "[links]", f"ground = [{', '.join(ground)}]", *links, "", "[[inputs]]", 'link = "crank"', ""]
    return "\n".join(lines)


def test_kennedy_box_asks_the_server_for_the_centres_of_a_model_past_the_default_size(page):
    d = page
    loaded(d, chain(4))  # 10 bodies: centres are answered by default up to 8
    assert js(d, "return workbench.frames().centres") is None
    d.find_element(By.ID, "show-kennedy").click()
    wait_for(d, "const f = workbench.frames(); return f && f.centres && !workbench.state().pending", 60)
    f = js(d, "return workbench.frames()")
    assert len(f["centres"]) == 45 and len(f["kennedy"]) == 120
    assert js(d, "return document.querySelectorAll('[data-kennedy]').length") > 50
