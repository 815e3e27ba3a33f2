"""Tissue meshes and FE indentation from Python: progress callbacks, the GIL released, Ctrl-C stops the run with
nothing half-written, and the insertion pieces (post-puncture loads, the insertion curve)."""
import json
import threading

import numpy as np
import pytest

import needlekit as nk
from conftest import EXAMPLES


def coarse_flat_punch(steps=2):
    case = nk.read_indentation_case(str(EXAMPLES / "indent_flat_punch.toml"))
    case.block.size_at_site = "60 um"
    case.block.size_far = "900 um"
    case.steps = steps
    return case


def test_a_tissue_mesh_has_numpy_nodes_and_layers():
    options = nk.LayeredBlockOptions(width="1 mm", length="1 mm", size_at_site="60 um", size_far="300 um",
                                     refinement_radius="200 um")
    result = nk.layered_block_mesh(options)
    mesh = result.mesh
    assert mesh.nodes.shape[1] == 3 and mesh.tets.shape[1] == 4 and len(mesh.tet_layer) == len(mesh.tets)
    assert [layer.name for layer in mesh.layers] == [layer.name for layer in nk.skin_layers()]
    assert mesh.nodes[:, 2].max() == pytest.approx(0, abs=1e-12)  # top surface z = 0
    assert mesh.nodes[:, 2].min() == pytest.approx(-1150e-6, rel=1e-9)  # the skin preset's 1150 um
    assert np.ptp(mesh.nodes[:, 0]) == pytest.approx(1e-3, rel=1e-9)
    assert {q.name for q in result.quality} == {layer.name for layer in mesh.layers}


def test_indentation_reports_progress_and_runs_without_the_gil(tmp_path):
    seen, other_thread_ran = [], []
    ticker = threading.Thread(target=lambda: other_thread_ran.append(sum(range(1000))))

    def progress(p):
        if not ticker.is_alive() and not other_thread_ran:
            ticker.start()
        seen.append((p.stage, p.fraction))

    result = nk.run_indentation(coarse_flat_punch(), progress=progress, output_directory=str(tmp_path))
    ticker.join()
    assert other_thread_ran  # another Python thread ran while the FE worked
    assert result.status == nk.IndentationStatus.ReachedDepth and len(result.steps) == 2
    assert {stage for stage, _ in seen} >= {"mesh", "setup", "step"} and seen[-1][1] == pytest.approx(1)
    assert result.depth == pytest.approx([10e-6, 20e-6]) and np.all(np.diff(result.force) > 0)
    # a flat punch compresses the tissue under it more with depth, far from crushing it
    assert 0.3 < result.min_volume_ratio[1] < result.min_volume_ratio[0] < 1
    assert nk.indentation_json(coarse_flat_punch(), result)["status"] == "reached-depth"
    assert (tmp_path / "flat_punch_result.json").exists() and (tmp_path / "flat_punch.pvd").exists()


def test_a_rezoned_run_reports_its_remesh_and_writes_every_step(tmp_path):
    case = coarse_flat_punch()
    case.solver.contact = nk.ContactModel.Surface
    case.solver.order = nk.ElementOrder.Linear
    case.solver.rezone = True
    case.solver.rezone_volume_ratio = 0.999  # after the first step, whatever its J
    written = []  # the rezonings in the incomplete result file while the run goes on

    def watch(progress):
        path = tmp_path / "flat_punch_result.json"
        if path.exists():
            partial = json.loads(path.read_text())
            if partial["status"] == "incomplete":
                written.append(partial["remeshes"])

    result = nk.run_indentation(case, progress=watch, output_directory=str(tmp_path))
    assert result.status == nk.IndentationStatus.ReachedDepth, result.reason
    assert len(result.remeshes) == 1  # the last step is never followed by one
    remesh = result.remeshes[0]
    assert remesh.failure == "" and remesh.step == 1 and remesh.depth == pytest.approx(10e-6)
    assert remesh.elements_after > 0 and abs(remesh.force_jump) < 0.02
    assert remesh.balance in (nk.StartBalance.Newton, nk.StartBalance.Eased)
    assert remesh.force_before == pytest.approx(result.force[0])
    assert (tmp_path / "flat_punch_step_002.vtu").exists()  # the step solved on the new mesh
    assert nk.indentation_json(case, result)["remeshes"][0]["step"] == 1
    assert written and written[-1] and written[-1][0]["step"] == 1  # written when it happened, before the end


def test_ctrl_c_stops_the_run_cleanly(tmp_path):
    def interrupt(p):
        if p.stage == "step":
            raise KeyboardInterrupt  # what PyErr_CheckSignals raises on Ctrl-C

    with pytest.raises(KeyboardInterrupt):
        nk.run_indentation(coarse_flat_punch(steps=4), progress=interrupt, output_directory=str(tmp_path))
    assert not list(tmp_path.glob("*tmp*"))  # nothing half-written
    assert not (tmp_path / "flat_punch_result.json").exists()  # the run did not finish


