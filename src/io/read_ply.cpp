// PLY reader: ascii, binary_little_endian and binary_big_endian. Keeps the positions of
// element `vertex` and the triangles of element `face` (list `vertex_indices` or
// `vertex_index`) or `tristrips` (list `vertex_indices`, -1 separated); skips the rest.

#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "readers.hpp"

namespace dynmesh::detail {

namespace {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

std::optional<PlyType> ply_type(std::string_view s) {
    if (s == "char" || s == "int8") return PlyType::Int8;
    if (s == "uchar" || s == "uint8") return PlyType::UInt8;
    if (s == "short" || s == "int16") return PlyType::Int16;
    if (s == "ushort" || s == "uint16") return PlyType::UInt16;
    if (s == "int" || s == "int32") return PlyType::Int32;
    if (s == "uint" || s == "uint32") return PlyType::UInt32;
    if (s == "float" || s == "float32") return PlyType::Float32;
    if (s == "double" || s == "float64") return PlyType::Float64;
    return std::nullopt;
}

constexpr std::size_t type_size(PlyType t) {
    switch (t) {
        case PlyType::Int8:
        case PlyType::UInt8:
            return 1;
        case PlyType::Int16:
        case PlyType::UInt16:
            return 2;
        case PlyType::Int32:
        case PlyType::UInt32:
        case PlyType::Float32:
            return 4;
        case PlyType::Float64:
            return 8;
    }
    return 0;
}

constexpr bool is_integral(PlyType t) { return t != PlyType::Float32 && t != PlyType::Float64; }

struct PlyProperty {
    std::string name;
    PlyType type = PlyType::Float32;  // the item type for a list
    bool is_list = false;
    PlyType count_type = PlyType::UInt8;
};

struct PlyElement {
    std::string name;
    std::uint64_t count = 0;
    std::size_t line = 0;  // header line declaring it
    std::vector<PlyProperty> properties;

