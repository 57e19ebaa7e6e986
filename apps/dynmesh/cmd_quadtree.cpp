/// `dynmesh qmesh` (alias `quadtree`): a balanced quadtree (2D) or octree (3D) over a point set,
/// updated by an insert/erase script, and the quality simplicial mesh derived from it
/// (shared/specs/dynamic-quadtree.md §1–§5), maintained through the script: triangles or
/// tetrahedra by DynQuadMesh, or, with --rho in 2D, the off-center mesh by DynOffCenterMesh2.
#include <algorithm>
#include <array>
#include <cctype>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_common.hpp"
#include "commands.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/io/input_file.hpp"
#include "dynmesh/io/mesh_io.hpp"
#include "dynmesh/io/point_set_io.hpp"
#include "dynmesh/io/simplex_mesh_io.hpp"
#include "dynmesh/io/text_inputs.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/quadtree/domain.hpp"
#include "dynmesh/quadtree/dyn_mesh.hpp"
#include "dynmesh/quadtree/dyn_offcenter.hpp"
#include "dynmesh/quadtree/oct_mesh.hpp"
#include "dynmesh/quadtree/offcenter.hpp"
#include "dynmesh/quadtree/quad_mesh.hpp"
#include "dynmesh/quadtree/quadtree.hpp"

