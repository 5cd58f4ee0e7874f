// The cost terms of `cinepath optimize`, one functor per term (docs/optimize.md, "Costs"). Each takes
// the four knot blocks a sample (or a spline segment) depends on and writes dimensionless, weighted
// residuals; Ceres differentiates them automatically. Hinges (max(0, x)) are zero inside a limit, so a
// plan that keeps every limit and meets every goal has zero cost and comes back unchanged.
// The clearance term, which asks the mesh, has its own file (optimizer/clearance_cost.h).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/drone_profile.h"
#include "core/optics.h"
#include "core/trajectory.h"
#include "optimizer/sample_model.h"

namespace cinepath::optimizer {

template <typename T>
T Hinge(const T& x) {
  return x > T(0) ? x : T(0);
}

template <typename T>
T SafeNorm(const Vec3T<T>& v) {
  using std::sqrt;
  return sqrt(v.squaredNorm() + T(1e-12));
}

template <typename T>
T SafeNorm2(const T& x, const T& y) {
  using std::sqrt;
  return sqrt(x * x + y * y + T(1e-12));
}

// CameraPoint in doubles with its derivatives in the state's position (columns 0-2), yaw (3) and tilt (4), for the
// goals' gradients by hand (their Gradients below): p = Rx(-tilt) M Rz(-yaw) (point - position), so
// dp/dposition = -Rx(-tilt) M Rz(-yaw), dp/dyaw = Rx(-tilt) M (u_y, -u_x, 0) with u = Rz(-yaw) (point - position),
// and dp/dtilt = (0, p_z, -p_y). The point is the same number as CameraPoint<double> gives (the same operations).
struct CameraPointJacobian {
  Eigen::Vector3d p;
  Eigen::Matrix<double, 3, 5> d;
};
inline CameraPointJacobian CameraPointWithJacobian(const SampleBase& b, const SampleState<double>& s,
                                                   const Eigen::Vector3d& point_enu_m) {
  const Eigen::Vector3d v = point_enu_m - s.position;
  const CameraTrig trig = StateTrig(s);  // shared by the sample's terms
  const double cy = trig.cy, sy = trig.sy, ct = trig.ct, st = trig.st;
  const Eigen::Vector3d u(cy * v[0] + sy * v[1], -sy * v[0] + cy * v[1], v[2]);
  const Eigen::Vector3d c = b.camera_from_world * u;
  CameraPointJacobian out;
  out.p = Eigen::Vector3d(c[0], ct * c[1] + st * c[2], -st * c[1] + ct * c[2]);
  Eigen::Matrix3d tilt_m;  // Rx(-tilt) M
  tilt_m.row(0) = b.camera_from_world.row(0);
  tilt_m.row(1) = ct * b.camera_from_world.row(1) + st * b.camera_from_world.row(2);
  tilt_m.row(2) = -st * b.camera_from_world.row(1) + ct * b.camera_from_world.row(2);
  Eigen::Matrix3d yaw;  // Rz(-yaw)
  yaw << cy, sy, 0, -sy, cy, 0, 0, 0, 1;
  out.d.leftCols<3>() = -tilt_m * yaw;
  out.d.col(3) = tilt_m * Eigen::Vector3d(u[1], -u[0], 0);
  out.d.col(4) = Eigen::Vector3d(0, out.p[2], -out.p[1]);
  return out;
}

// A goal's gradient rows in the eight channel values (the state's kValues fields, Channel order).
using ValueGradient = double[kNumChannels];

// Where the subject's aim point falls on screen ([0, 1] x right, y down) and the fraction of the frame
// height the subject fills (its height over the frame's height at its distance, as `plan` frames it).
template <typename T>
struct Framing {
  T screen_x, screen_y, height_fraction;
};

template <typename T>
Framing<T> MeasureFraming(const SampleBase& b, const SampleState<T>& s, const Eigen::Vector3d& aim_enu_m,
                          double subject_height_m, double image_width_mm, double image_height_mm) {
  const Vec3T<T> p = CameraPoint(b, s, aim_enu_m);
  const T depth = p[2] > T(1e-3) ? p[2] : T(1e-3);
  const T f_mm = FocalLengthMm(b, s);
  Framing<T> out;
  out.screen_x = T(0.5) + f_mm * p[0] / depth / image_width_mm;
  out.screen_y = T(0.5) + f_mm * p[1] / depth / image_height_mm;
  out.height_fraction =
      subject_height_m * f_mm / (SafeNorm(Vec3T<T>(aim_enu_m.cast<T>() - s.position)) * image_height_mm);
  return out;
}

// framing: the subject stays where the plan put it on screen, at the height fraction the shot asks for.
struct FramingCost {
  SampleBase base;
  Eigen::Vector3d aim_enu_m;
  double subject_height_m = 1.8;
  double image_width_mm = 36, image_height_mm = 24;
  double target_x = 0.5, target_y = 0.5;
  double target_fraction = 0;  // 0: no size goal (the residual is then 0)
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    using std::log;
    const Framing<T> m = MeasureFraming(base, s, aim_enu_m, subject_height_m, image_width_mm, image_height_mm);
    r[0] = weight * (m.screen_x - target_x);
    r[1] = weight * (m.screen_y - target_y);
    r[2] = target_fraction > 0 ? weight * log(m.height_fraction / target_fraction) : T(0);
    return true;
  }
  // The residuals (the same numbers as Residuals) and their gradients in the channel values, written out
  // (tests/optimizer/cost_terms_test.cc checks them against automatic differentiation).
  void Gradients(const SampleState<double>& s, double* r, ValueGradient* g) const {
    const CameraPointJacobian cp = CameraPointWithJacobian(base, s, aim_enu_m);
    const Eigen::Vector3d& p = cp.p;
    const bool clamped = !(p[2] > 1e-3);
    const double depth = clamped ? 1e-3 : p[2];
    const double f_mm = FocalLengthMm(base, s);
    const Eigen::Vector3d to_aim = aim_enu_m - s.position;
    const double distance = SafeNorm(to_aim);
    const double height_fraction = subject_height_m * f_mm / (distance * image_height_mm);
    const double extent[2] = {image_width_mm, image_height_mm}, target[2] = {target_x, target_y};
    for (int i = 0; i < 2; ++i) {
      // screen = 0.5 + q, q = f p_i / depth / extent: dq = (f / (depth extent)) dp_i - (q / depth) ddepth + q dlog_f
      const double q = f_mm * p[i] / depth / extent[i];
      r[i] = weight * (0.5 + q - target[i]);
      const double along = weight * f_mm / (depth * extent[i]), across = clamped ? 0.0 : weight * q / depth;
      for (int f = 0; f < 5; ++f) g[i][f] = along * cp.d(i, f) - across * cp.d(2, f);
      g[i][kLogFocal] = weight * q;
      g[i][kDioptre] = g[i][kStops] = 0;
    }
    std::fill(g[2], g[2] + kNumChannels, 0.0);
    r[2] = 0;
    if (!(target_fraction > 0)) return;
    // log(h f / (|aim - position| extent)): d/dlog_f = 1, d/dposition = (aim - position) / |.|^2
    r[2] = weight * std::log(height_fraction / target_fraction);
    for (int c = 0; c < 3; ++c) g[2][c] = weight * to_aim[c] / (distance * distance);
    g[2][kLogFocal] = weight;
  }
};

