#pragma once
/// \file The probing device (specs/probing.md §1, §3.3, §3.5): a point in free space that
/// moves along segments inside Ω, travels outside Ω on and beyond ∂Ω, and casts rays.
///
/// Counters (spec §1, §8.11): probes (cast calls), segments travelled by move_to, the length
/// of those moves inside Ω, and the exterior length (the part of move_to outside Ω plus every
/// move_exterior), with the number of exterior moves.
///
/// With a safety monitor (a GroundTruth, never seen by the algorithm) every position and
/// every segment is checked free before the device moves, and exterior moves are checked to
/// keep at distance ≥ R_Ω − margin from c_Ω; a violation throws UnsafeMove and leaves the
/// device where it was. Without a monitor nothing is checked beyond the Ω preconditions.

#include <cstddef>
#include <optional>
#include <vector>

#include "dynmesh/error.hpp"
#include "dynmesh/geometry/vec.hpp"
#include "dynmesh/probing/oracle.hpp"

namespace dynmesh {

/// A move that the safety monitor found unsafe (a bug: the device only travels certified
/// segments); the message names the segment's endpoints.
struct UnsafeMove : InternalError {
    using InternalError::InternalError;
};

struct DeviceCounters {
    std::size_t probes = 0;          ///< cast() calls
    std::size_t segments = 0;        ///< move_to() segments
    std::size_t exterior_moves = 0;  ///< move_exterior() calls
    double inside_length = 0;        ///< length of move_to segments inside Ω
    double exterior_length = 0;      ///< length travelled outside the open ball Ω
    std::size_t monitored_segments = 0;  ///< segments the safety monitor verified
};

class ProbingDevice {
public:
    /// `margin` < 0 means the default 1e-6 R_Ω. The oracle and the monitor must outlive the
    /// device. \throw InvalidInput unless Ω has a finite centre and a positive finite radius.
    ProbingDevice(const Oracle& oracle, Ball omega, const GroundTruth* monitor = nullptr,
                  double margin = -1);

    /// Puts the device at q (start of a run). \throw InvalidInput when |q − c_Ω| < R_Ω − margin
    /// (q must be outside Ω); UnsafeMove when the monitor finds q not free.
    void place(const Point3& q);
    /// Moves along the segment from the current position to q.
    /// \throw InvalidInput when not placed; UnsafeMove when the monitor finds the segment not
    /// free (naming both endpoints).
    void move_to(const Point3& q);
    /// Exterior travel to q (spec §3.3): radially to ∂Ω, along a great-circle arc of ∂Ω,
    /// radially out to q. Its length (|p − c| − R) + R θ + (|q − c| − R), θ the angle between
    /// p − c and q − c, is counted as exterior length. \throw InvalidInput when not placed or
    /// when the current position or q is at distance < R_Ω − margin from c_Ω; UnsafeMove when
    /// the monitor finds a piece of the path not free.
    void move_exterior(const Point3& q);
    /// Follows again a path of `segments` segments inside Ω that the device has travelled
    /// before (each was certified free then), ending at q, of total length `length`: counted
    /// like move_to, in O(1), and not checked or recorded again (a monitored or recording run
    /// replays such paths with move_to instead).
    /// \throw InvalidInput when not placed or when q or length is not finite.
    void retrace(const Point3& q, std::size_t segments, double length);
    /// The first crossing of the ray from the current position (Oracle::cast); counted.
    /// \throw InvalidInput when not placed, or as Oracle::cast.
    [[nodiscard]] std::optional<ProbeHit> cast(const Vec3& d, double t_max);

    [[nodiscard]] bool placed() const { return placed_; }
    [[nodiscard]] const Point3& position() const { return position_; }
    [[nodiscard]] const Ball& omega() const { return omega_; }
    [[nodiscard]] double margin() const { return margin_; }
    [[nodiscard]] const DeviceCounters& counters() const { return counters_; }
    [[nodiscard]] bool monitored() const { return monitor_ != nullptr; }

    /// Recording of the path as polylines (one per place() or break in the path; exterior
    /// arcs sampled every 10°), for drawing. Off by default.
    void set_recording(bool on) { recording_ = on; }
    [[nodiscard]] bool recording() const { return recording_; }
    [[nodiscard]] const std::vector<std::vector<Point3>>& recorded_paths() const {
        return paths_;
    }
    /// The recorded polylines so far, moved out; recording goes on from the current position.
    [[nodiscard]] std::vector<std::vector<Point3>> take_recorded_paths();

private:
    void require_placed(const char* who) const;
    void check_segment(const char* who, const Point3& a, const Point3& b);
    void record(const Point3& p, bool new_polyline);

    const Oracle& oracle_;
    Ball omega_;
    const GroundTruth* monitor_;
    double margin_;
    Point3 position_{};
    bool placed_ = false;
    bool recording_ = false;
    DeviceCounters counters_;
    std::vector<std::vector<Point3>> paths_;
};

/// The length of the part of segment ab inside the closed ball.
[[nodiscard]] double length_inside(const Ball& ball, const Point3& a, const Point3& b);

}  // namespace dynmesh
