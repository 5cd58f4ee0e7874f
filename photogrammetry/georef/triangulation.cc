#include "photogrammetry/georef/triangulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <ceres/ceres.h>
#include <Eigen/Dense>

#include "core/ceres_logging.h"
#include "core/number_format.h"
#include "photogrammetry/georef/camera_models.h"

namespace cinepath::photogrammetry {
namespace {

// Reprojection of a point X (model frame) into one image: project(k, R X + t) - observed (px).
struct PointReprojectionError {
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const Eigen::Matrix<T, 3, 1> p(x[0], x[1], x[2]);
    const Eigen::Matrix<T, 3, 1> c = rotation.cast<T>() * p + translation.cast<T>();
    if (!(c.z() > T(1e-12))) return false;
    std::vector<T> k(params.begin(), params.end());
    T px, py;
    if (!ProjectNormalizedToPixel(model_id, k.data(), c.x() / c.z(), c.y() / c.z(), &px, &py)) return false;
    residual[0] = px - T(observed.x());
    residual[1] = py - T(observed.y());
    return true;
  }
  int model_id;
  std::vector<double> params;
  Eigen::Matrix3d rotation;
  Eigen::Vector3d translation;
  Eigen::Vector2d observed;
};

struct Ray {
  Eigen::Vector3d center;
  Eigen::Vector3d direction;  // unit, world frame
};

bool Reproject(const ColmapModel& model, const PixelObservation& o, const Eigen::Vector3d& x, double* error_px) {
  const ColmapImage& image = model.images.at(o.image_id);
  const ColmapCamera& camera = model.cameras.at(image.camera_id);
  const Eigen::Vector3d c = image.cam_from_world_rotation * x + image.cam_from_world_translation;
  if (!(c.z() > 1e-12)) return false;
  double px, py;
  if (!ProjectNormalizedToPixel(camera.model_id, camera.params.data(), c.x() / c.z(), c.y() / c.z(), &px, &py)) {
    return false;
  }
  *error_px = std::hypot(px - o.pixel_px.x(), py - o.pixel_px.y());
  return std::isfinite(*error_px);
}

// Linear midpoint of the rays, then Ceres refinement. False when the rays do not define a point.
bool Solve(const ColmapModel& model, const std::vector<PixelObservation>& obs, const std::vector<Ray>& rays,
           const std::vector<int>& use, Eigen::Vector3d* x) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int i : use) {
    const Eigen::Matrix3d p = Eigen::Matrix3d::Identity() - rays[i].direction * rays[i].direction.transpose();
    a += p;
    b += p * rays[i].center;
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (!lu.isInvertible()) return false;
  Eigen::Vector3d point = lu.solve(b);
  if (!point.allFinite()) return false;
  for (int i : use) {
    if ((point - rays[i].center).dot(rays[i].direction) <= 0) return false;  // behind a camera
  }
  double xyz[3] = {point.x(), point.y(), point.z()};
  ceres::Problem problem;
  for (int i : use) {
    const ColmapImage& image = model.images.at(obs[i].image_id);
    const ColmapCamera& camera = model.cameras.at(image.camera_id);
    auto* functor =
        new PointReprojectionError{camera.model_id, camera.params, image.cam_from_world_rotation.toRotationMatrix(),
                                   image.cam_from_world_translation, obs[i].pixel_px};
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PointReprojectionError, 2, 3>(functor), nullptr, xyz);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 20;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  QuietCeresLogging();
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  const Eigen::Vector3d refined(xyz[0], xyz[1], xyz[2]);
  bool in_front = refined.allFinite();
  for (int i : use) in_front = in_front && (refined - rays[i].center).dot(rays[i].direction) > 0;
  *x = in_front ? refined : point;
  return true;
}

}  // namespace

