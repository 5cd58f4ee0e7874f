#include "photogrammetry/georef/camera_models.h"

#include <array>
#include <cmath>

namespace cinepath::photogrammetry {
namespace {

struct ModelInfo {
  std::string_view name;
  int num_params;
  bool single_focal;
};

constexpr std::array<ModelInfo, kNumCameraModels> kModels = {{
    {"SIMPLE_PINHOLE", 3, true},
    {"PINHOLE", 4, false},
    {"SIMPLE_RADIAL", 4, true},
    {"RADIAL", 5, true},
    {"OPENCV", 8, false},
    {"OPENCV_FISHEYE", 8, false},
    {"FULL_OPENCV", 12, false},
    {"FOV", 5, false},
    {"SIMPLE_RADIAL_FISHEYE", 4, true},
    {"RADIAL_FISHEYE", 5, true},
    {"THIN_PRISM_FISHEYE", 12, false},
}};

}  // namespace

bool IsKnownCameraModel(int model_id) { return model_id >= 0 && model_id < kNumCameraModels; }

int CameraModelNumParams(int model_id) { return IsKnownCameraModel(model_id) ? kModels[model_id].num_params : 0; }

std::string_view CameraModelName(int model_id) {
  return IsKnownCameraModel(model_id) ? kModels[model_id].name : std::string_view();
}

std::optional<int> CameraModelIdFromName(std::string_view name) {
  for (int i = 0; i < kNumCameraModels; ++i) {
    if (kModels[i].name == name) return i;
  }
  return std::nullopt;
}

bool CameraModelHasSingleFocal(int model_id) { return IsKnownCameraModel(model_id) && kModels[model_id].single_focal; }

std::vector<int> CameraModelFocalIndices(int model_id) {
  if (!IsKnownCameraModel(model_id)) return {};
  return CameraModelHasSingleFocal(model_id) ? std::vector<int>{0} : std::vector<int>{0, 1};
}

std::vector<int> CameraModelPrincipalPointIndices(int model_id) {
  if (!IsKnownCameraModel(model_id)) return {};
  return CameraModelHasSingleFocal(model_id) ? std::vector<int>{1, 2} : std::vector<int>{2, 3};
}

std::vector<int> CameraModelExtraIndices(int model_id) {
  std::vector<int> extra;
  const int first = CameraModelHasSingleFocal(model_id) ? 3 : 4;
  for (int i = first; i < CameraModelNumParams(model_id); ++i) extra.push_back(i);
  return extra;
}

bool PixelToNormalized(int model_id, std::span<const double> params, double x, double y, double* u, double* v) {
  if (!IsKnownCameraModel(model_id) || static_cast<int>(params.size()) != CameraModelNumParams(model_id)) {
    return false;
  }
  // Undistorted guess from the pinhole part, then Newton on distort(u, v) = (ud, vd).
  double fx, fy, cx, cy;
  if (CameraModelHasSingleFocal(model_id)) {
    fx = fy = params[0];
    cx = params[1];
    cy = params[2];
  } else {
    fx = params[0];
    fy = params[1];
    cx = params[2];
    cy = params[3];
  }
  const double target_u = (x - cx) / fx, target_v = (y - cy) / fy;
  double cu = target_u, cv = target_v;
  constexpr int kMaxIterations = 100;
  constexpr double kStep = 1e-7;
  for (int it = 0; it < kMaxIterations; ++it) {
    double du0, dv0, du1, dv1, du2, dv2;
    DistortNormalized<double>(model_id, params.data(), cu, cv, &du0, &dv0);
    const double ru = du0 - target_u, rv = dv0 - target_v;
    if (std::hypot(ru, rv) < 1e-12) break;
    const double hu = kStep * std::max(1.0, std::abs(cu));
    const double hv = kStep * std::max(1.0, std::abs(cv));
    DistortNormalized<double>(model_id, params.data(), cu + hu, cv, &du1, &dv1);
    DistortNormalized<double>(model_id, params.data(), cu, cv + hv, &du2, &dv2);
    const double j00 = (du1 - du0) / hu, j10 = (dv1 - dv0) / hu;
    const double j01 = (du2 - du0) / hv, j11 = (dv2 - dv0) / hv;
    const double det = j00 * j11 - j01 * j10;
    if (!std::isfinite(det) || std::abs(det) < 1e-300) return false;
    cu -= (j11 * ru - j01 * rv) / det;
    cv -= (-j10 * ru + j00 * rv) / det;
  }
  double du, dv;
  DistortNormalized<double>(model_id, params.data(), cu, cv, &du, &dv);
  if (!std::isfinite(cu) || !std::isfinite(cv) || std::hypot(du - target_u, dv - target_v) > 1e-9) {
    return false;
  }
  *u = cu;
  *v = cv;
  return true;
}

}  // namespace cinepath::photogrammetry
