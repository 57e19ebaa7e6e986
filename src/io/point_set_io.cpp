#include "dynmesh/io/point_set_io.hpp"

#include <cmath>
#include <string>

#include "dynmesh/error.hpp"
#include "io_common.hpp"

namespace dynmesh {

namespace {

using detail::FileContext;
using detail::Tokens;

double parse_coordinate(std::string_view token, const FileContext& ctx, std::size_t ln, std::size_t i) {
    double v = 0;
    if (!detail::parse_double(token, v))
        ctx.fail_line(ln, "point " + std::to_string(i) + ": invalid coordinate " +
                              detail::quote_text(token));
    if (!std::isfinite(v))
        ctx.fail_line(ln, "point " + std::to_string(i) + ": non-finite coordinate " +
                              detail::quote_text(token));
    return v;
}

std::int64_t parse_header_int(Tokens& t, const FileContext& ctx, std::size_t ln, const char* what) {
    std::string_view token;
    std::int64_t v = 0;
    if (!t.next(token) || !detail::parse_int(token, v) || v < 0)
        ctx.fail_line(ln, std::string("header: expected a non-negative ") + what);
    return v;
}

PointSet read_node(const std::string& data, const FileContext& ctx) {
    detail::LineReader lines(data);
    std::string_view line, token;
    PointSet out;
    std::int64_t n = -1, dim = 0, nattr = 0, nmark = 0, first_id = -1;
    while (lines.next(line)) {
        Tokens t(detail::strip_comment(line));
        if (Tokens(t).empty()) continue;
        const std::size_t ln = lines.line_number();
        if (n < 0) {
            n = parse_header_int(t, ctx, ln, "point count");
            dim = parse_header_int(t, ctx, ln, "dimension");
            if (dim != 2 && dim != 3)
                ctx.fail_line(ln, "header: dimension " + std::to_string(dim) + " (only 2 and 3 are supported)");
            if (!Tokens(t).empty()) nattr = parse_header_int(t, ctx, ln, "attribute count");
            if (!Tokens(t).empty()) nmark = parse_header_int(t, ctx, ln, "boundary-marker flag");
            if (nmark > 1) ctx.fail_line(ln, "header: the boundary-marker flag must be 0 or 1");
            // Every point line needs at least 2 bytes per number.
            if (!detail::fits_in(static_cast<std::uint64_t>(n), 2 * (1 + dim), data.size()))
                ctx.fail_line(ln, "header: " + std::to_string(n) + " points cannot fit in the file");
            out.dimension = static_cast<int>(dim);
            out.points.reserve(static_cast<std::size_t>(n));
            out.lines.reserve(static_cast<std::size_t>(n));
            continue;
        }
        const std::size_t i = out.points.size();
        if (static_cast<std::int64_t>(i) >= n)
            ctx.fail_line(ln, "more point lines than the " + std::to_string(n) + " of the header");
        std::int64_t id = 0;
        if (!t.next(token) || !detail::parse_int(token, id))
            ctx.fail_line(ln, "point " + std::to_string(i) + ": invalid id " + detail::quote_text(token));
        if (first_id < 0) {
            if (id != 0 && id != 1) ctx.fail_line(ln, "the first point id must be 0 or 1, not " + std::to_string(id));
            first_id = id;
        }
        if (id != first_id + static_cast<std::int64_t>(i))
            ctx.fail_line(ln, "point ids must be consecutive: expected " +
                                  std::to_string(first_id + static_cast<std::int64_t>(i)) + ", found " +
                                  std::to_string(id));
        Point3 p;
        for (std::int64_t k = 0; k < dim; ++k) {
            if (!t.next(token)) ctx.fail_line(ln, "point " + std::to_string(i) + ": missing coordinate");
            p[static_cast<std::size_t>(k)] = parse_coordinate(token, ctx, ln, i);
        }
        std::int64_t extra = 0;
        while (t.next(token)) ++extra;
        if (extra != nattr + nmark)
            ctx.fail_line(ln, "point " + std::to_string(i) + ": expected " + std::to_string(nattr + nmark) +
                                  " attribute/marker values after the coordinates, found " +
                                  std::to_string(extra));
        out.points.push_back(p);
        out.lines.push_back(ln);
    }
    if (n < 0) ctx.fail("empty file (no header)");
    if (static_cast<std::int64_t>(out.points.size()) != n)
        ctx.fail("the header announces " + std::to_string(n) + " points but the file has " +
                 std::to_string(out.points.size()));
    if (out.points.empty()) ctx.fail("no points");
    return out;
}

PointSet read_plain(const std::string& data, const FileContext& ctx) {
    detail::LineReader lines(data);
    std::string_view line, token;
    PointSet out;
    int dim = 0;
    while (lines.next(line)) {
        Tokens t(detail::strip_comment(line));
        if (Tokens(t).empty()) continue;
        const std::size_t ln = lines.line_number(), i = out.points.size();
        Point3 p;
        int k = 0;
        while (t.next(token)) {
            if (k == 3) ctx.fail_line(ln, "point " + std::to_string(i) + ": more than 3 numbers");
            p[static_cast<std::size_t>(k++)] = parse_coordinate(token, ctx, ln, i);
        }
        if (k < 2) ctx.fail_line(ln, "point " + std::to_string(i) + ": fewer than 2 numbers");
        if (dim == 0) dim = k;
        if (k != dim)
            ctx.fail_line(ln, "point " + std::to_string(i) + " has " + std::to_string(k) +
                                  " coordinates but the first point has " + std::to_string(dim));
        out.points.push_back(p);
        out.lines.push_back(ln);
    }
    if (out.points.empty()) ctx.fail("no points found (only blanks and comments)");
    out.dimension = dim;
    return out;
}

}  // namespace

PointSet read_point_set(const std::filesystem::path& path) {
    const FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx);
    if (data.empty()) ctx.fail("empty file");
    return detail::lower_extension(path) == ".node" ? read_node(data, ctx) : read_plain(data, ctx);
}

