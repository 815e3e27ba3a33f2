"""The design page of `needlekit serve` in headless Chromium: the index it shows equals `needlekit evaluate --json`
for the same design to the printed digits, as a value moves and as the form changes; an out-of-range value shows the
CLI's message next to its field; the TOML it downloads is read by `needlekit evaluate`; the optimizer and the
uncertainty analysis run with a progress bar; the console stays free of errors. Screenshots go under the build tree."""
import io
import json
import re
import subprocess

import pytest
from PIL import Image, ImageStat
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select, WebDriverWait

from chromium_session import chromium, console_errors, screenshot
from serve_fixture import CLI, EXAMPLES, after_location, cli_error, cli_json, server, toml_text  # noqa: F401


@pytest.fixture(scope="module")
def page(server):
    with chromium() as driver:
        driver.get(server.url + "/")
        WebDriverWait(driver, 30).until(lambda d: d.execute_script("return document.body.dataset.ready === 'true'"))
        yield driver


def shown_index(driver):
    return driver.find_element(By.ID, "performance-index").text


def same_to_printed_digits(shown, value):
    """`shown` is `value` rounded to the digits it prints (toPrecision(6))."""
    return float(shown) == float(f"{value:.6g}")


def wait_for_answer(driver):
    """Waits until the page shows the answer for its latest value."""
    WebDriverWait(driver, 15).until(lambda d: d.execute_script("return document.body.dataset.pending") == "false")


def set_text(driver, element_id, text):
    """Types into a field as a user would, and waits until the page shows the answer for it."""
    field = driver.find_element(By.ID, element_id)
    field.clear()
    field.send_keys(text)
    assert driver.execute_script("return document.getElementById(arguments[0]).value", element_id) == text
    wait_for_answer(driver)


def cli_for_page(driver, tmp_path, name):
    """`needlekit evaluate --json` of the TOML file the page downloads for its current design."""
    path = tmp_path / f"{name}.toml"
    path.write_text(driver.execute_script("return window.needlekitDesign.tomlText()"))
    return cli_json("evaluate", str(path))


def test_the_index_shown_is_the_clis(page, tmp_path):
    expected = cli_json("evaluate", str(EXAMPLES / "evaluate_table_6_1_cone.toml"))
    assert same_to_printed_digits(shown_index(page), expected["performance_index_per_um"]), shown_index(page)
    assert page.find_element(By.ID, "status").text == expected["status"]
    assert console_errors(page) == []
    screenshot(page, "design_page_table_6_1_cone")


def test_moving_values_and_changing_the_form_follow_the_cli(page, tmp_path):
    set_text(page, "tip_diameter", "50 um")
    set_text(page, "length", "600 um")
    set_text(page, "angle", "12 deg")
    Select(page.find_element(By.ID, "material")).select_by_value("su-8")
    wait_for_answer(page)
    page.find_element(By.ID, "hollow").click()
    wait_for_answer(page)
    set_text(page, "bore_diameter", "25 um")
    set_text(page, "needles_per_row", "15")
    design = page.execute_script("return window.needlekitDesign.designJson()")
    assert design["needle"] == {"shape": "cone", "tip_diameter": "50 um", "base_diameter": "150 um",
                                "bore_diameter": "25 um", "length": "600 um", "material": "su-8"}
    expected = cli_for_page(page, tmp_path, "moved")
    assert same_to_printed_digits(shown_index(page), expected["performance_index_per_um"]), shown_index(page)
    buckling = page.find_element(By.CSS_SELECTOR, "#margin-buckling .ok").text
    assert buckling == ("ok" if expected["buckling_ok"] else "FAILS")
    # a slider moves the value in its unit
    slider = page.find_element(By.ID, "base_diameter-slider")
    page.execute_script("arguments[0].value = 200; arguments[0].dispatchEvent(new Event('input'))", slider)
    assert page.execute_script("return window.needlekitDesign.designJson().needle.base_diameter") == "200 um"
    wait_for_answer(page)
    expected = cli_for_page(page, tmp_path, "slider")
    assert same_to_printed_digits(shown_index(page), expected["performance_index_per_um"]), shown_index(page)
    assert console_errors(page) == []
    screenshot(page, "design_page_moved")


