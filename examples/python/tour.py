"""A tour of dynmesh from Python (run from the repository root after scripts/demo or scripts/test)."""
import meshio
import numpy as np

import dynmesh

# A mesh read with meshio: its vertices and triangles are NumPy arrays.
m = meshio.read("examples/data/blobby.off")
v, f = m.points, m.cells_dict["triangle"]

# Worsen it by random edge flips, then flip it back to quality (the edge-flip paper's rule).
worse, report = dynmesh.worsen(v, f, rounds=5, seed=1)
print("worsen:", report)
better, report = dynmesh.flip(v, worse, criterion="angle")
print("flip:", report)
print("min angle: %.1f -> %.1f deg" % (dynmesh.quality(v, worse)["min_angle_deg"],
                                       dynmesh.quality(v, better)["min_angle_deg"]))

# Deform it: the samples (its vertices) stretch by 30% along x over 400 time units; the mesh
# follows, with flips, insertions and removals at the scheduled time steps.
lam = 0.3 * np.abs(v[:, 0]).max() / 400  # the most any point moves in one time unit
dm = dynmesh.DeformingMesh(v, lambda_=lam, reference_faces=better)
for t in range(1, 401):
    if dm.advance(t, v * [1 + 0.3 * t / 400, 1, 1])["update_due"]:
        update = dm.update()
print("last update:", update)
print("totals:", {k: dm.report[k] for k in ("updates", "flips", "insertions", "removals", "violations")})
vertices, faces, samples = dm.mesh()
check = dm.check()
print("deformed: %d vertices, %d triangles, invariants hold: %s" % (len(vertices), len(faces), check["ok"]))

# Mesh a point set dynamically: an off-center Delaunay mesh (radius-edge ratio <= 1.5) kept
# under insertions and deletions, each reporting what it changed.
rng = np.random.default_rng(7)
points = rng.uniform(0, 1, (200, 2))
mesh = dynmesh.DynOffCenterMesh2(points, rho=1.5)
for p in rng.uniform(0.2, 0.8, (20, 2)):
    mesh.insert(p)
mesh.erase(points[0])
change = mesh.last_change()
print("erase:", mesh.last_update(), "-", len(change["removed_simplices"]), "triangles out,",
      len(change["added_simplices"]), "in")
pts, triangles, inputs = mesh.mesh()
print("point set: %d points, %d vertices, %d triangles, check %s" % (len(mesh), len(pts), len(triangles),
                                                                      mesh.check()["ok"]))
assert check["ok"] and mesh.check()["ok"]
