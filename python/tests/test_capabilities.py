"""Every capability of the Python module end to end, against the CLI on the same input where the
CLI has the same operation, and against the module's own invariants otherwise."""
import gc
import json
import os
import subprocess

import numpy as np
import pytest

import dynmesh

BIN = os.environ["DYNMESH_BIN"]
DATA = os.environ["DYNMESH_DATA"]
SHARED = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(DATA))), "..", "shared", "data")


def cli_report(tmp_path, *args):
    """Runs the CLI with --report and returns the report."""
    rep = str(tmp_path / "cli_report.json")
    subprocess.run([BIN, *args, "--report", rep, "-q"], check=True)
    with open(rep) as f:
        return json.load(f)


def write_off(path, v, f):
    path.write_text("OFF\n%d %d 0\n" % (len(v), len(f)) + "".join("%r %r %r\n" % tuple(p) for p in v)
                    + "".join("3 %d %d %d\n" % tuple(t) for t in f))
    return str(path)


def write_node(path, points):
    d = points.shape[1]
    path.write_text("%d %d 0 0\n" % (len(points), d)
                    + "".join("%d %s\n" % (i + 1, " ".join(repr(float(x)) for x in p)) for i, p in enumerate(points)))
    return str(path)


def blobby():
    return dynmesh.read_mesh(os.path.join(DATA, "blobby.off"))


# ---- quality and local flips -----------------------------------------------------------------

def test_quality_matches_dynmesh_stats(tmp_path):
    v, f = blobby()
    f, _ = dynmesh.worsen(v, f, rounds=2, seed=3)
    path = write_off(tmp_path / "worse.off", v, f)
    cli = cli_report(tmp_path, "stats", path, "--self-intersections")
    q = dynmesh.quality(v, f, self_intersections=True)
    assert q["min_angle_deg"] < 10  # worsened: the comparison is not between two perfect meshes
    assert {"vertices", "faces", "euler", "closed", "min_angle_deg", "self_intersections"} <= q.keys()
    for key, value in q.items():
        assert type(value) is type(cli[key]), key  # counts as int, closed as bool, the rest as float
        assert value == pytest.approx(cli[key], rel=1e-12), key


def test_local_flip_matches_the_cli(tmp_path):
    v, f = blobby()
    f, _ = dynmesh.worsen(v, f, rounds=3, seed=1)
    path = write_off(tmp_path / "worse.off", v, f)
    around = np.array([5, 17, 400, 17])  # a repeat is kept, as the CLI keeps it
    (tmp_path / "V.txt").write_text("5\n17\n400\n17\n")
    out = str(tmp_path / "cli.off")
    cli = cli_report(tmp_path, "flip", path, "-o", out, "--vertices", str(tmp_path / "V.txt"))
    faces, report = dynmesh.flip(v, f, around=around)
    assert 0 < report["flips"] < dynmesh.flip(v, f)[1]["flips"]  # local: fewer flips than global
    for key in ("flips", "checks", "converged"):
        assert report[key] == cli[key], key
    assert report["local"]["vertices_given"] == 4
    for key, value in report["local"].items():
        assert value == cli["local"][key], key
    with pytest.raises(ValueError, match=r"around\[0\] = 999999"):
        dynmesh.flip(v, f, around=np.array([999999]))
    with pytest.raises(ValueError, match="non-empty"):
        dynmesh.flip(v, f, around=np.array([], dtype=np.int64))
    with pytest.raises(ValueError, match="integers"):
        dynmesh.flip(v, f.astype(float))  # not truncated silently


# ---- the deforming mesh ------------------------------------------------------------------------

