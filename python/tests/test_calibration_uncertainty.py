"""Calibration, uncertainty, robust design and case-file writing from Python: the results equal the CLI's JSON to the
last digit, Ctrl-C (a raising progress callback) stops a fit, and edited case files read back with the new values."""
import math

import pytest

import needlekit as nk

from conftest import EXAMPLES, cli_json

# A cylinder design with the analytic tissue model written out, so that calibrate can fit alpha and tau.
DESIGN = """[needle]
shape = "cylinder"
tip_diameter = "{tip} um"
length = "600 um"
material = "silicon"
[array]
needles_per_row = 10
width = "1 cm"
[tissue]
model = {{ alpha = "{alpha} N", tau = "{tau} /mm" }}
"""


def synthetic_calibration(directory, tips=(80, 100, 120, 150)):
    """A calibration file fitting alpha and tau to the deformations d (Eq 4.3) that the true values (0.0183 N,
    6.25 /mm) give."""
    experiments = ""
    for tip in tips:
        truth = nk.evaluate(nk.parse_design_toml(DESIGN.format(tip=tip, alpha=0.0183, tau=6.25)))
        (directory / f"tip_{tip}.toml").write_text(DESIGN.format(tip=tip, alpha=0.01, tau=4))
        experiments += (f'[[experiments]]\nname = "tip {tip} um"\ncase = "tip_{tip}.toml"\n'
                        f'puncture = {{ depth = "{truth.deformation * 1e6!r} um" }}\n')
    path = directory / "fit.toml"
    path.write_text('[[parameters]]\npath = "tissue.model.alpha"\ninitial = "0.01 N"\nbounds = ["0.001 N", "0.1 N"]\n'
                    '[[parameters]]\npath = "tissue.model.tau"\ninitial = "4 /mm"\nbounds = ["1 /mm", "20 /mm"]\n'
                    + experiments)
    return path


def test_calibrate_recovers_alpha_and_tau_and_equals_the_cli(tmp_path):
    path = synthetic_calibration(tmp_path)
    problem = nk.read_calibration_file(str(path))
    iterations = []
    result = nk.calibrate(problem, progress=lambda p: iterations.append(p.iteration))
    assert result.status == nk.CalibrationStatus.Converged, result.reason
    alpha, tau = result.values()
    assert alpha == pytest.approx(0.0183, rel=1e-6)
    assert tau == pytest.approx(6250.0, rel=1e-6)
    assert iterations[0] == 0 and len(iterations) == result.iterations + 1
    ours = nk.calibration_json(problem, result)
    cli = cli_json("calibrate", path, "--no-plot", "--out", tmp_path / "out")
    for volatile in ("seconds", "files"):
        ours.pop(volatile, None)
        cli.pop(volatile, None)
    assert ours == cli
    assert set(ours["parameters"]) == {"tissue.model.alpha", "tissue.model.tau"}


def test_a_raising_progress_callback_stops_the_fit(tmp_path):
    problem = nk.read_calibration_file(str(synthetic_calibration(tmp_path)))

    def stop(progress):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nk.calibrate(problem, progress=stop)


def test_calibrated_case_text_writes_the_fitted_values_in_the_users_units(tmp_path):
    problem = nk.read_calibration_file(str(synthetic_calibration(tmp_path)))
    text = nk.calibrated_case_text(problem, 0, [0.0183, 6250.0])
    assert 'alpha = "0.0183 N"' in text and 'tau = "6.25 /mm"' in text


def test_case_files_are_edited_in_place_and_read_back(tmp_path):
    source = EXAMPLES / "insert_blunt_bevel.toml"
    text = source.read_text()
    old = nk.case_value(text, "tissue.layers.0.youngs_modulus", str(source))
    assert old.dimension == nk.Dimension.Pressure and old.value == 0.2e6
    edited = nk.with_case_value(text, "tissue.layers.0.youngs_modulus", "0.35 MPa", str(source))
    edited = nk.with_case_value(edited, "puncture.critical_pressure", 7e5, str(source))
    assert 'youngs_modulus = "0.35 MPa"' in edited
    assert edited.count("\n") == text.count("\n")  # comments and layout kept
    target = tmp_path / "insert_stiffer.toml"
    nk.write_text_file_atomically(str(target), edited)
    case = nk.read_insertion_case(str(target))
    assert case.indentation.block.layers[0].youngs_modulus == 0.35e6
    assert case.indentation.puncture.critical_pressure == 7e5
    with pytest.raises(nk.InvalidInput, match="tissue.layers.5.youngs_modulus"):
        nk.with_case_value(text, "tissue.layers.5.youngs_modulus", "1 MPa", str(source))
    with pytest.raises(nk.InvalidInput, match="youngs_modulus"):
        nk.with_case_value(text, "tissue.layers.0.youngs_modulus", "3 um", str(source))


def test_design_uncertainty_equals_the_cli():
    path = EXAMPLES / "uncertainty_cone_su8.toml"
    file = nk.read_uncertainty_file(str(path))
    result = nk.design_uncertainty(file.design, file.inputs, file.correlations,
                                   nk.DesignUncertaintyOptions(sampling=file.sampling))
    assert nk.uncertainty_json(file, result) == cli_json("uncertainty", path)
    success = result.event(nk.DesignEvent.Success)
    assert 0 < success.mean < 1 and success.ci95.lo <= success.mean <= success.ci95.hi
    assert result.index().name == "performance_index"
    assert [o.name for o in result.outputs] == ["performance_index", "puncture", "buckling_failure", "bending_failure",
                                                "reaches_target", "success", "invalid_sample"]
    assert len(result.index().first) == len(file.inputs)


