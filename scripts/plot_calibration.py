#!/usr/bin/python3
"""Plot measured vs fitted force-depth curves written by `needlekit calibrate` (CSV: experiment, series, depth_um,
force_N with series measured | fitted | measured_puncture | fitted_puncture): one colour per experiment, measured
samples as dots, the fitted model as a line, puncture points as circles (measured) and crosses (fitted).

usage: plot_calibration.py CURVES.csv OUT.png [--title TEXT]
Uses Debian's python3-matplotlib with the Agg backend. Exit code 2 on bad input.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(message):
    print(f"plot_calibration: error: {message}", file=sys.stderr)
    sys.exit(2)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("curves")
    parser.add_argument("out")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    series = {}
    try:
        with open(args.curves, newline="") as f:
            reader = csv.DictReader(f)
            if reader.fieldnames != ["experiment", "series", "depth_um", "force_N"]:
                fail(f"{args.curves}: header {reader.fieldnames}, expected experiment,series,depth_um,force_N")
            for row in reader:
                key = (row["experiment"], row["series"])
                series.setdefault(key, ([], []))
                series[key][0].append(float(row["depth_um"]))
                series[key][1].append(float(row["force_N"]))
    except OSError as e:
        fail(f"{args.curves}: cannot read: {e.strerror}")
    except ValueError:
        fail(f"{args.curves}: a value is not a number")
    experiments = list(dict.fromkeys(name for name, _ in series))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, name in enumerate(experiments):
        colour = f"C{k % 10}"
        style = {"measured": dict(marker=".", linestyle="none", label=f"{name}: measured"),
                 "fitted": dict(linestyle="-", label=f"{name}: fitted"),
                 "measured_puncture": dict(marker="o", markerfacecolor="none", linestyle="none", markersize=9,
                                           label=f"{name}: measured puncture"),
                 "fitted_puncture": dict(marker="x", linestyle="none", markersize=9, label=f"{name}: fitted puncture")}
        for kind, options in style.items():
            if (name, kind) in series:
                x, y = series[(name, kind)]
                ax.plot(x, y, color=colour, **options)
    ax.set_xlabel("depth (um)")
    ax.set_ylabel("force (N)")
    if args.title:
        ax.set_title(args.title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)


if __name__ == "__main__":
    main()
