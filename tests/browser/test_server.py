"""`needlekit serve`'s JSON API over loopback HTTP: /api/evaluate answers exactly what `needlekit evaluate --json`
prints, bad input is 400 with the CLI's message, malformed and oversized requests are 4xx and leave the server serving,
200 concurrent requests are all answered correctly, no path reaches the file system, and jobs run, report progress,
cancel and fill their queue (docs/serve.md)."""
import concurrent.futures
import json
import random
import socket
import time
import tomllib

import pytest

from serve_fixture import (CONE_DESIGN, EXAMPLES, after_location, cli_error, cli_json, server, start_server,  # noqa
                           stop_server, toml_text)


def design_of(path):
    with open(path, "rb") as file:
        return tomllib.load(file)


@pytest.mark.parametrize("name", ["cone", "cone_hollow", "cylinder", "cylinder_hollow", "bevel", "bevel_hollow"])
def test_evaluate_answers_exactly_what_the_cli_prints(server, name):
    path = EXAMPLES / f"evaluate_table_6_1_{name}.toml"
    status, answer = server.json("POST", "/api/evaluate", design_of(path))
    assert status == 200, answer
    assert answer == cli_json("evaluate", str(path))


BAD_VALUES = [  # (table, key, value, part of the CLI's message)
    ("needle", "tip_diameter", "-30 um", "key 'needle.tip_diameter': '-30 um' is not positive"),
    ("needle", "tip_diameter", 30, "key 'needle.tip_diameter': 30 is a bare number without a unit"),
    ("needle", "length", "500", "key 'needle.length'"),
    ("needle", "colour", "red", "unknown key 'needle.colour'"),
    ("insertion", "angle", "95 deg", "key 'insertion.angle': '95 deg' is out of range"),
    ("array", "needles_per_row", 0, "key 'array.needles_per_row': 0 is out of range"),
    ("needle", "material", "gold", "key 'needle.material'"),
]


@pytest.mark.parametrize("table, key, value, expected", BAD_VALUES)
def test_bad_input_is_400_with_the_clis_message(server, tmp_path, table, key, value, expected):
    design = json.loads(json.dumps(CONE_DESIGN))
    design[table][key] = value
    path = tmp_path / "design.toml"
    path.write_text(toml_text(design))
    cli_message = cli_error("evaluate", str(path))
    assert expected in cli_message
    status, answer = server.json("POST", "/api/evaluate", design)
    assert status == 400
    assert answer["error"].startswith("design.json:1: ")
    assert after_location(answer["error"]) == after_location(cli_message)
    assert answer["key"] == f"{table}.{key}"


def malformed_request(server, index):
    """One of several kinds of bad request, chosen by `index`; returns the status."""
    kind = index % 8
    rng = random.Random(index)
    if kind == 0:  # truncated JSON
        text = json.dumps(CONE_DESIGN)
        return server.request("POST", "/api/evaluate", text[:rng.randrange(1, len(text) - 1)].encode(),
                              {"Content-Type": "application/json"})[0]
    if kind == 1:  # random bytes
        return server.request("POST", "/api/evaluate", bytes(rng.randrange(256) for _ in range(200)),
                              {"Content-Type": "application/json"})[0]
    if kind == 2:  # JSON that is not a design
        return server.json("POST", "/api/evaluate", [1, 2, {"needle": None}])[0]
    if kind == 3:  # a body over the 1 MiB limit
        return server.request("POST", "/api/evaluate", b"{" + b" " * (1 << 20) + b"}",
                              {"Content-Type": "application/json"})[0]
    if kind == 4:  # not JSON's content type
        return server.request("POST", "/api/evaluate", json.dumps(CONE_DESIGN).encode(),
                              {"Content-Type": "text/plain"})[0]
    if kind == 5:  # an unknown route or method
        return server.request(rng.choice(["GET", "PUT", "POST"]), f"/api/nothing{index}", b"{}",
                              {"Content-Type": "application/json"})[0]
    if kind == 6:  # a garbage request line on a raw socket
        with socket.create_connection((server.host, server.port), timeout=10) as raw:
            raw.sendall(b"\x16\x03\x01 garbage " + str(index).encode() + b"\r\n\r\n")
            reply = raw.recv(100)
        return int(reply.split()[1]) if reply.startswith(b"HTTP/1.1 ") else 0
    # deeply nested JSON
    return server.request("POST", "/api/evaluate", b"[" * 5000 + b"]" * 5000,
                          {"Content-Type": "application/json"})[0]


