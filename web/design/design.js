// needlekit serve's design page: builds a design as JSON with the keys and unit strings of a design TOML file,
// asks POST /api/evaluate as a value moves (debounced), and shows the index, the failure margins, the needle in 3D
// (three.js from Debian's libjs-three, classic scripts) and the API's messages next to their field. The optimizer
// and the uncertainty analysis run as jobs (POST /api/optimize, /api/uncertainty) polled for their progress.
"use strict";

(function () {
  const $ = (id) => document.getElementById(id);
  const QUANTITY_FIELDS = ["tip_diameter", "base_diameter", "bore_diameter", "length", "width", "angle",
                           "target_depth"];
  let evaluateTimer = null;
  let evaluateSequence = 0;
  let view = null;
  let patchView = null;  // the last fit's 3D view (web/viewer/needlekit_viewer.js)
  let bodyView = null;   // the chosen body mesh's view, where a click places the patch (POST /api/body-view)
  let pickSequence = 0;  // the clicks on the body's view; only the last one's answer is used
  let lastBodyPick = null;  // the last answer of POST /api/body-pick
  let bodySequence = 0;
  const jobFractions = {};  // per job kind: the fractions its progress bar showed, in order (for the tests)

  // ---- the design as JSON (the same keys and unit strings as a design TOML file) --------------------------------

  // An integer when the text is one, else the text itself, so that the API names what is wrong with it.
  function integerOrText(text) {
    const trimmed = text.trim();
    return /^-?\d+$/.test(trimmed) ? parseInt(trimmed, 10) : trimmed;
  }

  function designJson() {
    const shape = $("shape").value;
    const needle = { shape: shape, tip_diameter: $("tip_diameter").value.trim() };
    if (shape !== "cylinder") needle.base_diameter = $("base_diameter").value.trim();
    if ($("hollow").checked) needle.bore_diameter = $("bore_diameter").value.trim();
    needle.length = $("length").value.trim();
    needle.material = $("material").value;
    return {
      needle: needle,
      array: { needles_per_row: integerOrText($("needles_per_row").value), width: $("width").value.trim() },
      tissue: { model: $("tissue").value },
      insertion: { angle: $("angle").value.trim(), target_depth: $("target_depth").value.trim() },
    };
  }

  function tomlValue(value) {
    if (typeof value === "number" || typeof value === "boolean") return String(value);
    return JSON.stringify(String(value));  // a TOML basic string has JSON's escapes
  }

  // The design as a TOML file that `needlekit evaluate` reads.
  function tomlText(design) {
    const lines = ["# needlekit design file, written by the design page of `needlekit serve`"];
    for (const [table, entries] of Object.entries(design)) {
      lines.push("", `[${table}]`);
      for (const [key, value] of Object.entries(entries)) lines.push(`${key} = ${tomlValue(value)}`);
    }
    return lines.join("\n") + "\n";
  }

  // ---- talking to the API ---------------------------------------------------------------------------------------

  async function postJson(url, body) {
    const response = await fetch(url, {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
    });
    return { status: response.status, json: await response.json() };
  }

  function clearErrors() {
    for (const field of document.querySelectorAll(".field")) {
      field.classList.remove("invalid");
      field.querySelector(".error").textContent = "";
    }
    $("form-error").textContent = "";
  }

  // The message next to the field whose key it names (needle.material.* next to the material), else below the form.
  function showError(error) {
    clearErrors();
    let key = error.key || "";
    if (key.startsWith("needle.material")) key = "needle.material";
    if (key.startsWith("tissue.")) key = "tissue.model";
    const field = key ? document.querySelector(`.field[data-key="${key}"]`) : null;
    if (field) {
      field.classList.add("invalid");
      field.querySelector(".error").textContent = error.error;
    } else {
      $("form-error").textContent = error.error;
    }
  }

  // body[data-pending] is "true" from a change until the answer for the latest value is shown.
  function scheduleEvaluate() {
    clearTimeout(evaluateTimer);
    document.body.dataset.pending = "true";
    evaluateTimer = setTimeout(() => { evaluateTimer = null; evaluate(); }, 120);
  }

  async function evaluate() {
    const sequence = ++evaluateSequence;
    const design = designJson();
    const answer = await postJson("/api/evaluate", design);
    if (sequence !== evaluateSequence) return;  // a newer value is on its way
    document.body.dataset.evaluated = String(sequence);
    if (evaluateTimer === null) document.body.dataset.pending = "false";
    if (answer.status !== 200) {
      showError(answer.json);
      $("performance-index").textContent = "–";
      $("status").textContent = "invalid";
      $("reason").textContent = "";
      for (const cell of document.querySelectorAll("#margins tbody td:not(:first-child)")) cell.textContent = "";
      return;
    }
    clearErrors();
    showResult(answer.json);
    drawNeedle(answer.json);
  }

  // ---- presenting the result ------------------------------------------------------------------------------------

  function number(value, digits) {
    return value === null || value === undefined ? "–" : Number(value).toPrecision(digits || 4);
  }

  function showMargin(id, load, capacity, unit, ok) {
    const row = $(id);
    row.querySelector(".load").textContent = load === null ? "–" : `${number(load)} ${unit}`;
    row.querySelector(".capacity").textContent = capacity === null ? "not assessed" : `${number(capacity)} ${unit}`;
    row.querySelector(".margin").textContent =
        load === null || capacity === null || load === 0 ? "–" : `${number(capacity / load, 3)}×`;
    const cell = row.querySelector(".ok");
    cell.textContent = ok === null ? "not assessed" : ok ? "ok" : "FAILS";
    cell.className = "ok " + (ok === null ? "" : ok ? "pass" : "fail");
  }

  function showResult(r) {
    $("performance-index").textContent = Number(r.performance_index_per_um).toPrecision(6);
    $("status").textContent = r.status;
    $("reason").textContent = r.reason || "";
    // Puncture: the needle travels d before the skin gives; it gets in when L > d and reaches T when L >= d + T.
    showMargin("margin-puncture", r.deformation_um, r.length_um, "um", r.permeation_depth_um > 0);
    showMargin("margin-buckling", Math.abs(r.buckling_force_N), r.critical_buckling_load_N, "N", r.buckling_ok);
    showMargin("margin-bending", Math.abs(r.bending_force_N), r.critical_bending_load_N, "N", r.bending_ok);
  }

  // ---- the needle in 3D, to scale (1 scene unit = 1 um) -----------------------------------------------------------

  function makeView() {
    const container = $("view");
    const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    renderer.setPixelRatio(window.devicePixelRatio);
    renderer.setSize(container.clientWidth, container.clientHeight);
    renderer.setClearColor(0xeef2f6);
    container.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 0.9));
    const light = new THREE.DirectionalLight(0xffffff, 0.6);
    light.position.set(1, 2, 1.5);
    scene.add(light);
    const camera = new THREE.PerspectiveCamera(35, container.clientWidth / container.clientHeight, 1, 1e6);
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    const v = { renderer, scene, camera, controls, mesh: null, grid: null, framedFor: null };
    v.render = () => renderer.render(scene, camera);
    controls.addEventListener("change", v.render);
    return v;
  }

  // The needle's profile turned about its axis: base at y = 0, tip at y = L, the bore through a hollow needle. A
  // bevel is drawn with its tip diameter (the lathe cannot show the slanted face).
  function drawNeedle(r) {
    if (!view) return;
    const rb = r.base_diameter_um / 2, rt = r.tip_diameter_um / 2, ri = r.bore_diameter_um / 2, L = r.length_um;
    const points = ri > 0
        ? [[ri, 0], [rb, 0], [rt, L], [ri, L], [ri, 0]]
        : [[0, 0], [rb, 0], [rt, L], [0, L]];
    const geometry = new THREE.LatheBufferGeometry(points.map(([x, y]) => new THREE.Vector2(x, y)), 64);
    const material = new THREE.MeshStandardMaterial({ color: 0x8fa3b8, metalness: 0.3, roughness: 0.5,
                                                       side: THREE.DoubleSide });
    if (view.mesh) {
      view.scene.remove(view.mesh);
      view.mesh.geometry.dispose();
      view.mesh.material.dispose();
    }
    view.mesh = new THREE.Mesh(geometry, material);
    view.scene.add(view.mesh);
    const size = Math.max(L, 2 * rb);
    const frame = Math.pow(10, Math.ceil(Math.log10(size)));
    if (view.framedFor !== frame) {  // re-frame only when the needle's order of magnitude changes
      if (view.grid) view.scene.remove(view.grid);
      view.grid = new THREE.GridHelper(frame, Math.round(frame / 100), 0x888888, 0xcccccc);  // 100 um squares
      view.scene.add(view.grid);
      view.camera.position.set(size * 1.2, size * 0.9, size * 1.6);
      view.controls.target.set(0, L / 2, 0);
      view.controls.update();
      view.framedFor = frame;
    }
    view.render();
  }

  // ---- jobs -------------------------------------------------------------------------------------------------------

  function rangeOf(id, integers) {
    const parts = $(id).value.split(",").map((s) => s.trim());
    return integers ? parts.map(integerOrText) : parts;
  }

  function spaceJson() {
    const d = designJson();
    const hollow = $("hollow").checked;
    const ranges = {
      needles_per_row: rangeOf("r-n", true),
      tip_diameter: rangeOf("r-tip_diameter"),
      width: rangeOf("r-width"),
      length: rangeOf("r-length"),
    };
    if (d.needle.shape !== "cylinder") ranges.base_diameter = rangeOf("r-base_diameter");
    if (hollow) ranges.bore_diameter = rangeOf("r-bore_diameter");
    const space = { shape: d.needle.shape, hollow: hollow, material: d.needle.material, tissue: d.tissue.model,
                    target_depth: d.insertion.target_depth, ranges: ranges };
    // Robust design: the level, and the uncertainty analysis's inputs and sampling.
    const level = $("r-min-success").value.trim();
    if (level !== "") {
      const u = uncertaintyJson();
      space.min_success_probability = /^[0-9.eE+-]+$/.test(level) ? Number(level) : level;
      space.uncertain = u.uncertain;
      space.sampling = u.sampling;
    }
    return space;
  }

  function uncertaintyJson() {
    const d = designJson();
    const sigma = Number($("u-sigma").value);
    d.uncertain = {
      "tissue.alpha": { distribution: "lognormal", sigma_log: sigma },
      "tissue.tau": { distribution: "lognormal", sigma_log: sigma },
      "needle.tip_diameter": { distribution: "normal", sd: $("u-tip_sd").value.trim() },
      "needle.length": { distribution: "normal", sd: $("u-length_sd").value.trim() },
      "insertion.angle": { distribution: "uniform", min: "0 deg", max: $("u-angle").value.trim() },
    };
    d.sampling = { samples: integerOrText($("u-samples").value), method: "sobol", seed: 2012 };
    return d;
  }

  // Submits a job, polls its progress into the bar, and calls done(result) at the end; the cancel button deletes it.
  async function runJob(name, url, body, done) {
    const run = $(`run-${name}`), cancel = $(`cancel-${name}`), bar = $(`${name}-progress`), out = $(`${name}-result`);
    out.textContent = "";
    bar.value = 0;
    const answer = await postJson(url, body);
    if (answer.status !== 202) {
      out.textContent = answer.json.error;
      out.className = "error";
      return;
    }
    out.className = "";
    const id = answer.json.id;
    const shown = jobFractions[name] = [];
    run.disabled = true;
    cancel.disabled = false;
    cancel.onclick = () => fetch(`/api/jobs/${id}`, { method: "DELETE" });
    for (;;) {
      const status = await (await fetch(`/api/jobs/${id}`)).json();
      bar.value = status.fraction;
      shown.push(status.fraction);
      out.textContent = `${status.state} ${Math.round(100 * status.fraction)} %`;
      if (status.state === "done") { done(status.result); break; }
      if (status.state === "failed" || status.state === "cancelled") {
        out.textContent = status.state === "failed" ? status.error : "cancelled";
        out.className = status.state === "failed" ? "error" : "";
        break;
      }
      await new Promise((resolve) => setTimeout(resolve, 100));
    }
    run.disabled = false;
    cancel.disabled = true;
  }

  function showOptimum(result) {
    const out = $("optimize-result");
    const b = result.robust ? result.robust.design : result.best;
    if (result.robust && !b) { out.textContent = `robust design: ${result.robust.status}: ${result.robust.reason}`; return; }
    if (!b) { out.textContent = `${result.status}: ${result.reason}`; return; }
    out.innerHTML = "";
    out.append(`${result.status}: n = ${b.needles_per_row}, D1 = ${b.tip_diameter_um} um, D2 = ${b.base_diameter_um} um` +
               (b.bore_diameter_um > 0 ? `, D3 = ${b.bore_diameter_um} um` : "") +
               `, w = ${b.width_um} um, L = ${b.length_um} um: PI = ${Number(b.performance_index_per_um).toPrecision(6)}` +
               ` 1/um (${result.grid_points} grid points, ${Number(result.seconds).toFixed(2)} s) `);
    if (result.robust) {
      out.append(`robust: P(success) = ${Number(b.success_probability).toFixed(4)} >= ` +
                 `${result.robust.min_success_probability} after ${result.robust.candidates_checked} candidates; ` +
                 `it costs ${Number(result.robust.index_cost_percent).toPrecision(3)} % of the nominal optimum's index `);
    }
    const use = document.createElement("button");
    use.type = "button";
    use.id = "use-optimum";
    use.textContent = "Use this design";
    use.onclick = () => {
      $("needles_per_row").value = String(b.needles_per_row);
      $("tip_diameter").value = `${b.tip_diameter_um} um`;
      $("base_diameter").value = `${b.base_diameter_um} um`;
      if (b.bore_diameter_um > 0) $("bore_diameter").value = `${b.bore_diameter_um} um`;
      $("width").value = `${b.width_um} um`;
      $("length").value = `${b.length_um} um`;
      syncSliders();
      scheduleEvaluate();
    };
    out.append(use);
  }

  function showSuccess(result) {
    const p = result.probabilities.success;
    $("uncertainty-result").textContent =
        `P(success) = ${Number(p.value).toFixed(4)} [${Number(p.ci95[0]).toFixed(4)}, ${Number(p.ci95[1]).toFixed(4)}]` +
        ` over ${result.samples} samples (${result.status})`;
  }

  // ---- the patch ------------------------------------------------------------------------------------------------

  function patchJson() {
    const d = designJson();
    const kind = $("p-kind").value;
    const patch = { kind: kind, size: $("p-size").value.trim(), needles_per_row: integerOrText($("p-n").value),
                    spring_constant: $("p-k").value.trim() };
    if (kind === "flexible") patch.max_spring_energy = $("p-energy").value.trim();
    return {
      surface: { mesh: $("p-mesh").value, unit: $("p-unit").value.trim(),
                 center_vertex: integerOrText($("p-center").value), approach: $("p-approach").value },
      patch: patch, needle: d.needle, tissue: d.tissue, insertion: d.insertion,
    };
  }

  function showPatch(s) {
    const range = (r, unit) => r ? `${number(r.min)} .. ${number(r.max)} ${unit} (mean ${number(r.mean)})` : "–";
    const rows = [
      ["fit", `${s.kind}: ${s.status}${s.reason ? ": " + s.reason : ""} in ${number(s.fit_ms, 3)} ms`],
      ["needles penetrating / buckled / bent", `${s.penetrating} / ${s.buckled} / ${s.bent} of ${s.needles}`],
      ["insertion angle", range(s.angle_deg, "deg")],
      ["buckling force |F|/cos", range(s.buckling_force_N, "N")],
      ["bending force |F| tan", range(s.bending_force_N, "N")],
      ["travel x (Eq 5.12)", range(s.travel_um, "um")],
      ["performance index", `${range(s.performance_index_per_um, "1/um")}`],
      ["spring energy", s.spring_energy_mJ ? `total ${number(s.spring_energy_mJ.total)} mJ` : "–"],
    ];
    const table = $("patch-numbers");
    table.innerHTML = "";
    for (const [label, value] of rows) {
      const row = table.insertRow();
      row.insertCell().textContent = label;
      row.insertCell().textContent = value;
    }
    $("patch-result").textContent = `done: ${s.penetrating} of ${s.needles} needles penetrate`;
    if (patchView) patchView.dispose();
    patchView = s.view ? window.needlekitViewer.mount(s.view, $("patch-view")) : null;
  }

  // An OBJ, STL or PLY file from this computer: the server keeps it in its own temporary file and lists it.
  async function upload(meshes) {
    const file = $("p-upload").files[0];
    const out = $("upload-result");
    if (!file) { out.textContent = "choose a file first"; return; }
    const format = file.name.split(".").pop().toLowerCase();
    const response = await fetch(`/api/uploads?format=${encodeURIComponent(format)}`, {
      method: "POST", headers: { "Content-Type": "application/octet-stream" }, body: await file.arrayBuffer(),
    });
    const answer = await response.json();
    if (response.status !== 201) { out.textContent = answer.error; out.className = "error"; return; }
    out.className = "";
    out.textContent = `${answer.name}: ${answer.triangles} triangles`;
    meshes.push(answer);
    fillSelect($("p-mesh"), [answer], answer.name);
    showBody();
  }

  function chooseMesh(meshes) {
    const mesh = meshes.find((m) => m.name === $("p-mesh").value);
    if (mesh && mesh.example) {
      $("p-unit").value = `${mesh.unit_m} m`;
      $("p-center").value = String(mesh.center_vertex);
      $("p-approach").value = mesh.approach;
    }
    return showBody();
  }

  // The chosen body's surface in 3D (decimated by the library if large), before any fit: a click on it puts the
  // nearest vertex into the centre field and the approach along the surface normal there (approach = "normal").
  async function showBody() {
    const sequence = ++bodySequence, out = $("body-view-result");
    document.body.dataset.bodyView = "loading";
    const answer = await postJson("/api/body-view", { surface: { mesh: $("p-mesh").value, unit: $("p-unit").value.trim() } });
    if (sequence !== bodySequence) return;  // another mesh was chosen meanwhile
    if (bodyView) bodyView.dispose();
    bodyView = null;
    if (answer.status !== 200) {
      out.textContent = answer.json.error;
      out.className = "error";
      document.body.dataset.bodyView = "failed";
      return;
    }
    out.className = "";
    out.textContent = (answer.json.notes || []).join("; ");
    bodyView = window.needlekitViewer.mount(answer.json, $("body-view"), { onPick: placePatch });
    markCenter();
    document.body.dataset.bodyView = "ready";
  }

  // A click on the body's view: the view picked a vertex of what it draws (decimated when the mesh is large); the
  // server casts the same ray on the full mesh (POST /api/body-pick) and names the vertex the fit will use.
  async function placePatch(pick) {
    const sequence = ++pickSequence, out = $("body-view-result");
    document.body.dataset.bodyPick = "resolving";
    const format = (p) => p.map((x) => `${x} m`);
    const answer = await postJson("/api/body-pick", {
      surface: { mesh: $("p-mesh").value, unit: $("p-unit").value.trim() },
      ray: { origin: format(pick.ray.origin), direction: pick.ray.direction } });
    if (sequence !== pickSequence) return;  // a later click is being resolved
    lastBodyPick = answer.json;
    if (answer.status !== 200 || !answer.json.hit) {
      out.textContent = answer.status !== 200 ? answer.json.error : "the click missed the body";
      out.className = "error";
      document.body.dataset.bodyPick = "failed";
      return;
    }
    const vertex = answer.json.vertex;
    $("p-center").value = String(vertex);
    $("p-approach").value = "normal";
    if (bodyView) bodyView.markAt(answer.json.position_m, answer.json.normal);
    const mm = answer.json.position_m.map((x) => (1e3 * x).toPrecision(4)).join(", ");
    out.className = "";
    out.textContent = `centre: vertex ${vertex} at (${mm}) mm, approach against the normal`;
    document.body.dataset.bodyPick = "done";
  }

  // The typed centre vertex, marked when the view draws it.
  function markCenter() {
    if (!bodyView) return;
    const text = $("p-center").value.trim();
    bodyView.markMeshVertex(/^\d+$/.test(text) ? parseInt(text, 10) : -1);
  }

  // ---- the form ---------------------------------------------------------------------------------------------------

  function syncSliders() {
    for (const slider of document.querySelectorAll("input[type=range]")) {
      const text = $(slider.dataset.for).value.trim();
      const unit = slider.dataset.unit;
      const match = unit ? text.match(new RegExp(`^([0-9.eE+-]+)\\s*${unit}$`)) : text.match(/^(\d+)$/);
      if (match) slider.value = match[1];
    }
  }

  function showFieldsOfShape() {
    const cylinder = $("shape").value === "cylinder";
    document.querySelector('.field[data-key="needle.base_diameter"]').style.display = cylinder ? "none" : "";
    document.querySelector('.field[data-key="needle.bore_diameter"]').style.display = $("hollow").checked ? "" : "none";
  }

  function fillSelect(select, entries, chosen) {
    for (const entry of entries) {
      const option = document.createElement("option");
      option.value = entry.name;
      option.textContent = entry.name;
      option.title = entry.meaning || entry.source || "";
      select.append(option);
    }
    select.value = chosen;
  }

  function download() {
    const blob = new Blob([tomlText(designJson())], { type: "application/toml" });
    const link = document.createElement("a");
    link.href = URL.createObjectURL(blob);
    link.download = "design.toml";
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }

  async function start() {
    const presets = await (await fetch("/api/presets")).json();
    fillSelect($("shape"), presets.shapes, "cone");
    fillSelect($("material"), presets.materials, "silicon");
    fillSelect($("tissue"), presets.tissue_models, "skin");
    fillSelect($("p-kind"), presets.patch_kinds, "rigid");
    fillSelect($("p-approach"), presets.approaches, presets.approaches[0].name);
    const meshes = await (await fetch("/api/meshes")).json();
    const suggested = meshes.find((m) => m.example) || meshes[0];
    fillSelect($("p-mesh"), meshes, suggested ? suggested.name : "");
    $("p-mesh").addEventListener("change", () => chooseMesh(meshes));
    $("p-center").addEventListener("input", markCenter);
    chooseMesh(meshes);
    $("upload-mesh").addEventListener("click", () => upload(meshes));
    $("run-patch").addEventListener("click", () => runJob("patch", "/api/patch?view=true", patchJson(), showPatch));
    view = makeView();
    for (const slider of document.querySelectorAll("input[type=range]")) {
      slider.addEventListener("input", () => {
        $(slider.dataset.for).value = slider.dataset.unit ? `${slider.value} ${slider.dataset.unit}` : slider.value;
        scheduleEvaluate();
      });
    }
    for (const id of QUANTITY_FIELDS.concat(["needles_per_row"])) {
      $(id).addEventListener("input", () => { syncSliders(); scheduleEvaluate(); });
    }
    for (const id of ["shape", "hollow", "material", "tissue"]) {
      $(id).addEventListener("change", () => { showFieldsOfShape(); scheduleEvaluate(); });
    }
    $("download-toml").addEventListener("click", download);
    $("certified").addEventListener("change", () => {  // Fig 6.20's bounds at 1 um steps (6.9e11 grid points)
      if (!$("certified").checked) return;
      $("r-tip_diameter").value = "30 um, 150 um, 1 um";
      $("r-base_diameter").value = "30 um, 300 um, 1 um";
      $("r-width").value = "5000 um, 10000 um, 1 um";
      $("r-length").value = "300 um, 500 um, 1 um";
    });
    $("run-optimize").addEventListener("click", () =>
        runJob("optimize", `/api/optimize?top=5&certified=${$("certified").checked}`, spaceJson(), showOptimum));
    $("run-uncertainty").addEventListener("click", () =>
        runJob("uncertainty", "/api/uncertainty", uncertaintyJson(), showSuccess));
    showFieldsOfShape();
    syncSliders();
    await evaluate();
    document.body.dataset.ready = "true";
  }

  // For scripts and the browser tests: the design as the page would send it, and as the TOML it downloads.
  window.needlekitDesign = { designJson, patchJson, spaceJson, tomlText: () => tomlText(designJson()), evaluate,
                              patchView: () => patchView, bodyView: () => bodyView,
                              lastBodyPick: () => lastBodyPick,
                              jobFractions: (name) => jobFractions[name] || [] };
  window.addEventListener("DOMContentLoaded", start);
})();
