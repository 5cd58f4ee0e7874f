// The mission model every exporter writes: the waypoints chosen from a plan's per-frame trajectory,
// georeferenced, with their altitudes in every reference a format may need, plus what the camera does
// at each one.
//
// Units and frames: lat/lon degrees WGS84; heights in metres — ellipsoidal (WGS84), AMSL (EGM96) and
// relative to home (AMSL difference, as MAVLink's frame 3 and DJI/Litchi's "relative to take-off"
// mean it). Headings are compass degrees [0, 360); gimbal pitch is degrees from the horizon (−90 down),
// gimbal yaw degrees relative to the drone's nose.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/geodesy.h"
#include "export/waypoint_selection.h"

namespace cinepath::exporter {

// Where a format's altitudes are measured from.
enum class AltitudeRef { kRelative, kAmsl, kEllipsoid };
const char* AltitudeRefName(AltitudeRef ref);

struct MissionWaypoint {
  int sample_index = 0;  // index of the trajectory sample this waypoint sits on
  double time_s = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  double lat_deg = 0;
  double lon_deg = 0;
  double ellipsoidal_height_m = 0;
  double amsl_m = 0;
  double relative_alt_m = 0;  // amsl_m − home amsl
  double speed_mps = 0;       // ground-path speed on the leg that leaves this waypoint (last: previous leg)
  double heading_deg = 0;     // drone compass heading at the waypoint
  double gimbal_pitch_deg = 0;
  double gimbal_yaw_deg = 0;  // relative to the nose
  double focal_length_mm = 24;
  double focus_distance_m = 10;  // +inf = infinity
  double f_number = 2.8;
  // Recording: on from a shot's first waypoint to its last. Across a "cut" between shots the plan
  // jumps; the leg leaving the last waypoint before the cut is a transit flown with recording off.
  bool record_start = false;
  bool record_stop = false;
  bool transit_after = false;
  // Hover here this long before leaving (set where close waypoints were merged; MSDK STAY actions).
  double hold_s = 0;
  // Point-of-interest stretch this waypoint belongs to (index into Mission::rois; −1: none). The
  // stretch's legs are those between its first and last waypoint.
  int roi = -1;
  // DJI coordinated turn (dji_turns.h): damping distance in metres; 0 = stop at the waypoint.
  double turn_damping_m = 0;
};

// A point the camera keeps centred over a stretch of waypoints (roi.h), georeferenced.
struct MissionRoi {
  int first_waypoint = 0;
  int last_waypoint = 0;
  double start_time_s = 0;
  double end_time_s = 0;
  Eigen::Vector3d point_enu_m = Eigen::Vector3d::Zero();
  double lat_deg = 0;
  double lon_deg = 0;
  double ellipsoidal_height_m = 0;
  double amsl_m = 0;
  double relative_alt_m = 0;  // amsl_m − home amsl
  double fit_angle_deg = 0;   // largest angle between a plan axis and the point
};

// What the waypoints were chosen for: how the target flies between them.
enum class TurnModel { kStraight, kDjiCoordinatedTurn };

struct Home {
  double lat_deg = 0;
  double lon_deg = 0;
  double amsl_m = 0;
  double ellipsoidal_height_m = 0;
};

struct Mission {
  Home home;
  Geodetic origin;  // WGS84 origin of the plan's ENU frame
  // Camera range used to express focal length as a percentage of the zoom range (ArduPilot) and as a
  // 35 mm equivalent (DJI).
  double min_focal_length_mm = 24;
  double max_focal_length_mm = 24;
  double sensor_diagonal_mm = 43.27;
  std::vector<MissionWaypoint> waypoints;
  std::vector<MissionRoi> rois;
  TurnModel turn_model = TurnModel::kStraight;
  RoiTracking roi_tracking = RoiTracking::kNone;  // how the target points at the rois
  // How closely the flown path follows the per-frame plan (the selection's result; for
  // kDjiCoordinatedTurn the modelled turns included). straight_deviation_reached_m: the same waypoints
  // joined by straight legs.
  double max_deviation_reached_m = 0;
  double straight_deviation_reached_m = 0;
  double max_angle_error_reached_deg = 0;
  int plan_sample_count = 0;
  int cut_count = 0;             // transits inserted at "cut" transitions
  double transit_speed_mps = 0;  // speed of those transits
  // The plan's own fence (plan.json "drone"): altitude band above home (the ENU up coordinate less
  // home's, as plan's feasibility measures it above the take-off point), and the drone's horizontal
  // speed limit.
  double fence_min_up_m = -std::numeric_limits<double>::infinity();
  double fence_max_up_m = std::numeric_limits<double>::infinity();
  double home_up_m = 0;  // home's ENU up coordinate about the origin
  double plan_max_horizontal_speed_mps = std::numeric_limits<double>::infinity();
  std::string plan_drone_name;
};

// Focal length as percent of the camera's zoom range [0, 100] (0 when the lens is a prime).
double ZoomPercent(const Mission& mission, double focal_length_mm);
// 35 mm-equivalent focal length (full-frame diagonal 43.27 mm).
double FocalLength35mmEquivalent(const Mission& mission, double focal_length_mm);
// Altitude of a waypoint in the given reference.
double AltitudeIn(const MissionWaypoint& wp, AltitudeRef ref);

}  // namespace cinepath::exporter
