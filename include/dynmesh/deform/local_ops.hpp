#pragma once
/// \file The two local mesh operations of the deforming-surface paper (Cheng & Dey, SODA 2008;
/// digest `specs/deforming-mesh.md`): Add(p, abc), which makes a sample a vertex (§4.4), and
/// Remove(v), which deletes a vertex and re-triangulates its link by a planar constrained
/// Delaunay triangulation (§4.7). Both finish with a local flip (§4.3) under the diametric rule.
///
/// Handles. Both operations work on meshes that hold deleted elements and never call
/// garbage_collection(), so every handle not named below stays a valid index. Flips keep edge
/// and face indices but re-wire them: after either operation, a kept Edge or Face handle may
/// join different vertices than before, so re-derive adjacency from the mesh.
/// - add_point(): no existing vertex moves; the new vertex, 3 edges and 2 faces are appended
///   (2 edges and 1 face when a boundary edge is split); `nearest` is reused as one of the
///   new triangles.
/// - remove_point(): v is deleted, as are the edges of its spokes and 2 of its k incident
///   faces; the other k - 2 face indices are reused for the new triangles and the k - 3
///   diagonals are new edges. Every other vertex keeps its index and position.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynmesh/flips/flip_rules.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {


// ---- Add(p, abc) -------------------------------------------------------------------------

/// Where the closest point p~ of the nearest triangle falls.
enum class AddCase {
    Interior,  ///< strictly inside: 1-to-3 face split
    Edge,      ///< on an edge (one barycentric coordinate < bary_tol): 2-to-4 edge split
    Vertex,    ///< at a corner (two coordinates < bary_tol): refused, mesh unchanged
    /// On a locked edge (kLockedEdges) that AddOptions::split_edge does not name: refused,
    /// mesh unchanged (near_vertex = the nearer end). Only a sample known to lie on the
    /// crease splits it.
    LockedEdge
};

struct AddOptions {
    double bary_tol = 1e-6;                ///< tau_bary of the digest (§5)
    FlipRule rule = FlipRule::DiametricBallNoFold;
    /// The final check looks for vertices within this many edge hops of p inside the
    /// diametric ball of one of p's triangles, and for p inside the balls of the other
    /// triangles around p's neighbours; violations re-seed the local flip with every edge
    /// within check_rings hops of p.
    std::size_t check_rings = 2;
    std::size_t max_repair_rounds = 4;  ///< re-seeded flip rounds before giving up
    /// Sharp-feature guard of every flip (FlipOptions::feature_angle_deg; 180 = off).
    double feature_angle_deg = 180.0;
    /// When valid: the Edge case on this edge whatever the barycentric coordinates (p~ is
    /// the point of the segment nearest to p, kept within its middle 80 %). For a sample
    /// known to lie on a crease, whose crease edge it must split; add_point()'s face
    /// argument then only has to be a valid face.
    Edge split_edge;
};

struct AddResult {
    Vertex vertex;                   ///< the new vertex (invalid for AddCase::Vertex)
    AddCase kind = AddCase::Interior;
    Vertex near_vertex;              ///< AddCase::Vertex: the existing vertex p~ falls on
    Point3 projected;                ///< p~, where the new vertex was created before moving
    double offset = 0;               ///< |p - p~|, the distance from p to `nearest`
    bool conditional_flip = false;   ///< the paper's single obtuse-angle flip happened
    std::size_t flips = 0;           ///< conditional + local flips
    std::size_t not_improving = 0;   ///< flips refused by the circumradius guard
    /// The final check found every diametric ball of p's triangles empty of the vertices
    /// within check_rings hops of p. Expected for dense, well-spaced samples (Theorem 4.1);
    /// false means the flips got stuck (refused by the circumradius guard, a degenerate quad,
    /// or an existing diagonal).
    bool balls_empty = false;
    /// Diagnostic, the digest's "v lies in no nearby diametric ball": how many triangles
    /// around p's neighbours (not incident to p) still hold p strictly inside their
    /// diametric ball. Can be > 0 on irregular samples where the circumradius guard refuses
    /// the flip that would remove it; the local flip tries, it is not a failure of Add.
    std::size_t nearby_balls_containing_p = 0;
};