Triangulation TriangulatePoint(const ColmapModel& model, const std::vector<PixelObservation>& observations,
                               const TriangulationOptions& options) {
  Triangulation t;
  t.observations.resize(observations.size());
  std::vector<Ray> rays(observations.size());
  std::vector<int> use;
  for (size_t i = 0; i < observations.size(); ++i) {
    const PixelObservation& o = observations[i];
    const ColmapImage& image = model.images.at(o.image_id);
    const ColmapCamera& camera = model.cameras.at(image.camera_id);
    ObservationResult& r = t.observations[i];
    if (o.pixel_px.x() < 0 || o.pixel_px.y() < 0 || o.pixel_px.x() > static_cast<double>(camera.width_px) ||
        o.pixel_px.y() > static_cast<double>(camera.height_px)) {
      r.note = "outside the image (" + std::to_string(camera.width_px) + " x " + std::to_string(camera.height_px) +
               " px): pixel coordinates must be measured on the images COLMAP reconstructed";
      continue;
    }
    double u, v;
    if (!PixelToNormalized(camera.model_id, camera.params, o.pixel_px.x(), o.pixel_px.y(), &u, &v)) {
      r.note = "cannot undistort the pixel through the camera model";
      continue;
    }
    const Eigen::Matrix3d world_from_cam = image.cam_from_world_rotation.toRotationMatrix().transpose();
    rays[i] = {image.ProjectionCenter(), (world_from_cam * Eigen::Vector3d(u, v, 1)).normalized()};
    use.push_back(static_cast<int>(i));
  }

  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  bool have_point = false;  // x is a point in front of the cameras used (reprojection errors mean something)
  while (true) {
    if (use.size() < 2) {
      t.reason = "fewer than 2 usable observations (" + std::to_string(use.size()) + ")";
      break;
    }
    if (!Solve(model, observations, rays, use, &x)) {
      t.reason = "the rays do not meet in front of the cameras";
      have_point = false;
      break;
    }
    have_point = true;
    // Drop the worst observation while it is over the limit and more than two remain.
    int worst = -1;
    double worst_px = -1;
    for (int i : use) {
      double e;
      if (!Reproject(model, observations[i], x, &e)) e = std::numeric_limits<double>::infinity();
      if (e > worst_px) worst_px = e, worst = i;
    }
    if (worst_px > options.max_reprojection_px) {
      if (use.size() > 2) {
        t.observations[worst].note = "dropped: reprojection error " + FormatFixed(worst_px, 2) + " px > " +
                                     FormatFixed(options.max_reprojection_px, 2) + " px";
        use.erase(std::find(use.begin(), use.end(), worst));
        continue;
      }
      t.reason = "the two observations disagree: reprojection error " + FormatFixed(worst_px, 2) + " px > " +
                 FormatFixed(options.max_reprojection_px, 2) + " px";
      break;
    }
    t.ok = true;
    break;
  }
  if (have_point) {
    for (size_t i = 0; i < observations.size(); ++i) {
      double e;
      if (Reproject(model, observations[i], x, &e)) t.observations[i].reprojection_px = e;
    }
  }
  if (!t.ok) return t;

  t.xyz = x;
  double sum2 = 0;
  for (int i : use) {
    t.observations[i].used = true;
    sum2 += t.observations[i].reprojection_px * t.observations[i].reprojection_px;
  }
  t.num_used = static_cast<int>(use.size());
  t.rms_reprojection_px = std::sqrt(sum2 / static_cast<double>(use.size()));
  for (size_t a = 0; a < use.size(); ++a) {
    for (size_t b = a + 1; b < use.size(); ++b) {
      const Eigen::Vector3d da = (x - rays[use[a]].center).normalized();
      const Eigen::Vector3d db = (x - rays[use[b]].center).normalized();
      t.max_angle_deg = std::max(t.max_angle_deg, std::acos(std::clamp(da.dot(db), -1.0, 1.0)) * 180.0 / M_PI);
    }
  }
  if (t.max_angle_deg < options.min_angle_deg) {
    t.ok = false;
    t.reason = "triangulation angle " + FormatFixed(t.max_angle_deg, 2) + " deg < " +
               FormatFixed(options.min_angle_deg, 2) + " deg: the rays are nearly parallel, the depth is undetermined";
  }
  return t;
}

}  // namespace cinepath::photogrammetry