// depth of field: an actor that must be sharp lies inside [near, far]; residual = the dioptres outside,
// relative to the actor's own (so 0.01 is 1 % of its distance). With follow = true the focus itself
// tracks the actor (a shot that asks nothing of the depth of field, whose camera moves).
struct SharpCost {
  SampleBase base;
  Eigen::Vector3d aim_enu_m;
  double coc_m = 0.03e-3;
  bool follow = false;
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    using std::abs;
    const Vec3T<T> p = CameraPoint(base, s, aim_enu_m);
    const T depth = p[2] > T(0.05) ? p[2] : T(0.05);
    if (follow) {
      r[0] = weight * (depth * s.dioptre - T(1));
      return true;
    }
    const T focal_m = FocalLengthMm(base, s) * 1e-3;
    const T half = DepthOfFieldHalfWidthDioptres(focal_m, FNumber(base, s), s.dioptre, coc_m);
    r[0] = weight * depth * Hinge(abs(T(1) / depth - s.dioptre) - half);
    return true;
  }
  // The residual (the same number as Residuals) and its gradient in the channel values, written out
  // (tests/optimizer/cost_terms_test.cc checks it against automatic differentiation).
  void Gradients(const SampleState<double>& s, double* r, ValueGradient* g) const {
    const CameraPointJacobian cp = CameraPointWithJacobian(base, s, aim_enu_m);
    const bool clamped = !(cp.p[2] > 0.05);
    const double depth = clamped ? 0.05 : cp.p[2];
    double d_depth[5];  // depth's gradient in position, yaw, tilt
    for (int f = 0; f < 5; ++f) d_depth[f] = clamped ? 0.0 : cp.d(2, f);
    std::fill(g[0], g[0] + kNumChannels, 0.0);
    if (follow) {
      r[0] = weight * (depth * s.dioptre - 1.0);
      for (int f = 0; f < 5; ++f) g[0][f] = weight * s.dioptre * d_depth[f];
      g[0][kDioptre] = weight * depth;
      return;
    }
    const double focal_m = FocalLengthMm(base, s) * 1e-3, f_number = FNumber(base, s);
    const double half = DepthOfFieldHalfWidthDioptres(focal_m, f_number, s.dioptre, coc_m);
    const double off = 1.0 / depth - s.dioptre;  // dioptres from the focus to the actor
    const double x = std::abs(off) - half;
    r[0] = weight * depth * Hinge(x);
    if (!(x > 0)) return;  // sharp: zero, with zero derivatives
    // half = N c0 / f^2 (1 - f D): d/dlog_f = -2 half - N c0 D / f, d/dstops = half ln2 / 2, d/dD = -N c0 / f
    const double sign = std::copysign(1.0, off);
    const double d_half_log_focal = -2.0 * half - f_number * coc_m * s.dioptre / focal_m;
    const double d_half_stops = half * 0.5 * std::log(2.0), d_half_dioptre = -f_number * coc_m / focal_m;
    // r = w depth x: dr = w (x ddepth + depth dx), dx = sign (-ddepth / depth^2 - dD) - dhalf
    for (int f = 0; f < 5; ++f) g[0][f] = weight * (x - sign / depth) * d_depth[f];
    g[0][kLogFocal] = -weight * depth * d_half_log_focal;
    g[0][kDioptre] = weight * depth * (-sign - d_half_dioptre);
    g[0][kStops] = -weight * depth * d_half_stops;
  }
};