def test_the_insertion_curve_from_a_pre_puncture_curve_and_the_post_puncture_load():
    needle = nk.NeedleGeometry(shape="cylinder", tip_diameter="230 um", base_diameter="230 um", length="1000 um")
    loads = nk.post_puncture_loads(nk.needle_surface_mesh(needle))
    # A flat tip: its face, the 64-gon of the surface mesh, is the loaded (alpha) area.
    segments, radius = nk.NeedleMeshOptions().circumferential_segments, 115e-6
    assert loads.alpha_area == pytest.approx(segments / 2 * radius ** 2 * np.sin(2 * np.pi / segments), rel=1e-9)
    pre = nk.PrePunctureCurve(nk.ForceDepthCurve(np.array([0, 100e-6, 200e-6]), np.array([0, 0.05, 0.12])),
                              nk.PuncturePoint(depth="200 um", force="0.12 N",
                                               criterion=nk.PunctureCriterion.CriticalPressure))
    curve = nk.insertion_curve([pre], loads, stiffness="0.84 N/mm2", scale=0.168, final_depth="1000 um")
    assert curve.status == nk.InsertionStatus.Complete and curve.depth[-1] == pytest.approx(1e-3)
    forces = nk.post_puncture_forces(loads, np.array([500e-6]), "0.84 N/mm2", 0.168)
    assert forces[0] > 0


def test_the_complete_insertion_of_an_insertion_case_with_a_given_pre_puncture_curve():
    """The library's pipeline (`needlekit insert`) without FE: after the puncture the force is the post-puncture
    model's K*S times the loaded area (Eq 3.18), here checked against post_puncture_forces."""
    case = nk.read_insertion_case(str(EXAMPLES / "insert_cylinder.toml"))
    options = case.options
    options.pre_puncture = nk.PrePunctureCurve(
        nk.ForceDepthCurve(np.array([0, 100e-6, 200e-6]), np.array([0, 0.05, 0.12])),
        nk.PuncturePoint(depth="200 um", force="0.12 N", criterion=nk.PunctureCriterion.CriticalPressure))
    result = nk.complete_insertion(case.indentation, options)
    assert result.status == nk.CompleteInsertionStatus.Complete and result.indentation is None
    curve = result.curve
    cutting = np.array([phase == nk.InsertionPhase.Cutting for phase in curve.phase])
    expected = nk.post_puncture_forces(result.loads, curve.depth[cutting], result.stiffness, result.scale)
    np.testing.assert_allclose(curve.force[cutting], expected, rtol=1e-12)
    assert curve.depth[-1] == pytest.approx(options.curve.final_depth)


def test_an_array_case_gives_every_needle_and_the_totals():
    case = nk.read_indentation_case(str(EXAMPLES / "indent_array_3x3.toml"))
    assert case.array.rows == 3 and case.array.layout == nk.ArrayLayout.Square
    assert case.array.pitch == pytest.approx(600e-6)
    assert len(case.needles) == 9
    nk.set_array(case, nk.NeedleArray(rows=2, columns=2, pitch="800 um", margin="400 um", backing_plate=True),
                 size_width=False, size_length=False)  # the 3 x 3 example's block
    case.block.size_at_site = "60 um"
    case.steps = 3
    result = nk.run_indentation(case)
    assert len(result.needles) == 4 and result.array is not None
    # The array is centred on the block: needles at (+-400 um, +-400 um).
    assert sorted(abs(n.position[0]) for n in result.needles) == pytest.approx([400e-6] * 4)
    forces = np.array([n.force for n in result.needles])  # needle x step
    assert forces.shape == (4, len(result.steps))
    # Four needles placed symmetrically carry the same force up to the mesh's asymmetry (5 % here on a coarse
    # unstructured mesh; the verification tests check 1 % on fine ones), and together the step's total.
    assert np.ptp(forces[:, -1]) < 0.08 * forces[:, -1].mean()
    assert forces.sum(axis=0) == pytest.approx(result.force, rel=1e-9)
    assert result.array.plate_travel == pytest.approx(result.depth)
    assert 0 <= result.array.punctured_fraction[-1] <= 1


def test_the_averaged_pressure_law_is_a_puncture_option_with_units():
    options = nk.PunctureOptions(criterion=nk.PunctureLaw.AveragedPressure, critical_pressure="0.5 MPa",
                                 material_length="40 um")
    assert options.criterion == nk.PunctureLaw.AveragedPressure
    assert options.material_length == pytest.approx(40e-6)
    assert nk.PunctureOptions().criterion == nk.PunctureLaw.Dissertation
    assert nk.PunctureOptions().material_length == pytest.approx(50e-6)
    with pytest.raises(Exception, match="material_length"):
        nk.PunctureOptions(material_length="40")  # a length without its unit
    case = coarse_flat_punch()
    case.solver.contact = nk.ContactModel.TipNodes
    case.puncture = options
    with pytest.raises(Exception, match="puncture.criterion"):  # the tip-node rule has no contact field
        nk.run_indentation(case)