@pytest.mark.parametrize("case, value", [("negative", "-30 um"), ("bare_number", "30"), ("wrong_unit", "30 kg")])
def test_an_out_of_range_value_shows_the_clis_message_next_to_its_field(page, tmp_path, case, value):
    set_text(page, "tip_diameter", value)
    message = page.find_element(By.CSS_SELECTOR, '.field[data-key="needle.tip_diameter"] .error').text
    path = tmp_path / "bad.toml"
    path.write_text(page.execute_script("return window.needlekitDesign.tomlText()"))
    cli_message = cli_error("evaluate", str(path))
    assert "key 'needle.tip_diameter'" in cli_message
    assert after_location(message) == after_location(cli_message)
    assert page.find_element(By.ID, "performance-index").text == "–"
    screenshot(page, f"design_page_bad_tip_diameter_{case}")
    # The only console entries are the browser's own notes of the 400 answer.
    errors = console_errors(page)
    assert all("/api/evaluate" in e["message"] and "400" in e["message"] for e in errors), errors
    set_text(page, "tip_diameter", "50 um")
    assert page.find_element(By.CSS_SELECTOR, '.field[data-key="needle.tip_diameter"] .error').text == ""


def test_the_optimizer_and_the_uncertainty_analysis_run_with_a_progress_bar(page, tmp_path):
    set_text(page, "angle", "0 deg")  # the optimizer's space has no angle: Fig 6.20 is at 0 deg
    Select(page.find_element(By.ID, "material")).select_by_value("silicon")
    if page.find_element(By.ID, "hollow").is_selected():
        page.find_element(By.ID, "hollow").click()
    wait_for_answer(page)
    page.find_element(By.ID, "run-optimize").click()
    WebDriverWait(page, 120).until(lambda d: d.find_elements(By.ID, "use-optimum"))
    assert page.find_element(By.ID, "optimize-progress").get_attribute("value") == "1"
    expected = cli_json("optimize", str(EXAMPLES / "optimize_fig_6_20_cone_solid.toml"), "--top", "5")
    shown = page.find_element(By.ID, "optimize-result").text
    assert f"n = {expected['best']['needles_per_row']}," in shown
    assert same_to_printed_digits(shown.split("PI = ")[1].split()[0], expected["best"]["performance_index_per_um"])
    page.find_element(By.ID, "use-optimum").click()
    wait_for_answer(page)
    assert same_to_printed_digits(shown_index(page), expected["best"]["performance_index_per_um"])
    screenshot(page, "design_page_optimum")

    page.find_element(By.ID, "run-uncertainty").click()
    WebDriverWait(page, 120).until(lambda d: "P(success) =" in d.find_element(By.ID, "uncertainty-result").text)
    assert page.find_element(By.ID, "uncertainty-progress").get_attribute("value") == "1"
    assert console_errors(page) == [] or all("400" in e["message"] for e in console_errors(page))
    screenshot(page, "design_page_uncertainty")


def test_a_robust_design_runs_with_a_progress_bar(page):
    """A level of P(success) makes the optimizer a robust design (the uncertainty inputs of the page): the design found
    meets the level, after a progress bar that ends full."""
    page.find_element(By.ID, "r-min-success").send_keys("0.9")
    samples = page.find_element(By.ID, "u-samples")
    samples.clear()
    samples.send_keys("256")
    space = page.execute_script("return window.needlekitDesign.spaceJson()")
    assert space["min_success_probability"] == 0.9 and space["sampling"]["samples"] == 256
    page.find_element(By.ID, "run-optimize").click()
    WebDriverWait(page, 150).until(lambda d: "robust: P(success) =" in d.find_element(By.ID, "optimize-result").text
                                   or "error" in d.find_element(By.ID, "optimize-result").get_attribute("class"))
    shown = page.find_element(By.ID, "optimize-result").text
    assert page.find_element(By.ID, "optimize-progress").get_attribute("value") == "1", shown
    probability = float(shown.split("robust: P(success) = ")[1].split()[0])
    assert probability >= 0.9, shown
    screenshot(page, "design_page_robust")
    page.find_element(By.ID, "r-min-success").clear()
    assert "min_success_probability" not in page.execute_script("return window.needlekitDesign.spaceJson()")