// background blur: the blur circle of the background behind the subject (at background_behind_m beyond
// the subject's depth; infinity = 0 dioptres) at least goal_px pixels; residual = the missing fraction.
struct BackgroundBlurCost {
  SampleBase base;
  Eigen::Vector3d aim_enu_m;
  double background_behind_m = std::numeric_limits<double>::infinity();
  double goal_px = 10;
  double pixels_per_m = 1e5;  // on the sensor: width_px / sensor width
  double weight = 1;

  template <typename T>
  T BlurPx(const SampleState<T>& s) const {
    const Vec3T<T> p = CameraPoint(base, s, aim_enu_m);
    const T depth = p[2] > T(0.05) ? p[2] : T(0.05);
    const T background_dioptre = std::isinf(background_behind_m) ? T(0) : T(1) / (depth + T(background_behind_m));
    const T focal_m = FocalLengthMm(base, s) * 1e-3;
    return BlurCircleDiameterM(focal_m, FNumber(base, s), s.dioptre, background_dioptre) * pixels_per_m;
  }
  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    r[0] = weight * Hinge((T(goal_px) - BlurPx(s)) / goal_px);
    return true;
  }
  // The residual (the same number as Residuals) and its gradient in the channel values, written out
  // (tests/optimizer/cost_terms_test.cc checks it against automatic differentiation).
  void Gradients(const SampleState<double>& s, double* r, ValueGradient* g) const {
    const CameraPointJacobian cp = CameraPointWithJacobian(base, s, aim_enu_m);
    const bool clamped = !(cp.p[2] > 0.05);
    const double depth = clamped ? 0.05 : cp.p[2];
    const bool at_infinity = std::isinf(background_behind_m);
    const double background_dioptre = at_infinity ? 0.0 : 1.0 / (depth + background_behind_m);
    const double focal_m = FocalLengthMm(base, s) * 1e-3, f_number = FNumber(base, s);
    const double blur_px =
        BlurCircleDiameterM(focal_m, f_number, s.dioptre, background_dioptre) * pixels_per_m;  // as BlurPx
    const double missing = (goal_px - blur_px) / goal_px;
    r[0] = weight * Hinge(missing);
    std::fill(g[0], g[0] + kNumChannels, 0.0);
    if (!(missing > 0)) return;  // blurred enough: zero, with zero derivatives
    // blur = f^2 / N |D - B| / (1 - f D) (pixels): d/dlog_f = blur (2 + f D / (1 - f D)), d/dstops = -blur ln2 / 2,
    // d/dD = f^2 / N / (1 - f D) (sign + |D - B| f / (1 - f D)), d/dB = -f^2 / N / (1 - f D) sign
    const double across = s.dioptre - background_dioptre, sign = std::copysign(1.0, across);
    const double denominator = 1.0 - focal_m * s.dioptre;
    const double scale = focal_m * focal_m / f_number / denominator * pixels_per_m;
    const double d_log_focal = blur_px * (2.0 + focal_m * s.dioptre / denominator);
    const double d_stops = -blur_px * 0.5 * std::log(2.0);
    const double d_dioptre = scale * (sign + std::abs(across) * focal_m / denominator);
    // B = 1 / (depth + behind): dB/ddepth = -B^2
    const double d_depth = clamped || at_infinity ? 0.0 : -scale * sign * -(background_dioptre * background_dioptre);
    const double w = -weight / goal_px;  // r = w' (goal - blur) / goal
    for (int f = 0; f < 5; ++f) g[0][f] = w * d_depth * cp.d(2, f);
    g[0][kLogFocal] = w * d_log_focal;
    g[0][kDioptre] = w * d_dioptre;
    g[0][kStops] = w * d_stops;
  }
};

