// One plan sample as the optimizer sees it: the planned values, fixed, plus the change carried by four
// knots of the spline (optimizer/knot_spline.h). Templated so that Ceres' automatic differentiation
// runs through it (T = double or ceres::Jet).
//
// The change has eight channels per knot (Channel): the position offset (ENU metres); `yaw`, a rotation
// of the camera about the world's up axis (radians, counter-clockwise seen from above, so the compass
// heading drops by it); `tilt`, a rotation about the camera's x axis (radians, positive looks up); the
// focal length as a log ratio (f = f0 exp(log_focal)); the focus in dioptres (D = D0 + dioptre, D0 = 1/s0,
// 0 at infinity); and the aperture in stops (N = N0 2^(stops/2)). The camera rotation is
//   world_from_camera = Rz(yaw) * world_from_camera0 * Rx(tilt),
// which keeps a level horizon level: neither rotation rolls the image.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "optimizer/knot_spline.h"

namespace cinepath::optimizer {

enum Channel { kEast = 0, kNorth, kUp, kYaw, kTilt, kLogFocal, kDioptre, kStops, kNumChannels };

// What one sample was before the change, and the planned path's derivatives there (finite differences
// over the samples, as the feasibility check takes them).
struct SampleBase {
  KnotWeights knots;  // first_knot indexes the problem's knot list
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  Eigen::Quaterniond world_from_camera = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d camera_from_world = Eigen::Matrix3d::Identity();
  double focal_length_mm = 24;
  double dioptre = 0.1;  // 1 / focus distance (0 at infinity)
  double f_number = 4;
  double pitch_deg = 0;
  Eigen::Vector3d velocity_m_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_m_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d jerk_m_s3 = Eigen::Vector3d::Zero();
  double heading_rate_deg_s = 0;  // compass heading, clockwise
  double pitch_rate_deg_s = 0;
  double focal_rate_mm_s = 0;
  double aperture_rate_stops_s = 0;
  bool has_rates = false;  // false for a sample alone between cuts
  bool has_jerk = false;   // needs four samples in its group
};

template <typename T>
using Vec3T = Eigen::Matrix<T, 3, 1>;

// The sample with the change applied, and the change's time derivatives.
template <typename T>
struct SampleState {
  Vec3T<T> position, velocity, acceleration, jerk;  // velocity... are the change's derivatives only
  T yaw, yaw_rate, tilt, tilt_rate;
  T log_focal, log_focal_rate, dioptre, dioptre_rate, stops, stops_rate;
  // In doubles, the state's exponentials and sines as FocalLengthMm, FNumber and CameraPoint below first compute
  // them, kept with the inputs they came from: the terms of one sample share them (docs/optimize.md, "Speed"),
  // and a field changed afterwards (or another base) misses the memo and computes afresh, so every result is
  // the same number as without it. Unused by Jets.
  struct Memo {
    double log_focal = std::numeric_limits<double>::quiet_NaN(), base_focal_mm = 0, focal_mm = 0;
    double stops = std::numeric_limits<double>::quiet_NaN(), base_f_number = 0, f_number = 0;
    double yaw = std::numeric_limits<double>::quiet_NaN(), cos_yaw = 0, sin_yaw = 0;
    double tilt = std::numeric_limits<double>::quiet_NaN(), cos_tilt = 0, sin_tilt = 0;
  };
  mutable Memo memo;
};

template <typename T>
T Blend(const std::array<double, 4>& w, const T* const* k, int channel) {
  return w[0] * k[0][channel] + w[1] * k[1][channel] + w[2] * k[2][channel] + w[3] * k[3][channel];
}

template <typename T>
SampleState<T> EvaluateSample(const SampleBase& b, const T* const* k) {
  const KnotWeights& w = b.knots;
  SampleState<T> s;
  for (int c = 0; c < 3; ++c) {
    s.position[c] = T(b.position_enu_m[c]) + Blend(w.value, k, c);
    s.velocity[c] = Blend(w.d1, k, c);
    s.acceleration[c] = Blend(w.d2, k, c);
    s.jerk[c] = Blend(w.d3, k, c);
  }
  s.yaw = Blend(w.value, k, kYaw);
  s.yaw_rate = Blend(w.d1, k, kYaw);
  s.tilt = Blend(w.value, k, kTilt);
  s.tilt_rate = Blend(w.d1, k, kTilt);
  s.log_focal = Blend(w.value, k, kLogFocal);
  s.log_focal_rate = Blend(w.d1, k, kLogFocal);
  s.dioptre = T(b.dioptre) + Blend(w.value, k, kDioptre);
  s.dioptre_rate = Blend(w.d1, k, kDioptre);
  s.stops = Blend(w.value, k, kStops);
  s.stops_rate = Blend(w.d1, k, kStops);
  return s;
}

// The same in doubles, each derivative order of the eight channels at once (the same sums in the same order as
// Blend's, so the same numbers; the solver evaluates every sample's state twice per iteration).
inline SampleState<double> EvaluateSample(const SampleBase& b, const double* const* k) {
  using Vec8 = Eigen::Matrix<double, kNumChannels, 1>;
  const KnotWeights& w = b.knots;
  const Eigen::Map<const Vec8> k0(k[0]), k1(k[1]), k2(k[2]), k3(k[3]);
  const auto blend = [&](const std::array<double, 4>& x) -> Vec8 {
    return x[0] * k0 + x[1] * k1 + x[2] * k2 + x[3] * k3;
  };
  // The second and third derivatives of the position's three channels only (the state has no others).
  const auto blend3 = [&](const std::array<double, 4>& x) -> Eigen::Vector3d {
    return x[0] * k0.head<3>() + x[1] * k1.head<3>() + x[2] * k2.head<3>() + x[3] * k3.head<3>();
  };
  const Vec8 value = blend(w.value), d1 = blend(w.d1);
  SampleState<double> s;
  s.position = b.position_enu_m + value.head<3>();
  s.velocity = d1.head<3>();
  s.acceleration = blend3(w.d2);
  s.jerk = blend3(w.d3);
  s.yaw = value[kYaw];
  s.yaw_rate = d1[kYaw];
  s.tilt = value[kTilt];
  s.tilt_rate = d1[kTilt];
  s.log_focal = value[kLogFocal];
  s.log_focal_rate = d1[kLogFocal];
  s.dioptre = b.dioptre + value[kDioptre];
  s.dioptre_rate = d1[kDioptre];
  s.stops = value[kStops];
  s.stops_rate = d1[kStops];
  return s;
}

// A world point in the changed camera's frame (x right, y down, z forward):
// camera_from_world = Rx(-tilt) * camera_from_world0 * Rz(-yaw).
template <typename T>
Vec3T<T> CameraPoint(const SampleBase& b, const SampleState<T>& s, const Eigen::Vector3d& point_enu_m) {
  using std::cos;
  using std::sin;
  const Vec3T<T> v = point_enu_m.cast<T>() - s.position;
  const T cy = cos(s.yaw), sy = sin(s.yaw);
  const Vec3T<T> u(cy * v[0] + sy * v[1], -sy * v[0] + cy * v[1], v[2]);
  const Vec3T<T> c = b.camera_from_world.cast<T>() * u;
  const T ct = cos(s.tilt), st = sin(s.tilt);
  return Vec3T<T>(c[0], ct * c[1] + st * c[2], -st * c[1] + ct * c[2]);
}

template <typename T>
T FocalLengthMm(const SampleBase& b, const SampleState<T>& s) {
  using std::exp;
  return b.focal_length_mm * exp(s.log_focal);
}

template <typename T>
T FNumber(const SampleBase& b, const SampleState<T>& s) {
  using std::exp;
  return b.f_number * exp(s.stops * (0.5 * std::log(2.0)));
}

// The same in doubles through the state's memo (the same operations, so the same numbers).
inline double FocalLengthMm(const SampleBase& b, const SampleState<double>& s) {
  SampleState<double>::Memo& m = s.memo;
  if (!(m.log_focal == s.log_focal && m.base_focal_mm == b.focal_length_mm)) {
    m.focal_mm = b.focal_length_mm * std::exp(s.log_focal);
    m.log_focal = s.log_focal;
    m.base_focal_mm = b.focal_length_mm;
  }
  return m.focal_mm;
}
inline double FNumber(const SampleBase& b, const SampleState<double>& s) {
  SampleState<double>::Memo& m = s.memo;
  if (!(m.stops == s.stops && m.base_f_number == b.f_number)) {
    m.f_number = b.f_number * std::exp(s.stops * (0.5 * std::log(2.0)));
    m.stops = s.stops;
    m.base_f_number = b.f_number;
  }
  return m.f_number;
}
// cos and sin of the state's yaw and tilt, through its memo.
struct CameraTrig {
  double cy, sy, ct, st;
};
inline CameraTrig StateTrig(const SampleState<double>& s) {
  SampleState<double>::Memo& m = s.memo;
  if (!(m.yaw == s.yaw)) {
    m.cos_yaw = std::cos(s.yaw);
    m.sin_yaw = std::sin(s.yaw);
    m.yaw = s.yaw;
  }
  if (!(m.tilt == s.tilt)) {
    m.cos_tilt = std::cos(s.tilt);
    m.sin_tilt = std::sin(s.tilt);
    m.tilt = s.tilt;
  }
  return {m.cos_yaw, m.sin_yaw, m.cos_tilt, m.sin_tilt};
}
// The same in doubles, its sines and cosines through the state's memo.
inline Eigen::Vector3d CameraPoint(const SampleBase& b, const SampleState<double>& s,
                                   const Eigen::Vector3d& point_enu_m) {
  const Eigen::Vector3d v = point_enu_m - s.position;
  const CameraTrig t = StateTrig(s);
  const Eigen::Vector3d u(t.cy * v[0] + t.sy * v[1], -t.sy * v[0] + t.cy * v[1], v[2]);
  const Eigen::Vector3d c = b.camera_from_world * u;
  return Eigen::Vector3d(c[0], t.ct * c[1] + t.st * c[2], -t.st * c[1] + t.ct * c[2]);
}

// The changed camera orientation, for the output (doubles).
inline Eigen::Quaterniond ChangedWorldFromCamera(const SampleBase& b, double yaw, double tilt) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())) * b.world_from_camera *
         Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()));
}

}  // namespace cinepath::optimizer
