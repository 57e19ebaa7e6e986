#pragma once
/// \file Typed index handles for mesh elements (a Face can never be passed as a Vertex).

#include <compare>
#include <cstdint>
#include <functional>
#include <limits>

namespace dynmesh {

template <class Tag>
class Handle {
public:
    constexpr Handle() = default;  ///< invalid
    constexpr explicit Handle(std::uint32_t i) : idx_(i) {}
    [[nodiscard]] constexpr std::uint32_t idx() const { return idx_; }
    [[nodiscard]] constexpr bool is_valid() const { return idx_ != kInvalid; }
    constexpr auto operator<=>(const Handle&) const = default;

    static constexpr std::uint32_t kInvalid = std::numeric_limits<std::uint32_t>::max();

private:
    std::uint32_t idx_ = kInvalid;
};

using Vertex = Handle<struct VertexTag>;
using Halfedge = Handle<struct HalfedgeTag>;  ///< twin is idx ^ 1, edge is idx / 2
using Edge = Handle<struct EdgeTag>;
using Face = Handle<struct FaceTag>;

}  // namespace dynmesh

template <class Tag>
struct std::hash<dynmesh::Handle<Tag>> {
    std::size_t operator()(const dynmesh::Handle<Tag>& h) const noexcept {
        return std::hash<std::uint32_t>()(h.idx());
    }
};
