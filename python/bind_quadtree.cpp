// The dynamic quadtree meshes: DynQuadMesh2, DynQuadMesh3 (quality triangles / tetrahedra of a
// balanced tree) and DynOffCenterMesh2 (off-center Delaunay refinement), under insertions and
// deletions, with the current mesh and the last change.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "arrays.hpp"
#include "bindings.hpp"
#include "dict.hpp"
#include "dynmesh/error.hpp"
#include "dynmesh/quadtree/domain.hpp"
#include "dynmesh/quadtree/dyn_mesh.hpp"
#include "dynmesh/quadtree/dyn_offcenter.hpp"

namespace dynmesh::python {

namespace {

const char* name_of(InsertResult r) {
    switch (r) {
        case InsertResult::Inserted: return "inserted";
        case InsertResult::Duplicate: return "duplicate";
        case InsertResult::OutsideDomain: return "outside_domain";
        case InsertResult::NotFinite: return "not_finite";
        case InsertResult::BeyondPrecision: return "beyond_precision";
    }
    return "?";
}
const char* name_of(EraseResult r) { return r == EraseResult::Erased ? "erased" : "not_found"; }

/// A point argument; with finite = false a NaN or infinite coordinate is left for the
/// library to refuse (insert: 'not_finite'; erase: 'not_found').
template <int D>
PointD<D> point_of(const Doubles& a, const char* what = "p", bool finite = true) {
    if constexpr (D == 2)
        return point2_of(a, what, finite);
    else
        return point3_of(a, what, finite);
}

template <int D>
std::vector<PointD<D>> points_of(const Doubles& a) {
    if constexpr (D == 2)
        return points2_of(a, "points");
    else
        return points3_of(a, "points");
}

/// The box: [origin, origin + width]^D when both are given, else auto_domain() of the points
/// (the CLI's `--domain auto`).
template <int D>
QuadtreeOptions<D> domain_of(const std::vector<PointD<D>>& points, const std::optional<Doubles>& origin,
                             std::optional<double> width, const std::string& mode) {
    if (origin.has_value() != width.has_value()) throw InvalidInput("origin and width go together");
    if (!origin && points.empty())
        throw InvalidInput("without points, give the box: origin and width (the automatic box needs points)");
    QuadtreeOptions<D> o = origin ? QuadtreeOptions<D>{} : auto_domain<D>(points);
    if (origin) {
        o.origin = point_of<D>(*origin, "origin");
        o.width = *width;
        if (!(std::isfinite(o.width) && o.width > 0)) throw InvalidInput("width must be a positive number");
    }
    if (mode == "paper")
        o.mode = QuadtreeMode::Paper;
    else if (mode == "mesh")
        o.mode = QuadtreeMode::Mesh;
    else
        throw InvalidInput("mode must be 'paper' or 'mesh', not '" + mode + "'");
    return o;
}

/// The live mesh, slot by slot (ids as last_change() gives them): points (slots, D) and
/// simplices (slots, D + 1), -1 in the rows of free slots.
template <int D>
py::tuple live_arrays(const LiveMesh<D>& live) {
    Doubles points({py::ssize_t(live.vertex_slots()), py::ssize_t(D)});
    auto p = points.mutable_unchecked<2>();
    for (std::uint32_t v = 0; v < live.vertex_slots(); ++v)
        for (int k = 0; k < D; ++k) p(v, k) = live.has_vertex(v) ? live.point(v)[std::size_t(k)] : NAN;
    Indices simplices({py::ssize_t(live.simplex_slots()), py::ssize_t(D + 1)});
    auto s = simplices.mutable_unchecked<2>();
    for (std::uint32_t i = 0; i < live.simplex_slots(); ++i)
        for (int k = 0; k <= D; ++k) s(i, k) = live.has_simplex(i) ? std::int64_t(live.simplex(i)[std::size_t(k)]) : -1;
    return py::make_tuple(points, simplices);
}

template <int D>
py::dict change_dict(const MeshDelta<D>& delta) {
    std::vector<std::uint32_t> vid, sid;
    std::vector<PointD<D>> points;
    std::vector<std::array<std::uint32_t, D + 1>> simplices;
    for (const auto& a : delta.added_vertices) {
        vid.push_back(a.id);
        points.push_back(a.point);
    }
    for (const auto& a : delta.added_simplices) {
        sid.push_back(a.id);
        simplices.push_back(a.vertices);
    }
    py::dict d;
    d["removed_simplices"] = adopt_flat(std::vector<std::uint32_t>(delta.removed_simplices));
    d["removed_vertices"] = adopt_flat(std::vector<std::uint32_t>(delta.removed_vertices));
    d["added_vertex_ids"] = adopt_flat(std::move(vid));
    d["added_vertices"] = adopt<double, D>(std::move(points));
    d["added_simplex_ids"] = adopt_flat(std::move(sid));
    d["added_simplices"] = adopt<std::uint32_t, D + 1>(std::move(simplices));
    return d;
}

constexpr const char* kChangeDoc =
    "What the last insert() or erase() changed in current_mesh(): a dict of arrays\n"
    "removed_simplices, removed_vertices (ids), added_vertex_ids with added_vertices (points),\n"
    "added_simplex_ids with added_simplices (vertex ids, positively oriented).";
constexpr const char* kCurrentDoc =
    "The live mesh slot by slot, ids as last_change() uses them: (points (slots, D) with NaN\n"
    "rows for free slots, simplices (slots, D + 1) with -1 rows for free slots).";

/// The canonical mesh as arrays that adopt the library's vectors.
template <int D, std::size_t K>
py::tuple mesh_tuple(std::vector<PointD<D>>&& points, std::vector<std::array<std::uint32_t, K>>&& simplices,
                     std::vector<std::uint32_t>&& input_vertices) {
    return py::make_tuple(adopt<double, D>(std::move(points)), adopt<std::uint32_t, K>(std::move(simplices)),
                          adopt_flat(std::move(input_vertices)));
}

/// The methods every dynamic mesh has: insert, erase, current_mesh, last_change, check.
template <int D, class M>
void bind_updates(py::class_<M>& c) {
    c.def(
         "insert", [](M& m, const Doubles& p) { return name_of(m.insert(point_of<D>(p, "p", false))); }, py::arg("p"),
         "Inserts a point: 'inserted', 'duplicate', 'outside_domain', 'not_finite' or 'beyond_precision'.")
        .def(
            "erase", [](M& m, const Doubles& p) { return name_of(m.erase(point_of<D>(p, "p", false))); }, py::arg("p"),
            "Erases a point: 'erased' or 'not_found'.")
        .def("current_mesh", [](const M& m) { return live_arrays<D>(m.current_mesh()); }, kCurrentDoc)
        .def("last_change", [](const M& m) { return change_dict<D>(m.last_change()); }, kChangeDoc)
        .def(
            "check", [](const M& m) { return check_dict(m.check_invariants()); },
            "The invariants (for the quadtree meshes: balance, conformity, orientation; for the\n"
            "off-center mesh: Delaunay, the radius-edge bound), and the mesh equal to a fresh\n"
            "build's: a dict with ok, problems, n_problems and notes.");
}

template <int D>
void bind_quad_mesh(py::module_& m, const char* name, const char* doc) {
    using Q = DynQuadMesh<D>;
    py::class_<Q> c(m, name, doc);
    bind_updates<D>(c);
    c.def(py::init([](std::optional<Doubles> points, std::optional<Doubles> origin, std::optional<double> width,
                         const std::string& mode) {
                 const std::vector<PointD<D>> p = points ? points_of<D>(*points) : std::vector<PointD<D>>{};
                 const QuadtreeOptions<D> domain = domain_of<D>(p, origin, width, mode);
                 if (!points) return Q(domain);
                 py::gil_scoped_release unlocked;
                 return Q::build(p, domain);
             }),
             py::arg("points") = py::none(), py::arg("origin") = py::none(), py::arg("width") = py::none(),
             py::arg("mode") = "paper",
             "The domain is the box [origin, origin + width]^D (default: the automatic box of the\n"
             "points, as `dynmesh qmesh --domain auto`); points must lie in its middle third.\n"
             "mode: 'paper' (the paper's balanced tree) or 'mesh' (graded for quality meshing).\n"
             "points: built at once (the same mesh as inserting them one by one).")
        .def("__len__", &Q::size)
        .def(
            "mesh",
            [](const Q& q) {
                auto mesh = q.mesh();
                if constexpr (D == 2)
                    return mesh_tuple<2>(std::move(mesh.points), std::move(mesh.triangles), std::move(mesh.input_vertices));
                else
                    return mesh_tuple<3>(std::move(mesh.points), std::move(mesh.tets), std::move(mesh.input_vertices));
            },
            "The canonical mesh (identical after any sequence of updates to a fresh build):\n"
            "(points (k, D), simplices (m, D + 1), input_vertices: the vertex of each stored point).")
        .def(
            "last_update",
            [](const Q& q) {
                const auto& r = q.last_update();
                py::dict d;
                d["cells_split"] = r.tree.split.size();
                d["cells_merged"] = r.tree.merged.size();
                d["crowding_changes"] = r.tree.crowding_changes;
                d["support_updates"] = r.tree.support_updates;
                d["leaves_examined"] = r.leaves_examined;
                d["leaves_removed"] = r.leaves_removed;
                d["leaves_created"] = r.leaves_created;
                d["leaves_remeshed"] = r.leaves_remeshed;
                d["simplices_removed"] = r.simplices_removed;
                d["simplices_added"] = r.simplices_added;
                d["vertices_removed"] = r.vertices_removed;
                d["vertices_added"] = r.vertices_added;
                return d;
            },
            "The work of the last update (cells_split and cells_merged as in `dynmesh qmesh --report`).");
}

void bind_offcenter(py::module_& m) {
    using O = DynOffCenterMesh2;
    py::class_<O> c(m, "DynOffCenterMesh2",
                    "An off-center Delaunay mesh of a 2D point set (radius-edge ratio at most rho) kept\n"
                    "under insertions and deletions, identical to a fresh build after any sequence.");
    bind_updates<2>(c);
    c.def(py::init([](std::optional<Doubles> points, std::optional<Doubles> origin, std::optional<double> width,
                         double rho, bool use_offcenters) {
                 const std::vector<Vec2> p = points ? points2_of(*points, "points") : std::vector<Vec2>{};
                 const QuadtreeOptions<2> domain = domain_of<2>(p, origin, width, "paper");
                 const OffCenterOptions options{.rho = rho, .use_offcenters = use_offcenters};
                 py::gil_scoped_release unlocked;
                 return O::build(p, domain, options);
             }),
             py::arg("points") = py::none(), py::arg("origin") = py::none(), py::arg("width") = py::none(),
             py::arg("rho") = 1.5, py::arg("use_offcenters") = true,
             "The domain is the square [origin, origin + width]^2 (default: the automatic box of the\n"
             "points); points must lie in its middle third.\n"
             "rho: the radius-edge bound (> sqrt 2). use_offcenters=False: circumcentres only.")
        .def("__len__", [](const O& o) { return o.tree().size(); })
        .def(
            "mesh",
            [](const O& o) {
                OffCenterMesh2 mesh = o.mesh();
                return mesh_tuple<2>(std::move(mesh.points), std::move(mesh.triangles), std::move(mesh.input_vertices));
            },
            "The canonical mesh: (points (k, 2): the input points, then the Steiner points sorted,\n"
            "triangles (m, 3) counter-clockwise, input_vertices: the vertex of each stored point).")
        .def(
            "last_update",
            [](const O& o) {
                const OffCenterUpdateReport& r = o.last_update();
                py::dict d;
                d["steiner_added"] = r.steiner_added;
                d["steiner_removed"] = r.steiner_removed;
                d["simplices_added"] = r.simplices_added;
                d["simplices_removed"] = r.simplices_removed;
                d["evaluations"] = r.evaluations;
                d["rounds_visited"] = r.rounds_visited;
                d["queries"] = r.queries;
                return d;
            },
            "The work of the last update.");
}

}  // namespace

void bind_quadtree(py::module_& m) {
    bind_quad_mesh<2>(m, "DynQuadMesh2",
                      "A balanced quadtree and its quality triangle mesh under point insertions and deletions\n"
                      "(Acar & Hudson), O(lg L/s) per update, history independent.");
    bind_quad_mesh<3>(m, "DynQuadMesh3",
                      "A balanced octree and its quality tetrahedral mesh under point insertions and deletions\n"
                      "(Acar & Hudson), O(lg L/s) per update, history independent.");
    bind_offcenter(m);
}

}  // namespace dynmesh::python