// The limits a sample must keep (the drone's and the lens's), each as a hinge on the fraction by
// which it is exceeded. Rates add the planned path's finite-difference rate and the change's own.
struct LimitsCost {
  static constexpr int kNumResiduals = 19;
  SampleBase base;
  DroneProfile drone;
  CameraSpec camera;
  double takeoff_up_m = 0;
  double margin = 0.02;  // aim at (1 - margin) of each limit
  double weight = 1;
  bool raw = false;  // the hinges' arguments instead of the hinges (Headroom)
  // The augmented Lagrangian's shifts (docs/optimize.md, "Limits as constraints"): residual i is
  // weight max(0, argument_i + shift_i), shift_i = multiplier_i / weight^2, updated by UpdateShifts.
  std::array<double, kNumResiduals> shift{};
  // The channels the change may move at this sample: only their limits get multipliers (a limit of a
  // channel that does not move is a constant, and one aimed inside an empty range, as a prime lens's focal
  // range at (1 - margin), would grow its multiplier for ever).
  std::array<bool, kNumChannels> free = {true, true, true, true, true, true, true, true};

  // The feasibility check's name of each residual's limit (core/feasibility.h).
  static constexpr const char* kLimitName[kNumResiduals] = {
      "horizontal_speed", "climb_rate",        "descent_rate",       "horizontal_acceleration", "jerk",
      "yaw_rate",         "gimbal_pitch_rate", "focal_length_rate",  "aperture_rate",           "gimbal_pitch_min",
      "gimbal_pitch_max", "altitude_min",      "altitude_max",       "focal_length_min",        "focal_length_max",
      "f_number_min",     "f_number_max",      "focus_distance_min", "focus_beyond_infinity"};
  // The channel each residual moves with (kEast standing for the position).
  static constexpr int kChannelOf[kNumResiduals] = {kEast,     kEast,  kEast,  kEast,    kEast,   kYaw, kTilt,
                                                    kLogFocal, kStops, kTilt,  kTilt,    kUp,     kUp,  kLogFocal,
                                                    kLogFocal, kStops, kStops, kDioptre, kDioptre};