    [[nodiscard]] std::optional<std::size_t> find(std::string_view prop) const {
        for (std::size_t i = 0; i < properties.size(); ++i)
            if (properties[i].name == prop) return i;
        return std::nullopt;
    }
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyHeader {
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    std::size_t body_offset = 0;  // first byte after the end_header line
    std::size_t body_line = 0;    // line number of that byte (ascii)
};

PlyHeader parse_header(std::string_view data, const FileContext& ctx) {
    PlyHeader h;
    LineReader lines(data);
    std::string_view line, word, token;
    if (!lines.next(line) || !Tokens(line).next(word) || word != "ply")
        ctx.fail_line(1, "not a PLY file: the first line must be 'ply'");
    bool has_format = false;
    while (true) {
        if (!lines.next(line)) ctx.fail("unexpected end of file: the header has no 'end_header'");
        const std::size_t ln = lines.line_number();
        Tokens tokens(line);
        if (!tokens.next(word)) continue;
        if (word == "end_header") break;
        if (word == "comment" || word == "obj_info") continue;
        if (word == "format") {
            if (!tokens.next(token)) ctx.fail_line(ln, "'format' without a format name");
            if (token == "ascii")
                h.format = PlyFormat::Ascii;
            else if (token == "binary_little_endian")
                h.format = PlyFormat::BinaryLittleEndian;
            else if (token == "binary_big_endian")
                h.format = PlyFormat::BinaryBigEndian;
            else
                ctx.fail_line(ln, "unknown PLY format " + quote_text(token) +
                                      " (expected ascii, binary_little_endian or "
                                      "binary_big_endian)");
            has_format = true;
        } else if (word == "element") {
            PlyElement e;
            std::string_view count_text;
            if (!tokens.next(token) || !tokens.next(count_text))
                ctx.fail_line(ln, "'element' needs a name and a count");
            std::int64_t count = 0;
            if (!parse_int(count_text, count) || count < 0)
                ctx.fail_line(ln, "element " + quote_text(token) + " has an invalid count " +
                                      quote_text(count_text));
            for (const auto& other : h.elements)
                if (other.name == token)
                    ctx.fail_line(ln, "element " + quote_text(token) + " is declared twice");
            e.name = std::string(token);
            e.count = static_cast<std::uint64_t>(count);
            e.line = ln;
            h.elements.push_back(std::move(e));
        } else if (word == "property") {
            if (h.elements.empty()) ctx.fail_line(ln, "'property' before any 'element'");
            PlyProperty p;
            if (!tokens.next(token)) ctx.fail_line(ln, "'property' without a type");
            if (token == "list") {
                std::string_view count_type, item_type;
                if (!tokens.next(count_type) || !tokens.next(item_type))
                    ctx.fail_line(ln, "'property list' needs a count type and an item type");
                const auto ct = ply_type(count_type), it = ply_type(item_type);
                if (!ct) ctx.fail_line(ln, "unknown PLY type " + quote_text(count_type));
                if (!it) ctx.fail_line(ln, "unknown PLY type " + quote_text(item_type));
                if (!is_integral(*ct))
                    ctx.fail_line(ln, "the count type of a list must be an integer type, not " +
                                          quote_text(count_type));
                p.is_list = true;
                p.count_type = *ct;
                p.type = *it;
            } else {
                const auto t = ply_type(token);
                if (!t) ctx.fail_line(ln, "unknown PLY type " + quote_text(token));
                p.type = *t;
            }
            if (!tokens.next(token)) ctx.fail_line(ln, "'property' without a name");
            p.name = std::string(token);
            if (h.elements.back().find(p.name))
                ctx.fail_line(ln, "property " + quote_text(p.name) + " of element " +
                                      quote_text(h.elements.back().name) + " is declared twice");
            h.elements.back().properties.push_back(std::move(p));
        } else {
            ctx.fail_line(ln, "unexpected " + quote_text(word) + " in the PLY header");
        }
    }
    if (!has_format) ctx.fail("the PLY header has no 'format' line");
    for (const auto& e : h.elements)
        if (e.properties.empty() && e.count > 0)
            ctx.fail_line(e.line, "element " + quote_text(e.name) + " has no properties");
    h.body_offset = lines.position();
    h.body_line = lines.line_number() + 1;
    return h;
}

/// Where a value is read: the element kind and its index, for messages.
struct Locus {
    const std::string* element;
    std::uint64_t index;
    [[nodiscard]] std::string str() const { return *element + " " + std::to_string(index); }
};

/// Values of an ascii body: blank- or newline-separated tokens.
class AsciiSource {
public:
    AsciiSource(std::string_view body, std::size_t first_line, const FileContext& ctx)
        : body_(body), line_(first_line), ctx_(ctx) {}

    [[noreturn]] void fail(const Locus& at, const std::string& msg) const {
        ctx_.fail_line(line_, at.str() + msg);
    }
    /// Whether `n` more values can possibly be in the file (each needs 2 bytes but the last).
    [[nodiscard]] bool can_hold(std::uint64_t n, PlyType) const {
        return fits_in(n, 2, body_.size() - pos_ + 1);
    }

    double read_real(PlyType, const Locus& at) {
        const std::string_view t = token(at);
        double v = 0;
        if (!parse_double(t, v)) fail(at, ": invalid number " + quote_text(t));
        if (!std::isfinite(v)) fail(at, " has a non-finite coordinate " + quote_text(t));
        return v;
    }
    std::int64_t read_integer(PlyType, const Locus& at) {
        const std::string_view t = token(at);
        std::int64_t v = 0;
        if (!parse_int(t, v)) fail(at, ": invalid integer " + quote_text(t));
        return v;
    }
    void skip(PlyType, const Locus& at) { (void)token(at); }
    /// Fails when anything but blanks follows the last element the header announced.
    void expect_end() {
        while (pos_ < body_.size() && (is_blank(body_[pos_]) || body_[pos_] == '\n')) {
            if (body_[pos_] == '\n') ++line_;
            ++pos_;
        }
        if (pos_ < body_.size())
            ctx_.fail_line(line_, "more data after the elements announced in the header "
                                  "(is an element count in the header wrong?)");
    }
    void skip_items(std::uint64_t n, PlyType type, const Locus& at) {
        for (std::uint64_t i = 0; i < n; ++i) skip(type, at);
    }

private:
    std::string_view token(const Locus& at) {
        while (pos_ < body_.size() && (is_blank(body_[pos_]) || body_[pos_] == '\n')) {
            if (body_[pos_] == '\n') ++line_;
            ++pos_;
        }
        if (pos_ == body_.size()) fail(at, ": unexpected end of file (truncated?)");
        const std::size_t start = pos_;
        while (pos_ < body_.size() && !is_blank(body_[pos_]) && body_[pos_] != '\n') ++pos_;
        return body_.substr(start, pos_ - start);
    }

