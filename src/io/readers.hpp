#pragma once
/// \file Internal: the per-format parsers behind read_soup(). Each parses a whole file
/// already in memory and throws IoError through `ctx`; none of them accepts a soup without
/// triangles.

#include <string_view>

#include "dynmesh/mesh/soup.hpp"
#include "io_common.hpp"

namespace dynmesh::detail {

TriangleSoup parse_off(std::string_view data, const FileContext& ctx);
TriangleSoup parse_obj(std::string_view data, const FileContext& ctx);
TriangleSoup parse_ply(std::string_view data, const FileContext& ctx);
TriangleSoup parse_stl(std::string_view data, const FileContext& ctx);

}  // namespace dynmesh::detail
