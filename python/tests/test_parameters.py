"""Every parameter table's class binds its rows as docs/reference.md lists them (a C++ unit test checks that the
reference is what the tables generate): SolverOptions exactly the rows of fem::kSolverParameters, every field a
property with its docstring, every field a keyword of the constructor, quantities with units; the other tabled
classes every row of theirs, and the commands' --help every key their files take."""
import re

import needlekit
import pytest

from conftest import SOURCE_DIR, CLI


def reference_sections():
    """(title, class name, section text) of each table in docs/reference.md."""
    text = (SOURCE_DIR / "docs" / "reference.md").read_text()
    return [(title, options, section) for title, section in re.findall(r"^## ([^\n]+)\n\n(.*?)(?=^## |\Z)", text, re.M | re.S)
            for options in re.findall(r"\| Python `([A-Za-z]+)\.` \|", section)]


def reference_rows(options):
    """(key, python name, default) of each row of `options` in docs/reference.md (every table of that class)."""
    return [row for _, name, section in reference_sections() if name == options
            for row in re.findall(r"^\| `([a-z_.]+)` \| [^|]+ \| `([^`]+)` \|.*\| `([a-z_]+)` \|$", section, re.M)]


def properties(cls):
    return {name for name, value in vars(cls).items() if isinstance(value, property)}


def test_solver_options_binds_exactly_the_rows_of_its_table():
    names = {name for _, _, name in reference_rows("SolverOptions")}
    assert len(names) == 29  # SolverOptions' 30 fields but the progress callback
    assert properties(needlekit.SolverOptions) == names


def test_each_property_documents_its_range_and_default():
    defaults = needlekit.SolverOptions()
    for key, _, name in reference_rows("SolverOptions"):
        doc = getattr(needlekit.SolverOptions, name).__doc__
        assert "Default: " in doc, name
        assert f"  {name}: " in needlekit.SolverOptions.__doc__, name
    assert "in (0, 1)" in needlekit.SolverOptions.residual_tolerance.__doc__
    assert defaults.residual_tolerance == 1e-6


def test_the_keyword_constructor_takes_every_field_and_quantities_with_units():
    options = needlekit.SolverOptions(friction=0.2, two_pass=True, backend=needlekit.SolverBackend.Builtin,
                                      volumetric=needlekit.VolumetricFormulation.Element, boundary_tolerance="2 nm",
                                      max_augmentations=3, line_search=False, extrapolate_predictor=False)
    assert options.friction == 0.2 and options.two_pass and not options.line_search
    assert options.boundary_tolerance == pytest.approx(2e-9)
    assert options.max_augmentations == 3 and not options.extrapolate_predictor
    with pytest.raises(needlekit.InvalidInput, match="no field 'frction'"):
        needlekit.SolverOptions(frction=0.2)


def test_describe_lists_the_same_keys_as_the_reference():
    import subprocess
    keys = [key for _, _, section in reference_sections()
            for key in re.findall(r"^\| `([a-z_.]+)` \|", section, re.M)]
    described = subprocess.run([CLI, "describe", "--all"], capture_output=True, text=True, check=True).stdout
    assert re.findall(r"^([a-z_.]+)$", described, re.M) == keys


def test_every_tabled_class_binds_every_row_with_its_docstring():
    for _, options, _ in reference_sections():
        cls = getattr(needlekit, options)
        for key, _, name in reference_rows(options):
            assert name in properties(cls), (options, name)
            assert "Default: " in getattr(cls, name).__doc__, (options, name)
            assert f"  {name}: " in cls.__doc__, (options, name)


def test_the_help_of_each_command_lists_every_key_of_its_files():
    import subprocess
    for title, options, _ in reference_sections():
        for command in re.findall(r"`needlekit ([a-z-]+)`", title):
            help_text = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
            for key, _, _ in reference_rows(options):
                if "." in key:  # rows of no file are set by the commands' options or from Python
                    assert re.search(rf"(^|[^a-z_]){key.split('.')[1]}( |$|,)", help_text, re.M), (command, key)


def test_loading_reads_like_the_case_file():
    case = needlekit.IndentationCase(depth="150 um", angle="10 deg", steps=5, stop_at_puncture=False)
    assert case.depth == pytest.approx(150e-6) and case.angle == pytest.approx(0.174532925199)
    assert case.steps == 5 and not case.stop_at_puncture
    assert "negation of the case file's loading.continue_after_puncture" in needlekit.IndentationCase.stop_at_puncture.__doc__


def test_post_puncture_options_read_like_the_case_file():
    options = needlekit.PostPunctureOptions(reference_radius="100 um", max_edge_fraction=0.1, axial_component=True)
    assert options.reference_radius == pytest.approx(100e-6) and options.max_edge_fraction == 0.1
    assert options.axial_component and options.cap_at_cutting_pressure and options.tip_tolerance == 1e-6
    assert "axis_point" in properties(needlekit.PostPunctureOptions)


def test_the_fit_options_read_like_the_patch_case_file():
    flexible = needlekit.FlexibleFitOptions(max_spring_energy="0.05 mJ", walk=needlekit.WalkMethod.Unfolding)
    assert flexible.max_spring_energy == pytest.approx(5e-5) and flexible.walk == needlekit.WalkMethod.Unfolding
    assert needlekit.EquilibriumFitOptions(node_load="70 mN").node_load == pytest.approx(0.07)
    fit = needlekit.FitOptions(kind=needlekit.PatchKind.Equilibrium, equilibrium=needlekit.EquilibriumFitOptions(tolerance=1e-4))
    assert fit.kind == needlekit.PatchKind.Equilibrium and fit.equilibrium.tolerance == 1e-4
    assert "in (0, inf]" in needlekit.FlexibleFitOptions.max_spring_energy.__doc__


def test_an_optional_quantity_is_none_unless_given():
    assert needlekit.PunctureOptions().critical_pressure is None and needlekit.PunctureOptions().toughness is None
    assert needlekit.PunctureOptions(toughness="100 J/m2").toughness == pytest.approx(100)
    assert "Default: None." in needlekit.PunctureOptions.critical_pressure.__doc__
    assert "optional" in [kind for key, kind in re.findall(r"^\| `(puncture\.[a-z_]+)` \| [^|]+ \| `([^`]+)` \|",
                                                            (SOURCE_DIR / "docs" / "reference.md").read_text(), re.M)
                          if key == "puncture.toughness"]


def test_the_insertion_sampling_and_calibration_tables_read_like_their_files():
    import math
    model = needlekit.PostPunctureFitOptions(stiffness="0.2 N/mm2", scale=0.3)
    assert model.stiffness == pytest.approx(0.2e6) and model.scale == 0.3 and not model.fit_stiffness
    curve = needlekit.InsertionCurveOptions(final_depth="1 mm", cutting_samples=50)
    assert curve.final_depth == pytest.approx(1e-3) and curve.cutting_samples == 50
    classes = needlekit.TriangleClassificationOptions(side_tolerance="2 deg", occlusion_test=True)
    assert classes.side_tolerance == pytest.approx(math.radians(2)) and classes.occlusion_test
    assert {"insertion_direction", "axis_point"} <= properties(needlekit.TriangleClassificationOptions)
    sampling = needlekit.PropagationOptions(samples=256, method=needlekit.SamplingMethod.MonteCarlo, seed=7)
    assert sampling.samples == 256 and sampling.method == needlekit.SamplingMethod.MonteCarlo and sampling.seed == 7
    assert not needlekit.CalibrationSolverSettings(mesh_error=False).mesh_error
    assert "in [0, 0.1)" in needlekit.CalibrationSolverSettings.relative_step.__doc__
