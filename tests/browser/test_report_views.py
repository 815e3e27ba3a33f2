"""The 3D views (docs/views.md) in a real browser, opened from file:// with no network: every view of the report of
`needlekit reproduce --quick` renders (its canvas is not blank), follows its load-step slider (an FE run) or its
colour select and a click on a needle (a patch fit), and the console stays free of errors; the same for the
NAME_view.html and patch_view.html that `indent --out` and `patch --out` write, and for the view of a needle array,
whose needles show their puncture state and depth per step as the run's JSON has them. Screenshots go under the build tree
(chromium_session.screenshot).
"""
import io
import json
import os
import pathlib
import subprocess
import time

import pytest
from PIL import Image, ImageChops, ImageStat
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

from chromium_session import chromium, console_errors, screenshot

CLI = os.environ.get("NEEDLEKIT_CLI", "build/bin/needlekit")
SOURCE = pathlib.Path(os.environ.get("NEEDLEKIT_SOURCE_DIR", "."))


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    """A quick reproduce run (exit 0: every section ran)."""
    out = tmp_path_factory.mktemp("reproduce")
    run = subprocess.run([CLI, "reproduce", "--quick", "--out", str(out)], capture_output=True, text=True,
                         timeout=480)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    return out


def canvas_image(canvas):
    return Image.open(io.BytesIO(canvas.screenshot_as_png)).convert("RGB")


def pixel_spread(image):
    """The standard deviation of the pixels' grey levels (0 for a blank canvas)."""
    return ImageStat.Stat(image.convert("L")).stddev[0]


def difference(a, b):
    """The mean absolute difference of two images' grey levels."""
    return ImageStat.Stat(ImageChops.difference(a.convert("L"), b.convert("L"))).mean[0]


def wait_for_views(driver, count, seconds=60):
    deadline = time.time() + seconds
    while time.time() < deadline:
        mounted = driver.execute_script(
            "return window.needlekitViewer ? window.needlekitViewer.mounted.length : -1")
        if mounted == count:
            return
        time.sleep(0.2)
    raise AssertionError(f"{mounted} of {count} views mounted after {seconds} s")


def move_slider(driver, slider, value):
    driver.execute_script("arguments[0].value = arguments[1];"
                          "arguments[0].dispatchEvent(new Event('input', {bubbles: true}));", slider, str(value))


def click_a_needle(driver, host, index):
    """Clicks the needle's centre on the canvas (projected by the view's camera); returns the info box's text."""
    canvas = host.find_element(By.CSS_SELECTOR, ".nk-canvas")
    x, y = driver.execute_script("""
        var view = window.needlekitViewer.mounted[arguments[0]], mesh = view.needleMeshes[0];
        var box = new THREE.Box3().setFromObject(mesh), p = box.getCenter(new THREE.Vector3()).project(view.camera);
        var r = view.canvas.getBoundingClientRect();
        return [(p.x / 2) * r.width, (-p.y / 2) * r.height];""", index)
    ActionChains(driver).move_to_element_with_offset(canvas, int(round(x)), int(round(y))).click().perform()
    info = host.find_element(By.CSS_SELECTOR, ".nk-info")
    return info.text if info.is_displayed() else ""


def check_views(driver, prefix):
    """Every mounted view: not blank; the slider (FE) or the select (patch) changes the picture; a patch needle
    answers a click with its numbers. Returns the views' names."""
    hosts = driver.find_elements(By.CSS_SELECTOR, ".nk-view")
    names = []
    for index, host in enumerate(hosts):
        name = host.get_attribute("data-view-name")
        names.append(name)
        driver.execute_script("arguments[0].scrollIntoView({block: 'center'});", host)
        canvas = host.find_element(By.CSS_SELECTOR, ".nk-canvas")
        before = canvas_image(canvas)
        assert pixel_spread(before) > 5, f"{name}: the canvas is blank"
        screenshot(driver, f"{prefix}_{name}")
        sliders = host.find_elements(By.CSS_SELECTOR, ".nk-step")
        kind = driver.execute_script("return window.needlekitViewer.mounted[arguments[0]].data.kind", index)
        if kind == "indentation":
            assert sliders, f"{name}: an FE view without a load-step slider"
            move_slider(driver, sliders[0], 0)
            after = canvas_image(canvas)
            assert difference(before, after) > 0.05, f"{name}: the picture does not change with the load step"
            screenshot(driver, f"{prefix}_{name}_first_step")
            move_slider(driver, sliders[0], sliders[0].get_attribute("max"))
            assert difference(before, canvas_image(canvas)) < 0.01, f"{name}: the last step is not drawn again"
        else:
            select = host.find_element(By.CSS_SELECTOR, ".nk-field")
            options = select.find_elements(By.TAG_NAME, "option")
            assert any("margin" in o.text for o in options), f"{name}: no margin to colour the needles by"
            text = click_a_needle(driver, host, index)
            assert "buckling force" in text and "status" in text, f"{name}: a click shows '{text}'"
            screenshot(driver, f"{prefix}_{name}_clicked")
            Select(select).select_by_index(len(options) - 1)  # colour by status
            assert difference(before, canvas_image(canvas)) > 0.01, f"{name}: the colours do not change"
        bar = host.find_element(By.CSS_SELECTOR, ".nk-colour-bar").text
        assert "(" in bar or "status" in bar, f"{name}: the colour bar '{bar}' names no unit"
    return names