def test_deforming_mesh_follows_its_samples_and_applies_edits():
    v, f = blobby()
    lam = 0.0005
    dm = dynmesh.DeformingMesh(v, lambda_=lam, reference_faces=f)
    init = dm.init_report
    assert init["tri0"] == "restricted_delaunay" and init["euler"] == 2 and init["invariant_failures"] == []
    positions = v.copy()
    theta = 0.0
    updates = 0
    new_id = None
    for t in range(1, 31):
        theta += lam / 2  # a rotation about z: no point moves more than lambda per unit
        c, s = np.cos(theta), np.sin(theta)
        rot = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        positions = v @ rot.T
        if new_id is not None:
            positions = np.vstack([positions, extra @ rot.T])
        step = dm.advance(t, positions)
        assert step["t"] == t and step["max_displacement"] <= lam * 1.0001
        if t == 10:  # queue a sample on the surface (a vertex's position, nudged) and a deletion
            extra = (v[:1] * 0.999 + v[1:2] * 0.001)
            new_id = dm.queue_insertion(extra[0] @ rot.T)
            assert new_id == len(v)
            _, _, samples = dm.mesh()
            dm.queue_deletion(int(samples[3]))
            gone = int(samples[3])
        if step["update_due"]:
            u = dm.update()
            updates += 1
            assert u["next_step"] > t
            if t >= 10 and new_id is not None and "done" not in locals():
                assert u["samples_inserted"] == 1 and u["samples_deleted"] == 1
                done = True
    assert updates > 0 and "done" in locals()
    vv, ff, samples = dm.mesh()
    # Every mesh vertex is its sample, at the sample's current position.
    np.testing.assert_array_equal(vv, positions[samples])
    assert gone not in set(samples.tolist())
    q = dynmesh.quality(vv, ff)
    assert q["closed"] and q["euler"] == 2
    check = dm.check()
    assert check["ok"], check["problems"]
    assert check["vertices"] == len(vv) and check["samples"] == dm.live_samples == len(v)  # +1 -1
    assert dm.report["updates"] == updates and dm.report["samples_inserted"] == 1
    assert dm.report["violations"] == {} and dm.report["violation_examples"] == []
    with pytest.raises(ValueError, match="rows"):
        dm.advance(31, positions[:10])
    with pytest.raises(ValueError):
        dm.advance(30, positions)  # t must increase
    with pytest.raises(ValueError):
        dm.queue_deletion(gone)  # already deleted
    filler = positions.copy()
    filler[gone] = np.nan  # the row of a deleted sample is not read
    assert dm.advance(31, filler)["t"] == 31
    filler[int(samples[0])] = np.nan
    with pytest.raises(ValueError, match=str(int(samples[0]))):
        dm.advance(32, filler)


def test_deforming_mesh_updates_between_substeps_locally():
    # A fast push on one side of the blob: the unit is cut into sub-steps, and the updates
    # between them work on a region around the moving part (local_updates), or on the whole
    # mesh when asked.
    v, f = blobby()
    top = v[:, 2].max()
    push = np.clip((v[:, 2] - (top - 0.06)) / 0.06, 0.0, 1.0) ** 2  # 0 below, 1 at the top
    for local in (True, False):
        dm = dynmesh.DeformingMesh(v, lambda_=1e-4, reference_faces=f, local_updates=local)
        step = dm.advance(1, v - np.outer(push, [0.0, 0.0, 0.04]))
        assert step["substeps"] > 1 and step["internal_updates"] > 0
        assert not step["self_intersecting"] and step["inverted_triangles"] == 0
        if local:
            assert step["local_updates"] == step["internal_updates"]
            # The pushed cap is a few percent of the surface; the regions (U and its 2-ring)
            # stay under a quarter of the vertices.
            assert step["region_vertices"] < step["local_updates"] * len(dm.mesh()[0]) / 4
        else:
            assert step["local_updates"] == 0 and step["region_vertices"] == 0
        if step["update_due"]:
            dm.update()
        check = dm.check()
        assert check["ok"], check["problems"]


def test_deforming_mesh_refuses_bad_input():
    v, f = blobby()
    with pytest.raises(ValueError, match="lambda"):
        dynmesh.DeformingMesh(v, lambda_=-1.0, reference_faces=f)
    bad = v.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ValueError, match="point 7"):
        dynmesh.DeformingMesh(bad, lambda_=0.001)