/// Add(p, f) of §4.4. p~ = closest point of triangle `nearest` to p.
/// - Interior: split_face at p~; then for the old edges xy in the order ab, ca, bc: if the
///   angle x p~ y is obtuse and xy is flippable under options.rule, flip it and stop (at most
///   one flip).
/// - Edge: split_edge at p~ (put exactly on the edge), then the same test on the outer edges
///   of the new triangles (at most one flip). Both halves of a locked edge (kLockedEdges)
///   are locked.
/// - Vertex: nothing changes; returns kind = Vertex and near_vertex (the caller puts p in that
///   vertex's dormant list and raises its diagnostic).
/// Then the new vertex moves from p~ to p exactly (bit-identical coordinates), and the local
/// flip (flip_from seeded with the spokes and link edges of p) runs until the diametric balls
/// of p's triangles are empty (see AddResult::balls_empty).
/// \pre `nearest` is the mesh triangle nearest to p (the caller's search; not checked), and p
///      is well away from every vertex (§4.4).
/// \throw InvalidInput when `nearest` is invalid or deleted, or p is not finite.
AddResult add_point(SurfaceMesh& mesh, const Point3& p, Face nearest,
                    const AddOptions& options = {});

// ---- Remove(v) ---------------------------------------------------------------------------

struct RemoveOptions {
    FlipRule rule = FlipRule::DiametricBallNoFold;
    bool flip_after = true;             ///< run the local flip after re-triangulating
    std::size_t check_rings = 2;        ///< as AddOptions::check_rings, around the link
    std::size_t max_repair_rounds = 4;  ///< as AddOptions::max_repair_rounds
    double feature_angle_deg = 180.0;   ///< as AddOptions::feature_angle_deg
};

struct RemoveResult {
    bool removed = false;
    std::string reason;          ///< why not, when !removed
    std::vector<Vertex> link;    ///< neighbors(v) in counter-clockwise order (before removal)
    std::size_t planes_tried = 0;
    /// The plane that worked (unit normal of the incident triangle it came from) and the
    /// triangles of the link polygon's CDT in that plane, as indices into `link`,
    /// counter-clockwise seen from the normal side; as applied, before any local flip.
    Vec3 plane_normal;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::size_t flips = 0;
    std::size_t not_improving = 0;  ///< flips refused by the circumradius guard
    /// As AddResult::balls_empty, for the triangles incident to the link vertices and the
    /// vertices within check_rings hops of the link. Checked after the local flip, or right
    /// after the re-triangulation when flip_after is false.
    bool balls_empty = false;
};

/// Remove(v) of §4.7. Projects link(v) onto the plane of an incident triangle (first the one
/// whose normal is closest to the area-weighted star normal, then the others), requires a
/// simple polygon with the mesh's orientation, triangulates its interior with CGAL's
/// constrained Delaunay triangulation (exact predicates), and maps the triangles back to the
/// 3D link vertices; a plane whose triangulation uses an existing mesh edge as a diagonal is
/// rejected. Applies the first plane that works with SurfaceMesh::remove_vertex(v, tris), then
/// (options.flip_after) the local flip seeded with all edges among the link vertices.
/// Locked edges (kLockedEdges, e.g. creases): a vertex inside a chain of them (two locked
/// spokes a, b) is removed by collapsing it onto a or b instead, so that ab is a locked edge
/// afterwards (RemoveResult::triangles and plane_normal are then empty); a vertex where one
/// or more than two locked edges meet (a corner) is refused.
/// Refuses (removed = false, reason set, mesh unchanged) a boundary or isolated vertex, a
/// vertex whose removal would leave fewer than 4 vertices, a link that is not a simple cycle,
/// a tetrahedron's vertex, and the case where no plane works. Never throws for geometric
/// failure. Dormant lists are the caller's (the digest's UserDeletion / Decimation).
/// \throw InvalidInput when v is invalid or deleted.
RemoveResult remove_point(SurfaceMesh& mesh, Vertex v, const RemoveOptions& options = {});

}  // namespace dynmesh