def test_a_thousand_malformed_and_oversized_requests_are_4xx_and_the_server_goes_on(server):
    with concurrent.futures.ThreadPoolExecutor(16) as pool:
        statuses = list(pool.map(lambda i: malformed_request(server, i), range(1000)))
    assert len(statuses) == 1000
    bad = [(i, s) for i, s in enumerate(statuses) if not 400 <= s < 500]
    assert not bad, bad[:10]
    assert statuses.count(413) == 125  # every oversized body
    assert server.alive()
    assert server.json("POST", "/api/evaluate", CONE_DESIGN)[0] == 200
    print(f"1000 bad requests: {sorted(set(statuses))} statuses, server still serving")


def test_two_hundred_concurrent_requests_are_all_answered_correctly(server, tmp_path):
    designs, expected = [], []
    for i in range(10):  # ten designs, each asked twenty times
        design = json.loads(json.dumps(CONE_DESIGN))
        design["needle"]["tip_diameter"] = f"{30 + 5 * i} um"
        path = tmp_path / f"design_{i}.toml"
        path.write_text(toml_text(design))
        designs.append(design)
        expected.append(cli_json("evaluate", str(path)))
    with concurrent.futures.ThreadPoolExecutor(200) as pool:
        answers = list(pool.map(lambda i: server.json("POST", "/api/evaluate", designs[i % 10]), range(200)))
    for i, (status, answer) in enumerate(answers):
        assert status == 200
        assert answer == expected[i % 10]


TRAVERSALS = ["/../../etc/passwd", "/%2e%2e/%2e%2e/etc/passwd", "/..%2f..%2fetc%2fpasswd", "//etc/passwd",
              "/three/../../../../etc/passwd", "/three/%2e%2e%2f%2e%2e%2f%2e%2e%2fetc%2fpasswd",
              "/design.js/../../../etc/passwd", "/three/three.min.js%00.txt", "/%252e%252e/etc/passwd",
              "/three/examples/js/controls/OrbitControls.js", "/web/design/index.html", "/../web/design/design.js",
              "/three/../../../../usr/share/javascript/three/three.js", "/index.html/..", "/.%2e/.%2e/etc/passwd"]


@pytest.mark.parametrize("path", TRAVERSALS)
def test_no_path_reaches_the_file_system(server, path):
    status, _, body = server.request("GET", path)
    assert status == 404
    assert b"root:" not in body


def test_the_page_and_three_js_are_served_from_the_allow_list(server):
    for path, type_ in [("/", "text/html"), ("/design.js", "text/javascript"), ("/design.css", "text/css"),
                        ("/three/three.min.js", "text/javascript"), ("/three/OrbitControls.js", "text/javascript")]:
        status, headers, body = server.request("GET", path)
        assert status == 200 and headers["Content-Type"].startswith(type_) and body


def test_other_hosts_and_content_types_are_refused(server):
    status, _, body = server.request("POST", "/api/evaluate", json.dumps(CONE_DESIGN).encode(),
                                     {"Content-Type": "application/json", "Host": "rebound.example:80"})
    assert status == 403 and b"rebound.example" in body
    assert server.request("POST", "/api/evaluate", json.dumps(CONE_DESIGN).encode(),
                          {"Content-Type": "text/plain"})[0] == 415


def test_presets_come_from_the_librarys_tables(server):
    status, presets = server.json("GET", "/api/presets")
    assert status == 200
    assert [s["name"] for s in presets["shapes"]] == ["cylinder", "cone", "bevel"]
    names = [m["name"] for m in presets["materials"]]
    assert names[:2] == ["silicon", "su-8"] and len(names) >= 9
    assert [t["name"] for t in presets["tissue_models"]] == ["skin", "brain"]
    assert presets["tissue_models"][0]["tau_per_mm"] == pytest.approx(6.25)