    std::string_view body_;
    std::size_t pos_ = 0;
    std::size_t line_;
    const FileContext& ctx_;
};

/// Values of a binary body in either byte order.
class BinarySource {
public:
    BinarySource(std::string_view data, std::size_t offset, bool big_endian, const FileContext& ctx)
        : data_(data),
          pos_(offset),
          swap_(big_endian != (std::endian::native == std::endian::big)),
          ctx_(ctx) {}

    /// Reports a problem at the start of the value read last (or about to be read).
    [[noreturn]] void fail(const Locus& at, const std::string& msg) const {
        ctx_.fail_byte(value_start_, at.str() + msg);
    }
    [[nodiscard]] bool can_hold(std::uint64_t n, PlyType type) const {
        return fits_in(n, type_size(type), data_.size() - pos_);
    }

    double read_real(PlyType type, const Locus& at) {
        const double v = read(type, at);
        if (!std::isfinite(v)) fail(at, " has a non-finite coordinate");
        return v;
    }
    std::int64_t read_integer(PlyType type, const Locus& at) {
        // Only called for integer types (checked in the header), so the conversion is exact.
        return static_cast<std::int64_t>(read(type, at));
    }
    void skip(PlyType type, const Locus& at) { skip_items(1, type, at); }
    /// Fails when more than trailing white space follows the last element of the header.
    void expect_end() const {
        for (std::size_t i = pos_; i < data_.size(); ++i)
            if (!is_blank(data_[i]) && data_[i] != '\n')
                ctx_.fail_byte(pos_, std::to_string(data_.size() - pos_) +
                                         " bytes of data after the elements announced in the "
                                         "header (is an element count in the header wrong?)");
    }
    void skip_items(std::uint64_t n, PlyType type, const Locus& at) {
        value_start_ = pos_;
        if (!can_hold(n, type)) fail(at, ": unexpected end of file (truncated?)");
        pos_ += static_cast<std::size_t>(n * type_size(type));
    }

private:
    template <class T>
    T get() {
        unsigned char b[sizeof(T)];
        std::memcpy(b, data_.data() + pos_, sizeof(T));
        if (swap_)
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
        pos_ += sizeof(T);
        T v;
        std::memcpy(&v, b, sizeof(T));
        return v;
    }
    double read(PlyType type, const Locus& at) {
        value_start_ = pos_;
        if (data_.size() - pos_ < type_size(type))
            fail(at, ": unexpected end of file (truncated?)");
        switch (type) {
            case PlyType::Int8:
                return get<std::int8_t>();
            case PlyType::UInt8:
                return get<std::uint8_t>();
            case PlyType::Int16:
                return get<std::int16_t>();
            case PlyType::UInt16:
                return get<std::uint16_t>();
            case PlyType::Int32:
                return get<std::int32_t>();
            case PlyType::UInt32:
                return get<std::uint32_t>();
            case PlyType::Float32:
                return static_cast<double>(get<float>());
            case PlyType::Float64:
                return get<double>();
        }
        return 0;
    }

