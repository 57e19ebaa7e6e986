#pragma once
/// \file The topology changes of a growing skin (specs/skin-surfaces.md §2.2, §8 correction 6):
/// with every weight growing by t, the mixed complex is fixed and simplex δ is critical when
/// its orthocentre lies in its own mixed cell (z_δ ∈ δ and z_δ ∈ ν_δ: the centred simplices of
/// the weighted alpha-complex filtration); the skin changes topology at t = W_δ.

#include <cstddef>
#include <vector>

#include "dynmesh/skin/skin_function.hpp"

namespace dynmesh {

struct SkinEvent {
    enum class Kind {
        Birth,        ///< dim 0: a sphere component appears at z
        Neck,         ///< dim 1: a neck forms (components merge or a handle appears)
        TunnelClose,  ///< dim 2: a tunnel closes (a handle disappears or a void splits off)
        Death,        ///< dim 3: a void shrinks to z and disappears
    };
    Kind kind = Kind::Birth;
    double time = 0;          ///< t = W_δ
    Point3 where{};           ///< z_δ
    std::size_t simplex = 0;  ///< index into SkinFunction::simplices()
};

/// The critical events of the input balls with t_min ≤ time ≤ t_max, sorted by time, then by
/// dimension, then by simplex index (deterministic). Simplices with a bounding point are left out.
[[nodiscard]] std::vector<SkinEvent> critical_events(const SkinFunction& phi, double t_min, double t_max = 0);

}  // namespace dynmesh
