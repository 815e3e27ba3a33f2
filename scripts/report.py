#!/usr/bin/python3
"""Figures and the self-contained HTML report of `needlekit reproduce`.

Usage: report.py RUN_DIR

Reads RUN_DIR/results.json (written by `needlekit reproduce`), draws every figure it lists as a PNG under RUN_DIR
(matplotlib, Agg backend, no display needed) and writes RUN_DIR/report.html with the PNGs embedded as base64 (no
network needed to open it). Every number comes from results.json or the CSV files of the run: this script only
formats them. Figure kinds: "bars", "lines", "scatter2d", "points3d", "patch3d" (see each draw_* function for its fields).
The 3D views that a section lists ("views": data files views/NAME_view.js) are shown by the viewer that the run copied
into RUN_DIR/viewer (docs/views.md), loaded as classic scripts so that the report opens from file://.
"""
import base64
import csv
import html
import json
import os
import signal
import sys

signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C: stop at once, needlekit removes the partial run

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

RUN_DIR = ""


def read_csv(relative):
    """Columns of a CSV file of the run as {name: list of floats (or strings when not numeric)}."""
    with open(os.path.join(RUN_DIR, relative), newline="") as f:
        rows = list(csv.DictReader(f))
    columns = {}
    for name in rows[0].keys() if rows else []:
        values = [r[name] for r in rows]
        try:
            columns[name] = [float(v) if v != "" else float("nan") for v in values]
        except ValueError:
            columns[name] = values
    return columns


def series_xy(s):
    """x, y of a series: inline ("x_values", "y_values") or CSV columns ("csv", "x", "y"), x optionally divided by
    "x_divide_by" and y multiplied by "y_scale"."""
    if "csv" in s:
        data = read_csv(s["csv"])
        x, y = np.asarray(data[s["x"]], float), np.asarray(data[s["y"]], float)
    else:
        x, y = np.asarray(s["x_values"], float), np.asarray(s["y_values"], float)
    return x / s.get("x_divide_by", 1.0), y * s.get("y_scale", 1.0)


def draw_bars(ax, spec):
    """Grouped bars: "categories", "series" [{"label", "values"}], "ylabel", "log"."""
    categories = spec["categories"]
    series = spec["series"]
    width = 0.8 / len(series)
    x = np.arange(len(categories))
    for i, s in enumerate(series):
        values = [np.nan if v is None else v for v in s["values"]]
        ax.bar(x + (i - (len(series) - 1) / 2) * width, values, width, label=s["label"])
    ax.set_xticks(x)
    ax.set_xticklabels(categories, rotation=20, ha="right")
    ax.set_ylabel(spec.get("ylabel", ""))
    if spec.get("log"):
        ax.set_yscale("log")
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.28), ncol=min(len(series), 3))
    ax.grid(axis="y", alpha=0.3)


def draw_lines(ax, spec):
    """Curves: "series" [{csv/x/y or x_values/y_values, "label", "style"}], optional "markers" [{"x", "y", "label"}],
    "hlines"/"vlines" [{"value", "label"}], "xlabel", "ylabel"."""
    for s in spec["series"]:
        x, y = series_xy(s)
        ax.plot(x, y, s.get("style", "-"), label=s.get("label"), lw=1.6)
    for m in spec.get("markers", []):
        ax.plot([m["x"]], [m["y"]], m.get("style", "o"), ms=7, label=m.get("label"))
    for h in spec.get("hlines", []):
        ax.axhline(h["value"], ls=":", color="grey", label=h.get("label"))
    for v in spec.get("vlines", []):
        ax.axvline(v["value"], ls=":", color="grey", label=v.get("label"))
    ax.set_xlabel(spec.get("xlabel", ""))
    ax.set_ylabel(spec.get("ylabel", ""))
    if spec.get("log_y"):
        ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)


def draw_points3d(fig, spec):
    """A 3-D rendering coloured by a value: "csv" with columns "x", "y", "z" (mm) and "value"; optional "surface_csv"
    (columns x, y, z of surface points, drawn small and grey), "colorbar" label, "title"."""
    ax = fig.add_subplot(111, projection="3d")
    if spec.get("surface_csv"):
        s = read_csv(spec["surface_csv"])
        ax.scatter(s["x"], s["y"], s["z"], s=1, c="0.75", alpha=0.3, depthshade=False)
    d = read_csv(spec["csv"])
    values = np.asarray(d[spec["value"]], float)
    p = ax.scatter(d[spec.get("x", "x")], d[spec.get("y", "y")], d[spec.get("z", "z")], c=values,
                   cmap=spec.get("cmap", "viridis"), s=spec.get("size", 18), depthshade=False)
    fig.colorbar(p, ax=ax, shrink=0.7, label=spec.get("colorbar", spec["value"]))
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_zlabel("z (mm)")
    if "view" in spec:
        ax.view_init(elev=spec["view"][0], azim=spec["view"][1])
    try:
        ax.set_box_aspect(None, zoom=0.9)
    except TypeError:
        pass
    return ax


