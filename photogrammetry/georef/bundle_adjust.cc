#include "photogrammetry/georef/bundle_adjust.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include <ceres/ceres.h>

#include "core/ceres_logging.h"
#include "core/error.h"
#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

constexpr int kMaxParams = 12;  // camera blocks are padded to the largest COLMAP model

// Reprojection of a point into an image.
// Parameters: q = cam_from_enu rotation, Eigen coefficient order (x, y, z, w); c = camera centre (ENU m);
// p = point (ENU m); k = camera parameters (COLMAP order, padded to 12).
// Residual (px): project(k, (R (p - c)).xy / (R (p - c)).z) - observed.
struct ReprojectionError {
  ReprojectionError(int model_id, const Eigen::Vector2d& observed_px) : model_id(model_id), observed(observed_px) {}

  template <typename T>
  bool operator()(const T* q, const T* c, const T* p, const T* k, T* residual) const {
    const Eigen::Map<const Eigen::Quaternion<T>> rotation(q);
    const Eigen::Matrix<T, 3, 1> x_cam =
        rotation * (Eigen::Map<const Eigen::Matrix<T, 3, 1>>(p) - Eigen::Map<const Eigen::Matrix<T, 3, 1>>(c));
    if (!(x_cam.z() > T(1e-12))) return false;
    const T u = x_cam.x() / x_cam.z();
    const T v = x_cam.y() / x_cam.z();
    T x, y;
    if (!ProjectNormalizedToPixel(model_id, k, u, v, &x, &y)) return false;
    residual[0] = x - T(observed.x());
    residual[1] = y - T(observed.y());
    return true;
  }

  static ceres::CostFunction* Create(int model_id, const Eigen::Vector2d& observed_px) {
    return new ceres::AutoDiffCostFunction<ReprojectionError, 2, 4, 3, 3, kMaxParams>(
        new ReprojectionError(model_id, observed_px));
  }

  int model_id;
  Eigen::Vector2d observed;
};

// Position prior on a camera centre (GPS) or a control point (survey):
// ((c - c_gps).x / sh, (c - c_gps).y / sh, (c - c_gps).z / sv).
struct CenterPriorError {
  template <typename T>
  bool operator()(const T* c, T* residual) const {
    residual[0] = (c[0] - T(gps.x())) / T(sigma_h);
    residual[1] = (c[1] - T(gps.y())) / T(sigma_h);
    residual[2] = (c[2] - T(gps.z())) / T(sigma_v);
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector3d& gps, double sigma_h, double sigma_v) {
    return new ceres::AutoDiffCostFunction<CenterPriorError, 3, 3>(new CenterPriorError{gps, sigma_h, sigma_v});
  }
  Eigen::Vector3d gps;
  double sigma_h, sigma_v;
};

// Prior on one focal parameter: (k[index] - prior) / sigma.
struct FocalPriorError {
  template <typename T>
  bool operator()(const T* k, T* residual) const {
    residual[0] = (k[index] - T(prior_px)) / T(sigma_px);
    return true;
  }
  static ceres::CostFunction* Create(int index, double prior_px, double sigma_px) {
    return new ceres::AutoDiffCostFunction<FocalPriorError, 1, kMaxParams>(
        new FocalPriorError{index, prior_px, sigma_px});
  }
  int index;
  double prior_px, sigma_px;
};

struct Observation {
  size_t image;  // index into State::images
  size_t point;  // index into State::points
  Eigen::Vector2d xy_px;
};

struct State {
  std::vector<uint32_t> image_ids;
  std::vector<size_t> image_camera;              // index into cameras
  std::vector<std::array<double, 4>> rotations;  // x, y, z, w
  std::vector<std::array<double, 3>> centers;
  std::vector<uint32_t> camera_ids;
  std::vector<int> camera_models;
  std::vector<std::array<double, kMaxParams>> intrinsics;
  std::vector<uint64_t> point_ids;
  std::vector<std::array<double, 3>> points;
  std::vector<Observation> observations;
  // Control points: points[control_first + k] has the prior control[k].
  size_t control_first = 0;
  std::vector<ControlPointPrior> control;
};

// kPrior: free, with the prior at focal_prior_sigma_ratio; kMeasured: free, with the prior as the weak
// measured_focal_prior_sigma_ratio; kFixed: held.
enum class FocalMode { kPrior, kMeasured, kFixed };

struct SolveResult {
  double reprojection_cost = 0;  // 1/2 sum of robustified squared residuals (px^2)
  int iterations = 0;
  bool converged = false;
};