  // How near the sample, with the change `k`, is to a limit it can move towards: the largest hinge
  // argument (how far past the aimed value, per unit of the limit; per 10 units for the focus, whose
  // arguments are dioptres over the closest focus's) among the residuals whose channel is free. Negative:
  // those limits hold with room to spare, and their residuals and derivatives are zero.
  double Headroom(const double* const* k, const std::array<bool, kNumChannels>& free) const {
    LimitsCost measure = *this;
    measure.raw = true;
    measure.weight = 1;
    double r[kNumResiduals];
    measure(k[0], k[1], k[2], k[3], r);
    double most = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < kNumResiduals; ++i) {
      if (free[kChannelOf[i]]) most = std::max(most, kChannelOf[i] == kDioptre ? 10 * r[i] : r[i]);
    }
    return most;
  }
  // Its cost (half the sum of the squared residuals, as Ceres counts it) with the change `k`.
  double Cost(const double* const* k) const {
    double r[kNumResiduals];
    (*this)(k[0], k[1], k[2], k[3], r);
    double cost = 0;
    for (double v : r) cost += 0.5 * v * v;
    return cost;
  }
  // The multiplier update after a solve ended at `k`: shift_i = max(0, shift_i + argument_i). Returns the
  // largest argument (how far past its aimed value the worst limit is, per unit of the limit).
  double UpdateShifts(const double* const* k) {
    LimitsCost measure = *this;
    measure.raw = true;
    double a[kNumResiduals];
    measure(k[0], k[1], k[2], k[3], a);
    double most = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < kNumResiduals; ++i) {
      if (!free[kChannelOf[i]]) continue;
      shift[i] = std::max(0.0, shift[i] + a[i]);
      most = std::max(most, a[i]);
    }
    return most;
  }

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    constexpr double kDeg = 180.0 / M_PI;
    const double m = 1.0 - margin;
    const auto over = [&](const T& value, double limit) { return (value - T(limit * m)) / limit; };
    const auto under = [&](const T& value, double limit, double scale) {
      return (T(limit) - value) / scale + T(margin);
    };
    // The hinges' arguments first (minus infinity: no such limit at this sample), then the residuals.
    for (int i = 0; i < kNumResiduals; ++i) r[i] = T(-std::numeric_limits<double>::infinity());
    if (base.has_rates) {
      const Vec3T<T> v = base.velocity_m_s.cast<T>() + s.velocity;
      const Vec3T<T> a = base.acceleration_m_s2.cast<T>() + s.acceleration;
      r[0] = over(SafeNorm2(v[0], v[1]), drone.max_horizontal_speed_m_s);
      r[1] = over(v[2], drone.max_climb_rate_m_s);
      r[2] = over(-v[2], drone.max_descent_rate_m_s);
      r[3] = over(SafeNorm2(a[0], a[1]), drone.max_acceleration_m_s2);
      if (base.has_jerk) r[4] = over(SafeNorm(Vec3T<T>(base.jerk_m_s3.cast<T>() + s.jerk)), drone.max_jerk_m_s3);
      const T heading_rate = T(base.heading_rate_deg_s) - s.yaw_rate * kDeg;
      r[5] = over(SafeNorm2(heading_rate, T(0)), drone.max_yaw_rate_deg_s);
      const T pitch_rate = T(base.pitch_rate_deg_s) + s.tilt_rate * kDeg;
      r[6] = over(SafeNorm2(pitch_rate, T(0)), drone.max_gimbal_pitch_rate_deg_s);
      const T focal_rate = T(base.focal_rate_mm_s) + FocalLengthMm(base, s) * s.log_focal_rate;
      r[7] = over(SafeNorm2(focal_rate, T(0)), camera.max_focal_rate_mm_s);
      const T aperture_rate = T(base.aperture_rate_stops_s) + s.stops_rate;
      r[8] = over(SafeNorm2(aperture_rate, T(0)), camera.max_aperture_rate_stops_s);
    }
    const T pitch = T(base.pitch_deg) + s.tilt * kDeg;
    r[9] = under(pitch, drone.min_gimbal_pitch_deg, 90.0);
    r[10] = (pitch - T(drone.max_gimbal_pitch_deg)) / 90.0 + T(margin);
    const T altitude = s.position[2] - T(takeoff_up_m);
    r[11] = under(altitude, drone.min_altitude_m, std::max(drone.min_altitude_m, 10.0));
    r[12] = over(altitude, drone.max_altitude_m);
    const T focal = FocalLengthMm(base, s);
    r[13] = under(focal, camera.min_focal_length_mm, camera.min_focal_length_mm);
    r[14] = over(focal, camera.max_focal_length_mm);
    const T f_number = FNumber(base, s);
    r[15] = under(f_number, camera.min_f_number, camera.min_f_number);
    r[16] = over(f_number, camera.max_f_number);
    const double max_dioptre = 1.0 / camera.min_focus_distance_m;
    r[17] = over(s.dioptre, max_dioptre);
    r[18] = -s.dioptre / max_dioptre;  // focus beyond infinity
    if (raw) return true;
    for (int i = 0; i < kNumResiduals; ++i) r[i] = weight * Hinge(r[i] + T(shift[i]));
    return true;
  }
  // The gradients of the residuals `only` names (active hinges: weight (argument + shift) > 0) in the state's
  // fields, in optimizer/state_cost_function.h's kValuesAndRates order (the 8 channel values, their 8 first
  // derivatives, the path's acceleration and jerk): weight times the argument's gradient, written out, since
  // each hinge reads one to three of the 22 fields. Rows not named are left as they are.
  // tests/optimizer/state_cost_function_test.cc checks every hinge against automatic differentiation.
  void ActiveGradients(const SampleState<double>& s, const bool* only, double (*g)[2 * kNumChannels + 6]) const {
    constexpr double kDeg = 180.0 / M_PI;
    constexpr int kRate = kNumChannels, kAccel = 2 * kNumChannels, kJerk = 2 * kNumChannels + 3;
    const auto row = [&](int i) -> double* {
      if (!only[i]) return nullptr;
      std::fill(g[i], g[i] + 2 * kNumChannels + 6, 0.0);
      return g[i];
    };
    const auto norm = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z + 1e-12); };
    if (base.has_rates) {
      const Eigen::Vector3d v = base.velocity_m_s + s.velocity, a = base.acceleration_m_s2 + s.acceleration;
      if (double* d = row(0)) {
        const double n = norm(v[0], v[1], 0) * drone.max_horizontal_speed_m_s;
        d[kRate + kEast] = v[0] / n;
        d[kRate + kNorth] = v[1] / n;
      }
      if (double* d = row(1)) d[kRate + kUp] = 1.0 / drone.max_climb_rate_m_s;
      if (double* d = row(2)) d[kRate + kUp] = -1.0 / drone.max_descent_rate_m_s;
      if (double* d = row(3)) {
        const double n = norm(a[0], a[1], 0) * drone.max_acceleration_m_s2;
        d[kAccel] = a[0] / n;
        d[kAccel + 1] = a[1] / n;
      }
      if (double* d = base.has_jerk ? row(4) : nullptr) {
        const Eigen::Vector3d j = base.jerk_m_s3 + s.jerk;
        const double n = norm(j[0], j[1], j[2]) * drone.max_jerk_m_s3;
        for (int c = 0; c < 3; ++c) d[kJerk + c] = j[c] / n;
      }
      if (double* d = row(5)) {
        const double rate = base.heading_rate_deg_s - s.yaw_rate * kDeg;
        d[kRate + kYaw] = rate / norm(rate, 0, 0) * -kDeg / drone.max_yaw_rate_deg_s;
      }
      if (double* d = row(6)) {
        const double rate = base.pitch_rate_deg_s + s.tilt_rate * kDeg;
        d[kRate + kTilt] = rate / norm(rate, 0, 0) * kDeg / drone.max_gimbal_pitch_rate_deg_s;
      }
      if (double* d = row(7)) {
        const double focal = FocalLengthMm(base, s), rate = base.focal_rate_mm_s + focal * s.log_focal_rate;
        const double along = rate / norm(rate, 0, 0) / camera.max_focal_rate_mm_s;
        d[kLogFocal] = along * focal * s.log_focal_rate;
        d[kRate + kLogFocal] = along * focal;
      }
      if (double* d = row(8)) {
        const double rate = base.aperture_rate_stops_s + s.stops_rate;
        d[kRate + kStops] = rate / norm(rate, 0, 0) / camera.max_aperture_rate_stops_s;
      }
    }
    if (double* d = row(9)) d[kTilt] = -kDeg / 90.0;
    if (double* d = row(10)) d[kTilt] = kDeg / 90.0;
    if (double* d = row(11)) d[kUp] = -1.0 / std::max(drone.min_altitude_m, 10.0);
    if (double* d = row(12)) d[kUp] = 1.0 / drone.max_altitude_m;
    if (double* d = row(13)) d[kLogFocal] = -FocalLengthMm(base, s) / camera.min_focal_length_mm;
    if (double* d = row(14)) d[kLogFocal] = FocalLengthMm(base, s) / camera.max_focal_length_mm;
    if (double* d = row(15)) d[kStops] = -FNumber(base, s) * 0.5 * std::log(2.0) / camera.min_f_number;
    if (double* d = row(16)) d[kStops] = FNumber(base, s) * 0.5 * std::log(2.0) / camera.max_f_number;
    if (double* d = row(17)) d[kDioptre] = camera.min_focus_distance_m;  // 1 / the largest dioptre
    if (double* d = row(18)) d[kDioptre] = -camera.min_focus_distance_m;
    for (int i = 0; i < kNumResiduals; ++i) {
      if (!only[i]) continue;
      for (double& d : g[i]) d *= weight;
    }
  }
};

