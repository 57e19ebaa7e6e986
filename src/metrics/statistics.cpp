#include "dynmesh/metrics/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "dynmesh/error.hpp"
#include "dynmesh/metrics/histogram.hpp"

namespace dynmesh {

// ---- Summary ---------------------------------------------------------------------------------

void SummaryAccumulator::merge(const SummaryAccumulator& o) {
    skipped_ += o.skipped_;
    if (o.n_ == 0) return;
    if (n_ == 0) {
        const std::size_t skipped = skipped_;
        *this = o;
        skipped_ = skipped;
        return;
    }
    const double na = static_cast<double>(n_), nb = static_cast<double>(o.n_);
    const double n = na + nb;
    const double delta = o.mean_ - mean_;
    mean_ += delta * nb / n;
    m2_ += o.m2_ + delta * delta * na * nb / n;
    n_ += o.n_;
    min_ = std::min(min_, o.min_);
    max_ = std::max(max_, o.max_);
}

Summary SummaryAccumulator::summary() const {
    Summary s;
    s.count = n_;
    if (n_ == 0) return s;
    s.mean = mean_;
    s.sd = std::sqrt(std::max(0.0, m2_ / static_cast<double>(n_)));
    s.min = min_;
    s.max = max_;
    return s;
}

Summary summarize(std::span<const double> values) {
    SummaryAccumulator acc;
    for (const double x : values) acc.add(x);
    return acc.summary();
}

// ---- Histogram -------------------------------------------------------------------------------

std::size_t Histogram::total() const {
    return std::accumulate(bins.begin(), bins.end(), std::size_t{0});
}

void Histogram::add(double x) {
    if (std::isnan(x) || bins.empty()) return;
    const double t = (x - lo) / (hi - lo) * static_cast<double>(bins.size());
    std::size_t i = 0;
    if (t >= static_cast<double>(bins.size()))
        i = bins.size() - 1;
    else if (t > 0)
        i = static_cast<std::size_t>(t);
    ++bins[i];
}

Histogram make_histogram(double lo, double hi, std::size_t bins) {
    DYNMESH_CHECK(bins > 0, "make_histogram: need at least one bin");
    DYNMESH_CHECK(lo < hi && std::isfinite(lo) && std::isfinite(hi),
                  "make_histogram: need finite lo < hi, got [" + std::to_string(lo) + ", " +
                      std::to_string(hi) + "]");
    Histogram h;
    h.lo = lo;
    h.hi = hi;
    h.bins.assign(bins, 0);
    return h;
}

Histogram make_histogram(std::span<const double> values, double lo, double hi, std::size_t bins) {
    Histogram h = make_histogram(lo, hi, bins);
    for (const double x : values) h.add(x);
    return h;
}

namespace {
/// Shortest "%g"-style text for a bin edge (at most 4 significant digits).
std::string edge_label(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", x);
    return buf;
}
}  // namespace

std::string render_ascii(const Histogram& h, std::size_t width) {
    if (h.bins.empty()) return {};
    const std::size_t n = h.bins.size();
    const double w = h.bin_width();
    std::vector<std::string> labels(n), counts(n);
    std::size_t label_width = 0, count_width = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = h.lo + w * static_cast<double>(i);
        const double b = i + 1 == n ? h.hi : h.lo + w * static_cast<double>(i + 1);
        std::string& label = labels[i];  // append(), not operator+: GCC 12 -Wrestrict noise
        label.append("[").append(edge_label(a)).append(", ").append(edge_label(b));
        label.append(i + 1 == n ? "]" : ")");
        counts[i] = std::to_string(h.bins[i]);
        label_width = std::max(label_width, labels[i].size());
        count_width = std::max(count_width, counts[i].size());
    }
    const std::size_t peak = *std::max_element(h.bins.begin(), h.bins.end());
    std::string out;
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t bar = 0;
        if (peak > 0 && h.bins[i] > 0) {
            bar = static_cast<std::size_t>(
                std::llround(static_cast<double>(h.bins[i]) / static_cast<double>(peak) *
                             static_cast<double>(width)));
            bar = std::max<std::size_t>(bar, 1);
        }
        out += labels[i];
        out.append(label_width - labels[i].size() + 1, ' ');
        out.append(count_width - counts[i].size(), ' ');
        out += counts[i];
        out += ' ';
        out.append(bar, '#');
        out += '\n';
    }
    return out;
}

}  // namespace dynmesh