double MeanFocal(const State& s, size_t cam) {
  const auto idx = CameraModelFocalIndices(s.camera_models[cam]);
  double sum = 0;
  for (int i : idx) sum += s.intrinsics[cam][i];
  return sum / static_cast<double>(idx.size());
}

SolveResult Solve(State& s, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                  const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options, FocalMode mode,
                  int max_iterations) {
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  std::vector<ceres::ResidualBlockId> reprojection_blocks;
  reprojection_blocks.reserve(s.observations.size());
  for (const Observation& o : s.observations) {
    const size_t cam = s.image_camera[o.image];
    reprojection_blocks.push_back(problem.AddResidualBlock(
        ReprojectionError::Create(s.camera_models[cam], o.xy_px), new ceres::HuberLoss(options.reprojection_huber_px),
        s.rotations[o.image].data(), s.centers[o.image].data(), s.points[o.point].data(), s.intrinsics[cam].data()));
  }
  for (size_t i = 0; i < s.image_ids.size(); ++i) {
    if (!problem.HasParameterBlock(s.rotations[i].data())) continue;
    problem.SetManifold(s.rotations[i].data(), new ceres::EigenQuaternionManifold());
    const auto it = gps_enu_m.find(s.image_ids[i]);
    if (it != gps_enu_m.end()) {
      problem.AddResidualBlock(
          CenterPriorError::Create(it->second, options.gps_sigma_horizontal_m, options.gps_sigma_vertical_m), nullptr,
          s.centers[i].data());
    }
  }
  for (size_t k = 0; k < s.control.size(); ++k) {
    const ControlPointPrior& c = s.control[k];
    problem.AddResidualBlock(CenterPriorError::Create(c.target_enu_m, c.sigma_horizontal_m, c.sigma_vertical_m),
                             nullptr, s.points[s.control_first + k].data());
  }
  for (size_t cam = 0; cam < s.camera_ids.size(); ++cam) {
    double* k = s.intrinsics[cam].data();
    if (!problem.HasParameterBlock(k)) continue;
    const int model = s.camera_models[cam];
    const auto focal_idx = CameraModelFocalIndices(model);
    const auto prior = focal_prior_px.find(s.camera_ids[cam]);
    const bool focal_free = options.refine_focal && mode != FocalMode::kFixed;
    const double prior_sigma_ratio =
        mode == FocalMode::kMeasured ? options.measured_focal_prior_sigma_ratio : options.focal_prior_sigma_ratio;
    std::vector<int> constant;
    for (int i : CameraModelPrincipalPointIndices(model)) constant.push_back(i);
    if (!focal_free)
      for (int i : focal_idx) constant.push_back(i);
    if (!options.refine_distortion)
      for (int i : CameraModelExtraIndices(model)) constant.push_back(i);
    for (int i = CameraModelNumParams(model); i < kMaxParams; ++i) constant.push_back(i);
    if (static_cast<int>(constant.size()) == kMaxParams) {
      problem.SetParameterBlockConstant(k);
    } else {
      problem.SetManifold(k, new ceres::SubsetManifold(kMaxParams, constant));
    }
    if (focal_free && prior != focal_prior_px.end()) {
      for (int i : focal_idx) {
        problem.AddResidualBlock(FocalPriorError::Create(i, prior->second, prior_sigma_ratio * prior->second), nullptr,
                                 k);
      }
    }
  }

  ceres::Solver::Options solver_options;
  // Dense reduced camera system for survey-sized models; sparse (SuiteSparse) beyond.
  solver_options.linear_solver_type = s.image_ids.size() > 60 ? ceres::SPARSE_SCHUR : ceres::DENSE_SCHUR;
  solver_options.num_threads = 1;  // determinism: the Schur complement sums in a fixed order
  solver_options.max_num_iterations = max_iterations;
  solver_options.function_tolerance = 1e-6;
  solver_options.gradient_tolerance = 1e-12;
  solver_options.parameter_tolerance = 1e-10;
  solver_options.logging_type = ceres::SILENT;
  QuietCeresLogging();
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  SolveResult result;
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  ceres::Problem::EvaluateOptions eval;
  eval.residual_blocks = reprojection_blocks;
  eval.apply_loss_function = true;
  eval.num_threads = 1;
  problem.Evaluate(eval, &result.reprojection_cost, nullptr, nullptr, nullptr);
  return result;
}

