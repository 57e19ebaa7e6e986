#pragma once
/// \file Fixed-range histograms and a short ASCII rendering of them (for the paper's
/// Figures 18-23: normal deviation and 180 - dihedral, spec §6).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace dynmesh {

/// Equal-width bins over [lo, hi]. Bin i covers [lo + i w, lo + (i + 1) w) with
/// w = (hi - lo) / bins.size(); the last bin also holds hi. Values below lo go to the first
/// bin and values above hi to the last, so total() counts every finite value added.
struct Histogram {
    double lo = 0, hi = 0;
    std::vector<std::size_t> bins;

    [[nodiscard]] double bin_width() const {
        return bins.empty() ? 0.0 : (hi - lo) / static_cast<double>(bins.size());
    }
    [[nodiscard]] std::size_t total() const;
    /// Adds one value (NaN is ignored). \pre !bins.empty() and lo < hi.
    void add(double x);
};

/// An empty histogram with `bins` bins over [lo, hi].
/// \throw InvalidInput when bins == 0 or !(lo < hi).
[[nodiscard]] Histogram make_histogram(double lo, double hi, std::size_t bins);
/// The histogram of `values` with `bins` bins over [lo, hi] (out-of-range values clamped).
/// \throw InvalidInput as make_histogram.
[[nodiscard]] Histogram make_histogram(std::span<const double> values, double lo, double hi,
                                       std::size_t bins);

/// A few lines of text, one per bin, "[lo, hi)  count #######" with aligned columns; the
/// fullest bin gets `width` '#', any other non-empty bin at least one. Empty for no bins.
[[nodiscard]] std::string render_ascii(const Histogram& h, std::size_t width = 40);

}  // namespace dynmesh