def draw_scatter2d(ax, fig, spec):
    """A map coloured by a value: "csv" with columns "x", "y" and "value" (names given), "xlabel", "ylabel",
    "colorbar", "log" (logarithmic colour scale)."""
    d = read_csv(spec["csv"])
    values = np.asarray(d[spec["value"]], float)
    norm = None
    if spec.get("log"):
        positive = values[values > 0]
        if positive.size:
            norm = matplotlib.colors.LogNorm(vmin=max(positive.min(), positive.max() * 1e-4), vmax=positive.max())
            values = np.maximum(values, norm.vmin)
    p = ax.scatter(d[spec["x"]], d[spec["y"]], c=values, s=spec.get("size", 6), cmap=spec.get("cmap", "viridis"),
                   norm=norm, linewidths=0)
    fig.colorbar(p, ax=ax, label=spec.get("colorbar", spec["value"]))
    ax.set_xlabel(spec.get("xlabel", ""))
    ax.set_ylabel(spec.get("ylabel", ""))
    ax.set_aspect("equal", adjustable="box")


def draw_patch3d(fig, spec):
    """A fitted patch on its surface, one 3-D panel per value: "csv" (the per-needle CSV with base_/tip_ x, y, z in
    mm), "surface" (JSON with "vertices" in mm and "triangles" near the patch), "panels" [{"value", "colorbar"}].
    Each needle is drawn as a base-to-tip segment and its base as a dot, coloured by the panel's value."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    d = read_csv(spec["csv"])
    with open(os.path.join(RUN_DIR, spec["surface"])) as f:
        surface = json.load(f)
    v = np.asarray(surface["vertices"], float).reshape(-1, 3)
    t = np.asarray(surface["triangles"], int).reshape(-1, 3)
    base = np.column_stack([d["base_x_mm"], d["base_y_mm"], d["base_z_mm"]])
    tip = np.column_stack([d["tip_x_mm"], d["tip_y_mm"], d["tip_z_mm"]])
    centre = base.mean(axis=0)
    half = 0.6 * max(np.ptp(base[:, 0]), np.ptp(base[:, 1]), np.ptp(base[:, 2]), 1e-3)
    panels = spec["panels"]
    for k, panel in enumerate(panels):
        ax = fig.add_subplot(1, len(panels), k + 1, projection="3d")
        if len(t):
            ax.plot_trisurf(v[:, 0], v[:, 1], v[:, 2], triangles=t, color="0.85", alpha=0.35, linewidth=0.1,
                            edgecolor="0.6", shade=True)
        values = np.asarray(d[panel["value"]], float)
        finite = values[np.isfinite(values)]
        vmin, vmax = (finite.min(), finite.max()) if finite.size else (0.0, 1.0)
        if vmax <= vmin:
            vmax = vmin + (abs(vmin) * 1e-3 or 1e-12)
        norm = matplotlib.colors.Normalize(vmin=vmin, vmax=vmax)
        cmap = plt.get_cmap("viridis")
        segments = np.stack([base, base + 4 * (tip - base)], axis=1)  # needles drawn 4x longer to be seen
        ax.add_collection3d(Line3DCollection(segments, colors=cmap(norm(np.nan_to_num(values, nan=vmin))),
                                             linewidths=1.2))
        p = ax.scatter(base[:, 0], base[:, 1], base[:, 2], c=values, cmap=cmap, norm=norm, s=10, depthshade=False)
        fig.colorbar(p, ax=ax, shrink=0.55, pad=0.08, label=panel.get("colorbar", panel["value"]))
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)
        ax.set_xlabel("x (mm)", fontsize=7)
        ax.set_ylabel("y (mm)", fontsize=7)
        ax.set_zlabel("z (mm)", fontsize=7)
        ax.tick_params(labelsize=6)
        ax.view_init(elev=spec.get("elevation", 20), azim=spec.get("azimuth", -60))


def draw_figure(figure):
    spec = figure["spec"]
    kind = spec["kind"]
    if kind == "points3d":
        fig = plt.figure(figsize=(7, 5.5))
        draw_points3d(fig, spec)
    elif kind == "patch3d":
        fig = plt.figure(figsize=(15, 5))
        draw_patch3d(fig, spec)
    else:
        fig, ax = plt.subplots(figsize=(7, 4.5))
        if kind == "scatter2d":
            draw_scatter2d(ax, fig, spec)
        else:
            {"bars": draw_bars, "lines": draw_lines}[kind](ax, spec)
    if spec.get("title"):
        fig.suptitle(spec["title"], fontsize=10)
    fig.tight_layout()
    path = os.path.join(RUN_DIR, figure["file"])
    os.makedirs(os.path.dirname(path), exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def fmt_number(value, digits=6):
    if value is None:
        return "&ndash;"
    if isinstance(value, str):
        return html.escape(value)
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if value == 0 or value != value:
        return "0" if value == 0 else "&ndash;"
    magnitude = int(np.floor(np.log10(abs(value))))
    return f"{value:.{max(digits, magnitude + 2)}g}"


def comparison_rows(comparisons):
    out = []
    for c in comparisons:
        rel = c.get("relative_difference")
        diff = fmt_number(c["difference"], 3) + ("" if rel is None else f" ({100 * rel:+.2f} %)")
        if c["agrees"]:
            verdict = '<span class="ok">agrees</span>'
        elif c["reproduces"]:
            verdict = '<span class="bad">DIFFERS</span>'
        else:
            verdict = '<span class="na">differs (expected)</span>'
        note = c.get("note") or ""
        if not c["reproduces"] and c.get("why_not"):
            note = (note + "; " if note else "") + "not expected to reproduce: " + c["why_not"]
        out.append(
            f"<tr><td>{html.escape(c['quantity'])}</td><td>{html.escape(c['where'])}</td>"
            f"<td class=num>{html.escape(c['published'])}</td><td class=num>{fmt_number(c['needlekit'])}</td>"
            f"<td>{html.escape(c['unit'])}</td><td class=num>{diff}</td><td>{verdict}</td>"
            f"<td class=note>{html.escape(note)}</td></tr>")
    return "\n".join(out)


def table_html(table):
    head = "".join(f"<th>{html.escape(c)}</th>" for c in table["columns"])
    rows = "".join("<tr>" + "".join(f"<td class=num>{fmt_number(v)}</td>" for v in row) + "</tr>"
                   for row in table["rows"])
    note = f"<p class=note>{html.escape(table['note'])}</p>" if table.get("note") else ""
    return f"<h4>{html.escape(table['title'])}</h4><table><tr>{head}</tr>{rows}</table>{note}"


def figure_html(figure, png_path):
    with open(png_path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    attribution = (f"<div class=attribution>{html.escape(figure['attribution'])}</div>"
                   if figure.get("attribution") else "")
    return (f"<figure><img alt=\"{html.escape(figure['file'])}\" src=\"data:image/png;base64,{data}\">"
            f"<figcaption>{html.escape(figure['caption'])} <span class=file>({html.escape(figure['file'])})</span>"
            f"</figcaption>{attribution}</figure>")


def views_html(views, results):
    """The section's 3D views (docs/views.md): a placeholder per view that the viewer fills from its data file."""
    if "viewer" not in results:
        reason = results.get("viewer_error", "the viewer was not written")
        return f"<h3>3D views</h3><p class=unavailable>The 3D views are left out: {html.escape(reason)}</p>"
    blocks = [f"<div class=view><div data-needlekit-view=\"{html.escape(v['name'])}\"></div>"
              f"<p class=note>{html.escape(v['caption'])} <span class=file>({html.escape(v['script'])})</span></p></div>"
              for v in views]
    return ("<h3>3D views</h3><p class=note>Drag to turn, scroll to zoom, right-drag to pan; the select colours the "
            "surface or the needles, the slider moves through the load steps.</p>" + "".join(blocks))


