#pragma once
/// \file Shared by the benchmarks: a console reporter that also keeps every run's time and
/// counters, so a benchmark can print ratios and scaling after Google Benchmark's table.

#include <benchmark/benchmark.h>

#include <functional>
#include <map>
#include <string>

namespace dynmesh::bench {

/// One run of `BM_Name/arg`: seconds per iteration and its user counters.
struct RunRecord {
    double seconds = 0;
    std::map<std::string, double> counters;
    [[nodiscard]] double counter(const std::string& name, double fallback = 0) const {
        const auto it = counters.find(name);
        return it == counters.end() ? fallback : it->second;
    }
};

class RecordingReporter : public benchmark::ConsoleReporter {
public:
    void ReportRuns(const std::vector<Run>& runs) override {
        for (const Run& r : runs) {
            if (r.run_type != Run::RT_Iteration || r.iterations == 0) continue;
            const std::string name = r.benchmark_name();
            const auto slash = name.find('/');
            if (slash == std::string::npos) continue;
            RunRecord& rec = runs_[name.substr(0, slash)][std::stoul(name.substr(slash + 1))];
            rec.seconds = r.real_accumulated_time / double(r.iterations);
            for (const auto& [k, c] : r.counters) rec.counters[k] = double(c);
        }
        ConsoleReporter::ReportRuns(runs);
    }
    /// The runs of one benchmark function by argument (empty if it did not run).
    [[nodiscard]] const std::map<std::size_t, RunRecord>& runs(const std::string& function) const {
        static const std::map<std::size_t, RunRecord> none;
        const auto it = runs_.find(function);
        return it == runs_.end() ? none : it->second;
    }
    [[nodiscard]] const std::map<std::string, std::map<std::size_t, RunRecord>>& all() const {
        return runs_;
    }

private:
    std::map<std::string, std::map<std::size_t, RunRecord>> runs_;
};

/// The body of a benchmark's main(): runs the registered benchmarks, then `summary`.
inline int run_benchmarks(int argc, char** argv,
                          const std::function<void(const RecordingReporter&)>& summary) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    RecordingReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    summary(reporter);
    benchmark::Shutdown();
    return 0;
}

}  // namespace dynmesh::bench