    std::string_view data_;
    std::size_t pos_;
    std::size_t value_start_ = 0;
    bool swap_;
    const FileContext& ctx_;
};

/// Which elements and properties hold the geometry.
struct PlyRoles {
    std::size_t vertex = 0;
    std::array<std::size_t, 3> xyz{};
    std::optional<std::size_t> face, face_list;
    std::optional<std::size_t> strips, strips_list;
};

PlyRoles find_roles(const PlyHeader& h, const FileContext& ctx) {
    PlyRoles r;
    std::optional<std::size_t> vertex;
    for (std::size_t i = 0; i < h.elements.size(); ++i) {
        const PlyElement& e = h.elements[i];
        if (e.name == "vertex") {
            vertex = i;
            for (std::size_t c = 0; c < 3; ++c) {
                const char* name = c == 0 ? "x" : (c == 1 ? "y" : "z");
                const auto p = e.find(name);
                if (!p || e.properties[*p].is_list)
                    ctx.fail_line(e.line, std::string("element 'vertex' has no scalar property '") +
                                              name + "'");
                r.xyz[c] = *p;
            }
        } else if (e.name == "face" || e.name == "tristrips") {
            auto p = e.find("vertex_indices");
            if (!p && e.name == "face") p = e.find("vertex_index");
            if (!p || !e.properties[*p].is_list)
                ctx.fail_line(e.line, "element " + quote_text(e.name) +
                                          " has no list property 'vertex_indices'");
            if (!is_integral(e.properties[*p].type))
                ctx.fail_line(e.line, "the vertex indices of element " + quote_text(e.name) +
                                          " must have an integer type");
            (e.name == "face" ? r.face : r.strips) = i;
            (e.name == "face" ? r.face_list : r.strips_list) = *p;
        }
    }
    if (!vertex) ctx.fail("the PLY header declares no 'vertex' element");
    r.vertex = *vertex;
    if (!r.face && !r.strips)
        ctx.fail("the PLY header declares neither a 'face' nor a 'tristrips' element");
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint32_t>::max() - 1;
    const PlyElement& v = h.elements[r.vertex];
    if (v.count > kMax) ctx.fail_line(v.line, "more than 2^32 - 2 vertices are not supported");
    if (r.face && h.elements[*r.face].count > kMax)
        ctx.fail_line(h.elements[*r.face].line, "more than 2^32 - 2 faces are not supported");
    return r;
}

/// Rejects headers whose elements cannot fit in the `room` bytes of the body, before
/// anything is allocated. A binary value takes at least its size, an ascii one 2 bytes
/// (a digit and a separator).
void check_sizes(const PlyHeader& h, std::uint64_t room, bool binary, const FileContext& ctx) {
    for (const PlyElement& e : h.elements) {
        std::uint64_t min_bytes = 0;  // per item
        for (const PlyProperty& p : e.properties)
            min_bytes += binary ? type_size(p.is_list ? p.count_type : p.type) : 2;
        if (!fits_in(e.count, min_bytes, room))
            ctx.fail_line(e.line, "element " + quote_text(e.name) + " announces " +
                                      std::to_string(e.count) + " items of at least " +
                                      std::to_string(min_bytes) +
                                      " bytes each, which cannot fit in the " +
                                      std::to_string(room) + " bytes left in the file");
        room -= e.count * min_bytes;
    }
}

std::string face_size_problem(std::int64_t n) {
    if (n > 3) return " has " + std::to_string(n) + " vertices; only triangles are supported";
    if (n >= 0) return " has " + std::to_string(n) + " vertices; a face needs 3";
    return ": invalid vertex count " + std::to_string(n);
}

template <class Source>
void read_body(Source& src, const PlyHeader& h, const PlyRoles& roles, TriangleSoup& soup) {
    const std::uint64_t nv = h.elements[roles.vertex].count;
    const auto check_index = [&](std::int64_t idx, const Locus& at) {
        if (idx < 0 || static_cast<std::uint64_t>(idx) >= nv)
            src.fail(at, ": vertex index " + std::to_string(idx) +
                             " is out of range (the file has " + std::to_string(nv) + " vertices)");
        return static_cast<std::uint32_t>(idx);
    };
    for (std::size_t ei = 0; ei < h.elements.size(); ++ei) {
        const PlyElement& e = h.elements[ei];
        const auto& props = e.properties;
        Locus at{&e.name, 0};
        if (ei == roles.vertex) soup.points.resize(e.count);
        if (ei == roles.face) soup.triangles.reserve(soup.triangles.size() + e.count);
        for (at.index = 0; at.index < e.count; ++at.index) {
            for (std::size_t pi = 0; pi < props.size(); ++pi) {
                const PlyProperty& p = props[pi];
                if (ei == roles.vertex && !p.is_list) {
                    if (pi == roles.xyz[0] || pi == roles.xyz[1] || pi == roles.xyz[2]) {
                        const std::size_t c = pi == roles.xyz[0] ? 0 : (pi == roles.xyz[1] ? 1 : 2);
                        soup.points[at.index][c] = src.read_real(p.type, at);
                    } else {
                        src.skip(p.type, at);
                    }
                    continue;
                }
                if (!p.is_list) {
                    src.skip(p.type, at);
                    continue;
                }
                const std::int64_t n = src.read_integer(p.count_type, at);
                const bool is_face = ei == roles.face && pi == roles.face_list;
                if (is_face && n != 3) src.fail(at, face_size_problem(n));
                if (n < 0) src.fail(at, ": negative list length " + std::to_string(n));
                if (!src.can_hold(static_cast<std::uint64_t>(n), p.type))
                    src.fail(at, ": a list of " + std::to_string(n) +
                                     " items cannot fit in the rest of the file");
                if (is_face) {
                    std::array<std::uint32_t, 3> tri{};
                    for (auto& v : tri) v = check_index(src.read_integer(p.type, at), at);
                    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
                        src.fail(at, " repeats a vertex (" + std::to_string(tri[0]) + " " +
                                         std::to_string(tri[1]) + " " + std::to_string(tri[2]) +
                                         ")");
                    soup.triangles.push_back(tri);
                } else if (ei == roles.strips && pi == roles.strips_list) {
                    // Strip triangle k is (s[k], s[k+1], s[k+2]) with the first two swapped
                    // for odd k, so all triangles share the orientation of the first one.
                    soup.triangles.reserve(soup.triangles.size() + static_cast<std::size_t>(n));
                    std::uint32_t a = 0, b = 0;
                    std::size_t k = 0;  // position in the current strip
                    for (std::int64_t j = 0; j < n; ++j) {
                        const std::int64_t idx = src.read_integer(p.type, at);
                        if (idx == -1) {
                            k = 0;
                            continue;
                        }
                        const std::uint32_t c = check_index(idx, at);
                        if (k >= 2) {
                            const bool odd = (k - 2) % 2 == 1;
                            if (a != b && b != c && a != c)
                                soup.triangles.push_back(odd ? std::array{b, a, c}
                                                             : std::array{a, b, c});
                        }
                        a = b;
                        b = c;
                        ++k;
                    }
                } else {
                    src.skip_items(static_cast<std::uint64_t>(n), p.type, at);
                }
            }
        }
    }
}

}  // namespace

TriangleSoup parse_ply(std::string_view data, const FileContext& ctx) {
    if (data.empty()) ctx.fail("empty file");
    const PlyHeader h = parse_header(data, ctx);
    const bool binary = h.format != PlyFormat::Ascii;
    const std::uint64_t body_size = data.size() - h.body_offset;
    check_sizes(h, binary ? body_size : body_size + 1, binary, ctx);  // +1: last value
    const PlyRoles roles = find_roles(h, ctx);
    TriangleSoup soup;
    if (binary) {
        BinarySource src(data, h.body_offset, h.format == PlyFormat::BinaryBigEndian, ctx);
        read_body(src, h, roles, soup);
        src.expect_end();
    } else {
        AsciiSource src(data.substr(h.body_offset), h.body_line, ctx);
        read_body(src, h, roles, soup);
        src.expect_end();
    }
    if (soup.triangles.empty()) ctx.fail("the file holds no triangle");
    return soup;
}

}  // namespace dynmesh::detail
