#pragma once
/// \file Summary statistics (mean, population standard deviation, min, max, count) of a
/// stream of numbers, as reported in the tables of the edge-flip paper (spec §4.7).

#include <cmath>
#include <cstddef>
#include <span>

namespace dynmesh {

/// Mean / SD / min / max over `count` values. The SD is the *population* SD
/// (divide by count, not count - 1). All fields are 0 when count == 0.
struct Summary {
    double mean = 0, sd = 0, min = 0, max = 0;
    std::size_t count = 0;
};

/// Streaming accumulator (Welford's update, so the SD is accurate even when the values are
/// large compared with their spread). Linear time, constant memory.
class SummaryAccumulator {
public:
    /// Adds one value. Non-finite values (NaN, +-inf) are not added but counted in
    /// skipped(), so that one degenerate element cannot poison a whole mean.
    void add(double x) {
        if (!std::isfinite(x)) {
            ++skipped_;
            return;
        }
        ++n_;
        const double delta = x - mean_;
        mean_ += delta / static_cast<double>(n_);
        m2_ += delta * (x - mean_);
        if (n_ == 1 || x < min_) min_ = x;
        if (n_ == 1 || x > max_) max_ = x;
    }
    /// Merges another accumulator (Chan et al.'s pairwise update).
    void merge(const SummaryAccumulator& o);
    [[nodiscard]] std::size_t count() const { return n_; }
    [[nodiscard]] std::size_t skipped() const { return skipped_; }
    [[nodiscard]] Summary summary() const;

private:
    std::size_t n_ = 0, skipped_ = 0;
    double mean_ = 0, m2_ = 0, min_ = 0, max_ = 0;
};

/// Summary of a list of values (non-finite values are ignored, as in SummaryAccumulator).
[[nodiscard]] Summary summarize(std::span<const double> values);

}  // namespace dynmesh
