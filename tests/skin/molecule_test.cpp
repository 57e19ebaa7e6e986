#include "dynmesh/skin/molecule.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "dynmesh/error.hpp"
#include "test_support.hpp"

namespace dynmesh {
namespace {

namespace fs = std::filesystem;

/// Writes a file into a scratch directory of the running test's own (tests run in parallel
/// processes; each test's directory is emptied once, when it writes its first file).
fs::path write_file(const std::string& name, const std::string& text) {
    static std::string current;
    const std::string test = std::string("skin_molecule_") + testing::UnitTest::GetInstance()->current_test_info()->name();
    if (test != current) {
        (void)test::scratch_dir(test);
        current = test;
    }
    const fs::path p = fs::path(DYNMESH_TEST_TMP_DIR) / test / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
}

using test::io_error_of;

TEST(Molecule, PqrFilesOfTheSharedData) {
    const auto hca = read_pqr(test::shared_data("molecules/hca.pqr"));
    EXPECT_EQ(hca.size(), 2482u);  // the data README: 2,482 atoms, 442 of them hydrogens
    std::size_t hydrogens = 0;
    double rmin = 1e9, rmax = 0;
    for (const Atom& a : hca) {
        hydrogens += a.element == "H";
        rmin = std::min(rmin, a.radius);
        rmax = std::max(rmax, a.radius);
    }
    EXPECT_EQ(hydrogens, 442u);
    EXPECT_DOUBLE_EQ(rmin, 0.8);  // radii 0.8–2.4 Å
    EXPECT_DOUBLE_EQ(rmax, 2.4);
    // First record: "ATOM      1  N   HIS     1      10.610  -0.430   7.576 -0.300 1.800"
    EXPECT_EQ(hca[0].center, (Point3{10.610, -0.430, 7.576}));
    EXPECT_EQ(hca[0].radius, 1.8);
    EXPECT_EQ(hca[0].element, "N");
    EXPECT_EQ(hca[0].line, 1u);
    const auto lig = read_pqr(test::shared_data("molecules/bx6_7_lig_apbs.pqr"));
    EXPECT_EQ(lig.size(), 47u);
}

TEST(Molecule, WeightedPointsAndXyzr) {
    const auto caffeine = read_weighted_points(test::shared_data("molecules/caffeine.cin"));
    ASSERT_EQ(caffeine.size(), 23u);
    EXPECT_EQ(caffeine[0], (WeightedPoint{{-3.3804130, -1.1272367, 0.5733036}, 0.46875}));
    const auto atoms = read_xyzr(write_file("two.xyzr", "# two atoms\n0 0 0 1.7\n\n1.5 0 0 1.52  # O\n"));
    ASSERT_EQ(atoms.size(), 2u);
    EXPECT_EQ(atoms[1].center, (Point3{1.5, 0, 0}));
    EXPECT_EQ(atoms[1].line, 4u);
    const auto w = skin_weights(atoms, 0.5);
    EXPECT_DOUBLE_EQ(w[0].weight, 1.7 * 1.7 / 0.5);
    EXPECT_DOUBLE_EQ(w[1].weight, 1.52 * 1.52 / 0.5);
    EXPECT_THROW((void)skin_weights(atoms, 0), InvalidInput);
    EXPECT_THROW((void)skin_weights(atoms, 1.5), InvalidInput);
}

TEST(Molecule, BadFilesNameTheFileAndTheLine) {
    struct Case {
        const char* name;
        const char* text;
        const char* expect;  // part of the message after "<file>"
        int reader;          // 0 xyzr, 1 pqr, 2 weighted points
    };
    for (const Case& c : {
             Case{"empty.xyzr", "", "empty.xyzr", 0},
             Case{"comments.xyzr", "# nothing\n\n", "no atom in the file", 0},
             Case{"word.xyzr", "0 0 0 1\n0 x 0 1\n", "word.xyzr:2: expected 'x y z r'", 0},
             Case{"nan.xyzr", "0 0 nan 1\n", "nan.xyzr:1:", 0},
             Case{"three.xyzr", "0 0 0\n", "three.xyzr:1:", 0},
             Case{"zero.xyzr", "0 0 0 1\n1 0 0 0\n", "zero.xyzr:2: the radius must be positive", 0},
             Case{"five.cin", "0 0 0 1 2\n", "five.cin:1:", 2},
             Case{"short.pqr", "REMARK x\nATOM 1 N HIS 1 0 0 0 1.8\n", "short.pqr:2: a PQR atom record", 1},
             Case{"coord.pqr", "ATOM 1 N HIS 1 1.0 abc 3.0 -0.3 1.8\n", "coord.pqr:1: the coordinate 'abc'", 1},
             Case{"radius.pqr", "ATOM 1 N HIS 1 1.0 2.0 3.0 -0.3 -1\n", "radius.pqr:1: the radius must be positive", 1},
             Case{"none.pqr", "REMARK only\nEND\n", "no ATOM or HETATM record", 1},
         }) {
        SCOPED_TRACE(c.name);
        const fs::path p = write_file(c.name, c.text);
        const std::string msg = io_error_of([&] {
            if (c.reader == 0) (void)read_xyzr(p);
            if (c.reader == 1) (void)read_pqr(p);
            if (c.reader == 2) (void)read_weighted_points(p);
        });
        EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
    EXPECT_NE(io_error_of([] { (void)read_xyzr("no/such/file.xyzr"); }).find("file.xyzr"), std::string::npos);
}

TEST(RadiusTable, BondiDefaultsAndTheSharedTable) {
    const RadiusTable b = RadiusTable::bondi();
    EXPECT_EQ(b.radius("C"), 1.70);
    EXPECT_EQ(b.radius("cl"), 1.75);
    EXPECT_EQ(b.radius("Br"), 1.85);
    EXPECT_EQ(b.radius("ZN"), 1.80);  // not listed: the fallback
    EXPECT_FALSE(b.contains("ZN"));
    const RadiusTable csv = RadiusTable::read_csv(test::shared_data("molecules/radii/bondi_vdw_radii.csv"));
    // Bondi's own entries agree with the built-in table.
    for (const char* e : {"H", "C", "N", "O", "F", "P", "S", "CL", "BR", "I"}) {
        ASSERT_TRUE(csv.contains(e)) << e;
        EXPECT_EQ(csv.radius(e), b.radius(e)) << e;
    }
    EXPECT_GT(csv.size(), 50u);
    EXPECT_EQ(csv.radius("FE"), 1.80);  // "Elements not listed (e.g. Fe, ...)"
    EXPECT_NE(io_error_of([] { (void)RadiusTable::read_csv(write_file("nohead.csv", "C,1.7\n")); }).find("nohead.csv:1: the header"),
              std::string::npos);
    EXPECT_NE(io_error_of([] { (void)RadiusTable::read_csv(write_file("twice.csv", "symbol,radius\nC,1.7\nc,1.8\n")); })
                  .find("twice.csv:3: the element 'C' is listed twice"),
              std::string::npos);
    EXPECT_NE(io_error_of([] { (void)RadiusTable::read_csv(write_file("neg.csv", "symbol,radius\nC,-1\n")); }).find("neg.csv:2:"),
              std::string::npos);
    RadiusTable t = RadiusTable::bondi();
    t.set("zn", 1.39);
    EXPECT_EQ(t.radius("Zn"), 1.39);
    EXPECT_THROW(t.set("C", 0), InvalidInput);
}

}  // namespace
}  // namespace dynmesh

namespace dynmesh {
namespace {

/// PDB through gemmi: every ATOM/HETATM record of 1UBQ but the waters (counted from the file's
/// text here), each atom naming its line, whose columns 31-54 hold its centre.
TEST(Molecule, PdbThroughGemmiKeepsTheRecordsAndTheirLines) {
    const auto path = test::shared_data("molecules/1ubq.pdb");
    std::ifstream in(path);
    std::vector<std::string> lines;
    std::size_t records = 0, waters = 0;
    for (std::string line; std::getline(in, line);) {
        lines.push_back(line);
        if (line.rfind("ATOM  ", 0) == 0 || line.rfind("HETATM", 0) == 0) {
            ++records;
            if (line.substr(17, 3) == "HOH") ++waters;
        }
    }
    ASSERT_GT(waters, 0u);
    MoleculeReadReport report;
    const auto atoms = read_pdb(path, RadiusTable::bondi(), {}, &report);
    EXPECT_EQ(atoms.size(), records - waters);
    EXPECT_EQ(report.skipped_water, waters);
    for (const Atom& a : atoms) {
        ASSERT_GT(a.line, 0u);
        const std::string& l = lines[a.line - 1];
        EXPECT_NEAR(std::stod(l.substr(30, 8)), a.center.x, 1e-9) << a.line;
        EXPECT_NEAR(std::stod(l.substr(46, 8)), a.center.z, 1e-9) << a.line;
        EXPECT_DOUBLE_EQ(a.radius, RadiusTable::bondi().radius(a.element)) << a.line;
    }
    MoleculeReadOptions keep;
    keep.keep_water = true;
    EXPECT_EQ(read_pdb(path, RadiusTable::bondi(), keep).size(), records);
    EXPECT_EQ(read_molecule(path, RadiusTable::bondi()).size(), records - waters);
}

}  // namespace
}  // namespace dynmesh
