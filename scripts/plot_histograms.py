#!/usr/bin/python3
"""Plot the histogram CSVs written by `dynmesh experiment --out DIR` into one PNG.

usage: plot_histograms.py DIR OUT.png

One row per case (sphere, torus, real meshes); left: 180 - dihedral, right: normal
deviation (when the true surface is known). Initial, worsened and smoothed meshes are
overlaid, as in the edge-flip paper's Figures 18-21.
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    cols = {k: [float(r[k]) for r in rows] for k in rows[0]}
    return cols


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    files = sorted(glob.glob(os.path.join(sys.argv[1], "*_histograms.csv")))
    if not files:
        sys.exit(f"no *_histograms.csv in {sys.argv[1]}")
    fig, axes = plt.subplots(len(files), 2, figsize=(11, 3.2 * len(files)), squeeze=False)
    for row, path in enumerate(files):
        name = os.path.basename(path)[: -len("_histograms.csv")]
        h = read(path)
        centers = [(a + b) / 2 for a, b in zip(h["bin_lo_deg"], h["bin_hi_deg"])]
        width = h["bin_hi_deg"][0] - h["bin_lo_deg"][0]
        for col, (kind, label) in enumerate([("dihedral", "180° − dihedral (deg)"),
                                             ("normal", "normal deviation (deg)")]):
            ax = axes[row][col]
            if f"initial_{kind}" not in h:
                ax.set_axis_off()
                continue
            for stage, color, style in [("worsened", "tab:red", "-"), ("smoothed", "tab:blue", "-"),
                                        ("initial", "black", ":")]:
                ax.step(centers, h[f"{stage}_{kind}"], where="mid", color=color, label=stage,
                        linestyle=style, linewidth=1.8 if stage == "smoothed" else 1.1)
            ax.set_yscale("symlog", linthresh=10)
            ax.set_xlim(0, h["bin_hi_deg"][-1] + width / 2)
            ax.set_xlabel(label)
            ax.set_ylabel("count")
            ax.set_title(name.replace("__", ", ").replace("_", " "), fontsize=9)
            ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(sys.argv[2], dpi=110)
    print(f"wrote {sys.argv[2]}")


if __name__ == "__main__":
    main()
