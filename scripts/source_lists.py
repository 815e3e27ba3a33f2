#!/usr/bin/env python3
"""The explicit source lists of the CMake build (issue 38: no GLOB), and their check.

  source_lists.py check [SOURCE_DIR]   every .cpp under src/, apps/needlekit/, tests/<kind>/, bench/, fuzz/ and
                                       python/src/ is in cmake/sources.cmake and every listed file exists (CTest
                                       architecture.source_lists); exit 1 naming the files otherwise
  source_lists.py write [SOURCE_DIR]   writes cmake/sources.cmake from the files on disk (after adding or removing
                                       a source file, then review the diff)
"""
import pathlib
import re
import sys

# CMake variable -> (folder or single file, recursive, files left out)
LISTS = {
    "NEEDLEKIT_LIBRARY_SOURCES": ("src", True, ("src/mesh/gmsh/", "src/fem/petsc/", "src/fem/serial_session.cpp")),
    "NEEDLEKIT_GMSH_SOURCES": ("src/mesh/gmsh", False, ()),
    # The FE solver's PETSc backend (NEEDLEKIT_WITH_PETSC) or, without it, the one-process session.
    "NEEDLEKIT_PETSC_SOURCES": ("src/fem/petsc", False, ()),
    "NEEDLEKIT_SERIAL_SESSION_SOURCES": ("src/fem/serial_session.cpp", False, ()),
    "NEEDLEKIT_CLI_SOURCES": ("apps/needlekit", False, ()),
    "NEEDLEKIT_UNIT_TEST_SOURCES": ("tests/unit", True, ()),
    "NEEDLEKIT_VERIFICATION_TEST_SOURCES": ("tests/verification", True, ()),
    "NEEDLEKIT_REGRESSION_TEST_SOURCES": ("tests/regression", True, ()),
    "NEEDLEKIT_EXAMPLE_TEST_SOURCES": ("tests/example", True, ()),
    "NEEDLEKIT_MPI_TEST_SOURCES": ("tests/mpi", True, ()),
    "NEEDLEKIT_SERVE_TEST_SOURCES": ("tests/serve", True, ()),
    "NEEDLEKIT_BENCH_SOURCES": ("bench", False, ()),
    "NEEDLEKIT_FUZZ_TARGET_SOURCES": ("fuzz", False, ("fuzz/replay_main.cpp",)),
    "NEEDLEKIT_PYTHON_SOURCES": ("python/src", False, ()),
}
LIST_FILE = "cmake/sources.cmake"


def on_disk(source_dir):
    lists = {}
    for name, (folder, recursive, left_out) in LISTS.items():
        root = source_dir / folder
        if root.is_file():
            found = [root]
        else:
            found = root.rglob("*.cpp") if recursive else root.glob("*.cpp")
        files = sorted(p.relative_to(source_dir).as_posix() for p in found)
        lists[name] = [f for f in files if not any(f.startswith(x) for x in left_out)]
    return lists


def text_of(lists):
    lines = ["# The source files of every target, listed by hand (scripts/source_lists.py writes and checks this file;",
             "# CTest architecture.source_lists fails when a .cpp is missing here or a listed file is gone).", ""]
    for name, files in lists.items():
        lines.append(f"set({name}")
        lines += [f"  {f}" for f in files]
        lines += [")", ""]
    return "\n".join(lines)


def listed(source_dir):
    text = (source_dir / LIST_FILE).read_text(encoding="utf-8")
    return {m.group(1): m.group(2).split() for m in re.finditer(r"set\((\w+)\n(.*?)\)", text, re.S)}


def main():
    command = sys.argv[1] if len(sys.argv) > 1 else "check"
    source_dir = pathlib.Path(sys.argv[2] if len(sys.argv) > 2 else pathlib.Path(__file__).resolve().parents[1])
    if command == "write":
        (source_dir / LIST_FILE).write_text(text_of(on_disk(source_dir)), encoding="utf-8")
        return 0
    disk, have = on_disk(source_dir), listed(source_dir)
    problems = []
    for name, files in disk.items():
        listed_files = have.get(name, [])
        problems += [f"{f}: not in {name} ({LIST_FILE})" for f in files if f not in listed_files]
        problems += [f"{f}: listed in {name} but not on disk" for f in listed_files if f not in files]
    for line in problems:
        print(line)
    if not problems:
        print(f"source lists: complete ({sum(len(f) for f in disk.values())} files)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
