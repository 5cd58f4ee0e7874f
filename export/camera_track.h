// A drone's planned camera as a camera track: what the camera-track formats (gltf_camera.h,
// nuke_chan.h) write, one key per plan sample, in the Y-up frame glTF and Nuke share
// (core/three_frame.h): x east, y up, z south, metres; the camera looks along its -Z with +Y up.
//
// Keys sit on frames: frame = time_s * frame_rate_hz, which must be within 0.001 of a whole number
// and increase (plan.json samples are one per frame). Frame 0 is t = 0, as Blender's glTF importer
// places a key at time * fps.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/trajectory.h"

namespace cinepath::exporter {

struct CameraKey {
  long frame = 0;
  double time_s = 0;
  Eigen::Vector3d position_yup_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond yup_from_camera = Eigen::Quaterniond::Identity();  // sign kept continuous key to key
  double vertical_fov_deg = 0;
  double focal_length_mm = 0;
  double focus_distance_m = 0;  // +inf = infinity
  double f_number = 0;
  double shutter_s = 0;
};

struct CameraTrack {
  std::string name;  // the drone's name
  double frame_rate_hz = 30;
  CameraSpec camera;
  std::vector<CameraKey> keys;
};

// The track of drone `name`'s flight (its positions in the ENU frame the output uses). InputError naming
// `source` and the sample ("plan.json: flights[north].samples[3].time_s: ..." when `in_team`) for a
// flight without samples or a sample off the frame grid.
CameraTrack TrackOfFlight(const Trajectory& flight, const std::string& name, const std::string& source, bool in_team);

// The first and last frame over every track (each has at least one key).
std::pair<long, long> FrameRange(const std::vector<CameraTrack>& tracks);

}  // namespace cinepath::exporter
