"""The type stubs list every public name of the module, and are what scripts/python_stubs.py generates now."""
import ast
import pathlib
import subprocess
import sys

import needlekit as nk
from conftest import SOURCE_DIR

STUBS = SOURCE_DIR / "python" / "needlekit"


def stub_names(path):
    tree = ast.parse(path.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            names.add(node.target.id)
        elif isinstance(node, ast.Assign):
            names.update(t.id for t in node.targets if isinstance(t, ast.Name))
    return names


def test_the_stubs_list_every_public_name():
    public = {name for name in dir(nk) if not name.startswith("_") and name not in {"annotations", "dask"}}
    listed = stub_names(STUBS / "__init__.pyi") | stub_names(STUBS / "_needlekit.pyi")
    assert public - listed == set()


def test_the_committed_stubs_are_current(tmp_path):
    subprocess.run([sys.executable, str(SOURCE_DIR / "scripts" / "python_stubs.py"), str(tmp_path)], check=True)
    assert (tmp_path / "_needlekit.pyi").read_text() == (STUBS / "_needlekit.pyi").read_text()


def test_properties_in_the_stubs_carry_their_units():
    text = (STUBS / "_needlekit.pyi").read_text()
    assert "def tip_diameter(self) -> float:\n        \"\"\"m, D1 > 0" in text
