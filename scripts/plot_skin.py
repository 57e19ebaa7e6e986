#!/usr/bin/python3
"""Draw a skin mesh coloured by its length scale rho, into one PNG.

usage: plot_skin.py OUT.png MESH.obj RHO.txt [--title TEXT]

MESH.obj: `v` vertices and `f` triangles (read by plot_probe.py's reader: one-line errors
naming the file and the line). RHO.txt: one number per line, rho at each vertex in the order
of the `v` statements. Each triangle is coloured by the mean rho of its vertices on a
logarithmic scale (small rho, near necks and crevices, is dark), lit by its normal; two views
half a turn apart. Thin edges are drawn below 20,000 triangles.
Needs matplotlib and numpy (run with /usr/bin/python3).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import colors  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from plot_probe import Obj  # noqa: E402

EDGES_BELOW = 20_000


def read_rho(path, count):
    values = []
    try:
        f = open(path, encoding="utf-8", errors="replace")
    except OSError as e:
        sys.exit(f"plot_skin.py: error: {path}: {e.strerror}")
    with f:
        for number, raw in enumerate(f, 1):
            text = raw.strip()
            if not text:
                continue
            try:
                v = float(text)
            except ValueError:
                sys.exit(f"plot_skin.py: error: {path}:{number}: not a number: {text[:40]!r}")
            if not math.isfinite(v) or v < 0:
                sys.exit(f"plot_skin.py: error: {path}:{number}: rho must be finite and >= 0")
            values.append(v)
    if len(values) != count:
        sys.exit(f"plot_skin.py: error: {path}: {len(values)} values for {count} vertices")
    return np.array(values)


def main():
    ap = argparse.ArgumentParser(description="Draw a skin mesh coloured by rho.")
    ap.add_argument("out")
    ap.add_argument("mesh")
    ap.add_argument("rho")
    ap.add_argument("--title", default="")
    a = ap.parse_args()
    mesh = Obj(a.mesh)
    if not mesh.faces:
        sys.exit(f"plot_skin.py: error: {a.mesh}: no triangles to draw")
    rho = read_rho(a.rho, len(mesh.points))
    faces = np.asarray(mesh.faces, dtype=np.int64)
    tris = mesh.points[faces]
    face_rho = rho[faces].mean(axis=1)
    lo = max(float(face_rho.min()), 1e-12)
    hi = max(float(face_rho.max()), lo * 1.0001)
    norm = colors.LogNorm(vmin=lo, vmax=hi)
    cmap = plt.get_cmap("viridis")
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    centre = mesh.points.mean(axis=0)
    extent = float(np.max(np.ptp(mesh.points, axis=0))) / 2 or 1.0
    fig = plt.figure(figsize=(12, 6.4))
    fig.subplots_adjust(left=0, right=0.86, bottom=0, top=0.94, wspace=0)
    for k, azim in enumerate((-60, 120)):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        light = np.array([math.cos(math.radians(azim + 30)), math.sin(math.radians(azim + 30)), 0.8])
        light /= np.linalg.norm(light)
        shade = 0.55 + 0.45 * np.clip(n @ light, 0, 1)
        rgba = cmap(norm(face_rho))
        rgba[:, :3] *= shade[:, None]
        coll = Poly3DCollection(tris, facecolors=rgba,
                                edgecolors=(0, 0, 0, 0.25) if len(faces) < EDGES_BELOW else "none",
                                linewidths=0.2)
        ax.add_collection3d(coll)
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            setter(c - extent, c + extent)
        try:
            ax.set_box_aspect((1, 1, 1), zoom=1.45)
        except TypeError:  # matplotlib before 3.6
            ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=20, azim=azim)
        ax.set_axis_off()
    sm = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=fig.axes, shrink=0.6, label="length scale rho (log)")
    fig.suptitle(a.title or os.path.basename(a.mesh))
    try:
        fig.savefig(a.out, dpi=110)
    except OSError as e:
        sys.exit(f"plot_skin.py: error: {a.out}: {e.strerror}")
    print(f"plot_skin.py: wrote {a.out}")


if __name__ == "__main__":
    main()
