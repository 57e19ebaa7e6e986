#!/usr/bin/python3
"""Plot a sweep of probing runs (one CSV row per run) into one PNG of four panels.

usage: plot_probe_sweep.py OUT.png SWEEP.csv [--title TEXT]

SWEEP.csv has a header naming at least the columns
  surface, eps, vertices, probes, cells_created, detection_edges, positioning_edges,
  path_length, hausdorff, hausdorff_bound, seconds
(any order; more columns are allowed and ignored). One line per surface, points sorted along
the x axis, with markers:
  - probes / N against N (log x), N = vertices;
  - cells_created / (N ln N) against N (log x);
  - hausdorff against eps, log-log, with hausdorff_bound dashed in the same colour;
  - seconds / N (in microseconds) against N (log x).
Empty cells, "nan" and "inf" leave a point out; lines starting with '#' are comments.
A malformed file stops the script with a one-line message naming the file and the line.
Needs matplotlib (run with /usr/bin/python3).
"""
import argparse
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

REQUIRED = ["surface", "eps", "vertices", "probes", "cells_created", "detection_edges",
            "positioning_edges", "path_length", "hausdorff", "hausdorff_bound", "seconds"]
EMPTY = {"", "nan", "-nan", "inf", "-inf", "+inf"}


def fail(msg):
    sys.exit(f"plot_probe_sweep.py: error: {msg}")


def read_sweep(path):
    """{surface: [row dict of floats (nan when empty)]}, in file order."""
    try:
        with open(path, newline="", encoding="utf-8", errors="replace") as f:
            numbered = [(n, line) for n, line in enumerate(f, 1)
                        if line.strip() and not line.lstrip().startswith("#")]
    except OSError as e:
        fail(f"{path}: {e.strerror}")
    if not numbered:
        fail(f"{path}: empty file (no header)")
    header_line, header = numbered[0][0], next(csv.reader([numbered[0][1]]))
    header = [h.strip() for h in header]
    missing = [c for c in REQUIRED if c not in header]
    if missing:
        fail(f"{path}:{header_line}: the header lacks the column(s) {', '.join(missing)}")
    runs = {}
    for number, line in numbered[1:]:
        cells = next(csv.reader([line]))
        if len(cells) != len(header):
            fail(f"{path}:{number}: {len(cells)} fields, the header has {len(header)}")
        row = dict(zip(header, (c.strip() for c in cells)))
        if not row["surface"]:
            fail(f"{path}:{number}: empty surface name")
        values = {}
        for col in REQUIRED[1:]:
            text = row[col]
            if text.lower() in EMPTY:
                values[col] = math.nan
                continue
            try:
                values[col] = float(text)
            except ValueError:
                fail(f"{path}:{number}: column {col}: {text!r} is not a number")
        runs.setdefault(row["surface"], []).append(values)
    if not runs:
        fail(f"{path}: no data rows")
    return runs


def series(rows, x, y, positive_y=False):
    """Finite points (x(row), y(row)) with x > 0 (and y > 0 if asked), sorted by x."""
    pts = []
    for r in rows:
        xv, yv = x(r), y(r)
        if math.isfinite(xv) and math.isfinite(yv) and xv > 0 and (yv > 0 or not positive_y):
            pts.append((xv, yv))
    pts.sort()
    return [p[0] for p in pts], [p[1] for p in pts]


def per_n_log_n(r):
    n = r["vertices"]
    return r["cells_created"] / (n * math.log(n)) if n > 1 else math.nan


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("sweep")
    parser.add_argument("--title", default=None)
    args = parser.parse_args()
    runs = read_sweep(args.sweep)

    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5))
    panels = [
        (axes[0][0], lambda r: r["vertices"], lambda r: r["probes"] / r["vertices"],
         "vertices N", "probes / N", "linear"),
        (axes[0][1], lambda r: r["vertices"], per_n_log_n,
         "vertices N", "cells created / (N ln N)", "linear"),
        (axes[1][0], lambda r: r["eps"], lambda r: r["hausdorff"],
         "ε", "Hausdorff distance", "log"),
        (axes[1][1], lambda r: r["vertices"], lambda r: 1e6 * r["seconds"] / r["vertices"],
         "vertices N", "seconds / N  [µs]", "linear"),
    ]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    markers = "osD^v<>ph*"
    for i, (surface, rows) in enumerate(runs.items()):
        color, marker = colors[i % len(colors)], markers[i % len(markers)]
        for ax, x, y, _, _, yscale in panels:
            xs, ys = series(rows, x, y, positive_y=yscale == "log")
            if xs:
                ax.plot(xs, ys, marker=marker, color=color, linewidth=1.2, markersize=5,
                        label=surface)
        xs, ys = series(rows, lambda r: r["eps"], lambda r: r["hausdorff_bound"], positive_y=True)
        if xs:
            axes[1][0].plot(xs, ys, linestyle="--", color=color, linewidth=1,
                            label=f"{surface}: bound")
    for ax, _, _, xlabel, ylabel, yscale in panels:
        ax.set_xscale("log")
        ax.set_yscale(yscale)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=8)
    for ax, title in ((axes[0][0], "probes per vertex"),
                      (axes[0][1], "Delaunay cells created per N ln N"),
                      (axes[1][0], "Hausdorff distance and its bound (dashed)"),
                      (axes[1][1], "time per vertex")):
        ax.set_title(title, fontsize=9)
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
