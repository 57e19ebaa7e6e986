// STL reader (ascii and binary). STL stores each facet's three corners separately; corners
// with bit-identical coordinates are welded into one vertex, in order of first appearance.

#include <bit>
#include <cmath>
#include <string>
#include <unordered_map>

#include "dynmesh/io/input_file.hpp"
#include "dynmesh/system/hash.hpp"
#include "readers.hpp"

namespace dynmesh::detail {

namespace {

/// Welds points with identical coordinates (-0 and +0 count as identical).
class Welder {
public:
    explicit Welder(TriangleSoup& soup, std::size_t expected_corners) : soup_(soup) {
        index_.reserve(expected_corners / 4 + 16);
    }
    std::uint32_t add(Point3 p) {
        p += Point3{0.0, 0.0, 0.0};  // -0 + 0 = +0
        const Key key{std::bit_cast<std::uint64_t>(p.x), std::bit_cast<std::uint64_t>(p.y),
                      std::bit_cast<std::uint64_t>(p.z)};
        const auto [it, inserted] =
            index_.try_emplace(key, static_cast<std::uint32_t>(soup_.points.size()));
        if (inserted) soup_.points.push_back(p);
        return it->second;
    }

private:
    struct Key {
        std::uint64_t x, y, z;
        bool operator==(const Key&) const = default;
    };
    struct KeyHash {
        std::size_t operator()(const Key& k) const noexcept {
            return static_cast<std::size_t>(hash_ints(k.x, k.y, k.z));
        }
    };
    TriangleSoup& soup_;
    std::unordered_map<Key, std::uint32_t, KeyHash> index_;
};

bool iequals(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        char c = a[i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != b[i]) return false;
    }
    return true;
}

bool starts_with_solid(std::string_view data) {
    data = skip_utf8_bom(data);
    std::size_t i = 0;
    while (i < data.size() && (is_blank(data[i]) || data[i] == '\n')) ++i;
    return data.size() - i >= 5 && iequals(data.substr(i, 5), "solid");
}

void add_triangle(TriangleSoup& soup, const std::array<std::uint32_t, 3>& tri, std::size_t facet,
                  const FileContext& ctx, std::size_t line_or_offset, bool binary) {
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) {
        const std::string msg = "facet " + std::to_string(facet) +
                                " is degenerate: two of its corners have identical coordinates";
        if (binary) ctx.fail_byte(line_or_offset, msg);
        ctx.fail_line(line_or_offset, msg);
    }
    soup.triangles.push_back(tri);
}

TriangleSoup parse_binary_stl(std::string_view data, std::uint32_t n, const FileContext& ctx) {
    if (n == 0) ctx.fail_byte(80, "the binary STL header announces no triangles");
    TriangleSoup soup;
    soup.triangles.reserve(n);
    Welder welder(soup, std::size_t{3} * n);
    const auto read_float = [&](std::size_t offset) {
        std::uint32_t bits = 0;
        std::memcpy(&bits, data.data() + offset, 4);
        if constexpr (std::endian::native == std::endian::big)
            bits =
                (bits >> 24) | ((bits >> 8) & 0xff00u) | ((bits << 8) & 0xff0000u) | (bits << 24);
        return static_cast<double>(std::bit_cast<float>(bits));
    };
    for (std::uint32_t t = 0; t < n; ++t) {
        const std::size_t base = 84 + std::size_t{50} * t;
        std::array<std::uint32_t, 3> tri{};
        for (std::size_t c = 0; c < 3; ++c) {
            const std::size_t offset = base + 12 + 12 * c;  // after the facet normal
            const Point3 p{read_float(offset), read_float(offset + 4), read_float(offset + 8)};
            if (!is_finite(p))
                ctx.fail_byte(offset, "triangle " + std::to_string(t) + " corner " +
                                          std::to_string(c) + " has a non-finite coordinate");
            tri[c] = welder.add(p);
        }
        add_triangle(soup, tri, t, ctx, base, /*binary=*/true);
    }
    return soup;
}