def wait_for_job(server, job_id, until, timeout=120):
    """Polls GET /api/jobs/ID until `until(status)`; returns the statuses seen."""
    seen = []
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        status, job = server.json("GET", f"/api/jobs/{job_id}")
        assert status == 200
        seen.append(job)
        if until(job):
            return seen
        time.sleep(0.05)
    raise AssertionError(f"job {job_id}: {seen[-1]}")


def space_of(path):
    return design_of(path)


def run_job(server, route, body):
    """Submits a job and polls it to its end; returns every status seen."""
    status, job = server.json("POST", route, body)
    assert status == 202, job  # its state may already be final: a worker can take it before the answer is sent
    return wait_for_job(server, job["id"], lambda j: j["state"] not in ("queued", "running"))


def done_job(server, route, body):
    """Runs a job to its end, which must be done with a fraction that never decreased and ended at 1; returns the
    statuses seen."""
    seen = run_job(server, route, body)
    assert seen[-1]["state"] == "done", seen[-1]
    fractions = [j["fraction"] for j in seen]
    assert fractions == sorted(fractions) and fractions[-1] == 1.0
    return seen


def test_an_optimize_job_gives_the_clis_optimum(server):
    path = EXAMPLES / "optimize_fig_6_20_cone_solid.toml"
    seen = done_job(server, "/api/optimize?top=5", space_of(path))
    result, expected = seen[-1]["result"], cli_json("optimize", str(path), "--top", "5")
    assert result["best"] == expected["best"]
    assert [t["details"] for t in result["top"]] == [t["details"] for t in expected["top"]]


def test_the_1um_certified_optimization_streams_progress_to_the_clis_optimum(server):
    path = EXAMPLES / "optimize_certified_1um_cone_solid.toml"
    seen = run_job(server, "/api/optimize?certified=true", space_of(path))
    assert seen[-1]["state"] == "done", seen[-1]
    # The branch-and-bound reports every 256 (D1, D2) pairs it examines; on this grid it proves the optimum after a
    # few hundred, in milliseconds, so a poll rarely sees it between 0 and 1.
    assert seen[-1]["progress_reports"] >= 1
    assert seen[-1]["result"]["best"] == cli_json("optimize", str(path), "--certified")["best"]
    print(f"1 um certified job: {seen[-1]['progress_reports']} progress reports, "
          f"{seen[-1]['result']['seconds']:.3f} s")


def long_space():
    """A brute-force grid of 7.4e8 points (seconds of work): Fig 6.20's bounds, D1 and D2 at 1 um, w at 100 um, L at
    10 um."""
    space = space_of(EXAMPLES / "optimize_fig_6_20_cone_solid.toml")
    space["ranges"].update(tip_diameter=["30 um", "150 um", "1 um"], base_diameter=["30 um", "300 um", "1 um"],
                           width=["5000 um", "10000 um", "100 um"], length=["300 um", "500 um", "10 um"])
    return space


def test_a_long_job_reports_progress_and_cancels(server):
    status, job = server.json("POST", "/api/optimize", long_space())
    assert status == 202
    seen = wait_for_job(server, job["id"], lambda j: 0 < j["fraction"] < 1 or j["state"] not in ("queued", "running"))
    assert seen[-1]["state"] == "running", seen[-1]
    assert server.json("DELETE", f"/api/jobs/{job['id']}")[0] == 200
    seen = wait_for_job(server, job["id"], lambda j: j["state"] not in ("queued", "running"), timeout=30)
    assert seen[-1]["state"] == "cancelled"
    print(f"long job cancelled at {seen[-1]['fraction']:.3f}")


