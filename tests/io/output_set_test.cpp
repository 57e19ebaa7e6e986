// All-or-nothing outputs: clashes refused before any work, staged files moved together.
#include <sys/stat.h>

#include <chrono>
#include <csignal>
#include <thread>

#include <gtest/gtest.h>

#include "dynmesh/io/output_set.hpp"
#include "dynmesh/io/text_file.hpp"
#include "dynmesh/system/process.hpp"
#include "io_test_util.hpp"
#include "test_support.hpp"

namespace dynmesh::test {
namespace {

namespace fs = std::filesystem;

std::string invalid_input_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InvalidInput& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected InvalidInput";
    return {};
}

TEST(OutputSet, NothingAppearsUntilCommit) {
    const auto dir = scratch_dir("output_set_commit");
    {
        OutputSet set;
        const fs::path a = set.add_file(dir / "a.off", "-o");
        const fs::path r = set.add_file(dir / "r.json", "--report");
        EXPECT_EQ(a.parent_path(), dir);
        EXPECT_EQ(a.extension(), ".off");  // writers choose the format by extension
        write_text_file(a, "mesh");
        write_text_file(r, "{}");
        EXPECT_FALSE(fs::exists(dir / "a.off"));
        EXPECT_FALSE(fs::exists(dir / "r.json"));
        set.commit();
    }
    EXPECT_EQ(read_bytes(dir / "a.off"), "mesh");
    EXPECT_EQ(read_bytes(dir / "r.json"), "{}");
    EXPECT_EQ(listing(dir), (std::vector<std::string>{"a.off", "r.json"}));
}

TEST(OutputSet, AFailedRunLeavesNoTraceAndKeepsOldTargets) {
    const auto dir = scratch_dir("output_set_failed");
    write_text_file(dir / "old.off", "old");
    try {
        OutputSet set;
        write_text_file(set.add_file(dir / "old.off", "-o"), "new");
        (void)set.add_file(dir / "r.json", "--report");
        throw std::runtime_error("the run failed");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(read_bytes(dir / "old.off"), "old");
    EXPECT_EQ(listing(dir), (std::vector<std::string>{"old.off"}));
}

TEST(OutputSet, RefusesTwoOutputsThatAreOneFile) {
    const auto dir = scratch_dir("output_set_same");
    OutputSet set;
    (void)set.add_file(dir / "x.off", "-o");
    const std::string msg = invalid_input_of([&] { (void)set.add_file(dir / "sub/../x.off", "--report"); });
    EXPECT_NE(msg.find("--report"), std::string::npos) << msg;
    EXPECT_NE(msg.find("same file"), std::string::npos) << msg;
    // The refused registration staged nothing.
    EXPECT_EQ(listing(dir).size(), 1u);
}

TEST(OutputSet, AFileSetClashesWithEachOfItsMembers) {
    const auto dir = scratch_dir("output_set_node_ele");
    OutputSet set;
    const fs::path base = set.add_file_set(dir / "p", {".node", ".ele"}, "-o");
    EXPECT_NE(invalid_input_of([&] { (void)set.add_file(dir / "p.ele", "--report"); }).find("same file"),
              std::string::npos);
    fs::path node = base, ele = base;
    node += ".node";
    ele += ".ele";
    write_text_file(node, "n");
    write_text_file(ele, "e");
    set.commit();
    EXPECT_EQ(read_bytes(dir / "p.node"), "n");
    EXPECT_EQ(read_bytes(dir / "p.ele"), "e");
}

TEST(OutputSet, RefusesToOverwriteAnInputEvenThroughALink) {
    const auto dir = scratch_dir("output_set_input");
    write_text_file(dir / "in.off", "input");
    fs::create_symlink(dir / "in.off", dir / "link.off");
    fs::create_hard_link(dir / "in.off", dir / "hard.off");
    OutputSet set({dir / "in.off"});
    for (const char* name : {"in.off", "link.off", "hard.off", "./in.off"}) {
        const std::string msg = invalid_input_of([&] { (void)set.add_file(dir / name, "-o"); });
        EXPECT_NE(msg.find("input"), std::string::npos) << name << ": " << msg;
    }
    EXPECT_EQ(read_bytes(dir / "in.off"), "input");
}

TEST(OutputSet, RefusesAMissingDirectoryBeforeAnyWork) {
    const auto dir = scratch_dir("output_set_nodir");
    OutputSet set;
    const std::string msg = invalid_input_of([&] { (void)set.add_file(dir / "nodir/r.json", "--report"); });
    EXPECT_NE(msg.find("does not exist"), std::string::npos) << msg;
    EXPECT_FALSE(fs::exists(dir / "nodir"));
    EXPECT_NE(invalid_input_of([&] { (void)set.add_file(dir, "-o"); }).find("is a directory"),
              std::string::npos);
}

TEST(OutputSet, DirectoriesAreFilledOnCommit) {
    const auto dir = scratch_dir("output_set_directory");
    fs::create_directory(dir / "existing");
    write_text_file(dir / "existing/keep.txt", "keep");
    write_text_file(dir / "existing/log.csv", "old");
    {
        OutputSet set;
        const fs::path fresh = set.add_directory(dir / "fresh", "--out");
        const fs::path existing = set.add_directory(dir / "existing", "--out2");
        write_text_file(fresh / "a.txt", "a");
        write_text_file(existing / "log.csv", "new");
        EXPECT_FALSE(fs::exists(dir / "fresh"));
        EXPECT_EQ(read_bytes(dir / "existing/log.csv"), "old");
        set.commit();
    }
    EXPECT_EQ(read_bytes(dir / "fresh/a.txt"), "a");
    EXPECT_EQ(read_bytes(dir / "existing/log.csv"), "new");
    EXPECT_EQ(read_bytes(dir / "existing/keep.txt"), "keep");
    EXPECT_EQ(listing(dir), (std::vector<std::string>{"existing", "fresh"}));
}

TEST(OutputSet, RefusesInputsAndOutputsInsideAnOutputDirectory) {
    const auto dir = scratch_dir("output_set_inside");
    fs::create_directory(dir / "d");
    write_text_file(dir / "d/in.off", "input");
    {
        OutputSet set({dir / "d/in.off"});
        EXPECT_NE(invalid_input_of([&] { (void)set.add_directory(dir / "d", "--out"); }).find("contains the input"),
                  std::string::npos);
    }
    OutputSet set;
    fs::create_directory(dir / "e");
    (void)set.add_directory(dir / "e", "--out");
    EXPECT_NE(invalid_input_of([&] { (void)set.add_file(dir / "e/r.json", "--report"); }).find("inside"),
              std::string::npos);
}

TEST(OutputSet, AFailedCommitRestoresEveryTarget) {
    // The directory output holds a file whose name is taken by a directory in the target:
    // that move fails, and every move before it is undone.
    const auto dir = scratch_dir("output_set_rollback");
    fs::create_directories(dir / "out/summary.json");
    write_text_file(dir / "mesh.off", "old mesh");
    write_text_file(dir / "out/log.csv", "old log");
    {
        OutputSet set;
        write_text_file(set.add_file(dir / "mesh.off", "-o"), "new mesh");
        write_text_file(set.add_file(dir / "r.json", "--report", OutputSet::Order::Last), "{}");
        const fs::path out = set.add_directory(dir / "out", "--out");
        write_text_file(out / "log.csv", "new log");
        write_text_file(out / "summary.json", "{}");
        EXPECT_THROW(set.commit(), IoError);
    }
    EXPECT_EQ(read_bytes(dir / "mesh.off"), "old mesh");
    EXPECT_EQ(read_bytes(dir / "out/log.csv"), "old log");
    EXPECT_FALSE(fs::exists(dir / "r.json"));
    EXPECT_TRUE(fs::is_directory(dir / "out/summary.json"));
    EXPECT_EQ(listing(dir), (std::vector<std::string>{"mesh.off", "out"}));
    EXPECT_EQ(listing(dir / "out"), (std::vector<std::string>{"log.csv", "summary.json"}));
}

TEST(OutputSet, RefusesToReplaceDevicesPipesAndUnresolvablePaths) {
    const auto dir = scratch_dir("output_set_special");
    ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
    OutputSet set;
    EXPECT_NE(invalid_input_of([&] { (void)set.add_file("/dev/null", "--report"); }).find("not a regular file"),
              std::string::npos);
    EXPECT_NE(invalid_input_of([&] { (void)set.add_file(dir / "pipe", "--report"); }).find("not a regular file"),
              std::string::npos);
    EXPECT_TRUE(fs::is_fifo(dir / "pipe"));
    EXPECT_THROW((void)set.add_file("", "-o"), InvalidInput);
}

TEST(OutputSet, LongNamesKeepTheirExtensionAndFit) {
    const auto dir = scratch_dir("output_set_long");
    const std::string name = std::string(240, 'a') + ".off";
    OutputSet set;
    const fs::path staged = set.add_file(dir / name, "-o");
    EXPECT_EQ(staged.extension(), ".off");
    EXPECT_LE(staged.filename().string().size(), 200u);
    write_text_file(staged, "x");  // a writer's own temporary beside it fits as well
    set.commit();
    EXPECT_EQ(read_bytes(dir / name), "x");
}

TEST(OutputSet, AReplacedFileKeepsItsPermissions) {
    const auto dir = scratch_dir("output_set_mode");
    write_text_file(dir / "m.off", "old");
    fs::permissions(dir / "m.off", fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
    OutputSet set;
    write_text_file(set.add_file(dir / "m.off", "-o"), "new");
    set.commit();
    EXPECT_EQ(fs::status(dir / "m.off").permissions(),
              fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
}

TEST(OutputSet, MessagesNameTheTargetNotTheStagingFile) {
    const auto dir = scratch_dir("output_set_names");
    OutputSet set;
    const fs::path staged = set.add_file(dir / "picture.xyz", "-o");
    const std::string msg = io_error_of([&] { write_mesh(octahedron(), staged); });
    EXPECT_NE(msg.find((dir / "picture.xyz").string()), std::string::npos) << msg;
    EXPECT_EQ(msg.find(".dynmesh-"), std::string::npos) << msg;
}

TEST(OutputSetDeathTest, ASignalRemovesTheStagedFiles) {
    const auto dir = scratch_dir("output_set_signal");
    EXPECT_EXIT(
        {
            install_output_cleanup_on_signals();
            OutputSet set;
            write_text_file(set.add_file(dir / "a.off", "-o"), "partial");
            const fs::path d = set.add_directory(dir / "frames", "--out");
            write_text_file(d / "mesh_00001.vtp", "partial");
            std::raise(SIGTERM);
        },
        testing::KilledBySignal(SIGTERM), "");
    EXPECT_TRUE(listing(dir).empty()) << listing(dir).front();
}

TEST(OutputSetDeathTest, ASignalDuringAChildProcessKillsTheChildFirst) {
    const auto dir = scratch_dir("output_set_signal_child");
    const std::string late = (dir / "late").string();
    EXPECT_EXIT(
        {
            install_output_cleanup_on_signals();
            OutputSet set;
            write_text_file(set.add_file(dir / "a.png", "--png"), "partial");
            // The child signals its parent, then writes a file a second later.
            (void)run_process({"/bin/sh", "-c", "sleep 0.2; kill -TERM $PPID; sleep 1; echo late > \"$0\"", late});
        },
        testing::KilledBySignal(SIGTERM), "");
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    EXPECT_TRUE(listing(dir).empty()) << listing(dir).front();
}

}  // namespace
}  // namespace dynmesh::test