double RmsReprojection(const State& s) {
  double sum = 0;
  for (const Observation& o : s.observations) {
    const size_t cam = s.image_camera[o.image];
    ReprojectionError e(s.camera_models[cam], o.xy_px);
    double r[2];
    if (!e(s.rotations[o.image].data(), s.centers[o.image].data(), s.points[o.point].data(), s.intrinsics[cam].data(),
           r)) {
      continue;
    }
    sum += r[0] * r[0] + r[1] * r[1];
  }
  return s.observations.empty() ? 0 : std::sqrt(sum / static_cast<double>(s.observations.size()));
}

State StateFromModel(const ColmapModel& model, const std::vector<ControlPointPrior>& control = {}) {
  State s;
  std::map<uint32_t, size_t> cam_index, image_index;
  for (const auto& [id, cam] : model.cameras) {
    cam_index[id] = s.camera_ids.size();
    s.camera_ids.push_back(id);
    s.camera_models.push_back(cam.model_id);
    std::array<double, kMaxParams> k{};
    for (size_t i = 0; i < cam.params.size() && i < kMaxParams; ++i) k[i] = cam.params[i];
    s.intrinsics.push_back(k);
  }
  for (const auto& [id, image] : model.images) {
    image_index[id] = s.image_ids.size();
    s.image_ids.push_back(id);
    s.image_camera.push_back(cam_index.at(image.camera_id));
    const Eigen::Quaterniond& q = image.cam_from_world_rotation;
    s.rotations.push_back({q.x(), q.y(), q.z(), q.w()});
    const Eigen::Vector3d c = image.ProjectionCenter();
    s.centers.push_back({c.x(), c.y(), c.z()});
  }
  for (const auto& [id, point] : model.points3d) {
    if (point.track.size() < 2) continue;
    const size_t pi = s.points.size();
    std::vector<Observation> obs;
    for (const auto& element : point.track) {
      const size_t ii = image_index.at(element.image_id);
      const ColmapImage& image = model.images.at(element.image_id);
      const Eigen::Vector3d x_cam = image.cam_from_world_rotation * point.xyz + image.cam_from_world_translation;
      if (!(x_cam.z() > 1e-9)) continue;  // behind the camera: cannot start from there
      obs.push_back({ii, pi, image.points2d_px.at(element.point2d_idx)});
    }
    if (obs.size() < 2) continue;
    s.point_ids.push_back(id);
    s.points.push_back({point.xyz.x(), point.xyz.y(), point.xyz.z()});
    s.observations.insert(s.observations.end(), obs.begin(), obs.end());
  }
  s.control_first = s.points.size();
  for (const ControlPointPrior& c : control) {
    const size_t pi = s.points.size();
    s.points.push_back({c.initial_enu_m.x(), c.initial_enu_m.y(), c.initial_enu_m.z()});
    for (const PixelObservation& o : c.observations)
      s.observations.push_back({image_index.at(o.image_id), pi, o.pixel_px});
    s.control.push_back(c);
  }
  return s;
}

void StateToModel(const State& s, ColmapModel& model) {
  for (size_t cam = 0; cam < s.camera_ids.size(); ++cam) {
    auto& params = model.cameras.at(s.camera_ids[cam]).params;
    for (size_t i = 0; i < params.size(); ++i) params[i] = s.intrinsics[cam][i];
  }
  for (size_t i = 0; i < s.image_ids.size(); ++i) {
    ColmapImage& image = model.images.at(s.image_ids[i]);
    const auto& r = s.rotations[i];
    image.cam_from_world_rotation = Eigen::Quaterniond(r[3], r[0], r[1], r[2]).normalized();
    const Eigen::Vector3d c(s.centers[i][0], s.centers[i][1], s.centers[i][2]);
    image.cam_from_world_translation = -(image.cam_from_world_rotation * c);
  }
  for (size_t p = 0; p < s.point_ids.size(); ++p) {
    model.points3d.at(s.point_ids[p]).xyz = {s.points[p][0], s.points[p][1], s.points[p][2]};
  }
}

