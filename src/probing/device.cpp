#include "dynmesh/probing/device.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "probe_common.hpp"

namespace dynmesh {

double length_inside(const Ball& ball, const Point3& a, const Point3& b) {
    const double len = distance(a, b);
    if (len == 0) return 0;
    const Vec3 u = (b - a) / len, m = a - ball.center;
    const double B = dot(m, u), C = sqnorm(m) - ball.radius * ball.radius;
    const double disc = B * B - C;
    if (disc <= 0) return 0;
    const double r = std::sqrt(disc);
    const double lo = std::max(-B - r, 0.0), hi = std::min(-B + r, len);
    return std::max(hi - lo, 0.0);
}

ProbingDevice::ProbingDevice(const Oracle& oracle, Ball omega, const GroundTruth* monitor,
                             double margin)
    : oracle_(oracle), omega_(omega), monitor_(monitor),
      margin_(margin < 0 ? 1e-6 * omega.radius : margin) {
    DYNMESH_CHECK(is_finite(omega.center) && std::isfinite(omega.radius) && omega.radius > 0,
                  "ProbingDevice: Ω needs a finite centre and a positive finite radius");
    DYNMESH_CHECK(std::isfinite(margin_) && margin_ < omega.radius,
                  "ProbingDevice: the margin must be finite and smaller than R_Ω");
}

void ProbingDevice::require_placed(const char* who) const {
    if (!placed_)
        throw InvalidInput(std::string("ProbingDevice::") + who +
                           ": the device has not been placed");
}

void ProbingDevice::check_segment(const char* who, const Point3& a, const Point3& b) {
    if (monitor_ == nullptr) return;
    ++counters_.monitored_segments;
    if (!monitor_->segment_is_free(a, b))
        throw UnsafeMove(std::string("ProbingDevice::") + who + ": the segment " +
                         format_point(a) + " - " + format_point(b) +
                         " is not free");
}

void ProbingDevice::record(const Point3& p, bool new_polyline) {
    if (!recording_) return;
    if (new_polyline || paths_.empty()) paths_.emplace_back();
    paths_.back().push_back(p);
}

void ProbingDevice::place(const Point3& q) {
    DYNMESH_CHECK(is_finite(q), "ProbingDevice::place: the point is not finite");
    const double r = distance(q, omega_.center);
    if (r < omega_.radius - margin_)
        throw InvalidInput("ProbingDevice::place: " + format_point(q) +
                           " lies inside Ω (distance " + std::to_string(r) +
                           " from its centre, radius " + std::to_string(omega_.radius) + ")");
    if (monitor_ != nullptr && !monitor_->is_free(q))
        throw UnsafeMove("ProbingDevice::place: " + format_point(q) + " is not free");
    position_ = q;
    placed_ = true;
    record(q, true);
}

void ProbingDevice::move_to(const Point3& q) {
    require_placed("move_to");
    DYNMESH_CHECK(is_finite(q), "ProbingDevice::move_to: the point is not finite");
    check_segment("move_to", position_, q);
    const double len = distance(position_, q);
    const double in = std::min(length_inside(omega_, position_, q), len);
    counters_.segments += 1;
    counters_.inside_length += in;
    counters_.exterior_length += len - in;
    position_ = q;
    record(q, false);
}

void ProbingDevice::move_exterior(const Point3& q) {
    require_placed("move_exterior");
    DYNMESH_CHECK(is_finite(q), "ProbingDevice::move_exterior: the point is not finite");
    const Point3& c = omega_.center;
    const double R = omega_.radius;
    const double rp = distance(position_, c), rq = distance(q, c);
    for (const auto& [p, r] : {std::pair{position_, rp}, std::pair{q, rq}})
        if (r < R - margin_)
            throw InvalidInput("ProbingDevice::move_exterior: " + format_point(p) +
                               " lies inside Ω (distance " + std::to_string(r) +
                               " from its centre, radius " + std::to_string(R) + ")");
    const Vec3 up = normalized(position_ - c), uq = normalized(q - c);
    const double theta = std::atan2(norm(cross(up, uq)), dot(up, uq));
    const double length = std::fabs(rp - R) + R * theta + std::fabs(rq - R);
    if (monitor_ == nullptr && !recording_) {  // nothing to check or draw: only the counts
        counters_.exterior_moves += 1;
        counters_.exterior_length += length;
        position_ = q;
        return;
    }
    // The great circle through up and uq (any one through up when they are antipodal).
    Vec3 w = uq - dot(up, uq) * up;
    // Antipodal points: a great circle through the plane z = const of up when there is one
    // (a planar run stays in its plane).
    if (norm(w) < 1e-6) w = cross(up, std::fabs(up.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0});
    w = normalized(w - dot(w, up) * up);  // orthogonal to up to rounding: arc points stay on ∂Ω
    const int n = std::max(1, static_cast<int>(std::ceil(theta / (std::numbers::pi / 360))));
    std::vector<Point3> path{position_, c + R * up};
    for (int i = 1; i < n; ++i) {
        const double phi = theta * i / n;
        path.push_back(c + R * (std::cos(phi) * up + std::sin(phi) * w));
    }
    path.push_back(c + R * uq);
    path.push_back(q);
    if (monitor_ != nullptr) {
        check_segment("move_exterior", path[0], path[1]);
        check_segment("move_exterior", path[path.size() - 2], path.back());
        for (const Point3& p : path)
            if (distance(p, c) < R - margin_ || !monitor_->is_free(p))
                throw UnsafeMove("ProbingDevice::move_exterior: the path from " +
                                 format_point(position_) + " to " +
                                 format_point(q) + " passes through " +
                                 format_point(p) + ", which is not free or inside Ω");
    }
    counters_.exterior_moves += 1;
    counters_.exterior_length += length;
    position_ = q;
    // The drawing needs less: every 20th arc point (10°) and the ends.
    for (std::size_t i = 1; i < path.size(); ++i)
        if (i % 20 == 0 || i + 2 >= path.size()) record(path[i], false);
}

void ProbingDevice::retrace(const Point3& q, std::size_t segments, double length) {
    require_placed("retrace");
    DYNMESH_CHECK(is_finite(q) && std::isfinite(length) && length >= 0,
                  "ProbingDevice::retrace: the end point or the length is not finite");
    counters_.segments += segments;
    counters_.inside_length += length;
    position_ = q;
    if (recording_) record(q, true);
}

std::vector<std::vector<Point3>> ProbingDevice::take_recorded_paths() {
    std::vector<std::vector<Point3>> out;
    out.swap(paths_);
    if (placed_ && recording_) paths_.push_back({position_});
    return out;
}

std::optional<ProbeHit> ProbingDevice::cast(const Vec3& d, double t_max) {
    require_placed("cast");
    counters_.probes += 1;
    return oracle_.cast(position_, d, t_max);
}

}  // namespace dynmesh
