#include "export/validation.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "export/formats.h"

namespace cinepath::exporter {

namespace {

class Collector {
 public:
  Collector(const Mission& mission, Format format) : mission_(mission), format_(FormatName(format)) {}

  void Add(int waypoint, const std::string& limit, const std::string& what) {
    std::string where = waypoint < 0 ? std::string(format_)
                                     : fmt::format("{}: waypoint {} (t={:.2f} s)", format_, waypoint,
                                                   mission_.waypoints[waypoint].time_s);
    violations_.push_back({waypoint, limit, where + ": " + what});
  }
  std::vector<Violation> Take() { return std::move(violations_); }

 private:
  const Mission& mission_;
  const char* format_;
  std::vector<Violation> violations_;
};

}  // namespace

std::vector<Violation> ValidateMission(const Mission& mission, Format format, const DroneProfile& profile,
                                       int mavlink_item_count) {
  Collector out(mission, format);
  const FormatLimits limits = LimitsOf(format);
  const auto& wps = mission.waypoints;
  const int n = static_cast<int>(wps.size());
  const std::string fname = FormatName(format);

  if (n < limits.min_waypoints) {
    out.Add(-1, fname + " min waypoints",
            fmt::format("{} waypoint(s), the format needs at least {}", n, limits.min_waypoints));
  }
  if (n > limits.max_waypoints) {
    out.Add(-1, fname + " max waypoints",
            fmt::format("{} waypoints, the format allows at most {}", n, limits.max_waypoints));
  }
  if (IsMavlinkFormat(format) && mavlink_item_count > profile.max_mission_items) {
    out.Add(-1, profile.name + " max mission items",
            fmt::format("{} mission items, drone profile {} stores at most {}", mavlink_item_count, profile.name,
                        profile.max_mission_items));
  }

  // Each bound comes from the tighter of the format and the drone profile; messages name which.
  const std::string drone = "drone " + profile.name;
  const auto tighter_max = [&](double format_v, double profile_v) {
    return format_v <= profile_v ? std::make_pair(format_v, fname) : std::make_pair(profile_v, drone);
  };
  const auto tighter_min = [&](double format_v, double profile_v) {
    return format_v >= profile_v ? std::make_pair(format_v, fname) : std::make_pair(profile_v, drone);
  };
  const auto [max_speed, max_speed_src] = tighter_max(limits.max_speed_mps, profile.max_horizontal_speed_m_s);
  const auto [min_alt_v, min_alt_src] = tighter_min(limits.min_relative_alt_m, profile.min_relative_altitude_m);
  const auto [max_alt_v, max_alt_src] = tighter_max(limits.max_relative_alt_m, profile.max_relative_altitude_m);
  const auto [min_pitch_v, min_pitch_src] = tighter_min(limits.min_gimbal_pitch_deg, profile.min_gimbal_pitch_deg);
  const auto [max_pitch_v, max_pitch_src] = tighter_max(limits.max_gimbal_pitch_deg, profile.max_gimbal_pitch_deg);
  const double min_alt = min_alt_v, max_alt = max_alt_v, min_pitch = min_pitch_v, max_pitch = max_pitch_v;

  for (int w = 0; w < n; ++w) {
    const MissionWaypoint& wp = wps[w];
    for (double v : {wp.lat_deg, wp.lon_deg, wp.ellipsoidal_height_m, wp.amsl_m, wp.relative_alt_m, wp.speed_mps,
                     wp.heading_deg, wp.gimbal_pitch_deg, wp.gimbal_yaw_deg, wp.focal_length_mm, wp.f_number}) {
      if (!std::isfinite(v)) {
        out.Add(w, "finite values", "a value is NaN or infinite");
        break;
      }
    }
    const bool is_leg_start = w + 1 < n || n == 1;
    if (is_leg_start && wp.speed_mps > max_speed) {
      out.Add(w, max_speed_src + " max speed",
              fmt::format("speed {:.2f} m/s above the limit {:g} m/s ({})", wp.speed_mps, max_speed, max_speed_src));
    }
    if (is_leg_start && n > 1 && wp.speed_mps < limits.min_speed_mps) {
      out.Add(w, "min speed",
              fmt::format("speed {:.2f} m/s below the format's minimum {:g} m/s", wp.speed_mps, limits.min_speed_mps));
    }
    if (wp.relative_alt_m < min_alt || wp.relative_alt_m > max_alt) {
      out.Add(w, "altitude range",
              fmt::format("altitude {:.2f} m relative to home outside [{:g} ({}), {:g} ({})] m", wp.relative_alt_m,
                          min_alt, min_alt_src, max_alt, max_alt_src));
    }
    const double up_m = wp.position_enu_m.z() - mission.home_up_m;
    if (up_m < mission.fence_min_up_m || up_m > mission.fence_max_up_m) {
      out.Add(w, "drone altitude band",
              fmt::format("height {:.2f} m above home outside the drone's altitude band [{:g}, {:g}] m", up_m,
                          mission.fence_min_up_m, mission.fence_max_up_m));
    }
    if (is_leg_start && n > 1 && !wp.transit_after) {
      const Eigen::Vector3d leg = wps[w + 1].position_enu_m - wp.position_enu_m;
      const double horizontal_mps = leg.head<2>().norm() / (wps[w + 1].time_s - wp.time_s);
      if (horizontal_mps > mission.plan_max_horizontal_speed_mps) {
        out.Add(w, "drone max horizontal speed",
                fmt::format("horizontal speed {:.2f} m/s above the drone's ({}) limit {:g} m/s", horizontal_mps,
                            mission.plan_drone_name, mission.plan_max_horizontal_speed_mps));
      }
    }
    if (wp.gimbal_pitch_deg < min_pitch || wp.gimbal_pitch_deg > max_pitch) {
      out.Add(w, "gimbal pitch range",
              fmt::format("gimbal pitch {:.2f} deg outside [{:g} ({}), {:g} ({})] deg", wp.gimbal_pitch_deg, min_pitch,
                          min_pitch_src, max_pitch, max_pitch_src));
    }
    if (w + 1 < n) {
      const double spacing = (wps[w + 1].position_enu_m - wp.position_enu_m).norm();
      if (spacing < limits.min_spacing_m || spacing > limits.max_spacing_m) {
        out.Add(w, "waypoint spacing",
                fmt::format("{:.3f} m to the next waypoint, outside [{:g}, {:g}] m", spacing, limits.min_spacing_m,
                            limits.max_spacing_m));
      }
    }
  }
  return out.Take();
}

}  // namespace cinepath::exporter
