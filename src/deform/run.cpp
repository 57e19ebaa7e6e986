#include "dynmesh/deform/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/triangle.hpp"
#include "dynmesh/metrics/self_intersection.hpp"

namespace dynmesh {

std::string_view to_string(Schedule s) { return s == Schedule::Paper ? "paper" : "every-step"; }

Schedule parse_schedule(std::string_view name) {
    if (name == "paper") return Schedule::Paper;
    if (name == "every-step" || name == "every") return Schedule::EveryStep;
    throw InvalidInput("unknown schedule '" + std::string(name) + "' (expected paper or every-step)");
}

namespace {

using Clock = std::chrono::steady_clock;

std::string record_line(const ViolationRecord& v) {
    return "t=" + std::to_string(v.t) + ": " + std::string(to_string(v.kind)) + ": " + v.detail;
}

FrameMetrics unmeasured(int t) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    FrameMetrics m;
    m.t = t;
    m.R = m.h = m.R_over_h = m.min_angle_deg = m.min_angle_off_creases_deg = m.max_radius_edge = m.min_edge_angle_deg = nan;
    m.normal_dev_max_deg = m.normal_dev_mean_deg = m.hausdorff = m.hausdorff_over_h = nan;
    return m;
}

}  // namespace

DeformRunReport run_deform(const Scenario& s, const DeformRunOptions& options) {
    DYNMESH_CHECK(options.measure_every >= 0, "run_deform: measure_every must not be negative");
    DYNMESH_CHECK(options.stop_after >= 0, "run_deform: stop_after must not be negative");
    const auto t_start = Clock::now();
    DeformRunReport rep;
    rep.scenario = s.name;
    rep.schedule = std::string(to_string(options.schedule));
    const int horizon = s.time_units;
    const int T = options.stop_after > 0 ? std::min(options.stop_after, horizon) : horizon;  // last unit run
    rep.time_units = T;

    DeformOptions params = options.params;
    params.lambda = s.lambda;
    params.h0 = s.h0;
    params.horizon = horizon;
    rep.kappa = params.kappa;
    rep.lambda = params.lambda;
    rep.h0 = s.h0;

    // Sample id -> pool index, and the t = 0 positions of every sample id.
    std::vector<std::uint32_t> pool_of(s.initial.begin(), s.initial.end());
    std::vector<Point3> x0(pool_of.size());
    for (std::size_t i = 0; i < pool_of.size(); ++i) x0[i] = s.reference.position(Vertex(pool_of[i]));
    std::vector<SampleId> sample_of_pool(s.pool_size(), kNoSample);
    for (std::size_t i = 0; i < pool_of.size(); ++i) sample_of_pool[pool_of[i]] = static_cast<SampleId>(i);
    rep.samples = pool_of.size();

    const auto t_init = Clock::now();
    InitialSurface init{.surface = s.surface0.get(), .mesh = nullptr, .vertex_samples = {}, .reference = nullptr};
    if (!s.surface0 && s.input_mesh) init.reference = &*s.input_mesh;
    DeformingMesh dm(x0, params, init);
    rep.seconds_init = std::chrono::duration<double>(Clock::now() - t_init).count();
    rep.init_vertices = dm.init_report().vertices;
    rep.crease_edges = dm.init_report().crease_edges;
    rep.crease_lines = dm.init_report().crease_lines;
    rep.corners = dm.init_report().corners;
    rep.euler = dm.init_report().euler;
    if (options.check_invariants) {  // the invariants at t = 0, as after an update
        const InitReport& ir = dm.init_report();
        rep.nonempty_balls_max = ir.nonempty_balls;
        rep.nonempty_balls_total = ir.nonempty_balls;
        if (ir.nonempty_balls > 0) {
            ++rep.updates_with_nonempty_balls;
            rep.first_nonempty_balls.push_back("t=0: " + ir.first_nonempty_ball + " (" +
                                               std::to_string(ir.nonempty_balls) + " such triangles)");
        }
        if (!ir.invariant_failures.empty()) {
            ++rep.invariant_failures;
            rep.first_invariant_failures.push_back("t=0: " + ir.invariant_failures.front());
        }
    }

    GroundTruth truth(s);
    std::vector<Point3> pos(x0.size());
    std::vector<std::uint32_t> vertex_pool, live_pool;
    // Pool indices of the live samples, into live_pool.
    auto collect_live_pool = [&] {
        live_pool.clear();
        for (SampleId id = 0; id < pool_of.size(); ++id)
            if (dm.is_live(id)) live_pool.push_back(pool_of[id]);
    };

    auto measure = [&](int t, const UpdateCounters& c, bool updated, bool emergency, std::size_t nviol,
                       const StepReport* step) {
        DeformLogRow row;
        row.update = updated;
        row.emergency = emergency;
        row.counters = c;
        row.violations = nviol;
        if (step != nullptr) {
            row.substeps = step->substeps;
            row.internal_updates = step->internal_updates;
            row.max_strain_ratio = step->max_strain_ratio;
        }
        // Cheap measures at every unit; Hausdorff and h (which warp and search the whole
        // reference) every measure_every units.
        const bool ends = t == 0 || t == T;
        const bool full = ends || (options.measure_every > 0 && t % options.measure_every == 0);
        MeasureOptions mo = options.measure;
        if (!full) {
            mo.hausdorff = false;
            mo.sampling_radius = false;
        }
        if (options.measure_every == 0 && !ends) {
            row.metrics = unmeasured(t);
        } else {
            const SurfaceMesh& m = dm.mesh();
            vertex_pool.assign(m.vertices_size(), 0);
            for (Vertex v : m.vertices()) vertex_pool[v.idx()] = pool_of[dm.sample_of(v)];
            collect_live_pool();
            truth.set_time(t);
            row.metrics = truth.measure(m, vertex_pool, live_pool, mo);
            row.measured = full;
            const FrameMetrics& f = row.metrics;
            if (std::isfinite(f.hausdorff_over_h))
                rep.worst_hausdorff_over_eps = std::max(rep.worst_hausdorff_over_eps, f.hausdorff_over_h);
            rep.worst_min_angle_deg = std::min(rep.worst_min_angle_deg, f.min_angle_deg);
            rep.worst_min_angle_off_creases_deg =
                std::min(rep.worst_min_angle_off_creases_deg, f.min_angle_off_creases_deg);
            rep.worst_max_radius_edge = std::max(rep.worst_max_radius_edge, f.max_radius_edge);
            if (std::isfinite(f.R_over_h)) rep.worst_R_over_h = std::max(rep.worst_R_over_h, f.R_over_h);
            rep.worst_normal_dev_deg = std::max(rep.worst_normal_dev_deg, f.normal_dev_max_deg);
            rep.worst_min_edge_angle_deg = std::min(rep.worst_min_edge_angle_deg, f.min_edge_angle_deg);
            rep.self_intersections += f.self_intersections;
            rep.inverted += f.inverted;
            // The place of the first of each, as sample ids.
            auto face_str = [&](Face x) {
                std::string out = "(";
                for (const Vertex u : m.face_vertices(x)) {
                    if (out.size() > 1) out += ", ";
                    out += std::to_string(dm.sample_of(u));
                }
                return out + ")";
            };
            if (f.self_intersections > 0 && rep.first_self_intersection_t < 0) {
                rep.first_self_intersection_t = t;
                const auto pairs = self_intersections(m, 1);
                if (!pairs.empty())
                    rep.first_self_intersection = "triangles " + face_str(pairs[0].first) + " and " + face_str(pairs[0].second);
            }
            if (f.inverted > 0 && rep.first_inverted_t < 0) {
                rep.first_inverted_t = t;
                if (f.first_inverted.is_valid()) rep.first_inverted = "triangle " + face_str(f.first_inverted);
            }
        }
        row.metrics.t = t;
        rep.log.push_back(row);
        if (options.on_frame) {
            DeformFrame fr;
            fr.t = t;
            fr.updated = updated;
            fr.emergency = emergency;
            fr.mesh = &dm;
            fr.metrics = &rep.log.back().metrics;
            fr.counters = c;
            fr.violations = nviol;
            fr.substeps = row.substeps;
            fr.internal_updates = row.internal_updates;
            options.on_frame(fr);
        }
    };
    measure(0, {}, false, false, 0, nullptr);
    // Totals of the work of one update (the caller's or one between sub-steps).
    auto count = [&](const UpdateCounters& c) {
        rep.seconds_updates += c.seconds;
        rep.flips += c.flips;
        rep.insertions += c.insertions;
        rep.removals += c.removals;
        rep.samples_inserted += c.samples_inserted;
        rep.samples_deleted += c.samples_deleted;
        rep.rebuilds += c.rebuilds;
        rep.rollbacks += c.rollbacks;
        rep.flip_refusals += c.flip_refusals;
    };

    for (int t = 1; t <= T; ++t) {
        pos.resize(x0.size());
        warp_points(s, t, x0, pos);
        const StepReport st = dm.advance(t, pos);
        std::size_t nviol = st.violations.size();
        const bool due = st.update_due || options.schedule == Schedule::EveryStep;
        UpdateCounters c = st.internal;
        count(st.internal);
        rep.substeps += st.substeps;
        rep.max_substeps_per_unit = std::max(rep.max_substeps_per_unit, st.substeps);
        rep.internal_updates += st.internal_updates;
        rep.substep_retries += st.retries;
        rep.max_strain_ratio = std::max(rep.max_strain_ratio, st.max_strain_ratio);
        bool emergency = false;
        if (due) {
            if (s.edits) {
                collect_live_pool();
                const SampleEdits e = plan_sample_edits(s, t, live_pool, s.h0);
                for (std::uint32_t q : e.insert_pool) {
                    const Point3 p0 = s.reference.position(Vertex(q));
                    Point3 pt;
                    warp_points(s, t, std::span<const Point3>(&p0, 1), std::span<Point3>(&pt, 1));
                    const SampleId id = dm.queue_insertion(pt);
                    DYNMESH_ASSERT(id == pool_of.size(), "run_deform: sample ids out of step");
                    pool_of.push_back(q);
                    x0.push_back(p0);
                    sample_of_pool[q] = id;
                }
                for (std::uint32_t q : e.delete_pool) {
                    if (sample_of_pool[q] == kNoSample) continue;
                    dm.queue_deletion(sample_of_pool[q]);
                    sample_of_pool[q] = kNoSample;
                }
            }
            const DeformUpdateReport u = dm.update();
            c += u.counters;
            count(u.counters);
            emergency = u.emergency;
            nviol += u.violations.size();
            ++rep.updates;
            if (u.emergency) ++rep.emergency_updates;
            if (options.check_invariants) {
                InvariantOptions io;
                io.self_intersections = false;  // measured at every unit below
                io.empty_balls_soft = true;
                const CheckReport inv = dm.check_invariants(io);
                const auto nonempty_balls = static_cast<std::size_t>(inv.integer("nonempty_balls"));
                rep.nonempty_balls_max = std::max(rep.nonempty_balls_max, nonempty_balls);
                rep.nonempty_balls_total += nonempty_balls;
                if (nonempty_balls > 0 && rep.updates_with_nonempty_balls++ < 10)
                    rep.first_nonempty_balls.push_back("t=" + std::to_string(t) + ": " + (inv.notes.empty() ? "" : inv.notes.front()) + " (" +
                                                       std::to_string(nonempty_balls) + " such triangles)");
                if (!inv.ok()) {
                    ++rep.invariant_failures;
                    if (rep.first_invariant_failures.size() < 10)
                        rep.first_invariant_failures.push_back("t=" + std::to_string(t) + ": " + inv.problems.front());
                }
            }
        }
        measure(t, c, due, emergency, nviol, &st);
    }
    std::size_t warned = 0;
    for (const auto& v : dm.violations()) {
        const std::string kind(to_string(v.kind));
        if (rep.violations[kind]++ < kViolationExamples) rep.violation_examples.push_back(v);
        if (v.kind == Violation::Coarsened || v.kind == Violation::TopologyRollback ||
            v.kind == Violation::InitFallback) {
            if (warned++ < kMaxWarnings) rep.warnings.push_back(record_line(v));
        }
    }
    if (warned > kMaxWarnings)
        rep.warnings.push_back(std::to_string(warned - kMaxWarnings) + " more warnings (coarsened, rollback)");
    rep.seconds_total = std::chrono::duration<double>(Clock::now() - t_start).count();
    return rep;
}

