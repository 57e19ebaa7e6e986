#include "dynmesh/metrics/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/metrics/histogram.hpp"

namespace dynmesh {
namespace {

TEST(Summary, KnownValuesUsePopulationSd) {
    const std::vector<double> v = {2, 4, 4, 4, 5, 5, 7, 9};
    const Summary s = summarize(v);
    EXPECT_EQ(s.count, 8u);
    EXPECT_DOUBLE_EQ(s.mean, 5.0);
    EXPECT_DOUBLE_EQ(s.sd, 2.0);  // the sample SD would be 2.138
    EXPECT_DOUBLE_EQ(s.min, 2.0);
    EXPECT_DOUBLE_EQ(s.max, 9.0);
}

TEST(Summary, EmptyIsAllZero) {
    const Summary s = summarize(std::vector<double>{});
    EXPECT_EQ(s.count, 0u);
    EXPECT_EQ(s.mean, 0.0);
    EXPECT_EQ(s.sd, 0.0);
    EXPECT_EQ(s.min, 0.0);
    EXPECT_EQ(s.max, 0.0);
}

TEST(Summary, SingleValueHasZeroSd) {
    const Summary s = summarize(std::vector<double>{-3.5});
    EXPECT_EQ(s.count, 1u);
    EXPECT_EQ(s.mean, -3.5);
    EXPECT_EQ(s.sd, 0.0);
    EXPECT_EQ(s.min, -3.5);
    EXPECT_EQ(s.max, -3.5);
}

TEST(Summary, NonFiniteValuesAreSkippedAndCounted) {
    SummaryAccumulator acc;
    for (double x : {1.0, std::numeric_limits<double>::infinity(), 3.0,
                     std::numeric_limits<double>::quiet_NaN()})
        acc.add(x);
    EXPECT_EQ(acc.count(), 2u);
    EXPECT_EQ(acc.skipped(), 2u);
    const Summary s = acc.summary();
    EXPECT_DOUBLE_EQ(s.mean, 2.0);
    EXPECT_DOUBLE_EQ(s.sd, 1.0);
}

TEST(Summary, StableForLargeOffsets) {
    // A naive sum of squares loses every digit here; Welford does not.
    std::vector<double> v;
    for (double x : {2, 4, 4, 4, 5, 5, 7, 9}) v.push_back(1e9 + x);
    const Summary s = summarize(v);
    EXPECT_NEAR(s.mean, 1e9 + 5, 1e-6);
    EXPECT_NEAR(s.sd, 2.0, 1e-6);
}

TEST(Summary, MergeEqualsOnePass) {
    std::vector<double> all;
    SummaryAccumulator left, right, empty;
    for (int i = 0; i < 100; ++i) {
        const double x = std::sin(0.37 * i) * 10 + i * 0.1;
        all.push_back(x);
        (i < 37 ? left : right).add(x);
    }
    left.merge(right);
    left.merge(empty);
    empty.merge(left);
    const Summary one = summarize(all);
    for (const Summary& s : {left.summary(), empty.summary()}) {
        EXPECT_EQ(s.count, one.count);
        EXPECT_NEAR(s.mean, one.mean, 1e-12);
        EXPECT_NEAR(s.sd, one.sd, 1e-12);
        EXPECT_EQ(s.min, one.min);
        EXPECT_EQ(s.max, one.max);
    }
}

TEST(Histogram, BinsAndClamping) {
    const std::vector<double> v = {0.5,  1.5,  1.6,  9.9,
                                   10.0, 12.0, -1.0, std::numeric_limits<double>::quiet_NaN()};
    const Histogram h = make_histogram(v, 0.0, 10.0, 10);
    ASSERT_EQ(h.bins.size(), 10u);
    EXPECT_DOUBLE_EQ(h.bin_width(), 1.0);
    EXPECT_EQ(h.bins[0], 2u);  // 0.5 and the clamped -1
    EXPECT_EQ(h.bins[1], 2u);
    EXPECT_EQ(h.bins[9], 3u);  // 9.9, hi itself, and the clamped 12
    EXPECT_EQ(h.total(), 7u);  // NaN ignored
}

TEST(Histogram, BinEdgesAreHalfOpen) {
    Histogram h = make_histogram(0.0, 180.0, 18);
    h.add(10.0);
    h.add(9.999);
    EXPECT_EQ(h.bins[0], 1u);
    EXPECT_EQ(h.bins[1], 1u);
}

TEST(Histogram, RejectsBadRanges) {
    EXPECT_THROW((void)make_histogram(0.0, 1.0, 0), InvalidInput);
    EXPECT_THROW((void)make_histogram(1.0, 1.0, 4), InvalidInput);
    EXPECT_THROW((void)make_histogram(2.0, 1.0, 4), InvalidInput);
}

TEST(Histogram, RendersOneLinePerBinWithScaledBars) {
    Histogram h = make_histogram(0.0, 30.0, 3);
    h.bins = {100, 0, 1};
    const std::string text = render_ascii(h, 20);
    std::istringstream in(text);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    ASSERT_EQ(lines.size(), 3u);
    auto bar = [](const std::string& s) { return std::count(s.begin(), s.end(), '#'); };
    EXPECT_EQ(bar(lines[0]), 20);
    EXPECT_EQ(bar(lines[1]), 0);
    EXPECT_EQ(bar(lines[2]), 1);  // non-empty bins always show
    EXPECT_EQ(lines[0].rfind("[0, 10)", 0), 0u) << text;
    EXPECT_EQ(lines[2].rfind("[20, 30]", 0), 0u) << text;
    EXPECT_NE(lines[0].find(" 100 "), std::string::npos) << text;
    EXPECT_EQ(render_ascii(Histogram{}), "");
}

}  // namespace
}  // namespace dynmesh