def viewer_scripts(results):
    """The viewer and the views' data files, as classic scripts (they load from file://, with no network)."""
    if "viewer" not in results:
        return ""
    folder = html.escape(results["viewer"])
    scripts = [f"{folder}/three.min.js", f"{folder}/OrbitControls.js", f"{folder}/needlekit_viewer.js"]
    scripts += [v["script"] for section in results["sections"] for v in section.get("views", [])]
    return (f"<link rel=\"stylesheet\" href=\"{folder}/needlekit_viewer.css\">\n"
            + "".join(f"<script src=\"{html.escape(s)}\"></script>\n" for s in scripts)
            + "<script>needlekitViewer.mountAll(document.body);</script>\n")


CSS = """
body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.4}
h1{font-size:1.6em} h2{border-bottom:2px solid #369;padding-bottom:.2em;margin-top:2em} h4{margin-bottom:.3em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0} td,th{border:1px solid #ccc;padding:2px 6px;vertical-align:top}
th{background:#eef} td.num{text-align:right;font-family:monospace} td.note,p.note{font-size:.9em;color:#555}
.ok{color:#070;font-weight:bold} .bad{color:#b00;font-weight:bold} .na{color:#886}
.unavailable{background:#fff4e0;border:1px solid #e0b060;padding:.6em} .failed{background:#fde;border:1px solid #c66;padding:.6em}
figure{margin:1em 0} img{max-width:100%;border:1px solid #ddd} figcaption{font-size:.9em}
.attribution{font-size:.8em;color:#555;font-style:italic} .file{color:#888;font-size:.85em}
"""