def grid_cube(n):
    """The cube [-1, 1]^3 with an n x n grid of squares per face, two triangles each, outward."""
    index, pts, tris = {}, [], []

    def vertex(k):
        if k not in index:
            index[k] = len(pts)
            pts.append([-1 + 2.0 * c / n for c in k])
        return index[k]

    for axis in range(3):
        u, w = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, n):
            for i in range(n):
                for j in range(n):
                    q = []
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        k = [0, 0, 0]
                        k[axis], k[u], k[w] = side, i + di, j + dj
                        q.append(vertex(tuple(k)))
                    for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
                        a, b, c = (np.array(pts[x]) for x in t)
                        outward = np.cross(b - a, c - a)[axis] * (1 if side else -1) > 0
                        tris.append(t if outward else (t[0], t[2], t[1]))
    return np.array(pts), np.array(tris, dtype=np.int64)


def test_deforming_mesh_keeps_creases_given_a_feature_angle():
    v, f = grid_cube(8)
    with_creases = dynmesh.DeformingMesh(v, lambda_=0.05, reference_faces=f, feature_angle_deg=45.0)
    init = with_creases.init_report
    assert (init["crease_edges"], init["crease_lines"], init["corners"]) == (12 * 8, 12, 8)
    assert init["tri0"] == "decimated"
    assert dynmesh.DeformingMesh(v, lambda_=0.05, reference_faces=f).init_report["crease_edges"] == 0
    for t in range(1, 11):  # a quarter twist about z, back and forth
        a = 0.3 * np.sin(np.pi * t / 10) * v[:, 2]
        c, s = np.cos(a), np.sin(a)
        x = np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1], v[:, 2]])
        if with_creases.advance(t, x)["update_due"]:
            with_creases.update()
        check = with_creases.check()
        assert check["crease_edges"] >= 12 * 8 and check["crease_problems"] == 0, check["problems"]
        assert check["self_intersections"] == 0


# ---- dynamic quadtree meshes -------------------------------------------------------------------

def apply_change(points, simplices, change):
    """Applies last_change() to copies of current_mesh() arrays, as a caller mirroring the mesh."""
    points, simplices = points.copy(), simplices.copy()
    simplices[change["removed_simplices"]] = -1
    points[change["removed_vertices"]] = np.nan
    for ids, rows, target in ((change["added_vertex_ids"], change["added_vertices"], "p"),
                              (change["added_simplex_ids"], change["added_simplices"], "s")):
        if len(ids) == 0:
            continue
        arr = points if target == "p" else simplices
        need = int(ids.max()) + 1
        if need > len(arr):
            pad = np.full((need - len(arr), arr.shape[1]), np.nan if target == "p" else -1, dtype=arr.dtype)
            arr = np.vstack([arr, pad])
        arr[ids] = rows
        if target == "p":
            points = arr
        else:
            simplices = arr
    return points, simplices


def same_live(a, b):
    pa, sa = a
    pb, sb = b
    n, m = max(len(pa), len(pb)), max(len(sa), len(sb))
    pad = lambda x, k, fill: np.vstack([x, np.full((k - len(x), x.shape[1]), fill, dtype=x.dtype)])
    np.testing.assert_array_equal(pad(pa, n, np.nan), pad(pb, n, np.nan))
    np.testing.assert_array_equal(pad(sa, m, -1), pad(sb, m, -1))


@pytest.mark.parametrize("cls,dim", [(dynmesh.DynQuadMesh2, 2), (dynmesh.DynQuadMesh3, 3),
                                     (dynmesh.DynOffCenterMesh2, 2)])
