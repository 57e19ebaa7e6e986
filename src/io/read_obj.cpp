// Wavefront OBJ reader: `v` and `f` statements; everything else is ignored.

#include <limits>
#include <string>

#include "readers.hpp"

namespace dynmesh::detail {

TriangleSoup parse_obj(std::string_view data, const FileContext& ctx) {
    if (data.empty()) ctx.fail("empty file");
    constexpr std::size_t kMaxVertices = std::numeric_limits<std::uint32_t>::max() - 1;
    TriangleSoup soup;
    LineReader lines(data);
    std::string_view line;
    std::string_view token;
    std::size_t first_face_line = 0;
    while (lines.next(line)) {
        Tokens tokens(strip_comment(line));
        if (!tokens.next(token)) continue;
        const std::size_t ln = lines.line_number();
        if (token == "v") {
            if (soup.points.size() >= kMaxVertices)
                ctx.fail_line(ln, "more than 2^32 - 2 vertices are not supported");
            // `v x y z [w]` or `v x y z r g b`: the extra values are ignored.
            soup.points.push_back(parse_point(tokens, ctx, ln, "vertex", soup.points.size()));
        } else if (token == "f") {
            const std::size_t i = soup.triangles.size();
            if (first_face_line == 0) first_face_line = ln;
            const auto face = [i] { return "face " + std::to_string(i); };
            const std::size_t nv = soup.points.size();
            std::array<std::uint32_t, 3> tri{};
            std::size_t k = 0;
            while (tokens.next(token)) {
                if (k < 3) {
                    // Corner forms a, a/b, a//c, a/b/c: only the vertex index matters.
                    const std::string_view index_text = token.substr(0, token.find('/'));
                    std::int64_t idx = 0;
                    if (!parse_int(index_text, idx) || idx == 0)
                        ctx.fail_line(ln,
                                      face() + ": invalid vertex reference " + quote_text(token));
                    // Positive indices are 1-based; negative ones count back from the last
                    // vertex defined so far.
                    const std::int64_t resolved =
                        idx > 0 ? idx - 1 : static_cast<std::int64_t>(nv) + idx;
                    if (resolved < 0 || static_cast<std::uint64_t>(resolved) >= nv)
                        ctx.fail_line(ln, face() + ": vertex reference " + quote_text(token) +
                                              " is out of range (" + std::to_string(nv) +
                                              " vertices are defined above this line)");
                    tri[k] = static_cast<std::uint32_t>(resolved);
                }
                ++k;
            }
            if (k > 3)
                ctx.fail_line(ln, face() + " has " + std::to_string(k) +
                                      " vertices; only triangles are supported");
            if (k < 3)
                ctx.fail_line(ln,
                              face() + " has " + std::to_string(k) + " vertices; a face needs 3");
            if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
                ctx.fail_line(ln, face() + " repeats a vertex (" + std::to_string(tri[0] + 1) +
                                      " " + std::to_string(tri[1] + 1) + " " +
                                      std::to_string(tri[2] + 1) + ", 1-based)");
            if (soup.triangles.size() >= kMaxVertices)
                ctx.fail_line(ln, "more than 2^32 - 2 faces are not supported");
            soup.triangles.push_back(tri);
        }
        // vt, vn, vp, l, p, o, g, s, usemtl, mtllib, ...: not geometry we keep.
    }
    if (soup.triangles.empty())
        ctx.fail("no faces ('f' lines) found; only triangle meshes are read");
    return soup;
}

}  // namespace dynmesh::detail
