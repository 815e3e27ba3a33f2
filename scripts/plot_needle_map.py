#!/usr/bin/python3
"""Plot the needle map of an array indentation written by `needlekit indent --out` (NAME_needles.csv: needle, row,
column, x_um, y_um, punctured, ..., inserted_depth_um): one marker per needle at its (x, y), coloured by its inserted
depth at the last step (its travel beyond its puncture point; the tips of a rigid patch all reach the same depth),
filled when it punctured and hollow when not.

usage: plot_needle_map.py NEEDLES.csv OUT.png [--title TEXT]
Uses Debian's python3-matplotlib with the Agg backend (no display needed). The PNG is written to a temporary name
and renamed. Exit code 2 on bad input.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REQUIRED = ("x_um", "y_um", "punctured", "inserted_depth_um")


def fail(message):
    print(f"plot_needle_map: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_needles(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: cannot read: {e.strerror}")
    if not rows:
        fail(f"{path}: no needles")
    missing = [key for key in REQUIRED if key not in rows[0]]
    if missing:
        fail(f"{path}: missing columns {', '.join(missing)}")
    try:
        return [(float(r["x_um"]), float(r["y_um"]), r["punctured"] == "1", float(r["inserted_depth_um"])) for r in rows]
    except ValueError as e:
        fail(f"{path}: {e}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("needles")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    needles = read_needles(args.needles)
    x = [n[0] for n in needles]
    y = [n[1] for n in needles]
    depth = [n[3] for n in needles]
    fig, ax = plt.subplots(figsize=(6, 5))
    low, high = min(depth), max(depth)
    norm = matplotlib.colors.Normalize(vmin=low, vmax=high if high > low else low + 1)
    colours = matplotlib.cm.viridis(norm(depth))
    punctured = [i for i, n in enumerate(needles) if n[2]]
    intact = [i for i, n in enumerate(needles) if not n[2]]
    ax.scatter([x[i] for i in punctured], [y[i] for i in punctured], c=[colours[i] for i in punctured], s=120,
               edgecolors="black", label="punctured")
    ax.scatter([x[i] for i in intact], [y[i] for i in intact], facecolors="none", edgecolors=[colours[i] for i in intact],
               s=120, linewidths=2, label="not punctured")
    fig.colorbar(matplotlib.cm.ScalarMappable(norm=norm, cmap="viridis"), ax=ax, label="inserted depth at the last step (um)")
    ax.set_xlabel("x (um)")
    ax.set_ylabel("y (um)")
    ax.set_aspect("equal")
    ax.margins(0.15)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, fontsize="small")
    ax.set_title(args.title or f"{len(punctured)} of {len(needles)} needles punctured")
    temporary = args.out + ".partial.png"
    try:
        fig.savefig(temporary, dpi=120, bbox_inches="tight")
        os.replace(temporary, args.out)
    except OSError as e:
        fail(f"{args.out}: cannot write: {e.strerror}")


if __name__ == "__main__":
    main()
