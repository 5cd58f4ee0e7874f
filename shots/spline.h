// Position curves through timed keyframes (ENU metres against seconds).
//
//   linear        piecewise linear; C0.
//   catmull_rom   centripetal Catmull-Rom (alpha = 1/2, Barry-Goldman evaluation) through the keys,
//                 C1 in its own knot parameter s; time maps to s through a monotone C1 cubic
//                 (Fritsch-Carlson) through (t_i, s_i), so the flight is C1 in time and passes each
//                 key at its time. The end tangents use reflected phantom points.
//   cubic_bspline the interpolating cubic B-spline with natural end conditions (second derivative 0
//                 at the ends), built per coordinate in time: C2 in time, through every key.
// Outside [t_first, t_last] the curve holds its end point (velocity 0).
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace cinepath::shots {

enum class PathInterpolation { kLinear, kCatmullRom, kCubicBSpline };

std::string_view PathInterpolationName(PathInterpolation p);
std::optional<PathInterpolation> PathInterpolationFromName(std::string_view name);  // also "bspline"

class PathSpline {
 public:
  // times strictly increasing, same count as points, at least one key. Throws InputError otherwise.
  PathSpline(std::vector<double> times_s, std::vector<Eigen::Vector3d> points_enu_m, PathInterpolation kind);

  Eigen::Vector3d Position(double time_s) const;
  Eigen::Vector3d Velocity(double time_s) const;  // analytic where available, m/s

  const std::vector<double>& times() const { return t_; }
  PathInterpolation kind() const { return kind_; }

 private:
  size_t Segment(double time_s) const;
  Eigen::Vector3d CatmullRom(size_t segment, double s) const;
  double KnotParameter(size_t segment, double time_s, double* ds_dt) const;

  std::vector<double> t_;
  std::vector<Eigen::Vector3d> p_;
  PathInterpolation kind_;
  // Catmull-Rom: knot parameters (with phantom points at both ends) and the time->knot slopes.
  std::vector<Eigen::Vector3d> cr_points_;  // p_ with a phantom point prepended and appended
  std::vector<double> cr_knots_;
  std::vector<double> knot_slopes_;  // ds/dt at each key
  // Cubic spline: second derivatives at each key.
  std::vector<Eigen::Vector3d> m_;
};

}  // namespace cinepath::shots
