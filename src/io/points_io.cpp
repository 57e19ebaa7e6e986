#include "dynmesh/io/points_io.hpp"

#include <cmath>
#include <string>

#include "dynmesh/error.hpp"
#include "io_common.hpp"

namespace dynmesh {

std::vector<Point3> read_points_xyz(const std::filesystem::path& path) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx);
    if (data.empty()) ctx.fail("empty file");
    std::vector<Point3> points;
    detail::LineReader lines(data);
    std::string_view line, token;
    while (lines.next(line)) {
        detail::Tokens tokens(detail::strip_comment(line));
        if (detail::Tokens(tokens).empty()) continue;
        const std::size_t ln = lines.line_number();
        const std::size_t i = points.size();
        points.push_back(detail::parse_point(tokens, ctx, ln, "point", i));
        // An optional normal: three more finite numbers, read and dropped.
        std::size_t extra = 0;
        while (tokens.next(token)) {
            double v = 0;
            if (!detail::parse_double(token, v) || !std::isfinite(v))
                ctx.fail_line(ln, "point " + std::to_string(i) + ": invalid normal component " +
                                      detail::quote_text(token) + " (expected a finite number)");
            ++extra;
        }
        if (extra != 0 && extra != 3)
            ctx.fail_line(ln, "point " + std::to_string(i) + ": expected 3 or 6 numbers, found " +
                                  std::to_string(3 + extra));
    }
    if (points.empty()) ctx.fail("no points found (only blanks and comments)");
    return points;
}

void write_points_xyz(std::span<const Point3> points, const std::filesystem::path& path) {
    for (std::size_t i = 0; i < points.size(); ++i)
        if (!is_finite(points[i]))
            throw InvalidInput("write_points_xyz: point " + std::to_string(i) +
                               " has a non-finite coordinate");
    detail::AtomicWriter out(path);
    for (const Point3& p : points) {
        out.put_number(p.x);
        out.put(' ');
        out.put_number(p.y);
        out.put(' ');
        out.put_number(p.z);
        out.put('\n');
    }
    out.commit();
}

}  // namespace dynmesh