def test_every_sd_zero_gives_the_deterministic_evaluation():
    file = nk.read_uncertainty_file(str(EXAMPLES / "uncertainty_cone_su8.toml"))
    inputs = [nk.DesignUncertainInput(key="needle.tip_diameter",
                                      distribution=nk.Distribution(kind=nk.DistributionKind.Normal, mean=70e-6, sd=0))]
    options = nk.DesignUncertaintyOptions(sampling=nk.PropagationOptions(samples=64, sobol_indices=False))
    result = nk.design_uncertainty(file.design, inputs, options=options)
    nominal = nk.performance_index(file.design.design, file.design.conditions, file.design.options)
    assert result.index().mean == nominal.performance_index
    assert result.index().sd == 0


def test_uncertainty_bad_input_names_the_key():
    file = nk.read_uncertainty_file(str(EXAMPLES / "uncertainty_cone_su8.toml"))
    bad = nk.DesignUncertainInput(key="needle.tip_diameter",
                                  distribution=nk.Distribution(kind=nk.DistributionKind.Normal, mean=70e-6, sd=-1e-6))
    with pytest.raises(nk.InvalidInput, match="needle.tip_diameter"):
        nk.design_uncertainty(file.design, [bad])
    with pytest.raises(nk.InvalidInput, match="needle.nose"):
        nk.design_uncertainty(file.design, [nk.DesignUncertainInput(key="needle.nose", distribution=bad.distribution)])
    with pytest.raises(nk.InvalidInput, match="uq.toml"):
        nk.parse_uncertainty_toml('[needle]\nshape = "cone"\n[uncertain]\n"needle.length" = { distribution = "x" }\n',
                                  "uq.toml")


def test_robust_design_equals_the_cli():
    path = EXAMPLES / "optimize_robust_cone_su8.toml"
    file = nk.read_space_file(str(path))
    options = nk.RobustDesignOptions(min_success_probability=file.robust.min_success_probability,
                                     sampling=file.robust.sampling)
    result = nk.robust_design(file.space, file.robust.inputs, file.robust.correlations, options)
    assert result.status == nk.RobustStatus.Found
    ours = nk.robust_design_json(file.space, options, result)
    cli = cli_json("optimize", path, "--top", len(ours["top"]))
    ours.pop("seconds")
    cli.pop("seconds")
    assert ours == cli
    assert not math.isnan(result.index_cost)


def test_enum_members_follow_the_library_tables():
    assert set(nk.DistributionKind.__members__) == {"Normal", "TruncatedNormal", "Lognormal", "Uniform", "Triangular"}
    assert set(nk.SamplingMethod.__members__) == {"MonteCarlo", "Sobol"}
    assert "BucklingFailure" in nk.DesignEvent.__members__
    assert ("needle.tip_diameter", "um") in [(k, u) for k, u, _ in nk.design_input_keys()]


def test_patch_uncertainty_equals_the_cli():
    path = EXAMPLES / "uncertainty_patch_neck.toml"
    file = nk.read_patch_uncertainty_file(str(path))
    result = nk.patch_uncertainty(file)
    assert nk.patch_uncertainty_json(file, result) == cli_json("uncertainty", path)
    success = result.needle_probabilities(nk.DesignEvent.Success)
    assert success.shape == (result.needles,)
    assert all(result.needle_event(n, nk.DesignEvent.Success).mean == success[n] for n in range(result.needles))
    # Every needle succeeding is at most as likely as the least likely needle succeeding.
    assert result.all_succeed().mean <= success.min()
    with pytest.raises(nk.InvalidInput, match="invalid_sample"):
        result.needle_probabilities(nk.DesignEvent.InvalidSample)


def without_wall_times(value):
    """The JSON without the keys that hold wall times (they differ from run to run)."""
    if isinstance(value, dict):
        return {k: without_wall_times(v) for k, v in value.items() if not k.endswith("seconds")}
    if isinstance(value, list):
        return [without_wall_times(v) for v in value]
    return value


def test_fe_surrogate_equals_the_cli_and_reproduces_its_fe_runs():
    path = EXAMPLES / "uncertainty_fe_puncture.toml"
    file = nk.read_fe_uncertainty_file(str(path))
    done = []
    result = nk.fe_surrogate(file.indentation, file.inputs, file.correlations, file.options,
                             progress=lambda d, t: done.append((d, t)))
    assert result.status == nk.FeSurrogateStatus.Ok, result.reason
    assert done[-1][0] == done[-1][1] == len(result.design) + len(result.validation)
    ours = without_wall_times(nk.fe_uncertainty_json(file, result))
    cli = without_wall_times(cli_json("uncertainty", path))
    assert ours == cli
    # The surrogate at a held-out run's inputs is that run's fitted value, within the stated error of the FE value.
    run = result.validation[0]
    depth, force = result.surrogate(run.inputs)
    assert depth == run.surrogate_depth and force == run.surrogate_force
    assert abs(depth / run.depth - 1) <= result.validation_depth_error.max + 1e-15


def test_fe_surrogate_stops_on_a_raising_progress_callback():
    file = nk.read_fe_uncertainty_file(str(EXAMPLES / "uncertainty_fe_puncture.toml"))

    def stop(done, total):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        nk.fe_surrogate(file.indentation, file.inputs, file.correlations, file.options, progress=stop)
