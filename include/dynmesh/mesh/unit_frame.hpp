#pragma once
/// \file Running an algorithm on a mesh in the unit frame: positions scaled by an exact power
/// of two so that max|coordinate| lies in [1, 2), restored bit for bit afterwards.
///
/// Angle and ratio decisions are scale-invariant, and on scaled positions every square and
/// product an algorithm forms stays clear of overflow (coordinates near 1e308) and underflow
/// (subnormal coordinates near 1e-310). For a mesh of ordinary size the scaling is exact, so
/// every decision, and therefore the result, is bit-identical to running unscaled.

#include <vector>

#include "dynmesh/geometry/scaled_frame.hpp"
#include "dynmesh/mesh/surface_mesh.hpp"

namespace dynmesh {

class ScopedUnitFrame {
public:
    /// Scales `mesh`'s positions into the unit frame (a copy of the originals is kept).
    explicit ScopedUnitFrame(SurfaceMesh& mesh)
        : mesh_(mesh), scale_(ExactScale::to_unit(mesh.positions())) {
        if (scale_.exponent() == 0) return;
        original_ = mesh.positions();
        for (Point3& p : mesh.positions()) p = scale_.apply(p);
    }
    ScopedUnitFrame(const ScopedUnitFrame&) = delete;
    ScopedUnitFrame& operator=(const ScopedUnitFrame&) = delete;
    /// Restores the original positions (also when an exception is propagating). Positions are
    /// restored by index: the algorithm may flip, not add or remove vertices.
    ~ScopedUnitFrame() {
        if (scale_.exponent() == 0) return;
        std::vector<Point3>& pos = mesh_.positions();
        for (std::size_t i = 0; i < pos.size() && i < original_.size(); ++i) pos[i] = original_[i];
    }
    [[nodiscard]] const ExactScale& scale() const { return scale_; }

private:
    SurfaceMesh& mesh_;
    ExactScale scale_;
    std::vector<Point3> original_;
};

}  // namespace dynmesh
