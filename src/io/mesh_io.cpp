// Reading side of mesh_io.hpp: format dispatch, read_mesh, ensure_not_same_file.

#include "dynmesh/io/mesh_io.hpp"

#include <system_error>

#include "dynmesh/error.hpp"
#include "io_common.hpp"
#include "readers.hpp"

namespace dynmesh {

namespace fs = std::filesystem;

namespace {

/// from_soup's messages start with "from_soup: "; after the file name that says nothing.
std::string without_function_prefix(const char* what) {
    const std::string_view s(what);
    constexpr std::string_view prefix = "from_soup: ";
    return std::string(s.starts_with(prefix) ? s.substr(prefix.size()) : s);
}

}  // namespace

std::vector<std::string> readable_mesh_extensions() { return {".off", ".obj", ".ply", ".stl"}; }

TriangleSoup read_soup(const fs::path& path) {
    const detail::FileContext ctx(path);
    const std::string ext = detail::lower_extension(path);
    using Parser = TriangleSoup (*)(std::string_view, const detail::FileContext&);
    Parser parse = nullptr;
    if (ext == ".off")
        parse = detail::parse_off;
    else if (ext == ".obj")
        parse = detail::parse_obj;
    else if (ext == ".ply")
        parse = detail::parse_ply;
    else if (ext == ".stl")
        parse = detail::parse_stl;
    else
        ctx.fail("unsupported extension " + detail::quote_text(ext) + " (meshes are read from " +
                 detail::join_list(readable_mesh_extensions()) + ")");
    const std::string data = detail::load_file(path, ctx);
    return parse(data, ctx);
}

SurfaceMesh read_mesh(const fs::path& path) {
    const TriangleSoup soup = read_soup(path);
    const detail::FileContext ctx(path);
    try {
        return SurfaceMesh::from_soup(soup);
    } catch (const TopologyError& e) {
        throw TopologyError(ctx.name() + ": " + without_function_prefix(e.what()));
    } catch (const InvalidInput& e) {
        ctx.fail(without_function_prefix(e.what()));
    }
}

void ensure_not_same_file(const fs::path& in, const fs::path& out) {
    std::error_code ec;
    if (!fs::exists(in, ec) || !fs::exists(out, ec)) return;
    const bool same = fs::equivalent(in, out, ec);
    if (!ec && same)
        throw IoError(detail::printable(out.string(), 400) +
                      ": refusing to overwrite the input file '" +
                      detail::printable(in.string(), 400) + "' (same file)");
}

}  // namespace dynmesh
