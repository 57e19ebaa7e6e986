#pragma once
/// \file Ancestor queries on the trees of free paths (spec §3.5): every active in-Ω node has a
/// parent `prev` (the node its certified segment came from) up to the top of its tree, whose
/// parent is on ∂Ω. Myers' skew-binary jump pointers find lowest common ancestors in O(log
/// depth) steps with one pointer per node, set once when the node is activated.
///
/// `Nodes` is any random-access container of records with the fields `prev`, `depth` and
/// `jump` (std::uint32_t); tops have depth 1 and jump to themselves.

#include <cstdint>
#include <utility>

namespace dynmesh::detail {

/// The jump pointer of a new child of the node p: p's jump's jump when the two jumps above p
/// span equal depths, else p itself (it depends on the depth only).
template <class Nodes>
[[nodiscard]] std::uint32_t skew_jump(const Nodes& nodes, std::uint32_t p) {
    const auto& P = nodes[p];
    const auto& J = nodes[P.jump];
    return P.depth - J.depth == J.depth - nodes[J.jump].depth ? J.jump : p;
}

/// The lowest common ancestor of two nodes of the same tree (a node is its own ancestor).
template <class Nodes>
[[nodiscard]] std::uint32_t lowest_common_ancestor(const Nodes& nodes, std::uint32_t a, std::uint32_t b) {
    if (nodes[a].depth < nodes[b].depth) std::swap(a, b);
    const auto d = nodes[b].depth;
    while (nodes[a].depth > d) a = nodes[nodes[a].jump].depth >= d ? nodes[a].jump : nodes[a].prev;
    while (a != b) {
        // At equal depths the jumps have equal depths: jump both while they differ.
        if (nodes[a].jump != nodes[b].jump) {
            a = nodes[a].jump;
            b = nodes[b].jump;
        } else {
            a = nodes[a].prev;
            b = nodes[b].prev;
        }
    }
    return a;
}

}  // namespace dynmesh::detail