// Multiplies camera `cam`'s focal length(s) by `ratio` and moves the points along the focal/depth
// valley so that the images barely change: each point's depth in every camera that sees it is scaled
// by `ratio` (lateral offsets kept), and the point goes to the mean of those positions.
void ScaleFocal(State& s, size_t cam, double ratio) {
  for (int i : CameraModelFocalIndices(s.camera_models[cam])) s.intrinsics[cam][i] *= ratio;
  std::vector<Eigen::Vector3d> sum(s.points.size(), Eigen::Vector3d::Zero());
  std::vector<int> count(s.points.size(), 0);
  for (const Observation& o : s.observations) {
    const auto& r = s.rotations[o.image];
    const Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
    const Eigen::Vector3d c(s.centers[o.image][0], s.centers[o.image][1], s.centers[o.image][2]);
    const Eigen::Vector3d p(s.points[o.point][0], s.points[o.point][1], s.points[o.point][2]);
    Eigen::Vector3d x_cam = q * (p - c);
    if (s.image_camera[o.image] == cam) x_cam.z() *= ratio;
    sum[o.point] += c + q.conjugate() * x_cam;
    ++count[o.point];
  }
  for (size_t p = 0; p < s.points.size(); ++p) {
    if (count[p] == 0) continue;
    const Eigen::Vector3d m = sum[p] / count[p];
    s.points[p] = {m.x(), m.y(), m.z()};
  }
}

// The views' power to separate focal length from depth: depth relief per image (RMS depth spread over
// the median depth, median over images) and the spread of the optical axes (the largest angle between
// an axis and their mean).
struct ViewGeometry {
  double depth_relief_ratio = 0;
  double view_axis_spread_deg = 0;
  bool resolves_focal = false;
};

ViewGeometry MeasureViewGeometry(const State& state, const BundleAdjustOptions& options) {
  ViewGeometry g;
  std::vector<std::vector<double>> depths(state.image_ids.size());
  for (const Observation& o : state.observations) {
    const auto& r = state.rotations[o.image];
    const Eigen::Quaterniond q(r[3], r[0], r[1], r[2]);
    const Eigen::Vector3d c(state.centers[o.image][0], state.centers[o.image][1], state.centers[o.image][2]);
    const Eigen::Vector3d p(state.points[o.point][0], state.points[o.point][1], state.points[o.point][2]);
    depths[o.image].push_back((q * (p - c)).z());
  }
  std::vector<double> relief;
  for (auto& d : depths) {
    if (d.size() < 10) continue;
    double mean = 0;
    for (double v : d) mean += v;
    mean /= static_cast<double>(d.size());
    double var = 0;
    for (double v : d) var += (v - mean) * (v - mean);
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    relief.push_back(std::sqrt(var / static_cast<double>(d.size())) / std::max(d[d.size() / 2], 1e-9));
  }
  if (!relief.empty()) {
    std::nth_element(relief.begin(), relief.begin() + relief.size() / 2, relief.end());
    g.depth_relief_ratio = relief[relief.size() / 2];
  }
  Eigen::Vector3d mean_axis = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> axes;
  for (const auto& r : state.rotations) {
    axes.push_back(Eigen::Quaterniond(r[3], r[0], r[1], r[2]).conjugate() * Eigen::Vector3d::UnitZ());
    mean_axis += axes.back();
  }
  if (mean_axis.norm() > 0) mean_axis.normalize();
  for (const auto& a : axes) {
    g.view_axis_spread_deg =
        std::max(g.view_axis_spread_deg, std::acos(std::clamp(a.dot(mean_axis), -1.0, 1.0)) * 180 / M_PI);
  }
  g.resolves_focal = g.depth_relief_ratio >= options.min_depth_relief_ratio ||
                     g.view_axis_spread_deg >= options.min_view_axis_spread_deg;
  return g;
}

// The images' own constraint on the focal length about a solved state: the focal length moved by
// ±profile_step (points moved along the valley), held, re-solved; the cost's parabola gives the standard
// deviation and the minimum. Empty when the profile is off or the parabola opens downward.
struct FocalProfile {
  std::optional<double> sigma_ratio, preferred_ratio;
};

template <typename Log>
FocalProfile ProfileFocal(const State& state, const SolveResult& at,
                          const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                          const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                          const Log& log) {
  FocalProfile profile;
  if (!options.profile_focal || !options.refine_focal) return profile;
  const double step = options.profile_step_ratio;
  double cost[2];
  for (int side = 0; side < 2; ++side) {
    State moved = state;
    for (size_t cam = 0; cam < moved.camera_ids.size(); ++cam) ScaleFocal(moved, cam, side == 0 ? 1 - step : 1 + step);
    const SolveResult r =
        Solve(moved, gps_enu_m, focal_prior_px, options, FocalMode::kFixed, options.profile_iterations);
    cost[side] = r.reprojection_cost;
    log(side == 0 ? "profile -" : "profile +", r);
  }
  // cost(x) ~ a x^2 + b x + c0 for a relative focal change x; cost = 1/2 sum r^2 (px^2), so the
  // information about x is 2a / sigma_px^2.
  const double c0 = at.reprojection_cost;
  const double a = (cost[0] + cost[1] - 2 * c0) / (2 * step * step);
  const double b = (cost[1] - cost[0]) / (2 * step);
  const double sigma_px = std::max(RmsReprojection(state) / std::sqrt(2.0), 1e-3);
  if (a > 0) {
    profile.sigma_ratio = sigma_px / std::sqrt(2 * a);
    profile.preferred_ratio = 1 - b / (2 * a);
  }
  return profile;
}