void write_node_ele(const std::filesystem::path& base, const PointSet& ps,
                    std::span<const std::array<std::uint32_t, 4>> simplices) {
    DYNMESH_CHECK(ps.dimension == 2 || ps.dimension == 3, "write_node_ele: dimension must be 2 or 3");
    const std::size_t corners = static_cast<std::size_t>(ps.dimension) + 1;
    for (std::size_t i = 0; i < ps.points.size(); ++i)
        DYNMESH_CHECK(is_finite(ps.points[i]),
                      "write_node_ele: point " + std::to_string(i) + " has a non-finite coordinate");
    for (std::size_t s = 0; s < simplices.size(); ++s)
        for (std::size_t k = 0; k < corners; ++k)
            DYNMESH_CHECK(simplices[s][k] < ps.points.size(),
                          "write_node_ele: simplex " + std::to_string(s) + " uses a point index out of range");
    std::filesystem::path node = base, ele = base;
    node += ".node";
    ele += ".ele";
    detail::AtomicWriter nout(node);
    nout.put_number(std::uint64_t{ps.points.size()});
    nout.put(ps.dimension == 2 ? "  2  0  0\n" : "  3  0  0\n");
    for (std::size_t i = 0; i < ps.points.size(); ++i) {
        nout.put_number(std::uint64_t{i + 1});
        for (int k = 0; k < ps.dimension; ++k) {
            nout.put(' ');
            nout.put_number(ps.points[i][static_cast<std::size_t>(k)]);
        }
        nout.put('\n');
    }
    detail::AtomicWriter eout(ele);
    eout.put_number(std::uint64_t{simplices.size()});
    eout.put(ps.dimension == 2 ? "  3  0\n" : "  4  0\n");
    for (std::size_t s = 0; s < simplices.size(); ++s) {
        eout.put_number(std::uint64_t{s + 1});
        for (std::size_t k = 0; k < corners; ++k) {
            eout.put(' ');
            eout.put_number(std::uint64_t{simplices[s][k] + 1u});
        }
        eout.put('\n');
    }
    nout.commit();
    eout.commit();
}

}  // namespace dynmesh
