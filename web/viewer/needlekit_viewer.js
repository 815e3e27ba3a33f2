// needlekit's 3D viewer (docs/views.md): shows the views that the data files NAME_view.js add to
// window.needlekitViews (format "needlekit-view/1", written by src/io/indentation_view.cpp and src/io/patch_view.cpp).
// A classic script on three.js r111 (Debian's libjs-three, global THREE with THREE.OrbitControls): the page opens from
// file:// with no network and no modules.
(function () {
  "use strict";

  // Viridis at 9 stops (matplotlib's colour map, public domain).
  var VIRIDIS = [[0.267, 0.005, 0.329], [0.283, 0.141, 0.458], [0.254, 0.265, 0.530], [0.207, 0.372, 0.553],
                 [0.164, 0.471, 0.558], [0.128, 0.567, 0.551], [0.135, 0.659, 0.518], [0.267, 0.749, 0.441],
                 [0.478, 0.821, 0.318], [0.741, 0.873, 0.150], [0.993, 0.906, 0.144]];
  var NEEDLE_GREY = [0.55, 0.57, 0.62];
  // A patch needle's status (src/io/patch_view.cpp) and an array needle's puncture state (src/io/indentation_view.cpp).
  var STATUS_COLOURS = {ok: [0.20, 0.63, 0.17], no_surface: [0.6, 0.6, 0.6], short: [0.99, 0.55, 0.38],
                        too_shallow: [0.99, 0.75, 0.44], buckles: [0.89, 0.10, 0.11], bends: [0.60, 0.31, 0.64],
                        intact: [0.19, 0.42, 0.74], punctured: [0.84, 0.15, 0.16]};

  function colourAt(t) {
    if (!(t >= 0)) t = 0;
    if (t > 1) t = 1;
    var x = t * (VIRIDIS.length - 1), i = Math.min(Math.floor(x), VIRIDIS.length - 2), f = x - i;
    var a = VIRIDIS[i], b = VIRIDIS[i + 1];
    return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
  }

  // A typed array of io/view_arrays.hpp: float32, uint32, or uint16 (quantized with lo/hi: returned as Float32Array).
  function decode(array) {
    var text = atob(array.base64), bytes = new Uint8Array(text.length);
    for (var i = 0; i < text.length; ++i) bytes[i] = text.charCodeAt(i);
    if (array.dtype === "float32") return new Float32Array(bytes.buffer, 0, array.count);
    if (array.dtype === "uint32") return new Uint32Array(bytes.buffer, 0, array.count);
    if (array.dtype !== "uint16") throw new Error("needlekit viewer: unknown dtype " + array.dtype);
    var codes = new Uint16Array(bytes.buffer, 0, array.count);
    if (!array.lo) return codes;
    var c = array.components, values = new Float32Array(array.count);
    for (var k = 0; k < array.count; ++k) {
      var j = k % c;
      values[k] = array.lo[j] + codes[k] * (array.hi[j] - array.lo[j]) / 65535;
    }
    return values;
  }

  function element(tag, className, parent, text) {
    var e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    if (parent) parent.appendChild(e);
    return e;
  }

  function formatNumber(value) {
    if (value === null || value === undefined) return "–";
    if (typeof value !== "number") return String(value);
    if (value === 0) return "0";
    return Math.abs(value) >= 1e4 || Math.abs(value) < 1e-3 ? value.toExponential(3) : String(+value.toPrecision(4));
  }

  // The colour bar: a gradient between the range's ends, labelled in the unit.
  function drawColourBar(bar, label, lo, hi, unit) {
    bar.innerHTML = "";
    element("span", "nk-bar-label", bar, label + (unit ? " (" + unit + ")" : ""));
    element("span", "nk-bar-end", bar, formatNumber(lo));
    var gradient = element("canvas", "nk-bar-gradient", bar);
    gradient.width = 160;
    gradient.height = 12;
    var g = gradient.getContext("2d");
    for (var x = 0; x < gradient.width; ++x) {
      var c = colourAt(x / (gradient.width - 1));
      g.fillStyle = "rgb(" + Math.round(255 * c[0]) + "," + Math.round(255 * c[1]) + "," + Math.round(255 * c[2]) + ")";
      g.fillRect(x, 0, 1, gradient.height);
    }
    element("span", "nk-bar-end", bar, formatNumber(hi));
  }

  // `options.onPick(pick)`: a click on the surface of a body view (kind "body") picks the nearest corner of the
  // triangle hit and calls it with {vertex (its index in the full mesh), position [m], point [m] (where the ray hit),
  // normal (unit, outward), ray: {origin [m], direction} (the camera's ray in the mesh's coordinates, to resolve the
  // click on the full mesh when the view is decimated)}; the view marks the spot.
  function View(data, host, options) {
    this.data = data;
    this.options = options || {};
    this.step = data.steps.length - 1;
    this.buildPage(host);
    this.buildScene();
    this.setStep(this.step);
  }

  View.prototype.buildPage = function (host) {
    var view = this, data = this.data;
    this.host = host;
    host.classList.add("nk-view");
    host.setAttribute("data-view-name", data.name);
    element("div", "nk-title", host, data.title);
    var stage = element("div", "nk-stage", host);
    this.canvas = element("canvas", "nk-canvas", stage);
    this.info = element("div", "nk-info", stage);
    this.info.hidden = true;
    var controls = element("div", "nk-controls", host);
    var choices = this.colourChoices();
    if (choices.length > 0) {
      var label = element("label", "", controls, "colour: ");
      this.select = element("select", "nk-field", label);
      choices.forEach(function (choice, i) {
        var option = element("option", "", view.select, choice.label + (choice.unit ? " (" + choice.unit + ")" : ""));
        option.value = String(i);
      });
      this.select.addEventListener("change", function () { view.refresh(); });
      // An FE run with each needle's puncture state (an array) opens on it.
      if (data.kind === "indentation") {
        choices.forEach(function (choice, i) { if (choice.kind === "status") view.select.value = String(i); });
      }
    }
    this.choices = choices;
    if (data.steps.length > 1) {
      var stepLabel = element("label", "", controls, "load step: ");
      this.slider = element("input", "nk-step", stepLabel);
      this.slider.type = "range";
      this.slider.min = "0";
      this.slider.max = String(data.steps.length - 1);
      this.slider.value = String(this.step);
      this.slider.addEventListener("input", function () { view.setStep(+view.slider.value); });
    }
    this.stepText = element("span", "nk-step-text", controls);
    this.bar = element("div", "nk-colour-bar", host);
    (data.notes || []).forEach(function (note) { element("div", "nk-note", host, note); });
  };

  // What the select offers: the surface's fields, then the needle table's colour columns.
  View.prototype.colourChoices = function () {
    var choices = [], data = this.data;
    (data.surface.fields || []).forEach(function (field) {
      choices.push({kind: "field", field: field, label: field.label, unit: field.unit});
    });
    var table = data.needles && data.needles.table;
    var several = table && table.rows.length > 1;
    if (table && (data.kind === "patch" || several)) {
      table.columns.forEach(function (column, index) {
        if (column.colour) choices.push({kind: "needle", column: index, label: "needles: " + column.label, unit: column.unit});
      });
      table.columns.forEach(function (column) {
        if (column.key === "status") choices.push({kind: "status", label: "needles: " + column.label, unit: ""});
      });
    }
    return choices;
  };

  View.prototype.buildScene = function () {
    var data = this.data;
    this.renderer = new THREE.WebGLRenderer({canvas: this.canvas, antialias: true, preserveDrawingBuffer: true});
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setSize(this.canvas.clientWidth || 640, this.canvas.clientHeight || 420, false);
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xf4f5f7);
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.4));
    this.world = new THREE.Group();
    this.scene.add(this.world);

    var surface = data.surface;
    this.surfacePositions = decode(surface.positions);
    this.surfaceNormals = surface.normals ? decode(surface.normals) : null;  // a body view's: the full mesh's
    this.vertexCount = surface.vertices;
    this.fields = (surface.fields || []).map(function (f) { return decode(f.values); });
    var geometry = new THREE.BufferGeometry();
    geometry.setIndex(new THREE.BufferAttribute(decode(surface.indices), 1));
    geometry.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * this.vertexCount), 3));
    geometry.setAttribute("color", new THREE.BufferAttribute(new Float32Array(3 * this.vertexCount), 3));
    this.surfaceGeometry = geometry;
    var material = new THREE.MeshLambertMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide});
    this.surfaceMesh = new THREE.Mesh(geometry, material);
    this.world.add(this.surfaceMesh);
    this.vertexIds = surface.vertex_ids ? decode(surface.vertex_ids) : null;

    if (data.lines) {
      var lines = new THREE.BufferGeometry();
      lines.setAttribute("position", new THREE.BufferAttribute(decode(data.lines.positions), 3));
      this.world.add(new THREE.LineSegments(lines, new THREE.LineBasicMaterial({color: 0x1f3a93})));
    }
    this.needleMeshes = [];
    if (data.needles && data.needles.meshes) this.buildPlacedNeedles(data.needles);
    if (data.needles && data.needles.segments) this.buildSegmentNeedles(data.needles);
    this.frameCamera();
    var view = this, down = null;
    // A click picks; a drag (the orbit controls') does not.
    this.canvas.addEventListener("pointerdown", function (event) { down = [event.clientX, event.clientY]; });
    this.canvas.addEventListener("click", function (event) {
      if (down && Math.abs(event.clientX - down[0]) + Math.abs(event.clientY - down[1]) > 4) return;
      if (view.data.kind === "body") view.pickSurface(event); else view.pick(event);
    });
  };

  // Indentation: needle meshes placed per instance, moved along the direction by each step's displacement.
  View.prototype.buildPlacedNeedles = function (needles) {
    var view = this;
    var geometries = needles.meshes.map(function (m) {
      var g = new THREE.BufferGeometry();
      g.setIndex(new THREE.BufferAttribute(decode(m.indices), 1));
      g.setAttribute("position", new THREE.BufferAttribute(decode(m.positions), 3));
      g.computeVertexNormals();
      return g;
    });
    needles.instances.forEach(function (instance, i) {
      var mesh = new THREE.Mesh(geometries[instance.mesh], new THREE.MeshLambertMaterial({color: 0x8c92a0}));
      mesh.userData = {needle: i, offset: instance.offset};
      view.world.add(mesh);
      view.needleMeshes.push(mesh);
    });
  };

  // Patch: each needle a cylinder from its base to its tip.
  View.prototype.buildSegmentNeedles = function (needles) {
    var s = decode(needles.segments), size = this.extent().size;
    var radius = Math.max(needles.radius_m, 0.01 * size);  // visible and clickable
    var up = new THREE.Vector3(0, 1, 0);
    for (var n = 0; 6 * n < s.length; ++n) {
      var base = new THREE.Vector3(s[6 * n], s[6 * n + 1], s[6 * n + 2]);
      var tip = new THREE.Vector3(s[6 * n + 3], s[6 * n + 4], s[6 * n + 5]);
      var axis = tip.clone().sub(base), length = axis.length();
      var geometry = new THREE.CylinderBufferGeometry(0.4 * radius, radius, Math.max(length, 1e-12), 10);
      var mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({color: 0x8c92a0}));
      mesh.quaternion.setFromUnitVectors(up, axis.normalize());
      mesh.position.copy(base.add(tip).multiplyScalar(0.5));
      mesh.userData = {needle: n};
      this.world.add(mesh);
      this.needleMeshes.push(mesh);
    }
  };

  // The bounding box of the surface over all stored steps.
  View.prototype.extent = function () {
    var p = this.surfacePositions, lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (var k = 0; k < p.length; ++k) {
      lo[k % 3] = Math.min(lo[k % 3], p[k]);
      hi[k % 3] = Math.max(hi[k % 3], p[k]);
    }
    var size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    return {center: new THREE.Vector3((lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2), size: size,
            top: hi[2]};
  };

  // Metres are scaled to a unit scene (WebGL's float precision and the camera's clip planes).
  View.prototype.frameCamera = function () {
    var e = this.extent(), scale = 1 / e.size;
    this.world.scale.setScalar(scale);
    this.world.position.copy(e.center.clone().multiplyScalar(-scale));
    var aspect = (this.canvas.clientWidth || 640) / (this.canvas.clientHeight || 420);
    this.camera = new THREE.PerspectiveCamera(35, aspect, 0.01, 100);
    this.camera.up.set(0, 0, 1);
    // A head light: the side in view is always lit.
    var light = new THREE.DirectionalLight(0xffffff, 0.6);
    light.position.set(0.3, 0.5, 1);
    this.camera.add(light);
    this.scene.add(this.camera);
    var focus = new THREE.Vector3(0, 0, 0);
    if (this.data.kind === "body") {
      // A body mesh as the repository's (y up, the face towards +z, the OBJ convention): from the front.
      this.camera.up.set(0, 1, 0);
      this.camera.position.set(0, 0, 2.2);
    } else if (this.data.kind === "patch" && this.needleMeshes.length > 0) {
      // Look along the needles, from their bases.
      var s = decode(this.data.needles.segments), mid = Math.floor(s.length / 12);
      var dir = new THREE.Vector3(s[6 * mid] - s[6 * mid + 3], s[6 * mid + 1] - s[6 * mid + 4], s[6 * mid + 2] - s[6 * mid + 5]);
      dir.normalize();
      this.camera.position.copy(dir.multiplyScalar(1.8).add(new THREE.Vector3(0.3, 0.3, 0.3)));
    } else {
      // The tissue's top surface, where the needles act, from above at an angle.
      focus.z = (e.top - e.center.z) * scale;
      this.camera.position.set(0.75, -1.15, 1.05).add(focus);
    }
    this.camera.lookAt(focus);
    this.controls = new THREE.OrbitControls(this.camera, this.canvas);
    this.controls.target.copy(focus);
    var view = this;
    this.controls.addEventListener("change", function () { view.render(); });
  };

  View.prototype.setStep = function (step) {
    this.step = step;
    var v = this.vertexCount, p = this.surfacePositions;
    var position = this.surfaceGeometry.getAttribute("position");
    var offset = p.length > 3 * v ? 3 * v * step : 0;
    position.array.set(p.subarray(offset, offset + 3 * v));
    position.needsUpdate = true;
    if (this.surfaceNormals) {
      this.surfaceGeometry.setAttribute("normal", new THREE.BufferAttribute(this.surfaceNormals, 3));
    } else {
      this.surfaceGeometry.computeVertexNormals();
    }
    this.surfaceGeometry.computeBoundingSphere();
    var needles = this.data.needles;
    if (needles && needles.instances) {
      var d = needles.displacement_m[step] || 0, dir = needles.direction;
      this.needleMeshes.forEach(function (mesh) {
        var o = mesh.userData.offset;
        mesh.position.set(o[0] + d * dir[0], o[1] + d * dir[1], o[2] + d * dir[2]);
      });
    }
    if (this.stepText) this.stepText.textContent = this.data.steps[step].label || "";
    this.refresh();
  };

  // Colours the surface (a field) or the needles (a table column) and redraws.
  View.prototype.refresh = function () {
    var choice = this.select ? this.choices[+this.select.value] : null;
    var colours = this.surfaceGeometry.getAttribute("color"), v = this.vertexCount;
    var needleColours = this.needleMeshes.map(function () { return NEEDLE_GREY; });
    if (choice && choice.kind === "field") {
      var values = this.fields[this.choices.indexOf(choice)], field = choice.field;
      var lo = field.values.lo[0], hi = field.values.hi[0], offset = values.length > v ? v * this.step : 0;
      for (var i = 0; i < v; ++i) {
        var c = colourAt(hi > lo ? (values[offset + i] - lo) / (hi - lo) : 0);
        colours.array[3 * i] = c[0];
        colours.array[3 * i + 1] = c[1];
        colours.array[3 * i + 2] = c[2];
      }
      drawColourBar(this.bar, field.label, lo * field.scale, hi * field.scale, field.unit);
    } else {
      colours.array.fill(0.72);
      this.bar.innerHTML = "";
    }
    colours.needsUpdate = true;
    if (choice && choice.kind === "needle") needleColours = this.needleColumnColours(choice);
    if (choice && choice.kind === "status") needleColours = this.needleStatusColours();
    this.needleMeshes.forEach(function (mesh, i) { mesh.material.color.setRGB.apply(mesh.material.color, needleColours[i]); });
    this.render();
  };

  View.prototype.cell = function (row, column) {
    var value = row[column];
    return this.data.needles.table.columns[column].per_step ? value[this.step] : value;
  };

  View.prototype.needleColumnColours = function (choice) {
    var view = this, rows = this.data.needles.table.rows;
    var values = this.needleMeshes.map(function (mesh) { return view.cell(rows[mesh.userData.needle], choice.column); });
    var finite = values.filter(function (x) { return typeof x === "number" && isFinite(x); });
    var lo = Math.min.apply(null, finite), hi = Math.max.apply(null, finite);
    drawColourBar(this.bar, choice.label, lo, hi, choice.unit);
    return values.map(function (x) {
      if (typeof x !== "number" || !isFinite(x)) return NEEDLE_GREY;
      return colourAt(hi > lo ? (x - lo) / (hi - lo) : 0.5);
    });
  };

  // The legend names the states the column holds (at any step), with the count of needles in each at this step.
  View.prototype.needleStatusColours = function () {
    var view = this, table = this.data.needles.table, column = -1;
    table.columns.forEach(function (c, i) { if (c.key === "status") column = i; });
    var states = this.needleMeshes.map(function (mesh) { return view.cell(table.rows[mesh.userData.needle], column); });
    var present = {};
    table.rows.forEach(function (row) { [].concat(row[column]).forEach(function (s) { present[s] = 0; }); });
    states.forEach(function (s) { present[s] += 1; });
    this.bar.innerHTML = "";
    element("span", "nk-bar-label", this.bar, "status:");
    Object.keys(STATUS_COLOURS).filter(function (name) { return name in present; }).forEach(function (name) {
      var c = STATUS_COLOURS[name], chip = element("span", "nk-chip", this.bar, name + " " + present[name]);
      chip.setAttribute("data-status", name);
      chip.style.borderColor = "rgb(" + c.map(function (x) { return Math.round(255 * x); }).join(",") + ")";
    }, this);
    return states.map(function (s) { return STATUS_COLOURS[s] || NEEDLE_GREY; });
  };

  // The camera's ray through the pixel of a mouse event.
  View.prototype.rayAt = function (event) {
    var rect = this.canvas.getBoundingClientRect();
    var mouse = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
                                  -((event.clientY - rect.top) / rect.height) * 2 + 1);
    var raycaster = new THREE.Raycaster();
    raycaster.setFromCamera(mouse, this.camera);
    return raycaster;
  };

  // The objects under a mouse event, nearest first.
  View.prototype.hitsAt = function (event, objects) {
    return this.rayAt(event).intersectObjects(objects);
  };

  // A click on a body's surface: the nearest corner of the triangle hit, marked, and given to options.onPick.
  View.prototype.pickSurface = function (event) {
    var raycaster = this.rayAt(event), hits = raycaster.intersectObjects([this.surfaceMesh]);
    if (hits.length === 0 || !this.vertexIds) return;
    // The ray in the mesh's coordinates, for resolving the click on the full mesh (POST /api/body-pick).
    var origin = this.world.worldToLocal(raycaster.ray.origin.clone());
    var ahead = this.world.worldToLocal(raycaster.ray.origin.clone().add(raycaster.ray.direction));
    var direction = ahead.sub(origin);
    var point = this.world.worldToLocal(hits[0].point.clone()), face = hits[0].face, p = this.surfacePositions;
    var nearest = -1, best = Infinity;
    [face.a, face.b, face.c].forEach(function (k) {
      var d = point.distanceToSquared(new THREE.Vector3(p[3 * k], p[3 * k + 1], p[3 * k + 2]));
      if (d < best) { best = d; nearest = k; }
    });
    this.markVertex(nearest);
    var n = this.surfaceGeometry.getAttribute("normal");
    var pick = {vertex: this.vertexIds[nearest], position: [p[3 * nearest], p[3 * nearest + 1], p[3 * nearest + 2]],
                point: [point.x, point.y, point.z], normal: [n.getX(nearest), n.getY(nearest), n.getZ(nearest)],
                ray: {origin: [origin.x, origin.y, origin.z], direction: [direction.x, direction.y, direction.z]}};
    this.lastPick = pick;
    if (this.options.onPick) this.options.onPick(pick);
  };

  // Marks the drawn vertex k: a dot and an arrow along the approach (against the outward normal, the sign of
  // approach = "normal" in examples/patch_*.toml); k < 0 removes the mark.
  View.prototype.markVertex = function (k) {
    if (k < 0) return this.markAt(null, null);
    var p = this.surfacePositions, n = this.surfaceGeometry.getAttribute("normal");
    this.markAt([p[3 * k], p[3 * k + 1], p[3 * k + 2]], [n.getX(k), n.getY(k), n.getZ(k)]);
  };

  // Marks the point `position` [m] with its outward `normal` (a vertex of the full mesh that the view may not draw);
  // null removes the mark.
  View.prototype.markAt = function (position, normalVector) {
    if (this.marker) this.world.remove(this.marker);
    this.marker = null;
    if (position) {
      var size = this.extent().size;
      var at = new THREE.Vector3(position[0], position[1], position[2]);
      var normal = new THREE.Vector3(normalVector[0], normalVector[1], normalVector[2]).normalize();
      this.marker = new THREE.Group();
      var dot = new THREE.Mesh(new THREE.SphereBufferGeometry(0.012 * size, 16, 12),
                               new THREE.MeshBasicMaterial({color: 0xd62728}));
      dot.position.copy(at);
      this.marker.add(dot);
      var length = 0.12 * size;
      this.marker.add(new THREE.ArrowHelper(normal.clone().negate(), at.clone().addScaledVector(normal, length), length,
                                            0xd62728, 0.35 * length, 0.2 * length));
      this.world.add(this.marker);
    }
    this.render();
  };

  // Marks the vertex of the full mesh `id` when it is drawn (a decimated view draws some vertices only); returns
  // whether it is.
  View.prototype.markMeshVertex = function (id) {
    var k = -1;
    if (this.vertexIds) {
      for (var i = 0; i < this.vertexIds.length; ++i) if (this.vertexIds[i] === id) { k = i; break; }
    }
    this.markVertex(k);
    return k >= 0;
  };

  // A click on a needle shows its row of the table.
  View.prototype.pick = function (event) {
    if (!this.data.needles || !this.data.needles.table) return;
    var hits = this.hitsAt(event, this.needleMeshes);
    if (hits.length === 0) {
      this.info.hidden = true;
      return;
    }
    this.showNeedle(hits[0].object.userData.needle);
  };

  View.prototype.showNeedle = function (needle) {
    var table = this.data.needles.table, row = table.rows[needle], view = this;
    this.info.innerHTML = "";
    element("div", "nk-info-title", this.info, "needle " + (needle + 1));
    var list = element("table", "", this.info);
    table.columns.forEach(function (column, i) {
      var tr = element("tr", "", list);
      element("td", "", tr, column.label + (column.unit ? " (" + column.unit + ")" : ""));
      element("td", "nk-num", tr, formatNumber(view.cell(row, i)));
    });
    this.info.hidden = false;
  };

  View.prototype.render = function () {
    this.renderer.render(this.scene, this.camera);
  };

  // Frees the WebGL context and empties the host (a page that shows one fit after another).
  View.prototype.dispose = function () {
    this.controls.dispose();
    this.renderer.dispose();
    this.renderer.forceContextLoss();
    this.host.innerHTML = "";
  };

  // Mounts every view of window.needlekitViews: into the element with data-needlekit-view="NAME" if the page has
  // one, else into a new element appended to `container`.
  function mountAll(container) {
    var mounted = [];
    (window.needlekitViews || []).forEach(function (data) {
      var host = document.querySelector('[data-needlekit-view="' + data.name + '"]');
      if (!host) {
        host = element("div", "", container || document.body);
      }
      mounted.push(new View(data, host));
    });
    window.needlekitViewer.mounted = mounted;
    return mounted;
  }

  // One view of `data` (a needlekit-view/1 object, e.g. the "view" of a patch job of `needlekit serve`) in `host`;
  // `options` as View's.
  function mount(data, host, options) {
    return new View(data, host, options);
  }

  window.needlekitViewer = {mountAll: mountAll, mount: mount, decode: decode, mounted: []};
})();