def printed(value):
    """`value` to the 4 significant digits the page prints (Number.toPrecision(4)), as a number."""
    return float(f"{value:.4g}")


RANGE = re.compile(r"^(\S+) \.\. (\S+) (\S+) \(mean (\S+)\)$")


def assert_the_patch_numbers_are_the_clis(page, tmp_path):
    """The fit shown is `needlekit patch --json`'s for the case the page sent: every number of its table to the
    digits printed. Returns the CLI's JSON."""
    case = page.execute_script("return window.needlekitDesign.patchJson()")
    case["surface"]["mesh"] = str(EXAMPLES.parent / "data" / "meshes" / case["surface"]["mesh"])
    path = tmp_path / "patch.toml"
    path.write_text(toml_text(case))
    # Exit code 3 is a fit that ended with a numerical status (e.g. not converged): its JSON is still the result.
    done = subprocess.run([CLI, "patch", str(path), "--json"], capture_output=True, text=True)
    assert done.returncode in (0, 3), done
    expected = json.loads(done.stdout)
    assert page.find_element(By.ID, "patch-result").text == \
        f"done: {expected['penetrating']} of {expected['needles']} needles penetrate"
    # Every number of the table is the CLI's to the digits printed.
    rows = {r.find_elements(By.TAG_NAME, "td")[0].text: r.find_elements(By.TAG_NAME, "td")[1].text
            for r in page.find_elements(By.CSS_SELECTOR, "#patch-numbers tr")}
    assert rows["needles penetrating / buckled / bent"] == \
        f"{expected['penetrating']} / {expected['buckled']} / {expected['bent']} of {expected['needles']}"
    assert rows["fit"].startswith(f"{expected['kind']}: {expected['status']}")
    for label, key in [("insertion angle", "angle_deg"), ("buckling force |F|/cos", "buckling_force_N"),
                       ("bending force |F| tan", "bending_force_N"), ("travel x (Eq 5.12)", "travel_um"),
                       ("performance index", "performance_index_per_um")]:
        low, high, _, mean = RANGE.match(rows[label]).groups()
        assert [float(low), float(high), float(mean)] == \
            [printed(expected[key][k]) for k in ("min", "max", "mean")], (label, rows[label], expected[key])
    assert float(rows["spring energy"].split()[1]) == printed(expected["spring_energy_mJ"]["total"])
    return expected


def test_the_patch_tab_fits_a_patch_as_the_cli_does_and_shows_it_in_3d(page, tmp_path):
    meshes = [o.get_attribute("value") for o in page.find_elements(By.CSS_SELECTOR, "#p-mesh option")]
    assert "vh_male_head_neck_loop2.obj" in meshes
    Select(page.find_element(By.ID, "p-mesh")).select_by_value("vh_male_head_neck_loop2.obj")
    assert page.find_element(By.ID, "p-center").get_attribute("value") == "2243"  # from examples/patch_neck_*.toml
    page.find_element(By.ID, "run-patch").click()
    WebDriverWait(page, 180).until(lambda d: d.find_element(By.ID, "patch-result").text.startswith("done"))
    expected = assert_the_patch_numbers_are_the_clis(page, tmp_path)
    # The fit in 3D: the body, the springs and one cylinder per needle, drawn (not blank), a needle's numbers on a
    # click.
    host = page.find_element(By.CSS_SELECTOR, "#patch-view.nk-view")  # the viewer mounts into the element itself
    page.execute_script("arguments[0].scrollIntoView({block: 'center'})", host)
    canvas = host.find_element(By.CSS_SELECTOR, ".nk-canvas")
    image = Image.open(io.BytesIO(canvas.screenshot_as_png)).convert("L")
    assert ImageStat.Stat(image).stddev[0] > 5, "the patch's 3D view is blank"
    view = "window.needlekitDesign.patchView()"
    assert page.execute_script(f"return {view}.needleMeshes.length") == expected["needles"]
    assert page.execute_script(f"return {view}.data.kind") == "patch"
    x, y = page.execute_script(f"""
        var v = {view}, box = new THREE.Box3().setFromObject(v.needleMeshes[0]);
        var p = box.getCenter(new THREE.Vector3()).project(v.camera), r = v.canvas.getBoundingClientRect();
        return [(p.x / 2) * r.width, (-p.y / 2) * r.height];""")
    ActionChains(page).move_to_element_with_offset(canvas, int(round(x)), int(round(y))).click().perform()
    info = host.find_element(By.CSS_SELECTOR, ".nk-info")
    assert info.is_displayed() and "buckling force" in info.text, info.text
    assert console_errors(page) == [] or all("400" in e["message"] for e in console_errors(page))
    screenshot(page, "design_page_patch_3d")
    page.execute_script("document.getElementById('patch-numbers').scrollIntoView()")
    screenshot(page, "design_page_patch")


