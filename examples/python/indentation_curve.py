"""An indentation force-depth curve in Python: Sneddon's flat punch (examples/indent_flat_punch.toml: a 230 um flat
cylinder into a silicone-rubber block, quadratic tetrahedra) run by the FE solver with a progress callback, written
as a ParaView series, and plotted against Sneddon's half-space solution F = 2 a E d / (1 - nu^2).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/indentation_curve.py --out out/indentation

Writes indentation.png and the ParaView files (flat_punch.pvd, flat_punch_step_KKK.vtu, CSV, JSON) into --out.
--size-at-tip / --size-far / --steps coarsen the run (the tests use a coarse mesh).
"""
import argparse
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import needlekit as nk  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--case", default=str(EXAMPLES / "indent_flat_punch.toml"), help="indentation case file")
parser.add_argument("--out", default="indentation", help="output folder")
parser.add_argument("--size-at-tip", help='element size under the punch, e.g. "40 um"')
parser.add_argument("--size-far", help='element size far from the punch, e.g. "800 um"')
parser.add_argument("--steps", type=int, help="load steps")
args = parser.parse_args()
out = pathlib.Path(args.out)

case = nk.read_indentation_case(args.case)
if args.size_at_tip:
    case.block.size_at_site = args.size_at_tip
if args.size_far:
    case.block.size_far = args.size_far
if args.steps:
    case.steps = args.steps


def show(progress):
    sys.stderr.write(f"\r{progress.stage}: {progress.fraction:4.0%}")


result = nk.run_indentation(case, progress=show, output_directory=str(out))
sys.stderr.write("\n")
print(f"{case.name}: {result.status.name} after {len(result.steps)} steps, {result.elements} tets, "
      f"{result.total_seconds:.1f} s")

# Sneddon (1965): a rigid flat punch of radius a on an elastic half-space.
layer = case.block.layers[0]
radius = case.geometry.tip_diameter / 2
depth = np.concatenate([[0.0], result.depth])
force = np.concatenate([[0.0], result.force])
sneddon = 2 * radius * layer.youngs_modulus * depth / (1 - layer.poisson_ratio ** 2)
figure, axis = plt.subplots(figsize=(6, 4.2))
axis.plot(depth * 1e6, force * 1e3, "o-", label="needlekit FE")
axis.plot(depth * 1e6, sneddon * 1e3, "--", label="Sneddon half-space")
axis.set_xlabel("depth (um)"), axis.set_ylabel("force (mN)")
axis.set_title(f"{case.name}: {result.elements} tetrahedra")
axis.legend(), axis.grid(alpha=0.3)
figure.tight_layout()
figure.savefig(out / "indentation.png", dpi=110)
relative = float(force[-1] / sneddon[-1] - 1)
(out / "indentation_summary.json").write_text(json.dumps({
    "depth_um": (depth * 1e6).tolist(), "force_N": force.tolist(), "sneddon_force_N": sneddon.tolist(),
    "relative_difference_at_final_depth": relative}, indent=2) + "\n")
print(f"F({depth[-1] * 1e6:.3g} um) = {force[-1]:.4g} N, Sneddon {sneddon[-1]:.4g} N ({relative:+.1%}); "
      f"ParaView: {out / (case.name + '.pvd')}")
