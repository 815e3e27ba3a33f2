"""A design study in Python: evaluate the dissertation's Table 6.1 solid cone, find the best solid cone of the
Fig 6.20 grid (Table 6.3), and plot the sensitivity of the performance index to D1, D2, L and w around the optimum,
computed with evaluate_many (one call per curve).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/design_study.py --out out/design_study

Writes design_study.png and design_study.json into --out.
"""
import argparse
import json
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import needlekit as nk  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--out", default="design_study", help="output folder")
parser.add_argument("--points", type=int, default=400, help="points per sensitivity curve")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

# 1. One design, as `needlekit evaluate`.
table_6_1 = nk.read_design_file(str(EXAMPLES / "evaluate_table_6_1_cone.toml"))
evaluated = nk.evaluate(table_6_1)
print(f"Table 6.1 solid cone: PI = {evaluated.performance_index * 1e-6:.4g} 1/um (dissertation: 1.288e-4), "
      f"d = {evaluated.deformation * 1e6:.3g} um, P_cr = {evaluated.buckling.critical_load:.3g} N")

# 2. The optimizer over the Fig 6.20 grid, as `needlekit optimize`.
space = nk.read_space_file(str(EXAMPLES / "optimize_fig_6_20_cone_solid.toml")).space
optimum = nk.optimize_design(space, nk.OptimizerOptions(top=3))
best = optimum.top[0]
print(f"optimum of {optimum.grid_points} designs: n = {best.needles_per_row}, D1 = {best.tip_diameter * 1e6:.0f} um, "
      f"D2 = {best.base_diameter * 1e6:.0f} um, w = {best.width * 1e6:.0f} um, L = {best.length * 1e6:.0f} um, "
      f"PI = {best.performance_index * 1e-6:.4g} 1/um")

# 3. One-at-a-time sensitivity around the optimum, each curve one evaluate_many call.
around = dict(shape="cone", needles_per_row=best.needles_per_row, tip_diameter=best.tip_diameter,
              base_diameter=best.base_diameter, length=best.length, width=best.width,
              material=space.material, tissue=space.conditions.tissue,
              target_depth=space.conditions.target_depth)
curves = {
    "tip_diameter": np.linspace(10e-6, 0.99 * best.base_diameter, args.points),
    "base_diameter": np.linspace(1.01 * best.tip_diameter, 300e-6, args.points),
    "length": np.linspace(100e-6, 1000e-6, args.points),
    "width": np.linspace(3e-3, 12e-3, args.points),
}
figure, axes = plt.subplots(1, 4, figsize=(16, 3.8), sharey=True)
summary = {"table_6_1_cone_performance_index_per_um": evaluated.performance_index * 1e-6,
           # SI floats shown in um, rounded to 1e-9 um so that the grid's 70 um reads 70, not 70.00000000000001
           "optimum": {"needles_per_row": best.needles_per_row, "tip_diameter_um": round(best.tip_diameter * 1e6, 9),
                       "base_diameter_um": round(best.base_diameter * 1e6, 9), "width_um": round(best.width * 1e6, 9),
                       "length_um": round(best.length * 1e6, 9),
                       "performance_index_per_um": best.performance_index * 1e-6},
           "sensitivity": {}}
for axis, (name, values) in zip(axes, curves.items()):
    values = np.unique(np.append(values, around[name]))  # the curve passes through the optimum
    result = nk.evaluate_many(**{**around, name: values})
    axis.plot(values * 1e6, result.performance_index * 1e-6, lw=1.5)
    axis.axvline(around[name] * 1e6, color="grey", ls=":", lw=1)
    axis.set_xlabel(f"{name} (um)")
    axis.grid(alpha=0.3)
    summary["sensitivity"][name] = {"max_performance_index_per_um": float(result.performance_index.max() * 1e-6),
                                    "statuses": sorted(set(result.status_names()))}
axes[0].set_ylabel("performance index (1/um)")
figure.suptitle(f"Solid silicon cone around the Fig 6.20 optimum (n = {best.needles_per_row}), skin, T = 50 um")
figure.tight_layout()
figure.savefig(out / "design_study.png", dpi=110)
(out / "design_study.json").write_text(json.dumps(summary, indent=2) + "\n")
print(f"wrote {out / 'design_study.png'} and {out / 'design_study.json'}")