def test_the_patch_tab_uploads_a_mesh(page):
    mesh = EXAMPLES.parent / "data" / "meshes" / "skull_yahoojapan_10k.obj"
    page.find_element(By.ID, "p-upload").send_keys(str(mesh))
    page.find_element(By.ID, "upload-mesh").click()
    WebDriverWait(page, 60).until(lambda d: "triangles" in d.find_element(By.ID, "upload-result").text)
    assert page.find_element(By.ID, "upload-result").text.endswith(": 10312 triangles")
    chosen = page.find_element(By.ID, "p-mesh").get_attribute("value")
    assert chosen.startswith("upload-") and chosen.endswith(".obj")
    assert console_errors(page) == [] or all("400" in e["message"] for e in console_errors(page))


def body_view_shown(driver, mesh):
    """Waits until the patch tab draws the body `mesh` (POST /api/body-view) and returns its canvas."""
    WebDriverWait(driver, 60).until(lambda d: d.execute_script(
        "var v = window.needlekitDesign.bodyView(); return document.body.dataset.bodyView === 'ready' && v !== null"
        " && v.data.name === arguments[0]", mesh))
    canvas = driver.find_element(By.CSS_SELECTOR, "#body-view .nk-canvas")
    driver.execute_script("arguments[0].scrollIntoView({block: 'center'})", canvas)
    return canvas


