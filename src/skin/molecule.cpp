#include "dynmesh/skin/molecule.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>

#include "../io/io_common.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/input_file.hpp"
#include "dynmesh/io/text_inputs.hpp"

namespace dynmesh {

namespace {

std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

}  // namespace

// ---- radius table ---------------------------------------------------------------------------

RadiusTable RadiusTable::bondi() {
    RadiusTable t;
    for (const auto& [e, r] : {std::pair{"H", 1.20}, {"C", 1.70}, {"N", 1.55}, {"O", 1.52}, {"F", 1.47},
                               {"P", 1.80}, {"S", 1.80}, {"CL", 1.75}, {"BR", 1.85}, {"I", 1.98}})
        t.radii_[e] = r;
    return t;
}

void RadiusTable::set(std::string_view element, double radius) {
    DYNMESH_CHECK(!element.empty(), "RadiusTable::set: empty element symbol");
    DYNMESH_CHECK(std::isfinite(radius) && radius > 0, "RadiusTable::set: the radius must be positive");
    radii_[upper(element)] = radius;
}

bool RadiusTable::contains(std::string_view element) const { return radii_.count(upper(element)) != 0; }

double RadiusTable::radius(std::string_view element) const {
    const auto it = radii_.find(upper(element));
    return it == radii_.end() ? fallback_ : it->second;
}

RadiusTable RadiusTable::read_csv(const std::filesystem::path& path, double fallback) {
    DYNMESH_CHECK(std::isfinite(fallback) && fallback > 0, "RadiusTable::read_csv: the fallback radius must be positive");
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    const auto split = [](std::string_view s) {
        std::vector<std::string> cells;
        std::size_t start = 0;
        for (;;) {
            const std::size_t comma = s.find(',', start);
            std::string_view cell = s.substr(start, comma == std::string_view::npos ? s.npos : comma - start);
            while (!cell.empty() && detail::is_blank(cell.front())) cell.remove_prefix(1);
            while (!cell.empty() && detail::is_blank(cell.back())) cell.remove_suffix(1);
            cells.emplace_back(cell);
            if (comma == std::string_view::npos) return cells;
            start = comma + 1;
        }
    };
    RadiusTable t;
    t.fallback_ = fallback;
    detail::LineReader reader(data);
    std::string_view line;
    int symbol_col = -1, radius_col = -1;
    while (reader.next(line)) {
        const std::string_view body = detail::strip_comment(line);
        if (detail::Tokens(body).empty()) continue;
        const std::vector<std::string> cells = split(body);
        if (symbol_col < 0) {
            for (std::size_t i = 0; i < cells.size(); ++i) {
                if (upper(cells[i]) == "SYMBOL") symbol_col = int(i);
                if (upper(cells[i]) == "RADIUS") radius_col = int(i);
            }
            if (symbol_col < 0 || radius_col < 0)
                ctx.fail_line(reader.line_number(), "the header must name the columns 'symbol' and 'radius', got " +
                                                        detail::quote_text(body));
            continue;
        }
        const std::size_t need = std::size_t(std::max(symbol_col, radius_col)) + 1;
        double r = 0;
        if (cells.size() < need || cells[std::size_t(symbol_col)].empty() ||
            !detail::parse_double(cells[std::size_t(radius_col)], r) || !std::isfinite(r) || !(r > 0))
            ctx.fail_line(reader.line_number(), "expected a symbol and a positive radius, got " + detail::quote_text(body));
        const std::string e = upper(cells[std::size_t(symbol_col)]);
        if (!t.radii_.emplace(e, r).second)
            ctx.fail_line(reader.line_number(), "the element " + detail::quote_text(e) + " is listed twice");
    }
    if (symbol_col < 0) ctx.fail("no header line (symbol, radius)");
    if (t.radii_.empty()) ctx.fail("no radius in the table");
    return t;
}

// ---- readers --------------------------------------------------------------------------------

std::vector<Atom> read_xyzr(const std::filesystem::path& path) {
    const detail::FileContext ctx(path);
    std::vector<Atom> atoms;
    for (const NumberRow& row : read_four_number_rows(path, "x y z r", "atom")) {
        if (!(row.v[3] > 0)) ctx.fail_line(row.line, "the radius must be positive");
        atoms.push_back({{row.v[0], row.v[1], row.v[2]}, row.v[3], "", row.line});
    }
    return atoms;
}

std::vector<WeightedPoint> read_weighted_points(const std::filesystem::path& path) {
    std::vector<WeightedPoint> points;
    for (const NumberRow& row : read_four_number_rows(path, "x y z w", "weighted point"))
        points.push_back({{row.v[0], row.v[1], row.v[2]}, row.v[3]});
    return points;
}

std::vector<Atom> read_pqr(const std::filesystem::path& path) {
    const detail::FileContext ctx(path);
    const std::string data = detail::load_file(path, ctx, kMaxScriptFileBytes);
    std::vector<Atom> atoms;
    detail::LineReader reader(data);
    std::string_view line, token;
    while (reader.next(line)) {
        if (!line.starts_with("ATOM") && !line.starts_with("HETATM")) continue;
        std::vector<std::string_view> fields;
        detail::Tokens tokens(line);
        while (tokens.next(token)) fields.push_back(token);
        if (fields[0] != "ATOM" && fields[0] != "HETATM") continue;  // e.g. "ATOMS" in a remark
        if (fields.size() < 10)
            ctx.fail_line(reader.line_number(), "a PQR atom record needs 'ATOM serial name residue [chain] "
                                                "resSeq x y z charge radius', got " + detail::quote_text(line));
        double v[5];
        for (int k = 0; k < 5; ++k) {
            const std::string_view f = fields[fields.size() - 5 + std::size_t(k)];
            if (!detail::parse_double(f, v[k]) || !std::isfinite(v[k]))
                ctx.fail_line(reader.line_number(), std::string(k < 3 ? "the coordinate " : k == 3 ? "the charge " : "the radius ") +
                                                        detail::quote_text(f) + " is not a finite number");
        }
        if (!(v[4] > 0)) ctx.fail_line(reader.line_number(), "the radius must be positive");
        std::string_view name = fields[2];
        while (!name.empty() && std::isdigit(static_cast<unsigned char>(name.front()))) name.remove_prefix(1);
        std::string element;
        if (!name.empty() && std::isalpha(static_cast<unsigned char>(name.front()))) element = upper(name.substr(0, 1));
        atoms.push_back({{v[0], v[1], v[2]}, v[4], element, reader.line_number()});
    }
    if (atoms.empty()) ctx.fail("no ATOM or HETATM record in the file");
    return atoms;
}

std::vector<WeightedPoint> skin_weights(const std::vector<Atom>& atoms, double s) {
    DYNMESH_CHECK(std::isfinite(s) && s > 0 && s <= 1, "skin_weights: the shrink factor must be in (0, 1]");
    std::vector<WeightedPoint> out;
    out.reserve(atoms.size());
    for (const Atom& a : atoms) out.push_back({a.center, a.radius * a.radius / s});
    return out;
}

}  // namespace dynmesh