// The problem's size and its reprojection error before adjusting.
BundleAdjustReport InputReport(const State& state, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m) {
  BundleAdjustReport report;
  report.num_images = static_cast<int>(state.image_ids.size());
  report.num_points = static_cast<int>(state.control_first);
  report.num_control_points = static_cast<int>(state.control.size());
  report.num_observations = static_cast<int>(state.observations.size());
  for (uint32_t id : state.image_ids) report.num_gps_priors += gps_enu_m.contains(id) ? 1 : 0;
  report.rms_reprojection_before_px = RmsReprojection(state);
  return report;
}

bool EveryCameraHasFocalPrior(const State& state, const std::map<uint32_t, double>& focal_prior_px) {
  if (focal_prior_px.empty()) return false;
  for (uint32_t id : state.camera_ids)
    if (!focal_prior_px.contains(id)) return false;
  return true;
}

// The main solve, and what the images say of the focal length about it.
struct FocalSolve {
  SolveResult main;
  FocalProfile profile;
  bool measured = false;  // the focal length the images measure was kept
};

// 1. The focal length the photos measure: solved free from COLMAP's, the prior (EXIF 35 mm
//    equivalents are rounded) a weak pull. Kept (into `state` and `solve`) when the profile confirms
//    that the images determine it.
template <typename Log>
void SolveMeasuredFocal(State& state, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                        const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                        const Log& log, FocalSolve& solve) {
  State trial = state;
  const SolveResult r = Solve(trial, gps_enu_m, focal_prior_px, options, FocalMode::kMeasured, options.max_iterations);
  log("focal measured by the images", r);
  const FocalProfile p = ProfileFocal(trial, r, gps_enu_m, focal_prior_px, options, log);
  if (p.sigma_ratio && *p.sigma_ratio <= options.resolvable_sigma_ratio) {
    state = std::move(trial);
    solve.main = r;
    solve.profile = p;
    solve.measured = true;
  }
}

// 2. Start at the prior focal length with the points moved along the focal/depth valley, and solve
//    with the focal length held there (without priors: free, with COLMAP's as the prior).
// 3. Profile the images' own constraint on the focal length (all cameras scaled together).
template <typename Log>
void SolveAtPriorFocal(State& state, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                       const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                       bool all_priors, const Log& log, FocalSolve& solve) {
  if (all_priors && options.refine_focal) {
    for (size_t cam = 0; cam < state.camera_ids.size(); ++cam) {
      ScaleFocal(state, cam, focal_prior_px.at(state.camera_ids[cam]) / MeanFocal(state, cam));
    }
  }
  const FocalMode first_mode = all_priors ? FocalMode::kFixed : FocalMode::kPrior;
  solve.main = Solve(state, gps_enu_m, focal_prior_px, options, first_mode, options.max_iterations);
  log(all_priors ? "focal held at the prior" : "focal free", solve.main);
  solve.profile = ProfileFocal(state, solve.main, gps_enu_m, focal_prior_px, options, log);
}

// What was decided about each camera's focal length, and why.
struct FocalVerdict {
  bool all_priors = false, resolve = false, conflict = false;
};

void AddFocalReports(const State& state, const std::vector<double>& focal_before,
                     const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                     const FocalSolve& solve, const FocalVerdict& verdict, BundleAdjustReport& report) {
  const std::optional<double>& sigma_ratio = solve.profile.sigma_ratio;
  const std::optional<double>& preferred_ratio = solve.profile.preferred_ratio;
  for (size_t cam = 0; cam < state.camera_ids.size(); ++cam) {
    FocalReport f;
    f.camera_id = state.camera_ids[cam];
    f.before_px = focal_before[cam];
    f.after_px = MeanFocal(state, cam);
    const auto prior = focal_prior_px.find(f.camera_id);
    if (prior != focal_prior_px.end()) f.prior_px = prior->second;
    f.images_sigma_ratio = sigma_ratio;
    if (preferred_ratio) f.images_preferred_px = f.after_px * *preferred_ratio;
    f.images_resolve_focal = verdict.resolve;
    f.images_conflict_with_prior = verdict.conflict;
    f.held_at_prior = verdict.all_priors && !solve.measured &&
                      !(verdict.resolve && !verdict.conflict && options.free_focal_when_resolved);
    f.measured_by_images = solve.measured;
    report.focal.push_back(f);
  }
}

