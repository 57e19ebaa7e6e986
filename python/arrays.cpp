#include "arrays.hpp"

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/soup.hpp"
#include "dynmesh/system/parallel.hpp"

namespace dynmesh::python {

void require_shape(const py::array& a, const char* what, const char* rows, py::ssize_t cols) {
    if (a.ndim() == 2 && a.shape(1) == cols) return;
    throw InvalidInput(std::string(what) + " must be an array of shape (" + rows + ", " + std::to_string(cols) +
                       "), not of " + std::to_string(a.ndim()) + " dimension(s)" +
                       (a.ndim() == 2 ? " with " + std::to_string(a.shape(1)) + " columns" : ""));
}

namespace {

/// Rows per thread in the conversions below (at least; a million rows use up to three threads).
constexpr std::size_t kRowsPerPart = std::size_t(1) << 18;

template <class P, int D>
std::vector<P> points_of(const Doubles& a, const char* what, bool finite) {
    require_shape(a, what, "n", D);
    const auto n = std::size_t(a.shape(0));
    const double* in = a.data();
    std::vector<P> out;
    reserve_huge(out, n);
    out.resize(n);
    // Each part throws at its first bad point; the lowest part's error is the one rethrown.
    run_parts(parallel_parts(n, kRowsPerPart), n, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
            for (std::size_t k = 0; k < D; ++k) {
                const double x = in[D * i + k];
                if (finite && !std::isfinite(x))
                    throw InvalidInput(std::string(what) + ": point " + std::to_string(i) +
                                       " has a coordinate that is not finite");
                out[i][k] = x;
            }
        }
    });
    return out;
}

template <class P, int D>
P point_of(const Doubles& a, const char* what, bool finite) {
    if (a.ndim() != 1 || a.shape(0) != D)
        throw InvalidInput(std::string(what) + " must be a sequence of " + std::to_string(D) + " numbers");
    P p{};
    for (int k = 0; k < D; ++k) {
        p[std::size_t(k)] = a.at(k);
        if (finite && !std::isfinite(p[std::size_t(k)]))
            throw InvalidInput(std::string(what) + " has a coordinate that is not finite");
    }
    return p;
}

}  // namespace

std::vector<Point3> points3_of(const Doubles& a, const char* what, bool finite) {
    return points_of<Point3, 3>(a, what, finite);
}
std::vector<Vec2> points2_of(const Doubles& a, const char* what, bool finite) {
    return points_of<Vec2, 2>(a, what, finite);
}
Point3 point3_of(const Doubles& a, const char* what, bool finite) { return point_of<Point3, 3>(a, what, finite); }
Vec2 point2_of(const Doubles& a, const char* what, bool finite) { return point_of<Vec2, 2>(a, what, finite); }

Indices indices_of(const py::array& a, const char* what) {
    const char kind = a.dtype().kind();
    if (kind != 'i' && kind != 'u' && a.size() > 0)
        throw InvalidInput(std::string(what) + " must be an array of integers, not of dtype " +
                           std::string(py::str(a.dtype())));
    return Indices::ensure(a);
}

SurfaceMesh mesh_of(const Doubles& vertices, const py::array& faces) {
    return SurfaceMesh::from_soup(soup_of(points3_of(vertices, "vertices"), faces));
}

TriangleSoup soup_of(std::vector<Point3> points, const py::array& face_array) {
    TriangleSoup soup;
    soup.points = std::move(points);
    const Indices faces = indices_of(face_array, "faces");
    require_shape(faces, "faces", "m", 3);
    const auto m = std::size_t(faces.shape(0));
    const std::int64_t* in = faces.data();
    const auto n = std::int64_t(soup.points.size());
    reserve_huge(soup.triangles, m);
    soup.triangles.resize(m);
    run_parts(parallel_parts(m, kRowsPerPart), m, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
            for (std::size_t k = 0; k < 3; ++k) {
                const std::int64_t idx = in[3 * i + k];
                if (idx < 0 || idx >= n)
                    throw InvalidInput("face " + std::to_string(i) + " refers to vertex " + std::to_string(idx) +
                                       ", not in [0, " + std::to_string(n) + ")");
                soup.triangles[i][k] = std::uint32_t(idx);
            }
        }
    });
    return soup;
}

Indices faces_of(const SurfaceMesh& mesh) {
    if (mesh.has_garbage()) throw InternalError("faces_of: the mesh holds deleted elements");
    Indices faces({py::ssize_t(mesh.n_faces()), py::ssize_t(3)});
    std::int64_t* out = faces.mutable_data();
    const std::size_t m = mesh.n_faces();
    run_parts(parallel_parts(m, kRowsPerPart), m, [&](unsigned, std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
            const Halfedge h = mesh.halfedge(Face(std::uint32_t(i)));
            out[3 * i] = mesh.from_vertex(h).idx();
            out[3 * i + 1] = mesh.to_vertex(h).idx();
            out[3 * i + 2] = mesh.to_vertex(mesh.next(h)).idx();
        }
    });
    return faces;
}

Doubles vertices_of(const SurfaceMesh& mesh) {
    Doubles vertices({py::ssize_t(mesh.n_vertices()), py::ssize_t(3)});
    auto v = vertices.mutable_unchecked<2>();
    for (Vertex x : mesh.vertices()) {
        const Point3& p = mesh.position(x);
        v(x.idx(), 0) = p.x;
        v(x.idx(), 1) = p.y;
        v(x.idx(), 2) = p.z;
    }
    return vertices;
}

py::tuple compact_arrays_of(const SurfaceMesh& mesh, std::vector<Vertex>* kept) {
    std::vector<std::int64_t> index(mesh.vertices_size(), -1);
    Doubles vertices({py::ssize_t(mesh.n_vertices()), py::ssize_t(3)});
    auto v = vertices.mutable_unchecked<2>();
    py::ssize_t n = 0;
    if (kept) kept->clear();
    for (Vertex x : mesh.vertices()) {
        const Point3& p = mesh.position(x);
        v(n, 0) = p.x;
        v(n, 1) = p.y;
        v(n, 2) = p.z;
        index[x.idx()] = n++;
        if (kept) kept->push_back(x);
    }
    Indices faces({py::ssize_t(mesh.n_faces()), py::ssize_t(3)});
    auto f = faces.mutable_unchecked<2>();
    py::ssize_t m = 0;
    for (Face x : mesh.faces()) {
        const Halfedge h = mesh.halfedge(x);
        f(m, 0) = index[mesh.from_vertex(h).idx()];
        f(m, 1) = index[mesh.to_vertex(h).idx()];
        f(m, 2) = index[mesh.to_vertex(mesh.next(h)).idx()];
        ++m;
    }
    return py::make_tuple(vertices, faces);
}

}  // namespace dynmesh::python