def test_a_click_on_the_body_places_the_patch_and_the_fit_runs_there_as_the_cli_does(page, tmp_path):
    """The patch tab draws the chosen body before any fit; a click on it puts the nearest vertex of the triangle hit
    into the centre field (a vertex of the full mesh, next to the spot clicked) and the approach along the normal
    there; the fit then runs there, with a progress bar that moves, and its numbers are `needlekit patch --json`'s
    for a case file with that vertex and approach."""
    console_errors(page)  # the earlier tests' notes of 400 answers
    mesh = "vh_male_head_neck_loop2.obj"
    Select(page.find_element(By.ID, "p-mesh")).select_by_value(mesh)
    canvas = body_view_shown(page, mesh)
    image = Image.open(io.BytesIO(canvas.screenshot_as_png)).convert("L")
    assert ImageStat.Stat(image).stddev[0] > 5, "the body's 3D view is blank"
    screenshot(page, "design_page_body_before_click")
    assert page.find_element(By.ID, "p-center").get_attribute("value") == "2243"
    view = "window.needlekitDesign.bodyView()"
    # The spot: a drawn vertex facing the camera (+z, the front of the neck) below the middle of the canvas, where a
    # ray from the camera meets the surface first.
    target, x, y = page.execute_script(f"""
        var v = {view}, p = v.surfacePositions, n = v.surfaceGeometry.getAttribute("normal");
        var r = v.canvas.getBoundingClientRect(), best = -1, bestScore = Infinity, screen = null;
        for (var k = 0; k < v.vertexCount; ++k) {{
          if (n.getZ(k) < 0.9) continue;
          var s = v.world.localToWorld(new THREE.Vector3(p[3 * k], p[3 * k + 1], p[3 * k + 2])).project(v.camera);
          var score = Math.abs(s.x) + Math.abs(s.y + 0.3);
          if (score < bestScore) {{ bestScore = score; best = k; screen = s; }}
        }}
        return [v.vertexIds[best], (screen.x / 2) * r.width, (-screen.y / 2) * r.height];""")
    ActionChains(page).move_to_element_with_offset(canvas, int(round(x)), int(round(y))).click().perform()
    WebDriverWait(page, 30).until(lambda d: d.execute_script("return document.body.dataset.bodyPick") == "done")
    pick = page.execute_script(f"return {view}.lastPick")  # on the decimated view
    answer = page.execute_script("return window.needlekitDesign.lastBodyPick()")  # the same ray on the full mesh
    center = int(page.find_element(By.ID, "p-center").get_attribute("value"))
    assert center == answer["vertex"] != 2243
    assert page.find_element(By.ID, "p-approach").get_attribute("value") == "normal"
    # The vertex of the mesh the fit reads (unit 1 m) that the click means: a corner of the full mesh's triangle that
    # the ray met, the nearest of its three to where it met it, so within that triangle's longest edge (about the
    # mesh's 1.6 mm median edge, not the view's 8.5 mm cells).
    lines = (EXAMPLES.parent / "data" / "meshes" / mesh).read_text().splitlines()
    vertices = [[float(x) for x in line.split()[1:4]] for line in lines if line.startswith("v ")]
    faces = [[int(k) - 1 for k in line.split()[1:4]] for line in lines if line.startswith("f ")]
    distance = lambda a, b: sum((a[c] - b[c]) ** 2 for c in range(3)) ** 0.5  # noqa: E731
    corners = faces[answer["triangle"]]
    assert center in corners, (center, corners)
    hit = answer["point_m"]
    assert distance(vertices[center], hit) == min(distance(vertices[k], hit) for k in corners)
    longest_edge = max(distance(vertices[corners[i]], vertices[corners[i - 1]]) for i in range(3))
    assert distance(vertices[center], hit) <= longest_edge < 5e-3, (center, hit, longest_edge)
    assert vertices[center] == pytest.approx(answer["position_m"], abs=1e-9)
    # The full mesh and the decimated view are met by the same ray within the view's cell diagonal of each other.
    reach = 2 * 3 ** 0.5 * page.execute_script(f"return {view}.data.cell_size_m")
    assert distance(hit, pick["point"]) <= reach, (hit, pick)
    assert distance(vertices[center], vertices[target]) <= reach, (center, target)
    assert answer["normal"][2] > 0.5, answer  # the front of the neck faces +z
    assert page.execute_script(f"return {view}.marker !== null")
    screenshot(page, "design_page_body_clicked")

    # The equilibrium fit, 16 x 16 needles: Newton iterations that last long enough for the page's 100 ms polls to
    # show the bar between the mesh read and the end (a flexible fit of the neck takes 1 ms).
    Select(page.find_element(By.ID, "p-kind")).select_by_value("equilibrium")
    needles = page.find_element(By.ID, "p-n")
    needles.clear()
    needles.send_keys("16")
    page.find_element(By.ID, "run-patch").click()
    WebDriverWait(page, 180).until(lambda d: d.find_element(By.ID, "patch-result").text.startswith("done"))
    case = page.execute_script("return window.needlekitDesign.patchJson()")
    assert case["surface"]["center_vertex"] == center and case["surface"]["approach"] == "normal"
    assert_the_patch_numbers_are_the_clis(page, tmp_path)
    # The progress bar moved: fractions that never decrease, some strictly between 0 and 1, ending full.
    shown = page.execute_script("return window.needlekitDesign.jobFractions('patch')")
    assert shown == sorted(shown) and shown[-1] == 1 and any(0 < f < 1 for f in shown), shown
    print(f"patch job progress shown: {shown}")
    host = page.find_element(By.CSS_SELECTOR, "#patch-view.nk-view")
    page.execute_script("arguments[0].scrollIntoView({block: 'center'})", host)
    screenshot(page, "design_page_body_clicked_fit")
    # Typing a vertex moves the mark when the view draws it.
    drawn = page.execute_script(f"return {view}.vertexIds[0]")
    field = page.find_element(By.ID, "p-center")
    field.clear()
    field.send_keys(str(drawn))
    assert page.execute_script(f"return {view}.marker !== null")
    assert console_errors(page) == []
