#!/usr/bin/env python3
"""Checks that needlekit's folders depend on each other one way only (docs/architecture.md).

Every folder of include/needlekit/ and src/ has a layer; a file may include another folder's public header
("needlekit/DOMAIN/...") only if that folder's layer is lower than its own, and never another folder's private
header ("../DOMAIN/..."). Prints every include that breaks the rule, as FILE:LINE, and exits 1 if there is one.
Usage: check_include_graph.py [SOURCE_DIR]
"""
import pathlib
import re
import sys

# The layers, lowest first (docs/architecture.md draws them). Folders of one layer never include each other.
LAYERS = [
    ["core"],
    ["geometry"],
    ["needle", "materials"],
    ["analysis", "mesh"],
    ["fem", "patch"],
    ["insertion"],
    ["uncertainty"],
    ["io"],
    ["calibration"],
    ["reference"],
]
LAYER_OF = {folder: rank for rank, folders in enumerate(LAYERS) for folder in folders}
PUBLIC = re.compile(r'^\s*#\s*include\s+"needlekit/([a-z_]+)/')
PRIVATE = re.compile(r'^\s*#\s*include\s+"\.\./([a-z_]+)/')


def violations(source_dir):
    found = []
    for root in (source_dir / "include" / "needlekit", source_dir / "src"):
        for path in sorted(root.rglob("*.[ch]pp")):
            folder = path.relative_to(root).parts[0]
            if folder not in LAYER_OF:
                found.append(f"{path}:1: folder '{folder}' has no layer in scripts/check_include_graph.py")
                continue
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
                if (match := PRIVATE.match(line)) and match.group(1) != folder:
                    found.append(f"{path}:{number}: includes the private header of '{match.group(1)}'")
                elif (match := PUBLIC.match(line)) and match.group(1) != folder:
                    target = match.group(1)
                    if LAYER_OF.get(target, len(LAYERS)) >= LAYER_OF[folder]:
                        found.append(f"{path}:{number}: '{folder}' (layer {LAYER_OF[folder]}) includes '{target}' "
                                     f"(layer {LAYER_OF.get(target, '?')}): an include that goes up or sideways")
    return found


def main():
    source_dir = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1])
    found = violations(source_dir)
    for line in found:
        print(line)
    if not found:
        print(f"include graph: one way ({len(LAYERS)} layers)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
