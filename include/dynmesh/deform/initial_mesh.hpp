#pragma once
/// \file Tri(0) of a deforming mesh when a closed mesh of Sigma(0) is known (the input mesh
/// the samples come from; spec deforming-mesh.md §10.5): nothing is reconstructed, and the
/// result has the reference's topology.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

struct ReferenceMeshOptions {
    /// RefineVert's fixed point on the vertex set (DeformOptions::init_refine): see
    /// initial_mesh_on_reference().
    bool refine = true;
    std::size_t max_refine_rounds = 16;
    /// MeshRestrictedDelaunayOptions::max_rounds of each restricted Delaunay triangulation.
    std::size_t max_rdt_rounds = 16;
    /// Path A first, path B only when it fails: for a reference with locked edges (creases,
    /// kLockedEdges), which path A keeps as mesh edges (remove_point() collapses a vertex
    /// along its chain) and path B does not know.
    bool decimate_first = false;
    /// A local size per sample (same indexing as the samples; empty: none): in step 2 a
    /// sample joins when it is farther than min(R, size) / 3 from the vertices, so parts
    /// thinner than the global R are resolved on the reference, before any Add.
    std::span<const double> size;
};

enum class ReferenceMeshPath {
    RestrictedDelaunay,  ///< §10.5 B: restricted Delaunay triangulation on the reference
    Decimated            ///< §10.5 A: the reference with every other vertex removed
};
[[nodiscard]] std::string_view to_string(ReferenceMeshPath p);

struct ReferenceMesh {
    SurfaceMesh mesh;
    /// Sample index of each mesh vertex (vertex v is samples[vertex_sample[v.idx()]]).
    std::vector<std::uint32_t> vertex_sample;
    ReferenceMeshPath path = ReferenceMeshPath::RestrictedDelaunay;
    std::size_t added = 0;     ///< samples added to the net for the topology or the balls
    std::size_t promoted = 0;  ///< samples the refinement made vertices
    /// The failure of the path tried first (B, or A with decimate_first) when the other one
    /// was taken.
    std::string fallback_reason;
};

/// Tri(0) over the samples (each on the reference) from the net (indices into samples):
/// 1. B: restricted_delaunay_on_mesh(samples, net, reference) with diametric-ball refinement
///    and samples added for the balls kept R/3 away from the net.
/// 2. With options.refine, RefineVert's fixed point on the vertex set: every sample farther
///    than min(R, options.size)/3 from the vertices (R = largest circumradius) joins them, in index order, each
///    new one counting for the next, and step 1 is redone on the larger net; until at most
///    1 % more samples would join (those are left to RefineVert's Add). When the larger net has no triangulation with the reference's topology
///    (creases, parts thinner than the net spacing), the samples that would join within 3R of
///    the failure stay out (up to 4 tries per round; then the last mesh is kept).
/// 3. When step 1 finds no triangulation with the reference's topology, A: the reference
///    itself with every vertex removed (remove_point(), which keeps the topology) except the
///    net; reference vertices that are no sample go first. Needs the net's samples to be
///    reference vertices (same coordinates); a sample vertex that cannot be removed stays.
/// With options.decimate_first, A is tried before B. A keeps the reference's kLockedEdges
/// property: the result's locked edges join consecutive net vertices of each chain.
/// The result is a closed manifold with the reference's Euler characteristic and components.
/// Deterministic.
/// \throw InvalidInput when neither path works (B's reason, and A's: a reference vertex that
///        is no sample and cannot be removed, or net samples that are not reference vertices).
[[nodiscard]] ReferenceMesh initial_mesh_on_reference(std::span<const Point3> samples,
                                                      std::span<const std::uint32_t> net,
                                                      const SurfaceMesh& reference,
                                                      const ReferenceMeshOptions& options = {});

}  // namespace dynmesh
