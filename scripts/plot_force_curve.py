#!/usr/bin/python3
"""Plot an insertion force curve written by `needlekit insert` (CSV: depth_um, force_N, phase, punctured_needles,
marker) as force vs depth, indentation and cutting phases in two colours, puncture points marked. Optionally overlay
measured curves (CSV with depth_<unit> and force_<unit> columns).

usage: plot_force_curve.py CURVE.csv OUT.png [--title TEXT] [--measured FILE.csv ...]
Uses Debian's python3-matplotlib with the Agg backend (no display needed). Exit code 2 on bad input.
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LENGTH = {"nm": 1e-3, "um": 1.0, "mm": 1e3, "cm": 1e4, "m": 1e6}  # to um
FORCE = {"uN": 1e-6, "mN": 1e-3, "N": 1.0}  # to N


def fail(message):
    print(f"plot_force_curve: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_rows(path):
    try:
        with open(path, newline="") as f:
            rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    except OSError as e:
        fail(f"{path}: cannot read: {e.strerror}")
    if not rows:
        fail(f"{path}: empty")
    return rows[0], rows[1:]


def column(header, prefix, units, path):
    for i, name in enumerate(header):
        if name.startswith(prefix) and name[len(prefix):] in units:
            return i, units[name[len(prefix):]]
    fail(f"{path}: missing column {prefix}<unit> in header {','.join(header)}")


def numbers(rows, index, factor, path):
    try:
        return [float(r[index]) * factor for r in rows]
    except (ValueError, IndexError):
        fail(f"{path}: a value in column {index + 1} is not a number")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("curve")
    parser.add_argument("png")
    parser.add_argument("--title", default="")
    parser.add_argument("--measured", nargs="*", default=[])
    args = parser.parse_args()

    header, rows = read_rows(args.curve)
    d_index, d_factor = column(header, "depth_", LENGTH, args.curve)
    f_index, f_factor = column(header, "force_", FORCE, args.curve)
    if "phase" not in header:
        fail(f"{args.curve}: missing column phase")
    depth = numbers(rows, d_index, d_factor, args.curve)
    force = numbers(rows, f_index, f_factor, args.curve)
    phase = [r[header.index("phase")] for r in rows]
    marker = [r[header.index("marker")] if "marker" in header else "" for r in rows]

    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=120)
    for name, colour in (("indentation", "tab:blue"), ("cutting", "tab:red")):
        xs = [d if p == name else float("nan") for d, p in zip(depth, phase)]
        ys = [f if p == name else float("nan") for f, p in zip(force, phase)]
        ax.plot(xs, ys, color=colour, lw=1.8, label=f"{name} (model)")
    # The relaxation drops: vertical segments from the puncture sample to the relaxed one.
    first = True
    for i, m in enumerate(marker):
        if m == "puncture" and i + 1 < len(depth):
            ax.plot([depth[i], depth[i + 1]], [force[i], force[i + 1]], color="grey", ls=":", lw=1.2)
            ax.plot(depth[i], force[i], "k*", ms=10, label="puncture" if first else None)
            first = False
    for path in args.measured:
        m_header, m_rows = read_rows(path)
        mi, mf = column(m_header, "depth_", LENGTH, path)
        fi, ff = column(m_header, "force_", FORCE, path)
        ax.plot(numbers(m_rows, mi, mf, path), numbers(m_rows, fi, ff, path), "o", ms=3, mfc="none",
                label=os.path.basename(path))
    ax.set_xlabel("depth (um)")
    ax.set_ylabel("force (N)")
    ax.set_title(args.title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="best", fontsize=8)
    fig.tight_layout()
    tmp = args.png + f".tmp-{os.getpid()}.png"
    try:
        fig.savefig(tmp)
        os.replace(tmp, args.png)
    except OSError as e:
        if os.path.exists(tmp):
            os.remove(tmp)
        fail(f"{args.png}: cannot write: {e.strerror}")


if __name__ == "__main__":
    main()