def test_dynamic_mesh_updates_equal_a_fresh_build_and_the_change_is_exact(cls, dim):
    rng = np.random.default_rng(5)
    pts = rng.uniform(0, 1, (60 if dim == 2 else 25, dim))
    box = dict(origin=[-1.0] * dim, width=3.0)
    mesh = cls(pts[:-5], **box)
    for p in pts[-5:]:
        before = mesh.current_mesh()
        assert mesh.insert(p) == "inserted"
        change = mesh.last_change()
        assert len(change["added_simplex_ids"]) > 0
        same_live(apply_change(*before, change), mesh.current_mesh())
    assert mesh.insert(pts[0]) == "duplicate"
    assert mesh.insert([5.0] * dim) == "outside_domain"
    fresh = cls(pts, **box)
    for a, b in zip(mesh.mesh(), fresh.mesh()):
        np.testing.assert_array_equal(a, b)  # history independence, through the API
    before = mesh.current_mesh()
    assert mesh.erase(pts[3]) == "erased"
    same_live(apply_change(*before, mesh.last_change()), mesh.current_mesh())
    assert mesh.erase(pts[3]) == "not_found"
    assert len(mesh) == len(pts) - 1
    check = mesh.check()
    assert check["ok"] and check["problems"] == [] and check["n_problems"] == 0
    assert sum(mesh.last_update().values()) > 0
    assert mesh.insert([np.nan] * dim) == "not_finite" and mesh.erase([np.nan] * dim) == "not_found"


def test_quadtree_mesh_matches_dynmesh_qmesh(tmp_path):
    pts = np.loadtxt(os.path.join(DATA, "dots.node"), skiprows=1)[:, 1:3]
    node = write_node(tmp_path / "p.node", pts)
    for kwargs, extra in (({}, []), ({"rho": 1.5}, ["--rho", "1.5"])):
        cli = cli_report(tmp_path, "qmesh", node, "-o", str(tmp_path / "out.node"), *extra)
        mesh = (dynmesh.DynOffCenterMesh2 if kwargs else dynmesh.DynQuadMesh2)(pts, **kwargs)
        points, simplices, inputs = mesh.mesh()
        assert (len(points), len(simplices)) == (cli["vertices"], cli["elements"])
        # The input points are kept bit for bit (in the tree's order).
        np.testing.assert_array_equal(np.unique(points[inputs], axis=0), np.unique(pts, axis=0))
        ele = np.loadtxt(str(tmp_path / "out.ele"), skiprows=1, dtype=np.int64)[:, 1:] - 1
        assert sorted(map(tuple, np.sort(ele, axis=1))) == sorted(map(tuple, np.sort(simplices, axis=1)))


def test_dynamic_mesh_arrays_outlive_the_mesh():
    rng = np.random.default_rng(2)
    mesh = dynmesh.DynQuadMesh2(rng.uniform(0, 1, (40, 2)))
    points, triangles, inputs = mesh.mesh()
    for a in (points, triangles, inputs):  # each owns the library's vector (a capsule), no copy
        assert not a.flags.owndata and type(a.base).__name__ == "PyCapsule"
    copies = points.copy(), triangles.copy(), inputs.copy()
    change = mesh.last_change()
    del mesh
    gc.collect()
    for a, b in zip((points, triangles, inputs), copies):
        np.testing.assert_array_equal(a, b)
    assert isinstance(change["added_simplices"], np.ndarray)
    with pytest.raises(ValueError, match="mode must be"):
        dynmesh.DynQuadMesh2(rng.uniform(0, 1, (4, 2)), mode="fast")
    with pytest.raises(ValueError, match="origin and width"):
        dynmesh.DynQuadMesh3()


# ---- probing and skins -------------------------------------------------------------------------