// The augmented Lagrangian's multiplier update of a one-residual constraint functor with `raw` and
// `shift` members: shift = max(0, shift + argument). Returns the argument over `scale`.
template <typename Functor>
double UpdateShift(Functor& f, const double* const* k, double scale) {
  Functor measure = f;
  measure.raw = true;
  double argument = 0;
  measure(k[0], k[1], k[2], k[3], &argument);
  f.shift = std::max(0.0, f.shift + argument);
  return argument / scale;
}

// keep-out: the camera at least min_subject_distance_m from an actor (a vertical segment from its base
// to its height), as the feasibility check measures it.
struct KeepOutCost {
  SampleBase base;
  Eigen::Vector3d subject_base_enu_m;
  double subject_height_m = 1.8;
  double min_distance_m = 2;
  double margin = 0.02;
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    Vec3T<T> d = s.position - subject_base_enu_m.cast<T>();
    const T top = T(subject_height_m);
    d[2] = d[2] < T(0) ? d[2] : (d[2] > top ? d[2] - top : T(0));
    r[0] = T(min_distance_m * (1.0 + margin)) - SafeNorm(d);  // metres short of the distance aimed at
    if (!raw) r[0] = weight * Hinge(r[0] + T(shift)) / min_distance_m;
    return true;
  }
  bool raw = false;  // the hinge's argument instead of the residual
  double shift = 0;  // the augmented Lagrangian's shift (metres), as LimitsCost's
  // The multiplier update; returns the argument per unit of the distance.
  double UpdateShifts(const double* const* k) { return UpdateShift(*this, k, min_distance_m); }
};