def main():
    global RUN_DIR
    RUN_DIR = sys.argv[1]
    with open(os.path.join(RUN_DIR, "results.json")) as f:
        results = json.load(f)

    parts = []
    summary = []
    for section in results["sections"]:
        comparisons = section["comparisons"]
        should = [c for c in comparisons if c["reproduces"]]
        summary.append(
            f"<tr><td><a href=\"#s{html.escape(section['id'])}\">{html.escape(section['title'])}</a></td>"
            f"<td>{html.escape(section['status'])}</td><td class=num>{len(comparisons)}</td>"
            f"<td class=num>{sum(c['agrees'] for c in comparisons)}</td>"
            f"<td class=num>{sum(c['agrees'] for c in should)} / {len(should)}</td>"
            f"<td class=num>{len(section['figures'])}</td><td class=num>{section['seconds']:.1f}</td></tr>")
        body = [f"<h2 id=\"s{html.escape(section['id'])}\">{html.escape(section['title'])}</h2>"]
        if section["status"] == "not_available":
            body.append(f"<p class=unavailable>{html.escape(section['reason'])}</p>")
        elif section["status"] == "failed":
            body.append(f"<p class=failed>This section failed: {html.escape(section['reason'])}</p>")
        if section["inputs"]:
            body.append("<h3>Inputs</h3><ul>" + "".join(f"<li>{html.escape(i)}</li>" for i in section["inputs"])
                        + "</ul>")
        if comparisons:
            body.append("<h3>needlekit beside the dissertation</h3>"
                        "<table><tr><th>quantity</th><th>printed in</th><th>dissertation</th><th>needlekit</th>"
                        "<th>unit</th><th>difference</th><th>to the printed digits</th><th>note</th></tr>"
                        + comparison_rows(comparisons) + "</table>")
        for table in section["tables"]:
            body.append(table_html(table))
        if section["figures"]:
            body.append("<h3>Figures</h3>")
            for figure in section["figures"]:
                body.append(figure_html(figure, draw_figure(figure)))
        if section.get("views"):
            body.append(views_html(section["views"], results))
        if section["deviations"]:
            body.append("<h3>Deviations from the dissertation and their causes</h3><ul>"
                        + "".join(f"<li>{html.escape(d)}</li>" for d in section["deviations"]) + "</ul>")
        if section["data_files"]:
            body.append("<p class=note>Data of this section (next to this report): "
                        + ", ".join(html.escape(d) for d in section["data_files"]) + "</p>")
        parts.append("\n".join(body))

    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(results['title'])}</title>
<style>{CSS}</style></head><body>
<h1>{html.escape(results['title'])}</h1>
<p>{html.escape(results['dissertation'])}, Chapter 6. Every needlekit number and figure below comes from the run that
wrote this report (<code>{html.escape(results['command'])}</code>, {html.escape(results['mode'])} run, started
{html.escape(results['started_utc'])}, {results['seconds']:.1f} s on {results['hardware_threads']} hardware threads).
The published numbers are in <code>{html.escape(results['published_values'])}</code> with where they are printed.
A needlekit value <i>agrees</i> with a printed one when they differ by at most one unit of the last printed digit
(the text both rounds and truncates); numbers that the dissertation's formulas determine are expected to agree,
the others (experiments, simulations with unstated inputs) are compared and their differences explained.</p>
<table><tr><th>section</th><th>status</th><th>numbers compared</th><th>agree</th>
<th>agree / expected to</th><th>figures</th><th>seconds</th></tr>
{''.join(summary)}</table>
{''.join(parts)}
{viewer_scripts(results)}</body></html>
"""
    tmp = os.path.join(RUN_DIR, "report.html.tmp")
    with open(tmp, "w") as f:
        f.write(page)
    os.replace(tmp, os.path.join(RUN_DIR, "report.html"))


if __name__ == "__main__":
    main()
