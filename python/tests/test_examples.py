"""Every script in examples/python runs (as a user would run it) and writes its figure and data; their numbers are
checked against the dissertation or an analytic solution."""
import json
import os
import subprocess
import sys

import pytest

from conftest import EXAMPLES

SCRIPTS = EXAMPLES / "python"
QUICK_ARGUMENTS = {
    "design_study.py": ["--points", "200"],
    "indentation_curve.py": ["--size-at-tip", "45 um", "--size-far", "900 um", "--steps", "2"],
    "patch_on_body.py": [],
}


def run(script, out):
    environment = dict(os.environ, MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, str(SCRIPTS / script), "--out", str(out), *QUICK_ARGUMENTS[script]],
                          capture_output=True, text=True, env=environment, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_every_python_example_is_tested():
    assert sorted(p.name for p in SCRIPTS.glob("*.py")) == sorted(QUICK_ARGUMENTS)


def png(path):
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 10_000, path


def test_design_study(tmp_path):
    run("design_study.py", tmp_path)
    png(tmp_path / "design_study.png")
    summary = json.loads((tmp_path / "design_study.json").read_text())
    assert summary["table_6_1_cone_performance_index_per_um"] == pytest.approx(1.288e-4, rel=5e-4)  # §6.3.1
    optimum = summary["optimum"]  # Table 6.3, solid cone
    assert [optimum[k] for k in ("needles_per_row", "tip_diameter_um", "base_diameter_um")] == [25, 70, 80]
    # The optimum of the grid is also the peak of each curve through it (up to the grid's resolution).
    for name, curve in summary["sensitivity"].items():
        assert curve["max_performance_index_per_um"] >= optimum["performance_index_per_um"] * (1 - 1e-9), name


def test_indentation_curve_against_sneddon(tmp_path):
    run("indentation_curve.py", tmp_path)
    png(tmp_path / "indentation.png")
    summary = json.loads((tmp_path / "indentation_summary.json").read_text())
    assert abs(summary["relative_difference_at_final_depth"]) < 0.15  # a coarse mesh; 2 % at the example's sizes
    pvd = (tmp_path / "flat_punch.pvd").read_text()
    assert pvd.count("<DataSet") >= 2 and (tmp_path / "flat_punch_step_002.vtu").exists()
    assert not list(tmp_path.glob("*.tmp*"))


def test_patch_on_body(tmp_path):
    run("patch_on_body.py", tmp_path)
    png(tmp_path / "patch_forces.png")
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["needles"] == 100 and summary["status"] == "ok"
    assert len((tmp_path / "needles.csv").read_text().splitlines()) == 101
