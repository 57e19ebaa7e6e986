"""The Python module against the CLI and the files it writes (run by ctest: python.pytest)."""
import gc
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import dynmesh

BIN = os.environ["DYNMESH_BIN"]
DATA = os.environ["DYNMESH_DATA"]


def octahedron():
    v = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], dtype=float)
    f = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4],
                  [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]])
    return v, f


def cycles(faces):
    """Each face rotated to start at its smallest index (the same oriented triangle)."""
    faces = np.asarray(faces)
    shift = np.argmin(faces, axis=1)
    return np.array([np.roll(t, -k) for t, k in zip(faces, shift)])


def corner_triangles(v, f):
    """The oriented triangles as corner coordinates, each rotated to start at its smallest corner."""
    out = set()
    for t in np.asarray(f):
        c = [tuple(v[i]) for i in t]
        k = c.index(min(c))
        out.add(tuple(c[k:] + c[:k]))
    return out


def write_off(path, v, f):
    """An OFF file written here (not by dynmesh), corners in the arrays' order."""
    path.write_text("OFF\n%d %d 0\n" % (len(v), len(f)) + "".join("%r %r %r\n" % tuple(p) for p in v)
                    + "".join("3 %d %d %d\n" % tuple(t) for t in f))
    return str(path)


def test_version_is_the_cli_version():
    out = subprocess.run([BIN, "--version"], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["dynmesh", dynmesh.__version__]


def test_round_trip_through_every_writable_format(tmp_path):
    v, f = octahedron()
    for ext in ("off", "obj", "ply", "stl"):
        path = str(tmp_path / f"o.{ext}")
        dynmesh.write_mesh(path, v, f)
        v2, f2 = dynmesh.read_mesh(path)
        assert v2.dtype == np.float64 and f2.dtype == np.int64
        if ext == "stl":  # no shared vertices in the file: the reader numbers them as it meets them
            assert corner_triangles(v2, f2) == corner_triangles(v, f)
            continue
        np.testing.assert_array_equal(v2, v)
        np.testing.assert_array_equal(cycles(f2), cycles(f))
    # Without a file between, the arrays come back as given, corner order included.
    faces, report = dynmesh.flip(v, f)
    assert report["flips"] == 0
    np.testing.assert_array_equal(faces, f)


def test_flip_matches_the_cli(tmp_path):
    """The same flips and the same faces as `dynmesh flip` on a worsened bundled mesh (the CLI
    reads the arrays the module flips, written by the module)."""
    worse = str(tmp_path / "worse.off")
    subprocess.run([BIN, "worsen", os.path.join(DATA, "blobby.off"), "-o", worse, "--rounds", "3",
                    "--seed", "1", "-q"], check=True)
    v, f = dynmesh.read_mesh(worse)
    given = write_off(tmp_path / "given.off", v, f)
    for criterion in ("angle", "delaunay"):
        out, rep = str(tmp_path / f"cli_{criterion}.off"), str(tmp_path / f"cli_{criterion}.json")
        subprocess.run([BIN, "flip", given, "-o", out, "--criterion", criterion, "--report", rep, "-q"], check=True)
        cli = json.load(open(rep))
        faces, report = dynmesh.flip(v, f, criterion=criterion)
        assert report["flips"] > 0
        for key in ("criterion", "vertices", "faces", "edges", "flips", "checks", "pushes", "converged"):
            assert report[key] == cli[key], key
        cli_v, cli_faces = dynmesh.read_mesh(out)
        np.testing.assert_array_equal(cli_v, v)
        np.testing.assert_array_equal(cycles(faces), cycles(cli_faces))


def test_worsen_matches_the_cli(tmp_path):
    v, f = dynmesh.read_mesh(os.path.join(DATA, "blobby.off"))
    given = write_off(tmp_path / "given.off", v, f)
    out, rep = str(tmp_path / "cli.off"), str(tmp_path / "cli.json")
    subprocess.run([BIN, "worsen", given, "-o", out, "--rounds", "2", "--seed", "7", "--probability", "0.3",
                    "--min-dihedral", "100", "--report", rep, "-q"], check=True)
    cli = json.load(open(rep))
    faces, report = dynmesh.worsen(v, f, rounds=2, probability=0.3, min_dihedral_deg=100, seed=7)
    assert report["flips"] > 0 and report["rejected"] > 0
    for key in ("vertices", "faces", "flips", "attempts", "rejected", "rounds", "seed"):
        assert report[key] == cli[key], key
    np.testing.assert_array_equal(cycles(faces), cycles(dynmesh.read_mesh(out)[1]))
    assert not np.array_equal(cycles(dynmesh.worsen(v, f, seed=8)[0]), cycles(faces))  # the seed is used
    with pytest.raises(ValueError, match="probability"):
        dynmesh.worsen(v, f, probability=1.5)


def test_errors_are_python_exceptions(tmp_path):
    v, f = octahedron()
    with pytest.raises(ValueError, match=r"shape \(n, 3\)"):
        dynmesh.flip(v[:, :2], f)
    with pytest.raises(ValueError, match="refers to vertex 6"):
        dynmesh.flip(v, np.vstack([f[:-1], [[0, 1, 6]]]))
    with pytest.raises(ValueError, match="unknown flip criterion 'nope'"):
        dynmesh.flip(v, f, criterion="nope")
    with pytest.raises(OSError, match="missing.off"):
        dynmesh.read_mesh(str(tmp_path / "missing.off"))
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(OSError, match="bad.off"):  # malformed: the file's problem
        dynmesh.read_mesh(str(bad))
    nonmanifold = np.vstack([f, [[0, 2, 4]]])
    with pytest.raises(ValueError):
        dynmesh.flip(v, nonmanifold)


def test_large_arrays_name_their_first_bad_row():
    # Arrays this long are converted by several threads; the message still names the first bad
    # row (a third of the way into part 0), not the one a later part finds first (at its start).
    n = 1 << 20
    v = np.zeros((n, 3))
    v[n // 3, 1] = np.nan
    v[n // 2, 0] = np.inf
    f = np.zeros((n, 3), dtype=np.int64)
    with pytest.raises(ValueError, match="vertices: point %d has a coordinate that is not finite" % (n // 3)):
        dynmesh.flip(v, f)
    v[:] = 0.0
    f[n // 5] = [0, 1, n]
    f[n // 2] = [0, 1, -1]
    with pytest.raises(ValueError, match="face %d refers to vertex %d" % (n // 5, n)):
        dynmesh.flip(v, f)


def test_arrays_outlive_their_mesh_and_inputs_are_not_kept():
    v, f = octahedron()
    refs = sys.getrefcount(v), sys.getrefcount(f)
    faces, report = dynmesh.flip(v, f)
    del report
    gc.collect()
    assert (sys.getrefcount(v), sys.getrefcount(f)) == refs  # the module keeps no reference
    del v, f
    gc.collect()
    assert faces.shape == (8, 3) and faces.dtype == np.int64
    assert sorted(np.bincount(faces.ravel())) == [4] * 6  # an octahedron still: every vertex in 4 faces


def test_signatures_and_docstrings_are_visible():
    doc = dynmesh.flip.__doc__
    assert "flip(vertices: numpy.ndarray" in doc and "criterion: str = 'angle'" in doc
    assert "field names of `dynmesh flip --report`" in doc
    assert "NumPy arrays" in dynmesh.__doc__
