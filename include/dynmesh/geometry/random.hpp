#pragma once
/// \file A seeded random source whose output is the same on every platform.
///
/// std::mt19937_64 is specified bit for bit, but std::uniform_real_distribution is not, so
/// the mapping from raw integers to doubles is ours.

#include <cmath>
#include <cstdint>
#include <random>

#include "dynmesh/geometry/vec.hpp"

namespace dynmesh {

class Rng {
public:
    explicit Rng(std::uint64_t seed) : engine_(seed) {}
    /// Uniform in [0, 1), 53 random bits.
    double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    /// Uniform integer in [0, n), n > 0 (Lemire's multiply-shift; bias below 2^-64 n).
    std::uint64_t below(std::uint64_t n) {
        __extension__ using U128 = unsigned __int128;
        return static_cast<std::uint64_t>((static_cast<U128>(engine_()) * n) >> 64);
    }
    bool coin(double p = 0.5) { return uniform() < p; }
    /// Standard normal (Box-Muller).
    double normal() {
        double u1 = uniform();
        while (u1 <= 0.0) u1 = uniform();
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
    }
    /// Uniform on the unit sphere.
    Vec3 unit_vector() {
        const double z = uniform(-1.0, 1.0), t = uniform(0.0, 6.283185307179586);
        const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
        return {s * std::cos(t), s * std::sin(t), z};
    }
    std::mt19937_64& engine() { return engine_; }

private:
    std::mt19937_64 engine_;
};

}  // namespace dynmesh
