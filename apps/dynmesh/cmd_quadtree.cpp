/// `dynmesh quadtree`: a balanced quadtree over a point set, updated by an insert/erase script,
/// and the quality triangle mesh derived from it (shared/specs/dynamic-quadtree.md §1–§4).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/quadtree/offcenter.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::cli {

namespace {

struct QuadtreeArgs {
    CommonOptions common;
    std::string points, ops, output;
    std::string domain = "auto";
    int dim = 2;
    double rho = 0;  ///< 0: the quadtree postprocess; else the off-center mesh with this bound
    bool check = false;
};

struct Op {
    bool insert = true;
    Vec2 p;
    std::size_t line = 0;
};

std::string fmt_point(const Vec2& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x, p.y);
    return buf;
}

/// Text of a line with its `#` comment removed.
std::string strip_comment(const std::string& line) { return line.substr(0, line.find('#')); }
bool is_blank(const std::string& s) {
    return std::all_of(s.begin(), s.end(),
                       [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
}

/// 1-based line numbers of the point lines of a point file (as read_point_set reads it:
/// `#` comments and blank lines skipped, the `.node` header skipped).
std::vector<std::size_t> point_lines(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::size_t> out;
    std::string line;
    bool header = std::filesystem::path(path).extension() == ".node";
    for (std::size_t ln = 1; std::getline(in, line); ++ln) {
        if (is_blank(strip_comment(line))) continue;
        if (header) {
            header = false;
            continue;
        }
        out.push_back(ln);
    }
    return out;
}

/// Parses `+ x y` / `- x y` lines (`#` comments and blank lines ignored).
std::vector<Op> read_ops(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot open the ops file");
    std::vector<Op> ops;
    std::string line;
    for (std::size_t ln = 1; std::getline(in, line); ++ln) {
        const std::string body = strip_comment(line);
        if (is_blank(body)) continue;
        std::istringstream ss(body);
        std::string sign, xs, ys, extra;
        ss >> sign >> xs >> ys;
        const std::string where = path + ":" + std::to_string(ln) + ": ";
        if ((sign != "+" && sign != "-") || ys.empty() || (ss >> extra))
            throw IoError(where + "expected '+ x y' or '- x y', got '" + body + "'");
        Op op{.insert = sign == "+", .p = {}, .line = ln};
        for (int k = 0; k < 2; ++k) {
            const std::string& t = k == 0 ? xs : ys;
            std::size_t used = 0;
            double v = 0;
            try {
                v = std::stod(t, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != t.size()) throw IoError(where + "not a number: '" + t + "'");
            if (!std::isfinite(v)) throw IoError(where + "non-finite coordinate '" + t + "'");
            (k == 0 ? op.p.x : op.p.y) = v;
        }
        ops.push_back(op);
    }
    return ops;
}

/// The domain box: explicit "X0,Y0,W", or "auto": centred on the bounding box of the initial
/// points and every inserted point, of width 4 × its larger extent (1 if the extent is 0), so
/// that the box's middle third holds every point with a margin.
QuadtreeOptions<2> choose_domain(const std::string& spec, const std::vector<Vec2>& pts,
                                 const std::vector<Op>& ops) {
    QuadtreeOptions<2> o;
    if (spec != "auto") {
        std::array<double, 3> v{};
        std::istringstream ss(spec);
        char c1 = 0, c2 = 0;
        std::string rest;
        if (!(ss >> v[0] >> c1 >> v[1] >> c2 >> v[2]) || c1 != ',' || c2 != ',' || (ss >> rest) ||
            !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]) || !(v[2] > 0))
            throw InvalidInput("--domain: expected 'auto' or 'X0,Y0,W' with W > 0, got '" + spec +
                               "'");
        o.origin = {v[0], v[1]};
        o.width = v[2];
        return o;
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    const auto grow = [&](const Vec2& p) {
        for (std::size_t i = 0; i < 2; ++i) {
            lo[i] = std::min(lo[i], p[i]);
            hi[i] = std::max(hi[i], p[i]);
        }
    };
    for (const Vec2& p : pts) grow(p);
    for (const Op& op : ops)
        if (op.insert) grow(op.p);
    if (!(lo[0] <= hi[0])) return o;  // no points at all: the unit box
    double extent = std::max(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(extent > 0)) extent = 1.0;
    o.width = 4 * extent;
    o.origin = {0.5 * (lo[0] + hi[0]) - 0.5 * o.width, 0.5 * (lo[1] + hi[1]) - 0.5 * o.width};
    return o;
}

std::string lower_ext(const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
    return e;
}

void run_quadtree(const QuadtreeArgs& a) {
    DYNMESH_CHECK(a.dim == 2, "--dim: only 2 is supported by the quadtree mesher");
    const std::string ext = lower_ext(a.output);
    const bool node_out = ext == ".node";
    const auto writable = writable_mesh_extensions();
    if (!node_out && std::find(writable.begin(), writable.end(), ext) == writable.end())
        throw InvalidInput("-o " + a.output +
                           ": unsupported extension (use .node, .off, .obj, .ply, "
                           ".vtk or .vtp)");
    std::filesystem::path base = a.output;
    if (node_out) base.replace_extension();
    std::vector<std::string> outputs = {a.output};
    if (node_out) outputs.push_back(base.string() + ".ele");
    for (const std::string& out : outputs) {
        ensure_not_same_file(a.points, out);
        if (!a.ops.empty()) ensure_not_same_file(a.ops, out);
    }
    std::vector<std::string> files = outputs;
    files.push_back(a.points);
    files.push_back(a.ops);
    check_report_path(a.common, files);

    Progress progress("quadtree", a.common.quiet);
    progress.stage("reading " + a.points);
    const PointSet input = read_point_set(a.points);
    if (input.dimension != 2)
        throw InvalidInput(a.points + ": a " + std::to_string(input.dimension) +
                           "D point set (the quadtree mesher is 2D)");
    std::vector<Vec2> pts;
    pts.reserve(input.points.size());
    for (const Point3& p : input.points) pts.push_back({p.x, p.y});
    const std::vector<Op> ops = a.ops.empty() ? std::vector<Op>{} : read_ops(a.ops);
    const QuadtreeOptions<2> domain = choose_domain(a.domain, pts, ops);

    // Validate the initial points with their line numbers before building anything.
    {
        const DynQuadtree<2> probe(domain);
        const std::vector<std::size_t> lines = point_lines(a.points);
        const auto where = [&](std::size_t i) {
            return a.points + ":" + (i < lines.size() ? std::to_string(lines[i]) : "?") +
                   ": point " + fmt_point(pts[i]);
        };
        std::set<DynQuadtree<2>::GridPoint> seen;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (!probe.is_admissible(pts[i]))
                throw InvalidInput(where(i) + " is outside the middle third of the domain");
            if (!seen.insert(probe.grid_point(pts[i])).second)
                throw InvalidInput(where(i) + " duplicates an earlier point");
        }
    }

    progress.stage("building the quadtree");
    auto t0 = std::chrono::steady_clock::now();
    DynQuadtree<2> tree = DynQuadtree<2>::build(pts, domain);
    const double seconds_build = seconds_since(t0);

    progress.stage("applying " + std::to_string(ops.size()) + " updates");
    nlohmann::json op_times = nlohmann::json::array();
    double seconds_ops = 0;
    for (const Op& op : ops) {
        const std::string where = a.ops + ":" + std::to_string(op.line) + ": ";
        t0 = std::chrono::steady_clock::now();
        if (op.insert) {
            switch (tree.insert(op.p)) {
                case InsertResult::Inserted:
                    break;
                case InsertResult::Duplicate:
                    throw InvalidInput(where + "inserting " + fmt_point(op.p) +
                                       ": a point with these coordinates is already present");
                case InsertResult::OutsideDomain:
                    throw InvalidInput(where + "inserting " + fmt_point(op.p) +
                                       ": outside the middle third of the domain");
                case InsertResult::NotFinite:
                    throw InvalidInput(where + "inserting a non-finite point");
            }
        } else if (tree.erase(op.p) != EraseResult::Erased) {
            throw InvalidInput(where + "erasing " + fmt_point(op.p) + ": no such point");
        }
        const double secs = seconds_since(t0);
        seconds_ops += secs;
        op_times.push_back({{"op", op.insert ? "+" : "-"}, {"seconds", secs}});
    }

    progress.stage("meshing");
    t0 = std::chrono::steady_clock::now();
    QuadMesh2 mesh;
    std::optional<OffCenterMesh2> oc;
    if (a.rho > 0) {
        OffCenterOptions oo;
        oo.rho = a.rho;
        oc = offcenter_mesh(tree, oo);
        mesh.origin = oc->origin;
        mesh.width = oc->width;
        mesh.points = oc->points;
        mesh.triangles = oc->triangles;
        mesh.input_vertices = oc->input_vertices;
    } else {
        mesh = quad_mesh(tree);
    }
    const double seconds_mesh = seconds_since(t0);
    const AngleRangeDeg angles = angle_range_deg(mesh);

    nlohmann::json rep = {
        {"command", "qmesh"},
        {"input", a.points},
        {"output", a.output},
        {"domain", {{"origin", {domain.origin.x, domain.origin.y}}, {"width", domain.width}}},
        {"points", tree.size()},
        {"leaves", tree.leaf_count()},
        {"mesh_leaves", mesh.leaves},
        {"vertices", mesh.points.size()},
        {"elements", mesh.triangles.size()},
        {"min_angle_deg", angles.min},
        {"max_angle_deg", angles.max},
        {"seconds_build", seconds_build},
        {"seconds_ops", seconds_ops},
        {"seconds_mesh", seconds_mesh},
        {"ops", op_times}};
    if (!a.ops.empty()) rep["ops_file"] = a.ops;
    rep["mesher"] = oc ? "offcenter" : "quadtree";
    if (oc) {
        rep["rho"] = a.rho;
        rep["steiner"] = oc->steiner;
        rep["min_angle_bound_deg"] = offcenter_min_angle_deg(a.rho);
    }
    if (a.check) {
        progress.stage("checking");
        std::vector<std::string> bad = tree.check_invariants();
        if (oc) {
            for (std::string& s : check_offcenter_mesh(*oc)) bad.push_back(std::move(s));
            if (angles.min < offcenter_min_angle_deg(a.rho) - 1e-7)
                bad.push_back("smallest angle " + std::to_string(angles.min) + " below the bound " +
                              std::to_string(offcenter_min_angle_deg(a.rho)) + " degrees");
        } else {
            for (std::string& s : check_quad_mesh(mesh)) bad.push_back(std::move(s));
            if (angles.min < kQuadMeshMinAngleDeg - 1e-6 || angles.max > kQuadMeshMaxAngleDeg + 1e-6)
                bad.push_back("angles outside [" + std::to_string(kQuadMeshMinAngleDeg) + ", " +
                              std::to_string(kQuadMeshMaxAngleDeg) + "] degrees");
        }
        if (!bad.empty())
            throw InternalError("--check failed (" + std::to_string(bad.size()) +
                                " problems): " + bad.front());
        rep["check"] = {{"violations", 0}};
    }

    progress.stage("writing " + a.output);
    if (node_out) {
        PointSet ps;
        ps.dimension = 2;
        ps.points.reserve(mesh.points.size());
        for (const Vec2& p : mesh.points) ps.points.push_back({p.x, p.y, 0.0});
        std::vector<std::array<std::uint32_t, 4>> ele;
        ele.reserve(mesh.triangles.size());
        for (const auto& t : mesh.triangles) ele.push_back({t[0], t[1], t[2], 0});
        write_node_ele(base, ps, ele);
    } else {
        TriangleSoup soup;
        soup.points.reserve(mesh.points.size());
        for (const Vec2& p : mesh.points) soup.points.push_back({p.x, p.y, 0.0});
        soup.triangles = mesh.triangles;
        write_soup(soup, a.output);
    }
    write_report(a.common, rep);
    std::cout << "quadtree: " << tree.size() << " points, " << tree.leaf_count() << " leaves, "
              << ops.size() << " updates; mesh " << mesh.points.size() << " vertices, "
              << mesh.triangles.size() << " triangles, angles " << angles.min << " .. "
              << angles.max << " deg\n  wrote " << a.output
              << (node_out ? " and " + base.string() + ".ele" : std::string()) << "\n";
}

}  // namespace