TriangleSoup parse_ascii_stl(std::string_view data, const FileContext& ctx) {
    enum class State { Outside, InSolid, InFacet, InLoop, AfterLoop };
    State state = State::Outside;
    TriangleSoup soup;
    Welder welder(soup, data.size() / 40);
    LineReader lines(data);
    std::string_view line, word, token;
    std::size_t facet = 0, facet_line = 0, corners = 0;
    std::array<std::uint32_t, 3> tri{};
    const auto expected = [&](const char* what) {
        ctx.fail_line(lines.line_number(),
                      std::string("expected ") + what + ", found " + quote_text(word));
    };
    while (lines.next(line)) {
        Tokens tokens(line);
        if (!tokens.next(word)) continue;
        const std::size_t ln = lines.line_number();
        switch (state) {
            case State::Outside:
                if (!iequals(word, "solid")) expected("'solid'");
                state = State::InSolid;
                break;
            case State::InSolid:
                if (iequals(word, "endsolid")) {
                    state = State::Outside;
                } else if (iequals(word, "facet")) {
                    state = State::InFacet;  // the facet normal is recomputed, never read
                    facet_line = ln;
                } else {
                    expected("'facet' or 'endsolid'");
                }
                break;
            case State::InFacet:
                if (!iequals(word, "outer") || !tokens.next(token) || !iequals(token, "loop"))
                    expected("'outer loop'");
                state = State::InLoop;
                corners = 0;
                break;
            case State::InLoop:
                if (iequals(word, "vertex")) {
                    if (corners == 3)
                        ctx.fail_line(ln, "facet " + std::to_string(facet) +
                                              " has more than 3 vertices; only triangles are "
                                              "supported");
                    const Point3 p = parse_point(tokens, ctx, ln, "facet", facet);
                    if (tokens.next(token))
                        ctx.fail_line(ln, "facet " + std::to_string(facet) + ": unexpected " +
                                              quote_text(token) +
                                              " after the 3 coordinates of a vertex");
                    tri[corners++] = welder.add(p);
                } else if (iequals(word, "endloop")) {
                    if (corners != 3)
                        ctx.fail_line(ln, "facet " + std::to_string(facet) + " has " +
                                              std::to_string(corners) +
                                              " vertices; a facet needs 3");
                    state = State::AfterLoop;
                } else {
                    expected("'vertex' or 'endloop'");
                }
                break;
            case State::AfterLoop:
                if (!iequals(word, "endfacet")) expected("'endfacet'");
                add_triangle(soup, tri, facet, ctx, facet_line, /*binary=*/false);
                ++facet;
                state = State::InSolid;
                break;
        }
    }
    if (state != State::Outside && state != State::InSolid)
        ctx.fail_line(lines.line_number(), "unexpected end of file inside facet " +
                                               std::to_string(facet) + " (started on line " +
                                               std::to_string(facet_line) + ")");
    if (soup.triangles.empty()) ctx.fail("no facets found");
    return soup;
}

}  // namespace

TriangleSoup parse_stl(std::string_view data, const FileContext& ctx) {
    if (data.empty()) ctx.fail("empty file");
    // Binary STL: 80-byte header, uint32 count, 50 bytes per triangle. Many binary files
    // also start with "solid", so the size decides first.
    if (data.size() >= 84) {
        std::uint32_t n = 0;
        std::memcpy(&n, data.data() + 80, 4);
        if constexpr (std::endian::native == std::endian::big)
            n = (n >> 24) | ((n >> 8) & 0xff00u) | ((n << 8) & 0xff0000u) | (n << 24);
        if (84 + std::uint64_t{50} * n == data.size()) return parse_binary_stl(data, n, ctx);
        if (!starts_with_solid(data))
            ctx.fail_byte(80, "binary STL header announces " + std::to_string(n) +
                                  " triangles, which needs " +
                                  std::to_string(84 + std::uint64_t{50} * n) +
                                  " bytes, but the file has " + std::to_string(data.size()));
    } else if (!starts_with_solid(data)) {
        ctx.fail("neither an ascii STL (no leading 'solid') nor a binary one (" +
                 std::to_string(data.size()) + " bytes, fewer than the 84-byte header)");
    }
    return parse_ascii_stl(data, ctx);
}

}  // namespace dynmesh::detail
