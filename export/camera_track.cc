#include "export/camera_track.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/number_format.h"
#include "core/three_frame.h"

namespace cinepath::exporter {

CameraTrack TrackOfFlight(const Trajectory& flight, const std::string& name, const std::string& source, bool in_team) {
  const std::string where = source + ": " + (in_team ? "flights[" + name + "]." : std::string());
  if (flight.samples.empty()) throw InputError(where + "samples: the plan has no samples");
  if (!(flight.frame_rate_hz > 0) || !std::isfinite(flight.frame_rate_hz)) {
    throw InputError(where + "frame_rate_hz: must be a finite number > 0");
  }
  CameraTrack track;
  track.name = name;
  track.frame_rate_hz = flight.frame_rate_hz;
  track.camera = flight.camera;
  for (size_t i = 0; i < flight.samples.size(); ++i) {
    const TrajectorySample& s = flight.samples[i];
    const double frame = s.time_s * flight.frame_rate_hz;
    CameraKey key;
    key.frame = std::lround(frame);
    if (std::abs(frame - static_cast<double>(key.frame)) > 1e-3 ||
        (!track.keys.empty() && key.frame <= track.keys.back().frame)) {
      throw InputError(where + "samples[" + std::to_string(i) + "].time_s: " + FormatShortest(s.time_s) +
                       " s is frame " + FormatSignificant(frame, 6) + " at frame_rate_hz " +
                       FormatShortest(flight.frame_rate_hz) + ": a camera track needs one sample per whole frame");
    }
    key.time_s = s.time_s;
    key.position_yup_m = ThreeFromEnu(s.position_enu_m);
    key.yup_from_camera = ThreeCameraFromWorldFromCamera(s.world_from_camera);
    if (!track.keys.empty() && track.keys.back().yup_from_camera.dot(key.yup_from_camera) < 0) {
      key.yup_from_camera.coeffs() = -key.yup_from_camera.coeffs();
    }
    key.vertical_fov_deg = VerticalFieldOfViewDeg(flight.camera, s.focal_length_mm);
    key.focal_length_mm = s.focal_length_mm;
    key.focus_distance_m = s.focus_distance_m;
    key.f_number = s.f_number;
    key.shutter_s = s.shutter_s;
    track.keys.push_back(key);
  }
  return track;
}

std::pair<long, long> FrameRange(const std::vector<CameraTrack>& tracks) {
  CINEPATH_CHECK(!tracks.empty());
  std::pair<long, long> range{tracks.front().keys.front().frame, tracks.front().keys.back().frame};
  for (const CameraTrack& t : tracks) {
    range.first = std::min(range.first, t.keys.front().frame);
    range.second = std::max(range.second, t.keys.back().frame);
  }
  return range;
}

}  // namespace cinepath::exporter
