#!/usr/bin/env python3
"""Checks that no constructor in include/, src/ and apps/ takes more than five parameters (issue 38 item 3).

Constructors are found with Universal Ctags (Debian universal-ctags; a hand-written C++ parser would be the risk
here): a function or prototype whose name is its class's. Its parameters are counted from the signature ctags
reports, at the top level of its parentheses (commas inside <>, (), [] and {} do not count). A constructor with more
parameters should take an options struct or group its arguments. Prints every one over the limit as
FILE:LINE CLASS (N parameters) and exits 1 if there is one.
Usage: check_constructor_parameters.py [SOURCE_DIR]
"""
import pathlib
import subprocess
import sys

LIMIT = 5
FOLDERS = ["include", "src", "apps"]


def parameter_count(signature):
    inner = signature.strip()[1:-1].strip()
    if not inner or inner == "void":
        return 0
    count, depth = 1, 0
    for c in inner:
        if c in "<([{":
            depth += 1
        elif c in ">)]}":
            depth -= 1
        elif c == "," and depth == 0:
            count += 1
    return count


def constructors(source_dir):
    """(file, line, class, parameter count) of every constructor declaration or definition under FOLDERS."""
    folders = [f for f in FOLDERS if (source_dir / f).is_dir()]
    command = ["ctags", "-R", "--languages=C++", "--kinds-C++=+p", "--fields=+nS", "-f", "-"]
    out = subprocess.run(command + folders, cwd=source_dir, capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        fields = line.split("\t")
        extra = dict(f.split(":", 1) for f in fields[3:] if ":" in f)
        scope = extra.get("class") or extra.get("struct")
        if scope and scope.split("::")[-1] == fields[0] and "signature" in extra:
            yield fields[1], int(extra.get("line", 0)), fields[0], parameter_count(extra["signature"])


def main():
    source_dir = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1])
    found = list(constructors(source_dir))
    over = [entry for entry in found if entry[3] > LIMIT]
    for path, line, name, count in over:
        print(f"{path}:{line} {name} ({count} parameters): over {LIMIT}, expected an options struct or grouped "
              "arguments")
    if not over:
        widest = max((entry[3] for entry in found), default=0)
        print(f"constructor parameters: none over {LIMIT} ({len(found)} constructors, the widest {widest})")
    return 1 if over else 0


if __name__ == "__main__":
    sys.exit(main())
