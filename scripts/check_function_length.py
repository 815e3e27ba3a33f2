#!/usr/bin/env python3
"""Checks that no function of src/ and apps/ is longer than 80 lines without a stated reason (issue 38 item 5).

A function is measured from its first line to its closing brace, as Universal Ctags (Debian universal-ctags) reports
them (a hand-written C++ parser would be the risk here). A longer function passes when the comment just above it (or
on its first lines) holds "Long function:" and the reason. Prints every function over the limit, as
FILE:LINE NAME (N lines), the unexplained ones first, and exits 1 if there is an unexplained one.
Usage: check_function_length.py [SOURCE_DIR]
"""
import pathlib
import subprocess
import sys

LIMIT = 80
FOLDERS = ["src", "apps"]
MARK = "Long function:"


def functions(source_dir):
    """(file, first line, last line, name) of every function definition under FOLDERS."""
    command = ["ctags", "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-f", "-"]
    out = subprocess.run(command + FOLDERS, cwd=source_dir, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        fields = line.split("\t")
        extra = dict(f.split(":", 1) for f in fields[3:] if ":" in f)
        if "line" in extra and "end" in extra:
            yield fields[1], int(extra["line"]), int(extra["end"]), fields[0]


def explained(lines, first):
    """Whether the comment block above line `first` (1-based), or the function's first three lines, hold MARK."""
    i = first - 2
    while i >= 0 and lines[i].lstrip().startswith("//"):
        if MARK in lines[i]:
            return True
        i -= 1
    return any(MARK in text for text in lines[first - 1:first + 2])


def main():
    source_dir = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1])
    unexplained, allowed = [], []
    texts = {}
    for path, first, last, name in functions(source_dir):
        length = last - first + 1
        if length <= LIMIT:
            continue
        lines = texts.setdefault(path, (source_dir / path).read_text(encoding="utf-8").splitlines())
        entry = f"{path}:{first} {name} ({length} lines)"
        (allowed if explained(lines, first) else unexplained).append(entry)
    for entry in unexplained:
        print(f"{entry}: over {LIMIT} lines, expected a shorter function or a '{MARK}' comment with the reason")
    for entry in allowed:
        print(f"{entry}: long, with a reason")
    if not unexplained:
        print(f"function length: none over {LIMIT} lines without a reason ({len(allowed)} with one)")
    return 1 if unexplained else 0


if __name__ == "__main__":
    sys.exit(main())
