// The process helper: argument vectors reach the program unchanged (no shell), failures are
// described, bundled scripts are found relative to the executable or $DYNMESH_SCRIPTS_DIR.
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "dynmesh/error.hpp"
#include "dynmesh/system/process.hpp"
#include "test_support.hpp"

namespace dynmesh::test {
namespace {

namespace fs = std::filesystem;

TEST(Process, ArgumentsAreNeverShellSyntax) {
    const auto dir = scratch_dir("process_no_shell");
    const fs::path marker = dir / "INJECTED";
    // Given to a shell, this string would run `touch`; as one element of an argument vector it
    // is only echoed, so nothing is created.
    const std::string hostile = "x';touch " + marker.string() + ";'$(touch " + marker.string() + ")";
    const ProcessResult r = run_process({"/bin/echo", hostile});
    EXPECT_TRUE(r.ok()) << r.describe();
    EXPECT_FALSE(fs::exists(marker));
}

TEST(Process, ReportsTheExitStatusAndTheLastErrorLine) {
    const ProcessResult r = run_process({"/bin/sh", "-c", "echo first >&2; echo 'last words' >&2; exit 3"});
    EXPECT_TRUE(r.started);
    EXPECT_EQ(r.exit_code, 3);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.error_tail, "last words");
    EXPECT_NE(r.describe().find("exit status 3: last words"), std::string::npos) << r.describe();
}

TEST(Process, AMissingProgramIsNotStarted) {
    const ProcessResult r = run_process({"/nonexistent/program", "a"});
    EXPECT_FALSE(r.started);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.describe().find("could not start"), std::string::npos);
    EXPECT_THROW((void)run_process({}), InvalidInput);
}

TEST(Process, ASignalIsReported) {
    const ProcessResult r = run_process({"/bin/sh", "-c", "kill -9 $$"});
    EXPECT_EQ(r.signal, 9);
    EXPECT_NE(r.describe().find("signal 9"), std::string::npos);
}

TEST(Process, ATimeoutKillsTheProgram) {
    const auto dir = scratch_dir("process_timeout");
    const fs::path marker = dir / "finished";
    const ProcessResult r = run_process({"/bin/sh", "-c", "sleep 30; touch " + marker.string()}, 0.5);
    EXPECT_TRUE(r.timed_out);
    EXPECT_FALSE(r.ok());
    EXPECT_NE(r.describe().find("time limit"), std::string::npos);
    EXPECT_FALSE(fs::exists(marker));  // killed, not waited for
}

TEST(Process, ADescendantHoldingStderrDoesNotKeepTheCallerWaiting) {
    const auto dir = scratch_dir("process_descendant");
    const fs::path marker = dir / "grandchild_done";
    const ProcessResult r = run_process(
        {"/bin/sh", "-c", "echo done >&2; (sleep 30; touch " + marker.string() + ") & exit 0"});
    EXPECT_TRUE(r.ok()) << r.describe();
    EXPECT_EQ(r.error_tail, "done");
    EXPECT_FALSE(fs::exists(marker));  // returned while the grandchild still holds stderr
}

TEST(Process, BundledScriptsAreFoundThroughTheEnvironmentOrNextToTheExecutable) {
    const auto dir = scratch_dir("process_scripts");
    std::ofstream(dir / "my_plot.py") << "print('hi')\n";
    ::setenv("DYNMESH_SCRIPTS_DIR", dir.c_str(), 1);
    EXPECT_EQ(find_bundled_script("my_plot.py"), dir / "my_plot.py");
    EXPECT_TRUE(find_bundled_script("no_such_script.py").empty());
    ::unsetenv("DYNMESH_SCRIPTS_DIR");
    EXPECT_TRUE(find_bundled_script("my_plot.py").empty());
    // The build tree mirrors an installed prefix: bin/ next to share/dynmesh/scripts/.
    const fs::path exe_dir = executable_directory();
    ASSERT_FALSE(exe_dir.empty());
    const fs::path shipped = find_bundled_script("plot_mesh2d.py");
    EXPECT_EQ(shipped, exe_dir.parent_path() / "share/dynmesh/scripts/plot_mesh2d.py");
}

}  // namespace
}  // namespace dynmesh::test