def test_a_full_queue_is_503_and_bad_jobs_are_400(server):
    answers = [server.json("POST", "/api/optimize", long_space())]
    wait_for_job(server, answers[0][1]["id"], lambda j: j["state"] == "running")
    answers += [server.json("POST", "/api/optimize", long_space()) for _ in range(7)]
    statuses = [status for status, _ in answers]
    assert statuses.count(202) == 5 and statuses.count(503) == 3, statuses  # one running, four queued
    for status, job in answers:
        if status == 202:
            assert server.json("DELETE", f"/api/jobs/{job['id']}")[0] == 200
    for status, job in answers:
        if status == 202:
            wait_for_job(server, job["id"], lambda j: j["state"] == "cancelled", timeout=30)
    path = EXAMPLES / "optimize_certified_1um_cone_solid.toml"
    bad = space_of(path)
    bad["ranges"]["tip_diameter"] = ["30 um", "150 um", "0 um"]
    status, answer = server.json("POST", "/api/optimize", bad)
    assert status == 400 and answer["key"] == "ranges.tip_diameter" and "step '0 um' is not positive" in answer["error"]
    assert server.json("POST", "/api/optimize?top=0", space_of(path))[0] == 400
    assert server.json("GET", "/api/jobs/999999")[0] == 404
    # A brute-force grid beyond the limit: the job's error (bad input), the server goes on.
    seen = run_job(server, "/api/optimize", space_of(path))
    assert seen[-1]["state"] == "failed" and seen[-1]["bad_input"] and "brute-force limit" in seen[-1]["error"]
    assert server.alive()


def test_an_uncertainty_job_gives_the_clis_probabilities(server):
    path = EXAMPLES / "uncertainty_cone_su8.toml"
    seen = run_job(server, "/api/uncertainty", design_of(path))
    assert seen[-1]["state"] == "done", seen[-1]
    result, expected = seen[-1]["result"], cli_json("uncertainty", str(path))
    assert result["probabilities"] == expected["probabilities"]
    assert result["performance_index_per_um"] == expected["performance_index_per_um"]


def test_another_host_is_served_with_a_warning():
    other = start_server("--host", "127.0.0.2")
    try:
        assert other.host == "127.0.0.2"
        assert other.json("POST", "/api/evaluate", CONE_DESIGN)[0] == 200
    finally:
        assert stop_server(other) == 130
    assert "warning: serving on 127.0.0.2 exposes the design API" in other.process.stderr.read()


def test_a_robust_design_job_gives_the_clis_answer_with_its_progress(server):
    path = EXAMPLES / "optimize_robust_cone_su8.toml"
    seen = done_job(server, "/api/optimize?top=3", space_of(path))
    assert seen[-1]["progress_reports"] > 2  # the ranking, then each candidate's sampling
    result, expected = seen[-1]["result"], cli_json("optimize", str(path), "--top", "3")
    for answer in (result, expected):
        del answer["seconds"]  # a wall time
    assert result == expected
    assert result["robust"]["status"] == "found"
    status, answer = server.json("POST", "/api/optimize?certified=true", space_of(path))
    assert status == 400 and "does not apply with min_success_probability" in answer["error"], answer


def patch_case_of(path):
    """A patch example as the API's JSON: [surface] mesh by its name in data/meshes."""
    case = design_of(path)
    case["surface"]["mesh"] = case["surface"]["mesh"].rsplit("/", 1)[-1]
    return case


def test_the_meshes_offered_are_the_repositorys(server):
    status, meshes = server.json("GET", "/api/meshes")
    assert status == 200
    names = [m["name"] for m in meshes]
    assert names == sorted(p.name for p in (EXAMPLES.parent / "data" / "meshes").glob("*.obj"))
    neck = next(m for m in meshes if m["name"] == "vh_male_head_neck_loop2.obj")
    assert neck["unit_m"] == 1 and neck["center_vertex"] == 2243


def test_a_patch_job_gives_the_clis_summary(server):
    path = EXAMPLES / "patch_neck_rigid.toml"
    seen = run_job(server, "/api/patch", patch_case_of(path))
    assert seen[-1]["state"] == "done", seen[-1]
    result, expected = seen[-1]["result"], cli_json("patch", str(path))
    for summary in (result, expected):
        del summary["fit_ms"]  # a wall time
    assert result == expected


@pytest.mark.parametrize("mesh", ["../../etc/passwd", "/etc/passwd", "../meshes/vh_male_skin.obj",
                                  "vh_male_skin.obj/../../../etc/passwd", "README.md", ""])
def test_a_patch_mesh_is_a_name_from_the_list_never_a_path(server, mesh):
    case = patch_case_of(EXAMPLES / "patch_neck_rigid.toml")
    case["surface"]["mesh"] = mesh
    status, answer = server.json("POST", "/api/patch", case)
    assert status == 400 and answer["key"] == "surface.mesh", answer
    assert "is not one of the meshes offered" in answer["error"]


