#pragma once
/// \file The metamorphoses of a growing skin (specs/skin-surfaces.md §3.3): the neighbourhood
/// of a critical point, the boundary loops of the mesh cut out of it, and the templates that
/// close them (two cones in the two-sheeted phase, a drum around a waist ring in the
/// one-sheeted one). Internal to grow_skin.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "dynmesh/mesh/surface_mesh.hpp"
#include "dynmesh/skin/critical_events.hpp"

namespace dynmesh {

/// One critical event and its surgery window.
struct Surgery {
    std::size_t simplex = 0;
    int dim = 0;
    Point3 z{};
    double W = 0;         ///< the event time
    double r = 0;         ///< the neighbourhood radius r_δ
    double t_on = 0;      ///< the skin enters B(z, δ_in·r) (births and deaths: when they act)
    double t_off = 0;     ///< the skin leaves it
    Vec3 axis{0, 0, 1};   ///< the quadric's axis: the edge (dim 1) or the triangle's normal (dim 2)
    Vec3 e1{1, 0, 0}, e2{0, 1, 0};  ///< completing an orthonormal frame
    bool active = false;     ///< a template is in the mesh
    bool cancelled = false;  ///< replaced by a remesh
    bool remesh_at_off = false;  ///< no template fitted (smaller than the floor): remeshed at t_off
    int remesh_attempts = 0;     ///< of that remesh (each one later)
};

[[nodiscard]] Surgery make_surgery(const SkinFunction& phi, const SkinEvent& ev, double inradius,
                                   double neighbourhood, double inner);

/// The boundary loops of the region `cut` (as vertex cycles in the direction the region's own
/// halfedges run): false when a vertex starts two boundary edges (the region is not a set of
/// discs and annuli with simple boundaries).
bool boundary_loops(const SurfaceMesh& mesh, const std::vector<Face>& cut, std::vector<std::vector<Vertex>>& loops);

struct TemplateVertex {
    bool is_new = false;
    std::uint32_t index = 0;  ///< into TemplatePlan::points when new
    Vertex vertex;            ///< a loop vertex otherwise
};

struct TemplatePlan {
    std::vector<Point3> points;  ///< the new vertices, on the skin at the template's time
    std::vector<std::array<TemplateVertex, 3>> triangles;
};

/// The template closing two loops around s.z at time `at`: in the two-sheeted phase each loop
/// is coned to its sheet's vertex on the axis, in the one-sheeted phase both are zipped by
/// angle to a ring on the waist circle. False when the loops are not on opposite sides of the
/// waist plane or do not wind around the axis.
bool plan_template(const Surgery& s, double at, const std::vector<std::vector<Vertex>>& loops,
                   const std::function<Point3(Vertex)>& position, TemplatePlan& plan);

}  // namespace dynmesh
