#include "core/rotation.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/error.h"

namespace cinepath {
namespace {

Eigen::Quaterniond Normalized(const Eigen::Quaterniond& q, const char* what) {
  const double n = q.norm();
  if (!(n > 0) || !std::isfinite(n)) {
    throw InputError(std::string("rotation: ") + what + " is not a valid quaternion (zero or non-finite)");
  }
  return Eigen::Quaterniond(q.coeffs() / n);
}

// Slerp without the short-arc flip (SQUAD's inner interpolations must not flip).
Eigen::Quaterniond SlerpNoFlip(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double t) {
  // Half the angle between the 4-vectors, stably: theta = 2 atan2(|a - b|, |a + b|).
  const double theta = 2.0 * std::atan2((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
  Eigen::Vector4d c;
  if (theta < 1e-9) {
    c = (1.0 - t) * a.coeffs() + t * b.coeffs();
  } else {
    const double s = std::sin(theta);
    c = (std::sin((1.0 - t) * theta) / s) * a.coeffs() + (std::sin(t * theta) / s) * b.coeffs();
  }
  return Eigen::Quaterniond(c / c.norm());
}

// The level camera looking east: x right = south, y down = -up, z forward = east.
Eigen::Matrix3d LevelEastCamera() {
  Eigen::Matrix3d b;
  b.col(0) = Eigen::Vector3d(0, -1, 0);
  b.col(1) = Eigen::Vector3d(0, 0, -1);
  b.col(2) = Eigen::Vector3d(1, 0, 0);
  return b;
}

Eigen::Matrix3d YawPitchMatrix(double yaw_enu_rad, double pitch_rad) {
  return Eigen::AngleAxisd(yaw_enu_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * LevelEastCamera() *
         Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitX()).toRotationMatrix();
}

Eigen::Quaterniond QuaternionFromMatrix(const Eigen::Matrix3d& m) {
  Eigen::Quaterniond q(m);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // canonical sign: w >= 0
  return q;
}

}  // namespace

Eigen::Quaterniond Slerp(const Eigen::Quaterniond& q0_in, const Eigen::Quaterniond& q1_in, double t) {
  const Eigen::Quaterniond q0 = Normalized(q0_in, "slerp start");
  Eigen::Quaterniond q1 = Normalized(q1_in, "slerp end");
  if (!std::isfinite(t)) throw InputError("rotation: slerp parameter is not finite");
  if (q0.coeffs().dot(q1.coeffs()) < 0) q1.coeffs() = -q1.coeffs();  // short arc
  if (t == 0.0) return q0;
  if (t == 1.0) return q1;
  return SlerpNoFlip(q0, q1, t);
}

double AngleBetweenRad(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Quaterniond d = Normalized(a, "angle start").conjugate() * Normalized(b, "angle end");
  return 2.0 * std::atan2(d.vec().norm(), std::fabs(d.w()));
}

Eigen::Vector3d QuaternionLog(const Eigen::Quaterniond& q) {
  const double n = q.vec().norm();
  if (n < 1e-300) return Eigen::Vector3d::Zero();
  const double half_angle = std::atan2(n, q.w());
  return q.vec() * (half_angle / n);
}

Eigen::Quaterniond QuaternionExp(const Eigen::Vector3d& v) {
  const double theta = v.norm();
  if (theta < 1e-12) return Eigen::Quaterniond(1.0, v.x(), v.y(), v.z()).normalized();
  const double s = std::sin(theta) / theta;
  return Eigen::Quaterniond(std::cos(theta), v.x() * s, v.y() * s, v.z() * s);
}

std::vector<Eigen::Quaterniond> AlignHemispheres(const std::vector<Eigen::Quaterniond>& keys) {
  std::vector<Eigen::Quaterniond> out;
  out.reserve(keys.size());
  for (const auto& k : keys) {
    Eigen::Quaterniond q = Normalized(k, "key rotation");
    if (!out.empty() && out.back().coeffs().dot(q.coeffs()) < 0) q.coeffs() = -q.coeffs();
    out.push_back(q);
  }
  return out;
}

std::vector<Eigen::Quaterniond> SquadControlPoints(const std::vector<Eigen::Quaterniond>& q) {
  std::vector<Eigen::Quaterniond> s(q.size());
  for (size_t i = 0; i < q.size(); ++i) {
    if (i == 0 || i + 1 == q.size()) {
      s[i] = q[i];
      continue;
    }
    const Eigen::Quaterniond inv = q[i].conjugate();
    const Eigen::Vector3d sum = QuaternionLog(inv * q[i + 1]) + QuaternionLog(inv * q[i - 1]);
    s[i] = (q[i] * QuaternionExp(-0.25 * sum)).normalized();
  }
  return s;
}

Eigen::Quaterniond Squad(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1, const Eigen::Quaterniond& s0,
                         const Eigen::Quaterniond& s1, double t) {
  if (t == 0.0) return q0.normalized();
  if (t == 1.0) return q1.normalized();
  return SlerpNoFlip(SlerpNoFlip(q0, q1, t), SlerpNoFlip(s0, s1, t), 2.0 * t * (1.0 - t));
}

Eigen::Quaterniond LookAt(const Eigen::Vector3d& forward_enu, double fallback_heading_deg) {
  const double n = forward_enu.norm();
  if (!(n > 0) || !std::isfinite(n)) {
    throw InputError("rotation: look-at direction is zero or not finite (camera on the target?)");
  }
  const Eigen::Vector3d f = forward_enu / n;
  const double horizontal = std::hypot(f.x(), f.y());
  Eigen::Vector3d right;
  if (horizontal < 1e-12) {
    // Vertical view: orient as if pitched from level while facing the fallback heading.
    const double yaw = EnuYawFromHeadingDeg(fallback_heading_deg);
    right = Eigen::Vector3d(std::sin(yaw), -std::cos(yaw), 0.0);  // heading x up
  } else {
    right = Eigen::Vector3d(f.y() / horizontal, -f.x() / horizontal, 0.0);  // f x up, normalized
  }
  Eigen::Vector3d down = f.cross(right);
  down.normalize();
  Eigen::Matrix3d m;
  m.col(0) = right;
  m.col(1) = down;
  m.col(2) = f;
  return QuaternionFromMatrix(m);
}

Eigen::Quaterniond AimWithScreenOffset(const Eigen::Vector3d& target_enu, const Eigen::Vector3d& ray_camera,
                                       double fallback_heading_deg) {
  const double tn = target_enu.norm();
  const double rn = ray_camera.norm();
  if (!(tn > 0) || !std::isfinite(tn)) {
    throw InputError("rotation: aim direction is zero or not finite (camera on the target?)");
  }
  if (!(rn > 0) || !std::isfinite(rn) || !(ray_camera.z() > 0)) {
    throw InputError("rotation: screen ray must point forward (z > 0)");
  }
  const Eigen::Vector3d t = target_enu / tn;
  const Eigen::Vector3d c = ray_camera / rn;
  const double a = c.x(), b = c.y(), cz = c.z();
  // Pitch: the ray's up component after pitching must equal the target's elevation sine.
  const double r = std::hypot(b, cz);
  const double phi = std::atan2(b, cz);
  const double sin_beta = std::clamp(t.z(), -1.0, 1.0);
  double pitch = phi + std::asin(std::clamp(sin_beta / r, -1.0, 1.0));
  pitch = std::clamp(pitch, -kPi / 2, kPi / 2);
  // Yaw: the ray's azimuth offset in the level frame after pitching.
  const double fwd = b * std::sin(pitch) + cz * std::cos(pitch);
  const double horizontal = std::hypot(t.x(), t.y());
  double yaw;
  if (horizontal < 1e-12) {
    yaw = EnuYawFromHeadingDeg(fallback_heading_deg);
  } else {
    const double azimuth = std::atan2(t.y(), t.x());
    const double delta = (std::hypot(a, fwd) < 1e-15) ? 0.0 : std::atan2(-a, fwd);
    yaw = azimuth - delta;
  }
  return QuaternionFromMatrix(YawPitchMatrix(yaw, pitch));
}

Eigen::Quaterniond WorldFromCameraFromGimbal(const GimbalAngles& g) {
  const double yaw = EnuYawFromHeadingDeg(g.drone_heading_deg + g.gimbal_yaw_deg);
  const Eigen::Matrix3d m =
      YawPitchMatrix(yaw, RadFromDeg(g.gimbal_pitch_deg)) *
      Eigen::AngleAxisd(RadFromDeg(g.gimbal_roll_deg), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return QuaternionFromMatrix(m);
}

namespace {

// Camera ENU yaw: the view azimuth, or for a vertical view the heading implied by the image top.
double CameraYawEnu(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d f = r.col(2);
  if (std::hypot(f.x(), f.y()) > 1e-9) return std::atan2(f.y(), f.x());
  const Eigen::Vector3d top = -r.col(1);
  const Eigen::Vector3d heading = f.z() < 0 ? top : Eigen::Vector3d(-top);
  return std::atan2(heading.y(), heading.x());
}

}  // namespace

double CameraHeadingDeg(const Eigen::Quaterniond& world_from_camera) {
  return HeadingDegFromEnuYaw(CameraYawEnu(Normalized(world_from_camera, "world_from_camera").toRotationMatrix()));
}

GimbalAngles GimbalFromWorldFromCamera(const Eigen::Quaterniond& world_from_camera, double drone_heading_deg) {
  const Eigen::Matrix3d r = Normalized(world_from_camera, "world_from_camera").toRotationMatrix();
  const Eigen::Vector3d f = r.col(2);
  const double pitch = std::asin(std::clamp(f.z(), -1.0, 1.0));
  const double yaw = CameraYawEnu(r);
  const Eigen::Matrix3d residual = YawPitchMatrix(yaw, pitch).transpose() * r;  // = Rz_cam(roll)
  const double roll = std::atan2(residual(1, 0), residual(0, 0));
  GimbalAngles g;
  const double camera_heading = HeadingDegFromEnuYaw(yaw);
  g.gimbal_pitch_deg = DegFromRad(pitch);
  g.gimbal_roll_deg = NormalizeDeg180Open(DegFromRad(roll));
  if (std::isnan(drone_heading_deg)) {
    g.drone_heading_deg = camera_heading;
    g.gimbal_yaw_deg = 0.0;
  } else {
    g.drone_heading_deg = NormalizeDeg360(drone_heading_deg);
    g.gimbal_yaw_deg = AngleDiffDeg(g.drone_heading_deg, camera_heading);
  }
  return g;
}

}  // namespace cinepath
