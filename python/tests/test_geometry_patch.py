"""Surfaces, geodesics and patches from Python: numpy in and out without copies, exact geodesics on a plane, and the
patch summary equal to the CLI's JSON."""
import json

import numpy as np
import pytest

import needlekit as nk
from conftest import EXAMPLES, cli_json


def grid_plane(n=20, size=0.02):
    x, y = np.meshgrid(np.linspace(-size / 2, size / 2, n), np.linspace(-size / 2, size / 2, n), indexing="ij")
    vertices = np.column_stack([x.ravel(), y.ravel(), np.zeros(n * n)])
    index = np.arange(n * n).reshape(n, n)
    a, b, c, d = index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(), index[:-1, 1:].ravel()
    return vertices, np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])


def test_meshes_are_numpy_views_of_the_library_arrays():
    vertices, triangles = grid_plane()
    mesh = nk.TriangleMesh(vertices, triangles)
    view = mesh.vertices
    assert view.shape == (400, 3) and not view.flags.writeable and not view.flags.owndata
    assert view.base is not None and np.array_equal(view, vertices)
    assert np.array_equal(mesh.triangles, triangles) and mesh.triangles.dtype == np.int32
    assert nk.surface_area(mesh) == pytest.approx(4e-4, rel=1e-12)
    needle = nk.needle_surface_mesh(nk.NeedleGeometry(shape="cone", tip_diameter="30 um", base_diameter="150 um",
                                                      length="500 um"))
    assert nk.signed_volume(needle) == pytest.approx(nk.volume(needle_geometry := nk.NeedleGeometry(
        shape="cone", tip_diameter="30 um", base_diameter="150 um", length="500 um")), rel=5e-3)
    assert needle_geometry.hollow is False


def test_a_straightest_geodesic_on_a_plane_is_the_straight_line():
    surface = nk.SurfaceMesh(nk.TriangleMesh(*grid_plane()))
    start = nk.surface_location(surface.closest_point(np.array([-0.004, -0.003, 0.0])))
    path = nk.straightest_geodesic(surface, start, np.array([1.0, 0.5, 0.0]), "6 mm")
    assert path.status == nk.PathStatus.Completed and path.length == pytest.approx(6e-3, rel=1e-12)
    expected = np.array([-0.004, -0.003, 0]) + 6e-3 * np.array([1, 0.5, 0]) / np.sqrt(1.25)
    assert np.allclose(path.end_point, expected, atol=1e-12)
    assert path.points.shape[1] == 3 and np.allclose(path.points[:, 2], 0)
    target = nk.surface_location(surface.closest_point(expected))
    distance = nk.geodesic_distance(surface, start, target)
    assert distance.status == nk.DistanceStatus.Converged and distance.distance == pytest.approx(6e-3, rel=1e-9)


@pytest.mark.parametrize("argument, value, message", [
    ("vertices", np.zeros((4, 2)), r"vertices: an array of shape \(4, 2\) is not an array of shape \(N, 3\)"),
    ("vertices", np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]]), r"vertices\[1, 1\]: nan is not a finite number"),
    ("vertices", "not an array", "vertices: str is not an array"),
    ("triangles", np.array([[0, 1, 7]]), r"triangles\[0, 2\]: vertex 7 does not exist"),
    ("triangles", np.array([[0, 1, 1.5]]), r"triangles\[0, 2\]: 1.5 is not a node index"),
])
def test_bad_arrays_raise_invalid_input_naming_the_argument_and_index(argument, value, message):
    arguments = dict(vertices=np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0.0]]), triangles=np.array([[0, 1, 2]]))
    arguments[argument] = value
    with pytest.raises(nk.InvalidInput, match=message):
        nk.TriangleMesh(**arguments)


@pytest.mark.parametrize("case", ["patch_neck_rigid.toml", "patch_neck_flexible.toml"])
def test_a_patch_fit_gives_the_cli_summary(case):
    path = EXAMPLES / case
    c = nk.read_patch_case(str(path))
    surface = nk.SurfaceMesh(nk.read_triangle_mesh(str(c.mesh), c.mesh_unit))
    run = nk.fit_and_evaluate(surface, c.design, nk.FitAndEvaluateOptions(placement=c.placement, fit=c.fit,
                                                                          evaluation=c.evaluation))
    ours = nk.patch_summary_json(run.design, c.fit, run.fit, run.evaluation, run.fit_seconds * 1e3)
    cli = cli_json("patch", path)
    # Timing, the CLI's geodesic check and its warnings (io.patch_scale_warnings, mesh attribution) are the CLI's.
    for key in ("fit_ms", "spring_geodesic_strain", "spring_geodesics_not_converged", "notes"):
        ours.pop(key, None), cli.pop(key, None)
    assert ours == cli
    # The pieces give the same patch as the pipeline.
    design = nk.patch_design(c.design)
    frame = nk.patch_frame(surface, c.placement, float(np.hypot(design.width_u, design.width_v)), design.needle.length)
    fit = nk.fit_patch(surface, design, frame, c.fit)
    np.testing.assert_array_equal(fit.positions, run.fit.positions)
    # With a progress callback: fractions that never decrease up to 1 (one per node mapped by node sweeping), and the
    # same fit; an exception raised in it stops the fit and comes out of fit_and_evaluate.
    fractions = []
    reported = nk.fit_and_evaluate(surface, c.design, nk.FitAndEvaluateOptions(
        placement=c.placement, fit=c.fit, evaluation=c.evaluation), progress=fractions.append)
    assert fractions == sorted(fractions) and fractions[0] == 0 and fractions[-1] == 1
    assert len(fractions) >= (100 if c.fit.kind == nk.PatchKind.Flexible else 4)
    np.testing.assert_array_equal(reported.fit.positions, run.fit.positions)

    def stop(fraction):
        if fraction > 0.1:
            raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        nk.fit_and_evaluate(surface, c.design, nk.FitAndEvaluateOptions(placement=c.placement, fit=c.fit,
                                                                        evaluation=c.evaluation), progress=stop)
    arrays = run.evaluation.needle_arrays()
    assert arrays["tip"].shape == (100, 3) and arrays["buckling_force"].shape == (100,)
    assert np.allclose(np.linalg.norm(arrays["tip"] - arrays["base"], axis=1), design.needle.length, rtol=1e-12)
