#pragma once
/// \file The records a probing run keeps (private; specs/probing.md §3): what is known about
/// each directed Voronoi edge, stored in the Delaunay simplex at the edge's start, and the
/// Voronoi vertices (nodes), current and former.

#include <cstdint>
#include <limits>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh::detail {

inline constexpr std::uint32_t kNoNode = std::numeric_limits<std::uint32_t>::max();

/// What is known about a directed Voronoi edge, probed from its simplex's end (spec §3.1,
/// §10.1). `s` and `d` are the start and unit direction of the probe (or of the probe the
/// record was inferred from); for a hit, x = s + t d.
struct Record {
    enum State : std::uint8_t { Unprobed, Miss, Hit, OutsideOmega };
    State state = Unprobed;
    Point3 s{};
    Vec3 d{};
    Point3 x{};
    double t = 0;
    std::uint64_t stamp = 0;
};

/// The data of a Delaunay simplex: its node id and one record per facet.
template <int kFacets>
struct SimplexInfo {
    std::uint32_t node = kNoNode;
    Record rec[kFacets];
};

/// A Voronoi vertex, current or former (spec §3.2). A node is a *root* when it is infinite or
/// outside Ω: active from birth. An in-Ω node becomes active when a free path from ∂Ω reaches
/// it: the chain prev → prev → ... → a node whose prev is a root; `entry` is the start of the
/// free segment from prev (pos(prev), or the point where the edge from a root enters Ω).
struct Node {
    Point3 pos{};                   ///< circumcentre, frozen at creation (finite nodes)
    Point3 entry{};                 ///< start of the certified segment that reached this node
    double path_len = 0;            ///< length of the chain from top's entry on ∂Ω to pos
    std::uint32_t prev = kNoNode;   ///< self for roots; kNoNode while inactive
    std::uint32_t top = kNoNode;    ///< the chain's first in-Ω node (whose entry is on ∂Ω)
    std::uint32_t depth = 0;        ///< segments from ∂Ω along the chain
    /// An in-Ω ancestor (itself for a top): the skew-binary jump pointer that finds ancestors
    /// and lowest common ancestors in O(log depth) steps with one pointer per node.
    std::uint32_t jump = kNoNode;
    bool infinite = false;
    bool in_omega = false;
    bool alive = true;
    bool active = false;
    bool verified = false;  ///< its certified segment was checked against the ground truth
    [[nodiscard]] bool root() const { return infinite || !in_omega; }
};

/// A bad ball in the queue (spec §3.4): valid while the node is alive and its record still
/// carries `stamp`. Ordered by radius, then first pushed first (deterministic runs).
struct BallEntry {
    double r2;
    std::uint32_t node;
    int facet;
    std::uint64_t stamp;
    std::uint64_t seq;
    bool operator<(const BallEntry& o) const {
        if (r2 != o.r2) return r2 < o.r2;
        return seq > o.seq;
    }
};

}  // namespace dynmesh::detail