def test_probe_matches_dynmesh_probe(tmp_path):
    out = str(tmp_path / "p.off")
    cli = cli_report(tmp_path, "probe", "torus:1,0.4", "--eps", "0.035", "-o", out, "--check")
    sample, v, f, rep = dynmesh.probe("torus:1,0.4", eps=0.035, check=True)
    assert rep["check"]["ok"], rep["check"]["problems"]
    for key in ("probes", "insertions", "vertices", "facets", "euler", "components", "path_length"):
        assert rep[key] == cli[key], key
    assert rep["euler"] == 0 and len(sample) == len(v) == rep["vertices"]
    q = dynmesh.quality(v, f)
    assert q["closed"] and q["euler"] == 0
    # A closed mesh given by arrays (a polyhedron: eps_S is required): a sphere's mesh.
    _, sv, sf, _ = dynmesh.probe("sphere:1", eps=0.08)
    with pytest.raises(ValueError, match="eps_S"):
        dynmesh.probe(vertices=sv, faces=sf, eps=0.08)
    _, v2, f2, rep2 = dynmesh.probe(vertices=sv, faces=sf, eps=0.08, eps_S=0.9)
    assert rep2["euler"] == 2 and rep2["components"] == 1 and dynmesh.quality(v2, f2)["closed"]
    with pytest.raises(ValueError, match="exactly one of eps and delta"):
        dynmesh.probe("sphere:1")
    with pytest.raises(ValueError, match="planar curve"):
        dynmesh.probe("torus:1,0.4", eps=0.035, dim=2)
    with pytest.raises(ValueError, match="reach"):
        dynmesh.probe("sphere:1", eps=0.05, eps_S=2.0)
    _, points, polygons, rep2d = dynmesh.probe("circle2:1", eps=0.05, dim=2)
    assert len(polygons) == 1 and rep2d["components"] == 1 and len(polygons[0]) >= len(points)


def test_skin_matches_dynmesh_skin(tmp_path):
    molecule = os.path.join(SHARED, "molecules", "small02.pdb")
    centers, radii = dynmesh.read_molecule(molecule)
    xyzr = tmp_path / "m.xyzr"
    xyzr.write_text("".join("%r %r %r %r\n" % (*c, r) for c, r in zip(centers, radii)))
    cli = cli_report(tmp_path, "skin", str(xyzr), "-o", str(tmp_path / "s.off"))
    cli_pdb = cli_report(tmp_path, "skin", molecule, "-o", str(tmp_path / "s2.off"))
    assert cli_pdb["atoms"] == len(centers) and cli_pdb["vertices"] == cli["vertices"]
    v, f, rho, rep = dynmesh.skin(centers, radii)
    for key in ("atoms", "vertices", "triangles", "euler", "components", "expected_euler", "min_angle_deg"):
        assert rep[key] == pytest.approx(cli[key], rel=1e-12), key
    assert rep["check"]["ok"] and rho.shape == (len(v),) and (rho > 0).all()
    with pytest.raises(ValueError, match="one radius per centre"):
        dynmesh.skin(centers, radii[:-1])
    with pytest.raises(OSError, match="nothing.pdb"):
        dynmesh.read_molecule(str(tmp_path / "nothing.pdb"))


def test_grow_skin_matches_dynmesh_skin_grow(tmp_path):
    centers = np.array([[0, 0, 0], [2.2, 0, 0], [1, 1.8, 0]], dtype=float)
    radii = np.array([1.6, 1.5, 1.7])
    xyzr = tmp_path / "three.xyzr"
    xyzr.write_text("".join("%r %r %r %r\n" % (*c, r) for c, r in zip(centers, radii)))
    cli = cli_report(tmp_path, "skin", str(xyzr), "--grow", "--steps", "2", "-o", str(tmp_path / "g.off"))
    v, f, rho, rep = dynmesh.grow_skin(centers, radii, snapshots=2)
    assert rep["checks"] > 0 and rep["violations"] == 0
    for key in ("vertices", "triangles", "checks", "violations", "euler"):
        assert rep[key] == cli[key], key
    assert rep["actions"] == cli["actions"]
    for key in ("t_start", "t_end", "events", "checks_edge", "checks_triangle"):
        assert rep["growth"][key] == cli["growth"][key], key


def test_help_shows_signatures_and_docs():
    for fn, text in ((dynmesh.DeformingMesh.advance, "advance(self: dynmesh.DeformingMesh, t: int"),
                     (dynmesh.DynQuadMesh2.insert, "'inserted'"),
                     (dynmesh.probe, "eps_S: Optional[float] = None"),
                     (dynmesh.grow_skin, "relaxed scheduling"),
                     (dynmesh.quality, "dynmesh stats")):
        assert text in fn.__doc__, fn
