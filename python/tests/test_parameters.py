"""SolverOptions binds exactly the rows of fem::kSolverParameters, as docs/reference.md lists them (a C++ unit test
checks that the reference is what the tables generate): every field a property with its docstring, every field a
keyword of the constructor, quantities with units."""
import re

import needlekit
import pytest

from conftest import SOURCE_DIR, CLI


def reference_rows(options):
    """(key, python name, default) of each row of `options` in docs/reference.md."""
    text = (SOURCE_DIR / "docs" / "reference.md").read_text()
    section = text.split(f"| Python `{options}.` |")[1].split("\n## ")[0]
    return re.findall(r"^\| `([a-z_.]+)` \| [^|]+ \| `([^`]+)` \|.*\| `([a-z_]+)` \|$", section, re.M)


def properties(cls):
    return {name for name, value in vars(cls).items() if isinstance(value, property)}


def test_solver_options_binds_exactly_the_rows_of_its_table():
    names = {name for _, _, name in reference_rows("SolverOptions")}
    assert len(names) == 26  # SolverOptions' 27 fields but the progress callback
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
    keys = [key for key, _, _ in reference_rows("SolverOptions")]
    described = subprocess.run([CLI, "describe", "--all"], capture_output=True, text=True, check=True).stdout
    assert re.findall(r"^([a-z_]+\.[a-z_]+)$", described, re.M) == keys
