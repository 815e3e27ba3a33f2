#!/usr/bin/python3
"""Plot the per-needle probability of success written by `needlekit uncertainty` for a patch case (CSV
needle_probabilities.csv with u_mm, v_mm, P_success): one square per needle at its rest position in the patch,
coloured by P(success) on a fixed 0..1 scale.

usage: plot_patch_probability.py NEEDLES.csv OUT.png [--title TEXT] [--event success]
Uses Debian's python3-matplotlib with the Agg backend. Exit code 2 on bad input.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(message):
    print(f"plot_patch_probability: error: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("needles")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    parser.add_argument("--event", default="success")
    args = parser.parse_args()
    column = f"P_{args.event}"
    u, v, p = [], [], []
    try:
        with open(args.needles, newline="") as f:
            reader = csv.DictReader(f)
            for name in ("u_mm", "v_mm", column):
                if name not in (reader.fieldnames or []):
                    fail(f"{args.needles}: no column {name}")
            for row in reader:
                u.append(float(row["u_mm"]))
                v.append(float(row["v_mm"]))
                p.append(float(row[column]) if row[column] else float("nan"))
    except OSError as e:
        fail(f"{args.needles}: cannot read: {e.strerror}")
    except ValueError:
        fail(f"{args.needles}: a value is not a number")
    if not p:
        fail(f"{args.needles}: no needles")
    fig, ax = plt.subplots(figsize=(5.5, 4.8))
    points = ax.scatter(u, v, c=p, cmap="RdYlGn", vmin=0, vmax=1, marker="s", s=max(20, 9000 / len(p)),
                        edgecolors="k", linewidths=0.3)
    fig.colorbar(points, ax=ax, label=f"P({args.event})")
    ax.set_xlabel("u (mm, patch axis U)")
    ax.set_ylabel("v (mm, patch axis V)")
    ax.set_aspect("equal")
    if args.title:
        ax.set_title(args.title, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)


if __name__ == "__main__":
    main()