def upload(server, data, format_):
    status, _, body = server.request("POST", f"/api/uploads?format={format_}", data,
                                     {"Content-Type": "application/octet-stream"})
    return status, json.loads(body)


def test_an_uploaded_mesh_is_its_own_temporary_file_and_fits_as_the_repositorys(server, tmp_path):
    mesh = EXAMPLES.parent / "data" / "meshes" / "skull_yahoojapan_10k.obj"
    status, entry = upload(server, mesh.read_bytes(), "obj")
    assert status == 201 and entry["upload"] and entry["triangles"] == 10312, entry
    assert entry["name"] in [m["name"] for m in server.json("GET", "/api/meshes")[1]]
    case = patch_case_of(EXAMPLES / "patch_skull.toml")
    case["surface"].update(center_vertex=3627)  # the forehead of the 10k skull (data/meshes/README.md)
    uploaded = json.loads(json.dumps(case))
    uploaded["surface"]["mesh"] = entry["name"]
    case["surface"]["mesh"] = "skull_yahoojapan_10k.obj"
    from_upload, from_repository = run_job(server, "/api/patch", uploaded), run_job(server, "/api/patch", case)
    assert from_upload[-1]["state"] == "done", from_upload[-1]
    notes = from_upload[-1]["result"]["notes"]
    assert len(notes) == 1 and notes[0].startswith("no licence or attribution found for ")  # as the CLI says
    for summary in (from_upload[-1]["result"], from_repository[-1]["result"]):
        del summary["fit_ms"], summary["notes"]
    assert from_upload[-1]["result"] == from_repository[-1]["result"]


def test_a_mesh_that_fails_to_read_is_400_with_the_readers_message(server, tmp_path):
    bad = b"v 0 0 0\nv 1 0 0\nf 1 2 7\n"
    path = tmp_path / "bad.obj"
    path.write_bytes(bad)
    status, answer = upload(server, bad, "obj")
    assert status == 400
    cli = cli_error("surface", str(path), "--unit", "m")
    assert after_location(answer["error"].split(": ", 1)[1]) == after_location(cli.split(": ", 1)[1]), (answer, cli)
    assert upload(server, b"solid x\nendsolid x\n", "exe")[0] == 400
    assert server.request("POST", "/api/uploads?format=obj", bad, {"Content-Type": "application/json"})[0] == 415
    assert upload(server, b" " * ((32 << 20) + 1), "obj")[0] == 413
    assert server.alive()


def decoded(array):
    """A typed array of a needlekit-view/1 object (io/view_arrays.hpp) as a list of numbers."""
    import base64
    import struct
    code = {"float32": "f", "uint32": "I"}[array["dtype"]]
    return list(struct.unpack(f"<{array['count']}{code}", base64.b64decode(array["base64"])))


def obj_vertices(path):
    return [[float(x) for x in line.split()[1:4]] for line in path.open() if line.startswith("v ")]


def test_a_body_view_is_the_meshs_own_vertices_decimated_to_a_small_view(server):
    path = EXAMPLES.parent / "data" / "meshes" / "vh_male_head_neck_loop2.obj"
    status, _, data = server.request("POST", "/api/body-view",
                                     {"surface": {"mesh": path.name, "unit": "mm"}})
    assert status == 200, data
    assert len(data) < 500_000, len(data)  # 240k triangles drawn as at most 12k
    view = json.loads(data)
    assert view["kind"] == "body" and view["full_mesh"]["triangles"] == 240272
    assert 6000 <= view["surface"]["triangles"] <= 12000
    vertices = obj_vertices(path)
    ids, positions = decoded(view["surface"]["vertex_ids"]), decoded(view["surface"]["positions"])
    assert len(positions) == 3 * len(ids)
    for k in range(0, len(ids), 97):  # in millimetres: unit = "mm" scales the file's numbers by 1e-3
        assert all(abs(positions[3 * k + c] - 1e-3 * vertices[ids[k]][c]) < 1e-9 for c in range(3)), k


