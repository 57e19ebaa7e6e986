#include "dynmesh/check_report.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/mesh/check.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

TEST(CheckReport, FiguresKeepNameOrderAndKind) {
    CheckReport r;
    r.add("faces", std::size_t{20});
    r.add("euler", -2LL);
    r.add("closed", true);
    r.add("hausdorff", 0.25);
    ASSERT_EQ(r.figures.size(), 4u);
    EXPECT_EQ(r.figures[0].name, "faces");
    EXPECT_EQ(r.figures[3].name, "hausdorff");
    EXPECT_EQ(r.figures[0].kind, CheckFigure::Kind::Integer);
    EXPECT_EQ(r.figures[2].kind, CheckFigure::Kind::Boolean);
    EXPECT_EQ(r.figures[3].kind, CheckFigure::Kind::Real);
    EXPECT_EQ(r.integer("faces"), 20);
    EXPECT_EQ(r.integer("euler"), -2);
    EXPECT_TRUE(r.flag("closed"));
    EXPECT_EQ(r.figure("closed"), 1.0);
    EXPECT_EQ(r.figure("hausdorff"), 0.25);
    EXPECT_TRUE(r.has("euler"));
    EXPECT_FALSE(r.has("genus"));
    EXPECT_TRUE(r.ok());
}

TEST(CheckReport, NamesAreUniqueAndLookupsChecked) {
    CheckReport r;
    r.add("euler", 2);
    EXPECT_THROW(r.add("euler", 2), InvalidInput);
    EXPECT_THROW(r.add("euler", 1.5), InvalidInput);  // whatever the kind
    EXPECT_EQ(r.figures.size(), 1u);
    EXPECT_THROW((void)r.figure("genus"), InternalError);  // asking for a figure that is not there is our bug
    EXPECT_THROW((void)r.integer("genus"), InternalError);
    EXPECT_THROW((void)r.flag("euler"), InternalError);  // an Integer is no flag
    r.add("gap", 0.5);
    EXPECT_THROW((void)r.integer("gap"), InternalError);  // a Real is no integer
}

TEST(CheckReport, ProblemsAreCountedAndListedUpToTheCap) {
    CheckReport r;
    r.fail("one", 2);
    r.fail("two", 2);
    r.fail("three", 2);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.n_problems, 3u);
    EXPECT_EQ(r.problems, (std::vector<std::string>{"one", "two"}));
    EXPECT_EQ(r.summary("  "), "  one\n  two\n  ... and 1 more\n");
    const CheckReport q = CheckReport::of_problems({"a", "b"});
    EXPECT_EQ(q.n_problems, 2u);
    EXPECT_FALSE(q.ok());
    EXPECT_TRUE(q.figures.empty());
    EXPECT_TRUE(CheckReport::of_problems({}).ok());
}

TEST(CheckReport, CheckMeshFiguresAreTheReportKeys) {
    const CheckReport r = check_mesh(test::icosphere(1), {.require_closed = true});
    std::vector<std::string> names;
    for (const CheckFigure& f : r.figures) names.push_back(f.name);
    EXPECT_EQ(names, (std::vector<std::string>{"vertices", "edges", "faces", "euler", "closed", "components",
                                               "boundary_edges", "degenerate_faces", "isolated_vertices",
                                               "non_manifold_vertices", "duplicate_edges"}));
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_EQ(r.integer("euler"), 2);
    EXPECT_TRUE(r.flag("closed"));
    EXPECT_EQ(r.integer("faces"), 80);
}

}  // namespace
}  // namespace dynmesh