def test_the_reports_3d_views_render_follow_the_slider_and_log_no_errors(report_dir):
    results = json.loads((report_dir / "results.json").read_text())
    views = [v for s in results["sections"] for v in s.get("views", [])]
    assert "viewer" in results, results.get("viewer_error")
    fe_views = [v for v in views if v["name"].startswith("6_2_")]
    patch_views = [v for v in views if v["name"].startswith("6_4_")]
    assert len(fe_views) >= 3 and len(patch_views) >= 2, [v["name"] for v in views]
    for view in views:  # the 5 MB budget
        assert (report_dir / view["script"]).stat().st_size <= 5e6
    with chromium() as driver:
        driver.get((report_dir / "report.html").as_uri())
        wait_for_views(driver, len(views))
        assert console_errors(driver) == []
        names = check_views(driver, "report_view")
        assert sorted(names) == sorted(v["name"] for v in views)
        assert console_errors(driver) == []


def test_the_view_page_of_indent_out(tmp_path):
    out = tmp_path / "indent"
    run = subprocess.run([CLI, "indent", str(SOURCE / "examples" / "indent_flat_punch.toml"), "--out", str(out),
                          "--size-at-tip", "120 um", "--size-far", "600 um", "--steps", "3"],
                         capture_output=True, text=True, timeout=240)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    pages = list(out.glob("*_view.html"))
    assert len(pages) == 1 and (out / "viewer" / "three.min.js").is_file()
    with chromium() as driver:
        driver.get(pages[0].as_uri())
        wait_for_views(driver, 1)
        check_views(driver, "indent_view")
        assert console_errors(driver) == []


def test_the_view_page_of_patch_out(tmp_path):
    out = tmp_path / "patch"
    run = subprocess.run([CLI, "patch", str(SOURCE / "examples" / "patch_neck_flexible.toml"), "--out", str(out)],
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    assert (out / "patch_view.html").is_file() and (out / "viewer" / "OrbitControls.js").is_file()
    with chromium() as driver:
        driver.get((out / "patch_view.html").as_uri())
        wait_for_views(driver, 1)
        check_views(driver, "patch_view")
        assert console_errors(driver) == []


def test_the_view_page_of_an_array_run(tmp_path):
    """A coarse 3 x 3 array (examples/indent_array_3x3.toml): the needles are coloured by their puncture state, the
    legend counts the needles the run's JSON says punctured by each step, the depth colours differ, and a click on a
    needle shows its position, force, depth and puncture step."""
    out = tmp_path / "array"
    run = subprocess.run([CLI, "indent", str(SOURCE / "examples" / "indent_array_3x3.toml"), "--out", str(out),
                          "--size-at-tip", "60 um", "--size-far", "400 um", "--steps", "3", "--no-plot"],
                         capture_output=True, text=True, timeout=240)
    assert run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]
    result = json.loads((out / "array_3x3_result.json").read_text())
    needles = result["needles"]
    assert len(needles) == 9 and len(result["depth_um"]) == 3
    with chromium() as driver:
        driver.get((out / "array_3x3_view.html").as_uri())
        wait_for_views(driver, 1)
        host = driver.find_element(By.CSS_SELECTOR, ".nk-view")
        select = Select(host.find_element(By.CSS_SELECTOR, ".nk-field"))
        assert select.first_selected_option.text == "needles: puncture state"
        slider = host.find_element(By.CSS_SELECTOR, ".nk-step")
        for step in range(3):
            move_slider(driver, slider, step)
            chips = {c.get_attribute("data-status"): int(c.text.split()[-1])
                     for c in host.find_elements(By.CSS_SELECTOR, ".nk-colour-bar .nk-chip")}
            punctured = sum(1 for n in needles if n["punctured"] and n["puncture_step"] <= step + 1)
            assert chips.get("punctured", 0) == punctured and chips.get("intact", 0) == 9 - punctured, (step, chips)
        screenshot(driver, "array_view_state_last_step")
        check_views(driver, "array_view")  # not blank, follows the slider
        canvas = host.find_element(By.CSS_SELECTOR, ".nk-canvas")
        by_state = canvas_image(canvas)
        select.select_by_visible_text("needles: inserted depth (um)")
        assert difference(by_state, canvas_image(canvas)) > 0.01, "the depth colours look like the state colours"
        bar = host.find_element(By.CSS_SELECTOR, ".nk-colour-bar").text
        inserted = [n["inserted_depth_um"] for n in needles]  # at the last step, shown now
        assert bar.split() == ["needles:", "inserted", "depth", "(um)", f"{min(inserted):.4g}", f"{max(inserted):.4g}"]
        screenshot(driver, "array_view_depth")
        text = click_a_needle(driver, host, 0)
        for label in ("x (um)", "y (um)", "force (N)", "tip depth (um)", "puncture state", "punctured at step"):
            assert label in text, f"a click on a needle shows '{text}'"
        first = needles[0]
        rows = dict(line.rsplit(" ", 1) for line in text.splitlines()[1:])
        assert float(rows["x (um)"]) == pytest.approx(first["x_um"], rel=1e-3)
        assert float(rows["force (N)"]) == pytest.approx(first["force_N"][-1], rel=1e-3)
        assert float(rows["tip depth (um)"]) == pytest.approx(first["depth_um"][-1], rel=1e-3)
        assert rows["punctured at step"] == (str(first["puncture_step"]) if first["punctured"] else "–")
        screenshot(driver, "array_view_clicked")
        assert console_errors(driver) == []
