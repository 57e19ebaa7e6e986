// The largest of a growing array of values, kept under single-value changes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace dynmesh::detail {

/// The largest of the values x[0..n) under set(i, v): a complete binary tree of maxima over a
/// power-of-two number of leaves, O(log n) per set, O(1) per max(). Unset leaves are 0; an
/// index past the leaves doubles them (O(n) once per doubling).
class MaxTree {
public:
    /// The tree over `values` (copied), in O(n).
    void assign(const std::vector<double>& values) {
        leaves_ = 1;
        while (leaves_ < values.size()) leaves_ *= 2;
        t_.assign(2 * leaves_, 0.0);
        std::copy(values.begin(), values.end(), t_.begin() + static_cast<std::ptrdiff_t>(leaves_));
        for (std::size_t i = leaves_ - 1; i >= 1; --i) t_[i] = std::max(t_[2 * i], t_[2 * i + 1]);
    }
    void set(std::size_t i, double v) {
        if (i >= leaves_) grow(i + 1);
        std::size_t k = leaves_ + i;
        t_[k] = v;
        for (k /= 2; k >= 1; k /= 2) {
            const double m = std::max(t_[2 * k], t_[2 * k + 1]);
            if (t_[k] == m) break;  // the maxima above do not change
            t_[k] = m;
        }
    }
    [[nodiscard]] double max() const { return t_.size() > 1 ? t_[1] : 0.0; }

private:
    void grow(std::size_t n) {
        std::vector<double> v(t_.begin() + static_cast<std::ptrdiff_t>(leaves_), t_.end());
        v.resize(std::max(n, 2 * leaves_), 0.0);
        assign(v);
    }
    std::size_t leaves_ = 0;
    std::vector<double> t_;
};

}  // namespace dynmesh::detail