namespace dynmesh::cli {

namespace {

struct QuadtreeArgs {
    CommonOptions common;
    std::string points, ops, output;
    std::string png;  ///< 2D: picture of the mesh before and after the ops
    std::string domain = "auto";
    int dim = 2;
    double rho = 0;  ///< with rho_given: the off-center mesh with this bound (2D only)
    const CLI::Option* rho_option = nullptr;
    bool check = false;
};

/// Output formats: the simplex-mesh formats (both dimensions) and, in 2D, the soup formats.
const std::vector<std::string> kSimplexExtensions = {".node", ".ele", ".off", ".vtu", ".mesh"};
const std::vector<std::string> kSoupExtensions2D = {".obj", ".ply", ".stl", ".vtk", ".vtp"};

template <int D>
struct Op {
    bool insert = true;
    PointD<D> p{};
    std::size_t line = 0;
};

template <int D>
std::string fmt_point(const PointD<D>& p) {
    std::string s = "(";
    for (std::size_t i = 0; i < static_cast<std::size_t>(D); ++i) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", p[i]);
        s += (i ? ", " : "") + std::string(buf);
    }
    return s + ")";
}

std::string fmt_double(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

/// The update script as operations on D-dimensional points.
template <int D>
std::vector<Op<D>> read_ops(const std::string& path) {
    std::vector<Op<D>> ops;
    for (const PointUpdate& u : read_update_script(path, D)) {
        Op<D> op{.insert = u.insert, .p = {}, .line = u.line};
        for (std::size_t k = 0; k < static_cast<std::size_t>(D); ++k) op.p[k] = u.point[k];
        ops.push_back(op);
    }
    return ops;
}

/// The grid unit W·2^-52 must be a normal double, and the box must be finite.
template <int D>
void check_domain_resolution(const QuadtreeOptions<D>& o, const std::string& what) {
    if (!std::isfinite(o.width))
        throw InvalidInput(what + ": the domain width overflows (the point spread is too large)");
    if (std::ldexp(o.width, -DynQuadtree<D>::kLevels) < DBL_MIN)
        throw InvalidInput(what + ": cell sizes underflow: the domain width " +
                           fmt_double(o.width) +
                           " is too small for the quadtree grid (needs >= 2^52 * DBL_MIN)");
    for (std::size_t i = 0; i < static_cast<std::size_t>(D); ++i)
        if (!std::isfinite(o.origin[i] + o.width))
            throw InvalidInput(what + ": the domain box overflows (coordinates too large)");
}

/// The domain box: explicit "X0,Y0,W" (2D) / "X0,Y0,Z0,W" (3D), or "auto": the library's
/// auto_domain_for_updates (quadtree/domain.hpp), a dyadic box snapped to a coarse grid,
/// chosen from the final point set of the run (the initial points with the script applied)
/// whenever every point the run ever holds fits in its middle third, so that an update run
/// and a from-scratch run on the final points write the same bytes.
template <int D>
QuadtreeOptions<D> choose_domain(const std::string& spec, const std::vector<PointD<D>>& pts,
                                 const std::vector<Op<D>>& ops, const std::string& points_file) {
    constexpr auto kD = static_cast<std::size_t>(D);
    QuadtreeOptions<D> o;
    if (spec != "auto") {
        const std::string form = D == 2 ? "X0,Y0,W" : "X0,Y0,Z0,W";
        const auto bad = [&] {
            return InvalidInput("--domain: expected 'auto' or '" + form +
                                "' with finite numbers and W > 0 (--dim " + std::to_string(D) +
                                "), got '" + spec + "'");
        };
        const std::optional<std::vector<double>> parsed = parse_number_list(spec);
        if (!parsed) throw bad();
        const std::vector<double>& v = *parsed;
        if (v.size() != kD + 1 || !(v[kD] > 0)) throw bad();
        for (std::size_t i = 0; i < kD; ++i) o.origin[i] = v[i];
        o.width = v[kD];
        check_domain_resolution<D>(o, "--domain " + spec);
        return o;
    }
    std::vector<PointD<D>> all = pts;
    std::map<std::array<double, kD>, std::size_t> present;  // coordinates -> count
    const auto key = [](const PointD<D>& p) {
        std::array<double, kD> k{};
        for (std::size_t i = 0; i < kD; ++i) k[i] = p[i];
        return k;
    };
    for (const PointD<D>& p : pts) ++present[key(p)];
    for (const Op<D>& op : ops) {
        if (op.insert) {
            all.push_back(op.p);
            ++present[key(op.p)];
        } else if (auto it = present.find(key(op.p)); it != present.end() && --it->second == 0) {
            present.erase(it);
        }
    }
    std::vector<PointD<D>> final_points;
    for (const auto& [k, count] : present) {
        PointD<D> p{};
        for (std::size_t i = 0; i < kD; ++i) p[i] = k[i];
        final_points.insert(final_points.end(), count, p);
    }
    try {
        return auto_domain_for_updates<D>(final_points, all);
    } catch (const InvalidInput& e) {
        throw InvalidInput(points_file + ": the automatic domain: " + e.what());
    }
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

std::string join(const std::vector<std::string>& v, const std::string& last = " or ") {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i)
        s += (i == 0 ? "" : (i + 1 == v.size() ? last : ", ")) + v[i];
    return s;
}

/// The mesh of either dimension, reduced to what the report, the checks and the writers need.
struct MeshResult {
    std::vector<Point3> points;
    std::vector<std::array<std::uint32_t, 4>> simplices;  // 2D: the 4th entry is unused (0)
    std::size_t mesh_leaves = 0;
    double min_angle = 0, max_angle = 0;  // 2D: triangle angles; 3D: dihedral angles
    std::vector<std::string> problems;    // filled only with --check
    nlohmann::json extra = nlohmann::json::object();
};

/// The 2D mesh: the maintained quadtree mesh, or (oc given) the off-center mesh.
MeshResult describe_mesh(QuadMesh2 mesh, const std::optional<OffCenterMesh2>& oc,
                         const QuadtreeArgs& a) {
    MeshResult r;
    if (oc) {
        mesh.origin = oc->origin;
        mesh.width = oc->width;
        mesh.points = oc->points;
        mesh.triangles = oc->triangles;
        mesh.input_vertices = oc->input_vertices;
    }
    const AngleRangeDeg angles = angle_range_deg(mesh);
    r.min_angle = angles.min;
    r.max_angle = angles.max;
    r.mesh_leaves = mesh.leaves;
    r.points.reserve(mesh.points.size());
    for (const Vec2& p : mesh.points) r.points.push_back({p.x, p.y, 0.0});
    r.simplices.reserve(mesh.triangles.size());
    for (const auto& t : mesh.triangles) r.simplices.push_back({t[0], t[1], t[2], 0});
    r.extra["min_angle_deg"] = angles.min;
    r.extra["max_angle_deg"] = angles.max;
    r.extra["mesher"] = oc ? "offcenter" : "quadtree";
    // The bound holds up to the slack of off-centers computed in double precision, which
    // grows as the shortest edge shrinks (offcenter.hpp, "Closed leaf").
    double promised = 0;
    if (oc) {
        OffCenterOptions o;
        o.rho = a.rho;
        promised = offcenter_promised_min_angle_deg(*oc, o);
        r.extra["rho"] = a.rho;
        r.extra["steiner"] = oc->steiner;
        r.extra["min_angle_bound_deg"] = offcenter_min_angle_deg(a.rho);
        r.extra["min_angle_promised_deg"] = promised;
    }
    if (a.check) {
        if (oc) {
            r.problems = check_offcenter_mesh(*oc).problems;
            if (angles.min < promised)
                r.problems.push_back("smallest angle " + fmt_double(angles.min) +
                                     " below the promised " + fmt_double(promised) +
                                     " degrees (the bound " +
                                     fmt_double(offcenter_min_angle_deg(a.rho)) +
                                     " less the rounding slack of the shortest edge)");
        } else {
            r.problems = check_quad_mesh(mesh).problems;
            if (angles.min < kQuadMeshMinAngleDeg - 1e-6 || angles.max > kQuadMeshMaxAngleDeg + 1e-6)
                r.problems.push_back("angles outside [" + std::to_string(kQuadMeshMinAngleDeg) +
                                     ", " + std::to_string(kQuadMeshMaxAngleDeg) + "] degrees");
        }
    }
    return r;
}

MeshResult describe_mesh(OctMesh3 mesh, const std::optional<OffCenterMesh2>& /*oc*/,
                         const QuadtreeArgs& a) {
    MeshResult r;
    const DihedralRangeDeg d = dihedral_range_deg(mesh);
    r.min_angle = d.min;
    r.max_angle = d.max;
    r.mesh_leaves = mesh.leaves;
    r.extra["min_dihedral_deg"] = d.min;
    r.extra["max_dihedral_deg"] = d.max;
    r.extra["mesher"] = "octree";
    if (a.check) {
        r.problems = check_oct_mesh(mesh).problems;
        if (d.min < kOctMeshMinDihedralDeg || d.max > kOctMeshMaxDihedralDeg)
            r.problems.push_back("dihedral angles [" + std::to_string(d.min) + ", " +
                                 std::to_string(d.max) + "] outside [" +
                                 std::to_string(kOctMeshMinDihedralDeg) + ", " +
                                 std::to_string(kOctMeshMaxDihedralDeg) + "] degrees");
    }
    r.points = std::move(mesh.points);
    r.simplices = std::move(mesh.tets);
    return r;
}

/// Draws the 2D meshes `before` and `after` side by side into `png` (a staging path) with
/// the bundled plot_mesh2d.py, from .node/.ele files in the run's scratch directory `scratch`.
/// \throw IoError naming --png and the cause if drawing fails or draws nothing.
void draw_before_after(const MeshResult& before, const MeshResult& after,
                       const std::filesystem::path& png, const std::filesystem::path& scratch,
                       const std::string& png_arg) {
    for (const auto& [name, m] : {std::pair{"before.node", &before}, {"after.node", &after}})
        (void)write_simplex_mesh(scratch / name, SimplexMeshView{.dimension = 2,
                                                                 .points = m->points,
                                                                 .simplices = m->simplices});
    run_plot_script("plot_mesh2d.py",
                    {png.string(), (scratch / "before.node").string(), (scratch / "after.node").string()},
                    "--png " + png_arg);
    std::string head;
    try {
        head = read_input_file(png, 1u << 30).substr(0, 8);
    } catch (const IoError&) {
    }
    if (head != "\x89PNG\r\n\x1a\n")
        throw IoError("--png " + png_arg + ": the plotting script wrote no PNG picture");
}

/// Where the run writes: the staging paths of -o (a .node/.ele pair shares one base) and --png.
struct QmeshOutputs {
    RunOutputs& set;
    std::filesystem::path mesh;  ///< the path to give the writer
    std::filesystem::path png;   ///< empty without --png
};

template <int D>
void run_dim(const QuadtreeArgs& a, const PointSet& input, bool offcenter, QmeshOutputs& out) {
    constexpr auto kD = static_cast<std::size_t>(D);
    const std::string ext = lower_extension(a.output);
    const bool simplex_out = contains(kSimplexExtensions, ext);
    const char* tree_name = D == 2 ? "quadtree" : "octree";

    Progress progress("qmesh", a.common.quiet);
    std::vector<PointD<D>> pts;
    pts.reserve(input.points.size());
    for (const Point3& p : input.points) {
        PointD<D> q{};
        for (std::size_t i = 0; i < kD; ++i) q[i] = p[i];
        pts.push_back(q);
    }
    const std::vector<Op<D>> ops = a.ops.empty() ? std::vector<Op<D>>{} : read_ops<D>(a.ops);
    const QuadtreeOptions<D> domain = choose_domain<D>(a.domain, pts, ops, a.points);
    const bool automatic = a.domain == "auto";
    const std::string outside =
        automatic ? " is outside the middle third of the automatic domain (its coordinates are "
                      "too large for the point spread: cell sizes underflow)"
                    : " is outside the middle third of the domain";
    const std::string quantum =
        " (after snapping to the grid quantum " +
        fmt_double(std::ldexp(domain.width, DynQuadtree<D>::kGuardBits - DynQuadtree<D>::kLevels)) +
        ")";

    OffCenterOptions oc_options;
    oc_options.rho = a.rho;
    const auto beyond_precision = [&]() -> std::string {
        const std::string cells = "so close to other points that its cells would fall below the "
                                  "coordinate resolution there (double precision)";
        if (!offcenter) return cells;
        const QuadtreeOptions<2> box{.origin = {domain.origin[0], domain.origin[1]},
                                     .width = domain.width};
        return "closer to a point than the off-center refinement resolves (" +
               fmt_double(offcenter_min_separation(box, oc_options)) +
               ", offcenter_min_separation), or " + cells;
    };

    // Validate the initial points with their line numbers before building anything.
    {
        const DynQuadtree<D> probe(domain);
        const std::vector<std::size_t>& lines = input.lines;
        const auto where = [&](std::size_t i) {
            return a.points + ":" + (i < lines.size() ? std::to_string(lines[i]) : "?") +
                   ": point " + fmt_point<D>(pts[i]);
        };
        std::set<typename DynQuadtree<D>::GridPoint> seen;
        for (std::size_t i = 0; i < pts.size(); ++i) {
            if (!is_finite(pts[i])) throw InvalidInput(where(i) + " is not finite");
            if (!probe.is_admissible(pts[i])) throw InvalidInput(where(i) + outside);
            if (!seen.insert(probe.grid_point(pts[i])).second)
                throw InvalidInput(where(i) + " duplicates an earlier point" + quantum);
        }
    }

    // Both meshers maintain their mesh through the updates: DynQuadMesh (quadtree postprocess)
    // or, with --rho in 2D, DynOffCenterMesh2 (off-center refinement).
    std::optional<DynQuadMesh<D>> dyn;
    std::optional<DynOffCenterMesh2> off;  // D == 2 only
    progress.stage(std::string("building the ") + tree_name + " and its mesh");
    auto t0 = std::chrono::steady_clock::now();
    try {
        if constexpr (D == 2) {
            if (offcenter) off.emplace(DynOffCenterMesh2::build(pts, domain, oc_options));
        }
        if (!offcenter) dyn.emplace(DynQuadMesh<D>::build(pts, domain));
    } catch (const InvalidInput& e) {
        // The library names the point by its index; the user knows it by its line.
        if (e.element >= input.lines.size()) throw InvalidInput(a.points + ": " + e.what());
        throw InvalidInput(a.points + ":" + std::to_string(input.lines[e.element]) + ": " +
                           e.what());
    }
    const double seconds_build = seconds_since(t0);
    const DynQuadtree<D>& tree = [&]() -> const DynQuadtree<D>& {
        if constexpr (D == 2)
            if (off) return off->tree();
        return dyn->tree();
    }();
    const auto insert = [&](const PointD<D>& p) {
        if constexpr (D == 2)
            if (off) return off->insert(p);
        return dyn->insert(p);
    };
    const auto erase = [&](const PointD<D>& p) {
        if constexpr (D == 2)
            if (off) return off->erase(p);
        return dyn->erase(p);
    };
    const auto current_offcenter = [&]() -> std::optional<OffCenterMesh2> {
        if constexpr (D == 2)
            if (off) return off->mesh();
        return std::nullopt;
    };

    std::optional<MeshResult> before;  // --png: the mesh before the update script
    if constexpr (D == 2)
        if (!a.png.empty()) {
            progress.stage("meshing the initial points for --png");
            before = describe_mesh(dyn ? dyn->mesh() : SimplexMeshD<D>{}, current_offcenter(), a);
        }

    progress.stage("applying " + std::to_string(ops.size()) + " updates");
    nlohmann::json op_times = nlohmann::json::array();
    double seconds_ops = 0;
    for (const Op<D>& op : ops) {
        const std::string where = a.ops + ":" + std::to_string(op.line) + ": ";
        t0 = std::chrono::steady_clock::now();
        if (op.insert) {
            switch (insert(op.p)) {
                case InsertResult::Inserted:
                    break;
                case InsertResult::Duplicate:
                    throw InvalidInput(where + "inserting " + fmt_point<D>(op.p) +
                                       ": a point with these coordinates is already present" +
                                       quantum);
                case InsertResult::OutsideDomain:
                    throw InvalidInput(where + "inserting " + fmt_point<D>(op.p) + ":" +
                                       outside.substr(3));
                case InsertResult::NotFinite:
                    throw InvalidInput(where + "inserting a non-finite point");
                case InsertResult::BeyondPrecision:
                    throw InvalidInput(where + "inserting " + fmt_point<D>(op.p) + ": " +
                                       beyond_precision());
            }
        } else if (erase(op.p) != EraseResult::Erased) {
            throw InvalidInput(where + "erasing " + fmt_point<D>(op.p) + ": no such point");
        }
        const double secs = seconds_since(t0);
        seconds_ops += secs;
        nlohmann::json entry = {{"op", op.insert ? "+" : "-"},
                                {"seconds", secs},
                                {"cells_split", tree.last_update().split.size()},
                                {"cells_merged", tree.last_update().merged.size()}};
        if (dyn) {
            const QuadMeshUpdateReport<D>& u = dyn->last_update();
            entry["leaves_examined"] = u.leaves_examined;
            entry["simplices_removed"] = u.simplices_removed;
            entry["simplices_added"] = u.simplices_added;
        }
        if constexpr (D == 2)
            if (off) {
                const OffCenterUpdateReport& u = off->last_update();
                entry["steiner_added"] = u.steiner_added;
                entry["steiner_removed"] = u.steiner_removed;
                entry["simplices_removed"] = u.simplices_removed;
                entry["simplices_added"] = u.simplices_added;
                entry["evaluations"] = u.evaluations;
            }
        // The change of the maintained mesh (MeshDelta: what a caller mirroring it applies).
        const auto record_delta = [&](const auto& delta) {
            entry["vertices_removed"] = delta.removed_vertices.size();
            entry["vertices_added"] = delta.added_vertices.size();
        };
        if constexpr (D == 2)
            if (off) record_delta(off->last_change());
        if (dyn) record_delta(dyn->last_change());
        op_times.push_back(std::move(entry));
    }

    progress.stage("meshing");
    t0 = std::chrono::steady_clock::now();
    MeshResult mesh = describe_mesh(dyn ? dyn->mesh() : SimplexMeshD<D>{}, current_offcenter(), a);
    const double seconds_mesh = seconds_since(t0);

    nlohmann::json origin = nlohmann::json::array();
    for (std::size_t i = 0; i < kD; ++i) origin.push_back(domain.origin[i]);
    nlohmann::json rep = {{"command", "qmesh"},
                          {"dim", D},
                          {"input", a.points},
                          {"output", a.output},
                          {"domain", {{"origin", origin}, {"width", domain.width}}},
                          {"points", tree.size()},
                          {"leaves", tree.leaf_count()},
                          {"mesh_leaves", mesh.mesh_leaves},
                          {"vertices", mesh.points.size()},
                          {"elements", mesh.simplices.size()},
                          {"seconds_build", seconds_build},
                          {"seconds_ops", seconds_ops},
                          {"seconds_mesh", seconds_mesh},
                          {"ops", op_times}};
    rep.update(mesh.extra);
    if (!a.ops.empty()) rep["ops_file"] = a.ops;
    std::vector<std::string> check_problems;
    if (a.check) {
        progress.stage("checking");
        // DynQuadMesh's check includes the tree's; DynOffCenterMesh2's does not.
        std::vector<std::string> bad = (dyn ? dyn->check_invariants() : tree.check_invariants()).problems;
        if constexpr (D == 2)
            if (off)
                for (std::string& e : off->check_invariants().problems) bad.push_back(std::move(e));
        for (std::string& s : mesh.problems) bad.push_back(std::move(s));
        rep["check"] = {{"violations", bad.size()}, {"problems", bad}};
        check_problems = std::move(bad);
    }

    if (before) {
        progress.stage("drawing " + a.png);
        draw_before_after(*before, mesh, out.png, out.set.scratch(a.png), a.png);
    }

    progress.stage("writing " + a.output);
    std::vector<std::string> written;
    if (simplex_out) {
        const SimplexMeshView view{.dimension = D, .points = mesh.points, .simplices = mesh.simplices};
        (void)write_simplex_mesh(out.mesh, view);
    } else {
        TriangleSoup soup;
        soup.points = mesh.points;
        soup.triangles.reserve(mesh.simplices.size());
        for (const auto& s : mesh.simplices) soup.triangles.push_back({s[0], s[1], s[2]});
        write_soup(soup, out.mesh);
    }
    out.set.report(rep);
    out.set.commit();
    if (ext == ".node" || ext == ".ele") {
        std::filesystem::path base = a.output;
        base.replace_extension();
        written = {base.string() + ".node", base.string() + ".ele"};
    } else {
        written = {a.output};
    }
    if (!a.png.empty()) written.push_back(a.png);
    std::cout << tree_name << ": " << tree.size() << " points, " << tree.leaf_count()
              << " leaves, " << ops.size() << " updates; " << (offcenter ? "off-center mesh " : "mesh ")
              << mesh.points.size()
              << " vertices, " << mesh.simplices.size()
              << (D == 2 ? " triangles, angles " : " tetrahedra, dihedral angles ")
              << mesh.min_angle << " .. " << mesh.max_angle << " deg\n  wrote " << join(written, " and ")
              << "\n";
    if (!check_problems.empty())
        throw CheckFailed(std::to_string(check_problems.size()) + " problems: " + check_problems.front());
}

void run_quadtree(const QuadtreeArgs& a, RunContext& ctx) {
    const bool offcenter = a.rho_option != nullptr && a.rho_option->count() > 0;
    if (offcenter && a.dim != 2) throw UsageError("--rho: the off-center mesher is 2D only (got --dim 3)");
    if (!a.png.empty()) {
        if (a.dim != 2) throw UsageError("--png: pictures are drawn for 2D meshes only (got --dim 3)");
        require_png_output(a.png, "plot_mesh2d.py");
    }
    const std::string ext = lower_extension(a.output);
    std::vector<std::string> allowed = kSimplexExtensions;
    if (a.dim == 2) allowed.insert(allowed.end(), kSoupExtensions2D.begin(), kSoupExtensions2D.end());
    if (!contains(allowed, ext))
        throw UsageError("-o " + a.output + ": unsupported extension for --dim " +
                         std::to_string(a.dim) + " (use " + join(allowed) + ")");
    RunOutputs set(a.common, {a.points, a.ops});
    QmeshOutputs out{set, {}, {}};
    if (ext == ".node" || ext == ".ele") {
        std::filesystem::path base = a.output;
        base.replace_extension();
        out.mesh = set.file_set(base, {".node", ".ele"}, "-o");
        out.mesh += ".node";
    } else {
        out.mesh = set.file(a.output, "-o");
    }
    if (!a.png.empty()) out.png = set.file(a.png, "--png");
    if (a.domain != "auto") {  // a malformed --domain is a usage error
        if (a.dim == 2)
            (void)choose_domain<2>(a.domain, {}, {}, a.points);
        else
            (void)choose_domain<3>(a.domain, {}, {}, a.points);
    }
    ctx.inputs_begin();

    const PointSet input = read_point_set(a.points);
    if (input.dimension != a.dim)
        throw InvalidInput(a.points + ": a " + std::to_string(input.dimension) +
                           "D point set, but --dim is " + std::to_string(a.dim));
    if (a.dim == 2)
        run_dim<2>(a, input, offcenter, out);
    else
        run_dim<3>(a, input, offcenter, out);
}

}  // namespace

void register_quadtree(CLI::App& root, int& result) {
    auto args = std::make_shared<QuadtreeArgs>();
    CLI::App* sub = root.add_subcommand(
        "qmesh",
        "Balanced quadtree (2D) or octree (3D) of a point set, updated by an insert/erase "
        "script, and its quality mesh with every point a vertex: triangles with angles in "
        "[18.43, 135] deg (or, with --rho, an off-center Delaunay mesh), tetrahedra with "
        "dihedral angles in [13.1, 164.3] deg");
    sub->add_option("points", args->points,
                    "Input points (.node, or 'x y' / 'x y z' per line), of dimension --dim")
        ->required();
    sub->add_option("-o,--output", args->output,
                    "Output mesh by extension: .node (writes OUT.node + OUT.ele, Triangle/TetGen), "
                    ".off (3D: the boundary surface), .vtu (VTK unstructured grid), .mesh "
                    "(Medit); 2D also .obj .ply .stl .vtk .vtp (z = 0)")
        ->required();
    sub->add_option("--ops", args->ops,
                    "Update script applied in order after the build: '+ x y [z]' inserts, "
                    "'- x y [z]' erases (# comments); each update is timed in the report");
    sub->add_option("--dim", args->dim, "Dimension: 2 (quadtree, triangles) or 3 (octree, "
                                        "tetrahedra)")
        ->check(CLI::IsMember({2, 3}))
        ->capture_default_str();
    args->rho_option =
        sub->add_option("--rho", args->rho,
                        "2D only: off-center (Har-Peled-Ungor) Delaunay mesh with radius-edge "
                        "ratio <= RHO (> sqrt(2); sqrt(2) ~ 20.7 deg) instead of the quadtree "
                        "postprocess, maintained through --ops like it")
            ->check(finite_number())
            ->check(CLI::Validator(
                [](std::string& v) {
                    return std::stod(v) > std::sqrt(2.0)
                               ? std::string()
                               : "rho must be > sqrt(2) ~ 1.41421356, got " + v;
                },
                "> sqrt(2)"));
    sub->add_option("--domain", args->domain,
                    "Domain box 'X0,Y0,W' (2D) or 'X0,Y0,Z0,W' (3D); every point must lie in "
                    "its middle third. Or 'auto': a power-of-two box about 6-12x the points' "
                    "extent, its origin snapped to a grid of W/8 so small changes do not move it, "
                    "chosen from the final points of --ops when every point fits (then an update "
                    "run and a from-scratch run on the final points write the same bytes). "
                    "Output is in input coordinates either way")
        ->capture_default_str();
    sub->add_option("--png", args->png,
                    "2D: also draw the mesh before and after the update script side by side "
                    "into this PNG (needs /usr/bin/python3 with matplotlib)");
    sub->add_flag("--check", args->check,
                  "Verify the tree invariants, the mesh (conforming, positively oriented, covers "
                  "the box) and the angle (2D) or dihedral-angle (3D) bounds");
    sub->alias("quadtree");
    add_common_options(*sub, args->common);
    sub->callback([args, &result] { result = guarded("qmesh", [&](RunContext& ctx) { run_quadtree(*args, ctx); }); });
}

}  // namespace dynmesh::cli
