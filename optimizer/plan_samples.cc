#include "optimizer/plan_samples.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "core/error.h"
#include "core/number_format.h"

namespace cinepath::optimizer {
namespace {

double WrapDeg(double d) {
  d = std::fmod(d + 180.0, 360.0);
  if (d < 0) d += 360.0;
  return d - 180.0;
}

void CheckFinite(const TrajectorySample& s, size_t k, const std::string& source) {
  const bool ok = s.position_enu_m.allFinite() && std::isfinite(s.focal_length_mm) && s.focal_length_mm > 0 &&
                  std::isfinite(s.f_number) && s.f_number > 0 && !std::isnan(s.focus_distance_m) &&
                  s.focus_distance_m > 0 && s.world_from_camera.coeffs().allFinite();
  if (!ok) throw InputError(source + ": samples[" + std::to_string(k) + "]: a non-finite or non-positive value");
}

}  // namespace

PlanSamples SplitPlan(const Trajectory& plan, double knot_spacing_s, const std::string& source, bool allow_refit) {
  const size_t n = plan.samples.size();
  if (n == 0) throw InputError(source + ": samples: the plan has no samples");
  PlanSamples out;
  std::map<std::string, int> shot_index;
  for (size_t i = 0; i < plan.shots.size(); ++i) shot_index.emplace(plan.shots[i].name, static_cast<int>(i));
  out.shot_of_sample.assign(n, -1);
  out.cut_before.assign(n, false);
  for (size_t k = 0; k < n; ++k) {
    CheckFinite(plan.samples[k], k, source);
    const auto it = shot_index.find(plan.samples[k].shot);
    if (it == shot_index.end() && !plan.shots.empty()) {
      throw InputError(source + ": samples[" + std::to_string(k) + "].shot: no shot named \"" + plan.samples[k].shot +
                       "\"");
    }
    if (it != shot_index.end()) out.shot_of_sample[k] = it->second;
    if (k > 0 && out.shot_of_sample[k] != out.shot_of_sample[k - 1] && out.shot_of_sample[k] >= 0) {
      // Every shot from the previous sample's (exclusive) to this one's: a cut anywhere between cuts here.
      for (int j = std::max(out.shot_of_sample[k - 1] + 1, 0); j <= out.shot_of_sample[k]; ++j) {
        if (plan.shots[j].transition == "cut") out.cut_before[k] = true;
      }
    }
  }

  // Groups between cuts, and their knots.
  size_t start = 0;
  for (size_t k = 1; k <= n; ++k) {
    if (k < n && !out.cut_before[k]) continue;
    SampleGroup g;
    g.first_sample = start;
    g.end_sample = k;
    g.first_knot = out.num_knots;
    g.spline = KnotSpline(plan.samples[start].time_s, plan.samples[k - 1].time_s, knot_spacing_s);
    out.num_knots += g.spline.num_knots();
    out.groups.push_back(g);
    start = k;
  }
  out.group_of_sample.assign(n, 0);
  for (size_t gi = 0; gi < out.groups.size(); ++gi) {
    for (size_t k = out.groups[gi].first_sample; k < out.groups[gi].end_sample; ++k) out.group_of_sample[k] = gi;
  }

  // Bases, with the planned path's rates by finite differences inside the group (indices clamped to it:
  // one-sided at its ends), as the feasibility check takes them.
  const double dt = 1.0 / plan.frame_rate_hz;
  out.bases.resize(n);
  for (const SampleGroup& g : out.groups) {
    const long first = static_cast<long>(g.first_sample), last = static_cast<long>(g.end_sample) - 1;
    const auto at = [&](long i) -> const TrajectorySample& { return plan.samples[std::clamp(i, first, last)]; };
    for (long i = first; i <= last; ++i) {
      const TrajectorySample& s = plan.samples[i];
      SampleBase& b = out.bases[i];
      b.knots = g.spline.At(s.time_s);
      b.knots.first_knot += g.first_knot;
      b.position_enu_m = s.position_enu_m;
      b.world_from_camera = s.world_from_camera.normalized();
      b.camera_from_world = b.world_from_camera.conjugate().toRotationMatrix();
      b.focal_length_mm = s.focal_length_mm;
      b.dioptre = std::isinf(s.focus_distance_m) ? 0.0 : 1.0 / s.focus_distance_m;
      b.f_number = s.f_number;
      b.pitch_deg = s.gimbal_pitch_deg;
      b.has_rates = last > first;
      b.has_jerk = last - first >= 3;
      if (!b.has_rates) continue;
      const Eigen::Vector3d pm = at(i - 1).position_enu_m, p0 = s.position_enu_m, pp = at(i + 1).position_enu_m;
      const double span = static_cast<double>(std::clamp(i + 1, first, last) - std::clamp(i - 1, first, last));
      b.velocity_m_s = (pp - pm) / (span * dt);
      b.acceleration_m_s2 =
          (i > first && i < last) ? Eigen::Vector3d((pp - 2 * p0 + pm) / (dt * dt)) : Eigen::Vector3d::Zero();
      if (b.has_jerk) {
        const long j0 = std::clamp(i - 1, first, last - 3);
        b.jerk_m_s3 = (plan.samples[j0 + 3].position_enu_m - 3 * plan.samples[j0 + 2].position_enu_m +
                       3 * plan.samples[j0 + 1].position_enu_m - plan.samples[j0].position_enu_m) /
                      (dt * dt * dt);
      }
      const long b0 = i > first ? i - 1 : i, b1 = i > first ? i : i + 1;  // backward differences
      const TrajectorySample &s0 = plan.samples[b0], &s1 = plan.samples[b1];
      b.heading_rate_deg_s = WrapDeg(s1.drone_heading_deg - s0.drone_heading_deg) / dt;
      b.pitch_rate_deg_s = (s1.gimbal_pitch_deg - s0.gimbal_pitch_deg) / dt;
      b.focal_rate_mm_s = (s1.focal_length_mm - s0.focal_length_mm) / dt;
      b.aperture_rate_stops_s = 2.0 * std::log2(s1.f_number / s0.f_number) / dt;
    }
  }
  // Groups whose planned path breaks the acceleration or jerk limit start from their C2 fit.
  for (SampleGroup& g : out.groups) {
    for (size_t i = g.first_sample; i < g.end_sample && allow_refit && !g.refit; ++i) {
      const SampleBase& b = out.bases[i];
      g.refit = b.acceleration_m_s2.head<2>().norm() > plan.drone.max_acceleration_m_s2 ||
                (b.has_jerk && b.jerk_m_s3.norm() > plan.drone.max_jerk_m_s3);
    }
    if (!g.refit) continue;
    const std::vector<Eigen::Vector3d> control = FitGroupPath(plan, g);
    for (size_t i = g.first_sample; i < g.end_sample; ++i) {
      SampleBase& b = out.bases[i];
      const int first = b.knots.first_knot - g.first_knot;
      b.position_enu_m.setZero();
      b.velocity_m_s.setZero();
      b.acceleration_m_s2.setZero();
      b.jerk_m_s3.setZero();
      for (int j = 0; j < 4; ++j) {
        b.position_enu_m += b.knots.value[j] * control[first + j];
        b.velocity_m_s += b.knots.d1[j] * control[first + j];
        b.acceleration_m_s2 += b.knots.d2[j] * control[first + j];
        b.jerk_m_s3 += b.knots.d3[j] * control[first + j];
      }
    }
  }
  return out;
}

std::vector<Eigen::Vector3d> FitGroupPath(const Trajectory& plan, const SampleGroup& group) {
  const int m = group.spline.num_knots();
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(m, 3);
  for (size_t i = group.first_sample; i < group.end_sample; ++i) {
    const KnotWeights w = group.spline.At(plan.samples[i].time_s);
    for (int a = 0; a < 4; ++a) {
      rhs.row(w.first_knot + a) += w.value[a] * plan.samples[i].position_enu_m.transpose();
      for (int b = 0; b < 4; ++b) triplets.emplace_back(w.first_knot + a, w.first_knot + b, w.value[a] * w.value[b]);
    }
  }
  // A tiny third-difference penalty keeps the system definite where no sample pins a knot.
  const double lambda = 1e-6;
  const double d3[4] = {-1, 3, -3, 1};
  for (int s = 0; s + 3 < m; ++s) {
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) triplets.emplace_back(s + a, s + b, lambda * d3[a] * d3[b]);
    }
  }
  Eigen::SparseMatrix<double> normal(m, m);
  normal.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
  if (solver.info() != Eigen::Success) throw RuntimeError("optimize: the path fit is singular");
  const Eigen::MatrixXd control = solver.solve(rhs);
  std::vector<Eigen::Vector3d> out(m);
  for (int j = 0; j < m; ++j) out[j] = control.row(j).transpose();
  return out;
}

}  // namespace cinepath::optimizer