std::string_view to_string(CheckLevel level) {
    switch (level) {
        case CheckLevel::Off: return "off";
        case CheckLevel::Invariants: return "invariants";
        case CheckLevel::Strict: return "strict";
    }
    return "unknown";
}

CheckLevel parse_check_level(std::string_view name) {
    if (name == "off") return CheckLevel::Off;
    if (name == "invariants" || name == "on") return CheckLevel::Invariants;
    if (name == "strict") return CheckLevel::Strict;
    throw InvalidInput("unknown check level '" + std::string(name) + "' (expected off, invariants or strict)");
}

CheckReport check_failures(const DeformRunReport& r, CheckLevel level) {
    std::vector<std::string> out;
    if (level == CheckLevel::Off) return {};
    if (r.invariant_failures > 0) {
        out.push_back(std::to_string(r.invariant_failures) + " updates failed the invariant checks");
        for (const std::string& f : r.first_invariant_failures) out.push_back(f);
    }
    if (level == CheckLevel::Strict && r.updates_with_nonempty_balls > 0) {
        out.push_back(std::to_string(r.updates_with_nonempty_balls) +
                      " updates left diametric balls holding a vertex (at most " + std::to_string(r.nonempty_balls_max) +
                      " triangles at once)");
        for (const std::string& f : r.first_nonempty_balls) out.push_back(f);
    }
    if (r.self_intersections > 0)
        out.push_back("t=" + std::to_string(r.first_self_intersection_t) + ": self-intersections" +
                      (r.first_self_intersection.empty() ? "" : ", first " + r.first_self_intersection) + " (" +
                      std::to_string(r.self_intersections) + " intersecting triangle pairs over the measured time units)");
    if (r.inverted > 0)
        out.push_back("t=" + std::to_string(r.first_inverted_t) + ": inverted triangles" +
                      (r.first_inverted.empty() ? "" : ", first " + r.first_inverted) + " (" + std::to_string(r.inverted) +
                      " over the measured time units)");
    // Records of one kind: the examples the report keeps, then a count of the rest.
    auto records = [&](auto&& wanted) {
        for (const auto& [kind, n] : r.violations) {
            std::size_t shown = 0;
            for (const ViolationRecord& v : r.violation_examples)
                if (std::string(to_string(v.kind)) == kind && wanted(v.kind)) {
                    out.push_back(record_line(v));
                    ++shown;
                }
            if (shown > 0 && n > shown) out.push_back(kind + ": " + std::to_string(n - shown) + " more");
        }
    };
    if (level == CheckLevel::Strict)
        records([](Violation) { return true; });
    else
        records([](Violation k) { return k == Violation::TopologyRollback; });
    return CheckReport::of_problems(std::move(out));
}

std::string log_csv(const DeformRunReport& report) {
    std::ostringstream out;
    out.precision(9);
    bool header = false;
    for (const DeformLogRow& r : report.log) {
        const auto cols = flatten(r.metrics);
        if (!header) {
            for (const auto& [name, v] : cols) out << name << ',';
            out << "update,emergency,flips,insertions,removals,samples_inserted,samples_deleted,violations,"
                   "update_seconds,substeps,internal_updates,max_strain_ratio\n";
            header = true;
        }
        for (const auto& [name, v] : cols) {
            if (std::isfinite(v)) out << v;
            out << ',';
        }
        const UpdateCounters& c = r.counters;
        out << int(r.update) << ',' << int(r.emergency) << ',' << c.flips << ',' << c.insertions << ','
            << c.removals << ',' << c.samples_inserted << ',' << c.samples_deleted << ',' << r.violations << ','
            << c.seconds << ',' << r.substeps << ',' << r.internal_updates << ',' << r.max_strain_ratio << '\n';
    }
    return out.str();
}

}  // namespace dynmesh
