#!/usr/bin/python3
"""Reads the polyline files dynmesh writes (WriteOptions::polylines) with real readers.

usage: polyline_readers_check.py SAMPLES_EXE WORK_DIR

SAMPLES_EXE (the io_polyline_samples test program) writes polygon.*, mixed.*, mixed_ascii.ply
and long.* into WORK_DIR; this script spells the expected content out again and compares:
  .vtp  VTK's vtkXMLPolyDataReader: points, lines, triangles, cell order (lines first), field
  .vtk  VTK's vtkPolyDataReader: the same
  .obj  VTK's vtkOBJReader: points, lines (the 2500-index one continued over three lines),
        triangles; meshio: the triangles of a file that also holds `l` statements
  .ply  VTK's vtkPLYReader: points and triangles (VTK 9.1 ignores the `edge` element; if
        a reader version returns lines, they are compared as segments)
What no installed reader understands is said, not skipped silently: meshio 5.0 reads neither
PLY `edge` elements (it refuses the whole file) nor POLYDATA legacy VTK nor .vtp nor 2-vertex
OFF faces, and VTK 9.1 has no OFF reader. Those are parsed structurally by
tests/io/polylines_write_test.cpp (and OFF by CGAL's reader there).
"""
import os
import shutil
import subprocess
import sys

POLYGON_POINTS = [(0, 0, 0), (2, 0, 0), (3, 1, 0), (2, 2, 0), (0, 2, 0), (-1, 1, 0)]
POLYGON_LINES = [[0, 1, 2, 3, 4, 5, 0]]
MIXED_POINTS = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1),
                (2, 2, 2), (-2, 2, 2), (0, -2, 2)]
MIXED_TRIANGLES = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
                   [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
MIXED_LINES = [[6, 7, 8, 6], [0, 6, 1, 7, 2]]
LONG_LINES = [[k % 9 for k in range(2500)]]

CASES = {  # name: points, triangles, lines
    "polygon": (POLYGON_POINTS, [], POLYGON_LINES),
    "mixed": (MIXED_POINTS, MIXED_TRIANGLES, MIXED_LINES),
    "long": (MIXED_POINTS, MIXED_TRIANGLES, LONG_LINES),
}

checks = 0


def check(ok, what):
    global checks
    if not ok:
        sys.exit(f"polyline_readers_check: FAIL: {what}")
    checks += 1


def segments(lines):
    return [(p[i], p[i + 1]) for p in lines for i in range(len(p) - 1)]


def cell_array(cells):
    """[[ids], ...] of a vtkCellArray."""
    from vtkmodules.vtkCommonCore import vtkIdList

    out, ids = [], vtkIdList()
    cells.InitTraversal()
    while cells.GetNextCell(ids):
        out.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
    return out


def read_vtk(reader_class, path):
    """The reader's output; any error or warning the reader reports fails the check."""
    reports = []
    reader = reader_class()
    for event in ("ErrorEvent", "WarningEvent"):
        reader.AddObserver(event, lambda obj, ev: reports.append(ev))
    reader.SetFileName(path)
    reader.Update()
    check(not reports, f"{path}: the VTK reader reported {reports}")
    return reader.GetOutput()


def points_of(data):
    return [tuple(data.GetPoint(i)) for i in range(data.GetNumberOfPoints())]


def check_vtk_polydata(path, name, data, with_field):
    points, triangles, lines = CASES[name]
    check(points_of(data) == [tuple(map(float, p)) for p in points], f"{path}: points")
    check(cell_array(data.GetLines()) == lines, f"{path}: lines {cell_array(data.GetLines())[:3]}")
    check(cell_array(data.GetPolys()) == triangles, f"{path}: triangles")
    check(data.GetNumberOfVerts() == 0 and data.GetNumberOfStrips() == 0, f"{path}: verts/strips")
    # VTK numbers cells verts, lines, polys, strips: the lines are cells 0.. n_lines-1.
    types = [data.GetCellType(i) for i in range(data.GetNumberOfCells())]
    check(types == [4 if len(l) > 2 else 3 for l in lines] + [5] * len(triangles),
          f"{path}: cell types {types[:12]}")
    if with_field:
        arr = data.GetPointData().GetArray("height")
        check(arr is not None and arr.GetNumberOfTuples() == len(points), f"{path}: height field")
        check(data.GetCellData().GetNumberOfArrays() == 0, f"{path}: no cell data")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    subprocess.run([exe, work], check=True)

    from vtkmodules.vtkIOGeometry import vtkOBJReader
    from vtkmodules.vtkIOLegacy import vtkPolyDataReader
    from vtkmodules.vtkIOPLY import vtkPLYReader
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
    import meshio

    for name in CASES:
        for ext, reader in ((".vtp", vtkXMLPolyDataReader), (".vtk", vtkPolyDataReader)):
            path = os.path.join(work, name + ext)
            check_vtk_polydata(path, name, read_vtk(reader, path), name == "mixed")

        path = os.path.join(work, name + ".obj")
        data = read_vtk(vtkOBJReader, path)
        points, triangles, lines = CASES[name]
        check(points_of(data) == [tuple(map(float, p)) for p in points], f"{path}: points")
        check(cell_array(data.GetLines()) == lines, f"{path}: lines")
        check(cell_array(data.GetPolys()) == triangles, f"{path}: triangles")
        if triangles:
            mesh = meshio.read(path)
            got = [c.data.tolist() for c in mesh.cells if c.type == "triangle"]
            check(got == [triangles], f"{path}: meshio triangles")
            check(mesh.points.tolist() == [list(map(float, p)) for p in points], f"{path}: meshio points")

    for file in ("polygon.ply", "mixed.ply", "mixed_ascii.ply", "long.ply"):
        path = os.path.join(work, file)
        name = file.split(".")[0].split("_")[0]
        points, triangles, lines = CASES[name]
        data = read_vtk(vtkPLYReader, path)
        check(points_of(data) == [tuple(map(float, p)) for p in points], f"{path}: points")
        check(cell_array(data.GetPolys()) == triangles, f"{path}: triangles")
        got = cell_array(data.GetLines())
        if got:  # a VTK that reads PLY edges: one 2-point line per segment
            check([tuple(c) for c in got] == segments(lines), f"{path}: edges")

    print(f"polyline readers: {checks} checks passed (VTK: .vtp .vtk .obj .ply; meshio: .obj)")
    print("not read by any installed reader (parsed by polylines_write_test instead): "
          ".ply edge elements (VTK 9.1 skips them, meshio 5.0 refuses the file), "
          ".off 2-vertex faces (no VTK OFF reader, meshio 5.0 reads triangles only)")


if __name__ == "__main__":
    main()
