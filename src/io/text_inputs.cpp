#include "dynmesh/io/text_inputs.hpp"

#include <cmath>
#include <string>

#include "dynmesh/error.hpp"
#include "dynmesh/io/input_file.hpp"
#include "io_common.hpp"

namespace dynmesh {

std::vector<std::uint32_t> read_vertex_list(const std::filesystem::path& path,
                                            std::size_t n_vertices) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    std::vector<std::uint32_t> out;
    detail::LineReader lines(data);
    std::string_view line, token;
    while (lines.next(line)) {
        detail::Tokens tokens(detail::strip_comment(line));
        while (tokens.next(token)) {
            const std::size_t ln = lines.line_number();
            std::int64_t v = 0;
            if (!detail::parse_int(token, v) || token.front() == '-' || token.front() == '+')
                ctx.fail_line(ln, "entry " + std::to_string(out.size() + 1) + " (" +
                                      detail::quote_text(token) +
                                      ") is not a vertex index (a non-negative integer)");
            if (static_cast<std::uint64_t>(v) >= n_vertices)
                ctx.fail_line(ln, "vertex " + std::to_string(v) +
                                      " does not exist (the mesh has " +
                                      std::to_string(n_vertices) + " vertices, numbered from 0)");
            out.push_back(static_cast<std::uint32_t>(v));
        }
    }
    if (out.empty()) ctx.fail("no vertex index in the file");
    return out;
}

std::vector<PointUpdate> read_update_script(const std::filesystem::path& path, int dimension) {
    DYNMESH_CHECK(dimension == 2 || dimension == 3,
                  "read_update_script: dimension must be 2 or 3, not " + std::to_string(dimension));
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    const std::string form = dimension == 2 ? "'+ x y' or '- x y'" : "'+ x y z' or '- x y z'";
    std::vector<PointUpdate> ops;
    detail::LineReader lines(data);
    std::string_view line, token;
    while (lines.next(line)) {
        const std::string_view body = detail::strip_comment(line);
        detail::Tokens tokens(body);
        if (!tokens.next(token)) continue;
        const std::size_t ln = lines.line_number();
        const auto malformed = [&] {
            ctx.fail_line(ln, "expected " + form + " (dimension " + std::to_string(dimension) +
                                  "), got " + detail::quote_text(body));
        };
        if (token != "+" && token != "-") malformed();
        PointUpdate op{.insert = token == "+", .point = {}, .line = ln};
        for (std::size_t k = 0; k < static_cast<std::size_t>(dimension); ++k) {
            if (!tokens.next(token)) malformed();
            double v = 0;
            if (!detail::parse_double(token, v))
                ctx.fail_line(ln, "not a number: " + detail::quote_text(token));
            if (!std::isfinite(v))
                ctx.fail_line(ln, "non-finite coordinate " + detail::quote_text(token));
            op.point[k] = v;
        }
        if (!tokens.empty()) malformed();
        ops.push_back(op);
    }
    return ops;
}

std::vector<NumberRow> read_four_number_rows(const std::filesystem::path& path, std::string_view layout,
                                             std::string_view what) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    std::vector<NumberRow> rows;
    detail::LineReader reader(data);
    std::string_view line, token;
    while (reader.next(line)) {
        const std::string_view body = detail::strip_comment(line);
        const auto bad = [&] {
            ctx.fail_line(reader.line_number(), "expected '" + std::string(layout) + "' (four finite numbers), got " +
                                                    detail::quote_text(body));
        };
        detail::Tokens tokens(body);
        NumberRow row;
        int k = 0;
        while (tokens.next(token)) {
            if (k == 4 || !detail::parse_double(token, row.v[k]) || !std::isfinite(row.v[k])) bad();
            ++k;
        }
        if (k == 0) continue;
        if (k != 4) bad();
        row.line = reader.line_number();
        rows.push_back(row);
    }
    if (rows.empty()) ctx.fail("no " + std::string(what) + " in the file");
    return rows;
}

}  // namespace dynmesh