void register_quadtree(CLI::App& root, int& result) {
    auto args = std::make_shared<QuadtreeArgs>();
    CLI::App* sub = root.add_subcommand(
        "qmesh",
        "Balanced quadtree of a 2D point set, updated by an insert/erase script, and its quality "
        "triangle mesh (every point a vertex, angles in [18.43, 135] deg)");
    sub->add_option("points", args->points, "Input points (.node, or 'x y' per line)")->required();
    sub->add_option("-o,--output", args->output,
                    "Output mesh: .node (writes .node + .ele) or .off .obj .ply .vtk .vtp (z = 0)")
        ->required();
    sub->add_option("--ops", args->ops,
                    "Update script applied in order after the build: '+ x y' inserts, '- x y' "
                    "erases (# comments)");
    sub->add_option("--dim", args->dim, "Dimension (only 2)")->capture_default_str();
    sub->add_option("--rho", args->rho,
                    "Off-center (Har-Peled-Ungor) Delaunay mesh with radius-edge ratio <= RHO (> sqrt(2); "
                    "sqrt(2) ~ 20.7 deg) instead of the quadtree postprocess")
        ->check(finite_number());
    sub->add_option("--domain", args->domain,
                    "Domain box 'X0,Y0,W' (every point must lie in its middle third), or 'auto': "
                    "centred on the bounding box of the points and all inserted points, 4x its "
                    "larger extent. Output is in input coordinates either way")
        ->capture_default_str();
    sub->add_flag("--check", args->check,
                  "Verify the tree invariants, the mesh (conforming, CCW, covers the box) and the "
                  "angle bounds");
    sub->alias("quadtree");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("qmesh", [&] { run_quadtree(*args); }); });
}

}  // namespace dynmesh::cli