// out_of_shot (several drones): a drone's body, a sphere, outside another drone's live frame. Either this
// drone is the body and the viewer is held fixed (`this_drone_views` false: `other_enu_m` is the viewer,
// with its orientation and focal length), or this drone's camera is the viewer and the other drone's
// body is held fixed (`other_enu_m` is the body; this sample's pose and focal length are the camera's).
// The residual is how far (metres at the body's depth) the sphere reaches into the frame past its
// nearest edge, so the cheapest way out is across that edge. Behind the camera is out.
struct OutOfShotCost {
  SampleBase base;
  bool this_drone_views = false;
  Eigen::Vector3d other_enu_m;
  Eigen::Matrix3d viewer_camera_from_world = Eigen::Matrix3d::Identity();  // this_drone_views false only
  double viewer_focal_length_mm = 24;                                      // this_drone_views false only
  double image_width_mm = 24.89, image_height_mm = 14;
  double body_radius_m = 0.4;
  double margin = 0.02;
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    using std::abs;
    Vec3T<T> c;
    T f_mm;
    if (this_drone_views) {
      c = CameraPoint(base, s, other_enu_m);
      f_mm = FocalLengthMm(base, s);
    } else {
      c = viewer_camera_from_world.cast<T>() * (s.position - other_enu_m.cast<T>());
      f_mm = T(viewer_focal_length_mm);
    }
    if (c[2] <= T(body_radius_m)) {
      r[0] = T(raw ? -std::numeric_limits<double>::infinity() : 0.0);
      return true;
    }
    const T reach = T(body_radius_m * (1.0 + margin) + margin);
    const T inside_x = T(0.5 * image_width_mm) / f_mm * c[2] + reach - abs(c[0]);
    const T inside_y = T(0.5 * image_height_mm) / f_mm * c[2] + reach - abs(c[1]);
    r[0] = inside_x < inside_y ? inside_x : inside_y;
    if (!raw) r[0] = weight * Hinge(r[0] + T(shift));
    return true;
  }
  bool raw = false;  // the hinge's argument instead of the residual
  double shift = 0;  // the augmented Lagrangian's shift (metres), as LimitsCost's
  double UpdateShifts(const double* const* k) { return UpdateShift(*this, k, 1.0); }
};

