#!/usr/bin/python3
"""Draw 2D triangle meshes written by `dynmesh quadtree -o X.node` (X.node + X.ele) side by side.

usage: plot_mesh2d.py OUT.png MESH.node [MESH2.node ...]
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402


def rows(path):
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if line:
                yield line


def read(node_path):
    nodes = list(rows(node_path))
    n, dim = int(nodes[0][0]), int(nodes[0][1])
    if dim != 2:
        sys.exit(f"{node_path}: only 2D meshes can be drawn")
    first = int(nodes[1][0])
    xs = [float(r[1]) for r in nodes[1:n + 1]]
    ys = [float(r[2]) for r in nodes[1:n + 1]]
    ele = list(rows(os.path.splitext(node_path)[0] + ".ele"))
    tris = [[int(v) - first for v in r[1:4]] for r in ele[1:int(ele[0][0]) + 1]]
    return xs, ys, tris


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    paths = sys.argv[2:]
    fig, axes = plt.subplots(1, len(paths), figsize=(6 * len(paths), 6), squeeze=False)
    for ax, path in zip(axes[0], paths):
        xs, ys, tris = read(path)
        ax.triplot(mtri.Triangulation(xs, ys, tris), color="tab:blue", linewidth=0.25)
        ax.set_aspect("equal")
        ax.set_title(f"{os.path.basename(path)}: {len(xs)} vertices, {len(tris)} triangles",
                     fontsize=9, pad=8)
        ax.set_axis_off()
    fig.tight_layout(rect=(0, 0, 1, 0.97))
    fig.savefig(sys.argv[1], dpi=120)
    print(f"wrote {sys.argv[1]}")


if __name__ == "__main__":
    main()