// The control points' adjusted positions (ENU m).
std::vector<Eigen::Vector3d> ControlPointsEnu(const State& state) {
  std::vector<Eigen::Vector3d> out;
  for (size_t k = 0; k < state.control.size(); ++k) {
    const auto& p = state.points[state.control_first + k];
    out.push_back({p[0], p[1], p[2]});
  }
  return out;
}

}  // namespace

double RmsReprojectionErrorPx(const ColmapModel& model) { return RmsReprojection(StateFromModel(model)); }

BundleAdjustReport BundleAdjustEnu(ColmapModel& model_enu, const std::map<uint32_t, Eigen::Vector3d>& gps_enu_m,
                                   const std::map<uint32_t, double>& focal_prior_px, const BundleAdjustOptions& options,
                                   const std::vector<ControlPointPrior>& control_points,
                                   std::vector<Eigen::Vector3d>* control_points_enu_m) {
  const auto start = std::chrono::steady_clock::now();
  const bool verbose = std::getenv("CINEPATH_BA_VERBOSE") != nullptr;
  auto log = [&](const char* what, const SolveResult& r) {
    if (verbose) {
      std::fprintf(stderr, "BA %s: %d iterations, %.2f s, reprojection cost %.3f\n", what, r.iterations,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                   r.reprojection_cost);
    }
  };
  State state = StateFromModel(model_enu, control_points);
  if (state.observations.empty()) {
    throw InfeasibleError("bundle adjustment: no 3D point is seen by two images in front of them");
  }
  BundleAdjustReport report = InputReport(state, gps_enu_m);
  std::vector<double> focal_before;
  for (size_t cam = 0; cam < state.camera_ids.size(); ++cam) focal_before.push_back(MeanFocal(state, cam));

  // 0. The geometry, as COLMAP left it: can these views separate focal length from depth at all?
  const ViewGeometry geometry = MeasureViewGeometry(state, options);
  report.depth_relief_ratio = geometry.depth_relief_ratio;
  report.view_axis_spread_deg = geometry.view_axis_spread_deg;
  report.geometry_resolves_focal = geometry.resolves_focal;
  FocalVerdict verdict;
  verdict.all_priors = EveryCameraHasFocalPrior(state, focal_prior_px);

  // 1. Where the geometry resolves it, the focal length the photos measure; 2-3. otherwise held at the prior.
  FocalSolve solve;
  if (verdict.all_priors && options.refine_focal && options.keep_measured_focal && geometry.resolves_focal) {
    SolveMeasuredFocal(state, gps_enu_m, focal_prior_px, options, log, solve);
  }
  if (!solve.measured) SolveAtPriorFocal(state, gps_enu_m, focal_prior_px, options, verdict.all_priors, log, solve);

  // 4. Free the focal length (with its prior) only when the images resolve it and agree with the prior.
  const FocalProfile& profile = solve.profile;
  verdict.resolve = solve.measured || (geometry.resolves_focal && profile.sigma_ratio &&
                                       *profile.sigma_ratio <= options.resolvable_sigma_ratio);
  if (verdict.all_priors && profile.preferred_ratio && !solve.measured) {
    verdict.conflict = std::abs(*profile.preferred_ratio - 1) > options.max_focal_disagreement_ratio;
  }
  if (!solve.measured && verdict.all_priors && verdict.resolve && !verdict.conflict &&
      options.free_focal_when_resolved) {
    solve.main = Solve(state, gps_enu_m, focal_prior_px, options, FocalMode::kPrior, options.max_iterations);
    log("focal free with its prior", solve.main);
  }
  report.iterations = solve.main.iterations;
  report.converged = solve.main.converged;
  report.rms_reprojection_after_px = RmsReprojection(state);
  AddFocalReports(state, focal_before, focal_prior_px, options, solve, verdict, report);
  StateToModel(state, model_enu);
  if (control_points_enu_m) *control_points_enu_m = ControlPointsEnu(state);
  report.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace cinepath::photogrammetry
