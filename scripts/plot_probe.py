#!/usr/bin/python3
"""Draw a mesh made by probing together with the probing device's path, into one PNG.

usage: plot_probe.py OUT.png MESH.obj PATH.obj [--title TEXT]

MESH.obj: `v` vertices and either `f` triangles (a 3D run) or `l` polylines (a 2D run, all
z = 0). PATH.obj: `v` vertices and `l` polylines, the device's path; each pair of consecutive
indices of an `l` statement is one segment. Indices are 1-based (negative ones count back
from the last vertex); a line ending in a backslash continues on the next line; `#` starts
a comment; other statements (vn, vt, g, o, s, usemtl, ...) are ignored.

3D: the mesh shaded by its normals (thin edges below 20,000 triangles) and the path as thin
semi-transparent lines, two views half a turn apart so the path behind the surface shows.
Path segments inside the mesh's bounding ball are drawn in red, the others (the exterior
arcs around the object) lighter. 2D: the polyline in black, the path in blue (lighter
outside the polyline's bounding disc). Paths of more than 300,000 segments are thinned to
every k-th segment (deterministic); the caption says so.

A malformed file stops the script with a one-line message naming the file and the line.
Needs matplotlib and numpy (run with /usr/bin/python3).
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection  # noqa: E402

MAX_SEGMENTS = 300_000
EDGES_BELOW = 20_000
INSIDE = "tab:red"
OUTSIDE = "#f4a582"  # a lighter red
PATH_2D = "tab:blue"
OUTSIDE_2D = "#9ecae1"


def fail(path, line, msg):
    sys.exit(f"plot_probe.py: error: {path}:{line}: {msg}")


class Obj:
    """The v, f and l statements of an OBJ file."""

    def __init__(self, path):
        self.path = path
        self.points = []
        self.faces = []  # triples of 0-based indices
        self.line_indices = []  # the 0-based indices of all `l` statements, one after another
        self.line_lengths = []  # how many indices each `l` statement has
        try:
            f = open(path, encoding="utf-8", errors="replace")
        except OSError as e:
            sys.exit(f"plot_probe.py: error: {path}: {e.strerror}")
        with f:
            pending, start = "", 0
            for number, raw in enumerate(f, 1):
                text = raw.split("#", 1)[0].strip()
                if pending:
                    text = pending + " " + text
                else:
                    start = number
                if text.endswith("\\"):
                    pending = text[:-1]
                    continue
                pending = ""
                if text:
                    self._statement(text.split(), start)
            if pending:
                fail(path, start, "the file ends inside a continued statement")
        self.points = np.array(self.points, dtype=float).reshape(-1, 3)

    def _index(self, token, line):
        word = token.split("/", 1)[0]
        try:
            i = int(word)
        except ValueError:
            fail(self.path, line, f"invalid vertex index {token!r}")
        n = len(self.points)
        if i < 0:
            i += n + 1
        if i < 1 or i > n:
            fail(self.path, line, f"vertex index {token} is out of range ({n} vertices defined above)")
        return i - 1

    def _statement(self, words, line):
        kind = words[0]
        if kind == "v":
            if len(words) < 4:
                fail(self.path, line, f"a vertex needs 3 coordinates, found {len(words) - 1}")
            try:
                xyz = [float(w) for w in words[1:4]]
            except ValueError:
                fail(self.path, line, "a vertex coordinate is not a number")
            if not all(math.isfinite(c) for c in xyz):
                fail(self.path, line, "a vertex coordinate is not finite")
            self.points.append(xyz)
        elif kind == "f":
            if len(words) != 4:
                fail(self.path, line, f"face has {len(words) - 1} vertices; only triangles are drawn")
            self.faces.append([self._index(w, line) for w in words[1:]])
        elif kind == "l":
            if len(words) < 3:
                fail(self.path, line, f"a polyline needs at least 2 indices, found {len(words) - 1}")
            self.line_indices.extend(self._index(w, line) for w in words[1:])
            self.line_lengths.append(len(words) - 1)

    def segments(self):
        """All segments of the polylines as an (n, 2) array of 0-based indices."""
        flat = np.asarray(self.line_indices, dtype=np.int64)
        starts = np.ones(len(flat), dtype=bool)  # positions where a segment starts
        starts[np.cumsum(np.asarray(self.line_lengths, dtype=np.int64)) - 1] = False
        first = np.flatnonzero(starts)
        return np.column_stack([flat[first], flat[first + 1]])


def thin(segments):
    """Every k-th segment, k the smallest stride keeping at most MAX_SEGMENTS; and k."""
    k = max(1, math.ceil(len(segments) / MAX_SEGMENTS))
    return segments[::k], k


def path_alpha(n):
    """Opacity of path lines: 0.5 for up to 20,000 segments, fading as 1/sqrt(n) beyond
    (at least 0.05), so a dense path does not paint over everything."""
    return max(0.05, min(0.5, 0.5 * math.sqrt(20_000 / max(n, 1))))


def bounding_ball(points):
    center = (points.min(axis=0) + points.max(axis=0)) / 2
    return center, float(np.sqrt(((points - center) ** 2).sum(axis=1).max()))


def split_inside(coords, center, radius):
    """Segments (n, 2, d) with both ends in the ball, and the others."""
    dist = np.sqrt(((coords - center) ** 2).sum(axis=2))
    inside = (dist <= radius * (1 + 1e-9)).all(axis=1)
    return coords[inside], coords[~inside]


def shaded_colors(points, faces):
    tri = points[faces]
    normals = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normals, axis=1)
    normals /= np.where(length > 0, length, 1)[:, None]
    light = np.array([0.4, -0.5, 0.77])
    light /= np.linalg.norm(light)
    shade = 0.35 + 0.65 * np.abs(normals @ light)
    base = np.array([0.62, 0.74, 0.86])
    colors = np.ones((len(faces), 4))
    colors[:, :3] = base * shade[:, None]
    return colors


def draw_3d(fig, mesh, path_points, segs, caption_parts):
    faces = np.asarray(mesh.faces, dtype=int)
    used = mesh.points[np.unique(faces)]
    center, radius = bounding_ball(used)
    coords = path_points[segs]
    inside, outside = split_inside(coords, center, radius)
    everything = np.concatenate([used, coords.reshape(-1, 3)]) if len(coords) else used
    lo, hi = everything.min(axis=0), everything.max(axis=0)
    mid, half = (lo + hi) / 2, max(float((hi - lo).max()) / 2, 1e-300)
    colors = shaded_colors(mesh.points, faces)
    edges = len(faces) < EDGES_BELOW
    elev = 20
    for i, azim in enumerate((30, 210)):
        # mplot3d sorts whole collections, not segments against triangles: the path is split
        # into the part nearer to the eye than the mesh's centre (drawn over the mesh) and the
        # part beyond it (drawn under), so each view hides roughly the far side of the path.
        a, e = math.radians(azim), math.radians(elev)
        eye = np.array([math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e)])
        ax = fig.add_subplot(1, 2, i + 1, projection="3d", computed_zorder=False)
        ax.add_collection3d(Poly3DCollection(
            mesh.points[faces], facecolors=colors, edgecolors="#30303080" if edges else "none",
            linewidths=0.1 if edges else 0, zorder=2))
        # Exterior travel (mostly arcs on the boundary of Omega) is context: drawn faint, so that
        # the path among the Voronoi vertices near the object stands out.
        for part, color, width, alpha in ((outside, OUTSIDE, 0.2, 0.25 * path_alpha(len(outside))),
                                          (inside, INSIDE, 0.3, path_alpha(len(inside)))):
            if not len(part):
                continue
            near = (part.mean(axis=1) - center) @ eye > 0
            for chosen, z in ((~near, 1), (near, 3)):
                if chosen.any():
                    ax.add_collection3d(Line3DCollection(part[chosen], colors=color, linewidths=width,
                                                         alpha=alpha, zorder=z))
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] - half, mid[1] + half)
        ax.set_zlim(mid[2] - half, mid[2] + half)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_title(f"azimuth {azim}°", fontsize=9)
        ax.tick_params(labelsize=6)
    caption_parts.append(f"path inside the mesh's bounding ball in red, outside it (exterior travel) "
                         f"faint: {len(inside):,} / {len(outside):,} drawn segments")


def draw_2d(fig, mesh, path_points, segs, caption_parts):
    outline = mesh.segments()
    used = mesh.points[np.unique(outline)][:, :2]
    center, radius = bounding_ball(used)
    coords = path_points[segs][:, :, :2]
    inside, outside = split_inside(coords, center, radius)
    ax = fig.add_subplot(1, 1, 1)
    fade = path_alpha(len(coords))
    if len(outside):
        ax.add_collection(LineCollection(outside, colors=OUTSIDE_2D, linewidths=0.3, alpha=fade))
    if len(inside):
        ax.add_collection(LineCollection(inside, colors=PATH_2D, linewidths=0.3, alpha=fade))
    ax.add_collection(LineCollection(mesh.points[outline][:, :, :2], colors="black", linewidths=0.8))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.tick_params(labelsize=7)
    caption_parts.append(f"polyline in black; path in blue, lighter outside the polyline's bounding "
                         f"disc: {len(inside):,} / {len(outside):,} drawn segments")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("mesh")
    parser.add_argument("path")
    parser.add_argument("--title", default=None)
    args = parser.parse_args()

    mesh, path = Obj(args.mesh), Obj(args.path)
    if mesh.faces:
        dim = 3
    elif mesh.line_lengths:
        dim = 2
        if (mesh.points[:, 2] != 0).any() or (len(path.points) and (path.points[:, 2] != 0).any()):
            sys.exit(f"plot_probe.py: error: {args.mesh}: a mesh of polylines is drawn in 2D, "
                     "but a vertex of the mesh or of the path has z != 0")
    else:
        sys.exit(f"plot_probe.py: error: {args.mesh}: holds neither `f` triangles nor `l` polylines")
    path_segments = path.segments()
    if len(path_segments) == 0:
        sys.exit(f"plot_probe.py: error: {args.path}: holds no `l` polyline")
    segs, stride = thin(path_segments)

    caption = []
    if stride == 1:
        caption.append(f"path: all {len(path_segments):,} segments drawn")
    else:
        caption.append(f"path: 1 segment in {stride} drawn (segments 0, {stride}, {2 * stride}, ... "
                       f"in file order: {len(segs):,} of {len(path_segments):,})")
    name = args.title or os.path.basename(args.mesh)
    if dim == 3:
        fig = plt.figure(figsize=(13, 6.5))
        draw_3d(fig, mesh, path.points, segs, caption)
        counts = f"{len(mesh.points):,} vertices, {len(mesh.faces):,} facets"
    else:
        fig = plt.figure(figsize=(8, 8))
        draw_2d(fig, mesh, path.points, segs, caption)
        counts = f"{len(mesh.points):,} vertices, {len(mesh.segments()):,} polyline segments"
    fig.suptitle(f"{name}: {counts}, {len(path_segments):,} path segments", fontsize=11)
    fig.text(0.5, 0.01, "; ".join(caption), ha="center", va="bottom", fontsize=8)
    fig.tight_layout(rect=(0, 0.03, 1, 0.96))
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