// smoothness: over one spline segment, the jerk and the acceleration of the path change and the rates
// and accelerations of the angle and lens changes (at the segment's middle), each over a reference scale, times sqrt(h)
// so that the sum over segments approximates an integral over time whatever the knot spacing.
struct SmoothnessCost {
  static constexpr int kNumResiduals = 16;
  double segment_s = 0.5;
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const double h = segment_s;
    const double w = weight * std::sqrt(h);
    const auto jerk = [&](int c) { return (-k0[c] + 3.0 * k1[c] - 3.0 * k2[c] + k3[c]) / (h * h * h); };
    const auto accel = [&](int c) { return (k0[c] - k1[c] - k2[c] + k3[c]) / (2.0 * h * h); };
    const auto rate = [&](int c) { return (-k0[c] - 5.0 * k1[c] + 5.0 * k2[c] + k3[c]) / (8.0 * h); };
    for (int c = 0; c < 3; ++c) r[c] = w * jerk(c) / 1.0;  // m/s^3
    r[3] = w * accel(kYaw) / 0.1;                          // rad/s^2
    r[4] = w * accel(kTilt) / 0.1;
    r[5] = w * accel(kLogFocal) / 0.1;  // e-folds/s^2
    r[6] = w * accel(kDioptre) / 0.01;  // dioptres/s^2
    r[7] = w * accel(kStops) / 0.5;     // stops/s^2
    r[8] = w * rate(kYaw) / 0.5;        // rad/s
    r[9] = w * rate(kTilt) / 0.5;
    r[10] = w * rate(kLogFocal) / 0.5;
    r[11] = w * rate(kDioptre) / 0.05;
    r[12] = w * rate(kStops) / 1.0;
    for (int c = 0; c < 3; ++c) r[13 + c] = w * accel(c) / 1.0;  // m/s^2: jerk alone rings around a pull
    return true;
  }
};

// adherence, per knot: a gentle pull of the path change back to zero, a stiff hinge beyond the shot's
// max_deviation_m (the spline is a convex blend of its knots, so bounding the knots bounds the path),
// and a small ridge on every other channel.
struct AdherenceCost {
  static constexpr int kNumResiduals = 9;
  double max_deviation_m = 5;
  double adherence_weight = 0.05;
  double deviation_weight = 200;
  double ridge_weight = 1e-3;

  template <typename T>
  bool operator()(const T* k, T* r) const {
    const Vec3T<T> d(k[kEast], k[kNorth], k[kUp]);
    for (int c = 0; c < 3; ++c) r[c] = adherence_weight * d[c];
    r[3] = deviation_weight * Hinge(SafeNorm(d) - T(max_deviation_m) + T(shift));
    for (int c = kYaw; c < kNumChannels; ++c) r[c + 1] = ridge_weight * k[c];
    return true;
  }
  double shift = 0;  // the augmented Lagrangian's shift on the deviation (metres), as LimitsCost's
  // The multiplier update; returns the metres past the deviation allowed.
  double UpdateShifts(const double* k) {
    const double past = Eigen::Vector3d(k[kEast], k[kNorth], k[kUp]).norm() - max_deviation_m;
    shift = std::max(0.0, shift + past);
    return past;
  }
};

// occlusion: a pull towards the nearest viewpoint from which the subject's aim point is in plain view
// (optimizer/visibility_targets.h finds it by ray casting; the targets are refreshed between rounds).
struct ClearViewCost {
  SampleBase base;
  Eigen::Vector3d target_enu_m;
  double weight = 1;

  template <typename T>
  bool operator()(const T* k0, const T* k1, const T* k2, const T* k3, T* r) const {
    const T* k[4] = {k0, k1, k2, k3};
    return Residuals(EvaluateSample(base, k), r);
  }
  // The residuals at the sample's state (optimizer/state_cost_function.h differentiates this).
  template <typename T>
  bool Residuals(const SampleState<T>& s, T* r) const {
    for (int c = 0; c < 3; ++c) r[c] = weight * (s.position[c] - target_enu_m[c]);
    return true;
  }
};

}  // namespace cinepath::optimizer
