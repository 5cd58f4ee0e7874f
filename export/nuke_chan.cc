#include "export/nuke_chan.h"

#include <cmath>
#include <numbers>

#include "core/number_format.h"

namespace cinepath::exporter {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// `angle` plus whole turns, within 180 degrees of `near`.
double NearestTurn(double angle, double near) { return angle + 360.0 * std::round((near - angle) / 360.0); }

}  // namespace

Eigen::Vector3d ZxyEulerDeg(const Eigen::Quaterniond& rotation, const Eigen::Vector3d* previous) {
  // R = Ry Rx Rz: row 1 is (cos rx sin rz, cos rx cos rz, -sin rx), column 2 is (sin ry cos rx, -sin rx,
  // cos ry cos rx).
  const Eigen::Matrix3d m = rotation.normalized().toRotationMatrix();
  const double cos_rx = std::hypot(m(1, 0), m(1, 1));
  double rx = std::atan2(-m(1, 2), cos_rx);
  double ry;
  double rz;
  if (cos_rx > 1e-6) {
    ry = std::atan2(m(0, 2), m(2, 2));
    rz = std::atan2(m(1, 0), m(1, 1));
  } else {
    // Looking straight down or up (sin rx = s = ±1): row 0 of Ry Rx Rz is (cos(ry - s rz),
    // s sin(ry - s rz), 0), so only ry - s rz is defined; rz keeps the previous key's value.
    const double s = rx > 0 ? 1.0 : -1.0;
    rx = s * std::numbers::pi / 2;
    rz = previous != nullptr ? (*previous)(2) / kDegPerRad : 0.0;
    ry = std::atan2(s * m(0, 1), m(0, 0)) + s * rz;
  }
  Eigen::Vector3d deg(rx * kDegPerRad, ry * kDegPerRad, rz * kDegPerRad);
  if (previous != nullptr) {
    deg(1) = NearestTurn(deg(1), (*previous)(1));
    deg(2) = NearestTurn(deg(2), (*previous)(2));
  }
  return deg;
}

std::string WriteNukeChan(const CameraTrack& track) {
  std::string out;
  Eigen::Vector3d previous;
  for (size_t i = 0; i < track.keys.size(); ++i) {
    const CameraKey& k = track.keys[i];
    const Eigen::Vector3d euler = ZxyEulerDeg(k.yup_from_camera, i == 0 ? nullptr : &previous);
    previous = euler;
    out += std::to_string(k.frame);
    for (int c = 0; c < 3; ++c) out += " " + FormatFixed(k.position_yup_m(c), 6);
    for (int c = 0; c < 3; ++c) out += " " + FormatFixed(euler(c), 6);
    out += " " + FormatFixed(k.vertical_fov_deg, 6) + "\n";
  }
  return out;
}

}  // namespace cinepath::exporter
