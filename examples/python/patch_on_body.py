"""A rigid patch fitted on a body mesh (dissertation §6.4.1): the 10 x 10 mm, 100-needle SU-8 patch of
examples/patch_neck_rigid.toml pressed onto the Visible Human Male neck (data/meshes/), every needle evaluated, and
a 3D plot of the per-needle buckling forces over the surface.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/patch_on_body.py --out out/patch

Writes patch_forces.png, needles.csv and summary.json into --out.
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
parser.add_argument("--case", default=str(EXAMPLES / "patch_neck_rigid.toml"), help="patch case file")
parser.add_argument("--out", default="patch", help="output folder")
args = parser.parse_args()
out = pathlib.Path(args.out)
out.mkdir(parents=True, exist_ok=True)

case = nk.read_patch_case(args.case)
surface = nk.SurfaceMesh(nk.read_triangle_mesh(str(case.mesh), case.mesh_unit))
# The patch pipeline of `needlekit patch`: design, frame, fit, every needle evaluated.
run = nk.fit_and_evaluate(surface, case.design,
                          nk.FitAndEvaluateOptions(placement=case.placement, fit=case.fit, evaluation=case.evaluation))
design, frame, fit, evaluation = run.design, run.frame, run.fit, run.evaluation
diagonal = float(np.hypot(design.width_u, design.width_v))
needles = evaluation.needle_arrays()
summary = nk.patch_summary_json(design, case.fit, fit, evaluation, run.fit_seconds * 1e3)
print(f"{case.mesh.name}: {summary['kind']} patch, fit {summary['status']}, {evaluation.penetrating} of "
      f"{len(evaluation.needles)} needles penetrate, buckling force {evaluation.buckling_force.min:.4g} .. "
      f"{evaluation.buckling_force.max:.4g} N, angle up to {np.degrees(evaluation.angle.max):.3g} deg")

# The surface around the patch and the needles coloured by their buckling force (Figs 6.21-6.23).
vertices, triangles = surface.mesh().vertices, surface.mesh().triangles
near = np.linalg.norm(vertices - frame.surface_point, axis=1) < diagonal
keep = near[triangles].all(axis=1)
figure = plt.figure(figsize=(7, 6))
axis = figure.add_subplot(projection="3d")
axis.plot_trisurf(*(vertices[:, k] * 1e3 for k in range(3)), triangles=triangles[keep], color="#e8d0c0", alpha=0.35,
                  linewidth=0)
hits = needles["hits_surface"]
points = axis.scatter(*(needles["surface_point"][hits, k] * 1e3 for k in range(3)),
                      c=needles["buckling_force"][hits], cmap="viridis", s=18)
figure.colorbar(points, ax=axis, shrink=0.7, label="buckling force |F|/cos(theta) (N)")
axis.set_xlabel("x (mm)"), axis.set_ylabel("y (mm)"), axis.set_zlabel("z (mm)")
axis.set_title(f"{summary['kind']} patch on {case.mesh.name}: per-needle buckling force")
figure.tight_layout()
figure.savefig(out / "patch_forces.png", dpi=110)
nk.write_text_file_atomically(str(out / "needles.csv"), nk.patch_needles_csv(design, fit, evaluation))
nk.write_text_file_atomically(str(out / "summary.json"), json.dumps(summary, indent=2) + "\n")
print(f"wrote {out / 'patch_forces.png'}, needles.csv and summary.json")
