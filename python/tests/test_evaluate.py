"""evaluate, optimize and sweep from Python give the CLI's JSON number for number; quantities with units; errors."""
import math

import numpy as np
import pytest

import needlekit as nk
from conftest import EXAMPLES, cli_json


@pytest.mark.parametrize("design_file", sorted(EXAMPLES.glob("evaluate_*.toml")), ids=lambda p: p.name)
def test_evaluate_equals_the_cli_json_to_the_last_digit(design_file):
    file = nk.read_design_file(str(design_file))
    result = nk.evaluate(file)
    assert nk.performance_json(file.design, result) == cli_json("evaluate", design_file)
    if design_file.name == "evaluate_table_6_1_cone.toml":  # §6.3.1: PI = 1.288e-4 1/um, d = 42.9 um
        assert result.performance_index * 1e-6 == pytest.approx(1.288e-4, rel=5e-4)
        assert result.deformation * 1e6 == pytest.approx(42.9, abs=0.1)


def test_optimize_equals_the_cli_json():
    path = EXAMPLES / "optimize_fig_6_20_cone_solid.toml"
    space = nk.read_space_file(str(path)).space
    result = nk.optimize_design(space, nk.OptimizerOptions(top=5))
    ours, cli = nk.optimizer_json(space, result), cli_json("optimize", path, "--top", 5)
    ours.pop("seconds"), cli.pop("seconds")
    assert ours == cli
    # Table 6.3, solid cone: n = 25, D1 = 70 um, D2 = 80 um, w = 6000 um, L = 500 um.
    best = result.top[0]
    assert [best.needles_per_row, *(round(x * 1e6) for x in (best.tip_diameter, best.base_diameter, best.width,
                                                             best.length))] == [25, 70, 80, 6000, 500]


def test_sweep_equals_the_cli_json():
    path = EXAMPLES / "evaluate_table_6_1_cone.toml"
    file = nk.read_design_file(str(path))
    sweep = nk.SweepOptions(parameter="base_diameter", from_="50 um", to="300 um", step="10 um")
    result = nk.sensitivity_sweep(file.design, file.conditions, file.options, sweep)
    assert nk.sweep_json(result) == cli_json("sweep", path, "--vary", "base_diameter=50um:300um:10um")
    assert len(result.points) == 26 and result.points[0].value == pytest.approx(50e-6)


def test_quantities_are_si_floats_or_strings_with_units():
    a = nk.NeedleGeometry(shape="cone", tip_diameter="30 um", base_diameter="0.15 mm", length=500e-6)
    micrometre = nk.parse_quantity("1 um", nk.Dimension.Length)
    assert (a.tip_diameter, a.base_diameter, a.length) == (nk.parse_quantity("30 um", nk.Dimension.Length),
                                                           nk.parse_quantity("0.15 mm", nk.Dimension.Length), 500e-6)
    assert a.tip_diameter == pytest.approx(30 * micrometre, rel=1e-15)
    assert a.shape == nk.Shape.Cone
    material = nk.NeedleMaterial(name="x", youngs_modulus="4.5 GPa", yield_strength=None)
    assert material.youngs_modulus == 4.5e9 and material.yield_strength is None
    design = nk.ArrayDesign(needle=a, material="silicon", needles_per_row=10, width="1 cm")
    by_strings = nk.performance_index(design, nk.InsertionConditions(angle="10 deg", target_depth="50 um"))
    by_floats = nk.performance_index(design, nk.InsertionConditions(
        angle=math.radians(10), target_depth=nk.parse_quantity("50 um", nk.Dimension.Length)))
    assert by_strings.to_dict() == by_floats.to_dict()
    assert by_strings.to_dict()["buckling"]["method"] == "TaperedEigenvalue"


def test_a_quantity_of_the_wrong_dimension_is_invalid_input_naming_the_field():
    with pytest.raises(nk.InvalidInput, match="tip_diameter") as error:
        nk.NeedleGeometry(tip_diameter="3 N")
    assert isinstance(error.value, ValueError)
    with pytest.raises(nk.InvalidInput, match="width"):
        nk.ArrayDesign(width=[1, 2])
    with pytest.raises(nk.InvalidInput, match="no field 'tip'"):
        nk.NeedleGeometry(tip="30 um")
    with pytest.raises(nk.InvalidInput, match="length"):
        nk.NeedleGeometry(length=float("nan"))


def test_a_bad_design_file_names_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[needle]\nshape = "cone"\ntip_diameter = 30\nbase_diameter = "150 um"\nlength = "500 um"\n'
                   'material = "silicon"\n[array]\nneedles_per_row = 10\nwidth = "1 cm"\n')
    with pytest.raises(nk.InvalidInput, match=r"bad\.toml:3.*needle\.tip_diameter"):
        nk.evaluate(bad)


def test_an_invalid_design_raises_and_a_failing_one_has_a_status_and_reason():
    with pytest.raises(nk.InvalidInput, match="base_diameter"):
        nk.performance_index(nk.ArrayDesign(needle=nk.NeedleGeometry(shape="cone", tip_diameter="200 um",
                                                                     base_diameter="100 um", length="500 um")))
    short = nk.performance_index(nk.ArrayDesign(
        needle=nk.NeedleGeometry(shape="cylinder", tip_diameter="100 um", base_diameter="100 um", length="60 um"),
        material="silicon"))
    assert short.status == nk.PerformanceStatus.TooShort and "target depth" in short.reason
    assert short.performance_index == 0 and short.failed_checks & (1 << int(nk.PerformanceStatus.TooShort))


def test_the_optimizer_stops_cleanly_when_its_progress_callback_raises():
    space = nk.figure_6_20_space(nk.Shape.Cone, False)

    def interrupt(fraction):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nk.optimize_design(space, nk.OptimizerOptions(), progress=interrupt)
    seen = []
    assert nk.optimize_design(space, nk.OptimizerOptions(), progress=seen.append).status == nk.OptimizerStatus.Optimal
    assert seen and all(0 <= f <= 1 for f in seen) and np.all(np.diff(seen) >= 0)