@pytest.mark.parametrize("surface, key", [({"mesh": "../../etc/passwd", "unit": "m"}, "surface.mesh"),
                                          ({"mesh": "/etc/passwd", "unit": "m"}, "surface.mesh"),
                                          ({"mesh": "vh_male_skin.obj", "unit": "2"}, "surface.unit"),
                                          ({"mesh": "vh_male_skin.obj"}, "surface.unit"),
                                          ({"mesh": "vh_male_skin.obj", "unit": "m", "center": 1}, "surface.center")])
def test_a_body_view_of_bad_input_is_400_naming_the_key(server, surface, key):
    status, answer = server.json("POST", "/api/body-view", {"surface": surface})
    assert status == 400 and answer["key"] == key, answer
    assert server.alive()


def test_a_body_pick_is_the_full_meshs_vertex_where_the_ray_meets_it(server):
    """A ray straight down onto the top of the skull (unit mm) meets the full mesh's topmost triangle there; the
    vertex named is that triangle's corner nearest the hit, and a ray that points away misses."""
    path = EXAMPLES.parent / "data" / "meshes" / "skull_yahoojapan_10k.obj"
    vertices = [[1e-3 * x for x in v] for v in obj_vertices(path)]
    top = max(range(len(vertices)), key=lambda k: vertices[k][2])
    above = [f"{vertices[top][0]} m", f"{vertices[top][1]} m", f"{vertices[top][2] + 0.05} m"]
    surface = {"mesh": path.name, "unit": "mm"}
    status, answer = server.json("POST", "/api/body-pick", {"surface": surface,
                                                            "ray": {"origin": above, "direction": [0, 0, -2]}})
    assert status == 200 and answer["hit"], answer
    assert answer["point_m"][2] == pytest.approx(vertices[top][2], abs=2e-3)
    assert answer["position_m"] == pytest.approx(vertices[answer["vertex"]], abs=1e-9)
    assert answer["normal"][2] > 0.5, answer
    status, answer = server.json("POST", "/api/body-pick", {"surface": surface,
                                                            "ray": {"origin": above, "direction": [0, 0, 1]}})
    assert status == 200 and answer == {"hit": False}


@pytest.mark.parametrize("ray, key", [({"origin": ["0 m", "0 m", "1 m"], "direction": [0, 0, 0]}, "ray.direction"),
                                      ({"origin": [0, 0, 1], "direction": [0, 0, -1]}, "ray.origin"),
                                      ({"origin": ["0 m", "0 m"], "direction": [0, 0, -1]}, "ray.origin"),
                                      ({"origin": ["0 m", "0 m", "1 m"], "direction": ["down", 0, 0]},
                                       "ray.direction"),
                                      ({"origin": ["0 m", "0 m", "1 m"]}, "ray.direction"),
                                      ({"origin": ["0 m", "0 m", "1 m"], "direction": [0, 0, -1], "up": 1},
                                       "ray.up")])
def test_a_body_pick_of_bad_input_is_400_naming_the_key(server, ray, key):
    status, answer = server.json("POST", "/api/body-pick",
                                 {"surface": {"mesh": "skull_yahoojapan_10k.obj", "unit": "mm"}, "ray": ray})
    assert status == 400 and answer["key"] == key, answer
    assert server.alive()


def test_a_patch_job_reports_the_fits_progress_node_by_node(server):
    """A flexible fit reports each node it maps (Alg 5.1), an equilibrium fit each Newton iteration: many progress
    reports, fractions that never decrease, ending at 1, the result the CLI's."""
    for example in ("patch_neck_flexible.toml", "patch_neck_equilibrium.toml"):
        path = EXAMPLES / example
        seen = run_job(server, "/api/patch", patch_case_of(path))
        assert seen[-1]["state"] == "done", seen[-1]
        fractions = [j["fraction"] for j in seen]
        assert fractions == sorted(fractions) and fractions[-1] == 1.0
        case = patch_case_of(path)
        nodes = case["patch"]["needles_per_row"] ** 2
        reports = seen[-1]["progress_reports"]
        assert reports > (nodes if "flexible" in example else 5), (example, reports)
        result, expected = seen[-1]["result"], cli_json("patch", str(path))
        for summary in (result, expected):
            del summary["fit_ms"]
        assert result == expected
