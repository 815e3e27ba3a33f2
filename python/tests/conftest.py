"""Shared paths of the Python tests (run by ctest: `python.pytest`, with PYTHONPATH=build/python)."""
import json
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("NEEDLEKIT_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
EXAMPLES = SOURCE_DIR / "examples"
CLI = os.environ.get("NEEDLEKIT_CLI", str(SOURCE_DIR / "build" / "bin" / "needlekit"))


def cli_json(*arguments, cwd=None):
    """The parsed JSON that `needlekit ARGUMENTS --json` prints."""
    run = subprocess.run([CLI, *map(str, arguments), "--json"], capture_output=True, text=True, cwd=cwd, check=False)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout)


@pytest.fixture
def examples():
    return EXAMPLES
