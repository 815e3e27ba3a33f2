"""evaluate_many equals the scalar performance_index on random designs (exactly), and refuses bad arrays."""
import numpy as np
import pytest

import needlekit as nk

SHAPES = [nk.Shape.Cylinder, nk.Shape.Cone, nk.Shape.Bevel]


def random_designs(count, seed=2026):
    """Valid designs of all three shapes, solid and hollow, with every kind of outcome (ok, too short, buckles,
    spacing violated)."""
    rng = np.random.default_rng(seed)
    shape = rng.integers(0, 3, count)
    d2 = rng.uniform(40e-6, 300e-6, count)
    d1 = np.where(shape == 0, d2, d2 * rng.uniform(0.1, 0.95, count))
    d3 = np.where(rng.random(count) < 0.5, 0.0, d1 * rng.uniform(0.1, 0.9, count))
    return dict(shape=shape.astype(np.uint8), needles_per_row=rng.integers(1, 40, count), tip_diameter=d1,
                base_diameter=d2, bore_diameter=d3, length=rng.uniform(50e-6, 2000e-6, count),
                width=rng.uniform(2e-3, 2e-2, count), angle=rng.uniform(0, 0.5, count),
                target_depth=rng.uniform(20e-6, 150e-6, count))


def scalar(d, i, material, conditions_tissue="skin"):
    design = nk.ArrayDesign(
        needle=nk.NeedleGeometry(shape=SHAPES[d["shape"][i]], tip_diameter=float(d["tip_diameter"][i]),
                                 base_diameter=float(d["base_diameter"][i]), bore_diameter=float(d["bore_diameter"][i]),
                                 length=float(d["length"][i])),
        material=material, needles_per_row=int(d["needles_per_row"][i]), width=float(d["width"][i]))
    conditions = nk.InsertionConditions(tissue=conditions_tissue, angle=float(d["angle"][i]),
                                        target_depth=float(d["target_depth"][i]))
    return nk.performance_index(design, conditions)


def test_evaluate_many_equals_the_scalar_evaluation_exactly_on_ten_thousand_random_designs():
    d = random_designs(10_000)
    many = nk.evaluate_many(material="titanium", **d)
    assert len(many) == 10_000
    statuses = set()
    for i in range(10_000):
        r = scalar(d, i, "titanium")
        expected = {"tip_area": r.tip_area, "puncture_force": r.puncture_force, "deformation": r.deformation,
                    "cutting_depth": r.cutting_depth, "permeation_depth": r.permeation_depth,
                    "diameter_at_surface": r.diameter_at_surface, "embedded_volume": r.embedded_volume,
                    "q_factor": r.q_factor, "hole_volume": r.hole_volume, "gap_volume": r.gap_volume,
                    "pitch": r.pitch, "fractional_skin_volume": r.fractional_skin_volume,
                    "needle_volume": r.needle_volume, "critical_buckling_load": r.buckling.critical_load,
                    "tapered_factor": r.buckling.tapered_factor, "slenderness_ratio": r.buckling.slenderness_ratio,
                    "buckling_force": r.buckling_force, "bending_force": r.bending_force,
                    "critical_bending_load": r.critical_bending_load, "performance_index": r.performance_index}
        for key, value in expected.items():
            assert getattr(many, key)[i] == value, (i, key)  # exact: the same code, the same bits
        assert many.status[i] == int(r.status) and many.failed_checks[i] == r.failed_checks
        assert many.buckling_method[i] == int(r.buckling.method)
        assert many.bending_ok[i] == (-1 if r.bending_ok is None else int(r.bending_ok))
        statuses.add(r.status)
    assert statuses == set(nk.PerformanceStatus.__members__.values())  # every outcome was exercised
    # The tapered-column factor is computed once per distinct section (random sections: all distinct).
    assert many.distinct_sections == int(np.count_nonzero(d["shape"] != 0))


def test_results_are_numpy_arrays_and_a_dataframe_with_units():
    d = random_designs(100)
    many = nk.evaluate_many(**d)
    assert isinstance(many.performance_index, np.ndarray) and many.performance_index.dtype == np.float64
    assert many.performance_index.flags.owndata is False  # the library's vector, not a copy
    frame = many.to_dataframe()
    assert {"tip_area_m2", "performance_index_1per_m", "critical_buckling_load_N", "status"} <= set(frame.columns)
    assert len(frame) == 100 and set(frame.status) <= {"ok", "constraint_violated", "too_short", "buckles", "bends"}
    i = int(np.argmax(many.failed_checks))
    assert many.reasons(i)[0] == many.status_names()[i]


def test_scalars_broadcast_and_take_units():
    many = nk.evaluate_many("cone", 10, "30 um", np.array([150e-6, 200e-6]), "500 um", "1 cm")
    one = nk.evaluate("%s/evaluate_table_6_1_cone.toml" % nk_examples())
    assert many.performance_index[0] == one.performance_index


def nk_examples():
    from conftest import EXAMPLES
    return EXAMPLES


@pytest.mark.parametrize("arguments, message", [
    (dict(tip_diameter=np.array([30e-6, np.nan])), r"tip_diameter\[1\]: nan is not a finite number"),
    (dict(length=np.array([[500e-6]])), "length: expected a 1-D array"),
    (dict(width=np.array(["1 cm", "2 cm"])), "width: expected a number"),
    (dict(needles_per_row=np.array([10, 10.5])), r"needles_per_row\[1\]: 10.5 is not a whole number"),
    (dict(base_diameter="150 N"), "base_diameter.*length"),
    (dict(tip_diameter=np.array([30e-6, 30e-6, 30e-6])), "3 values, but other columns have 2"),
    (dict(shape=["cone", "pyramid"]), r"shape\[1\]"),
    (dict(tip_diameter=np.array([30e-6, 400e-6])), r"design \[1\]: needle\.tip_diameter"),
])
def test_bad_arrays_raise_invalid_input_naming_the_argument_and_index(arguments, message):
    base = dict(shape="cone", needles_per_row=10, tip_diameter=30e-6, base_diameter=np.array([150e-6, 160e-6]),
                length=500e-6, width=1e-2)
    base.update(arguments)
    with pytest.raises(nk.InvalidInput, match=message):
        nk.evaluate_many(**base)
