#pragma once
/// \file Sample edits of a scenario (scenario.hpp): the pool points to insert where the warp
/// spreads the live samples apart, and the live samples to delete where it crowds them, so
/// that the sampling stays about as dense as P(0).

#include <cstdint>
#include <span>
#include <vector>

namespace dynmesh {

struct Scenario;

/// Planned edits, as pool indices. A pool point deleted earlier is not live and may be
/// planned for insertion again: give it a fresh SampleId then.
struct SampleEdits {
    std::vector<std::uint32_t> insert_pool;  ///< pool points to insert, increasing
    std::vector<std::uint32_t> delete_pool;  ///< live pool points to delete, increasing
};

struct SampleEditOptions {
    /// Insert a pool point whose distance at time t to every live sample exceeds this
    /// (typically Scenario::h0). Must be positive and finite.
    double insert_radius = 0;
    /// Deletion candidates: live samples whose density ratio (below) is >= this.
    double compress_ratio = 2.0;
    /// A candidate is deleted only while its running density ratio is still > this.
    double target_ratio = 1.25;
    bool deletions = true;
};

/// Sample edits that keep P(t) about as dense as P(0) where the warp stretches or compresses
/// the surface. Exact rule, everything at time t:
/// 1. Insertion: scan the pool points that are not live in index order; insert one when its
///    distance to every live sample and to every point inserted before it in this scan is
///    > insert_radius.
/// 2. Density ratio of a live sample p: n_t(p) / max(1, initial_density[p]), with n_t(p) the
///    number of live samples and planned insertions within density_radius of p at time t
///    (p included). It compares the local density now with that of P(0) around the same
///    material point at t = 0: exactly 1 at t = 0 with live = P(0) and under a rigid motion,
///    ~2.25 where the pulse shrank back after its peak's insertions; a warp's area factor
///    alone (always >= 1 on the cyclic paths here) cannot see the insertions that made the
///    surface too dense on the way back.
/// 3. Deletion: scan the live samples with ratio >= compress_ratio in index order, and keep
///    running counts (a deletion lowers n_t of every live sample within density_radius).
///    Delete p when (a) its running ratio is still > target_ratio, (b) p is not protected,
///    (c) its nearest kept sample q (live, not deleted, or a planned insertion) is closer than
///    min(spacing0, h0), and (d) fewer than floor(|live| / 2) samples are deleted so far. Then
///    q becomes protected (never deleted), so every deleted sample keeps a kept sample within
///    h0: deletions never open a hole larger than h0 beyond the existing covering radius.
/// Deterministic (index order; no randomness). Cost: O(|pool| + |live|) expected.
/// \throw InvalidInput for a live index >= pool size or repeated, or a bad insert_radius,
///        or target_ratio > compress_ratio, or non-positive ratios.
[[nodiscard]] SampleEdits plan_sample_edits(const Scenario& s, double t,
                                            std::span<const std::uint32_t> live_pool,
                                            const SampleEditOptions& options);
/// plan_sample_edits(s, t, live_pool, {.insert_radius = insert_radius}).
[[nodiscard]] SampleEdits plan_sample_edits(const Scenario& s, double t,
                                            std::span<const std::uint32_t> live_pool,
                                            double insert_radius);

}  // namespace dynmesh
