// OFF reader: "OFF", counts "nv nf [ne]", then one vertex per line and one face per line.

#include <limits>
#include <string>

#include "readers.hpp"

namespace dynmesh::detail {

namespace {

/// The next line with something besides blanks and a `#` comment (comment removed).
bool next_content_line(LineReader& lines, std::string_view& line) {
    while (lines.next(line)) {
        line = strip_comment(line);
        if (!Tokens(line).empty()) return true;
    }
    return false;
}

/// OFF with optional prefixes: ST (texture), C (colour), N (normal), 4 (4D), n (nD).
bool is_off_keyword(std::string_view w) {
    if (w.size() < 3 || w.substr(w.size() - 3) != "OFF") return false;
    for (char c : w.substr(0, w.size() - 3))
        if (std::string_view("STCN4n").find(c) == std::string_view::npos) return false;
    return true;
}

std::uint64_t parse_count(std::string_view token, const char* what, const FileContext& ctx,
                          std::size_t line) {
    std::int64_t n = 0;
    if (!parse_int(token, n))
        ctx.fail_line(line, std::string("invalid ") + what + " count " + quote_text(token));
    if (n < 0) ctx.fail_line(line, std::string("negative ") + what + " count " + quote_text(token));
    return static_cast<std::uint64_t>(n);
}

}  // namespace

TriangleSoup parse_off(std::string_view data, const FileContext& ctx) {
    if (data.empty()) ctx.fail("empty file");
    LineReader lines(data);
    std::string_view line;
    if (!next_content_line(lines, line)) ctx.fail("no content (only blanks and comments)");

    Tokens header(line);
    std::string_view word;
    header.next(word);
    if (!is_off_keyword(word))
        ctx.fail_line(lines.line_number(), "expected the keyword 'OFF', found " + quote_text(word));
    if (word.find_first_of("4n") != std::string_view::npos)
        ctx.fail_line(lines.line_number(),
                      "only 3D OFF files are supported, found " + quote_text(word));

    // The counts follow on the same line or on the next content line.
    std::string_view token;
    if (!header.next(token)) {
        if (!next_content_line(lines, line))
            ctx.fail_line(lines.line_number(),
                          "unexpected end of file: expected the vertex and face counts");
        header = Tokens(line);
        header.next(token);
    }
    const std::size_t count_line = lines.line_number();
    if (token == "BINARY") ctx.fail_line(count_line, "binary OFF files are not supported");
    const std::uint64_t nv = parse_count(token, "vertex", ctx, count_line);
    if (!header.next(token))
        ctx.fail_line(count_line, "expected the vertex and face counts, found only one number");
    const std::uint64_t nf = parse_count(token, "face", ctx, count_line);
    // A third number (the edge count) is optional and ignored.

    // Every vertex and face takes a line of at least 2 bytes: reject counts that cannot
    // fit before allocating anything (short lines are reported precisely further down).
    const std::uint64_t room = lines.remaining_bytes() + 1;  // the last line needs no '\n'
    if (!fits_in(nv, 2, room) || !fits_in(nf, 2, room - nv * 2))
        ctx.fail_line(count_line, "the header announces " + std::to_string(nv) + " vertices and " +
                                      std::to_string(nf) +
                                      " faces, which cannot fit in the remaining " +
                                      std::to_string(lines.remaining_bytes()) + " bytes");
    constexpr std::uint64_t kMaxIndex = std::numeric_limits<std::uint32_t>::max() - 1;
    if (nv > kMaxIndex || nf > kMaxIndex)
        ctx.fail_line(count_line, "more than 2^32 - 2 vertices or faces are not supported");
    if (nf == 0) ctx.fail_line(count_line, "the header announces no faces (not a surface)");

    TriangleSoup soup;
    soup.points.reserve(nv);
    for (std::uint64_t i = 0; i < nv; ++i) {
        if (!next_content_line(lines, line))
            ctx.fail_line(lines.line_number(),
                          "unexpected end of file: found " + std::to_string(i) + " of the " +
                              std::to_string(nv) + " vertices announced on line " +
                              std::to_string(count_line));
        Tokens tokens(line);
        soup.points.push_back(parse_point(tokens, ctx, lines.line_number(), "vertex", i));
        // Further values (normal, colour, texture coordinates) are ignored.
    }

    soup.triangles.reserve(nf);
    for (std::uint64_t i = 0; i < nf; ++i) {
        if (!next_content_line(lines, line))
            ctx.fail_line(lines.line_number(),
                          "unexpected end of file: found " + std::to_string(i) + " of the " +
                              std::to_string(nf) + " faces announced on line " +
                              std::to_string(count_line));
        const std::size_t ln = lines.line_number();
        const auto face = [i] { return "face " + std::to_string(i); };
        Tokens tokens(line);
        tokens.next(token);
        // A face starts with an integer count; a line of numbers starting with a fraction is a
        // vertex: the header announces fewer vertices than the file holds.
        if (std::int64_t first = 0; i == 0 && !parse_int(token, first)) {
            Tokens probe(line);
            std::string_view t;
            bool numeric = true;
            while (probe.next(t)) {
                double v = 0;
                numeric = numeric && parse_double(t, v);
            }
            if (numeric)
                ctx.fail_line(ln, "expected face 0 ('3 i j k'), found what looks like a vertex: "
                                  "does the header on line " + std::to_string(count_line) +
                                  " announce fewer than the file's vertices?");
        }
        std::int64_t k = 0;
        if (!parse_int(token, k) || k < 0)
            ctx.fail_line(ln, face() + ": invalid vertex count " + quote_text(token));
        if (k > 3)
            ctx.fail_line(ln, face() + " has " + std::to_string(k) +
                                  " vertices; only triangles are supported");
        if (k < 3)
            ctx.fail_line(ln, face() + " has " + std::to_string(k) + " vertices; a face needs 3" +
                                  (i == 0 ? " (or does the header on line " + std::to_string(count_line) +
                                                " announce fewer than the file's vertices?)"
                                          : std::string()));
        std::array<std::uint32_t, 3> tri{};
        for (std::size_t c = 0; c < 3; ++c) {
            if (!tokens.next(token))
                ctx.fail_line(ln,
                              face() + ": expected 3 vertex indices, found " + std::to_string(c));
            std::int64_t idx = 0;
            if (!parse_int(token, idx))
                ctx.fail_line(ln, face() + ": invalid vertex index " + quote_text(token));
            if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv)
                ctx.fail_line(ln, face() + ": vertex index " + std::to_string(idx) +
                                      " is out of range (the file has " + std::to_string(nv) +
                                      " vertices)");
            tri[c] = static_cast<std::uint32_t>(idx);
        }
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
            ctx.fail_line(ln, face() + " repeats a vertex (" + std::to_string(tri[0]) + " " +
                                  std::to_string(tri[1]) + " " + std::to_string(tri[2]) + ")");
        // Further values (a face colour) are ignored.
        soup.triangles.push_back(tri);
    }
    // A header that promises fewer elements than the file holds is an error, not a silent
    // truncation of the mesh.
    if (next_content_line(lines, line))
        ctx.fail_line(lines.line_number(),
                      "more data after the " + std::to_string(nf) + " faces announced on line " +
                          std::to_string(count_line) + " (is the face count in the header wrong?)");
    return soup;
}

}  // namespace dynmesh::detail
